// Private to vtkEGLHeadlessRenderWindow: EGL displays (counted, as EGL's are
// process-wide), devices, the displays to try and a context made current on
// one. No VTK here.
#ifndef vtkEGLHeadlessDevices_h
#define vtkEGLHeadlessDevices_h

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <sstream>
#include <string>
#include <vector>

namespace vtkrt
{
namespace egl
{

/// Whether a space-separated extension list holds `token`.
bool HasToken(const char* list, const char* token);

/// EGL's device enumeration and platform display entry points, where the
/// client has them.
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

/// One display to try: a device, the surfaceless platform or the default one.
struct DisplayCandidate
{
  EGLDisplay Display;
  std::string Description;
};

/// Drops one user of a display that a successful MakeContextCurrent
/// counted; the last one terminates it.
void ReleaseDisplay(EGLDisplay display);

/// The name of an EGL error code.
const char* EGLErrorName(EGLint code);

/// The device index asked for by SetDeviceIndex or else VTKRT_EGL_DEVICE
/// (-1: none), and where it came from; false, with why, when the variable is
/// not an index.
bool RequestedDeviceIndex(int deviceIndex, int& index, std::string& source, std::string& why);

/// The displays to try, in order: the requested device only (false, with
/// why, when it does not exist), else EGL's default display when the user
/// chose EGL_PLATFORM, else hardware devices, Mesa's surfaceless platform,
/// a software device, and at last the default display.
bool CandidateDisplays(const EGLDeviceApi& api, int index, const std::string& indexSource,
  std::vector<DisplayCandidate>& candidates, std::string& why);

/// An OpenGL 3.2 core context made current on the candidate's display (with
/// a 1x1 pbuffer where surfaceless contexts are missing); false, with the
/// reason appended to why and everything acquired released, when it fails.
bool MakeContextCurrent(
  const DisplayCandidate& candidate, EGLContext& context, EGLSurface& surface, std::string& why);

} // namespace egl
} // namespace vtkrt

#endif
