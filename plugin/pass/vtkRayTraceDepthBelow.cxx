#include "vtkRayTraceDepthBelow.h"

#include "vtkObject.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkSetGet.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

namespace vtkrt
{
namespace pass
{
namespace
{
/// The internal format of the depth attachment of the framebuffer bound for
/// drawing (0 when it has none or it cannot be told, as for the default
/// framebuffer's).
GLint DrawnDepthFormat()
{
  GLint drawn = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
  if (drawn == 0)
  {
    return 0;
  }
  GLint type = GL_NONE;
  GLint name = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
  GLint format = 0;
  if (type == GL_RENDERBUFFER)
  {
    GLint previous = 0;
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &previous);
    glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(name));
    glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_INTERNAL_FORMAT, &format);
    glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(previous));
  }
  else if (type == GL_TEXTURE)
  {
    GLint previous = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &previous);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, static_cast<GLuint>(name));
    glGetTexLevelParameteriv(GL_TEXTURE_2D_MULTISAMPLE, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, static_cast<GLuint>(previous));
  }
  return format;
}

/// Allocates `texture` as a depth texture of the GL internal format
/// `format`; false for a format vtkTextureObject does not allocate.
bool AllocateDepthOfFormat(vtkTextureObject* texture, unsigned int width, unsigned int height, GLint format)
{
  switch (format)
  {
    case GL_DEPTH_COMPONENT16:
      return texture->AllocateDepth(width, height, vtkTextureObject::Fixed16);
    case GL_DEPTH_COMPONENT24:
      return texture->AllocateDepth(width, height, vtkTextureObject::Fixed24);
    case GL_DEPTH_COMPONENT32:
      return texture->AllocateDepth(width, height, vtkTextureObject::Fixed32);
    case GL_DEPTH_COMPONENT32F:
      return texture->AllocateDepth(width, height, vtkTextureObject::Float32);
    case GL_DEPTH24_STENCIL8:
      return texture->AllocateDepthStencil(width, height);
    default:
      return false;
  }
}
} // namespace

DepthBelow::DepthBelow() = default;
DepthBelow::~DepthBelow() = default;

vtkTextureObject* DepthBelow::Take(vtkOpenGLRenderWindow* win, const int size[2], const int origin[2])
{
  const unsigned int width = static_cast<unsigned int>(std::max(size[0], 1));
  const unsigned int height = static_cast<unsigned int>(std::max(size[1], 1));
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  return samples > 0 ? this->Resolve(win, width, height, origin) : this->Copy(win, width, height, origin);
}

vtkTextureObject* DepthBelow::Copy(
  vtkOpenGLRenderWindow* win, unsigned int width, unsigned int height, const int origin[2])
{
  vtkTextureObject* depth = this->Copied;
  depth->SetContext(win);
  if (!depth->GetHandle() || depth->GetWidth() != width || depth->GetHeight() != height)
  {
    depth->AllocateDepth(width, height, vtkTextureObject::Float32);
  }
  // glCopyTexSubImage2D reads the read framebuffer: make it the one drawn
  // to. (vtkTextureObject::CopyFromFrameBuffer blits first whenever the
  // window has samples, whatever is bound.)
  vtkOpenGLState* ostate = win->GetState();
  GLint drawn = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
  ostate->PushReadFramebufferBinding();
  ostate->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(drawn));
  depth->Activate();
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, origin[0], origin[1], static_cast<GLsizei>(width),
    static_cast<GLsizei>(height));
  depth->Deactivate();
  ostate->PopReadFramebufferBinding();
  return depth;
}

vtkTextureObject* DepthBelow::Resolve(
  vtkOpenGLRenderWindow* win, unsigned int width, unsigned int height, const int origin[2])
{
  const GLint format = DrawnDepthFormat();
  vtkTextureObject* depth = this->Resolved;
  depth->SetContext(win);
  vtkOpenGLState* ostate = win->GetState();
  if (!depth->GetHandle() || depth->GetWidth() != width || depth->GetHeight() != height ||
    format != this->ResolvedFormat)
  {
    // AllocateDepth keeps a format and type set before.
    depth->ResetFormatAndType();
    if (!AllocateDepthOfFormat(depth, width, height, format))
    {
      if (format != this->WarnedFormat)
      {
        vtkGenericWarningMacro("vtkRayTracePass: the depth of a multisampled framebuffer of GL internal "
                               "format "
          << format << " cannot be resolved; the depth below this renderer is not traced against.");
        this->WarnedFormat = format;
      }
      this->ResolvedFormat = 0;
      return this->Nothing(win);
    }
    this->ResolvedFormat = format;
    this->ResolveTarget->SetContext(win);
    ostate->PushFramebufferBindings();
    this->ResolveTarget->Bind();
    this->ResolveTarget->AddDepthAttachment(depth);
    ostate->PopFramebufferBindings();
  }
  GLint drawn = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  ostate->vtkglDisable(GL_SCISSOR_TEST); // it would clip the blit's target
  ostate->PushFramebufferBindings();
  ostate->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(drawn));
  this->ResolveTarget->Bind(GL_DRAW_FRAMEBUFFER);
  glBlitFramebuffer(origin[0], origin[1], origin[0] + static_cast<GLint>(width),
    origin[1] + static_cast<GLint>(height), 0, 0, static_cast<GLint>(width), static_cast<GLint>(height),
    GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  ostate->PopFramebufferBindings();
  return depth;
}

vtkTextureObject* DepthBelow::Nothing(vtkOpenGLRenderWindow* win)
{
  if (!this->Far->GetHandle())
  {
    this->Far->SetContext(win);
    float farDepth = 1.0f;
    this->Far->Create2DFromRaw(1, 1, 1, VTK_FLOAT, &farDepth);
  }
  return this->Far;
}

void DepthBelow::Release(vtkWindow* w)
{
  this->Far->ReleaseGraphicsResources(w);
  this->Copied->ReleaseGraphicsResources(w);
  this->Resolved->ReleaseGraphicsResources(w);
  this->ResolveTarget->ReleaseGraphicsResources(w);
  this->ResolvedFormat = 0;
}

} // namespace pass
} // namespace vtkrt
