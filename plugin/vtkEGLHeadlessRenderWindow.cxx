#include "vtkEGLHeadlessRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

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

namespace
{
// EGL displays are process-wide: eglTerminate would pull the display out from
// under every other window using it, so count the users of each display.
struct DisplayRegistry
{
  std::mutex Mutex;
  std::map<EGLDisplay, int> Users;
};

DisplayRegistry& Registry()
{
  static DisplayRegistry registry;
  return registry;
}

bool AcquireDisplay(EGLDisplay display, EGLint& major, EGLint& minor)
{
  DisplayRegistry& reg = Registry();
  std::lock_guard<std::mutex> lock(reg.Mutex);
  // eglInitialize on an initialised display only returns its version.
  if (!eglInitialize(display, &major, &minor))
  {
    return false;
  }
  ++reg.Users[display];
  return true;
}

void ReleaseDisplay(EGLDisplay display)
{
  DisplayRegistry& reg = Registry();
  std::lock_guard<std::mutex> lock(reg.Mutex);
  auto it = reg.Users.find(display);
  if (it == reg.Users.end())
  {
    return;
  }
  if (--it->second == 0)
  {
    reg.Users.erase(it);
    eglTerminate(display);
  }
}

bool HasToken(const char* list, const char* token)
{
  if (!list)
  {
    return false;
  }
  const size_t len = std::strlen(token);
  for (const char* p = list; (p = std::strstr(p, token)) != nullptr; p += len)
  {
    const bool startOk = (p == list || p[-1] == ' ');
    const bool endOk = (p[len] == ' ' || p[len] == '\0');
    if (startOk && endOk)
    {
      return true;
    }
  }
  return false;
}

const char* EGLErrorName(EGLint code)
{
  switch (code)
  {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "unknown EGL error";
  }
}

struct EGLDeviceApi
{
  PFNEGLQUERYDEVICESEXTPROC QueryDevices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC QueryDeviceString = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC GetPlatformDisplay = nullptr;

  EGLDeviceApi()
  {
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (HasToken(clientExt, "EGL_EXT_platform_base"))
    {
      this->GetPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    }
    if (HasToken(clientExt, "EGL_EXT_device_enumeration") ||
      HasToken(clientExt, "EGL_EXT_device_base"))
    {
      this->QueryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      this->QueryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    }
  }

  std::vector<EGLDeviceEXT> Devices() const
  {
    std::vector<EGLDeviceEXT> devices;
    EGLint count = 0;
    if (!this->QueryDevices || !this->QueryDevices(0, nullptr, &count) || count <= 0)
    {
      return devices;
    }
    devices.resize(static_cast<size_t>(count));
    if (!this->QueryDevices(count, devices.data(), &count))
    {
      count = 0;
    }
    devices.resize(static_cast<size_t>(count));
    return devices;
  }

  bool IsSoftware(EGLDeviceEXT device) const
  {
    const char* ext =
      this->QueryDeviceString ? this->QueryDeviceString(device, EGL_EXTENSIONS) : nullptr;
    return HasToken(ext, "EGL_MESA_device_software");
  }

  std::string Describe(EGLDeviceEXT device, int index) const
  {
    std::ostringstream os;
    os << "EGL device " << index;
    if (this->QueryDeviceString)
    {
      const char* ext = this->QueryDeviceString(device, EGL_EXTENSIONS);
      if (HasToken(ext, "EGL_MESA_device_software"))
      {
        os << " (software)";
      }
      if (HasToken(ext, "EGL_EXT_device_drm"))
      {
        const char* file = this->QueryDeviceString(device, EGL_DRM_DEVICE_FILE_EXT);
        if (file)
        {
          os << " " << file;
        }
      }
    }
    return os.str();
  }
};

// One display to try: a device, the surfaceless platform or the default one.
struct DisplayCandidate
{
  EGLDisplay Display;
  std::string Description;
};

// The device index asked for by SetDeviceIndex or else VTKRT_EGL_DEVICE
// (-1: none), and where it came from; false, with why, when the variable is
// not an index.
bool RequestedDeviceIndex(int deviceIndex, int& index, std::string& source, std::string& why)
{
  index = deviceIndex;
  source = "SetDeviceIndex";
  if (index < 0)
  {
    const char* env = std::getenv("VTKRT_EGL_DEVICE");
    if (env && *env)
    {
      char* end = nullptr;
      errno = 0;
      const long value = std::strtol(env, &end, 10);
      if (errno != 0 || end == env || *end != '\0' || value < 0 || value > 1 << 20)
      {
        why = std::string("VTKRT_EGL_DEVICE=\"") + env + "\" is not a device index (0, 1, ...)";
        return false;
      }
      index = static_cast<int>(value);
      source = "VTKRT_EGL_DEVICE";
    }
  }
  return true;
}

// The displays to try, in order: the requested device only (false, with
// why, when it does not exist), else EGL's default display when the user
// chose EGL_PLATFORM, else hardware devices, Mesa's surfaceless platform,
// a software device, and at last the default display.
bool CandidateDisplays(const EGLDeviceApi& api, int index, const std::string& indexSource,
  std::vector<DisplayCandidate>& candidates, std::string& why)
{
  if (index >= 0)
  {
    // An explicit device: that one or nothing.
    if (!api.QueryDevices || !api.GetPlatformDisplay)
    {
      why = "EGL device " + std::to_string(index) + " requested (" + indexSource +
        ") but EGL_EXT_device_enumeration/EGL_EXT_platform_device are not available";
      return false;
    }
    const std::vector<EGLDeviceEXT> devices = api.Devices();
    if (index >= static_cast<int>(devices.size()))
    {
      why = "EGL device " + std::to_string(index) + " requested (" + indexSource + ") but only " +
        std::to_string(devices.size()) + " EGL device(s) exist";
      return false;
    }
    candidates.push_back({ api.GetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[index], nullptr),
      api.Describe(devices[index], index) });
  }
  else if (const char* platform = std::getenv("EGL_PLATFORM"))
  {
    // The user chose a platform for EGL's default display: respect it.
    candidates.push_back({ eglGetDisplay(EGL_DEFAULT_DISPLAY),
      std::string("EGL default display (EGL_PLATFORM=") + platform + ")" });
  }
  else
  {
    const std::vector<EGLDeviceEXT> devices = api.Devices();
    if (api.GetPlatformDisplay)
    {
      for (size_t i = 0; i < devices.size(); ++i)
      {
        if (!api.IsSoftware(devices[i]))
        {
          candidates.push_back({ api.GetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr),
            api.Describe(devices[i], static_cast<int>(i)) });
        }
      }
      if (HasToken(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_MESA_platform_surfaceless"))
      {
        candidates.push_back(
          { api.GetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
            "Mesa surfaceless platform" });
      }
      if (!devices.empty() && api.IsSoftware(devices[0]))
      {
        candidates.push_back({ api.GetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr),
          api.Describe(devices[0], 0) });
      }
    }
    if (candidates.empty())
    {
      candidates.push_back({ eglGetDisplay(EGL_DEFAULT_DISPLAY), "EGL default display" });
    }
  }
  return true;
}

