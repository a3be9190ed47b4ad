// vtkRayTracePass on scenes at the edge of what it can trace:
//   FarFromOrigin     a scene translated by 1e8 renders like the same scene
//                     at the origin
//   Degenerate        empty renderer, empty polydata, NaN points: clean image,
//                     no GL error, no VTK error
//   TooLarge          buffers over the texture-buffer limit: a clear error,
//                     raster draws the props instead, nothing counts as traced
//   Footprint         rays only within the traced instances' footprint: the
//                     image of raster, sampled or not, boxes cut by the
//                     viewport or behind the eye
//   FootprintTiles    rays only in the tiles the instances' upper tree boxes
//                     reach: the image of the whole footprint, bit for bit,
//                     from fewer pixels, as the camera turns, zooms and enters
//                     a box (its part in front of the near plane), with view-sized (points as spheres, tubes, wires),
//                     translucent and more than eight props
// TestRayTracePassRobustness <Case>.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkRayTraceFrameConstants.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPlane.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkCullerCollection.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkCubeSource.h"
#include "vtkLineSource.h"

#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
void TestFarFromOrigin()
{
  const double offset[3] = { 1e8, -1e8, 1e8 };
  auto bunny = ReadPolyData("bunny.vtp");
  auto spheres = ReadPolyData("demo-spheres.vtp");
  vtkSmartPointer<vtkImageData> images[3];
  double clipping[2] = { 0, 0 };
  double position[3], focal[3], up[3];
  for (int pass = 0; pass < 3; ++pass)
  {
    // 0: traced at the origin; 1: traced at 1e8 (data and actor offsets);
    // 2: raster at 1e8 (for information only).
    const bool far = pass > 0;
    const double zero[3] = { 0, 0, 0 };
    const double half[3] = { offset[0] / 2, offset[1] / 2, offset[2] / 2 };
    auto win = MakeWindow(300, 300);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    ren->SetBackground(0.1, 0.2, 0.3);
    // Bunny: offset in its (double) points; glyphs: half in the points,
    // half in the actor matrix.
    ren->AddActor(MeshActor(Shifted(bunny, far ? offset : zero)));
    auto glyphs = GlyphActor(Shifted(spheres, far ? half : zero));
    if (far)
    {
      glyphs->SetPosition(half[0], half[1], half[2]);
    }
    ren->AddActor(glyphs);
    vtkCamera* cam = ren->GetActiveCamera();
    if (pass == 0)
    {
      ren->ResetCamera();
      cam->Azimuth(30);
      cam->Elevation(10);
      ren->ResetCameraClippingRange();
      cam->GetClippingRange(clipping);
      cam->GetPosition(position);
      cam->GetFocalPoint(focal);
      cam->GetViewUp(up);
    }
    else
    {
      cam->SetPosition(position[0] + offset[0], position[1] + offset[1], position[2] + offset[2]);
      cam->SetFocalPoint(focal[0] + offset[0], focal[1] + offset[1], focal[2] + offset[2]);
      cam->SetViewUp(up);
      cam->SetClippingRange(clipping);
    }
    vtkNew<vtkRayTracePass> rt;
    if (pass < 2)
    {
      ren->SetPass(rt);
    }
    win->Render();
    images[pass] = Grab(win);
    NoGLError(win, "far from origin");
  }
  const double error = Difference(images[1], images[0]);
  const long differing = CountDifferingPixels(images[1], images[0], 24);
  std::ostringstream s;
  s << "traced at 1e8 vs traced at the origin: error " << error << " <= 5, " << differing
    << " pixels differ (<= 0.2%)";
  Check(error <= 5.0 && differing >= 0 && differing <= 300 * 300 / 500, s.str());
  std::cout << "info: raster at 1e8 vs traced at the origin: error "
            << Difference(images[2], images[0]) << " ("
            << CountDifferingPixels(images[2], images[0], 24) << " pixels differ)\n";
  if (error > 5.0)
  {
    WritePNG(images[0], std::string(VTKRT_TEMP_DIR) + "/pass_far_origin.png");
    WritePNG(images[1], std::string(VTKRT_TEMP_DIR) + "/pass_far_1e8.png");
  }
  NoVTKOutput("far from origin");
}

