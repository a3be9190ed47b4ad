// Points drawn as spheres (RenderPointsAsSpheres) by vtkRayTracePass:
//   ScreenSizedPoints     they keep VTK's pixel size (PointSize) through
//                         zooms, orbits, an actor scale and parallel
//                         projection, like raster, with no BVH build or
//                         geometry upload after the first frame; through the
//                         top-level BVH (10 actors), no rebuild on orbit
//   LitScreenSizedPoints  lit with raster's sprite normal (against raster);
//                         a tube beside them keeps its own shading
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkMath.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
const double kBlack[3] = { 0, 0, 0 };

/// Isolated points (vertices) at different depths, far enough apart on
/// screen that their spheres never overlap.
vtkSmartPointer<vtkPolyData> IsolatedPoints()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < 5; ++i)
  {
    const double d = static_cast<double>(i);
    points->InsertNextPoint(0.3 * d - 0.6, 0.12 * d - 0.24, -0.6 * d);
    verts->InsertNextCell(1, &i);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetVerts(verts);
  return poly;
}

void TestScreenSizedPoints()
{
  const int w = 320, h = 240;
  auto win = MakeWindow(w, h);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0, 0, 0);
  win->AddRenderer(ren);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(IsolatedPoints());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetScale(2.0); // VTK's sprites ignore it: pixel sizes stay
  actor->GetProperty()->RenderPointsAsSpheresOn();
  actor->GetProperty()->SetPointSize(14);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(1, 1, 1);
  ren->AddActor(actor);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(0.5, 1.0, 9.0);
  cam->SetFocalPoint(0, 0, -2);
  cam->SetViewUp(0, 1, 0);
  cam->SetViewAngle(30);
  cam->SetClippingRange(1, 40);
  vtkNew<vtkRayTracePass> pass;
  // Foreground pixels of a raster frame of `r`, then of a frame traced by `pass`.
  auto rasterThenTracedPixels = [&](vtkRenderer* r) {
    r->GetActiveCamera()->SetClippingRange(1, 40);
    r->SetPass(nullptr);
    win->Render();
    const long raster = CountForegroundPixels(Grab(win), kBlack);
    r->SetPass(pass);
    win->Render();
    return std::make_pair(raster, CountForegroundPixels(Grab(win), kBlack));
  };

  // Each step changes the view (or the point size); pass and raster must
  // cover about the same pixels, so every sphere stays PointSize wide.
  struct Step
  {
    const char* Name;
    std::function<void()> Apply;
    bool Rebuilds; // expected BVH builds on that frame
  };
  const Step steps[] = {
    { "first frame", [] {}, true },
    { "dolly in 1.5x", [&] { cam->Dolly(1.5); }, false },
    { "zoom (view angle) 1.6x", [&] { cam->Zoom(1.6); }, false },
    { "orbit 15 degrees", [&] { cam->Azimuth(15); }, false },
    { "dolly out 3x", [&] { cam->Dolly(1.0 / 3.0); }, false },
    { "point size 22", [&] { actor->GetProperty()->SetPointSize(22); }, false },
    { "parallel projection",
      [&] {
        cam->ParallelProjectionOn();
        cam->SetParallelScale(3.0);
      },
      false },
    { "parallel zoom 1.5x", [&] { cam->SetParallelScale(2.0); }, false },
  };
  for (const Step& step : steps)
  {
    step.Apply();
    const auto [raster, traced] = rasterThenTracedPixels(ren);
    const double size = actor->GetProperty()->GetPointSize();
    // Five disks PointSize wide (VTK's are a little smaller): all in view.
    const double disk = 5 * vtkMath::Pi() * size * size / 4.0;
    std::ostringstream s;
    s << step.Name << ": traced " << traced << " px, raster " << raster << " px, five " << size
      << "-px disks " << static_cast<long>(disk) << " px (want within 12% of raster)";
    Check(pass->GetLastTracedInstances() == 1 &&
        std::abs(traced - raster) <= 0.12 * static_cast<double>(raster) &&
        std::abs(traced - disk) <= 0.3 * disk,
      s.str());
    if (!step.Rebuilds)
    {
      std::ostringstream c;
      c << step.Name << ": " << pass->GetLastBVHBuilds() << " BVH builds, "
        << pass->GetLastGeometryBytesUploaded() << " geometry bytes uploaded (want 0, 0)";
      Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0, c.str());
    }
  }

  // More than 8 instances: the top-level BVH, whose boxes grow with the
  // radius bound (rounded to a power of two: rebuilt only when a zoom crosses
  // one, never on an orbit).
  vtkNew<vtkRenderer> many;
  many->SetBackground(0, 0, 0);
  win->RemoveRenderer(ren);
  win->AddRenderer(many);
  auto points = IsolatedPoints();
  for (int k = 0; k < 10; ++k)
  {
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputData(points);
    vtkNew<vtkActor> a;
    a->SetMapper(m);
    a->SetPosition(0.9 * (k % 5) - 1.8, k < 5 ? 0.9 : -0.9, 0.0);
    a->SetScale(0.5);
    a->GetProperty()->RenderPointsAsSpheresOn();
    a->GetProperty()->SetPointSize(9);
    a->GetProperty()->LightingOff();
    many->AddActor(a);
  }
  vtkCamera* c2 = many->GetActiveCamera();
  c2->SetPosition(0.2, 0.3, 9.0);
  c2->SetFocalPoint(0, 0, -1);
  c2->SetViewUp(0, 1, 0);
  c2->SetViewAngle(30);
  const char* manySteps[] = { "first frame", "orbit 10 degrees", "dolly in 1.3x" };
  for (int k = 0; k < 3; ++k)
  {
    if (k == 1)
    {
      c2->Azimuth(10);
    }
    if (k == 2)
    {
      c2->Dolly(1.3);
    }
    const auto [raster, traced] = rasterThenTracedPixels(many);
    std::ostringstream s;
    s << "10 actors, " << manySteps[k] << ": traced " << traced << " px, raster " << raster
      << " px (want within 12%), " << pass->GetLastBVHBuilds() << " BVH builds, "
      << pass->GetLastTopLevelBuilds() << " top-level builds";
    const bool builds = k == 0 || (pass->GetLastBVHBuilds() == 0 &&
      (k == 2 || pass->GetLastTopLevelBuilds() == 0));
    Check(pass->GetLastTracedInstances() == 10 && raster > 2000 &&
        std::abs(traced - raster) <= 0.12 * static_cast<double>(raster) && builds,
      s.str());
  }
  NoVTKOutput("screen-sized points");
}

