#include "vtkEGLHeadlessRenderWindow.h"

#include "vtkGenericRenderWindowInteractor.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

// After VTK and GLEW, as the EGL headers above.
#include "vtkEGLHeadlessDevices.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

vtkStandardNewMacro(vtkEGLHeadlessRenderWindow);

using namespace vtkrt::egl;

struct vtkEGLHeadlessRenderWindow::Internals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE; // 1x1 pbuffer, only without surfaceless_context

  /// An EGL binding to restore (PushContext / PopContext).
  struct Binding
  {
    EGLDisplay Display;
    EGLSurface Draw;
    EGLSurface Read;
    EGLContext Context;
  };
  std::vector<Binding> Pushed;
};

//------------------------------------------------------------------------------
vtkEGLHeadlessRenderWindow::vtkEGLHeadlessRenderWindow()
  : Internal(new Internals)
{
  // Nothing to show, no default framebuffer: render into VTK's framebuffer
  // objects and leave the result there for readback.
  this->ShowWindow = false;
  this->UseOffScreenBuffers = true;
  this->FrameBlitMode = NoBlit;
  this->OwnContext = 1;
  this->DeviceIndex = -1; // choose automatically (vtkRenderWindow's default is 0)
  this->SetWindowName("vtkrt EGL headless");
}

//------------------------------------------------------------------------------
vtkEGLHeadlessRenderWindow::~vtkEGLHeadlessRenderWindow()
{
  // The base destructors cannot reach this class's Finalize.
  this->Finalize();
  delete this->Internal;
}