void TestDegenerate()
{
  const double background[3] = { 0.25, 0.5, 0.75 };
  auto expectBackground = [&](vtkRenderWindow* win, const std::string& what, bool empty) {
    auto image = Grab(win);
    const long fg = CountForegroundPixels(image, background);
    Check(empty ? fg == 0 : fg > 0, what + (empty ? ": background only" : ": something drawn"));
    NoGLError(win, what);
    NoVTKOutput(what);
  };
  auto win = MakeWindow(120, 100);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(background[0], background[1], background[2]);
  win->AddRenderer(ren);
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  expectBackground(win, "empty renderer", true);

  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPolyDataMapper> emptyMapper;
  emptyMapper->SetInputData(empty);
  vtkNew<vtkActor> emptyActor;
  emptyActor->SetMapper(emptyMapper);
  ren->AddActor(emptyActor);
  win->Render();
  expectBackground(win, "actor with empty polydata", true);

  // Triangles with NaN points: those triangles are skipped, the rest drawn.
  vtkNew<vtkPoints> points;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double coords[6][3] = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 },
    { nan, 0, 0 }, { 0, nan, nan } };
  for (const auto& c : coords)
  {
    points->InsertNextPoint(c);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType tris[4][3] = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 1, 4 }, { 4, 5, 2 } };
  for (const auto& t : tris)
  {
    polys->InsertNextCell(3, t);
  }
  vtkNew<vtkPolyData> withNaN;
  withNaN->SetPoints(points);
  withNaN->SetPolys(polys);
  vtkNew<vtkPolyDataMapper> nanMapper;
  nanMapper->SetInputData(withNaN);
  vtkNew<vtkActor> nanActor;
  nanActor->SetMapper(nanMapper);
  ren->AddActor(nanActor);
  // Glyphs with a NaN center and a zero radius among valid ones.
  vtkNew<vtkPolyData> centers;
  vtkNew<vtkPoints> centerPoints;
  centerPoints->InsertNextPoint(0, 0, 0.5);
  centerPoints->InsertNextPoint(nan, 0, 0);
  centerPoints->InsertNextPoint(0.5, 0.5, 0.5);
  centers->SetPoints(centerPoints);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  radius->InsertNextValue(0.2);
  radius->InsertNextValue(0.2);
  radius->InsertNextValue(0.0);
  centers->GetPointData()->AddArray(radius);
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkGlyph3DMapper> glyphMapper;
  glyphMapper->SetInputData(centers);
  glyphMapper->SetSourceConnection(sphere->GetOutputPort());
  glyphMapper->SetScaleArray("radius");
  glyphMapper->SetScaleModeToScaleByMagnitude();
  glyphMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphMapper);
  ren->AddActor(glyphActor);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(0, 0, 5);
  cam->SetFocalPoint(0, 0, 0);
  cam->SetClippingRange(1, 10);
  win->Render();
  expectBackground(win, "NaN points and zero radii", false);
  Check(pass->GetLastTracedInstances() == 2, "NaN scene: the mesh and the glyphs are traced");
  Check(pass->GetLastTracedPrimitives() == 2 + 1,
    "NaN scene: 2 valid triangles and 1 valid sphere traced (traced " +
      std::to_string(pass->GetLastTracedPrimitives()) + ")");

  // A triangle whose point id lies past the points: the others drawn, with
  // one warning a build (VTK 9.1's frustum culler crashes on such cells, so
  // the renderer has none here).
  {
    auto badWin = MakeWindow(120, 100);
    vtkNew<vtkRenderer> badRen;
    badRen->GetCullers()->RemoveAllItems();
    badWin->AddRenderer(badRen);
    vtkNew<vtkPolyData> badIds;
    badIds->SetPoints(points);
    vtkNew<vtkCellArray> badPolys;
    const vtkIdType good[3] = { 0, 1, 2 }, bad[3] = { 0, 2, 99 };
    badPolys->InsertNextCell(3, good);
    badPolys->InsertNextCell(3, bad);
    badIds->SetPolys(badPolys);
    vtkNew<vtkPolyDataMapper> badMapper;
    badMapper->SetInputData(badIds);
    vtkNew<vtkActor> badActor;
    badActor->SetMapper(badMapper);
    badRen->AddActor(badActor);
    badRen->GetActiveCamera()->SetPosition(0, 0, 5);
    badRen->GetActiveCamera()->SetClippingRange(1, 10);
    vtkNew<vtkRayTracePass> badPass;
    badRen->SetPass(badPass);
    Output->Clear();
    badWin->Render();
    badWin->Render();
    const bool warned = Output->GetNumberOfWarnings() == 1 && Output->GetNumberOfErrors() == 0 &&
      Output->GetWarnings()[0].find("refer to point ids outside [0, 6)") != std::string::npos;
    Check(badPass->GetLastTracedPrimitives() == 1 && warned,
      "a cell past the points: 1 triangle traced (" + std::to_string(badPass->GetLastTracedPrimitives()) +
        "), one warning over two frames");
    Output->Clear();
  }
}

