// Translucent actors traced: every layer composited front to back, compared
// with VTK's raster of the same scene with depth peeling (many peels,
// occlusion ratio 0): a translucent shell over an opaque mesh, scalar colors
// with alpha, a textured quad with translucent texels (translucent sphere
// glyphs stay with raster, composited with the traced scene); shadows
// through translucent surfaces, their rays walked from shading or
// interleaved with the layers; translucency code only in shaders of scenes
// that have it; opacity outside [0, 1]; hardware selection of the nearest
// layer, as raster's; a translucent shell over opaque props raster draws
// (an image slice, points, an outline, text), which show through it.
#include "vtkrtPassTestUtils.h"

#include "vtkCellData.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkImageSlice.h"
#include "vtkImageSliceMapper.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkOutlineSource.h"
#include "vtkPlaneSource.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
constexpr int W = 320;
constexpr int H = 240;

/// A window and renderer set up as VTK's depth peeling draws translucency
/// exactly: many peels, occlusion ratio 0.
struct Scene
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(W, H);
  vtkNew<vtkRenderer> Renderer;

  Scene() { SetUpDepthPeeling(this->Window, this->Renderer); }

  void Frame(double azimuth, double zoom)
  {
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(azimuth);
    this->Renderer->GetActiveCamera()->Elevation(15);
    this->Renderer->GetActiveCamera()->Zoom(zoom);
    this->Renderer->ResetCameraClippingRange();
  }
};

/// Raster then traced; checks the traced prop count, the RGB RMSE and
/// that the shader composites layers.
RasterAndTraced Compare(const std::string& name, Scene& scene, int tracedProps, double maxRmse)
{
  RasterAndTraced frames = RenderRasterThenTraced(scene.Window, scene.Renderer);
  std::ostringstream props;
  props << name << ": " << frames.Pass->GetNumberOfTracedProps() << " props traced (" << tracedProps << ")";
  Check(frames.Pass->GetNumberOfTracedProps() == tracedProps, props.str());
  const double rmse = RootMeanSquareError(frames.Raster, frames.Traced);
  std::ostringstream what;
  what << name << ": RGB RMSE " << rmse << " against raster with depth peeling (<= " << maxRmse << ")";
  Check(rmse <= maxRmse, what.str());
  if (rmse > maxRmse)
  {
    WriteFailedImages(name, frames.Raster, frames.Traced);
  }
  Check(std::string(frames.Pass->GetLastFragmentShaderSource()).find("#define VTKRT_TRANSLUCENT") !=
      std::string::npos,
    name + ": the shader composites translucent layers");
  NoGLError(scene.Window, name);
  NoVTKOutput(name);
  return frames;
}

vtkSmartPointer<vtkFloatArray> ZBuffer(vtkRenderWindow* win)
{
  auto z = vtkSmartPointer<vtkFloatArray>::New();
  win->GetZbufferData(0, 0, W - 1, H - 1, z);
  return z;
}

/// Pixels whose depths differ by more than 1e-3.
long DepthsDiffering(vtkFloatArray* a, vtkFloatArray* b)
{
  long n = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    n += std::abs(a->GetValue(i) - b->GetValue(i)) > 1e-3f;
  }
  return n;
}

/// Pixels at the far plane.
long FarPixels(vtkFloatArray* z)
{
  long n = 0;
  for (vtkIdType i = 0; i < z->GetNumberOfValues(); ++i)
  {
    n += z->GetValue(i) == 1.0f;
  }
  return n;
}

