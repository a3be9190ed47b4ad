// Cell edges traced (issue 22, part 2), compared with VTK's raster of the
// same scene after a 1.5-pixel Gaussian blur (a fraction of a pixel moves a
// one-pixel line's raw RMSE by 5-10 on raster itself):
//   QuadEdges        a quad mesh (vtkPlaneSource) with edge visibility,
//                    LineWidth 1 and 3, perspective and parallel projection
//   TriangleEdges    a sphere with edge visibility, LineWidth 1 and 2
//   Wireframe        a wireframe sphere over an opaque plane (rays pass
//                    through the faces), LineWidth 1 and 2; a grid
//                    without normals lit by VTK's line normals
//   PolygonOutlines  hexagons with edges and as wireframes: their outlines
//                    only, no fan diagonal (the hexagon's center, on a
//                    diagonal, keeps the surface color / shows the floor)
//   EdgeCode         no edge code in a scene without edges; a camera move
//                    or an edge toggle builds and uploads no geometry
//   BadLineWidth     LineWidth 0 and negative: as VTK (edges at least 1.1
//                    pixels, wires 1), no crash, no warning
//   WireframeSelection  vtkHardwareSelector picks a wireframe's cells where
//                    its wires are, as raster; through its faces the prop
//                    behind
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkAppendPolyData.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkScalarsToColors.h"
#include "vtkCamera.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkRegularPolygonSource.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
constexpr int kSize = 240;
constexpr double kBound = 4.0; // RGB RMSE after the blur

/// A copy of an RGB(A) image blurred by a separable Gaussian (sigma 1.5
/// pixels, radius 4), clamped at the borders.
vtkSmartPointer<vtkImageData> NarrowBlurred(vtkImageData* image)
{
  int d[3];
  image->GetDimensions(d);
  const int comps = image->GetNumberOfScalarComponents();
  std::vector<double> weights;
  for (int k = -4; k <= 4; ++k)
  {
    weights.push_back(std::exp(-k * k / (2.0 * 1.5 * 1.5)));
  }
  double total = 0.0;
  for (double w : weights)
  {
    total += w;
  }
  const auto* in = static_cast<const unsigned char*>(image->GetScalarPointer());
  std::vector<double> pass(static_cast<std::size_t>(d[0]) * d[1] * comps, 0.0);
  std::vector<double> out(pass.size(), 0.0);
  auto at = [&](int x, int y, int c) { return (static_cast<std::size_t>(y) * d[0] + x) * comps + c; };
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      for (int c = 0; c < comps; ++c)
      {
        for (int k = -4; k <= 4; ++k)
        {
          pass[at(x, y, c)] += weights[k + 4] * in[at(std::clamp(x + k, 0, d[0] - 1), y, c)] / total;
        }
      }
    }
  }
  auto blurred = vtkSmartPointer<vtkImageData>::New();
  blurred->DeepCopy(image);
  auto* o = static_cast<unsigned char*>(blurred->GetScalarPointer());
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      for (int c = 0; c < comps; ++c)
      {
        double v = 0.0;
        for (int k = -4; k <= 4; ++k)
        {
          v += weights[k + 4] * pass[at(x, std::clamp(y + k, 0, d[1] - 1), c)] / total;
        }
        o[at(x, y, c)] = static_cast<unsigned char>(std::clamp(v + 0.5, 0.0, 255.0));
      }
    }
  }
  return blurred;
}

/// The scene's window and renderer: a view of whatever is added, compared
/// narrowly blurred.
struct Scene : ComparedScene
{
  Scene()
    : ComparedScene(kSize, "edges")
  {
    this->Blur = NarrowBlurred;
  }
  /// Raster, then traced: `traced` props traced and the narrowly blurred
  /// images' RGB RMSE at most kBound.
  RasterAndTraced Compare(const std::string& label, int traced)
  {
    return this->ComparedScene::Compare(label, traced, kBound);
  }
};

vtkSmartPointer<vtkActor> ActorOf(vtkAlgorithm* source)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

vtkSmartPointer<vtkActor> QuadMesh()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(6, 4);
  plane->SetPoint1(1.5, -0.5, 0.0);
  return ActorOf(plane);
}

