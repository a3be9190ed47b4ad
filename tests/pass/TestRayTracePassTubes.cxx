// Lines drawn as tubes (issue 22, part 3), traced and compared with VTK's
// raster of the same scene after a Gaussian blur of a few pixels (VTK's
// raster tubes are flat quads shaded like cylinders, without round joints or
// caps; a blur compares their shape and shading, not single edge pixels):
//   Helix        a polyline helix, RenderLinesAsTubes, LineWidth 8, colored
//                by point scalars, perspective and parallel projection;
//                a camera move or a LineWidth change uploads no geometry; scalars interpolated
//                before mapping (a 4-color table along coarse segments)
//   Mixed        one polydata of a surface and lines, colored by cell
//                scalars: both traced (triangles and tubes), both projections
//   ManyActors   twelve tube actors, walked through the top-level BVH
//   NoTubeCode   the shader of a scene without tubes has none of their code;
//                plain lines (no RenderLinesAsTubes, or LineWidth 1 or 0)
//                leave the actor to raster
//   Selection    vtkHardwareSelector picks the same line cell ids (after
//                the vertices, before the polygons) as raster
//   Shadow       traced tubes cast a shadow on a traced floor (and on
//                themselves); ambient occlusion darkens floor and tubes
//   BadInput     zero-length segments, single-point lines, NaN points, a
//                huge LineWidth: traced without a crash or a warning
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkLight.h"
#include "vtkLookupTable.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

using namespace vtkrtPassTest;

namespace
{
constexpr int kSize = 300;
constexpr double kPi = 3.14159265358979323846;

/// A helix of `points` points as one polyline, with a point scalar "t" along it.
vtkSmartPointer<vtkPolyData> Helix(int points, double turns)
{
  vtkNew<vtkPoints> pts;
  vtkNew<vtkDoubleArray> t;
  t->SetName("t");
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(points);
  for (int i = 0; i < points; ++i)
  {
    const double u = static_cast<double>(i) / (points - 1);
    const double a = 2.0 * kPi * turns * u;
    pts->InsertNextPoint(std::cos(a), 2.0 * u - 1.0, std::sin(a));
    t->InsertNextValue(u);
    lines->InsertCellPoint(i);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  poly->GetPointData()->SetScalars(t);
  return poly;
}

/// A sphere's polygons and, in the same polydata, rings of lines around it
/// and spokes out of it, with a cell scalar (lines first, as VTK numbers them).
vtkSmartPointer<vtkPolyData> SurfaceWithLines()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.6);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  sphere->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(sphere->GetOutput());
  poly->GetPointData()->Initialize();
  vtkPoints* pts = poly->GetPoints();
  vtkNew<vtkCellArray> lines;
  for (int ring = 0; ring < 3; ++ring)
  {
    const int n = 48;
    const double y = -0.5 + 0.5 * ring;
    lines->InsertNextCell(n + 1);
    const vtkIdType first = pts->GetNumberOfPoints();
    for (int i = 0; i < n; ++i)
    {
      const double a = 2.0 * kPi * i / n;
      pts->InsertNextPoint(1.0 * std::cos(a), y, 1.0 * std::sin(a));
      lines->InsertCellPoint(first + i);
    }
    lines->InsertCellPoint(first);
  }
  for (int spoke = 0; spoke < 6; ++spoke)
  {
    const double a = 2.0 * kPi * spoke / 6 + 0.3;
    const vtkIdType id0 = pts->InsertNextPoint(0.55 * std::cos(a), 0.0, 0.55 * std::sin(a));
    const vtkIdType id1 = pts->InsertNextPoint(1.3 * std::cos(a), 0.4, 1.3 * std::sin(a));
    const vtkIdType seg[2] = { id0, id1 };
    lines->InsertNextCell(2, seg);
  }
  poly->SetLines(lines);
  vtkNew<vtkFloatArray> cellScalar;
  const vtkIdType cells = poly->GetNumberOfCells();
  for (vtkIdType c = 0; c < cells; ++c)
  {
    cellScalar->InsertNextValue(static_cast<float>(c % 7));
  }
  poly->GetCellData()->SetScalars(cellScalar);
  return poly;
}

vtkSmartPointer<vtkActor> TubeActor(vtkPolyData* poly, double lineWidth, double range[2])
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->SetScalarRange(range);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetRenderLinesAsTubes(true);
  actor->GetProperty()->SetLineWidth(static_cast<float>(lineWidth));
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(20.0);
  return actor;
}