/// An opaque sphere inside a translucent specular shell, cut by a second
/// translucent sphere: up to six layers. The depth the pass leaves is the
/// opaque depth (the far plane where only translucent layers are), as
/// VTK's depth peeling leaves it.
void TestShell()
{
  Scene scene;
  auto core = SphereActor(0.0, 0.0, 0.0, 0.5, 48);
  core->GetProperty()->SetColor(0.9, 0.6, 0.3);
  auto shell = SphereActor(0.0, 0.0, 0.0, 1.0, 64);
  shell->GetProperty()->SetColor(0.3, 0.5, 1.0);
  shell->GetProperty()->SetOpacity(0.35);
  shell->GetProperty()->SetSpecular(0.5);
  shell->GetProperty()->SetSpecularPower(30);
  auto cutter = SphereActor(0.8, 0.3, 0.4, 0.6, 48);
  cutter->GetProperty()->SetColor(0.2, 1.0, 0.3);
  cutter->GetProperty()->SetOpacity(0.5);
  for (vtkActor* a : { core.Get(), shell.Get(), cutter.Get() })
  {
    scene.Renderer->AddActor(a);
  }
  scene.Frame(25, 1.3);
  scene.Window->Render();
  auto rasterZ = ZBuffer(scene.Window);
  RasterAndTraced frames = Compare("Shell", scene, 3, 3.0);
  auto tracedZ = ZBuffer(scene.Window);
  const long differ = DepthsDiffering(rasterZ, tracedZ);
  const long far = FarPixels(tracedZ);
  std::ostringstream s;
  s << "Shell: depth as raster's (the opaque depth) at all but " << differ << " pixels, "
    << far << " far";
  Check(differ < W * H / 200 && far > W * H / 4, s.str());
  // Sub-pixel samples: each adds its alpha, the resolve blends the sum.
  frames.Pass->SetSamplesPerPixel(4);
  scene.Window->Render();
  const double sampled = RootMeanSquareError(frames.Raster, Grab(scene.Window));
  std::ostringstream a;
  a << "Shell, 4 samples per pixel: RGB RMSE " << sampled << " against raster (<= 3)";
  Check(sampled <= 3.0, a.str());
  NoVTKOutput("Shell, 4 samples per pixel");
}

/// A composite of three spheres, two translucent by their block opacities
/// (0.35 and 0.6), one opaque with a block color: translucent blocks are
/// composited, the opaque one stops the layers behind it.
void TestBlocks()
{
  Scene scene;
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(3);
  const double centers[3][3] = { { 0.0, 0.0, 0.0 }, { 0.9, 0.2, -0.8 }, { -0.9, -0.2, -0.6 } };
  for (int b = 0; b < 3; ++b)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(centers[b][0], centers[b][1], centers[b][2]);
    sphere->SetRadius(b == 0 ? 0.8 : 0.5);
    sphere->SetThetaResolution(48);
    sphere->SetPhiResolution(48);
    sphere->Update();
    blocks->SetBlock(b, sphere->GetOutput());
  }
  vtkNew<vtkCompositePolyDataMapper2> mapper;
  mapper->SetInputDataObject(blocks);
  vtkNew<vtkCompositeDataDisplayAttributes> attributes;
  attributes->SetBlockOpacity(blocks->GetBlock(0), 0.35);
  attributes->SetBlockOpacity(blocks->GetBlock(2), 0.6);
  const double orange[3] = { 0.9, 0.6, 0.3 };
  attributes->SetBlockColor(blocks->GetBlock(1), orange);
  mapper->SetCompositeDataDisplayAttributes(attributes);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.3, 0.6, 1.0);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(20.0);
  scene.Renderer->AddActor(actor);
  scene.Frame(30, 1.2);
  Compare("Blocks", scene, 1, 3.0);
}

/// Twelve translucent spheres over an opaque floor: the top-level walk
/// (more than 8 instances) continues past each layer too.
void TestManyActors()
{
  Scene scene;
  for (int i = 0; i < 12; ++i)
  {
    auto ball = SphereActor(0.5 * (i % 4) - 0.75, 0.25 * (i / 4), 0.3 * (i % 3), 0.3, 32);
    ball->GetProperty()->SetColor(0.2 + 0.06 * i, 0.9 - 0.05 * i, 0.5);
    ball->GetProperty()->SetOpacity(0.3 + 0.05 * i);
    scene.Renderer->AddActor(ball);
  }
  auto floor = FloorActor(1.5);
  floor->SetPosition(0.0, -0.35, 0.0);
  scene.Renderer->AddActor(floor);
  scene.Frame(30, 1.2);
  Compare("ManyActors", scene, 13, 3.0);
}