bool HasCode(vtkRayTracePass* pass, const std::string& what)
{
  return std::string(pass->GetLastFragmentShaderSource()).find(what) != std::string::npos;
}

void TestQuadEdges()
{
  for (bool parallel : { false, true })
  {
    for (float width : { 1.0f, 3.0f })
    {
      Scene scene;
      auto mesh = QuadMesh();
      mesh->GetProperty()->SetColor(0.8, 0.8, 0.6);
      mesh->GetProperty()->EdgeVisibilityOn();
      mesh->GetProperty()->SetEdgeColor(0.9, 0.1, 0.1);
      mesh->GetProperty()->SetLineWidth(width);
      scene.Renderer->AddActor(mesh);
      scene.View(30, 35, parallel);
      std::ostringstream label;
      label << "quad mesh with edges, width " << width << (parallel ? ", parallel" : ", perspective");
      RasterAndTraced frames = scene.Compare(label.str(), 1);
      Check(HasCode(frames.Pass, "#define VTKRT_SURFACE_EDGES"), label.str() + ": edge code compiled");
    }
  }
  NoVTKOutput("quad edges");
}

void TestTriangleEdges()
{
  for (bool parallel : { false, true })
  {
    for (float width : { 1.0f, 2.0f })
    {
      Scene scene;
      auto sphere = SphereActor(0.0, 0.0, 0.0, 0.5, 16);
      sphere->GetProperty()->SetColor(0.4, 0.6, 0.9);
      sphere->GetProperty()->SetSpecular(0.3);
      sphere->GetProperty()->EdgeVisibilityOn();
      sphere->GetProperty()->SetEdgeColor(1.0, 1.0, 0.3);
      sphere->GetProperty()->SetLineWidth(width);
      scene.Renderer->AddActor(sphere);
      scene.View(20, 30, parallel);
      std::ostringstream label;
      label << "sphere with edges, width " << width << (parallel ? ", parallel" : ", perspective");
      scene.Compare(label.str(), 1);
    }
  }
  NoVTKOutput("triangle edges");
}

void AddFloor(Scene& scene)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1.0, -0.6, -1.0);
  plane->SetPoint1(1.0, -0.6, -1.0);
  plane->SetPoint2(-1.0, -0.6, 1.0);
  auto floor = ActorOf(plane);
  floor->GetProperty()->SetColor(0.5, 0.7, 0.5);
  scene.Renderer->AddActor(floor);
}

void TestWireframe()
{
  for (float width : { 1.0f, 2.0f })
  {
    Scene scene;
    AddFloor(scene);
    auto sphere = SphereActor(0.0, 0.0, 0.0, 0.5, 16);
    sphere->GetProperty()->SetColor(1.0, 0.9, 0.2);
    sphere->GetProperty()->SetRepresentationToWireframe();
    sphere->GetProperty()->SetLineWidth(width);
    scene.Renderer->AddActor(sphere);
    scene.View(20, 25);
    const std::string label = "wireframe sphere over a plane, width " + std::to_string(int(width));
    RasterAndTraced frames = scene.Compare(label, 2);
    Check(HasCode(frames.Pass, "#define VTKRT_HAS_WIREFRAME") &&
        !HasCode(frames.Pass, "#define VTKRT_SURFACE_EDGES"),
      label + ": wire code only");
  }
  // Without normals VTK lights a wire by its line normal (perpendicular to
  // the line, nearest the view direction), which raster takes from screen
  // derivatives (noisy on lines); the pass takes it exact: in a grid tilted
  // 60 degrees from the headlight the wires across the tilt face it and are
  // lit fully, their diffuse color (by the faces' normals nothing would be).
  Scene scene;
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(6, 4);
  plane->Update();
  vtkNew<vtkPolyData> bare;
  bare->ShallowCopy(plane->GetOutput());
  bare->GetPointData()->SetNormals(nullptr);
  auto grid = MeshActor(bare);
  grid->GetProperty()->SetColor(0.2, 0.8, 0.4);
  grid->GetProperty()->SetSpecular(0.0);
  grid->GetProperty()->SetRepresentationToWireframe();
  grid->GetProperty()->SetLineWidth(2.0f);
  scene.Renderer->AddActor(grid);
  scene.View(0, 60);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  const unsigned char lit[3] = { 51, 204, 102 };
  const double background[3] = { 0.1, 0.1, 0.15 };
  auto image = Grab(scene.Window);
  const long wires = CountForegroundPixels(image, background);
  const long fullyLit = CountColor(image, lit);
  Check(wires > 1000 && fullyLit > wires / 4,
    "wires without normals, tilted: " + std::to_string(fullyLit) + " of " + std::to_string(wires) +
      " wire pixels fully lit");
  NoVTKOutput("wireframe");
}

