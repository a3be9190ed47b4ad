// vtkRayTracePass in a desktop VTK window: the demo scene (bunny + sphere
// glyphs colored through a LUT, as `vtkrt-render --demo` builds it) rendered
// through the pass in VTK's default render window (vtkXOpenGLRenderWindow on
// this X11 build of VTK, GLX) and, side by side, in vtkEGLHeadlessRenderWindow;
// the two images must agree, also after a camera move and a resize, and the
// X11 image matches the baseline window_X11Demo.
// Run under an X server (CTest uses run-under-xvfb.sh: `xvfb-run -a`);
// without one (no DISPLAY) it exits 77, which CTest reports as skipped.
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"
#include "vtkrtDemoGlyphs.h"
#include "vtkrtImageRegression.h"
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>
#include <iostream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
/// The demo scene of vtkrt-render (bunny, 144 sphere glyphs through a LUT)
/// in `ren`, traced by `pass`.
void BuildDemo(vtkRenderer* ren, vtkPolyData* bunny, vtkPolyData* centres, vtkRayTracePass* pass)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(bunny);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.86, 0.82, 0.74);
  ren->AddActor(actor);

  vtkSmartPointer<vtkActor> glyphActor = vtkrtDemo::NewGlyphActor(centres);
  ren->AddActor(glyphActor);
  ren->SetBackground(0.32, 0.34, 0.43);
  ren->SetPass(pass);
}

/// The X11 and EGL images agree: at most 0.2% of the pixels differ by more
/// than 2/255, and vtkImageDifference's error stays under 2.
void Agree(vtkImageData* x11, vtkImageData* egl, const std::string& when)
{
  int dx[3], de[3];
  x11->GetDimensions(dx);
  egl->GetDimensions(de);
  const long differing = CountDifferingPixels(x11, egl, 2);
  const double error = Difference(x11, egl);
  const long allowed = static_cast<long>(dx[0]) * dx[1] / 500;
  Check(dx[0] == de[0] && dx[1] == de[1] && differing >= 0 && differing <= allowed && error <= 2.0,
    when + ": X11 (GLX) and EGL images agree (" + std::to_string(dx[0]) + "x" +
      std::to_string(dx[1]) + ", " + std::to_string(differing) + " pixels differ, allowed " +
      std::to_string(allowed) + ", error " + std::to_string(error) + ")");
  if (differing > allowed || error > 2.0)
  {
    WritePNG(x11, std::string(VTKRT_TEMP_DIR) + "/window_X11Demo_x11.png");
    WritePNG(egl, std::string(VTKRT_TEMP_DIR) + "/window_X11Demo_egl.png");
  }
}
} // namespace

