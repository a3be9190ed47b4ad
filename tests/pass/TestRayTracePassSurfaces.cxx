// Surfaces as the actor's property and texture make them (issue 22, parts 4
// and 5), traced and compared with VTK's raster of the same scene:
//   Textures          an RGB texture on a tilted plane and a lit sphere:
//                     repeat, clamp to edge, mirrored repeat and clamp to
//                     border, interpolate on and off, texture x property
//                     color and x scalar colors
//   TextureRGBA       an opaque RGBA texture, and one with cut-out texels
//                     (raster discards them: rays pass through)
//   TextureBadInput   a texture without texture coordinates (drawn
//                     untextured, as raster), with 3-component coordinates,
//                     or without an image: no crash, as raster
//   TextureUploads    several textured actors: one image shared, uploaded
//                     once; a camera move uploads nothing; no texture code
//                     in the shader of a scene without textures
//   TextureShadow     a traced sphere over a traced textured floor, shadows
//                     on: the shadow darkens the floor's texture; light
//                     passes the cut-out texels of a textured plane
//   Culling           back-face and front-face culling of open and closed
//                     meshes (also mirrored by the actor matrix)
//   BackfaceProperty  a back-face material on an open mesh, and on planes
//                     seen from both sides with a texture shown or hidden
//                     on back faces
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTexture.h"
#include "vtkTexturedSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
constexpr int kSize = 240;

/// A w x h image of 8-bit colors (`comps` 3 or 4): smooth color ramps with
/// a checker of darker texels, so both filtering and wrapping show.
vtkSmartPointer<vtkImageData> PatternImage(int w, int h, int comps, bool cutOuts = false)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(comps);
  colors->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const bool dark = ((x + y) & 1) != 0;
      unsigned char c[4] = { static_cast<unsigned char>(40 + 200 * x / (w - 1)),
        static_cast<unsigned char>(230 - 180 * y / (h - 1)),
        static_cast<unsigned char>(dark ? 60 : 200), 255 };
      if (dark)
      {
        c[0] = static_cast<unsigned char>(c[0] / 2);
      }
      if (cutOuts && x == y)
      {
        c[3] = 0;
      }
      colors->SetTypedTuple(static_cast<vtkIdType>(y) * w + x, c);
    }
  }
  image->GetPointData()->SetScalars(colors);
  return image;
}

vtkSmartPointer<vtkTexture> MakeTexture(vtkImageData* image, int wrap, bool interpolate)
{
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->SetWrap(wrap);
  texture->SetInterpolate(interpolate);
  texture->SetBorderColor(0.2f, 0.9f, 0.9f, 1.0f);
  return texture;
}

/// A unit plane in z = 0 whose texture coordinates run from -0.75 to 1.75,
/// so that the wrap mode decides a good part of it.
vtkSmartPointer<vtkPolyData> WidePlane(double cx, double cy)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(cx - 0.5, cy - 0.5, 0.0);
  plane->SetPoint1(cx + 0.5, cy - 0.5, 0.0);
  plane->SetPoint2(cx - 0.5, cy + 0.5, 0.0);
  plane->SetResolution(3, 2);
  plane->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(plane->GetOutput());
  vtkDataArray* tcoords = poly->GetPointData()->GetTCoords();
  for (vtkIdType i = 0; i < tcoords->GetNumberOfTuples(); ++i)
  {
    tcoords->SetComponent(i, 0, 2.5 * tcoords->GetComponent(i, 0) - 0.75);
    tcoords->SetComponent(i, 1, 2.5 * tcoords->GetComponent(i, 1) - 0.75);
  }
  return poly;
}

/// A textured sphere (texture coordinates from vtkTexturedSphereSource).
vtkSmartPointer<vtkPolyData> TexturedSphere()
{
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetRadius(0.45);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  sphere->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(sphere->GetOutput());
  return poly;
}

vtkSmartPointer<vtkActor> TexturedActor(vtkPolyData* poly, vtkTexture* texture)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetTexture(texture);
  return actor;
}

