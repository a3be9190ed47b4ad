// Private to vtkEGLHeadlessRenderWindow: EGL displays, devices, configs and
// contexts (see vtkEGLHeadlessDevices.h).
#include "vtkEGLHeadlessDevices.h"

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>

namespace vtkrt
{
namespace egl
{

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


} // namespace

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

} // namespace egl
} // namespace vtkrt
