// The pass as the delegate of VTK's passes that draw it into a framebuffer
// of their own (vtkSSAAPass at four times the pixels, vtkGaussianBlurPass
// and vtkSobelGradientMagnitudePass a few pixels wider, vtkToneMappingPass
// in float colors): each image against the same wrapper around VTK's
// vtkRenderStepsPass (pass.WrappedByPasses).
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkGaussianBlurPass.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSSAAPass.h"
#include "vtkSobelGradientMagnitudePass.h"
#include "vtkToneMappingPass.h"

#include <functional>
#include <memory>
#include <string>

using namespace vtkrtPassTest;

namespace
{
/// A window whose renderer (viewport `vp`) draws a sphere of `res` x `res`
/// beside a small one through `wrapper`, lit by a light of `intensity`.
vtkSmartPointer<vtkImageData> DrawWrapped(
  vtkRenderPass* wrapper, const double vp[4], int res, double intensity)
{
  auto win = MakeWindow(300, 220);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetViewport(vp[0], vp[1], vp[2], vp[3]);
  ren->SetBackground(0.2, 0.25, 0.3);
  ren->AddActor(MeshActor(Sphere(-0.3, res)));
  ren->AddActor(MeshActor(Sphere(0.5, 16)));
  vtkNew<vtkLight> light;
  light->SetLightTypeToHeadlight();
  light->SetIntensity(intensity);
  ren->AddLight(light);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(20);
  ren->ResetCameraClippingRange();
  ren->SetPass(wrapper);
  win->Render();
  win->Render();
  return Grab(win);
}

void TestWrappedByPasses()
{
  struct Wrapper
  {
    std::string Name;
    std::function<vtkSmartPointer<vtkRenderPass>(vtkRenderPass*)> Around;
  };
  auto around = [](auto wrapper) {
    return [wrapper](vtkRenderPass* inner) -> vtkSmartPointer<vtkRenderPass> {
      auto w = vtkSmartPointer<typename decltype(wrapper)::element_type>::New();
      w->SetDelegatePass(inner);
      return w;
    };
  };
  const Wrapper wrappers[] = {
    { "vtkSSAAPass", around(std::shared_ptr<vtkSSAAPass>()) },
    { "vtkGaussianBlurPass", around(std::shared_ptr<vtkGaussianBlurPass>()) },
    { "vtkSobelGradientMagnitudePass", around(std::shared_ptr<vtkSobelGradientMagnitudePass>()) },
    { "vtkToneMappingPass", around(std::shared_ptr<vtkToneMappingPass>()) },
  };
  const double whole[4] = { 0.0, 0.0, 1.0, 1.0 }, part[4] = { 0.2, 0.15, 0.95, 0.9 };
  struct Case
  {
    std::string Label;
    const double* Viewport;
    int Resolution; // 400 x 400: a tree deep enough for the walks' tile entries
    int Samples;
    double Intensity; // above 1: colors above 1 before a tone mapping
  };
  const Case cases[] = { { "whole window", whole, 48, 1, 1.0 }, { "a viewport off the corner", part, 48, 1, 1.0 },
    { "a mesh deep enough for tile entries", whole, 400, 1, 1.0 }, { "4 samples a pixel", part, 48, 4, 1.0 },
    { "a light of intensity 4", whole, 48, 1, 4.0 }, { "a light of intensity 4, 4 samples", whole, 48, 4, 4.0 } };
  int written = 0;
  for (const Wrapper& w : wrappers)
  {
    for (const Case& c : cases)
    {
      vtkNew<vtkRenderStepsPass> steps;
      auto raster = DrawWrapped(w.Around(steps), c.Viewport, c.Resolution, c.Intensity);
      vtkNew<vtkRayTracePass> pass;
      pass->SetSamplesPerPixel(c.Samples);
      auto traced = DrawWrapped(w.Around(pass), c.Viewport, c.Resolution, c.Intensity);
      const double rmse = RootMeanSquareError(Blurred(raster), Blurred(traced));
      const std::string label = w.Name + " around the pass, " + c.Label;
      Check(pass->GetNumberOfTracedProps() == 2 && rmse <= 2.0,
        label + ": blurred RGB RMSE vs raster " + std::to_string(rmse) + " (unblurred " +
          std::to_string(RootMeanSquareError(raster, traced)) + ")");
      if (rmse > 2.0)
      {
        WriteFailedImages("wrapped-" + std::to_string(written++), raster, traced);
      }
    }
  }
  NoVTKOutput("wrapped by passes");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv, { { "WrappedByPasses", TestWrappedByPasses } });
}