/// A sphere whose point scalars carry alpha (interpolated as raster does)
/// and a plane of cell scalars with alpha, over an opaque floor.
void TestScalars()
{
  Scene scene;
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(48);
  source->SetPhiResolution(32);
  source->Update();
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->DeepCopy(source->GetOutput());
  vtkNew<vtkUnsignedCharArray> pointRGBA;
  pointRGBA->SetNumberOfComponents(4);
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    const double* p = sphere->GetPoint(i);
    const unsigned char c[4] = { static_cast<unsigned char>(128 + 250 * p[0]), 80,
      static_cast<unsigned char>(128 - 250 * p[0]), static_cast<unsigned char>(40 + 400 * (p[1] + 0.5)) };
    pointRGBA->InsertNextTypedTuple(c);
  }
  sphere->GetPointData()->SetScalars(pointRGBA);
  auto ball = MeshActor(sphere);
  ball->GetMapper()->ScalarVisibilityOn();
  vtkPolyDataMapper::SafeDownCast(ball->GetMapper())->SetColorModeToDirectScalars();
  scene.Renderer->AddActor(ball);

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.9, -0.6, 0.3);
  plane->SetPoint1(0.9, -0.6, 0.3);
  plane->SetPoint2(-0.9, 0.6, 0.6);
  plane->SetResolution(6, 4);
  plane->Update();
  auto cells = vtkSmartPointer<vtkPolyData>::New();
  cells->DeepCopy(plane->GetOutput());
  vtkNew<vtkUnsignedCharArray> cellRGBA;
  cellRGBA->SetNumberOfComponents(4);
  for (vtkIdType i = 0; i < cells->GetNumberOfCells(); ++i)
  {
    const unsigned char c[4] = { 60, static_cast<unsigned char>(40 * (i % 6) + 40), 200,
      static_cast<unsigned char>(30 + 9 * i) };
    cellRGBA->InsertNextTypedTuple(c);
  }
  cells->GetCellData()->SetScalars(cellRGBA);
  cells->GetPointData()->SetNormals(nullptr);
  auto sheet = MeshActor(cells);
  sheet->GetMapper()->ScalarVisibilityOn();
  vtkPolyDataMapper::SafeDownCast(sheet->GetMapper())->SetColorModeToDirectScalars();
  scene.Renderer->AddActor(sheet);
  auto floor = FloorActor(1.5);
  floor->SetPosition(0.0, -0.7, 0.0);
  scene.Renderer->AddActor(floor);
  scene.Frame(-30, 1.2);
  Compare("Scalars", scene, 3, 3.0);
}

/// An RGBA texture whose texels' alpha runs from 0.15 to 1 (interpolated).
vtkSmartPointer<vtkTexture> TranslucentTexture()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < 8; ++y)
  {
    for (int x = 0; x < 8; ++x, p += 4)
    {
      const bool dark = (x + y) % 2 == 0;
      p[0] = dark ? 40 : 230;
      p[1] = static_cast<unsigned char>(30 * y);
      p[2] = dark ? 220 : 60;
      p[3] = static_cast<unsigned char>(40 + 30 * x);
    }
  }
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOn();
  return texture;
}

/// A quad textured with translucent texels in front of an opaque sphere.
void TestTexture()
{
  Scene scene;
  auto ball = SphereActor(0.0, 0.0, -0.6, 0.6, 48);
  ball->GetProperty()->SetColor(0.9, 0.8, 0.3);
  scene.Renderer->AddActor(ball);
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1.0, -0.8, 0.2);
  plane->SetPoint1(1.0, -0.8, 0.2);
  plane->SetPoint2(-1.0, 0.8, 0.2);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> quad;
  quad->SetMapper(mapper);
  quad->SetTexture(TranslucentTexture());
  scene.Renderer->AddActor(quad);
  scene.Frame(20, 1.3);
  Compare("Texture", scene, 2, 3.0);
}