/// Lit points drawn as spheres under a wide perspective view: VTK 9.1 lights
/// each as a sprite seen head-on, so the traced spheres take that normal
/// too (before, the true sphere's normal moved the off-axis highlights:
/// RGB RMSE 2.8 and 6.0 at PointSize 20 and 40).
void TestLitScreenSizedPoints()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < 6; ++i)
  {
    const double a = static_cast<double>(i);
    points->InsertNextPoint(1.6 * std::cos(a), 1.2 * std::sin(1.3 * a), -0.5 * a);
    verts->InsertNextCell(1, &i);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetVerts(verts);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->RenderPointsAsSpheresOn();
  actor->GetProperty()->SetColor(1.0, 0.8, 0.6);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(20);
  auto win = MakeWindow(320, 320);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(actor);
  ren->ResetCamera();
  ren->GetActiveCamera()->SetViewAngle(50);
  ren->ResetCameraClippingRange();
  for (const float size : { 20.0f, 40.0f })
  {
    actor->GetProperty()->SetPointSize(size);
    ren->SetPass(nullptr);
    auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
    const double rmse = RootMeanSquareError(traced, raster);
    std::ostringstream s;
    s << "lit points as spheres, PointSize " << size << ": RGB RMSE " << rmse
      << " against raster (want <= 1.5), " << pass->GetLastTracedInstances() << " instance traced";
    Check(rmse <= 1.5 && pass->GetLastTracedInstances() == 1, s.str());
  }

  // Lines drawn as tubes keep their own shading beside points drawn as
  // spheres (the sprite normal is the points'): the tube's lower half of
  // the image, traced without and then with the points above it.
  vtkNew<vtkPoints> linePoints;
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(8);
  for (vtkIdType i = 0; i < 8; ++i)
  {
    linePoints->InsertNextPoint(-2.0 + 0.6 * static_cast<double>(i), -1.6 + 0.15 * std::sin(static_cast<double>(i)), 0.0);
    line->InsertCellPoint(i);
  }
  vtkNew<vtkPolyData> polyline;
  polyline->SetPoints(linePoints);
  polyline->SetLines(line);
  vtkNew<vtkPolyDataMapper> lineMapper;
  lineMapper->SetInputData(polyline);
  vtkNew<vtkActor> tube;
  tube->SetMapper(lineMapper);
  tube->GetProperty()->RenderLinesAsTubesOn();
  tube->GetProperty()->SetLineWidth(12);
  tube->GetProperty()->SetSpecular(0.4);
  ren->AddActor(tube);
  actor->SetPosition(0.0, 1.2, 0.0);
  ren->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> tubePass;
  ren->SetPass(tubePass);
  std::vector<unsigned char> lowerHalf[2];
  for (int withPoints = 0; withPoints < 2; ++withPoints)
  {
    actor->SetVisibility(withPoints == 1);
    win->Render();
    auto image = Grab(win);
    const auto* rgb = static_cast<const unsigned char*>(image->GetScalarPointer());
    lowerHalf[withPoints].assign(rgb, rgb + 3 * 320 * 120);
  }
  const long tubePixels = std::count_if(lowerHalf[0].begin(), lowerHalf[0].end(), [](unsigned char c) { return c > 40; });
  Check(lowerHalf[0] == lowerHalf[1] && tubePixels > 500,
    "a tube beside points drawn as spheres: its half of the image unchanged (" + std::to_string(tubePixels) +
      " lit channel values)");
  NoVTKOutput("lit screen-sized points");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "ScreenSizedPoints", TestScreenSizedPoints }, { "LitScreenSizedPoints", TestLitScreenSizedPoints } });
}
