#include "RenderFrames.h"

#include "RenderErrors.h"
#include "RenderOptions.h"
#include "RenderProgress.h"
#include "RenderReport.h"

#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkRayTracePass.h"
#include "vtkRenderer.h"

#include <iostream>

namespace vtkrtRender
{
vtkSmartPointer<vtkEGLHeadlessRenderWindow> NewWindow(const Options& opt, vtkRenderer* renderer)
{
  auto window = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  window->SetSize(opt.Width, opt.Height);
  // Explicit: VTK's default is 8 (llvmpipe clamps to 4) and MSAA costs a lot.
  window->SetMultiSamples(opt.Mode == "raster" && opt.Samples > 0 ? opt.Samples : 0);
  window->AddRenderer(renderer);
  return window;
}

double RenderFirstFrame(vtkEGLHeadlessRenderWindow* window, CapturingOutputWindow* output)
{
  const auto start = Clock::now();
  output->StartCapture();
  window->Render();
  output->StopCapture();
  const auto end = Clock::now();
  if (!window->IsContextReady())
  {
    throw Failure{ output->Captured.empty() ? std::string("no usable EGL/OpenGL context")
                                            : MessageOf(output->Captured.front()),
      ExitRuntimeError };
  }
  for (const std::string& text : output->Captured)
  {
    std::cerr << text;
  }
  return Milliseconds(start, end);
}

void TakeBackgroundBuilds(vtkEGLHeadlessRenderWindow* window, vtkRenderer* renderer)
{
  auto* pass = vtkRayTracePass::SafeDownCast(renderer->GetPass());
  if (pass && pass->GetNumberOfBackgroundBuilds() > 0)
  {
    pass->WaitForBackgroundBuilds();
    window->Render();
    window->WaitForCompletion();
  }
}

double SteadyFrameMilliseconds(
  vtkEGLHeadlessRenderWindow* window, vtkRenderer* renderer, int frames)
{
  if (frames <= 0)
  {
    return 0.0;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkCamera> saved;
  saved->DeepCopy(camera);
  const auto start = Clock::now();
  for (int i = 0; i < frames; ++i)
  {
    camera->Azimuth(360.0 / frames);
    renderer->ResetCameraClippingRange();
    window->Render();
  }
  const double steady = Milliseconds(start, Clock::now()) / frames;
  camera->DeepCopy(saved);
  window->Render();
  return steady;
}

int AccumulateFrames(vtkEGLHeadlessRenderWindow* window, vtkRenderer* renderer, int frames)
{
  auto* pass = vtkRayTracePass::SafeDownCast(renderer->GetPass());
  if (!pass || frames <= 0)
  {
    return 0;
  }
  Progress::Begin("accumulating " + std::to_string(frames) + " frames");
  // The frame already drawn counts when nothing changed since.
  for (int done = pass->GetAccumulatedFrames(); done < frames; ++done)
  {
    window->Render();
    Progress::Update(pass->GetAccumulatedFrames(), frames);
  }
  Progress::End();
  return pass->GetAccumulatedFrames();
}
} // namespace vtkrtRender