/// Translucent sphere glyphs around an opaque sphere: left to raster
/// (VTK's glyph mapper blends their layers unlike a mesh's), composited
/// with the traced sphere as raster draws the scene.
void TestGlyphs()
{
  Scene scene;
  scene.Renderer->AddActor(SphereActor(0.0, 0.0, 0.0, 0.4, 64));
  vtkNew<vtkPolyData> centers;
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 5; ++i)
  {
    points->InsertNextPoint(0.6 * std::cos(1.3 * i), 0.3 * (i - 2), 0.6 * std::sin(1.3 * i));
  }
  centers->SetPoints(points);
  vtkNew<vtkSphereSource> source;
  source->SetRadius(0.35);
  source->SetThetaResolution(128);
  source->SetPhiResolution(64);
  vtkNew<vtkGlyph3DMapper> glyphs;
  glyphs->SetInputData(centers);
  glyphs->SetSourceConnection(source->GetOutputPort());
  glyphs->ScalingOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(glyphs);
  actor->GetProperty()->SetColor(0.4, 0.9, 0.6);
  actor->GetProperty()->SetOpacity(0.45);
  scene.Renderer->AddActor(actor);
  scene.Frame(10, 1.4);
  RasterAndTraced frames = RenderRasterThenTraced(scene.Window, scene.Renderer);
  const double rmse = RootMeanSquareError(frames.Raster, frames.Traced);
  std::ostringstream s;
  s << "Glyphs: " << frames.Pass->GetNumberOfTracedProps() << " prop traced (the opaque sphere), "
    << "RGB RMSE " << rmse << " against raster (<= 3)";
  Check(frames.Pass->GetNumberOfTracedProps() == 1 && rmse <= 3.0, s.str());
  if (rmse > 3.0)
  {
    WriteFailedImages("Glyphs", frames.Raster, frames.Traced);
  }
  NoGLError(scene.Window, "Glyphs");
  NoVTKOutput("Glyphs");
}

/// A traced floor under a traced sphere lit from straight above: the
/// translucent sphere's shadow is lighter than the opaque one's, by the
/// light its two layers let through ((1 - 0.4)^2 of the direct light).
void TestShadow()
{
  Scene scene;
  auto floor = FloorActor(2.0);
  floor->GetProperty()->SetColor(0.6, 0.6, 0.6); // lit floor below 255
  scene.Renderer->AddActor(floor);
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
  Check(pass->GetNumberOfTracedProps() == 2, "Shadow: floor and sphere traced");
  // Floor pixels in the opaque sphere's shadow that the sphere does not
  // cover in the view (the translucent sphere leaves them as they were).
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
  s << "Shadow: " << mask.size() << " floor pixels in the shadow: lit " << litMean << ", under the "
    << "opaque sphere " << opaqueMean << ", under the translucent one " << glassMean << " ("
    << through << " of the direct light through, 0.36 expected)";
  Check(mask.size() > 300 && opaqueMean < glassMean && glassMean < litMean &&
      std::abs(through - 0.36) < 0.03,
    s.str());
  NoGLError(scene.Window, "Shadow");
  NoVTKOutput("Shadow");
}

/// The actors of the interleaved-walks scenes: two overlapping translucent
/// spheres over an opaque one and a floor, or one deep translucent sphere
/// (its walk starts from tile entries).
void AddWalkActors(vtkRenderer* ren, bool deepMesh)
{
  if (deepMesh)
  {
    auto sphere = SphereActor(0.0, 0.0, 0.0, 0.5, 640);
    sphere->GetProperty()->SetOpacity(0.5);
    ren->AddActor(sphere);
    return;
  }
  ren->AddActor(FloorActor(2.0));
  auto glass = SphereActor(0.0, 0.5, 0.0, 0.4, 48);
  glass->GetProperty()->SetOpacity(0.4);
  ren->AddActor(glass);
  auto tinted = SphereActor(0.35, 0.6, 0.2, 0.3, 48);
  tinted->GetProperty()->SetOpacity(0.6);
  tinted->GetProperty()->SetColor(0.3, 0.6, 1.0);
  ren->AddActor(tinted);
  ren->AddActor(SphereActor(-0.2, 0.3, 0.3, 0.15, 32));
}