/// The tubes' scenes: failed images as tubes-N.*.png.
struct Scene : ComparedScene
{
  Scene()
    : ComparedScene(kSize, "tubes")
  {
  }
};

bool ShaderHasTubes(vtkRayTracePass* pass)
{
  const std::string source = pass->GetLastFragmentShaderSource();
  // The chunk's definitions (the main part names them only under #ifdef).
  return source.find("bool traverseTubes(") != std::string::npos ||
    source.find("bool intersectRayTube(") != std::string::npos ||
    source.find("#define VTKRT_HAS_TUBES") != std::string::npos;
}

void TestHelix()
{
  for (bool parallel : { false, true })
  {
    Scene scene;
    double range[2] = { 0.0, 1.0 };
    auto helix = TubeActor(Helix(400, 3.0), 8.0, range);
    scene.Renderer->AddActor(helix);
    scene.View(20.0, 25.0, parallel);
    const std::string label = std::string("helix, ") + (parallel ? "parallel" : "perspective");
    RasterAndTraced frames = scene.Compare(label, 1, 4.0);
    Check(ShaderHasTubes(frames.Pass), label + ": the shader has the tube code");
    // An orbit and a zoom: the tubes stay LineWidth wide, nothing uploads.
    scene.Renderer->GetActiveCamera()->Azimuth(35.0);
    scene.Renderer->GetActiveCamera()->Zoom(1.3);
    scene.Renderer->ResetCameraClippingRange();
    scene.Window->Render();
    Check(frames.Pass->GetLastGeometryBytesUploaded() == 0 && frames.Pass->GetLastBVHBuilds() == 0,
      label + ": a camera move uploads no geometry (" +
        std::to_string(frames.Pass->GetLastGeometryBytesUploaded()) + " bytes)");
    RasterAndTraced moved = scene.Compare(label + ", moved camera", 1, 4.0);
    // A thinner line: new radii in the instance record, no geometry.
    helix->GetProperty()->SetLineWidth(6.0f);
    scene.Window->Render();
    Check(moved.Pass->GetLastGeometryBytesUploaded() == 0 && moved.Pass->GetLastBVHBuilds() == 0,
      label + ": a LineWidth change uploads no geometry");
    scene.Compare(label + ", LineWidth 6", 1, 4.0);
  }
  // Scalars through the mapper's color texture, interpolated along the tubes.
  Scene scene;
  double range[2] = { 0.0, 1.0 };
  auto actor = TubeActor(Helix(60, 3.0), 8.0, range);
  actor->GetMapper()->InterpolateScalarsBeforeMappingOn();
  actor->GetMapper()->GetLookupTable()->SetRange(0.0, 1.0);
  vtkLookupTable::SafeDownCast(actor->GetMapper()->GetLookupTable())->SetNumberOfTableValues(4);
  vtkLookupTable::SafeDownCast(actor->GetMapper()->GetLookupTable())->Build();
  scene.Renderer->AddActor(actor);
  scene.View(20.0, 25.0, false);
  scene.Compare("helix, scalars interpolated before mapping", 1, 4.0);
  NoVTKOutput("Helix");
}

void TestMixed()
{
  for (bool parallel : { false, true })
  {
    Scene scene;
    double range[2] = { 0.0, 6.0 };
    auto actor = TubeActor(SurfaceWithLines(), 6.0, range);
    scene.Renderer->AddActor(actor);
    scene.View(30.0, 30.0, parallel);
    const std::string label = std::string("surface and lines, ") + (parallel ? "parallel" : "perspective");
    RasterAndTraced frames = scene.Compare(label, 1, 4.0);
    const std::string key = frames.Pass->GetLastFeatureKey();
    Check(key.find("T1") == 0 && ShaderHasTubes(frames.Pass),
      label + ": triangles and tubes in one shader (" + key + ")");
  }
  NoVTKOutput("Mixed");
}

/// Tubes in solid colors beside a solid-colored surface: no traced prop
/// has scalar colors, so the shader has no color code at all.
void TestUncolored()
{
  Scene scene;
  double range[2] = { 0.0, 1.0 };
  auto helix = TubeActor(Helix(200, 3.0), 8.0, range);
  helix->GetMapper()->ScalarVisibilityOff();
  helix->GetProperty()->SetColor(0.9, 0.4, 0.3);
  scene.Renderer->AddActor(helix);
  auto floor = FloorActor(1.5);
  floor->SetPosition(0.0, -1.0, 0.0);
  scene.Renderer->AddActor(floor);
  scene.View(20.0, 25.0, false);
  RasterAndTraced frames = scene.Compare("uncolored tubes", 2, 4.0);
  const std::string shader = frames.Pass->GetLastFragmentShaderSource();
  Check(ShaderHasTubes(frames.Pass) && shader.find("#define VTKRT_HAS_COLORS") == std::string::npos,
    "uncolored tubes: tube code without color code");
  NoGLError(scene.Window, "Uncolored");
  NoVTKOutput("Uncolored");
}

