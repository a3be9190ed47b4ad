// Tests of vtkRayTracePass's trade knobs beyond sampling: shadows from the
// renderer's scene lights (positional spotlight and directional), the
// precision mode (camera-relative vs plain float world coordinates) and the
// triangle BVH leaf size. Each case asserts analytic facts about the image
// and the per-frame counters; LightShadows also compares with a baseline.
// TestRayTracePassTrade <Case>.
#include "vtkrtImageRegression.h"
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
bool HasDefine(vtkRayTracePass* pass, const std::string& define)
{
  return std::string(pass->GetLastFragmentShaderSource()).find("#define " + define) !=
    std::string::npos;
}

/// Mean red channel over the (2r+1)^2 pixels around the pixel showing world
/// point (x, y, z).
double RedAround(vtkRenderer* ren, vtkImageData* image, double x, double y, double z, int r = 1)
{
  ren->SetWorldPoint(x, y, z, 1.0);
  ren->WorldToDisplay();
  double d[3];
  ren->GetDisplayPoint(d);
  int dims[3];
  image->GetDimensions(dims);
  const int comps = image->GetNumberOfScalarComponents();
  double sum = 0.0;
  int count = 0;
  for (int j = static_cast<int>(d[1]) - r; j <= static_cast<int>(d[1]) + r; ++j)
  {
    for (int i = static_cast<int>(d[0]) - r; i <= static_cast<int>(d[0]) + r; ++i)
    {
      if (i >= 0 && j >= 0 && i < dims[0] && j < dims[1])
      {
        sum += static_cast<const unsigned char*>(image->GetScalarPointer())[
          (static_cast<long>(j) * dims[0] + i) * comps];
        ++count;
      }
    }
  }
  return count ? sum / count : -1.0;
}