void TestTooLarge()
{
  auto win = MakeWindow(100, 100);
  vtkNew<vtkRenderer> ren;
  const double background[3] = { 0, 0, 0 };
  win->AddRenderer(ren);
  ren->AddActor(MeshActor(ReadPolyData("bunny.vtp")));
  ren->ResetCamera();
  win->Render();
  auto raster = Grab(win);
  vtkNew<vtkRayTracePass> pass;
  pass->SetMaximumTextureBufferTexels(10000);
  ren->SetPass(pass);
  Output->SetEcho(false);
  win->Render();
  Output->SetEcho(true);
  Check(Output->HasErrorContaining("more than the limit"), "too large: a clear error message");
  Output->Clear();
  // Nothing is lost: raster draws what could not be traced, and nothing
  // counts as traced.
  Check(Difference(Grab(win), raster) == 0.0, "too large: raster draws the mesh instead");
  Check(pass->GetNumberOfTracedProps() == 0 && pass->GetLastTracedPrimitives() == 0 &&
      pass->GetLastTracedInstances() == 0,
    "too large: nothing counted as traced");
  NoGLError(win, "too large");
  // The same frame again: no repeated error, still raster.
  win->Render();
  Check(Output->GetNumberOfErrors() == 0, "too large: the error is not repeated every frame");
  Check(Difference(Grab(win), raster) == 0.0 && pass->GetLastTracedPrimitives() == 0,
    "too large: still raster");
  // The limit lifted, the same pass traces (nothing changed but the limit).
  pass->SetMaximumTextureBufferTexels(0);
  win->Render();
  Check(CountForegroundPixels(Grab(win), background) > 0 && pass->GetNumberOfTracedProps() == 1 &&
      pass->GetLastTracedPrimitives() > 0,
    "limit lifted: the scene is traced");
  NoVTKOutput("too large");
}

/// Pixels inside `one`'s objects (the pixel and its eight neighbors not
/// black) whose color in `other` differs by more than `tolerance`: a
/// sampled image keeps every such pixel, only silhouettes soften.
long CountInteriorPixelsChanged(vtkImageData* one, vtkImageData* other, int tolerance)
{
  int dims[3];
  one->GetDimensions(dims);
  const int comps = one->GetNumberOfScalarComponents();
  const auto* a = static_cast<const unsigned char*>(one->GetScalarPointer());
  const auto* b = static_cast<const unsigned char*>(other->GetScalarPointer());
  auto lit = [&](int x, int y) {
    const unsigned char* p = a + (static_cast<long>(y) * dims[0] + x) * comps;
    return p[0] + p[1] + p[2] > 0;
  };
  long changed = 0;
  for (int y = 1; y + 1 < dims[1]; ++y)
  {
    for (int x = 1; x + 1 < dims[0]; ++x)
    {
      bool interior = true;
      for (int k = 0; k < 9; ++k)
      {
        interior = interior && lit(x + k % 3 - 1, y + k / 3 - 1);
      }
      const long at = (static_cast<long>(y) * dims[0] + x) * comps;
      for (int c = 0; interior && c < 3; ++c)
      {
        if (std::abs(int(a[at + c]) - int(b[at + c])) > tolerance)
        {
          ++changed;
          break;
        }
      }
    }
  }
  return changed;
}
} // namespace

/// The pass traces only the pixels around its instances' projected boxes:
/// cameras that make that rectangle tricky (a box reaching behind the eye,
/// objects cut by the viewport's edges, a renderer in part of the window)
/// still give raster's picture.
void TestFootprint()
{
  auto win = MakeWindow(160, 120);
  vtkNew<vtkRenderer> ren;
  ren->SetViewport(0.1, 0.2, 0.9, 1.0);
  win->AddRenderer(ren);
  ren->AddActor(SphereActor(0, 0, 0, 1.0, 48));
  ren->AddActor(SphereActor(2.5, 0.5, -1.0, 0.7, 48));
  ren->ResetCamera();
  auto compare = [&](const std::string& what) {
    ren->ResetCameraClippingRange();
    ren->SetPass(nullptr);
    win->Render();
    auto raster = Grab(win);
    vtkNew<vtkRayTracePass> pass;
    ren->SetPass(pass);
    win->Render();
    auto traced = Grab(win);
    const long off = CountDifferingPixels(raster, traced, 48);
    Check(off <= 40, "footprint, " + what + ": " + std::to_string(off) + " pixels off raster");
    // Sub-pixel samples, traced into the accumulation buffer within the
    // same footprint, keep every pixel of the objects.
    vtkNew<vtkRayTracePass> sampled;
    sampled->SetSamplesPerPixel(4);
    ren->SetPass(sampled);
    win->Render();
    auto soft = Grab(win);
    const long lost = CountInteriorPixelsChanged(traced, soft, 48);
    const long kept = CountDifferingPixels(raster, soft, 128);
    Check(lost == 0 && kept <= 80,
      "footprint, sampled, " + what + ": " + std::to_string(lost) + " object pixels changed, " +
        std::to_string(kept) + " pixels far off raster");
  };
  compare("whole scene in view");
  ren->GetActiveCamera()->Zoom(3.0);
  ren->GetActiveCamera()->Azimuth(20);
  compare("objects cut by the viewport's edges");
  ren->GetActiveCamera()->SetPosition(0.2, 0.1, 0.3); // inside the first sphere's box
  ren->GetActiveCamera()->SetFocalPoint(2.5, 0.5, -1.0);
  compare("a box reaching behind the eye");
  NoVTKOutput("footprint");
}