/// Twelve helices, each its own actor: more than 8 instances, so the rays
/// walk the top-level BVH, whose boxes grow by each instance's radius bound.
void TestManyActors()
{
  for (bool parallel : { false, true })
  {
    Scene scene;
    double range[2] = { 0.0, 1.0 };
    auto helix = Helix(120, 2.0);
    for (int i = 0; i < 12; ++i)
    {
      auto actor = TubeActor(helix, 5.0, range);
      actor->SetPosition(2.5 * (i % 4), 2.5 * (i / 4), -1.0 * i);
      actor->SetScale(0.8 + 0.05 * i);
      scene.Renderer->AddActor(actor);
    }
    scene.View(10.0, 15.0, parallel);
    const std::string label = std::string("12 helices, ") + (parallel ? "parallel" : "perspective");
    RasterAndTraced frames = scene.Compare(label, 12, 4.0);
    Check(std::string(frames.Pass->GetLastFragmentShaderSource()).find("#define VTKRT_HAS_TOP_LEVEL") !=
        std::string::npos,
      label + ": through the top-level BVH");
  }
  NoVTKOutput("ManyActors");
}

void TestNoTubeCode()
{
  Scene scene;
  scene.Renderer->AddActor(SphereActor(0.0, 0.0, 0.0, 1.0));
  scene.View(0.0, 0.0, false);
  scene.Renderer->SetPass(nullptr);
  RasterAndTraced frames = RenderRasterThenTraced(scene.Window, scene.Renderer);
  Check(frames.Pass->GetNumberOfTracedProps() == 1 && !ShaderHasTubes(frames.Pass),
    "a scene without tubes compiles no tube code");
  // Plain lines stay with raster (a stand-in draws them), the surface is
  // traced, and no tube code is compiled.
  const struct
  {
    bool Tubes;
    double Width;
    const char* Name;
  } plain[] = { { false, 8.0, "RenderLinesAsTubes off" }, { true, 1.0, "LineWidth 1" },
    { true, 0.0, "LineWidth 0" } };
  for (const auto& p : plain)
  {
    Scene lines;
    double range[2] = { 0.0, 6.0 };
    auto actor = TubeActor(SurfaceWithLines(), p.Width, range);
    actor->GetProperty()->SetRenderLinesAsTubes(p.Tubes);
    lines.Renderer->AddActor(actor);
    lines.View(30.0, 30.0, false);
    RasterAndTraced mixed = lines.Compare(std::string("plain lines, ") + p.Name + ": surface traced", 1, 1.0);
    Check(!ShaderHasTubes(mixed.Pass), std::string("plain lines, ") + p.Name + ": no tube code");
  }
  NoVTKOutput("NoTubeCode");
}

/// The cell ids vtkHardwareSelector selects over the whole view.
std::set<vtkIdType> SelectCells(Scene& scene)
{
  const unsigned int all[4] = { 0, 0, kSize - 1, kSize - 1 };
  return SelectedCells(scene.Renderer, all);
}