/// The scene's window and renderer: a tilted view of whatever is added.
struct Scene
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(kSize, kSize);
  vtkNew<vtkRenderer> Renderer;
  Scene()
  {
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.1, 0.1, 0.15);
  }
  void View(double azimuth, double elevation)
  {
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(azimuth);
    this->Renderer->GetActiveCamera()->Elevation(elevation);
    this->Renderer->ResetCameraClippingRange();
  }
  /// Raster, then traced: checks that `traced` props are traced and the
  /// RGB RMSE against raster is at most `bound`.
  RasterAndTraced Compare(const std::string& label, int traced, double bound)
  {
    this->Renderer->SetPass(nullptr);
    RasterAndTraced frames = RenderRasterThenTraced(this->Window, this->Renderer);
    const double rmse = RootMeanSquareError(frames.Raster, frames.Traced);
    std::ostringstream s;
    s << label << ": " << frames.Pass->GetNumberOfTracedProps() << " traced props (want "
      << traced << "), RGB RMSE vs raster " << rmse << " (bound " << bound << ")";
    Check(frames.Pass->GetNumberOfTracedProps() == traced && rmse <= bound, s.str());
    if (rmse > bound)
    {
      static int written = 0;
      const std::string name = "surfaces-" + std::to_string(written++);
      WritePNG(frames.Raster, name + "-raster.png");
      WritePNG(frames.Traced, name + "-traced.png");
    }
    NoGLError(this->Window, label);
    return frames;
  }
};

bool ShaderHasTextures(vtkRayTracePass* pass)
{
  return std::string(pass->GetLastFragmentShaderSource()).find("uTextures") != std::string::npos;
}

void TestTextures()
{
  auto image = PatternImage(12, 8, 3);
  const struct
  {
    int Wrap;
    const char* Name;
  } wraps[] = { { vtkTexture::Repeat, "repeat" }, { vtkTexture::ClampToEdge, "clamp to edge" },
    { vtkTexture::MirroredRepeat, "mirrored repeat" }, { vtkTexture::ClampToBorder, "clamp to border" } };
  for (const auto& wrap : wraps)
  {
    for (bool interpolate : { false, true })
    {
      Scene scene;
      auto texture = MakeTexture(image, wrap.Wrap, interpolate);
      auto plane = TexturedActor(WidePlane(0.0, 0.0), texture);
      plane->GetProperty()->SetColor(1.0, 0.9, 0.8);
      scene.Renderer->AddActor(plane);
      scene.View(25, -35);
      const std::string label =
        std::string("plane, ") + wrap.Name + (interpolate ? ", interpolated" : ", nearest");
      RasterAndTraced frames = scene.Compare(label, 1, 3.0);
      Check(ShaderHasTextures(frames.Pass), label + ": the shader samples the texture");
    }
  }

  // Lit, specular, texture x property color; then x point scalars.
  for (bool scalars : { false, true })
  {
    Scene scene;
    auto poly = TexturedSphere();
    if (scalars)
    {
      vtkNew<vtkElevationFilter> elevation;
      elevation->SetInputData(poly);
      elevation->SetLowPoint(0, -0.5, 0);
      elevation->SetHighPoint(0, 0.5, 0);
      elevation->Update();
      poly->DeepCopy(elevation->GetOutput());
    }
    auto sphere = TexturedActor(poly, MakeTexture(image, vtkTexture::Repeat, true));
    sphere->GetMapper()->SetScalarVisibility(scalars);
    sphere->GetProperty()->SetColor(0.9, 0.7, 0.5);
    sphere->GetProperty()->SetSpecular(0.5);
    sphere->GetProperty()->SetSpecularPower(30);
    scene.Renderer->AddActor(sphere);
    scene.View(30, 20);
    scene.Compare(scalars ? "sphere, texture x scalar colors" : "sphere, texture x lit color", 1, 3.0);
  }

  // Texture coordinates longer than the points (a tuple appended): raster
  // reads the first ones by point id, and so does the pass.
  {
    Scene scene;
    auto poly = TexturedSphere();
    poly->GetPointData()->GetTCoords()->InsertNextTuple2(0.5, 0.5);
    scene.Renderer->AddActor(TexturedActor(poly, MakeTexture(image, vtkTexture::Repeat, true)));
    scene.View(30, 20);
    RasterAndTraced frames = scene.Compare("sphere, texture coordinates longer than its points", 1, 3.0);
    Check(ShaderHasTextures(frames.Pass), "longer texture coordinates: the shader samples the texture");
  }
  NoVTKOutput("textures");
}

