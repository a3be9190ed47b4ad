#include "RenderReport.h"

#include "RenderErrors.h"
#include "RenderOptions.h"
#include "RenderScene.h"

#include "vtkBMPWriter.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkImageWriter.h"
#include "vtkJPEGWriter.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPropCollection.h"
#include "vtkRayTracePass.h"
#include "vtkRenderer.h"
#include "vtkTIFFWriter.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <iomanip>
#include <iostream>

namespace vtkrtRender
{
namespace
{
// The writer of the image type `path`'s extension names (checked by the
// option parser).
vtkSmartPointer<vtkImageWriter> NewImageWriter(const std::string& path)
{
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  if (ext == ".jpg" || ext == ".jpeg")
  {
    auto writer = vtkSmartPointer<vtkJPEGWriter>::New();
    writer->SetQuality(95);
    return writer;
  }
  if (ext == ".tif" || ext == ".tiff")
  {
    return vtkSmartPointer<vtkTIFFWriter>::New();
  }
  if (ext == ".bmp")
  {
    return vtkSmartPointer<vtkBMPWriter>::New();
  }
  return vtkSmartPointer<vtkPNGWriter>::New();
}
} // namespace

void WriteImage(
  vtkEGLHeadlessRenderWindow* window, const std::string& path, CapturingOutputWindow* output)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  output->StartCapture();
  vtkSmartPointer<vtkImageWriter> writer = NewImageWriter(path);
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
  output->StopCapture();
  if (!output->Captured.empty() || !vtksys::SystemTools::FileExists(path, true))
  {
    throw Failure{ "cannot write '" + path + "'" +
        (output->Captured.empty() ? std::string() : ": " + MessageOf(output->Captured.front())),
      ExitRuntimeError };
  }
}

void KeepPassPhases(vtkRenderer* renderer, Timings& timings)
{
  timings.PassPhases.clear();
  auto* pass = vtkRayTracePass::SafeDownCast(renderer->GetPass());
  if (pass)
  {
    timings.PassPhases = { 1e3 * pass->GetLastExtractionSeconds(),
      1e3 * pass->GetLastTriangulationSeconds(), 1e3 * pass->GetLastBuildSeconds(),
      1e3 * pass->GetLastPackingSeconds(), 1e3 * pass->GetLastUploadSeconds(),
      1e3 * pass->GetLastShaderCompileSeconds() };
  }
}

void PrintReport(const Options& opt, const Scene& scene, vtkEGLHeadlessRenderWindow* window,
  const Timings& timings, const std::vector<std::string>& picks)
{
  std::cout << std::fixed << std::setprecision(1);
  std::cout << "vtkrt-render: " << opt.Mode << " " << opt.Width << "x" << opt.Height
            << ", MultiSamples " << window->GetMultiSamples() << "\n"
            << "  scene:        " << scene.Description << "\n"
            << "  triangles:    " << scene.Triangles << "\n"
            << "  spheres:      " << scene.Spheres << "\n";
  if (scene.Points > 0)
  {
    std::cout << "  points:       " << scene.Points << " (point cloud, as spheres)\n";
  }
  if (!scene.Coloring.empty())
  {
    std::cout << "  coloured by:  " << scene.Coloring << "\n";
  }
  if (auto* pass = vtkRayTracePass::SafeDownCast(scene.Renderer->GetPass()))
  {
    std::cout << "  tracing:      " << pass->GetSamplesPerPixel() << " ray(s) per pixel, shadows "
              << (pass->GetShadows() ? "on" : "off") << ", ambient occlusion "
              << pass->GetAmbientOcclusionSamples() << " ray(s), precision "
              << pass->GetPrecisionModeAsString() << ", preset "
              << pass->GetQualityPresetAsString() << "\n"
              << "  traced props: " << pass->GetNumberOfTracedProps() << " of "
              << scene.Renderer->GetViewProps()->GetNumberOfItems() << " (the rest drawn by raster)\n";
  }
  std::cout << "  device:       " << window->GetGLRenderer() << " (" << window->GetGLVersion()
            << "; " << window->GetDeviceDescription() << ")\n"
            << "  scene build:  " << timings.SceneBuild << " ms (read + set up)\n"
            << "  first frame:  " << timings.FirstFrame << " ms (context, upload, build)\n";
  if (timings.PassPhases.size() == 6)
  {
    const std::vector<double>& p = timings.PassPhases;
    std::cout << "    of which:   extraction " << p[0] << ", triangulation " << p[1]
              << ", BVH build " << p[2] << ", packing " << p[3] << ", upload " << p[4]
              << ", shader compile " << p[5] << " ms\n";
  }
  if (opt.Frames > 0)
  {
    std::cout << "  steady frame: " << timings.SteadyFrame << " ms (mean of " << opt.Frames
              << " orbit steps)\n";
  }
  if (opt.Trace.Progressive > 0 && opt.Mode == "raytrace")
  {
    std::cout << "  accumulated:  " << timings.AccumulatedFrames << " frames in "
              << timings.Accumulation << " ms\n";
  }
  for (const std::string& pick : picks)
  {
    std::cout << "  " << pick << "\n";
  }
  std::cout << "  wrote " << opt.Output << "\n";
}
} // namespace vtkrtRender
