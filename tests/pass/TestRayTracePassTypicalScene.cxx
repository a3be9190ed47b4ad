// The scene a VTK user draws, every actor traced: a mesh colored by point
// scalars, sphere glyphs, a translucent shell, a wireframe box, a textured
// floor and a polyline drawn as a tube, compared with VTK's raster of the
// same scene (depth peeling on) after a blur; the same scene with shadows
// and ambient occlusion, where every actor casts and receives them; and a
// translucent sphere's shadow on a textured floor, lighter than an opaque
// one's by what the sphere lets through.
#include "vtkrtPassTestUtils.h"

#include "vtkCubeSource.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkPlaneSource.h"
#include "vtkPolyLineSource.h"
#include "vtkTexture.h"

#include <cmath>
#include <sstream>

using namespace vtkrtPassTest;

namespace
{
constexpr int W = 400;
constexpr int H = 300;

/// A window and renderer set up as VTK's depth peeling draws translucency
/// exactly: many peels, occlusion ratio 0.
struct Scene
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(W, H);
  vtkNew<vtkRenderer> Renderer;

  Scene() { SetUpDepthPeeling(this->Window, this->Renderer); }

  void View(double azimuth, double elevation)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(0.0, 0.0, 1.0);
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    this->Renderer->ResetCamera();
    camera->Azimuth(azimuth);
    camera->Elevation(elevation);
    camera->Zoom(1.2);
    this->Renderer->ResetCameraClippingRange();
  }
};

/// A checkerboard of two light greys (nearest texels), so the lit floor
/// stays below white.
vtkSmartPointer<vtkTexture> CheckerTexture()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 8; ++x, p += 3)
    {
      const bool dark = (x + y) % 2 == 0;
      p[0] = dark ? 150 : 220;
      p[1] = dark ? 140 : 210;
      p[2] = dark ? 120 : 190;
    }
  }
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOff();
  return texture;
}

vtkSmartPointer<vtkActor> TexturedFloor(double half, double y)
{
  auto floor = FloorActor(half);
  floor->SetPosition(0.0, y, 0.0);
  floor->SetTexture(CheckerTexture());
  return floor;
}

/// The six actors of the scene; returns them in the order added.
std::vector<vtkSmartPointer<vtkActor>> AddTypicalScene(vtkRenderer* renderer)
{
  std::vector<vtkSmartPointer<vtkActor>> actors;
  // A mesh colored by point scalars (elevation).
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.45);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(sphere->GetOutputPort());
  elevation->SetLowPoint(0.0, -0.45, 0.0);
  elevation->SetHighPoint(0.0, 0.45, 0.0);
  vtkNew<vtkPolyDataMapper> meshMapper;
  meshMapper->SetInputConnection(elevation->GetOutputPort());
  actors.push_back(vtkSmartPointer<vtkActor>::New());
  actors.back()->SetMapper(meshMapper);
  actors.back()->GetProperty()->SetSpecular(0.3);
  actors.back()->GetProperty()->SetSpecularPower(20.0);
  // Sphere glyphs on a ring around it.
  vtkNew<vtkPolyData> ring;
  vtkNew<vtkPoints> ringPoints;
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  vtkNew<vtkFloatArray> scalar;
  scalar->SetName("scalar");
  for (int i = 0; i < 10; ++i)
  {
    const double a = 2.0 * 3.14159265358979 * i / 10.0;
    ringPoints->InsertNextPoint(1.1 * std::cos(a), -0.3, 1.1 * std::sin(a));
    radius->InsertNextValue(0.06f + 0.01f * static_cast<float>(i % 3));
    scalar->InsertNextValue(static_cast<float>(i) / 9.0f);
  }
  ring->SetPoints(ringPoints);
  ring->GetPointData()->AddArray(radius);
  ring->GetPointData()->AddArray(scalar);
  actors.push_back(GlyphActor(ring));
  // A translucent shell around the mesh.
  actors.push_back(SphereActor(0.0, 0.0, 0.0, 0.7, 64));
  actors.back()->GetProperty()->SetColor(0.4, 0.6, 1.0);
  actors.back()->GetProperty()->SetOpacity(0.35);
  // A wireframe box around everything, unlit as outlines usually are (lit,
  // a cube's coincident face edges take the last face's normal in the pass
  // and in VTK's X11 window, but another in this window's raster).
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-1.3, 1.3, -0.55, 0.9, -1.3, 1.3);
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cube->GetOutputPort());
  actors.push_back(vtkSmartPointer<vtkActor>::New());
  actors.back()->SetMapper(cubeMapper);
  actors.back()->GetProperty()->SetRepresentationToWireframe();
  actors.back()->GetProperty()->SetColor(1.0, 1.0, 0.6);
  actors.back()->GetProperty()->SetLineWidth(2.0f);
  actors.back()->GetProperty()->LightingOff();
  // A textured floor.
  actors.push_back(TexturedFloor(1.6, -0.56));
  // A polyline drawn as a tube.
  vtkNew<vtkPolyLineSource> line;
  line->SetNumberOfPoints(40);
  for (int i = 0; i < 40; ++i)
  {
    const double a = 4.0 * 3.14159265358979 * i / 39.0;
    line->SetPoint(i, 0.95 * std::cos(a), -0.4 + 0.03 * i, 0.95 * std::sin(a));
  }
  vtkNew<vtkPolyDataMapper> lineMapper;
  lineMapper->SetInputConnection(line->GetOutputPort());
  actors.push_back(vtkSmartPointer<vtkActor>::New());
  actors.back()->SetMapper(lineMapper);
  actors.back()->GetProperty()->SetColor(0.9, 0.3, 0.3);
  actors.back()->GetProperty()->SetRenderLinesAsTubes(true);
  actors.back()->GetProperty()->SetLineWidth(6.0f);
  for (vtkActor* a : actors)
  {
    renderer->AddActor(a);
  }
  return actors;
}