std::string Str(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Two scene lights, two shadows: a positional spotlight at L = (-2, 3, 0)
/// aimed at the origin and a directional light shining along (-1, -2, 1),
/// over a floor (y = 0) with a sphere (center (0, 1, 0), radius 0.5). The
/// spotlight's shadow is centered at (1, 0, 0) (the sphere's center
/// projected from L), the directional one at (-0.5, 0, 0.5). A small
/// sphere just beyond L (on the far side from the floor) must not shadow
/// anything: rays toward a positional light stop at the light.
void TestLightShadows()
{
  auto win = MakeWindow(240, 180);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.2, 0.3, 0.4);
  ren->AddActor(FloorActor(3.0));
  auto ball = SphereActor(0.0, 1.0, 0.0, 0.5);
  ball->GetProperty()->SetColor(1.0, 0.6, 0.3);
  ren->AddActor(ball);
  // Beyond the spotlight as seen from the lit floor point q below: on the
  // line from q through L, 0.8 further on.
  const double L[3] = { -2.0, 3.0, 0.0 };
  const double q[3] = { 0.5, 0.0, 1.5 };
  double beyond[3];
  {
    double d[3] = { L[0] - q[0], L[1] - q[1], L[2] - q[2] };
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k)
    {
      beyond[k] = L[k] + 0.8 * d[k] / n;
    }
  }
  auto blocker = SphereActor(beyond[0], beyond[1], beyond[2], 0.3, 16);
  ren->AddActor(blocker);

  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->SetPositional(true);
  spot->SetPosition(L[0], L[1], L[2]);
  spot->SetFocalPoint(0.0, 0.0, 0.0);
  spot->SetConeAngle(60.0);
  spot->SetExponent(1.0);
  spot->SetIntensity(0.6);
  ren->AddLight(spot);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPosition(1.0, 2.0, -1.0);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  sun->SetIntensity(0.6);
  ren->AddLight(sun);
  ren->GetActiveCamera()->SetPosition(0.0, 3.5, 6.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.3, 0.0);
  ren->ResetCameraClippingRange();

  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  Check(!HasDefine(pass, "VTKRT_SHADOWS"), "shadows off: no shadow code in the shader");
  Check(HasDefine(pass, "VTKRT_NUMBER_OF_LIGHTS 2") && HasDefine(pass, "VTKRT_LIGHT_COMPLEXITY 3"),
    "two scene lights, positional lighting compiled");
  auto both = Grab(win);
  const std::string keyOff = pass->GetLastFeatureKey();
  // Each light alone, no shadows: what a point shadowed from the other
  // light must look like.
  sun->SwitchOff();
  win->Render();
  auto spotOnly = Grab(win);
  sun->SwitchOn();
  spot->SwitchOff();
  win->Render();
  auto sunOnly = Grab(win);
  spot->SwitchOn();

  pass->ShadowsOn();
  win->Render();
  Check(HasDefine(pass, "VTKRT_SHADOWS"), "shadows on: shadow code compiled");
  Check(pass->GetLastFeatureKey() != keyOff && pass->GetLastShaderCompiles() == 1,
    "shadows on: a new feature key, one compile (key " + std::string(pass->GetLastFeatureKey()) +
      ", " + std::to_string(pass->GetLastShaderCompiles()) + " compiles)");
  // The blocker is out of view: raster culling left it out, shadow rays
  // need it (secondary rays see props out of view).
  Check(pass->GetNumberOfTracedProps() == 3, "shadows on: every visible prop is traced (" +
      std::to_string(pass->GetNumberOfTracedProps()) + ")");
  auto shadowed = Grab(win);

  struct Probe
  {
    const char* What;
    double X, Y, Z;
    vtkImageData* Expected; // what the point must look like with shadows
  };
  const Probe probes[] = {
    { "spotlight shadow (1, 0, 0) = sun only", 1.0, 0.0, 0.0, sunOnly },
    { "sun shadow (-0.5, 0, 0.5) = spotlight only", -0.5, 0.0, 0.5, spotOnly },
    { "lit floor q (0.5, 0, 1.5): the blocker beyond the light casts nothing", q[0], q[1], q[2],
      both },
    { "lit floor (-1.5, 0, 1.5)", -1.5, 0.0, 1.5, both },
    { "lit floor (1.5, 0, 1.5)", 1.5, 0.0, 1.5, both },
    { "lit floor (2.0, 0, -1.0)", 2.0, 0.0, -1.0, both },
    { "sphere's top, lit by both (no self-shadow)", 0.0, 1.5, 0.0, both },
  };
  for (const Probe& p : probes)
  {
    const double got = RedAround(ren, shadowed, p.X, p.Y, p.Z);
    const double want = RedAround(ren, p.Expected, p.X, p.Y, p.Z);
    Check(std::abs(got - want) <= 2.0,
      std::string(p.What) + ": red " + Str(got) + ", expected " + Str(want));
  }
  // Both shadows are real: much darker than the unshadowed floor there.
  const double spotShadow = RedAround(ren, shadowed, 1.0, 0.0, 0.0);
  const double sunShadow = RedAround(ren, shadowed, -0.5, 0.0, 0.5);
  const double spotLit = RedAround(ren, both, 1.0, 0.0, 0.0);
  const double sunLit = RedAround(ren, both, -0.5, 0.0, 0.5);
  Check(spotLit - spotShadow > 40 && sunLit - sunShadow > 40,
    "two shadows: " + Str(spotShadow) + " vs " + Str(spotLit) + " and " + Str(sunShadow) + " vs " +
      Str(sunLit));
  Check(CountDifferingPixels(shadowed, both, 2) > 200, "shadows change the image");
  Check(vtkrtCompareWithBaseline(shadowed, "pass_LightShadows") == 1,
    "light shadows: matches its baseline");

  // The spotlight's cone: outside it the spotlight neither lights nor
  // shadows, so narrowing the cone to miss the sphere's shadow region
  // leaves there the sun-lit floor (no shadow from a light that is off).
  spot->SetConeAngle(5.0);
  win->Render();
  auto narrow = Grab(win);
  const double narrowSpot = RedAround(ren, narrow, 1.0, 0.0, 0.0);
  const double narrowSun = RedAround(ren, sunOnly, 1.0, 0.0, 0.0);
  Check(std::abs(narrowSpot - narrowSun) <= 2.0,
    "outside the cone the spotlight casts no shadow (" + Str(narrowSpot) + " vs " +
      Str(narrowSun) + ")");
  NoVTKOutput("LightShadows");
  ren->SetPass(nullptr);
}