void TestTextureRGBA()
{
  for (bool cutOuts : { false, true })
  {
    Scene scene;
    auto plane = TexturedActor(
      WidePlane(0.0, 0.0), MakeTexture(PatternImage(8, 8, 4, cutOuts), vtkTexture::Repeat, false));
    scene.Renderer->AddActor(plane);
    // Behind it, seen through the cut-outs.
    scene.Renderer->AddActor(SphereActor(0.2, 0.1, -0.8, 0.5));
    scene.View(-20, 30);
    RasterAndTraced frames =
      scene.Compare(cutOuts ? "RGBA with cut-out texels" : "opaque RGBA", 2, 3.0);
    const bool cutOutCode = std::string(frames.Pass->GetLastFragmentShaderSource())
                              .find("#define VTKRT_TEXTURE_CUTOUTS") != std::string::npos;
    Check(cutOutCode == cutOuts, "cut-out code only for a texture with cut-outs");
  }
  NoVTKOutput("RGBA");
}

void TestTextureBadInput()
{
  auto texture = MakeTexture(PatternImage(8, 8, 3), vtkTexture::Repeat, true);
  {
    // No texture coordinates: raster draws the actor untextured, so does the pass.
    Scene scene;
    auto poly = WidePlane(0.0, 0.0);
    poly->GetPointData()->SetTCoords(nullptr);
    scene.Renderer->AddActor(TexturedActor(poly, texture));
    scene.View(10, 10);
    RasterAndTraced frames = scene.Compare("texture without coordinates", 1, 3.0);
    Check(!ShaderHasTextures(frames.Pass), "no coordinates: no texture code");
  }
  {
    // 3-component coordinates: raster ignores the texture too.
    Scene scene;
    auto poly = WidePlane(0.0, 0.0);
    vtkNew<vtkFloatArray> str;
    str->SetNumberOfComponents(3);
    str->SetNumberOfTuples(poly->GetNumberOfPoints());
    str->Fill(0.5);
    poly->GetPointData()->SetTCoords(str);
    scene.Renderer->AddActor(TexturedActor(poly, texture));
    scene.View(10, 10);
    scene.Compare("3-component texture coordinates", 1, 3.0);
  }
  NoVTKOutput("bad input");
  {
    // A texture without an image (VTK 9.1's raster crashes on it): traced
    // untextured with one warning, as the plain actor.
    Scene scene;
    vtkNew<vtkTexture> empty;
    auto actor = TexturedActor(WidePlane(0.0, 0.0), empty);
    scene.Renderer->AddActor(actor);
    scene.View(10, 10);
    vtkNew<vtkRayTracePass> pass;
    scene.Renderer->SetPass(pass);
    scene.Window->Render();
    scene.Window->Render();
    auto traced = Grab(scene.Window);
    Check(pass->GetNumberOfTracedProps() == 1 && Output->GetNumberOfWarnings() == 1 &&
        Output->GetNumberOfErrors() == 0,
      "texture without an image: traced untextured, one warning over two frames");
    Output->Clear();
    actor->SetTexture(nullptr);
    scene.Renderer->SetPass(nullptr);
    scene.Window->Render();
    const double rmse = RootMeanSquareError(Grab(scene.Window), traced);
    Check(rmse <= 3.0, "texture without an image: as raster draws the untextured actor, RMSE " +
        std::to_string(rmse));
    NoVTKOutput("texture without an image");
  }
}

void TestTextureUploads()
{
  Scene scene;
  auto image = PatternImage(16, 16, 3);
  auto shared = MakeTexture(image, vtkTexture::Repeat, true);
  for (int i = 0; i < 3; ++i)
  {
    auto own = MakeTexture(image, vtkTexture::ClampToEdge, false);
    scene.Renderer->AddActor(TexturedActor(WidePlane(1.1 * i, 0.0), i < 2 ? shared.Get() : own.Get()));
  }
  // A plain mesh beside them: untextured in the same shader.
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(1.1, 1.1, 0.0);
  ball->SetRadius(0.4);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> plain;
  plain->SetMapper(mapper);
  scene.Renderer->AddActor(plain);
  scene.View(0, -30);
  RasterAndTraced frames = scene.Compare("three textured planes and a plain sphere", 4, 3.0);
  vtkRayTracePass* pass = frames.Pass;
  scene.Renderer->GetActiveCamera()->Azimuth(10);
  scene.Renderer->ResetCameraClippingRange();
  scene.Window->Render();
  Check(pass->GetLastGeometryBytesUploaded() == 0 && pass->GetLastBVHBuilds() == 0,
    "camera move: no texture or geometry upload");
  // Texture image modified: uploaded again, nothing rebuilt.
  image->Modified();
  scene.Window->Render();
  Check(pass->GetLastGeometryBytesUploaded() > 0 && pass->GetLastBVHBuilds() == 0,
    "texture image modified: textures uploaded, no BVH rebuilt");

  // The texture code is compiled only into shaders of scenes with textures.
  Scene plainScene;
  plainScene.Renderer->AddActor(SphereActor(0, 0, 0, 0.5));
  plainScene.View(0, 0);
  vtkNew<vtkRayTracePass> plainPass;
  plainScene.Renderer->SetPass(plainPass);
  plainScene.Window->Render();
  Check(!ShaderHasTextures(plainPass) && ShaderHasTextures(pass),
    "texture code only in the textured scene's shader");
  NoVTKOutput("uploads");
}