//------------------------------------------------------------------------------
bool vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers()
{
#if defined(__GLIBC__)
  // Keep buffers up to 32 MiB on the heap and do not give freed memory back
  // eagerly: llvmpipe then reuses its buffers instead of faulting them in.
  const int mmapOk = mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  const int trimOk = mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
  return mmapOk == 1 && trimOk == 1;
#else
  return false;
#endif
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::GetNumberOfDevices()
{
  EGLDeviceApi api;
  return static_cast<int>(api.Devices().size());
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::ReportFailure(const std::string& why)
{
  this->Failed = true;
  this->ContextReady = false;
  // Makes vtkGenericOpenGLRenderWindow skip rendering and readbacks.
  this->ReadyForRendering = false;
  vtkErrorMacro("No usable EGL display/OpenGL context: " << why
                                                        << ". Rendering is disabled for this window.");
}

//------------------------------------------------------------------------------
bool vtkEGLHeadlessRenderWindow::CreateContext()
{
  EGLDeviceApi api;
  std::vector<DisplayCandidate> candidates;
  std::string why;

  int index = -1;
  std::string indexSource;
  if (!RequestedDeviceIndex(this->DeviceIndex, index, indexSource, why) ||
    !CandidateDisplays(api, index, indexSource, candidates, why))
  {
    this->ReportFailure(why);
    return false;
  }

  for (const DisplayCandidate& candidate : candidates)
  {
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
    if (!MakeContextCurrent(candidate, context, surface, why))
    {
      continue;
    }

    EGLDisplay display = candidate.Display;
    this->Internal->Display = display;
    this->Internal->Context = context;
    this->Internal->Surface = surface;
    const char* vendor = eglQueryString(display, EGL_VENDOR);
    const char* version = eglQueryString(display, EGL_VERSION);
    this->EGLVendor = vendor ? vendor : "";
    this->EGLVersion = version ? version : "";
    this->DeviceDescription = candidate.Description;
    const GLubyte* renderer = glGetString(GL_RENDERER);
    const GLubyte* glVersion = glGetString(GL_VERSION);
    this->GLRenderer = renderer ? reinterpret_cast<const char*>(renderer) : "";
    this->GLVersion = glVersion ? reinterpret_cast<const char*>(glVersion) : "";
    return true;
  }

  if (why.size() >= 2)
  {
    why.resize(why.size() - 2);
  }
  this->ReportFailure(why.empty() ? std::string("no EGL display to try") : why);
  return false;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::DestroyContext()
{
  Internals& in = *this->Internal;
  if (in.Context != EGL_NO_CONTEXT)
  {
    if (eglGetCurrentContext() == in.Context)
    {
      eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(in.Display, in.Context);
  }
  if (in.Surface != EGL_NO_SURFACE)
  {
    eglDestroySurface(in.Display, in.Surface);
  }
  if (in.Display != EGL_NO_DISPLAY)
  {
    ReleaseDisplay(in.Display);
  }
  in.Display = EGL_NO_DISPLAY;
  in.Context = EGL_NO_CONTEXT;
  in.Surface = EGL_NO_SURFACE;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Initialize()
{
  if (this->Failed)
  {
    return;
  }
  if (this->Internal->Context == EGL_NO_CONTEXT && !this->CreateContext())
  {
    return;
  }
  // VTK's state initialisation issues GL calls: the context must be current.
  this->MakeCurrent();
  if (!this->Initialized)
  {
    this->OpenGLInit();
    if (!this->Initialized)
    {
      this->ReportFailure("VTK could not initialise OpenGL on " + this->DeviceDescription + " (" +
        this->GLRenderer + ", " + this->GLVersion + ")");
      this->DestroyContext();
      return;
    }
    // VTK's raster expects GL_LEQUAL, so that of two coincident surfaces or
    // lines the one drawn last shows, as in VTK's X11 windows; VTK 9.1's
    // state initialisation leaves a fresh EGL context at GL_LESS (the
    // cache is read first, so the call is never skipped as a repeat).
    this->GetState()->ResetGLDepthFuncState();
    this->GetState()->vtkglDepthFunc(GL_LEQUAL);
  }
  this->ContextReady = true;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::OpenGLInitContext()
{
  this->ContextCreationTime.Modified();
  if (this->Initialized)
  {
    return;
  }
  // Debian's GLEW is a GLX build: under EGL glewInit() loads every entry
  // point (glvnd's dispatch serves EGL contexts too), then fails to find a
  // GLX display. That one failure is harmless here.
  const GLenum result = glewInit();
  if (result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY)
  {
    vtkErrorMacro("GLEW could not be initialized: "
      << reinterpret_cast<const char*>(glewGetErrorString(result)));
    return;
  }
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 3 || (major == 3 && minor < 2))
  {
    vtkErrorMacro("OpenGL 3.2 or later is required; the EGL context offers " << major << "."
                                                                            << minor);
    return;
  }
  this->GlewInitValid = true;
  this->Initialized = true;

  GLfloat lineWidthRange[2] = { 1.0f, 1.0f };
  this->MaximumHardwareLineWidth = 1.0f;
  glGetFloatv(this->LineSmoothing ? GL_SMOOTH_LINE_WIDTH_RANGE : GL_ALIASED_LINE_WIDTH_RANGE,
    lineWidthRange);
  if (glGetError() == GL_NO_ERROR)
  {
    this->MaximumHardwareLineWidth = lineWidthRange[1];
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Render()
{
  this->Initialize();
  if (!this->ContextReady)
  {
    return;
  }
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Frame()
{
  if (!this->ContextReady)
  {
    return;
  }
  this->Superclass::Frame();
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Finalize()
{
  if (this->Internal->Context != EGL_NO_CONTEXT)
  {
    // VTK releases its GL objects with GL calls: keep this context current.
    this->MakeCurrent();
    this->Superclass::Finalize();
    this->DestroyContext();
  }
  this->Initialized = false;
  this->GlewInitValid = false;
  this->ContextReady = false;
  this->Failed = false;
  this->ReadyForRendering = true;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::MakeCurrent()
{
  Internals& in = *this->Internal;
  if (in.Context != EGL_NO_CONTEXT && eglGetCurrentContext() != in.Context)
  {
    if (!eglMakeCurrent(in.Display, in.Surface, in.Surface, in.Context))
    {
      vtkErrorMacro("eglMakeCurrent failed: " << EGLErrorName(eglGetError()));
    }
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::ReleaseCurrent()
{
  Internals& in = *this->Internal;
  if (in.Context != EGL_NO_CONTEXT && eglGetCurrentContext() == in.Context)
  {
    eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

//------------------------------------------------------------------------------
bool vtkEGLHeadlessRenderWindow::IsCurrent()
{
  return this->Internal->Context != EGL_NO_CONTEXT &&
    eglGetCurrentContext() == this->Internal->Context;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::PushContext()
{
  this->Internal->Pushed.push_back({ eglGetCurrentDisplay(), eglGetCurrentSurface(EGL_DRAW),
    eglGetCurrentSurface(EGL_READ), eglGetCurrentContext() });
  if (!this->IsCurrent())
  {
    this->MakeCurrent();
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::PopContext()
{
  std::vector<Internals::Binding>& pushed = this->Internal->Pushed;
  if (pushed.empty())
  {
    return;
  }
  const Internals::Binding b = pushed.back();
  pushed.pop_back();
  if (b.Context != eglGetCurrentContext())
  {
    if (b.Context == EGL_NO_CONTEXT)
    {
      eglMakeCurrent(this->Internal->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    else
    {
      eglMakeCurrent(b.Display, b.Draw, b.Read, b.Context);
    }
  }
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::SupportsOpenGL()
{
  this->Initialize();
  return this->ContextReady ? 1 : 0;
}

//------------------------------------------------------------------------------
vtkTypeBool vtkEGLHeadlessRenderWindow::IsDirect()
{
  return this->Internal->Context != EGL_NO_CONTEXT ? 1 : 0;
}

//------------------------------------------------------------------------------
void* vtkEGLHeadlessRenderWindow::GetGenericDisplayId()
{
  return this->Internal->Display;
}

//------------------------------------------------------------------------------
vtkRenderWindowInteractor* vtkEGLHeadlessRenderWindow::MakeRenderWindowInteractor()
{
  // As vtkRenderWindow's.
  this->Interactor = vtkGenericRenderWindowInteractor::New();
  this->Interactor->SetRenderWindow(this);
  return this->Interactor;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::SetInteractor(vtkRenderWindowInteractor* interactor)
{
  if (interactor && interactor->IsA("vtkXRenderWindowInteractor"))
  {
    vtkErrorMacro("vtkEGLHeadlessRenderWindow has no X11 window for a vtkXRenderWindowInteractor "
                  "(its Initialize() would crash): use vtkGenericRenderWindowInteractor, which "
                  "MakeRenderWindowInteractor() gives. The interactor is not attached.");
    if (interactor->GetRenderWindow() == this)
    {
      interactor->SetRenderWindow(nullptr);
    }
    return;
  }
  this->Superclass::SetInteractor(interactor);
}

//------------------------------------------------------------------------------
void* vtkEGLHeadlessRenderWindow::GetGenericContext()
{
  return this->Internal->Context;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::SetShowWindow(bool)
{
  // There is no window to show.
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::GetColorBufferSizes(int* rgba)
{
  if (!rgba)
  {
    return 0;
  }
  rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0;
  if (!this->BeginFramebufferQuery())
  {
    return 0;
  }
  const GLenum names[4] = { GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE,
    GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE, GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE,
    GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE };
  for (int i = 0; i < 4; ++i)
  {
    GLint size = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, names[i], &size);
    rgba[i] = glGetError() == GL_NO_ERROR ? static_cast<int>(size) : 0;
  }
  this->EndFramebufferQuery();
  return rgba[0] + rgba[1] + rgba[2] + rgba[3];
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::GetDepthBufferSize()
{
  if (!this->BeginFramebufferQuery())
  {
    return 0;
  }
  GLint size = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &size);
  if (glGetError() != GL_NO_ERROR)
  {
    size = 0;
  }
  this->EndFramebufferQuery();
  return static_cast<int>(size);
}

//------------------------------------------------------------------------------
bool vtkEGLHeadlessRenderWindow::BeginFramebufferQuery()
{
  if (!this->ContextReady)
  {
    return false;
  }
  this->MakeCurrent();
  if (!this->RenderFramebuffer || this->RenderFramebuffer->GetNumberOfColorAttachments() == 0)
  {
    // Queried before the first frame: create the framebuffer VTK would.
    this->CreateFramebuffers(
      this->Size[0] > 0 ? this->Size[0] : 300, this->Size[1] > 0 ? this->Size[1] : 300);
  }
  this->GetState()->PushDrawFramebufferBinding();
  this->RenderFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  return true;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::EndFramebufferQuery()
{
  this->GetState()->PopDrawFramebufferBinding();
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::GetZbufferData(int x1, int y1, int x2, int y2, float* z)
{
  if (!this->ContextReady)
  {
    this->WarnNotRendered("GetZbufferData");
    // Defined values for callers that do not check: the far plane.
    if (z)
    {
      const std::size_t n = static_cast<std::size_t>(std::abs(x2 - x1) + 1) * (std::abs(y2 - y1) + 1);
      std::fill(z, z + n, 1.0f);
    }
    return VTK_ERROR;
  }
  this->MakeCurrent();
  return this->Superclass::GetZbufferData(x1, y1, x2, y2, z);
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::ReadPixels(
  const vtkRecti& rect, int front, int glFormat, int glType, void* data, int right)
{
  if (!this->ContextReady)
  {
    this->WarnNotRendered("pixel readback");
    // Defined values for callers that do not check (vtkWindowToImageFilter):
    // black, transparent pixels; far depths.
    if (data && rect.GetWidth() > 0 && rect.GetHeight() > 0)
    {
      const std::size_t values = static_cast<std::size_t>(rect.GetWidth()) * rect.GetHeight() *
        (glFormat == GL_RGBA ? 4 : glFormat == GL_RGB ? 3 : glFormat == GL_RG ? 2 : 1);
      if (glFormat == GL_DEPTH_COMPONENT && glType == GL_FLOAT)
      {
        std::fill_n(static_cast<float*>(data), values, 1.0f);
      }
      else
      {
        const std::size_t bytes = glType == GL_FLOAT || glType == GL_UNSIGNED_INT || glType == GL_INT ? 4
          : glType == GL_UNSIGNED_SHORT || glType == GL_SHORT || glType == GL_HALF_FLOAT             ? 2
                                                                                                      : 1;
        std::memset(data, 0, values * bytes);
      }
    }
    return VTK_ERROR;
  }
  return this->Superclass::ReadPixels(rect, front, glFormat, glType, data, right);
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::WarnNotRendered(const char* what)
{
  // A failed window said why once already; one that never rendered has
  // nothing to read yet.
  if (!this->Failed)
  {
    vtkWarningMacro(<< what << " before the first Render(): nothing to read yet.");
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DeviceIndex: " << this->DeviceIndex << "\n";
  os << indent << "Device: " << (this->DeviceDescription.empty() ? "(none yet)" : this->DeviceDescription)
     << "\n";
  os << indent << "EGL vendor: " << this->EGLVendor << "\n";
  os << indent << "EGL version: " << this->EGLVersion << "\n";
  os << indent << "GL renderer: " << this->GLRenderer << "\n";
  os << indent << "GL version: " << this->GLVersion << "\n";
  os << indent << "ContextReady: " << this->ContextReady << "\n";
  os << indent << "Failed: " << this->Failed << "\n";
}