/// Every actor traced, and the image within a blurred RGB RMSE of 4 of
/// raster with depth peeling, under two views.
void TestTypicalScene()
{
  Scene scene;
  AddTypicalScene(scene.Renderer);
  for (double azimuth : { 25.0, -110.0 })
  {
    scene.Renderer->SetPass(nullptr);
    scene.View(azimuth, 20.0);
    RasterAndTraced frames = RenderRasterThenTraced(scene.Window, scene.Renderer);
    const double rmse = RootMeanSquareError(Blurred(frames.Raster), Blurred(frames.Traced));
    std::ostringstream s;
    s << "TypicalScene azimuth " << azimuth << ": " << frames.Pass->GetNumberOfTracedProps()
      << " of 6 props traced, blurred RGB RMSE vs raster with depth peeling " << rmse
      << " (bound 4; unblurred " << RootMeanSquareError(frames.Raster, frames.Traced) << ")";
    Check(frames.Pass->GetNumberOfTracedProps() == 6 && rmse <= 4.0, s.str());
    if (rmse > 4.0)
    {
      WriteFailedImages("TypicalScene" + std::to_string(static_cast<int>(azimuth)), frames.Raster, frames.Traced);
    }
    const std::string shader = frames.Pass->GetLastFragmentShaderSource();
    for (const char* feature : { "VTKRT_TRANSLUCENT", "VTKRT_HAS_WIREFRAME", "VTKRT_HAS_TUBES",
           "VTKRT_HAS_TEXTURES", "VTKRT_HAS_COLORS" })
    {
      Check(shader.find(std::string("#define ") + feature) != std::string::npos,
        std::string("TypicalScene: the shader defines ") + feature);
    }
    NoGLError(scene.Window, "TypicalScene");
  }
  NoVTKOutput("TypicalScene");
}