void TestTextureShadow()
{
  Scene scene;
  auto floorPoly = WidePlane(0.0, 0.0);
  auto floor = TexturedActor(floorPoly, MakeTexture(PatternImage(8, 8, 3), vtkTexture::Repeat, false));
  floor->SetOrientation(-90, 0, 0); // into y = 0
  floor->SetScale(3.0);
  floor->GetProperty()->SetAmbient(0.1);
  scene.Renderer->AddActor(floor);
  auto ball = SphereActor(0.0, 0.5, 0.0, 0.3);
  scene.Renderer->AddActor(ball);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(0.0, 10.0, 0.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPositional(false);
  scene.Renderer->AddLight(light);
  scene.Renderer->GetActiveCamera()->SetPosition(0.0, 2.5, 2.5);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  scene.Renderer->GetActiveCamera()->SetViewUp(0.0, 1.0, 0.0);
  scene.Renderer->ResetCameraClippingRange();

  vtkNew<vtkRayTracePass> pass;
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  auto lit = Grab(scene.Window);
  pass->SetShadows(true);
  scene.Window->Render();
  auto shadowed = Grab(scene.Window);
  Check(pass->GetNumberOfTracedProps() == 2, "shadow scene: floor and sphere traced");
  // The floor right under the sphere (but outside it in the view) darkens:
  // sample the floor pixels that differ.
  const long darker = CountDifferingPixels(lit, shadowed, 20);
  std::ostringstream s;
  s << "textured floor under a traced sphere: " << darker << " pixels darkened by its shadow";
  Check(darker > 300, s.str());
  // Where it changed, the shadowed floor is darker than the lit one.
  int d[3];
  lit->GetDimensions(d);
  const auto* a = static_cast<const unsigned char*>(lit->GetScalarPointer());
  const auto* b = static_cast<const unsigned char*>(shadowed->GetScalarPointer());
  long brighter = 0;
  for (long i = 0; i < static_cast<long>(d[0]) * d[1] * 3; ++i)
  {
    brighter += b[i] > a[i] + 2;
  }
  Check(brighter == 0, "shadows only darken the textured floor");

  // A plane above the floor, textured opaque, then with cut-outs: light
  // passes the cut-out texels (any-hit rays walk past them too).
  ball->SetVisibility(false);
  long shadowedPixels[2] = { 0, 0 };
  for (int cutOuts = 0; cutOuts < 2; ++cutOuts)
  {
    auto roof = TexturedActor(
      WidePlane(0.0, 0.0), MakeTexture(PatternImage(2, 2, 4, cutOuts == 1), vtkTexture::Repeat, false));
    roof->SetOrientation(-90, 0, 0);
    roof->SetPosition(0.0, 0.4, 0.0);
    roof->SetScale(0.8);
    scene.Renderer->AddActor(roof);
    pass->SetShadows(false);
    scene.Window->Render();
    auto unshadowed = Grab(scene.Window);
    pass->SetShadows(true);
    scene.Window->Render();
    shadowedPixels[cutOuts] = CountDifferingPixels(unshadowed, Grab(scene.Window), 20);
    scene.Renderer->RemoveActor(roof);
  }
  std::ostringstream c;
  c << "shadow of a textured plane (half its texels cut out): " << shadowedPixels[0]
    << " floor pixels opaque, " << shadowedPixels[1] << " with cut-outs (fewer, not none)";
  Check(shadowedPixels[1] > 0 && shadowedPixels[1] < shadowedPixels[0] * 4 / 5, c.str());
  NoGLError(scene.Window, "shadow");
  NoVTKOutput("shadow");
}

/// A hemisphere open towards +y (its inside seen from above).
vtkSmartPointer<vtkActor> OpenCup()
{
  vtkNew<vtkSphereSource> cup;
  cup->SetRadius(0.5);
  cup->SetThetaResolution(24);
  cup->SetPhiResolution(24);
  cup->SetEndPhi(100);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cup->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->SetOrientation(90.0, 0.0, 0.0); // the pole (+z) down to -y
  return actor;
}

/// An open cup and a closed sphere culled as `cull` says (0 none, 1 back,
/// 2 front), in front of a sphere that is not.
void AddCullingScene(Scene& scene, int cull, bool mirrored)
{
  auto open = OpenCup();
  open->GetProperty()->SetColor(0.9, 0.6, 0.3);
  auto closed = SphereActor(1.2, 0.0, 0.0, 0.4, 24);
  closed->GetProperty()->SetColor(0.4, 0.7, 0.9);
  auto behind = SphereActor(0.6, -0.8, -1.0, 0.7, 24);
  for (vtkActor* actor : { open.Get(), closed.Get() })
  {
    actor->GetProperty()->SetBackfaceCulling(cull == 1);
    actor->GetProperty()->SetFrontfaceCulling(cull == 2);
    actor->GetProperty()->SetSpecular(0.3);
    if (mirrored)
    {
      actor->SetScale(1.0, 1.0, -1.0);
    }
    scene.Renderer->AddActor(actor);
  }
  scene.Renderer->AddActor(behind);
}

void TestCulling()
{
  const char* names[] = { "no culling", "back-face culling", "front-face culling" };
  for (bool mirrored : { false, true })
  {
    for (int cull = 0; cull < 3; ++cull)
    {
      Scene scene;
      AddCullingScene(scene, cull, mirrored);
      scene.View(20, 40);
      RasterAndTraced frames = scene.Compare(
        std::string(names[cull]) + (mirrored ? ", mirrored" : ""), 3, 3.0);
      const bool culled = std::string(frames.Pass->GetLastFragmentShaderSource()).find(
                            "#define VTKRT_FACE_CULLING") != std::string::npos;
      Check(culled == (cull != 0), std::string(names[cull]) + ": culling code only when used");
    }
  }
  {
    // Both on: back faces culled, as raster.
    Scene scene;
    AddCullingScene(scene, 1, false);
    vtkActorCollection* actors = scene.Renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* a = actors->GetNextActor())
    {
      a->GetProperty()->FrontfaceCullingOn();
    }
    scene.View(20, 40);
    scene.Compare("back- and front-face culling", 3, 3.0);
  }
  NoVTKOutput("culling");
}

