// Image tests of vtkRayTracePass: each case renders a scene with VTK's
// raster, then with the pass, and asserts (1) the ray-traced image is close
// to raster (vtkImageDifference's thresholded error, summed over the image:
// "about this many wholly wrong pixels"; differences come from silhouettes
// without antialiasing and the rasterizer's coverage rules, never from
// shading), and (2) it matches its baseline under data/baselines/.
// TestRayTracePass <Case>.
#include "vtkrtImageRegression.h"
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
int Failures = 0;
vtkrtTestOutputWindow* Output = nullptr;

void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  if (!ok)
  {
    ++Failures;
  }
}

void NoVTKOutput(const std::string& label)
{
  Check(Output->GetNumberOfErrors() == 0 && Output->GetNumberOfWarnings() == 0,
    label + ": no VTK error or warning");
  Output->Clear();
}

std::string DataFile(const std::string& name)
{
  return std::string(VTKRT_DATA_DIR) + "/" + name;
}

vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& name)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(DataFile(name).c_str());
  reader->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(reader->GetOutput());
  return out;
}

/// Renders `setup`'s scene with raster, then with the pass; checks both.
void CompareWithRaster(const std::string& name, const std::function<void(vtkRenderer*)>& setup,
  double rasterThreshold, int width = 300, int height = 300)
{
  auto win = MakeWindow(width, height);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  setup(ren);
  win->Render();
  auto raster = Grab(win);
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  auto traced = Grab(win);
  const double error = Difference(traced, raster);
  std::ostringstream what;
  what << name << ": ray traced vs raster error " << error << " <= " << rasterThreshold;
  Check(error <= rasterThreshold, what.str());
  if (error > rasterThreshold)
  {
    WritePNG(raster, std::string(VTKRT_TEMP_DIR) + "/pass_" + name + ".raster.png");
    WritePNG(traced, std::string(VTKRT_TEMP_DIR) + "/pass_" + name + ".traced.png");
  }
  Check(pass->GetLastTracedInstances() > 0, name + ": the pass traced the scene");
  // Coverage: the traced image shows the scene, and at most 2% of the
  // pixels differ from raster by more than 24/255 in a channel (edges).
  const long covered = CountForegroundPixels(traced, ren->GetBackground());
  const long differing = CountDifferingPixels(traced, raster, 24);
  const long total = static_cast<long>(width) * height;
  std::ostringstream cover;
  cover << name << ": " << covered << " foreground pixels, " << differing
        << " differ from raster (<= 2% of " << total << ")";
  Check(covered > total / 100 && differing >= 0 && differing <= total / 50, cover.str());
  Check(vtkrtCompareWithBaseline(traced, "pass_" + name) == 1, name + ": matches its baseline");
  NoVTKOutput(name);
}

vtkSmartPointer<vtkActor> BunnyActor()
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(ReadPolyData("bunny.vtp"));
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.7, 0.5);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(20);
  return actor;
}

vtkSmartPointer<vtkActor> SphereGlyphActor()
{
  auto points = ReadPolyData("demo-spheres.vtp");
  points->GetPointData()->SetActiveScalars("scalar");
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(points);
  mapper->SetSourceConnection(sphere->GetOutputPort());
  mapper->SetScaleArray("radius");
  mapper->SetScaleModeToScaleByMagnitude();
  mapper->SetScaleFactor(2.0); // the unit sphere source has radius 0.5
  mapper->SetScalarRange(0.0, 1.0);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(30);
  return actor;
}

// The demo mesh with point normals, Phong shading, specular, headlight.
void TestMesh()
{
  CompareWithRaster("Mesh",
    [](vtkRenderer* ren) {
      ren->AddActor(BunnyActor());
      ren->SetBackground(0.1, 0.2, 0.3);
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(30);
      ren->GetActiveCamera()->Elevation(15);
      ren->ResetCameraClippingRange();
    },
    30.0);
}

// vtkGlyph3DMapper of vtkSphereSource: analytic spheres, radius array,
// colors through the mapper's lookup table; with the mesh for depth.
void TestGlyphs()
{
  CompareWithRaster("Glyphs",
    [](vtkRenderer* ren) {
      ren->AddActor(BunnyActor());
      ren->AddActor(SphereGlyphActor());
      ren->SetBackground(0.1, 0.2, 0.3);
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(30);
      ren->ResetCameraClippingRange();
    },
    40.0);
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Mesh", TestMesh },
    { "Glyphs", TestGlyphs },
  };
  const std::string which = argc > 1 ? argv[1] : "";
  auto it = cases.find(which);
  if (it == cases.end())
  {
    std::cerr << "usage: " << argv[0] << " <case>; cases:";
    for (const auto& c : cases)
    {
      std::cerr << " " << c.first;
    }
    std::cerr << "\n";
    return EXIT_FAILURE;
  }
  it->second();
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