/// A translucent layer's shadow and occlusion rays walked from its shading
/// or interleaved with the camera ray's layers in one loop
/// (Features::InterleavedWalks: on GPUs, not on llvmpipe;
/// VTKRT_INTERLEAVED_WALKS chooses here) give the same image: byte for byte
/// on llvmpipe; on a GPU two programs may round apart (RGB RMSE 0.5). With
/// shadows and 3 occlusion rays, under the headlight, a directional light, a
/// spot light, with 4 samples a pixel, and over one deep mesh.
void TestInterleavedWalks()
{
  struct Case
  {
    std::string Name;
    int Light; ///< 0: the headlight, 1: directional, 2: spot
    int Samples;
    bool DeepMesh;
  };
  const Case cases[] = { { "headlight", 0, 0, false }, { "directional light", 1, 0, false },
    { "spot light", 2, 0, false }, { "4 samples a pixel", 1, 4, false },
    { "one deep mesh, tile entries", 0, 0, true } };
  for (const Case& c : cases)
  {
    const std::string name = "InterleavedWalks, " + c.Name;
    Scene scene;
    AddWalkActors(scene.Renderer, c.DeepMesh);
    if (c.Light > 0)
    {
      vtkNew<vtkLight> light;
      light->SetLightTypeToSceneLight();
      light->SetPosition(0.3, c.Light == 1 ? 10.0 : 2.5, 0.2);
      light->SetFocalPoint(0.0, 0.0, 0.0);
      light->SetPositional(c.Light == 2);
      light->SetConeAngle(35.0);
      scene.Renderer->AddLight(light);
    }
    scene.Frame(20, 1.3);
    vtkNew<vtkRayTracePass> pass;
    pass->SetShadows(true);
    pass->SetAmbientOcclusionSamples(3);
    pass->SetSamplesPerPixel(std::max(1, c.Samples));
    scene.Renderer->SetPass(pass);
    std::vector<vtkSmartPointer<vtkImageData>> images;
    std::vector<std::string> shaders;
    for (const char* mode : { "0", "1" })
    {
      setenv("VTKRT_INTERLEAVED_WALKS", mode, 1);
      scene.Window->Render();
      images.push_back(Grab(scene.Window));
      shaders.push_back(pass->GetLastFragmentShaderSource());
    }
    unsetenv("VTKRT_INTERLEAVED_WALKS");
    pass->SetShadows(false);
    pass->SetAmbientOcclusionSamples(0);
    scene.Window->Render();
    const double shading = RootMeanSquareError(images[0], Grab(scene.Window));
    const auto has = [](const std::string& shader, const char* define) {
      return shader.find(std::string("#define ") + define) != std::string::npos;
    };
    Check(!has(shaders[0], "VTKRT_INTERLEAVED_WALKS") && has(shaders[1], "VTKRT_INTERLEAVED_WALKS") &&
        has(shaders[1], "VTKRT_TILE_ENTRIES") == c.DeepMesh &&
        has(shaders[1], "VTKRT_SAMPLES_PER_PIXEL") == (c.Samples > 1),
      name + ": VTKRT_INTERLEAVED_WALKS 0 walks from shading, 1 interleaves" +
        (c.DeepMesh ? ", from tile entries" : ""));
    const char* capabilities = scene.Window->ReportCapabilities();
    const bool cpu = capabilities && (std::strstr(capabilities, "llvmpipe") || std::strstr(capabilities, "softpipe"));
    const double rmse = RootMeanSquareError(images[0], images[1]);
    std::ostringstream what;
    what << name << ": the same image both ways (RGB RMSE " << rmse << (cpu ? ", llvmpipe: 0" : ", <= 0.5")
         << "; shadows and occlusion change it by " << shading << ")";
    Check((cpu ? rmse == 0.0 : rmse <= 0.5) && shading > 2.0, what.str());
    if (!(cpu ? rmse == 0.0 : rmse <= 0.5))
    {
      WriteFailedImages("InterleavedWalks", images[0], images[1]);
    }
    NoGLError(scene.Window, name);
    NoVTKOutput(name);
  }
}