/// Renders with rays over the whole footprint rectangle, then over its
/// tiles: the same image bit for bit, from `expect` pixels ("fewer": under
/// three quarters of the rectangle's, "no more", or "same").
void CompareTilesWithRectangle(vtkRenderWindow* win, vtkRenderer* ren, vtkRayTracePass* pass,
  const std::string& what, const std::string& expect)
{
  ren->ResetCameraClippingRange();
  setenv("VTKRT_FOOTPRINT_TILES", "0", 1);
  win->Render();
  auto whole = Grab(win);
  const vtkTypeInt64 wholePixels = pass->GetLastTracedPixels();
  unsetenv("VTKRT_FOOTPRINT_TILES");
  win->Render();
  auto tiled = Grab(win);
  const vtkTypeInt64 tiledPixels = pass->GetLastTracedPixels();
  const long off = CountDifferingPixels(whole, tiled, 0);
  if (off != 0)
  {
    // The whole footprint's image stands where raster's does.
    WriteFailedImages("FootprintTiles", whole, tiled);
  }
  Check(off == 0, "footprint tiles, " + what + ": " + std::to_string(off) + " pixels differ from the whole footprint's");
  const bool fewer = 4 * tiledPixels < 3 * wholePixels;
  const bool ok = expect == "fewer" ? fewer : (expect == "same" ? tiledPixels == wholePixels : tiledPixels <= wholePixels);
  Check(tiledPixels > 0 && ok,
    "footprint tiles, " + what + ": " + std::to_string(tiledPixels) + " pixels traced against " +
      std::to_string(wholePixels) + " (expected " + expect + ")");
}

/// Props whose traced primitives the view sizes or that blend: points as
/// spheres 14 pixels wide, a tube 8 pixels wide, a wireframe cube with
/// 4-pixel wires, a translucent ball, and eight small balls (more than
/// eight instances: the top-level walk).
void AddViewSizedAndTranslucentProps(vtkRenderer* ren)
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 6; ++i)
  {
    points->InsertNextPoint(-2.0 + 0.3 * i, 1.2, 0.2 * i);
  }
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < 6; ++i)
  {
    vertices->InsertNextCell(1, &i);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  cloud->SetVerts(vertices);
  auto cloudActor = MeshActor(cloud);
  cloudActor->GetProperty()->RenderPointsAsSpheresOn();
  cloudActor->GetProperty()->SetPointSize(14.0);
  ren->AddActor(cloudActor);
  vtkNew<vtkLineSource> line;
  line->SetPoint1(1.5, 1.3, -0.5);
  line->SetPoint2(2.6, 0.2, 0.4);
  line->Update();
  auto tube = MeshActor(line->GetOutput());
  tube->GetProperty()->RenderLinesAsTubesOn();
  tube->GetProperty()->SetLineWidth(8.0);
  ren->AddActor(tube);
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(-1.8, -1.2, 0.0);
  cube->SetXLength(0.6);
  cube->SetYLength(0.5);
  cube->SetZLength(0.4);
  cube->Update();
  auto wires = MeshActor(cube->GetOutput());
  wires->GetProperty()->SetRepresentationToWireframe();
  wires->GetProperty()->SetLineWidth(4.0);
  ren->AddActor(wires);
  auto glass = SphereActor(0.8, 0.6, 0.5, 0.5, 32);
  glass->GetProperty()->SetOpacity(0.4);
  ren->AddActor(glass);
  for (int i = 0; i < 8; ++i)
  {
    ren->AddActor(SphereActor(-0.6 + 0.25 * i, -1.5 + 0.05 * i, 0.3, 0.06, 12));
  }
}