/// The typical scene with shadows and ambient occlusion: each frame changes
/// the image where the objects stand (the floor darkens below them), and a
/// camera move uploads no geometry.
void TestTypicalSceneShadows()
{
  Scene scene;
  AddTypicalScene(scene.Renderer);
  scene.View(25.0, 35.0);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  auto plain = Grab(scene.Window);
  pass->SetShadows(true);
  scene.Window->Render();
  auto shadowed = Grab(scene.Window);
  pass->SetShadows(false);
  pass->SetAmbientOcclusionSamples(8);
  scene.Window->Render();
  auto occluded = Grab(scene.Window);
  const auto* p = static_cast<const unsigned char*>(plain->GetScalarPointer());
  const auto* s = static_cast<const unsigned char*>(shadowed->GetScalarPointer());
  const auto* o = static_cast<const unsigned char*>(occluded->GetScalarPointer());
  long darkerShadow = 0, darkerOcclusion = 0, brighter = 0;
  for (long i = 0; i < 3L * W * H; ++i)
  {
    darkerShadow += s[i] + 20 < p[i];
    darkerOcclusion += o[i] + 20 < p[i];
    brighter += s[i] > p[i] + 2 || o[i] > p[i] + 2;
  }
  scene.Renderer->GetActiveCamera()->Azimuth(10.0);
  scene.Window->Render();
  std::ostringstream m;
  m << "TypicalSceneShadows: " << pass->GetNumberOfTracedProps() << " of 6 traced; channels darker by "
    << "over 20: " << darkerShadow << " with shadows, " << darkerOcclusion << " with occlusion; "
    << brighter << " brighter; after a camera move " << pass->GetLastBVHBuilds() << " BVH builds, "
    << pass->GetLastGeometryBytesUploaded() << " geometry bytes uploaded";
  Check(pass->GetNumberOfTracedProps() == 6 && darkerShadow > 1500 && darkerOcclusion > 1500 && brighter == 0 &&
      pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0,
    m.str());
  NoGLError(scene.Window, "TypicalSceneShadows");
  NoVTKOutput("TypicalSceneShadows");
}

/// A translucent sphere over a textured floor casts a lighter shadow than
/// an opaque one: (1 - 0.4)^2 = 0.36 of the direct light passes its two
/// layers.
void TestTexturedFloorShadow()
{
  Scene scene;
  scene.Renderer->AddActor(TexturedFloor(2.0, 0.0));
  auto ball = SphereActor(0.0, 0.5, 0.0, 0.3, 48);
  scene.Renderer->AddActor(ball);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(0.0, 10.0, 0.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPositional(false);
  scene.Renderer->AddLight(light);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(0.0, 2.5, 2.5);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  scene.Renderer->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  auto render = [&](double opacity, bool shadows) {
    ball->GetProperty()->SetOpacity(opacity);
    pass->SetShadows(shadows);
    scene.Window->Render();
    return Grab(scene.Window);
  };
  auto lit = render(1.0, false);
  auto opaqueShadow = render(1.0, true);
  auto litThroughGlass = render(0.4, false);
  auto glassShadow = render(0.4, true);
  // Floor pixels in the opaque sphere's shadow that the sphere does not
  // cover in the view.
  std::vector<long> mask;
  const auto* l = static_cast<const unsigned char*>(lit->GetScalarPointer());
  const auto* o = static_cast<const unsigned char*>(opaqueShadow->GetScalarPointer());
  const auto* g = static_cast<const unsigned char*>(litThroughGlass->GetScalarPointer());
  for (long i = 0; i < static_cast<long>(W) * H; ++i)
  {
    if (l[3 * i] > o[3 * i] + 30 && l[3 * i] == g[3 * i] && l[3 * i + 2] == g[3 * i + 2])
    {
      mask.push_back(i);
    }
  }
  const double litMean = MeanOver(lit, mask);
  const double opaqueMean = MeanOver(opaqueShadow, mask);
  const double glassMean = MeanOver(glassShadow, mask);
  const double through = (glassMean - opaqueMean) / std::max(1.0, litMean - opaqueMean);
  std::ostringstream s;
  s << "TexturedFloorShadow: " << pass->GetNumberOfTracedProps() << " of 2 traced; " << mask.size()
    << " textured floor pixels in the shadow: lit " << litMean << ", under the opaque sphere " << opaqueMean
    << ", under the translucent one " << glassMean << " (" << through << " of the direct light through, 0.36 expected)";
  Check(pass->GetNumberOfTracedProps() == 2 && mask.size() > 300 && opaqueMean < glassMean && glassMean < litMean &&
      std::abs(through - 0.36) < 0.03,
    s.str());
  NoGLError(scene.Window, "TexturedFloorShadow");
  NoVTKOutput("TexturedFloorShadow");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "TypicalScene", TestTypicalScene }, { "TypicalSceneShadows", TestTypicalSceneShadows },
      { "TexturedFloorShadow", TestTexturedFloorShadow } });
}