/// The bunny translated by `t` along (1, -1, 1)/sqrt(3) with the camera,
/// rendered in one precision mode.
vtkSmartPointer<vtkImageData> RenderTranslated(vtkPolyData* bunny, double t, int mode)
{
  const double c = t / std::sqrt(3.0);
  const double offset[3] = { c, -c, c };
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.1, 0.2, 0.3);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(Shifted(bunny, offset));
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(20.0);
  ren->AddActor(actor);
  double b[6];
  bunny->GetBounds(b);
  const double center[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(center[0] + offset[0], center[1] + offset[1], center[2] + offset[2]);
  cam->SetPosition(
    center[0] + offset[0] + 0.1, center[1] + offset[1] + 0.05, center[2] + offset[2] + 0.45);
  cam->SetViewUp(0.0, 1.0, 0.0);
  cam->SetClippingRange(0.2, 0.8);
  vtkNew<vtkRayTracePass> pass;
  pass->SetPrecisionMode(mode);
  ren->SetPass(pass);
  win->Render();
  return Grab(win);
}

/// Precision modes: the same image at the origin; far away, world mode
/// degrades while camera-relative stays equal to the origin image. World
/// mode uploads nothing on a camera move; switching modes uploads no
/// geometry.
void TestPrecisionMode()
{
  auto bunny = ReadPolyData("bunny.vtp");
  Check(bunny->GetNumberOfCells() > 1000, "bunny.vtp read");
  vtkNew<vtkRayTracePass> probe;
  Check(probe->GetPrecisionMode() == vtkRayTracePass::CAMERA_RELATIVE,
    "default precision mode: camera-relative");
  probe->SetPrecisionModeToWorld();
  Check(probe->GetPrecisionMode() == vtkRayTracePass::WORLD &&
      std::string(probe->GetPrecisionModeAsString()) == "World",
    "SetPrecisionModeToWorld");
  probe->SetPrecisionMode(7);
  Check(probe->GetPrecisionMode() == vtkRayTracePass::WORLD, "out-of-range modes clamp");

  auto relative0 = RenderTranslated(bunny, 0.0, vtkRayTracePass::CAMERA_RELATIVE);
  auto world0 = RenderTranslated(bunny, 0.0, vtkRayTracePass::WORLD);
  const long originDiff = CountDifferingPixels(world0, relative0, 2);
  Check(originDiff >= 0 && originDiff <= 20,
    "at the origin both modes give the same image (" + std::to_string(originDiff) +
      " pixels differ by more than 2/255)");
  const double background[3] = { 0.1, 0.2, 0.3 };
  const long covered = CountForegroundPixels(relative0, background);
  Check(covered > 200 * 200 / 5, "the bunny fills the view (" + std::to_string(covered) + " px)");
  for (double t : { 1e6, 1e8 })
  {
    auto relative = RenderTranslated(bunny, t, vtkRayTracePass::CAMERA_RELATIVE);
    auto world = RenderTranslated(bunny, t, vtkRayTracePass::WORLD);
    const long relDiff = CountDifferingPixels(relative, relative0, 24);
    const long worldDiff = CountDifferingPixels(world, relative0, 24);
    const double relError = Difference(relative, relative0);
    const double worldError = Difference(world, relative0);
    Check(relDiff >= 0 && relDiff <= 200 * 200 / 500 && relError <= 5.0,
      "translated " + Str(t) + ": camera-relative equals the origin image (" +
        std::to_string(relDiff) + " pixels differ, error " + Str(relError) + ")");
    Check(worldDiff > covered / 10 && worldError > 100.0,
      "translated " + Str(t) + ": world mode visibly degrades (" + std::to_string(worldDiff) +
        " pixels differ, error " + Str(worldError) + ")");
    if (worldError <= 100.0 || relError > 5.0)
    {
      WritePNG(relative, std::string(VTKRT_TEMP_DIR) + "/pass_precision_relative_" + Str(t) + ".png");
      WritePNG(world, std::string(VTKRT_TEMP_DIR) + "/pass_precision_world_" + Str(t) + ".png");
    }
  }

  // Counters: world mode uploads nothing on a camera move.
  auto win = MakeWindow(120, 120);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(bunny);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  ren->GetActiveCamera()->Azimuth(10.0);
  win->Render();
  Check(pass->GetLastFrameBytesUploaded() > 0 && pass->GetLastGeometryBytesUploaded() == 0,
    "camera-relative: a camera move uploads the instance records (" +
      std::to_string(pass->GetLastFrameBytesUploaded()) + " bytes) and no geometry");
  win->Render();
  Check(pass->GetLastFrameBytesUploaded() == 0, "camera-relative: a still frame uploads nothing");
  pass->SetPrecisionModeToWorld();
  win->Render();
  Check(HasDefine(pass, "VTKRT_WORLD_COORDINATES") && pass->GetLastShaderCompiles() == 1 &&
      pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0,
    "switching to world: one compile, no build, no geometry upload");
  for (int k = 0; k < 3; ++k)
  {
    ren->GetActiveCamera()->Azimuth(10.0);
    ren->GetActiveCamera()->Elevation(5.0);
    ren->ResetCameraClippingRange();
    win->Render();
    Check(pass->GetLastFrameBytesUploaded() == 0 && pass->GetLastGeometryBytesUploaded() == 0 &&
        pass->GetLastBVHBuilds() == 0 && pass->GetLastShaderCompiles() == 0,
      "world: camera move " + std::to_string(k + 1) + " uploads, builds and compiles nothing");
  }
  pass->SetPrecisionModeToCameraRelative();
  win->Render();
  Check(!HasDefine(pass, "VTKRT_WORLD_COORDINATES") && pass->GetLastShaderCompiles() == 0,
    "back to camera-relative: the cached program, no world code");
  NoVTKOutput("PrecisionMode");
  ren->SetPass(nullptr);
}