void TestFootprintTiles()
{
  auto win = MakeWindow(240, 200);
  vtkNew<vtkRenderer> ren;
  ren->SetViewport(0.05, 0.1, 0.95, 1.0);
  win->AddRenderer(ren);
  // A long thin ellipsoid across the view, turned by its matrix, and a
  // small ball in a corner: their rectangle is most of the viewport, their
  // tiles a band and a spot.
  auto rod = SphereActor(0, 0, 0, 1.0, 48);
  rod->SetScale(3.0, 0.25, 0.25);
  rod->RotateZ(35.0);
  rod->RotateX(20.0);
  rod->SetPosition(0.2, 0.1, -0.3);
  ren->AddActor(rod);
  ren->AddActor(SphereActor(2.2, -1.6, 0.3, 0.2, 24));
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(nullptr);
  win->Render();
  auto raster = Grab(win);
  ren->SetPass(pass);
  win->Render();
  const long offRaster = CountDifferingPixels(raster, Grab(win), 48);
  Check(offRaster <= 40, "footprint tiles: " + std::to_string(offRaster) + " pixels off raster");
  CompareTilesWithRectangle(win, ren, pass, "rod and ball", "fewer");
  ren->GetActiveCamera()->Azimuth(50.0);
  ren->GetActiveCamera()->Elevation(30.0);
  ren->GetActiveCamera()->OrthogonalizeViewUp();
  CompareTilesWithRectangle(win, ren, pass, "turned", "fewer");
  ren->GetActiveCamera()->Zoom(4.0);
  CompareTilesWithRectangle(win, ren, pass, "zoomed, cut by the viewport's edges", "no more");
  ren->GetActiveCamera()->SetPosition(0.2, 0.1, -0.3); // inside the rod
  ren->GetActiveCamera()->SetFocalPoint(2.2, -1.6, 0.3);
  CompareTilesWithRectangle(win, ren, pass, "the eye inside the rod", "no more");
  // Inside the rod's box, beside the rod, facing the ball: the box lies
  // across the eye plane, the tiles come from its part in front.
  ren->GetActiveCamera()->SetPosition(1.8, -0.6, 0.3);
  ren->GetActiveCamera()->SetFocalPoint(2.2, -1.6, 0.3);
  ren->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
  ren->GetActiveCamera()->SetViewAngle(30.0); // undo the zoom
  CompareTilesWithRectangle(win, ren, pass, "the eye inside a box, beside the rod", "fewer");
  // A floor of two triangles from behind the eye to far ahead: its box lies
  // across the eye plane, and the floor just past the near plane, at the
  // bottom of the view, is only where the box's edges cross that plane.
  ren->RemoveAllViewProps();
  ren->AddActor(FloorActor(5.0));
  ren->AddActor(SphereActor(0.0, 0.3, -3.0, 0.3, 24));
  ren->GetActiveCamera()->SetPosition(0.0, 0.4, 2.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.2, -3.0);
  ren->GetActiveCamera()->SetViewUp(0.0, 1.0, 0.0);
  CompareTilesWithRectangle(win, ren, pass, "a floor under the eye", "no more");
  AddViewSizedAndTranslucentProps(ren);
  ren->ResetCamera();
  CompareTilesWithRectangle(win, ren, pass, "with view-sized, translucent and many props", "no more");
  Check(pass->GetNumberOfTracedProps() == 14,
    "footprint tiles: " + std::to_string(pass->GetNumberOfTracedProps()) + " props traced of 14");
  ren->GetActiveCamera()->Zoom(1.6);
  ren->GetActiveCamera()->Azimuth(-30.0);
  CompareTilesWithRectangle(win, ren, pass, "with them, zoomed and turned", "no more");
  NoVTKOutput("footprint tiles");
}