/// Three hexagons (one polygon each) in z = 0, unlit, with their centers.
vtkSmartPointer<vtkActor> Hexagons(std::vector<std::array<double, 3>>& centers)
{
  vtkNew<vtkAppendPolyData> append;
  for (int i = 0; i < 3; ++i)
  {
    vtkNew<vtkRegularPolygonSource> hexagon;
    hexagon->SetNumberOfSides(6);
    hexagon->SetRadius(0.45);
    hexagon->SetCenter(i - 1.0, 0.2 * i, 0.0);
    hexagon->GeneratePolylineOff();
    hexagon->Update();
    append->AddInputData(hexagon->GetOutput());
    centers.push_back({ { i - 1.0, 0.2 * i, 0.0 } });
  }
  auto actor = ActorOf(append);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(0.2, 0.3, 0.9);
  actor->GetProperty()->SetEdgeColor(0.95, 0.1, 0.1);
  actor->GetProperty()->SetLineWidth(2.0f);
  return actor;
}

/// The color of the pixel where a world point falls.
std::array<int, 3> PixelAt(vtkRenderer* ren, vtkImageData* image, const std::array<double, 3>& p)
{
  ren->SetWorldPoint(p[0], p[1], p[2], 1.0);
  ren->WorldToDisplay();
  const double* d = ren->GetDisplayPoint();
  const auto* px = static_cast<const unsigned char*>(
    image->GetScalarPointer(static_cast<int>(d[0]), static_cast<int>(d[1]), 0));
  return { { px[0], px[1], px[2] } };
}

void TestPolygonOutlines()
{
  for (bool wireframe : { false, true })
  {
    Scene scene;
    std::vector<std::array<double, 3>> centers;
    auto hexagons = Hexagons(centers);
    if (wireframe)
    {
      hexagons->GetProperty()->SetRepresentationToWireframe();
    }
    else
    {
      hexagons->GetProperty()->EdgeVisibilityOn();
    }
    scene.Renderer->AddActor(hexagons);
    scene.View(0, 0);
    scene.Renderer->GetActiveCamera()->Elevation(-30);
    scene.Renderer->ResetCameraClippingRange();
    const std::string label = wireframe ? "hexagon wireframes" : "hexagons with edges";
    RasterAndTraced frames = scene.Compare(label, 1);
    for (const auto& c : centers)
    {
      // The center lies on the fan diagonal v0-v3: no edge drawn there.
      const auto traced = PixelAt(scene.Renderer, frames.Traced, c);
      const auto raster = PixelAt(scene.Renderer, frames.Raster, c);
      const std::array<int, 3> want = wireframe ? std::array<int, 3>{ { 26, 26, 38 } }
                                                : std::array<int, 3>{ { 51, 77, 230 } };
      bool ok = true;
      for (int k = 0; k < 3; ++k)
      {
        ok = ok && std::abs(traced[k] - want[k]) <= 2 && std::abs(raster[k] - want[k]) <= 2;
      }
      std::ostringstream s;
      s << label << ": no diagonal through the center (traced " << traced[0] << "," << traced[1]
        << "," << traced[2] << ", raster " << raster[0] << "," << raster[1] << "," << raster[2] << ")";
      Check(ok, s.str());
    }
  }
  NoVTKOutput("polygon outlines");
}