/// Leaf size: one rebuild of the triangle geometry per change (not of the
/// sphere glyphs), identical images whatever the leaf size.
void TestLeafSize()
{
  auto bunny = ReadPolyData("bunny.vtp");
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.1, 0.2, 0.3);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(bunny);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  // A few sphere glyphs beside it (their BVH keeps its own leaf size).
  vtkNew<vtkPoints> centers;
  double b[6];
  bunny->GetBounds(b);
  for (int k = 0; k < 5; ++k)
  {
    centers->InsertNextPoint(b[1] + 0.01, b[2] + 0.03 * k, 0.5 * (b[4] + b[5]));
  }
  vtkNew<vtkPolyData> centerData;
  centerData->SetPoints(centers);
  vtkNew<vtkSphereSource> glyphSource;
  glyphSource->SetRadius(0.01);
  vtkNew<vtkGlyph3DMapper> glyphs;
  glyphs->SetInputData(centerData);
  glyphs->SetSourceConnection(glyphSource->GetOutputPort());
  glyphs->ScalingOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphs);
  ren->AddActor(glyphActor);
  ren->ResetCamera();

  vtkNew<vtkRayTracePass> pass;
  Check(pass->GetLeafSize() == 8, "default leaf size 8");
  ren->SetPass(pass);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 2, "first frame builds the mesh and the glyphs");
  auto reference = Grab(win);
  for (int leaf : { 1, 2, 4, 16, 64 })
  {
    pass->SetLeafSize(leaf);
    win->Render();
    const int builds = pass->GetLastBVHBuilds();
    const vtkTypeInt64 bytes = pass->GetLastGeometryBytesUploaded();
    win->Render();
    const int again = pass->GetLastBVHBuilds();
    auto image = Grab(win);
    // Same triangles, same hits: at most a rounding step where two
    // triangles tie on an edge (none here on llvmpipe).
    const long diff = CountDifferingPixels(image, reference, 1);
    Check(builds == 1 && bytes > 0 && again == 0,
      "leaf " + std::to_string(leaf) + ": one rebuild (" + std::to_string(builds) +
        "), geometry uploaded, none on the next frame (" + std::to_string(again) + ")");
    Check(diff == 0,
      "leaf " + std::to_string(leaf) + ": identical image (" + std::to_string(diff) + " differ)");
  }
  pass->SetLeafSize(0);
  Check(pass->GetLeafSize() == 1, "leaf size clamps to >= 1");
  pass->SetLeafSize(1000);
  Check(pass->GetLeafSize() == 64, "leaf size clamps to <= 64");
  NoVTKOutput("LeafSize");
  ren->SetPass(nullptr);
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "LightShadows", TestLightShadows },
    { "PrecisionMode", TestPrecisionMode },
    { "LeafSize", TestLeafSize },
  };
  return RunCase(argc, argv, cases);
}