/// Renders with a shader feature turned off by its environment variable
/// (`variable`=0), then on: the same image, the second shader the one that
/// #defines `define`. Where a ray meets two triangles at the same t (a shared
/// edge), walks in another order may pick either, whose shading differs in
/// rounding: with `ties`, up to that many pixels may differ, none by more
/// than 16 levels.
void CompareWithFeatureOff(vtkRenderWindow* win, vtkRenderer* ren, vtkRayTracePass* pass,
  const char* variable, const std::string& define, const std::string& what, long ties = 0)
{
  ren->ResetCameraClippingRange();
  const std::string line = "#define " + define + "\n";
  setenv(variable, "0", 1);
  win->Render();
  auto off = Grab(win);
  const bool offShader = std::string(pass->GetLastFragmentShaderSource()).find(line) == std::string::npos;
  unsetenv(variable);
  win->Render();
  auto on = Grab(win);
  const bool onShader = std::string(pass->GetLastFragmentShaderSource()).find(line) != std::string::npos;
  Check(offShader && onShader, what + ": the shaders with and without " + define);
  const long differ = CountDifferingPixels(off, on, 0);
  const long farOff = CountDifferingPixels(off, on, 16);
  if (differ > ties || farOff > 0)
  {
    // The image without the feature stands where raster's does.
    WriteFailedImages(define, off, on);
  }
  Check(differ <= ties && farOff == 0,
    what + ": " + std::to_string(differ) + " pixels differ from the image without " + define + ", " +
      std::to_string(farOff) + " by more than 16 levels");
}

/// Camera rays walking from the tree's root, then from their tile's entries.
void CompareEntriesWithRoot(
  vtkRenderWindow* win, vtkRenderer* ren, vtkRayTracePass* pass, const std::string& what, long ties = 0)
{
  CompareWithFeatureOff(win, ren, pass, "VTKRT_TILE_ENTRIES", "VTKRT_TILE_ENTRIES", "tile entries, " + what, ties);
}

/// One mesh deep enough for tile entries (a fine sphere) and a floor,
/// turned by its matrix (25 degrees about y, then `tiltX` about x), in view
/// from above; returned for its property.
vtkActor* AddSphereOverFloor(vtkRenderer* ren, double tiltX)
{
  auto actor = MeshActor(SphereOverFloor(400, 8));
  actor->RotateY(25.0);
  actor->RotateX(tiltX);
  ren->AddActor(actor);
  ren->GetActiveCamera()->SetPosition(1.0, 3.0, 5.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.5, 0.0);
  ren->ResetCamera();
  return actor;
}

void TestTileEntries()
{
  auto win = MakeWindow(240, 200);
  vtkNew<vtkRenderer> ren;
  ren->SetViewport(0.05, 0.1, 0.95, 1.0);
  win->AddRenderer(ren);
  // The floor's shadows come from rays that are not camera rays, which walk
  // from the root.
  vtkActor* actor = AddSphereOverFloor(ren, 10.0);
  vtkNew<vtkRayTracePass> pass;
  pass->SetShadows(true);
  ren->SetPass(pass);
  CompareEntriesWithRoot(win, ren, pass, "sphere over a floor, shadows");
  ren->GetActiveCamera()->Zoom(3.0);
  CompareEntriesWithRoot(win, ren, pass, "zoomed, cut by the viewport's edges");
  ren->GetActiveCamera()->SetPosition(0.1, 0.9, 0.2); // inside the sphere
  ren->GetActiveCamera()->SetFocalPoint(1.0, 0.2, -1.0);
  CompareEntriesWithRoot(win, ren, pass, "the eye inside the sphere");
  ren->GetActiveCamera()->SetPosition(0.3, 0.15, 2.5); // near the floor, boxes across the eye plane
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.6, 0.0);
  ren->GetActiveCamera()->SetViewAngle(60.0);
  CompareEntriesWithRoot(win, ren, pass, "low over the floor");
  pass->SetSamplesPerPixel(4);
  CompareEntriesWithRoot(win, ren, pass, "four samples a pixel");
  pass->SetSamplesPerPixel(1);
  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetViewAngle(30.0);
  camera->ParallelProjectionOn();
  ren->ResetCamera();
  camera->Roll(30.0);
  CompareEntriesWithRoot(win, ren, pass, "parallel projection, rolled");
  camera->ParallelProjectionOff();
  for (int view = 0; view < 4; ++view)
  {
    camera->Azimuth(75.0);
    camera->Elevation(view % 2 == 0 ? 35.0 : -50.0);
    camera->OrthogonalizeViewUp();
    ren->ResetCamera();
    camera->Zoom(1.0 + 0.6 * view);
    CompareEntriesWithRoot(win, ren, pass, "orbit view " + std::to_string(view));
  }
  // Shadows of a side light through translucent surfaces: rays that leave
  // the pixel's tile.
  vtkNew<vtkLight> side;
  side->SetPosition(-6.0, 2.0, 1.0);
  side->SetFocalPoint(0.0, 0.5, 0.0);
  ren->AddLight(side);
  actor->GetProperty()->SetOpacity(0.5);
  CompareEntriesWithRoot(win, ren, pass, "translucent, a side light's shadows", 20);
  NoVTKOutput("tile entries");
}