void TestEdgeCode()
{
  Scene scene;
  auto mesh = QuadMesh();
  scene.Renderer->AddActor(mesh);
  scene.View(30, 35);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  Check(!HasCode(pass, "uCameraToPixels") && !HasCode(pass, "#define VTKRT_SURFACE_EDGES") &&
      !HasCode(pass, "#define VTKRT_HAS_WIREFRAME") && !HasCode(pass, "wireEdgeAt"),
    "no edges: no edge code in the shader");
  mesh->GetProperty()->EdgeVisibilityOn();
  scene.Window->Render();
  Check(HasCode(pass, "uCameraToPixels") && pass->GetLastBVHBuilds() == 0 &&
      pass->GetLastGeometryBytesUploaded() == 0,
    "edges on: edge code, no geometry built or uploaded");
  scene.Renderer->GetActiveCamera()->Azimuth(20);
  scene.Renderer->GetActiveCamera()->Zoom(1.5);
  scene.Window->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0 &&
      pass->GetLastShaderCompiles() == 0,
    "edges, camera moved: nothing built, uploaded or compiled");
  mesh->GetProperty()->SetRepresentationToWireframe();
  scene.Window->Render();
  Check(HasCode(pass, "#define VTKRT_HAS_WIREFRAME") && pass->GetLastBVHBuilds() == 0 &&
      pass->GetLastGeometryBytesUploaded() == 0,
    "wireframe: wire code, no geometry built or uploaded");
  NoVTKOutput("edge code");
}

void TestBadLineWidth()
{
  for (bool wireframe : { false, true })
  {
    std::vector<vtkSmartPointer<vtkImageData>> images;
    for (float width : { wireframe ? 1.0f : 1.1f, 0.0f, -2.0f })
    {
      Scene scene;
      auto mesh = QuadMesh();
      mesh->GetProperty()->SetEdgeColor(0.9, 0.1, 0.1);
      if (wireframe)
      {
        mesh->GetProperty()->SetRepresentationToWireframe();
      }
      else
      {
        mesh->GetProperty()->EdgeVisibilityOn();
      }
      mesh->GetProperty()->SetLineWidth(width);
      scene.Renderer->AddActor(mesh);
      scene.View(30, 35);
      vtkNew<vtkRayTracePass> pass;
      scene.Renderer->SetPass(pass);
      scene.Window->Render();
      images.push_back(Grab(scene.Window));
      Check(pass->GetNumberOfTracedProps() == 1, "line width " + std::to_string(width) + ": traced");
    }
    const std::string what = wireframe ? "wireframe" : "edges";
    Check(CountDifferingPixels(images[0], images[1], 0) == 0 && CountDifferingPixels(images[0], images[2], 0) == 0,
      what + ": LineWidth 0 and -2 draw as " + (wireframe ? "1" : "1.1") + " (as VTK)");
  }
  NoVTKOutput("bad line width");
}