/// An opaque scene compiles no translucency code; a translucent one does;
/// TraceTranslucency off leaves translucent actors to raster.
void TestFeature()
{
  Scene scene;
  auto opaque = SphereActor(0.0, 0.0, 0.0, 0.5);
  auto glass = SphereActor(0.5, 0.0, 0.5, 0.5);
  scene.Renderer->AddActor(opaque);
  scene.Renderer->AddActor(glass);
  scene.Frame(0, 1.0);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  auto compiled = [&]() {
    scene.Window->Render();
    const std::string source = pass->GetLastFragmentShaderSource();
    // The define, or the compositing chunk (vtkrtRayTraceTranslucent).
    return source.find("#define VTKRT_TRANSLUCENT") != std::string::npos ||
      source.find("kLayerGapUlps") != std::string::npos;
  };
  Check(!compiled() && pass->GetNumberOfTracedProps() == 2, "opaque scene: no translucency code");
  glass->GetProperty()->SetOpacity(0.5);
  Check(compiled() && pass->GetNumberOfTracedProps() == 2, "translucent actor: traced, composited");
  pass->SetShadows(true);
  Check(compiled(), "translucent actor with shadows: transmittance compiled");
  pass->SetAmbientOcclusionSamples(4);
  Check(compiled(), "translucent actor with ambient occlusion: compiled");
  pass->SetAmbientOcclusionSamples(0);
  pass->TraceTranslucencyOff();
  Check(!compiled() && pass->GetNumberOfTracedProps() == 1, "TraceTranslucency off: left to raster");
  NoGLError(scene.Window, "Feature");
  NoVTKOutput("Feature");
}

/// Opacity outside [0, 1]: vtkProperty clamps it (above 1: opaque; below 0:
/// invisible, as raster draws it), and NaN draws as opaque; no crash.
void TestBadOpacity()
{
  Scene scene;
  scene.Renderer->AddActor(SphereActor(0.0, 0.0, 0.0, 0.5));
  auto other = SphereActor(0.5, 0.0, 0.5, 0.5);
  scene.Renderer->AddActor(other);
  scene.Frame(0, 1.0);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  auto opaque = Grab(scene.Window);
  other->GetProperty()->SetOpacity(1.5);
  scene.Window->Render();
  Check(RootMeanSquareError(opaque, Grab(scene.Window)) == 0.0, "opacity 1.5: as opaque");
  other->GetProperty()->SetOpacity(std::nan(""));
  scene.Window->Render();
  Check(RootMeanSquareError(opaque, Grab(scene.Window)) == 0.0, "opacity NaN: as opaque");
  other->GetProperty()->SetOpacity(-0.5);
  scene.Window->Render();
  auto invisible = Grab(scene.Window);
  Check(pass->GetNumberOfTracedProps() == 2, "opacity -0.5 (0): counted traced");
  other->SetVisibility(false);
  scene.Window->Render();
  Check(RootMeanSquareError(invisible, Grab(scene.Window)) == 0.0, "opacity -0.5 (0): invisible");
  NoGLError(scene.Window, "BadOpacity");
  NoVTKOutput("BadOpacity");
}

/// (prop, cell id) of every pixel's selection over the whole window.
std::set<std::pair<vtkProp*, vtkIdType>> SelectCells(vtkRenderer* ren)
{
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(ren);
  selector->SetArea(0, 0, W - 1, H - 1);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  vtkSmartPointer<vtkSelection> selection = vtk::TakeSmartPointer(selector->Select());
  std::set<std::pair<vtkProp*, vtkIdType>> cells;
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    auto* prop = vtkProp::SafeDownCast(node->GetProperties()->Get(vtkSelectionNode::PROP()));
    vtkDataArray* ids = vtkArrayDownCast<vtkDataArray>(node->GetSelectionList());
    for (vtkIdType i = 0; ids && i < ids->GetNumberOfTuples(); ++i)
    {
      cells.emplace(prop, static_cast<vtkIdType>(ids->GetTuple1(i)));
    }
  }
  return cells;
}