void TestLeafTrees()
{
  auto win = MakeWindow(200, 160);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  // A floor and a tilted card over it, two triangles each (one-leaf trees),
  // the card's shadow on the floor, and a full-view textured quad.
  ren->AddActor(FloorActor(2.0));
  vtkNew<vtkPlaneSource> card;
  card->SetOrigin(-0.6, 0.5, -0.3);
  card->SetPoint1(0.7, 0.8, -0.2);
  card->SetPoint2(-0.4, 0.9, 0.6);
  card->Update();
  ren->AddActor(MeshActor(card->GetOutput()));
  ren->GetActiveCamera()->SetPosition(1.5, 3.0, 4.0);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  pass->SetShadows(true);
  ren->SetPass(pass);
  CompareWithFeatureOff(win, ren, pass, "VTKRT_LEAF_TREES", "VTKRT_LEAF_TREES", "one-leaf trees, a card over a floor");
  ren->GetActiveCamera()->Zoom(4.0);
  pass->SetSamplesPerPixel(4);
  CompareWithFeatureOff(win, ren, pass, "VTKRT_LEAF_TREES", "VTKRT_LEAF_TREES", "one-leaf trees, zoomed, four samples");
  // A deeper tree in the scene: its walk is needed, so no one-leaf shader.
  ren->AddActor(SphereActor(0.0, 1.5, 0.0, 0.3, 24));
  win->Render();
  Check(std::string(pass->GetLastFragmentShaderSource()).find("#define VTKRT_LEAF_TREES") == std::string::npos,
    "one-leaf trees: a sphere's tree is walked");
  NoVTKOutput("one-leaf trees");
}

/// Walk stack entries of two words (the largest buffers' shader) against
/// the packed one: every walk the same, so the same image: a deep mesh
/// over a floor with shadows (tile entries), then with points as spheres,
/// a tube, wires, a translucent ball and more than eight instances.
void TestPackedStackEntries()
{
  auto win = MakeWindow(220, 180);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  AddSphereOverFloor(ren, 0.0);
  vtkNew<vtkRayTracePass> pass;
  pass->SetShadows(true);
  ren->SetPass(pass);
  const char* variable = "VTKRT_PACKED_STACK_ENTRIES";
  CompareWithFeatureOff(win, ren, pass, variable, variable, "packed stack entries, sphere over a floor");
  AddViewSizedAndTranslucentProps(ren);
  ren->ResetCamera();
  CompareWithFeatureOff(win, ren, pass, variable, variable, "packed stack entries, spheres, tubes, wires");
  NoVTKOutput("packed stack entries");
}