void TestWireframeSelection()
{
  std::set<vtkIdType> wires[2], behind[2];
  for (bool traced : { false, true })
  {
    Scene scene;
    auto grid = QuadMesh();
    grid->GetProperty()->SetRepresentationToWireframe();
    grid->GetProperty()->SetLineWidth(3.0f);
    grid->SetPosition(0.0, 0.0, 0.6);
    auto sphere = SphereActor(0.0, 0.0, 0.0, 0.4, 16);
    scene.Renderer->AddActor(sphere);
    scene.Renderer->AddActor(grid);
    scene.View(0, 0);
    vtkNew<vtkRayTracePass> pass;
    if (traced)
    {
      scene.Renderer->SetPass(pass);
    }
    scene.Window->Render();
    const unsigned int all[4] = { 0, 0, kSize - 1, kSize - 1 };
    wires[traced] = SelectedCells(scene.Renderer, all, grid);
    // A pixel in the middle of a grid cell: between the wires, the sphere.
    scene.Renderer->SetWorldPoint(0.0, -0.125, 0.6, 1.0);
    scene.Renderer->WorldToDisplay();
    const double* d = scene.Renderer->GetDisplayPoint();
    const unsigned int x = static_cast<unsigned int>(d[0]), y = static_cast<unsigned int>(d[1]);
    const unsigned int face[4] = { x, y, x, y };
    behind[traced] = SelectedCells(scene.Renderer, face, sphere);
    const std::set<vtkIdType> wireAtFace = SelectedCells(scene.Renderer, face, grid);
    Check(wireAtFace.empty(),
      std::string(traced ? "traced" : "raster") + ": no wire cell between the wires (pixel " +
        std::to_string(x) + "," + std::to_string(y) + ", " + std::to_string(wireAtFace.size()) +
        " wire cells, " + std::to_string(behind[traced].size()) + " sphere cells)");
    if (traced)
    {
      Check(pass->GetNumberOfTracedProps() == 2, "the wireframe grid and the sphere are traced");
    }
  }
  std::vector<vtkIdType> both;
  std::set_intersection(wires[0].begin(), wires[0].end(), wires[1].begin(), wires[1].end(),
    std::back_inserter(both));
  std::ostringstream s;
  s << "wireframe cells selected: raster " << wires[0].size() << ", traced " << wires[1].size()
    << ", in common " << both.size();
  Check(!wires[0].empty() && both.size() == wires[0].size() && wires[1].size() == wires[0].size(), s.str());
  Check(behind[0].size() == 1 && behind[0] == behind[1], "between the wires both select the same sphere cell");
  NoVTKOutput("wireframe selection");
}
/// Coincident wires: a vtkCubeSource holds its own copy of each corner per
/// face, so every cube edge is two faces' wire at one depth. Raster's depth
/// test (GL_LEQUAL) keeps the face it draws last; the pass keeps the
/// highest cell id whatever the BVH's order. Seen head-on, the front face
/// (+z, the last cell) colors its whole outline, each face colored by
/// point scalars.
void TestCoincidentWires()
{
  Scene scene;
  vtkNew<vtkCubeSource> cube;
  cube->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(cube->GetOutput());
  vtkNew<vtkFloatArray> face;
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    face->InsertNextValue(static_cast<float>(i / 4)); // the cube's points: four per face
  }
  poly->GetPointData()->SetScalars(face);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->SetScalarRange(0.0, 5.0);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetRepresentationToWireframe();
  actor->GetProperty()->SetLineWidth(3.0f);
  actor->GetProperty()->LightingOff();
  scene.Renderer->AddActor(actor);
  scene.Renderer->ResetCamera();
  // The middle of each front edge, in display coordinates.
  const double middles[4][3] = { { 0.0, 0.5, 0.5 }, { 0.0, -0.5, 0.5 }, { 0.5, 0.0, 0.5 }, { -0.5, 0.0, 0.5 } };
  auto frontColoredEdges = [&]() {
    scene.Window->Render();
    auto image = Grab(scene.Window);
    double front[3];
    mapper->GetLookupTable()->GetColor(5.0, front); // its range is the mapper's once drawn
    int frontColored = 0;
    int dims[3];
    image->GetDimensions(dims);
    const auto* rgb = static_cast<const unsigned char*>(image->GetScalarPointer());
    for (const auto& m : middles)
    {
      scene.Renderer->SetWorldPoint(m[0], m[1], m[2], 1.0);
      scene.Renderer->WorldToDisplay();
      double d[3];
      scene.Renderer->GetDisplayPoint(d);
      const int x = static_cast<int>(std::lround(d[0])), y = static_cast<int>(std::lround(d[1]));
      const unsigned char* p = rgb + 3 * (static_cast<long>(y) * dims[0] + x);
      bool match = true;
      for (int k = 0; k < 3; ++k)
      {
        match = match && std::abs(p[k] - 255.0 * front[k]) < 8.0;
      }
      frontColored += match ? 1 : 0;
    }
    return frontColored;
  };
  const int rasterColored = frontColoredEdges();
  Check(rasterColored == 4, "raster: the front face's color on " + std::to_string(rasterColored) + " of its 4 edges");
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  const int frontColored = frontColoredEdges();
  Check(pass->GetNumberOfTracedProps() == 1 && frontColored == 4,
    "coincident wires: the front face's color on " + std::to_string(frontColored) +
      " of its 4 edges (the highest cell id wins, as raster's last drawn)");
  NoGLError(scene.Window, "CoincidentWires");
  NoVTKOutput("CoincidentWires");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "QuadEdges", TestQuadEdges }, { "TriangleEdges", TestTriangleEdges },
      { "Wireframe", TestWireframe }, { "PolygonOutlines", TestPolygonOutlines },
      { "EdgeCode", TestEdgeCode }, { "BadLineWidth", TestBadLineWidth },
      { "WireframeSelection", TestWireframeSelection }, { "CoincidentWires", TestCoincidentWires } });
}
