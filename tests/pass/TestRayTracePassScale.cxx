// vtkRayTracePass on objects of any size a double holds:
//   MeshScales   the bunny scaled by 1e-30 .. 1e30 (and offset by 1e8 of its
//                size): traced like raster draws it, and like the pass draws
//                it at scale 1
//   GlyphScales  sphere glyphs with scale factors 1e12 and 1e19 (their
//                centers scaled alike, or one sphere far larger than its
//                center's coordinates): traced like raster
//   ZoomedDetail a mesh 1e-20 the size of the one around it, seen closely
//   TooSmallWarning  a mesh under 2^-60 of the view: one warning
// TestRayTracePassScale <Case>.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
constexpr int kSize = 200;
/// RGB RMSE (0-255) allowed between two images of one scene: edges and
/// float rounding only (a blank or flat image is far above it).
constexpr double kMaximumRMSE = 12.0;

/// A copy of `poly` with double points mapped by p -> p * scale + offset.
vtkSmartPointer<vtkPolyData> Mapped(vtkPolyData* poly, double scale, const double offset[3])
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(poly->GetNumberOfPoints());
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    double p[3];
    poly->GetPoint(i, p);
    points->SetPoint(
      i, p[0] * scale + offset[0], p[1] * scale + offset[1], p[2] * scale + offset[2]);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(poly);
  out->SetPoints(points);
  return out;
}

/// The scene `addActors` makes, seen as a VTK user frames it
/// (ResetCamera, then a turn): raster, then traced.
RasterAndTraced Render(const std::function<void(vtkRenderer*)>& addActors)
{
  auto win = MakeWindow(kSize, kSize);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.1, 0.2, 0.3);
  addActors(ren);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(30);
  ren->GetActiveCamera()->Elevation(10);
  ren->ResetCameraClippingRange();
  RasterAndTraced frames = RenderRasterThenTraced(win, ren);
  NoGLError(win, "scale");
  return frames;
}

/// Whether `image` matches `reference` (RMSE) and shows the scene; both
/// written out when not.
bool Matches(vtkImageData* image, vtkImageData* reference, const std::string& what,
  const std::string& file)
{
  const double background[3] = { 0.1, 0.2, 0.3 };
  const double rmse = RootMeanSquareError(image, reference);
  const long foreground = CountForegroundPixels(reference, background);
  const bool ok = rmse <= kMaximumRMSE && foreground > kSize * kSize / 20;
  std::ostringstream s;
  s << what << ": RGB RMSE " << rmse << " <= " << kMaximumRMSE << " (" << foreground
    << " foreground pixels in the reference)";
  Check(ok, s.str());
  if (!ok)
  {
    WritePNG(image, std::string(VTKRT_TEMP_DIR) + "/pass_scale_" + file + ".png");
    WritePNG(reference, std::string(VTKRT_TEMP_DIR) + "/pass_scale_" + file + ".reference.png");
  }
  return ok;
}

/// Raster is the reference where it draws the scene like at scale 1; else
/// (VTK's own float limits) the pass's image at scale 1 is.
void CompareScaled(const std::string& name, const RasterAndTraced& scaled,
  const RasterAndTraced& unit)
{
  const bool rasterGood = RootMeanSquareError(scaled.Raster, unit.Raster) <= kMaximumRMSE;
  std::cout << "info: " << name << ": raster " << (rasterGood ? "draws" : "does not draw")
            << " it as at scale 1 (RMSE " << RootMeanSquareError(scaled.Raster, unit.Raster)
            << ")\n";
  Matches(scaled.Traced, rasterGood ? scaled.Raster.Get() : unit.Traced.Get(),
    name + (rasterGood ? ": traced vs raster" : ": traced vs traced at scale 1"), name);
  Check(scaled.Pass->GetLastTracedInstances() > 0, name + ": traced");
}

void TestMeshScales()
{
  // The bunny about the origin, its bounding radius 1.
  auto raw = ReadPolyData("bunny.vtp");
  double b[6];
  raw->GetBounds(b);
  const double radius =
    0.5 * std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  const double center[3] = { -0.5 * (b[0] + b[1]) / radius, -0.5 * (b[2] + b[3]) / radius,
    -0.5 * (b[4] + b[5]) / radius };
  auto bunny = Mapped(raw, 1.0 / radius, center);
  // Points scaled by `scale` and offset, the actor scaled by `actorScale`.
  auto mesh = [&](double scale, const double offset[3], double actorScale) {
    return [=](vtkRenderer* ren) {
      vtkSmartPointer<vtkActor> actor = MeshActor(Mapped(bunny, scale, offset));
      actor->SetScale(actorScale);
      ren->AddActor(actor);
    };
  };
  const double zero[3] = { 0, 0, 0 };
  const RasterAndTraced unit = Render(mesh(1.0, zero, 1.0));
  Matches(unit.Traced, unit.Raster, "scale 1: traced vs raster", "1");
  // VTK's camera keeps 1e-20 from its focal point: data at 1e-30 is seen
  // through an actor scale of 1e20.
  for (const double scale : { 1e-30, 1e-20, 1e20, 1e25, 1e30 })
  {
    const double actorScale = scale < 1e-20 ? 1e20 : 1.0;
    std::ostringstream name;
    name << "mesh " << scale;
    if (actorScale != 1.0)
    {
      name << " (actor scale " << actorScale << ")";
    }
    CompareScaled(name.str(), Render(mesh(scale, zero, actorScale)), unit);
    const double offset[3] = { 1e8 * scale, -2e8 * scale, 3e8 * scale };
    name << " at 1e8 sizes";
    CompareScaled(name.str(), Render(mesh(scale, offset, actorScale)), unit);
  }
  NoVTKOutput("mesh scales");
}