/// Frame constants as flat inputs (as many as the varying slots hold) or
/// all uniforms: the same values, so the same image, in a shader of one
/// instance (tile entries, shadows, four samples, a spot light, a clip
/// plane, world coordinates) and in the general one.
void TestFlatFrameConstants()
{
  // The slots go to the constants in order; one that does not fit stays a
  // uniform, and a later, smaller one may still fit; unread ones stay uniforms.
  using vtkrt::pass::FrameConstant;
  const std::vector<FrameConstant> constants = { { "vec3", "uA", 3, 1, true }, { "mat4", "uB", 0, 4, true },
    { "vec4", "uC", 0, 1, true }, { "vec3", "uD", 2, 1, false } };
  const vtkrt::pass::FrameConstantShaders four = vtkrt::pass::DeclareFrameConstants(constants, 4);
  const auto declares = [&four](const std::string& line) {
    return four.FragmentDeclarations.find(line + "\n") != std::string::npos;
  };
  Check(four.FlatConstants == 2 && declares("flat in vec3 vtkrtFrame_uA[3];") &&
      declares("#define uA vtkrtFrame_uA") && declares("uniform mat4 uB;") && declares("flat in vec4 vtkrtFrame_uC;") &&
      declares("uniform vec3 uD[2];") && four.Vertex.find("vtkrtFrame_uC = uC;") != std::string::npos &&
      four.Vertex.find("uB") == std::string::npos,
    "frame constants in four slots: uA and uC flat, uB and uD uniforms");
  const vtkrt::pass::FrameConstantShaders none = vtkrt::pass::DeclareFrameConstants(constants, 0);
  Check(none.FlatConstants == 0 && none.FragmentDeclarations.find("\nflat in ") == std::string::npos &&
      none.FragmentDeclarations.find("\nuniform mat4 uB;\n") != std::string::npos,
    "frame constants in no slots: all uniforms");

  auto win = MakeWindow(220, 180);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkActor* actor = AddSphereOverFloor(ren, 0.0);
  vtkNew<vtkRayTracePass> pass;
  pass->SetShadows(true);
  ren->SetPass(pass);
  const char* variable = "VTKRT_FLAT_FRAME_CONSTANTS";
  const std::string define = "uInstance vtkrtFrame_uInstance";
  CompareWithFeatureOff(win, ren, pass, variable, define, "flat frame constants, sphere over a floor");
  pass->SetSamplesPerPixel(4);
  pass->SetPrecisionModeToWorld();
  vtkNew<vtkLight> spot;
  spot->SetPosition(-3.0, 4.0, 2.0);
  spot->SetFocalPoint(0.0, 0.5, 0.0);
  spot->SetPositional(true);
  spot->SetConeAngle(25.0);
  ren->AddLight(spot);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0.0, 0.0, 0.2);
  plane->SetNormal(0.0, 0.0, -1.0);
  actor->GetMapper()->AddClippingPlane(plane);
  CompareWithFeatureOff(win, ren, pass, variable, define,
    "flat frame constants, four samples, a spot light, a clip plane, world coordinates");
  // More lights than the slots hold (five vec3 a positional light): the
  // lights stay uniforms beside flat rays and record.
  for (int i = 0; i < 8; ++i)
  {
    vtkNew<vtkLight> light;
    light->SetPosition(-4.0 + i, 3.0, 2.0 - 0.5 * i);
    light->SetFocalPoint(0.0, 0.5, 0.0);
    light->SetPositional(true);
    light->SetConeAngle(40.0 + 5.0 * i);
    light->SetIntensity(0.2);
    ren->AddLight(light);
  }
  CompareWithFeatureOff(win, ren, pass, variable, define, "flat frame constants, ten lights as uniforms");
  Check(std::string(pass->GetLastFragmentShaderSource()).find("\nuniform vec3 uLightPosition[10];\n") !=
      std::string::npos,
    "flat frame constants: ten positional lights are uniforms");
  AddViewSizedAndTranslucentProps(ren);
  ren->ResetCamera();
  CompareWithFeatureOff(win, ren, pass, variable, "uRayDepth vtkrtFrame_uRayDepth",
    "flat frame constants, the general shader: spheres, tubes, wires, translucency");
  NoVTKOutput("flat frame constants");
}

/// A camera whose view up ends parallel to its direction of projection
/// (Pitch 90, then Azimuth and Elevation, not orthogonalized): its view
/// transform collapses the scene onto a line, and raster draws nothing; so
/// does the pass (it drew a few pixels at depth 0, a user trial).
void TestCollapsedView()
{
  auto win = MakeWindow(300, 300);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(MeshActor(ReadPolyData("bunny.vtp")));
  ren->AddActor(SphereActor(0.05, 0.15, 0.0, 0.03, 32));
  ren->ResetCamera();
  win->Render();
  vtkCamera* cam = ren->GetActiveCamera();
  for (int step = 0; step < 3; ++step)
  {
    step == 0 ? cam->Pitch(90) : step == 1 ? cam->Azimuth(30) : cam->Elevation(-20);
    ren->ResetCameraClippingRange();
    win->Render();
  }
  RasterAndTraced frames = RenderRasterThenTraced(win, ren);
  vtkNew<vtkFloatArray> z;
  win->GetZbufferData(0, 0, 299, 299, z);
  long nearer = 0;
  for (vtkIdType i = 0; i < z->GetNumberOfValues(); ++i)
  {
    nearer += z->GetValue(i) < 1.0f;
  }
  const long differing = CountDifferingPixels(frames.Raster, frames.Traced, 0);
  std::ostringstream s;
  s << "collapsed view: " << differing << " pixels differ from raster's (0), " << nearer
    << " pixels of depth under 1 (0), " << frames.Pass->GetNumberOfTracedProps() << " props traced (0)";
  Check(differing == 0 && nearer == 0 && frames.Pass->GetNumberOfTracedProps() == 0, s.str());
  NoVTKOutput("collapsed view");
}

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "FarFromOrigin", TestFarFromOrigin },
    { "Degenerate", TestDegenerate },
    { "TooLarge", TestTooLarge },
    { "Footprint", TestFootprint },
    { "FootprintTiles", TestFootprintTiles },
    { "TileEntries", TestTileEntries },
    { "LeafTrees", TestLeafTrees },
    { "PackedStackEntries", TestPackedStackEntries },
    { "FlatFrameConstants", TestFlatFrameConstants },
    { "CollapsedView", TestCollapsedView },
  };
  return RunCase(argc, argv, cases);
}
