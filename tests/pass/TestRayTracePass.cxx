// Image tests of vtkRayTracePass: each case renders a scene with VTK's
// raster, then with the pass, and asserts (1) the ray-traced image is close
// to raster (vtkImageDifference's thresholded error, summed over the image:
// "about this many wholly wrong pixels"; differences come from silhouettes
// without antialiasing and the rasterizer's coverage rules, never from
// shading), and (2) it matches its baseline under data/baselines/.
// TestRayTracePass <Case>.
#include "vtkrtDepthComparison.h"
#include "vtkrtImageRegression.h"
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkRayTraceRecords.h"
#include "vtkrt/core/GpuKernels.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLightKit.h"
#include "vtkLookupTable.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderer.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkCellData.h"
#include "vtkColor.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkConeSource.h"
#include "vtkCubeSource.h"
#include "vtkOutlineSource.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkPlane.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
/// Renders `setup`'s scene with raster, then with the pass; checks both.
void CompareWithRaster(const std::string& name, const std::function<void(vtkRenderer*)>& setup,
  double rasterThreshold, int width = 300, int height = 300)
{
  auto win = MakeWindow(width, height);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  setup(ren);
  auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
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
// Several actors with transforms (translation, rotation, non-uniform and
// mirroring scale), one flat shaded; four share one polydata, which is
// stored (and built) once: two-level BVH instances.
void TestActors()
{
  CompareWithRaster("Actors",
    [](vtkRenderer* ren) {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetThetaResolution(48);
      sphere->SetPhiResolution(24);
      sphere->Update();
      vtkSmartPointer<vtkPolyData> shared = sphere->GetOutput();
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(shared);
      vtkNew<vtkPolyDataMapper> mapper2;
      mapper2->SetInputData(shared);
      const double colors[4][3] = { { 1, 0.3, 0.3 }, { 0.3, 1, 0.3 }, { 0.3, 0.3, 1 }, { 1, 1, 0.3 } };
      for (int i = 0; i < 4; ++i)
      {
        vtkNew<vtkActor> actor;
        actor->SetMapper(i == 3 ? mapper2.Get() : mapper.Get());
        actor->GetProperty()->SetColor(colors[i][0], colors[i][1], colors[i][2]);
        actor->GetProperty()->SetSpecular(0.5);
        actor->GetProperty()->SetSpecularPower(40);
        actor->SetPosition(1.2 * (i % 2), 1.2 * (i / 2), 0.1 * i);
        actor->RotateZ(25.0 * i);
        actor->SetScale(1.0 + 0.3 * i, 1.0, i == 2 ? -0.6 : 0.8);
        if (i == 1)
        {
          actor->GetProperty()->SetInterpolationToFlat(); // faceted despite its normals
        }
        ren->AddActor(actor);
      }
      vtkNew<vtkConeSource> cone;
      cone->SetResolution(40);
      vtkNew<vtkPolyDataMapper> coneMapper;
      coneMapper->SetInputConnection(cone->GetOutputPort());
      vtkNew<vtkActor> coneActor;
      coneActor->SetMapper(coneMapper);
      coneActor->SetPosition(0.6, 0.6, 0.8);
      coneActor->RotateY(-60);
      coneActor->GetProperty()->SetColor(0.8, 0.8, 0.8);
      ren->AddActor(coneActor);
      ren->SetBackground(0.2, 0.2, 0.2);
      ren->ResetCamera();
      ren->GetActiveCamera()->Elevation(20);
      ren->ResetCameraClippingRange();
    },
    40.0);
}

// Point scalars (elevation) and cell scalars through lookup tables.
void TestScalars()
{
  CompareWithRaster("Scalars",
    [](vtkRenderer* ren) {
      vtkNew<vtkElevationFilter> elevation;
      elevation->SetInputData(ReadPolyData("bunny.vtp"));
      elevation->SetLowPoint(0, -0.1, 0);
      elevation->SetHighPoint(0, 0.2, 0);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(elevation->GetOutputPort());
      mapper->SetScalarRange(0.2, 0.8);
      vtkNew<vtkActor> bunny;
      bunny->SetMapper(mapper);
      ren->AddActor(bunny);

      vtkNew<vtkSphereSource> sphere;
      sphere->SetRadius(0.05);
      sphere->SetCenter(0.1, 0.15, 0.0);
      sphere->SetThetaResolution(12);
      sphere->SetPhiResolution(8);
      sphere->Update();
      auto poly = vtkSmartPointer<vtkPolyData>::New();
      poly->ShallowCopy(sphere->GetOutput());
      vtkNew<vtkFloatArray> cellValues;
      cellValues->SetName("cellValue");
      for (vtkIdType i = 0; i < poly->GetNumberOfCells(); ++i)
      {
        cellValues->InsertNextValue(static_cast<float>(i % 7));
      }
      poly->GetCellData()->SetScalars(cellValues);
      poly->GetPointData()->SetScalars(nullptr);
      vtkNew<vtkLookupTable> lut;
      lut->SetHueRange(0.0, 0.8);
      lut->Build();
      vtkNew<vtkPolyDataMapper> cellMapper;
      cellMapper->SetInputData(poly);
      cellMapper->SetScalarModeToUseCellData();
      cellMapper->SetLookupTable(lut);
      cellMapper->SetScalarRange(0, 6);
      vtkNew<vtkActor> cells;
      cells->SetMapper(cellMapper);
      ren->AddActor(cells);
      ren->SetBackground(0.1, 0.1, 0.15);
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(-20);
      ren->ResetCameraClippingRange();
    },
    40.0);
}

// Parallel projection of the mesh and the sphere glyphs.
void TestParallel()
{
  CompareWithRaster("Parallel",
    [](vtkRenderer* ren) {
      ren->AddActor(BunnyActor());
      ren->AddActor(SphereGlyphActor());
      ren->SetBackground(0.3, 0.3, 0.3);
      ren->GetActiveCamera()->ParallelProjectionOn();
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(60);
      ren->GetActiveCamera()->Elevation(-10);
      ren->ResetCameraClippingRange();
    },
    40.0, 320, 240);
}

// A parallel projection looking exactly along an axis (VTK's view buttons,
// 2D data): every camera ray is parallel to two axes, which the box tests
// decide by the ray's origin. Compared with raster pixel by pixel (no
// baseline): at most 0.5% of the pixels differ by more than 40 levels.
void TestParallelAlongAxes()
{
  const double views[][6] = { { 0, 0, 1, 0, 1, 0 }, { 1, 0, 0, 0, 1, 0 }, { 0, -1, 0, 0, 0, 1 } };
  for (const double* v : views)
  {
    auto win = MakeWindow(320, 240);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    ren->AddActor(BunnyActor());
    vtkCamera* camera = ren->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(v[0], v[1], v[2]);
    camera->SetViewUp(v[3], v[4], v[5]);
    ren->ResetCamera();
    auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
    const long differing = CountDifferingPixels(traced, raster, 40);
    const long covered = CountForegroundPixels(traced, ren->GetBackground());
    std::ostringstream s;
    s << "parallel view from (" << v[0] << ", " << v[1] << ", " << v[2] << "): " << covered
      << " foreground pixels, " << differing << " differ from raster by > 40 (<= 0.5%)";
    Check(covered > 320 * 240 / 20 && differing <= 320 * 240 / 200, s.str());
    if (differing > 320 * 240 / 200)
    {
      WriteFailedImages("pass_ParallelAlongAxes", raster, traced);
    }
  }
  NoVTKOutput("ParallelAlongAxes");
}

// A camera model transform (vtkCamera::SetModelTransformMatrix: a rotation
// and a uniform scale), with VTK's headlight, a light kit and a positional
// spot light: raster lights in view coordinates through it, and so does the
// pass. Compared
// with raster pixel by pixel: at most 0.5% differ by more than 40 levels.
void TestCameraModelTransform()
{
  const char* names[] = { "headlight", "light kit", "positional spot light" };
  for (int lights = 0; lights < 6; ++lights) // then each with a user view transform instead
  {
    const bool userView = lights >= 3;
    auto win = MakeWindow(320, 240);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    ren->AddActor(BunnyActor());
    if (lights % 3 == 1)
    {
      vtkNew<vtkLightKit> kit;
      kit->AddLightsToRenderer(ren);
    }
    else if (lights % 3 == 2)
    {
      vtkNew<vtkLight> spot;
      spot->SetLightTypeToSceneLight();
      spot->SetPositional(true);
      spot->SetPosition(0.1, 0.3, 0.3);
      spot->SetFocalPoint(-0.02, 0.1, 0.0);
      spot->SetConeAngle(25.0);
      ren->AddLight(spot);
    }
    ren->ResetCamera();
    vtkNew<vtkTransform> model;
    model->RotateY(30.0);
    model->RotateX(-20.0);
    model->Scale(1.5, 1.5, 1.5);
    vtkNew<vtkTransform> view;
    view->RotateY(15.0);
    view->RotateX(-10.0);
    view->Translate(0.01, 0.0, 0.0);
    if (userView)
    {
      ren->GetActiveCamera()->SetUserViewTransform(view);
    }
    else
    {
      ren->GetActiveCamera()->SetModelTransformMatrix(model->GetMatrix());
    }
    auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
    const long differing = CountDifferingPixels(traced, raster, 40);
    const long covered = CountForegroundPixels(traced, ren->GetBackground());
    std::ostringstream s;
    s << (userView ? "camera user view transform, " : "camera model transform, ") << names[lights % 3] << ": " << covered
      << " foreground pixels, " << differing << " differ from raster by > 40 (<= 0.5%)";
    Check(covered > 320 * 240 / 20 && differing <= 320 * 240 / 200, s.str());
    if (differing > 320 * 240 / 200)
    {
      WriteFailedImages("pass_CameraModelTransform" + std::to_string(lights), raster, traced);
    }
  }
  NoVTKOutput("CameraModelTransform");
}

// Mapper clipping planes on a mesh (two planes) and on the glyphs.
void TestClipPlanes()
{
  CompareWithRaster("ClipPlanes",
    [](vtkRenderer* ren) {
      auto bunny = BunnyActor();
      vtkNew<vtkPlane> plane;
      plane->SetOrigin(-0.02, 0.1, 0.0);
      plane->SetNormal(1.0, 0.3, 0.2);
      bunny->GetMapper()->AddClippingPlane(plane);
      vtkNew<vtkPlane> plane2;
      plane2->SetOrigin(0.0, 0.16, 0.0);
      plane2->SetNormal(0.0, -1.0, 0.0);
      bunny->GetMapper()->AddClippingPlane(plane2);
      bunny->GetProperty()->SetBackfaceCulling(false);
      ren->AddActor(bunny);
      auto glyphs = SphereGlyphActor();
      vtkNew<vtkPlane> plane3;
      plane3->SetOrigin(0.0, 0.0, 0.0);
      plane3->SetNormal(0.0, 0.0, 1.0);
      glyphs->GetMapper()->AddClippingPlane(plane3);
      ren->AddActor(glyphs);
      ren->SetBackground(0.1, 0.2, 0.3);
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(40);
      ren->ResetCameraClippingRange();
    },
    40.0);
}

// Three scene lights (VTK's positional lighting path): a colored
// directional light, a positional spot light, a camera light.
void TestLights()
{
  CompareWithRaster("Lights",
    [](vtkRenderer* ren) {
      ren->AddActor(BunnyActor());
      ren->AddActor(SphereGlyphActor());
      ren->SetBackground(0.05, 0.05, 0.05);
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(20);
      ren->ResetCameraClippingRange();
      vtkNew<vtkLight> directional;
      directional->SetLightTypeToSceneLight();
      directional->SetPosition(1, 1, 1);
      directional->SetFocalPoint(0, 0, 0);
      directional->SetColor(1.0, 0.6, 0.6);
      directional->SetIntensity(0.8);
      ren->AddLight(directional);
      vtkNew<vtkLight> spot;
      spot->SetLightTypeToSceneLight();
      spot->PositionalOn();
      spot->SetPosition(-0.1, 0.4, 0.3);
      spot->SetFocalPoint(0.0, 0.1, 0.0);
      spot->SetConeAngle(25);
      spot->SetExponent(2);
      spot->SetColor(0.5, 0.7, 1.0);
      ren->AddLight(spot);
      vtkNew<vtkLight> cameraLight;
      cameraLight->SetLightTypeToCameraLight();
      cameraLight->SetPosition(-1, 0, 1);
      cameraLight->SetFocalPoint(0, 0, 0);
      cameraLight->SetIntensity(0.4);
      ren->AddLight(cameraLight);
    },
    40.0);
}

// Props the pass does not trace (translucent, text) are drawn by the raster
// delegate and composite with the traced image (a mesh and a wireframe) by
// depth.
void TestFallback()
{
  CompareWithRaster("Fallback",
    [](vtkRenderer* ren) {
      ren->AddActor(BunnyActor());
      vtkNew<vtkSphereSource> sphere;
      sphere->SetCenter(0.0, 0.1, 0.0);
      sphere->SetRadius(0.06);
      sphere->SetThetaResolution(32);
      sphere->SetPhiResolution(16);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(sphere->GetOutputPort());
      vtkNew<vtkActor> wire;
      wire->SetMapper(mapper);
      wire->GetProperty()->SetRepresentationToWireframe();
      wire->GetProperty()->SetColor(1, 1, 0);
      wire->SetPosition(-0.08, 0.0, 0.0);
      ren->AddActor(wire);
      vtkNew<vtkActor> glass;
      glass->SetMapper(mapper);
      glass->GetProperty()->SetOpacity(0.4);
      glass->GetProperty()->SetColor(0.3, 0.6, 1.0);
      glass->SetPosition(0.05, -0.02, 0.02);
      ren->AddActor(glass);
      vtkNew<vtkTextActor> text;
      text->SetInput("vtkrt");
      text->GetTextProperty()->SetFontSize(24);
      text->SetDisplayPosition(10, 10);
      ren->AddActor2D(text);
      ren->SetBackground(0.1, 0.2, 0.3);
      ren->ResetCamera();
      ren->GetActiveCamera()->Azimuth(30);
      ren->ResetCameraClippingRange();
    },
    40.0);
}
// vtkCompositePolyDataMapper2 over a multiblock of meshes (one without
// normals; block colors, one inherited; a hidden block), over a gradient
// background.
void TestComposite()
{
  CompareWithRaster("Composite",
    [](vtkRenderer* ren) {
      vtkNew<vtkMultiBlockDataSet> blocks;
      blocks->SetNumberOfBlocks(3);
      for (int i = 0; i < 3; ++i)
      {
        vtkNew<vtkSphereSource> sphere;
        sphere->SetCenter(1.1 * i, 0.2 * i, 0.0);
        sphere->SetRadius(0.5);
        sphere->SetThetaResolution(16 + 8 * i);
        sphere->SetPhiResolution(12 + 4 * i);
        sphere->Update();
        vtkNew<vtkPolyData> poly;
        poly->DeepCopy(sphere->GetOutput());
        if (i == 1)
        {
          poly->GetPointData()->SetNormals(nullptr);
        }
        blocks->SetBlock(i, poly);
      }
      // A nested multiblock: its color is inherited by its two leaves, one
      // of which is hidden.
      vtkNew<vtkMultiBlockDataSet> nested;
      nested->SetNumberOfBlocks(2);
      for (int i = 0; i < 2; ++i)
      {
        vtkNew<vtkSphereSource> sphere;
        sphere->SetCenter(0.6 + 1.2 * i, 1.1, 0.2);
        sphere->SetRadius(0.35);
        sphere->SetThetaResolution(24);
        sphere->SetPhiResolution(16);
        sphere->Update();
        vtkNew<vtkPolyData> poly;
        poly->DeepCopy(sphere->GetOutput());
        nested->SetBlock(i, poly);
      }
      blocks->SetNumberOfBlocks(4);
      blocks->SetBlock(3, nested);
      vtkNew<vtkCompositePolyDataMapper2> mapper;
      mapper->SetInputDataObject(blocks);
      vtkNew<vtkCompositeDataDisplayAttributes> attributes;
      attributes->SetBlockColor(nested, vtkColor3d(1.0, 0.4, 0.2).GetData());
      attributes->SetBlockVisibility(nested->GetBlock(1), false);
      attributes->SetBlockColor(blocks->GetBlock(0), vtkColor3d(0.9, 0.9, 0.3).GetData());
      mapper->SetCompositeDataDisplayAttributes(attributes);
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetColor(0.4, 0.8, 0.9);
      actor->GetProperty()->SetSpecular(0.3);
      ren->AddActor(actor);
      ren->SetBackground(0.15, 0.15, 0.15);
      ren->SetBackground2(0.4, 0.4, 0.6);
      ren->GradientBackgroundOn();
      ren->ResetCamera();
      ren->GetActiveCamera()->Elevation(30);
      ren->ResetCameraClippingRange();
    },
    40.0);
}

// Points of a mesh drawn with RenderPointsAsSpheres: analytic spheres.
void TestPointsAsSpheres()
{
  CompareWithRaster("PointsAsSpheres",
    [](vtkRenderer* ren) {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetThetaResolution(12);
      sphere->SetPhiResolution(8);
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputConnection(sphere->GetOutputPort());
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->GetProperty()->SetRepresentationToPoints();
      actor->GetProperty()->RenderPointsAsSpheresOn();
      actor->GetProperty()->SetPointSize(12);
      actor->GetProperty()->SetColor(1.0, 0.5, 0.2);
      ren->AddActor(actor);
      ren->SetBackground(0.1, 0.1, 0.2);
      ren->ResetCamera();
      ren->GetActiveCamera()->Elevation(20);
      ren->ResetCameraClippingRange();
    },
    60.0);
}

// Raster lines lying on a traced mesh (the outline vtkInteractorStyle draws
// around a picked prop, a wireframe over a surface) pass the depth test as
// over raster's own triangles: the traced depth of a mesh is never in front
// of the exact depth of its triangles and stays within a few 24-bit steps
// behind it (the pass's bias), and the outline around a traced cube shows at
// least as much as over raster's. Raster's own depth is printed beside, not
// checked: drivers differ (NVIDIA's lay tens of steps behind the exact depth).
void TestCoincidentLines()
{
  const double kDepthTolerance = 32.0 / 16777216.0;
  constexpr int w = 300;
  constexpr int h = 200;
  for (const double azimuth : { 0.0, 30.0 })
  {
    auto win = MakeWindow(w, h);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    vtkNew<vtkCubeSource> cube;
    cube->SetCenter(2.5, 0.3, 0.0);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(cube->GetOutputPort());
    vtkNew<vtkActor> surface;
    surface->SetMapper(mapper);
    ren->AddActor(surface);
    vtkSmartPointer<vtkActor> ball = SphereActor(0.0, 0.0, 0.0, 0.5, 64);
    ren->AddActor(ball);
    ren->ResetCamera(-3.0, 3.0, -2.0, 2.0, -0.5, 0.5);
    ren->GetActiveCamera()->Azimuth(azimuth);
    ren->GetActiveCamera()->Elevation(azimuth * 0.5);
    ren->GetActiveCamera()->OrthogonalizeViewUp();
    ren->ResetCameraClippingRange();
    std::vector<float> rasterDepth(w * h), tracedDepth(w * h);
    win->Render();
    win->GetZbufferData(0, 0, w - 1, h - 1, rasterDepth.data());
    vtkNew<vtkRayTracePass> pass;
    ren->SetPass(pass);
    win->Render();
    win->GetZbufferData(0, 0, w - 1, h - 1, tracedDepth.data());
    const std::vector<double> exactDepth = ExactWindowDepths(ren, w, h, { surface, ball });
    const DepthComparison depth = CompareDepth(exactDepth, tracedDepth, w, h);
    std::cout << "azimuth " << azimuth << ", raster's depth against the exact depth: "
              << DescribeDepth(CompareDepth(exactDepth, rasterDepth, w, h)) << "\n";
    std::ostringstream what;
    what << "azimuth " << azimuth << ": traced depth at or behind the exact depth, within "
         << kDepthTolerance << ": " << DescribeDepth(depth);
    Check(pass->GetNumberOfTracedProps() == 2 && depth.Pixels > 1000 && depth.InFront == 0 &&
        depth.Largest < kDepthTolerance,
      what.str());

    // VTK's pick outline (vtkInteractorStyle::HighlightProp3D) around the cube.
    vtkNew<vtkOutlineSource> box;
    box->SetBounds(surface->GetBounds());
    vtkNew<vtkPolyDataMapper> boxMapper;
    boxMapper->SetInputConnection(box->GetOutputPort());
    vtkNew<vtkActor> outline;
    outline->SetMapper(boxMapper);
    outline->GetProperty()->SetColor(1.0, 0.0, 0.0);
    outline->GetProperty()->SetAmbient(1.0);
    outline->GetProperty()->SetDiffuse(0.0);
    ren->AddActor(outline);
    const unsigned char red[3] = { 255, 0, 0 };
    win->Render();
    const long traced = CountColor(Grab(win), red);
    ren->SetPass(nullptr);
    win->Render();
    const long raster = CountColor(Grab(win), red);
    std::ostringstream shown;
    shown << "azimuth " << azimuth << ": the outline shows over the traced cube (" << traced
          << " pixels) at least as over raster's (" << raster << ")";
    Check(raster > 20 && traced >= raster, shown.str());
  }
  NoVTKOutput("CoincidentLines");
}

// The camera rays of VTK's cameras are affine in the pixel ("p0" in the
// feature key: the shader takes them from three uniforms each): a
// perspective camera, an off-axis one (window center) and a parallel one,
// whose affine rays equal the unprojected ones at random points (camera-
// relative and world coordinates), and whose depth along a ray (the
// shader's affineRayDepth, in float) is the point's projection, also for a
// clipping range of 1e6. An explicit projective matrix (a
// keystone: clip w grows with x) is not affine ("p1": the shader unprojects
// each pixel). Each image against raster's, blurred (silhouettes).
void TestCameraRays()
{
  auto win = MakeWindow(320, 240);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(BunnyActor());
  ren->AddActor(SphereGlyphActor());
  ren->SetBackground(0.3, 0.3, 0.3);
  vtkCamera* cam = ren->GetActiveCamera();
  ren->ResetCamera();
  cam->Azimuth(30);
  cam->Elevation(15);
  ren->ResetCameraClippingRange();
  const auto raysMatch = [&](const std::string& label, bool world) {
    vtkrt::pass::CameraFrame frame;
    frame.Set(vtkOpenGLRenderer::SafeDownCast(ren), vtkOpenGLCamera::SafeDownCast(cam), world, 1.0);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> ndc(-1.0, 1.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::vec4 rayDepth(static_cast<float>(frame.RayDepth[0]), static_cast<float>(frame.RayDepth[1]),
      static_cast<float>(frame.RayDepth[2]), static_cast<float>(frame.RayDepth[3]));
    glm::mat4 clipToCamera;
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        clipToCamera[c][r] = static_cast<float>(frame.ClipToCamera->GetElement(r, c));
      }
    }
    double worst = 0.0;
    double worstDepth = 0.0;
    double worstBack = 0.0;
    for (int i = 0; i < 100; ++i)
    {
      const double x = ndc(random), y = ndc(random);
      double org[3], dir[3], o[3], d[3];
      frame.UnprojectRay(x, y, org, dir);
      frame.AffineRay(x, y, o, d);
      for (int k = 0; k < 3; ++k)
      {
        worst = std::max({ worst, std::abs(o[k] - org[k]) / (std::abs(org[k]) + std::abs(dir[k])),
          std::abs(d[k] - dir[k]) / std::abs(vtkMath::Norm(dir)) });
      }
      const float t = static_cast<float>(unit(random));
      double clip[4] = { org[0] + t * dir[0], org[1] + t * dir[1], org[2] + t * dir[2], 1.0 };
      frame.CameraToClip->MultiplyPoint(clip, clip);
      const float depth = vtkrt::core::gpu::affineRayDepth(rayDepth, t);
      worstDepth = std::max(worstDepth, std::abs(depth - clip[2] / clip[3]));
      // A depth back to its t (the depth below a renderer: uDepthBelow), by
      // the affine rays' formula and by unprojecting the point.
      const float affineT = vtkrt::core::gpu::affineRayT(rayDepth, depth);
      const float projectiveT = vtkrt::core::gpu::projectiveRayT(clipToCamera,
        glm::vec2(static_cast<float>(x), static_cast<float>(y)), depth, glm::vec3(o[0], o[1], o[2]),
        glm::vec3(d[0], d[1], d[2]));
      for (const float back : { affineT, projectiveT })
      {
        worstBack =
          std::max(worstBack, static_cast<double>(std::abs(vtkrt::core::gpu::affineRayDepth(rayDepth, back) - depth)));
      }
    }
    std::ostringstream s;
    s << label << (world ? ", world" : ", camera-relative") << ": affine rays equal the unprojected ones "
      << "(worst relative difference " << worst << "), their float depth the projected one (worst "
      << worstDepth << " in normalized device z), a depth's t gives it back (worst " << worstBack << ")";
    // Two steps of a 24-bit depth buffer (window depth is half of it); a
    // depth back from its t within eight, half the margin a camera ray's end
    // at the depth below gets (kCoincidentDepthBias).
    Check(frame.AffineRays && worst <= 1e-12 && worstDepth <= 4.0 / 16777216.0 &&
        worstBack <= 16.0 / 16777216.0,
      s.str());
  };
  const auto compare = [&](const std::string& label, const char* rays) {
    RasterAndTraced frames = CompareBlurred(win, ren, label, 2, 8.0, "CameraRays_" + label);
    const std::string key = frames.Pass->GetLastFeatureKey();
    Check(key.find(rays) != std::string::npos, label + ": rays " + rays + " (key " + key + ")");
    ren->SetPass(nullptr);
    if (std::string(rays) == "p0")
    {
      raysMatch(label, false);
      raysMatch(label, true);
      double range[2];
      cam->GetClippingRange(range);
      cam->SetClippingRange(range[0] * 1e-3, range[0] * 1e3);
      raysMatch(label + ", clipping range 1e6", false);
      cam->SetClippingRange(range);
    }
  };
  compare("perspective", "p0");
  cam->SetWindowCenter(0.3, -0.2);
  compare("off-axis", "p0");
  cam->SetWindowCenter(0.0, 0.0);
  cam->ParallelProjectionOn();
  compare("parallel", "p0");
  cam->ParallelProjectionOff();
  vtkNew<vtkMatrix4x4> keystone;
  keystone->SetElement(3, 0, 0.15);
  vtkNew<vtkMatrix4x4> projection;
  vtkMatrix4x4::Multiply4x4(keystone, cam->GetProjectionTransformMatrix(320.0 / 240.0, -1.0, 1.0), projection);
  cam->SetExplicitProjectionTransformMatrix(projection);
  cam->UseExplicitProjectionTransformMatrixOn();
  compare("keystone", "p1");
  vtkrt::pass::CameraFrame keystoneFrame;
  keystoneFrame.Set(vtkOpenGLRenderer::SafeDownCast(ren), vtkOpenGLCamera::SafeDownCast(cam), false, 1.0);
  Check(!keystoneFrame.AffineRays, "keystone: not affine");
  NoVTKOutput("CameraRays");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Mesh", TestMesh },
    { "Glyphs", TestGlyphs },
    { "Actors", TestActors },
    { "Scalars", TestScalars },
    { "Parallel", TestParallel }, { "ParallelAlongAxes", TestParallelAlongAxes },
    { "CameraModelTransform", TestCameraModelTransform },
    { "ClipPlanes", TestClipPlanes },
    { "Lights", TestLights },
    { "Fallback", TestFallback },
    { "Composite", TestComposite },
    { "PointsAsSpheres", TestPointsAsSpheres },
    { "CoincidentLines", TestCoincidentLines },
    { "CameraRays", TestCameraRays },
  };
  return RunCase(argc, argv, cases);
}