/// One lit sphere glyph of radius `factor` (scale factor on a unit radius
/// array) about a center near the origin, its source fine enough for
/// raster to draw it round.
void AddHugeSphereGlyph(vtkRenderer* ren, double factor)
{
  vtkNew<vtkPolyData> centers;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->InsertNextPoint(0.25, -0.5, 0.125);
  centers->SetPoints(points);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  radius->InsertNextValue(1.0);
  centers->GetPointData()->AddArray(radius);
  vtkNew<vtkSphereSource> source;
  source->SetRadius(1.0);
  source->SetThetaResolution(96);
  source->SetPhiResolution(96);
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(centers);
  mapper->SetSourceConnection(source->GetOutputPort());
  mapper->SetScaleArray("radius");
  mapper->SetScaleModeToScaleByMagnitude();
  mapper->SetScaleFactor(factor);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.7, 0.5);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(20);
  ren->AddActor(actor);
}

void TestGlyphScales()
{
  auto spheres = ReadPolyData("demo-spheres.vtp");
  const double zero[3] = { 0, 0, 0 };
  // Scale factor `factor`, the centers scaled alike: the scene at scale 1, scaled.
  auto glyphs = [&](double factor) {
    return [=](vtkRenderer* ren) {
      vtkSmartPointer<vtkActor> actor = GlyphActor(Mapped(spheres, factor, zero));
      vtkGlyph3DMapper::SafeDownCast(actor->GetMapper())->SetScaleFactor(2.0 * factor);
      ren->AddActor(actor);
    };
  };
  auto sphere = [](double factor) {
    return [=](vtkRenderer* ren) { AddHugeSphereGlyph(ren, factor); };
  };
  const RasterAndTraced unit = Render(glyphs(1.0));
  Matches(unit.Traced, unit.Raster, "glyph scale factor 1: traced vs raster", "glyphs_1");
  const RasterAndTraced unitSphere = Render(sphere(1.0));
  Matches(unitSphere.Traced, unitSphere.Raster, "one sphere glyph: traced vs raster", "sphere_1");
  for (const double factor : { 1e12, 1e19 })
  {
    std::ostringstream name;
    name << "glyph scale factor " << factor;
    CompareScaled(name.str() + ", centers scaled alike", Render(glyphs(factor)), unit);
    // A sphere 1e12 or 1e19 times larger than its center's coordinates.
    CompareScaled(name.str() + ", one sphere", Render(sphere(factor)), unitSphere);
  }
  NoVTKOutput("glyph scales");
}
/// A mesh 1e-20 the size of the one around it, the camera on the small
/// one: traced like raster, no warning.
void TestZoomedDetail()
{
  auto bunny = ReadPolyData("bunny.vtp");
  const double zero[3] = { 0, 0, 0 };
  auto win = MakeWindow(kSize, kSize);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.1, 0.2, 0.3);
  vtkSmartPointer<vtkActor> small = MeshActor(Mapped(bunny, 1e-12, zero));
  ren->AddActor(small);
  ren->AddActor(MeshActor(Mapped(bunny, 1e8, zero)));
  ren->ResetCamera(small->GetBounds());
  ren->ResetCameraClippingRange(small->GetBounds());
  const RasterAndTraced frames = RenderRasterThenTraced(win, ren);
  Matches(frames.Traced, frames.Raster, "a mesh 1e-20 of the scene, zoomed in: traced vs raster",
    "zoomed");
  NoVTKOutput("zoomed in");
}

/// A mesh under 2^-60 of the view: one warning (not one a frame) says
/// float cannot shade it; without it the scene warns nothing.
void TestTooSmallWarning()
{
  auto bunny = ReadPolyData("bunny.vtp");
  const double zero[3] = { 0, 0, 0 };
  auto win = MakeWindow(kSize, kSize);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(MeshActor(bunny));
  vtkSmartPointer<vtkActor> tiny = MeshActor(Mapped(bunny, 1e-20, zero));
  ren->AddActor(tiny);
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  ren->ResetCamera();
  win->Render();
  win->Render();
  std::ostringstream s;
  s << "a mesh 1e-20 of the view: " << Output->GetNumberOfWarnings()
    << " warning(s) over two frames (1), no error";
  Check(Output->GetNumberOfWarnings() == 1 && Output->GetNumberOfErrors() == 0, s.str());
  Output->Clear();
  ren->RemoveActor(tiny);
  win->Render();
  NoVTKOutput("without the tiny mesh");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "MeshScales", TestMeshScales },
    { "GlyphScales", TestGlyphScales },
    { "ZoomedDetail", TestZoomedDetail },
    { "TooSmallWarning", TestTooSmallWarning },
  };
  return RunCase(argc, argv, cases);
}
