// vtkrt-render: renders mesh files or the demo scene, ray traced by
// vtkRayTracePass or rasterized by VTK, headless (EGL) into an image with a
// report of timings and picks, or in a window to look around in. Run with
// --help for the options. The steps live in render/, one unit a concern:
// options, errors, reading, scene, colouring, camera, frames, pick, report,
// progress, window.
#include "render/RenderCamera.h"
#include "render/RenderErrors.h"
#include "render/RenderFrames.h"
#include "render/RenderOptions.h"
#include "render/RenderPick.h"
#include "render/RenderProgress.h"
#include "render/RenderReport.h"
#include "render/RenderScene.h"
#include "render/RenderWindow.h"

#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtksys/SystemTools.hxx"

#include <iostream>
#include <string>
#include <vector>

using namespace vtkrtRender;

namespace
{
// Ray traced unless asked otherwise; fails before any work when raytrace
// mode is asked of a build without it.
void ResolveMode(Options& opt)
{
  vtkNew<vtkRenderer> probe;
  const bool traceable = UseRayTracing(probe, opt);
  if (opt.Mode.empty())
  {
    opt.Mode = traceable ? "raytrace" : "raster";
  }
  if (opt.Mode == "raytrace")
  {
    if (!traceable)
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

// A window when there is a display and no --output (or events to play).
bool WantsWindow(const Options& opt)
{
  if (opt.OutputGiven)
  {
    return false;
  }
  if (DisplayAvailable())
  {
    return true;
  }
  if (!opt.InteractionPlay.empty())
  {
    throw Failure{ "--interaction-test-play needs a display for the window", ExitRuntimeError };
  }
  return false;
}

// Headless: the first frame, the timed orbit, accumulation, picks, the image
// and the report.
int RunOffscreen(Scene& scene, const Options& opt, CapturingOutputWindow* output, Timings& timings)
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> window = NewWindow(opt, scene.Renderer);
  Progress::Begin(opt.Mode == "raytrace" ? "first frame (context, BVH build, upload, shaders)"
                                         : "first frame (context, upload)");
  timings.FirstFrame = RenderFirstFrame(window, output);
  Progress::End();
  KeepPassPhases(scene.Renderer, timings);
  TakeBackgroundBuilds(window, scene.Renderer);
  timings.SteadyFrame = SteadyFrameMilliseconds(window, scene.Renderer, opt.Frames);
  const auto accumulationStart = Clock::now();
  timings.AccumulatedFrames = AccumulateFrames(window, scene.Renderer, opt.Trace.Progressive);
  timings.Accumulation = Milliseconds(accumulationStart, Clock::now());
  std::vector<std::string> picks;
  for (const Pixel& pixel : opt.Picks)
  {
    picks.push_back(PickPixel(scene, pixel, opt.Height));
  }
  WriteImage(window, opt.Output, output);
  PrintReport(opt, scene, window, timings, picks);
  return ExitOk;
}

int Run(Options opt)
{
  Progress::Enable(opt.Verbose);
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  vtkNew<CapturingOutputWindow> output;
  vtkOutputWindow::SetInstance(output);
  ResolveMode(opt);
  const bool window = WantsWindow(opt);
  if (!window)
  {
    RequireOutputDirectory(opt);
  }

  Timings timings;
  const auto start = Clock::now();
  Scene scene;
  BuildScene(scene, opt, output);
  AimCamera(scene, opt);
  timings.SceneBuild = Milliseconds(start, Clock::now());
  if (window)
  {
    return RunWindow(scene, opt);
  }
  return RunOffscreen(scene, opt, output, timings);
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
    Progress::Interrupt();
    std::cerr << "vtkrt-render: " << e.Message << "\n(run vtkrt-render --help for the options)\n";
    return ExitUsage;
  }
  catch (const Failure& e)
  {
    Progress::Interrupt();
    std::cerr << "vtkrt-render: " << e.Message << "\n";
    return e.Code;
  }
}
