#include "vtkRayTraceAccumulation.h"

#include "vtkRayTraceShader.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace vtkrt
{
namespace pass
{

bool ImageSignature::Same(const ImageSignature& other) const
{
  // The scene's words hold pointers and counts as well as floats: compared
  // as bytes (as floats, some are NaN patterns, never equal, or denormals
  // that flush to zero).
  if (this->Scene.size() != other.Scene.size() || this->Camera.size() != other.Camera.size() ||
    (!this->Scene.empty() &&
      std::memcmp(this->Scene.data(), other.Scene.data(), this->Scene.size() * sizeof(float)) != 0))
  {
    return false;
  }
  for (std::size_t first = 0; first < this->Camera.size(); first += 16)
  {
    const std::size_t end = std::min(first + 16, this->Camera.size());
    float largest = 0.0f;
    for (std::size_t i = first; i < end; ++i)
    {
      largest = std::max({ largest, std::abs(this->Camera[i]), std::abs(other.Camera[i]) });
    }
    for (std::size_t i = first; i < end; ++i)
    {
      // A non-finite entry (or largest) is the same only bit for bit.
      const bool finite = std::isfinite(this->Camera[i]) && std::isfinite(other.Camera[i]) && std::isfinite(largest);
      const bool same = finite ? std::abs(this->Camera[i] - other.Camera[i]) <= 1e-6f * largest
                               : std::memcmp(&this->Camera[i], &other.Camera[i], sizeof(float)) == 0;
      if (!same)
      {
        return false;
      }
    }
  }
  return true;
}

Accumulation::Accumulation() = default;
Accumulation::~Accumulation() = default;

int Accumulation::BeginFrame()
{
  const int before = this->Frames;
  this->Frames = 0;
  return before;
}

void Accumulation::Allocate(vtkOpenGLRenderWindow* win, int width, int height)
{
  vtkOpenGLState* ostate = win->GetState();
  this->Color->SetContext(win);
  this->Color->Allocate2D(width, height, 4, VTK_FLOAT);
  this->Depth->SetContext(win);
  this->Depth->AllocateDepth(width, height, vtkTextureObject::Float32);
  this->FBO->SetContext(win);
  ostate->PushFramebufferBindings();
  this->FBO->Bind();
  this->FBO->AddColorAttachment(0, this->Color);
  this->FBO->AddDepthAttachment(this->Depth);
  ostate->PopFramebufferBindings();
  this->Size[0] = width;
  this->Size[1] = height;
}

void Accumulation::Trace(vtkOpenGLRenderWindow* win, const int viewportSize[2],
  const int viewportOrigin[2], vtkOpenGLQuadHelper* tracer, ImageSignature signature,
  bool restart, int framesBefore, int samplesPerPixel, const int* footprint)
{
  vtkOpenGLState* ostate = win->GetState();
  const int width = std::max(viewportSize[0], 1), height = std::max(viewportSize[1], 1);
  const int originX = viewportOrigin[0], originY = viewportOrigin[1];
  const bool resized = width != this->Size[0] || height != this->Size[1];
  restart = restart || resized || framesBefore == 0 || !signature.Same(this->Signature);
  if (resized)
  {
    this->Allocate(win, width, height);
  }
  this->Frames = restart ? 1 : framesBefore + 1;
  // Kept from the restart on, so that a camera drifting by less than the
  // tolerance each frame still restarts once it has moved.
  if (restart)
  {
    this->Signature = std::move(signature);
  }

  ostate->PushFramebufferBindings();
  this->FBO->Bind();
  this->FBO->ActivateDrawBuffers(1);
  vtkOpenGLState::ScopedglViewport viewport(ostate);
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglScissor scissorBox(ostate);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  ostate->vtkglViewport(0, 0, width, height);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  if (restart)
  {
    vtkOpenGLState::ScopedglClearColor clearColor(ostate);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  if (footprint)
  {
    // The buffer's pixel (0, 0) is the renderer's lower left corner.
    ostate->vtkglEnable(GL_SCISSOR_TEST);
    ostate->vtkglScissor(footprint[0] - originX, footprint[1] - originY, footprint[2], footprint[3]);
  }
  // The depth is the first frame's; later frames only add colors.
  ostate->vtkglDepthMask(restart ? GL_TRUE : GL_FALSE);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  vtkShaderProgram* program = tracer->Program;
  program->SetUniformi("uFirstSample", (this->Frames - 1) * samplesPerPixel);
  const float pixelSize[2] = { 2.0f / width, 2.0f / height };
  program->SetUniform2f("uPixelSize", pixelSize);
  tracer->Render();
  ostate->PopFramebufferBindings();
}

bool Accumulation::Resolve(vtkOpenGLRenderWindow* win, int samplesPerPixel, FrameCounters& counters)
{
  if (!ReadyQuadProgram(win, this->ResolveProgram, ResolveShaderSource(), counters))
  {
    return false;
  }
  vtkOpenGLState* ostate = win->GetState();
  vtkShaderProgram* resolve = this->ResolveProgram->Program;
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  this->Color->Activate();
  this->Depth->Activate();
  resolve->SetUniformi("uAccumulation", this->Color->GetTextureUnit());
  resolve->SetUniformi("uAccumulationDepth", this->Depth->GetTextureUnit());
  resolve->SetUniformf(
    "uInverseSamples", 1.0f / static_cast<float>(this->Frames * samplesPerPixel));
  this->ResolveProgram->Render();
  this->Color->Deactivate();
  this->Depth->Deactivate();
  return true;
}

void Accumulation::Release(vtkWindow* w)
{
  if (this->ResolveProgram)
  {
    this->ResolveProgram->ReleaseGraphicsResources(w);
    this->ResolveProgram.reset();
  }
  this->FBO->ReleaseGraphicsResources(w);
  this->Color->ReleaseGraphicsResources(w);
  this->Depth->ReleaseGraphicsResources(w);
  this->Size[0] = this->Size[1] = 0;
  this->Signature.Clear();
  this->Frames = 0;
}

} // namespace pass
} // namespace vtkrt