void TestSelection()
{
  Scene scene;
  double range[2] = { 0.0, 6.0 };
  auto poly = SurfaceWithLines();
  // A vertex cell first (two points drawn as spheres), so that line ids
  // start after it.
  vtkNew<vtkCellArray> verts;
  const vtkIdType v[2] = { 0, 1 };
  verts->InsertNextCell(2, v);
  poly->SetVerts(verts);
  poly->GetCellData()->Initialize();
  auto actor = TubeActor(poly, 8.0, range);
  actor->GetProperty()->SetRenderPointsAsSpheres(true);
  actor->GetProperty()->SetPointSize(6.0f);
  scene.Renderer->AddActor(actor);
  scene.View(30.0, 30.0, false);
  scene.Window->Render();
  const std::set<vtkIdType> raster = SelectCells(scene);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  const std::set<vtkIdType> traced = SelectCells(scene);
  const vtkIdType firstPoly = 1 + poly->GetNumberOfLines();
  std::set<vtkIdType> rasterLines, tracedLines;
  for (vtkIdType id : raster)
  {
    if (id >= 1 && id < firstPoly)
    {
      rasterLines.insert(id);
    }
  }
  for (vtkIdType id : traced)
  {
    if (id >= 1 && id < firstPoly)
    {
      tracedLines.insert(id);
    }
  }
  std::vector<vtkIdType> both;
  std::set_intersection(raster.begin(), raster.end(), traced.begin(), traced.end(), std::back_inserter(both));
  const double overlap = static_cast<double>(both.size()) / static_cast<double>(raster.size() + traced.size() - both.size());
  std::ostringstream s;
  s << "selection: " << pass->GetNumberOfTracedProps() << " traced props; line cells raster "
    << rasterLines.size() << ", traced " << tracedLines.size() << " (" << poly->GetNumberOfLines()
    << " lines); all cells in common " << overlap;
  Check(pass->GetNumberOfTracedProps() == 1 && rasterLines == tracedLines && !tracedLines.empty() &&
      overlap >= 0.9,
    s.str());
  NoVTKOutput("Selection");
}

void TestShadow()
{
  Scene scene;
  double range[2] = { 0.0, 1.0 };
  auto tubes = TubeActor(Helix(200, 1.5), 10.0, range);
  tubes->SetPosition(0.0, 1.5, 0.0);
  scene.Renderer->AddActor(tubes);
  scene.Renderer->AddActor(FloorActor(3.0));
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(0.0, 10.0, 0.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPositional(false);
  scene.Renderer->AddLight(light);
  scene.Renderer->GetActiveCamera()->SetPosition(0.0, 6.0, 6.0);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.5, 0.0);
  scene.Renderer->GetActiveCamera()->SetViewUp(0.0, 1.0, 0.0);
  scene.Renderer->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  auto lit = Grab(scene.Window);
  pass->ShadowsOn();
  scene.Window->Render();
  auto shadowed = Grab(scene.Window);
  // The floor under the helix darkens (the tubes shade themselves too), and
  // nothing brightens.
  const long darker = CountDifferingPixels(lit, shadowed, 20);
  int d[3];
  lit->GetDimensions(d);
  const auto* a = static_cast<const unsigned char*>(lit->GetScalarPointer());
  const auto* b = static_cast<const unsigned char*>(shadowed->GetScalarPointer());
  long brighter = 0;
  for (long i = 0; i < static_cast<long>(d[0]) * d[1] * 3; ++i)
  {
    brighter += b[i] > a[i] + 2;
  }
  std::ostringstream s;
  s << "shadow: " << pass->GetNumberOfTracedProps() << " traced props, " << darker
    << " pixels darkened by the tubes' shadow, " << brighter << " channel values brightened";
  Check(pass->GetNumberOfTracedProps() == 2 && darker > 1000 && brighter == 0, s.str());
  // Ambient occlusion: the floor under the helix and the tubes near their
  // neighbours darken.
  pass->ShadowsOff();
  pass->SetAmbientOcclusionSamples(16);
  scene.Window->Render();
  const long occluded = CountDifferingPixels(lit, Grab(scene.Window), 12);
  Check(occluded > 200, "ambient occlusion: " + std::to_string(occluded) + " pixels darkened");
  NoGLError(scene.Window, "shadow");
  NoVTKOutput("Shadow");
}

