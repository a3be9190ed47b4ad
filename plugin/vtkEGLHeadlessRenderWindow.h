/**
 * @class   vtkEGLHeadlessRenderWindow
 * @brief   OpenGL render window that owns its own EGL context: no X server, no window.
 *
 * Debian's VTK 9.1 is built for GLX only. This window creates its own EGL
 * display and OpenGL core context (3.2 or later) and renders into VTK's
 * framebuffer objects; it is always offscreen. Use it wherever a
 * vtkRenderWindow is expected; read the image back with
 * vtkWindowToImageFilter, GetPixelData, GetRGBACharPixelData or GetZbufferData.
 *
 * Which EGL display it uses:
 * - a device index (SetDeviceIndex, or the environment variable
 *   VTKRT_EGL_DEVICE=index when the index is left at -1): the index-th device
 *   of eglQueryDevicesEXT through EGL_EXT_platform_device. An index that does
 *   not exist is an error (no silent fallback).
 * - otherwise, with EGL_PLATFORM set in the environment: EGL's default
 *   display, which honours EGL_PLATFORM.
 * - otherwise: the first hardware EGL device (one not flagged
 *   EGL_MESA_device_software), else Mesa's surfaceless platform
 *   (EGL_MESA_platform_surfaceless, llvmpipe), else the first EGL device.
 *
 * When no display or context can be made, the first Render() reports one
 * vtkErrorMacro and the window stays unusable: Render() and pixel readbacks
 * become no-ops (readbacks return VTK_ERROR / nullptr).
 *
 * Several windows may live in one process; each owns its own context and
 * MakeCurrent() switches between them. EGL displays are shared process-wide
 * and terminated only when the last window using one is finalized.
 */

#ifndef vtkEGLHeadlessRenderWindow_h
#define vtkEGLHeadlessRenderWindow_h

#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkrtPluginModule.h" // For export macro

#include <string> // For the stored EGL/GL description strings

class VTKRTPLUGIN_EXPORT vtkEGLHeadlessRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkEGLHeadlessRenderWindow* New();
  vtkTypeMacro(vtkEGLHeadlessRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // SetDeviceIndex / GetDeviceIndex (inherited from vtkRenderWindow): the EGL
  // device to use, as an index into eglQueryDevicesEXT's list. Here -1 is the
  // default: read VTKRT_EGL_DEVICE from the environment, and without it
  // choose automatically (see the class description). Takes effect when the
  // context is created (first Render or Initialize, or after Finalize).

  /**
   * Number of EGL devices that EGL_EXT_device_enumeration reports (0 when
   * the extension is missing).
   */
  int GetNumberOfDevices() override;

  /**
   * glibc's default malloc makes llvmpipe map and unmap its large buffers
   * every frame (page faults cost geometry-heavy frames several times).
   * Raising the mmap and trim thresholds removes that. Call once at program
   * start, before large allocations; applications and benchmarks should do
   * it the same way on every side of a comparison. Returns true on success
   * (false where mallopt is unavailable).
   */
  static bool TuneMallocForLargeBuffers();

  /**
   * Creates the EGL display and context if needed, makes the context current
   * and initialises VTK's OpenGL state. Called by Render(); call it yourself
   * to check for a usable context early. Reports one error on failure.
   */
  void Initialize() override;

  /**
   * True once the EGL context exists and VTK's OpenGL state is initialised.
   */
  bool IsContextReady() const { return this->ContextReady; }

  /**
   * True when creating the display or context failed (the window is then
   * unusable until Finalize, which allows another attempt).
   */
  bool HasFailed() const { return this->Failed; }

  /**
   * Releases VTK's graphics resources with this context current, then
   * destroys the context.
   */
  void Finalize() override;

  void Render() override;
  void Frame() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;

  /**
   * Makes this context current, keeping whichever was (any EGL context, or
   * none); PopContext makes that one current again. VTK releases a window's
   * graphics resources between the two while another window renders.
   */
  void PushContext() override;
  void PopContext() override;

  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;
  void* GetGenericDisplayId() override;
  void* GetGenericContext() override;

  /**
   * Always offscreen: there is no window to show, so ShowWindow stays false.
   */
  void SetShowWindow(bool) override;

  /**
   * A vtkGenericRenderWindowInteractor: widgets, pickers and interactor
   * styles work through it, driven by the application's own events.
   * (VTK's factory gives an X11 interactor in X11 builds, which needs an X
   * window and crashes in Initialize() on this one.)
   */
  vtkRenderWindowInteractor* MakeRenderWindowInteractor() override;

  /**
   * Refuses a vtkXRenderWindowInteractor with a VTK error, and detaches it,
   * so that its Initialize() reports no window instead of crashing.
   */
  void SetInteractor(vtkRenderWindowInteractor* interactor) override;

  /**
   * Accepts GLEW's GLEW_ERROR_NO_GLX_DISPLAY (Debian's GLEW is a GLX build,
   * but it has loaded every entry point before failing), checks for GL 3.2
   * and marks the context initialised.
   */
  void OpenGLInitContext() override;

  /**
   * Answered from VTK's render framebuffer: without an EGL surface there is
   * no default framebuffer to query.
   */
  int GetColorBufferSizes(int* rgba) override;
  int GetDepthBufferSize() override;

  using vtkOpenGLRenderWindow::GetZbufferData;
  int GetZbufferData(int x1, int y1, int x2, int y2, float* z) override;

  ///@{
  /**
   * Descriptions of the display and context in use (empty until created).
   */
  const char* GetEGLVendor() const { return this->EGLVendor.c_str(); }
  const char* GetEGLVersion() const { return this->EGLVersion.c_str(); }
  const char* GetDeviceDescription() const { return this->DeviceDescription.c_str(); }
  const char* GetGLRenderer() const { return this->GLRenderer.c_str(); }
  const char* GetGLVersion() const { return this->GLVersion.c_str(); }
  ///@}

protected:
  vtkEGLHeadlessRenderWindow();
  ~vtkEGLHeadlessRenderWindow() override;

  /**
   * VTK_ERROR before the first Render() (with a warning) or on a failed
   * window (silently: the failure was reported once).
   */
  int ReadPixels(const vtkRecti& rect, int front, int glFormat, int glType, void* data,
    int right) override;

  bool CreateContext();
  void DestroyContext();
  void ReportFailure(const std::string& why);
  void WarnNotRendered(const char* what);
  // Saves the draw framebuffer binding and binds the render framebuffer for
  // an attachment query (creating it as VTK would when queried before the
  // first frame); false without a context. EndFramebufferQuery restores.
  bool BeginFramebufferQuery();
  void EndFramebufferQuery();

  bool ContextReady = false;
  bool Failed = false;

  std::string EGLVendor;
  std::string EGLVersion;
  std::string DeviceDescription;
  std::string GLRenderer;
  std::string GLVersion;

private:
  vtkEGLHeadlessRenderWindow(const vtkEGLHeadlessRenderWindow&) = delete;
  void operator=(const vtkEGLHeadlessRenderWindow&) = delete;

  struct Internals;
  Internals* Internal;
};

#endif