void TestBackfaceProperty()
{
  auto image = PatternImage(8, 8, 3);
  for (int variant = 0; variant < 3; ++variant)
  {
    Scene scene;
    vtkNew<vtkProperty> back;
    back->SetColor(0.2, 0.5, 0.9);
    back->SetAmbient(0.2);
    back->SetSpecular(0.6);
    back->SetSpecularPower(40);
    std::string label = "backface property";
    if (variant == 0)
    {
      // An open cup (its inside, back faces, towards the camera).
      auto cup = OpenCup();
      cup->GetProperty()->SetColor(0.9, 0.6, 0.3);
      cup->GetProperty()->SetSpecular(0.3);
      cup->SetBackfaceProperty(back);
      scene.Renderer->AddActor(cup);
    }
    else
    {
      // Two textured planes, one turned away from the camera.
      for (int side = 0; side < 2; ++side)
      {
        auto plane = TexturedActor(WidePlane(0.0, 0.0), MakeTexture(image, vtkTexture::Repeat, true));
        plane->SetPosition(1.2 * side, 0.0, 0.0);
        plane->SetOrientation(0.0, 180.0 * side + 20.0, 0.0);
        plane->GetProperty()->SetShowTexturesOnBackface(variant == 1);
        plane->SetBackfaceProperty(back);
        scene.Renderer->AddActor(plane);
      }
      label += variant == 1 ? ", textured planes" : ", texture on front faces only";
    }
    scene.View(0, 40);
    scene.Compare(label, variant == 0 ? 1 : 2, 3.0);
  }
  NoVTKOutput("backface property");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "Textures", TestTextures }, { "TextureRGBA", TestTextureRGBA },
      { "TextureBadInput", TestTextureBadInput }, { "TextureUploads", TestTextureUploads },
      { "TextureShadow", TestTextureShadow }, { "Culling", TestCulling },
      { "BackfaceProperty", TestBackfaceProperty } });
}