// A pbuffer-capable config if there is one (needed without
// EGL_KHR_surfaceless_context); else any config; else no config at all.
EGLConfig ChooseConfig(EGLDisplay display, const char* displayExt, bool& pbufferConfig)
{
  EGLConfig config = nullptr;
  EGLint numConfigs = 0;
  const EGLint pbufferAttribs[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
    EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
    EGL_NONE };
  const EGLint anyAttribs[] = { EGL_SURFACE_TYPE, EGL_DONT_CARE, EGL_RENDERABLE_TYPE,
    EGL_OPENGL_BIT, EGL_NONE };
  pbufferConfig =
    eglChooseConfig(display, pbufferAttribs, &config, 1, &numConfigs) && numConfigs > 0;
  if (!pbufferConfig &&
    !(eglChooseConfig(display, anyAttribs, &config, 1, &numConfigs) && numConfigs > 0))
  {
    config = HasToken(displayExt, "EGL_KHR_no_config_context") ? EGL_NO_CONFIG_KHR : nullptr;
  }
  return config;
}

// An OpenGL 3.2 core context made current on the candidate's display (with
// a 1x1 pbuffer where surfaceless contexts are missing); false, with the
// reason appended to why and everything acquired released, when it fails.
bool MakeContextCurrent(
  const DisplayCandidate& candidate, EGLContext& context, EGLSurface& surface, std::string& why)
{
  EGLDisplay display = candidate.Display;
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY)
  {
    why += candidate.Description + ": no EGL display (" + EGLErrorName(eglGetError()) + "); ";
    return false;
  }
  if (!AcquireDisplay(display, major, minor))
  {
    why += candidate.Description + ": eglInitialize failed (" + EGLErrorName(eglGetError()) + "); ";
    return false;
  }

  const char* displayExt = eglQueryString(display, EGL_EXTENSIONS);
  context = EGL_NO_CONTEXT;
  surface = EGL_NO_SURFACE;
  if (!eglBindAPI(EGL_OPENGL_API))
  {
    why += candidate.Description + ": desktop OpenGL is not supported; ";
    ReleaseDisplay(display);
    return false;
  }

  bool pbufferConfig = false;
  EGLConfig config = ChooseConfig(display, displayExt, pbufferConfig);

  // Ask for 3.2 core; drivers hand out their highest compatible version.
  const EGLint contextAttribs[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
  if (config != nullptr || HasToken(displayExt, "EGL_KHR_no_config_context"))
  {
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
  }
  if (context == EGL_NO_CONTEXT)
  {
    why += candidate.Description + ": no OpenGL 3.2 core context (" +
      EGLErrorName(eglGetError()) + "); ";
    ReleaseDisplay(display);
    return false;
  }
  if (!HasToken(displayExt, "EGL_KHR_surfaceless_context"))
  {
    const EGLint surfaceAttribs[] = { EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE };
    surface = pbufferConfig ? eglCreatePbufferSurface(display, config, surfaceAttribs)
                            : EGL_NO_SURFACE;
    if (surface == EGL_NO_SURFACE)
    {
      why += candidate.Description + ": neither surfaceless contexts nor a pbuffer; ";
      eglDestroyContext(display, context);
      ReleaseDisplay(display);
      return false;
    }
  }
  if (!eglMakeCurrent(display, surface, surface, context))
  {
    why += candidate.Description + ": eglMakeCurrent failed (" + EGLErrorName(eglGetError()) +
      "); ";
    if (surface != EGL_NO_SURFACE)
    {
      eglDestroySurface(display, surface);
    }
    eglDestroyContext(display, context);
    ReleaseDisplay(display);
    return false;
  }
  return true;
}
} // namespace

struct vtkEGLHeadlessRenderWindow::Internals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE; // 1x1 pbuffer, only without surfaceless_context
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