/// Hardware selection sees the nearest layer, translucent or not, as
/// raster's selection does.
void TestSelection()
{
  Scene scene;
  scene.Renderer->AddActor(SphereActor(0.0, 0.0, 0.0, 0.5, 24));
  auto glass = SphereActor(0.4, 0.0, 0.6, 0.5, 24);
  glass->GetProperty()->SetOpacity(0.4);
  scene.Renderer->AddActor(glass);
  scene.Frame(0, 1.0);
  scene.Window->Render();
  const auto raster = SelectCells(scene.Renderer);
  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  const auto traced = SelectCells(scene.Renderer);
  long glassCells = 0;
  for (const auto& c : raster)
  {
    glassCells += c.first == glass.Get();
  }
  long missing = 0;
  for (const auto& c : raster)
  {
    missing += traced.count(c) == 0;
  }
  long extra = 0;
  for (const auto& c : traced)
  {
    extra += raster.count(c) == 0;
  }
  std::ostringstream s;
  s << "Selection: " << raster.size() << " raster cells (" << glassCells << " translucent), traced "
    << traced.size() << ": " << missing << " missing, " << extra << " extra";
  Check(pass->GetNumberOfTracedProps() == 2 && glassCells > 50 && missing <= 4 && extra <= 4, s.str());
  NoGLError(scene.Window, "Selection");
  NoVTKOutput("Selection");
}
// A traced translucent shell in front of opaque props that raster draws:
// an image slice behind it, points inside it, an outline through it and a
// text. Raster
// draws those before the trace (the shell's camera rays end at their depth)
// so they show through its layers, as with raster; the text stays on top.
// Before, raster drew them over the traced layers (RMSE 25.5 here). The
// accumulation continues while nothing changes.
void TestOverRasterProps()
{
  Scene scene;
  auto shell = SphereActor(0.0, 0.0, 0.0, 1.0, 64);
  shell->GetProperty()->SetColor(0.3, 0.5, 1.0);
  shell->GetProperty()->SetOpacity(0.4);
  scene.Renderer->AddActor(shell);
  vtkNew<vtkImageData> image;
  image->SetDimensions(32, 32, 1);
  // Behind the shell: where an opaque prop cuts a translucent surface, VTK
  // 9.1's dual depth peeling drops some unlit back layers in front of it
  // (a traced opaque plane gives the pass's image there; docs/pass.md).
  image->SetOrigin(-1.4, -1.4, -1.2);
  image->SetSpacing(2.8 / 31, 2.8 / 31, 1.0);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  for (int j = 0; j < 32; ++j)
  {
    for (int i = 0; i < 32; ++i)
    {
      *static_cast<unsigned char*>(image->GetScalarPointer(i, j, 0)) =
        static_cast<unsigned char>(((i / 4 + j / 4) % 2) ? 230 : 40);
    }
  }
  vtkNew<vtkImageSliceMapper> sliceMapper;
  sliceMapper->SetInputData(image);
  vtkNew<vtkImageSlice> slice;
  slice->SetMapper(sliceMapper);
  scene.Renderer->AddViewProp(slice);
  auto dots = PointCloudActor(-0.9, 0.045, 0.4, 5.0);
  scene.Renderer->AddActor(dots);
  vtkNew<vtkOutlineSource> box;
  box->SetBounds(-1.2, 1.2, -1.2, 1.2, -0.6, 0.6);
  box->Update();
  auto outline = MeshActor(box->GetOutput());
  outline->GetProperty()->SetColor(1.0, 0.3, 0.3);
  outline->GetProperty()->SetLineWidth(2.0);
  scene.Renderer->AddActor(outline);
  // A raster line lying on a traced opaque plane: it stays over the plane,
  // as when raster drew it after the trace (it vanished under the plane
  // when raster's props first moved before the trace).
  vtkNew<vtkPlaneSource> wall;
  wall->SetOrigin(-1.6, -1.6, -1.3);
  wall->SetPoint1(1.6, -1.6, -1.3);
  wall->SetPoint2(-1.6, 1.6, -1.3);
  wall->Update();
  auto back = MeshActor(wall->GetOutput());
  back->GetProperty()->SetColor(0.35, 0.35, 0.35);
  scene.Renderer->AddActor(back);
  vtkNew<vtkPoints> linePoints;
  vtkNew<vtkCellArray> lineCells;
  lineCells->InsertNextCell(2);
  lineCells->InsertCellPoint(linePoints->InsertNextPoint(-1.5, 1.45, -1.3));
  lineCells->InsertCellPoint(linePoints->InsertNextPoint(1.5, 1.45, -1.3));
  vtkNew<vtkPolyData> onWall;
  onWall->SetPoints(linePoints);
  onWall->SetLines(lineCells);
  auto line = MeshActor(onWall);
  line->GetProperty()->SetColor(0.1, 1.0, 0.2);
  line->GetProperty()->SetLineWidth(3.0);
  line->GetProperty()->LightingOff();
  scene.Renderer->AddActor(line);
  vtkNew<vtkTextActor> text;
  text->SetInput("over everything");
  text->GetTextProperty()->SetFontSize(24);
  text->SetDisplayPosition(60, 100);
  scene.Renderer->AddActor2D(text);
  scene.Frame(20.0, 1.2);
  RasterAndTraced frames = Compare("OverRasterProps", scene, 2, 3.0);
  const auto linePixels = [](vtkImageData* image) {
    long n = 0;
    for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
    {
      const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer()) + 3 * i;
      n += p[1] > 200 && p[0] < 80 && p[2] < 100;
    }
    return n;
  };
  const long rasterLine = linePixels(frames.Raster), tracedLine = linePixels(frames.Traced);
  std::ostringstream onPlane;
  onPlane << "OverRasterProps: a raster line on a traced plane shows (" << tracedLine << " pixels, raster "
          << rasterLine << ")";
  Check(rasterLine > 100 && tracedLine >= rasterLine - rasterLine / 10, onPlane.str());
  frames.Pass->ProgressiveAccumulationOn();
  for (int i = 0; i < 3; ++i)
  {
    scene.Window->Render();
  }
  std::ostringstream s;
  s << "OverRasterProps: " << frames.Pass->GetAccumulatedFrames() << " frames accumulated over still props (3)";
  Check(frames.Pass->GetAccumulatedFrames() == 3, s.str());
  dots->GetProperty()->SetColor(0.1, 0.9, 1.0);
  scene.Window->Render();
  std::ostringstream again;
  again << "OverRasterProps: " << frames.Pass->GetAccumulatedFrames()
        << " frames accumulated after a prop below changed (1)";
  Check(frames.Pass->GetAccumulatedFrames() == 1, again.str());
  NoVTKOutput("OverRasterProps");
}
/// Translucent layers write no depth, even where their composite is opaque
/// (a sphere forced translucent at opacity 1, and two layers at 0.98), as
/// VTK's translucent pass: the depth stays an opaque plane's behind them, or
/// the far plane (both wrote their own depth before, over whole spheres).
void TestOpaqueCompositeDepth()
{
  Scene scene;
  auto forced = SphereActor(-0.6, 0.0, 0.0, 0.5, 48);
  forced->ForceTranslucentOn();
  auto dense = SphereActor(0.6, 0.0, 0.0, 0.5, 48);
  dense->GetProperty()->SetOpacity(0.98);
  vtkNew<vtkPlaneSource> wall;
  wall->SetOrigin(-1.5, -1.0, -0.8);
  wall->SetPoint1(0.3, -1.0, -0.8);
  wall->SetPoint2(-1.5, 1.0, -0.8);
  wall->Update();
  auto back = MeshActor(wall->GetOutput());
  for (vtkActor* a : { forced.Get(), dense.Get(), back.Get() })
  {
    scene.Renderer->AddActor(a);
  }
  scene.Frame(0, 1.2);
  scene.Window->Render();
  auto rasterZ = ZBuffer(scene.Window);
  Compare("OpaqueCompositeDepth", scene, 3, 3.0);
  auto tracedZ = ZBuffer(scene.Window);
  const long differ = DepthsDiffering(rasterZ, tracedZ);
  // Where the spheres alone cover the pixel raster leaves the far plane.
  const long spheres = FarPixels(rasterZ);
  std::ostringstream s;
  s << "OpaqueCompositeDepth: depth as raster's at all but " << differ << " pixels (<= 0.5%; "
    << spheres << " far pixels in raster's)";
  Check(differ <= W * H / 200 && spheres > W * H / 10, s.str());
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "Shell", TestShell }, { "Scalars", TestScalars }, { "Texture", TestTexture },
      { "Glyphs", TestGlyphs }, { "ManyActors", TestManyActors }, { "Blocks", TestBlocks },
      { "Shadow", TestShadow }, { "InterleavedWalks", TestInterleavedWalks }, { "Feature", TestFeature },
      { "BadOpacity", TestBadOpacity }, { "Selection", TestSelection },
      { "OverRasterProps", TestOverRasterProps }, { "OpaqueCompositeDepth", TestOpaqueCompositeDepth } });
}