int main()
{
  Output = vtkrtTestOutputWindow::Install();
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::cout << "SKIP: no X display (DISPLAY unset); run under xvfb-run\n";
    return 77;
  }
  auto bunny = ReadPolyData("bunny.vtp");
  auto centres = ReadPolyData("demo-spheres.vtp");
  if (bunny->GetNumberOfCells() == 0 || !centres->GetPointData()->GetArray("radius"))
  {
    std::cout << "FAIL demo data not found under " << VTKRT_DATA_DIR << "\n";
    return EXIT_FAILURE;
  }

  // The reference: the same sequence (first frame, camera move, resize) in
  // the headless EGL window, rendered first and finalized before the X11
  // window exists (glvnd lets a thread have a current context of one API
  // at a time: EGL or GLX).
  vtkSmartPointer<vtkImageData> reference[3];
  auto sequence = [&](vtkRenderWindow* win, vtkRenderer* ren, vtkRayTracePass* pass,
                    vtkSmartPointer<vtkImageData> images[3], bool checks) {
    BuildDemo(ren, bunny, centres, pass);
    vtkCamera* camera = ren->GetActiveCamera();
    ren->ResetCamera();
    camera->Azimuth(30.0);
    camera->Elevation(20.0);
    camera->OrthogonalizeViewUp();
    camera->Zoom(1.4);
    ren->ResetCameraClippingRange();
    win->Render();
    if (checks)
    {
      // Which GL the X11 window got (information: Mesa GLX llvmpipe on CI).
      const std::string capabilities = win->ReportCapabilities();
      const std::size_t at = capabilities.find("OpenGL renderer");
      if (at != std::string::npos)
      {
        std::cout << "info: X11 window: "
                  << capabilities.substr(at, capabilities.find('\n', at) - at) << "\n";
      }
      Check(pass->GetNumberOfTracedProps() == 2 &&
          std::string(pass->GetLastFeatureKey()).find("T1S1") == 0,
        std::string("X11: the pass traces the bunny and the glyphs (key ") +
          pass->GetLastFeatureKey() + ")");
      Check(pass->GetLastBVHBuilds() == 2 && pass->GetLastShaderCompiles() >= 1,
        "X11: first frame builds both BVHs and compiles the shader");
    }
    images[0] = Grab(win);

    // Camera move: nothing rebuilt, uploaded or compiled.
    camera->Azimuth(40.0);
    camera->Elevation(-10.0);
    camera->OrthogonalizeViewUp();
    ren->ResetCameraClippingRange();
    win->Render();
    if (checks)
    {
      Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0 &&
          pass->GetLastShaderCompiles() == 0 && pass->GetLastFrameBytesUploaded() > 0,
        "X11 camera move: no build, no geometry upload, no compile; instance records uploaded");
    }
    images[1] = Grab(win);

    // Resize: the traced image follows the new size.
    win->SetSize(400, 300);
    win->Render();
    if (checks)
    {
      Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0,
        "X11 resize: no build, no geometry upload");
    }
    images[2] = Grab(win);
  };
  {
    auto egl = MakeWindow(320, 240);
    vtkNew<vtkRenderer> ren;
    egl->AddRenderer(ren);
    vtkNew<vtkRayTracePass> pass;
    sequence(egl, ren, pass, reference, false);
    ren->SetPass(nullptr);
    egl->Finalize();
  }

  // VTK's default window for this build: an X11 (GLX) window, as a desktop
  // VTK application gets it.
  vtkSmartPointer<vtkRenderWindow> x11 = vtk::TakeSmartPointer(vtkRenderWindow::New());
  Check(x11->IsA("vtkXOpenGLRenderWindow") != 0,
    std::string("vtkRenderWindow::New() gives a vtkXOpenGLRenderWindow (") +
      x11->GetClassName() + ")");
  x11->SetSize(320, 240);
  x11->SetMultiSamples(0);
  x11->SetWindowName("vtkrt: vtkRayTracePass in an X11 window");
  vtkNew<vtkRenderer> renX11;
  x11->AddRenderer(renX11);
  vtkNew<vtkRayTracePass> passX11;
  vtkSmartPointer<vtkImageData> images[3];
  sequence(x11, renX11, passX11, images, true);

  const long covered = CountForegroundPixels(images[0], renX11->GetBackground());
  Check(covered > 320 * 240 / 8, "X11: the scene covers the view (" + std::to_string(covered) +
      " pixels)");
  Agree(images[0], reference[0], "first frame");
  Check(vtkrtCompareWithBaseline(images[0], "window_X11Demo") == 1,
    "X11 image matches the baseline window_X11Demo");
  Agree(images[1], reference[1], "after a camera move");
  Check(CountDifferingPixels(images[1], images[0], 24) > 1000, "the camera move changes the image");
  int dims[3];
  images[2]->GetDimensions(dims);
  Check(dims[0] == 400 && dims[1] == 300,
    "X11 resize: a 400x300 image (" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + ")");
  Agree(images[2], reference[2], "after a resize");

  // Removing the pass gives VTK's raster back in the X11 window.
  renX11->SetPass(nullptr);
  x11->Render();
  auto raster = Grab(x11);
  const double rasterError = Difference(raster, images[2]);
  Check(CountForegroundPixels(raster, renX11->GetBackground()) > 400 * 300 / 8 &&
      CountDifferingPixels(raster, images[2], 0) > 0 && rasterError < 400.0,
    "X11 without the pass: raster draws the same scene (error vs traced " +
      std::to_string(rasterError) + ")");

  NoVTKOutput("X11Demo");
  x11->Finalize();
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
