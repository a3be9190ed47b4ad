// vtkrt-render: renders a mesh file or the demo scene headless (EGL) to a PNG,
// rasterized by VTK or ray traced by vtkRayTracePass, and reports timings.
// Run with --help for the options. The steps live in render/, one unit a
// concern: options, errors, scene, camera, frames, pick, report.
#include "render/RenderCamera.h"
#include "render/RenderErrors.h"
#include "render/RenderFrames.h"
#include "render/RenderOptions.h"
#include "render/RenderPick.h"
#include "render/RenderReport.h"
#include "render/RenderScene.h"

#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtksys/SystemTools.hxx"

#include <iostream>
#include <string>

using namespace vtkrtRender;

namespace
{
// Fails before any work when raytrace mode is asked of a build without it.
void RequireMode(const Options& opt)
{
  if (opt.Mode == "raytrace")
  {
    vtkNew<vtkRenderer> probe;
    if (!UseRayTracing(probe))
    {
      throw Failure{ "raytrace mode is not available in this build (vtkRayTracePass was not "
                     "built); use --mode raster",
        ExitUnavailable };
    }
  }
}

// Fails before any work when the image cannot go where asked.
void RequireOutputDirectory(const Options& opt)
{
  const std::string outputDir = vtksys::SystemTools::GetFilenamePath(opt.Output);
  if (!outputDir.empty() && !vtksys::SystemTools::FileIsDirectory(outputDir))
  {
    throw Failure{ "cannot write '" + opt.Output + "': no directory '" + outputDir + "'",
      ExitRuntimeError };
  }
}

int Run(const Options& opt)
{
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  vtkNew<CapturingOutputWindow> output;
  vtkOutputWindow::SetInstance(output);
  RequireMode(opt);
  RequireOutputDirectory(opt);

  Timings timings;
  const auto start = Clock::now();
  Scene scene;
  BuildScene(scene, opt, output);
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> window = NewWindow(opt, scene.Renderer);
  AimCamera(scene, opt);
  timings.SceneBuild = Milliseconds(start, Clock::now());

  timings.FirstFrame = RenderFirstFrame(window, output);
  KeepPassPhases(scene.Renderer, timings);
  timings.SteadyFrame = SteadyFrameMilliseconds(window, scene.Renderer, opt.Frames);
  const std::string pick = opt.Pick ? PickPixel(opt, scene) : std::string();
  WriteImage(window, opt.Output, output);
  PrintReport(opt, scene, window, timings, pick);
  return ExitOk;
}
} // namespace

int main(int argc, char* argv[])
{
  try
  {
    bool help = false;
    const Options opt = ParseArguments(argc, argv, help);
    if (help)
    {
      PrintHelp(std::cout);
      return ExitOk;
    }
    return Run(opt);
  }
  catch (const UsageError& e)
  {
    std::cerr << "vtkrt-render: " << e.Message << "\n(run vtkrt-render --help for the options)\n";
    return ExitUsage;
  }
  catch (const Failure& e)
  {
    std::cerr << "vtkrt-render: " << e.Message << "\n";
    return e.Code;
  }
}