void TestBadInput()
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, 0);
  pts->InsertNextPoint(1, 0, 0);
  pts->InsertNextPoint(1, 0, 0); // a zero-length segment after the first
  pts->InsertNextPoint(1, 1, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  pts->InsertNextPoint(nan, 0, 0);
  pts->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> lines;
  const vtkIdType polyline[4] = { 0, 1, 2, 3 };
  lines->InsertNextCell(4, polyline);
  const vtkIdType single[1] = { 5 };
  lines->InsertNextCell(1, single);
  const vtkIdType withNaN[3] = { 3, 4, 5 };
  lines->InsertNextCell(3, withNaN);
  const vtkIdType point[2] = { 5, 5 };
  lines->InsertNextCell(2, point);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  // LineWidth 1000: the eye inside the tubes, beyond what is framed.
  for (double width : { 8.0, 60.0, 1000.0 })
  {
    Scene scene;
    double range[2] = { 0.0, 1.0 };
    auto actor = TubeActor(poly, width, range);
    scene.Renderer->AddActor(actor);
    scene.Renderer->GetActiveCamera()->SetPosition(0.5, 0.5, 4.0);
    scene.Renderer->GetActiveCamera()->SetFocalPoint(0.5, 0.5, 0.0);
    scene.Renderer->ResetCameraClippingRange();
    vtkNew<vtkRayTracePass> pass;
    scene.Renderer->SetPass(pass);
    scene.Window->Render();
    auto image = Grab(scene.Window);
    const double background[3] = { 0.1, 0.1, 0.15 };
    std::ostringstream s;
    s << "degenerate lines, LineWidth " << width << ": " << pass->GetNumberOfTracedProps()
      << " traced props, " << CountForegroundPixels(image, background) << " tube pixels";
    Check(pass->GetNumberOfTracedProps() == 1 && (width > 100.0 || CountForegroundPixels(image, background) > 100),
      s.str());
    NoGLError(scene.Window, "degenerate lines");
  }
  NoVTKOutput("BadInput");
}
/// Polygons and plain lines (and a vertex cell, no spheres) in one
/// polydata: the surface is traced, the lines and points drawn by raster
/// through a stand-in; the image as raster's, a camera move uploads
/// nothing, hardware selection returns the actor's line and polygon cells
/// as raster does; a polydata of lines alone is left to raster whole.
void TestPlainLines()
{
  Scene scene;
  double range[2] = { 0.0, 6.0 };
  auto poly = SurfaceWithLines();
  vtkNew<vtkCellArray> verts;
  const vtkIdType v[2] = { 0, 1 };
  verts->InsertNextCell(2, v);
  poly->SetVerts(verts);
  poly->GetCellData()->Initialize();
  auto actor = TubeActor(poly, 2.0, range);
  actor->GetProperty()->SetRenderLinesAsTubes(false);
  actor->GetProperty()->SetPointSize(5.0f);
  scene.Renderer->AddActor(actor);
  scene.View(30.0, 30.0, false);
  scene.Window->Render();
  const std::set<vtkIdType> rasterCells = SelectCells(scene);
  RasterAndTraced frames = scene.Compare("plain lines", 1, 4.0);
  Check(frames.Pass->GetLastTracedPrimitives() > 0 && !ShaderHasTubes(frames.Pass),
    "plain lines: the surface is traced, the lines are not tubes");
  // Without the stand-in the lines would be missing: the image differs
  // from the traced surface alone.
  auto surfaceOnly = vtkSmartPointer<vtkPolyData>::New();
  surfaceOnly->ShallowCopy(poly);
  surfaceOnly->SetLines(nullptr);
  surfaceOnly->SetVerts(nullptr);
  vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(surfaceOnly);
  scene.Window->Render();
  auto bare = Grab(scene.Window);
  vtkPolyDataMapper::SafeDownCast(actor->GetMapper())->SetInputData(poly);
  scene.Window->Render();
  const long lineDifference = CountDifferingPixels(bare, frames.Traced, 30);
  scene.Renderer->GetActiveCamera()->Azimuth(20.0);
  scene.Window->Render();
  const bool nothingUploaded =
    frames.Pass->GetLastGeometryBytesUploaded() == 0 && frames.Pass->GetLastBVHBuilds() == 0;
  scene.Renderer->GetActiveCamera()->Azimuth(-20.0);
  scene.Window->Render();
  const std::set<vtkIdType> tracedCells = SelectCells(scene);
  std::ostringstream s;
  s << "plain lines: " << lineDifference << " pixels drawn by the raster stand-in; camera move uploads "
    << (nothingUploaded ? "nothing" : "geometry") << "; selected cells raster " << rasterCells.size()
    << ", with the pass " << tracedCells.size();
  Check(lineDifference > 500 && nothingUploaded && rasterCells == tracedCells && !rasterCells.empty(), s.str());
  // Lines alone: nothing to trace, raster draws the actor.
  Scene linesOnly;
  linesOnly.Renderer->AddActor(TubeActor(Helix(100, 2.0), 1.0, range));
  linesOnly.View(20.0, 25.0, false);
  linesOnly.Compare("lines alone", 0, 0.5);
  NoGLError(scene.Window, "PlainLines");
  NoVTKOutput("PlainLines");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "Helix", TestHelix }, { "Mixed", TestMixed }, { "ManyActors", TestManyActors },
      { "NoTubeCode", TestNoTubeCode }, { "Uncolored", TestUncolored },
      { "PlainLines", TestPlainLines },
      { "Selection", TestSelection }, { "Shadow", TestShadow }, { "BadInput", TestBadInput } });
}
