// vtkRayTracePass behaviour across frames and outside the pass itself:
//   Counters          what a frame builds, uploads and compiles across camera
//                     moves, property/light changes, data and feature changes
//   ManyActors        more than 8 actors: a top-level BVH, rebuilt only when
//                     an actor moves
//   ScalarChange      new scalars keep a mesh's BVH (only colors written);
//                     new normals or points rebuild it
//   IncrementalUpload a small prop changed beside a colored mesh writes only
//                     its own records and colors (appended, then packed anew
//                     when out of room or under a lowered texel limit);
//                     images and picks equal a fresh pass's
//   BorrowedGeometry  a scene of one mesh: on llvmpipe its cached arrays are
//                     the GL buffers' storage (no copy); a second prop, a
//                     new mesh and a new window switch between that and
//                     copies, each image the same as a copying pass's
//   Lifecycle         the pass removed and installed again, its window
//                     destroyed and replaced
//   MovedBetweenWindows one pass moved between two live windows' renderers and
//                     back, then its first window deleted: every frame traced
//                     as by a fresh pass, raster unharmed
//   App <vtkrt-render> vtkrt-render --mode raytrace on the demo and on a file,
//                     against its raster mode
// TestRayTracePassBehavior <Case> [vtkrt-render path].
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkElevationFilter.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPNGReader.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropPicker.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
std::string AppPath;

void TestCounters()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  auto bunnyData = ReadPolyData("bunny.vtp");
  auto bunny = MeshActor(bunnyData);
  auto glyphs = GlyphActor(ReadPolyData("demo-spheres.vtp"));
  ren->AddActor(bunny);
  ren->AddActor(glyphs);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);

  auto frame = [&](const std::string& what, int builds, bool geometry, int compiles) {
    win->Render();
    std::ostringstream s;
    s << what << ": " << pass->GetLastBVHBuilds() << " BVH builds (want " << builds << "), "
      << pass->GetLastGeometryBytesUploaded() << " geometry bytes (want "
      << (geometry ? "> 0" : "0") << "), " << pass->GetLastShaderCompiles()
      << " shader compiles (want " << compiles << "), " << pass->GetLastFrameBytesUploaded()
      << " per-frame bytes, " << pass->GetLastTracedPrimitives() << " primitives traced";
    Check(pass->GetLastBVHBuilds() == builds &&
        (pass->GetLastGeometryBytesUploaded() > 0) == geometry &&
        pass->GetLastShaderCompiles() == compiles,
      s.str());
  };
  frame("first frame", 2, true, 1);
  Check(pass->GetLastTriangulationSeconds() > 0 && pass->GetLastBuildSeconds() > 0 &&
      pass->GetLastPackingSeconds() > 0 && pass->GetLastUploadSeconds() > 0 &&
      pass->GetLastShaderCompileSeconds() > 0 && pass->GetLastExtractionSeconds() >= 0,
    "first frame: every phase took time");
  Check(pass->GetLastTracedPrimitives() ==
      bunnyData->GetNumberOfCells() + ReadPolyData("demo-spheres.vtp")->GetNumberOfPoints(),
    "first frame traces every triangle and sphere");
  Check(pass->GetLastFrameBytesUploaded() > 0 && pass->GetLastFrameBytesUploaded() < 1024,
    "per-frame upload is the two instance records only");
  const std::string twoKinds = pass->GetLastFeatureKey();
  for (int i = 0; i < 3; ++i)
  {
    ren->GetActiveCamera()->Azimuth(25);
    ren->GetActiveCamera()->Elevation(5);
    ren->ResetCameraClippingRange();
    frame("camera move " + std::to_string(i + 1), 0, false, 0);
    Check(pass->GetLastTriangulationSeconds() == 0 && pass->GetLastBuildSeconds() == 0 &&
        pass->GetLastPackingSeconds() == 0 && pass->GetLastShaderCompileSeconds() == 0,
      "camera move: no triangulation, build, packing or compile time");
  }
  ren->GetActiveCamera()->ParallelProjectionOn();
  frame("parallel projection", 0, false, 0);
  ren->GetActiveCamera()->ParallelProjectionOff();
  bunny->GetProperty()->SetColor(0.2, 0.8, 0.3);
  bunny->GetProperty()->SetSpecularPower(5);
  frame("property change", 0, false, 0);
  bunny->SetPosition(0.01, 0.0, 0.0);
  frame("actor moved", 0, false, 0);
  vtkLight* light = vtkLight::SafeDownCast(ren->GetLights()->GetItemAsObject(0));
  light->SetIntensity(0.7);
  frame("light intensity change", 0, false, 0);

  // Data change: the bunny's points move; only its BVH is rebuilt.
  vtkPoints* points = bunnyData->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, p[0] * 1.1, p[1], p[2]);
  }
  points->Modified();
  frame("bunny data change", 1, true, 0);
  frame("unchanged after data change", 0, false, 0);

  // A new feature (a clipping plane) compiles one new program; going back
  // finds the cached one.
  vtkNew<vtkPlane> plane;
  plane->SetNormal(1, 0, 0);
  bunny->GetMapper()->AddClippingPlane(plane);
  frame("clipping plane added", 0, false, 1);
  Check(std::string(pass->GetLastFeatureKey()) != twoKinds, "the feature key names the clip plane");
  bunny->GetMapper()->RemoveAllClippingPlanes();
  frame("clipping plane removed", 0, false, 0);

  // Without spheres the shader has no sphere code at all.
  glyphs->VisibilityOff();
  frame("glyphs hidden", 0, true, 1);
  const std::string source = pass->GetLastFragmentShaderSource();
  Check(source.find("raySphereRoots") == std::string::npos &&
      source.find("traverseTriangles") != std::string::npos,
    "a scene without spheres compiles no sphere code");
  glyphs->VisibilityOn();
  frame("glyphs shown again (their BVH was dropped with them)", 1, true, 0);
  pass->SetBuildQuality(0);
  frame("build quality changed: both BVHs rebuilt", 2, true, 0);
  frame("unchanged after the quality change", 0, false, 0);
  NoGLError(win, "counters");
  NoVTKOutput("counters");
}

/// Checks that `win`'s image equals that of a new pass tracing `ren`'s
/// actors with its camera in `freshWin` (of the same size).
void SameAsFreshPass(vtkRenderWindow* win, vtkRenderer* ren, vtkRenderWindow* freshWin, const std::string& what)
{
  vtkNew<vtkRenderer> freshRen;
  freshRen->SetActiveCamera(ren->GetActiveCamera());
  vtkActorCollection* actors = ren->GetActors();
  actors->InitTraversal();
  while (vtkActor* a = actors->GetNextActor())
  {
    freshRen->AddActor(a);
  }
  vtkNew<vtkRayTracePass> freshPass;
  freshRen->SetPass(freshPass);
  freshWin->AddRenderer(freshRen);
  freshWin->Render();
  auto fresh = Grab(freshWin);
  freshWin->RemoveRenderer(freshRen);
  freshRen->ReleaseGraphicsResources(freshWin);
  const double rmse = RootMeanSquareError(Grab(win), fresh);
  Check(rmse == 0.0, what + ": the image equals a fresh pass's (RGB RMSE " + std::to_string(rmse) + ")");
}

// A small sphere moved beside the bunny and the glyphs, frame after frame:
// only its rebuilt records are written, after what the buffers hold, until
// they run out of room; then everything is packed again. Every frame's
// image equals a fresh pass's in a second window, and a pick on the moved
// sphere finds it.
void TestIncrementalUpload()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  // The bunny and the ball colored by point scalars: the colors are
  // appended as the geometry is.
  auto bunnyData = ReadPolyData("bunny.vtp");
  vtkNew<vtkFloatArray> height;
  height->SetName("height");
  for (vtkIdType i = 0; i < bunnyData->GetNumberOfPoints(); ++i)
  {
    height->InsertNextValue(static_cast<float>(bunnyData->GetPoint(i)[1]));
  }
  bunnyData->GetPointData()->SetScalars(height);
  auto bunny = MeshActor(bunnyData);
  bunny->GetMapper()->ScalarVisibilityOn();
  bunny->GetMapper()->SetScalarRange(height->GetRange());
  auto glyphPoints = ReadPolyData("demo-spheres.vtp");
  auto glyphs = GlyphActor(glyphPoints);
  vtkNew<vtkSphereSource> ballSource;
  ballSource->SetRadius(0.01);
  ballSource->SetThetaResolution(12);
  ballSource->SetPhiResolution(12);
  vtkNew<vtkElevationFilter> ballColors;
  ballColors->SetInputConnection(ballSource->GetOutputPort());
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ballColors->GetOutputPort());
  vtkNew<vtkActor> ball;
  ball->SetMapper(ballMapper);
  ball->GetProperty()->SetColor(0.2, 0.4, 1.0);
  ren->AddActor(bunny);
  ren->AddActor(glyphs);
  ren->AddActor(ball);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);

  auto freshWin = MakeWindow(200, 200);
  auto sameAsFresh = [&](const std::string& what) { SameAsFreshPass(win, ren, freshWin, what); };

  win->Render();
  const vtkTypeInt64 everything = pass->GetLastGeometryBytesUploaded();
  Check(everything > 0, "first frame uploads the scene");
  sameAsFresh("first frame");
  double bounds[6];
  bunnyData->GetBounds(bounds);
  int repacked = 0;
  int appended = 0;
  for (int step = 0; step < 40; ++step)
  {
    // Around the bunny's middle, in front of it; every tenth step a larger
    // ball (more records than the room left), which the next step leaves
    // unused: more than half of the records, so that step packs anew too.
    const double t = step / 40.0;
    ballSource->SetCenter(bounds[0] + t * (bounds[1] - bounds[0]), 0.5 * (bounds[2] + bounds[3]), bounds[5]);
    const int res = step % 10 == 4 ? 300 : 12;
    ballSource->SetThetaResolution(res);
    ballSource->SetPhiResolution(res);
    win->Render();
    const vtkTypeInt64 bytes = pass->GetLastGeometryBytesUploaded();
    std::ostringstream s;
    s << "step " << step << ": " << pass->GetLastBVHBuilds() << " build, " << bytes << " geometry bytes (the scene: "
      << everything << ")";
    Check(pass->GetLastBVHBuilds() == 1 && bytes > 0, s.str());
    if (step % 10 != 4 && step % 10 != 5)
    {
      Check(bytes < everything / 10, s.str() + ": only the ball's records");
    }
    (bytes > everything / 2 ? repacked : appended)++;
    sameAsFresh("step " + std::to_string(step));
  }
  Check(appended == 32 && repacked == 8,
    "appended " + std::to_string(appended) + " times, packed anew " + std::to_string(repacked) + " times");

  // The ball picked where it is drawn (hardware selection through the pass).
  double center[3];
  ballSource->GetCenter(center);
  ren->SetWorldPoint(center[0], center[1], center[2], 1.0);
  ren->WorldToDisplay();
  double display[3];
  ren->GetDisplayPoint(display);
  vtkNew<vtkPropPicker> picker;
  picker->Pick(display[0], display[1], 0.0, ren);
  Check(picker->GetActor() == ball, "a pick on the moved ball finds it");

  // Hidden: nothing to write (its records stay unused). Shown again: its
  // cache entry went with it, so it is rebuilt and appended.
  ball->VisibilityOff();
  win->Render();
  Check(pass->GetLastGeometryBytesUploaded() == 0,
    "ball hidden: nothing written (" + std::to_string(pass->GetLastGeometryBytesUploaded()) + " bytes)");
  sameAsFresh("ball hidden");
  ball->VisibilityOn();
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1 && pass->GetLastGeometryBytesUploaded() > 0 &&
      pass->GetLastGeometryBytesUploaded() < everything / 10,
    "ball shown again: only its records");
  sameAsFresh("ball shown again");

  // Glyphs moved: their sphere records are appended too.
  vtkPoints* centers = glyphPoints->GetPoints();
  double p[3];
  centers->GetPoint(0, p);
  centers->SetPoint(0, p[0] + 0.01, p[1], p[2]);
  centers->Modified();
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1 && pass->GetLastGeometryBytesUploaded() > 0 &&
      pass->GetLastGeometryBytesUploaded() < everything,
    "glyphs moved: only their records");
  sameAsFresh("glyphs moved");

  // A texel limit lowered below the scene: refused at once with the
  // limit's error (nothing changed), and so is the next change, not
  // appended into the room of the old limit.
  pass->SetMaximumTextureBufferTexels(1000);
  Output->SetEcho(false);
  win->Render();
  Check(Output->HasErrorContaining("The ray-traced scene needs a texture buffer") &&
      pass->GetLastTracedPrimitives() == 0,
    "limit lowered: refused with the limit's error");
  Output->Clear();
  ballSource->SetCenter(bounds[0], bounds[2], bounds[5]);
  win->Render();
  Output->SetEcho(true);
  Check(Output->HasErrorContaining("The ray-traced scene needs a texture buffer") &&
      pass->GetLastTracedPrimitives() == 0,
    "limit lowered, then a change: refused with the limit's error");
  Output->Clear();
  pass->SetMaximumTextureBufferTexels(0);
  win->Render();
  Check(pass->GetLastTracedPrimitives() > 0, "limit lifted: traced again");
  sameAsFresh("limit lifted");
  NoGLError(win, "incremental upload");
  NoVTKOutput("incremental upload");
}

// New scalars (values modified in place, another array set) keep the
// mesh's BVH: only its colors are written. New normals or points rebuild
// it. A filter's new output (the polydata modified) is rebuilt the first
// time; from then on its contents are fingerprinted, and the same points
// and cells keep the BVH, while one point one ulp away rebuilds it.
void TestScalarChange()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(120);
  source->SetPhiResolution(120);
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(source->GetOutputPort());
  elevation->SetLowPoint(0, -0.5, 0);
  elevation->SetHighPoint(0, 0.5, 0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(elevation->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  auto freshWin = MakeWindow(200, 200);
  win->Render();
  const vtkTypeInt64 everything = pass->GetLastGeometryBytesUploaded();
  auto frame = [&](const std::string& what, int builds) {
    win->Render();
    std::ostringstream s;
    s << what << ": " << pass->GetLastBVHBuilds() << " BVH builds (want " << builds << "), "
      << pass->GetLastGeometryBytesUploaded() << " bytes written (the scene: " << everything << ")";
    Check(pass->GetLastBVHBuilds() == builds && pass->GetLastGeometryBytesUploaded() > 0, s.str());
    Check(pass->GetLastTriangulationSeconds() == 0.0 || builds > 0, what + ": nothing triangulated without a build");
    if (builds == 0)
    {
      Check(pass->GetLastGeometryBytesUploaded() < everything / 4, what + ": only the colors written");
    }
    SameAsFreshPass(win, ren, freshWin, what);
  };
  // The filter runs again: a new output, rebuilt; then again, kept.
  elevation->SetHighPoint(0, 0.2, 0);
  frame("elevation range changed (a new output)", 1);
  elevation->SetHighPoint(0, 0.3, 0);
  frame("elevation range changed again (same points and cells)", 0);
  // Values modified in place, then another array.
  mapper->Update();
  vtkPolyData* output = vtkPolyData::SafeDownCast(mapper->GetInput());
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); i += 2)
  {
    scalars->SetTuple1(i, 1.0 - scalars->GetTuple1(i));
  }
  scalars->Modified();
  frame("scalar values modified", 0);
  vtkNew<vtkFloatArray> other;
  other->SetName("other");
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    other->InsertNextValue(static_cast<float>(output->GetPoint(i)[0]));
  }
  output->GetPointData()->SetScalars(other);
  frame("another scalar array", 0);
  // A new scalar range maps the colors again, once: the next frame writes nothing.
  mapper->SetScalarRange(0.2, 0.8);
  frame("scalar range changed", 0);
  win->Render();
  Check(pass->GetLastGeometryBytesUploaded() == 0 && pass->GetLastBVHBuilds() == 0,
    "the frame after the range change writes nothing (" + std::to_string(pass->GetLastGeometryBytesUploaded()) +
      " bytes)");
  // Normals replaced, then points moved: the BVH is rebuilt.
  vtkNew<vtkFloatArray> normals;
  normals->DeepCopy(output->GetPointData()->GetNormals());
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    normals->SetTuple3(i, n[1], n[2], n[0]);
  }
  output->GetPointData()->SetNormals(normals);
  frame("normals replaced", 1);
  // Normals edited in place, announced by the point data's Modified() only.
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    normals->SetTuple3(i, n[2], n[0], n[1]);
  }
  output->GetPointData()->Modified();
  frame("normals edited in place, point data modified", 1);
  source->SetRadius(0.8);
  frame("points moved", 1);
  // New points objects: the same values keep the BVH, one ulp rebuilds it.
  mapper->Update();
  output = vtkPolyData::SafeDownCast(mapper->GetInput());
  vtkNew<vtkPoints> same;
  same->DeepCopy(output->GetPoints());
  output->SetPoints(same);
  frame("an equal copy of the points", 0);
  vtkNew<vtkPoints> nudged;
  nudged->DeepCopy(output->GetPoints());
  double p[3];
  nudged->GetPoint(7, p);
  p[0] = std::nextafter(static_cast<float>(p[0]), 1.0f);
  nudged->SetPoint(7, p);
  output->SetPoints(nudged);
  frame("a copy of the points, one ulp apart", 1);

  // Points drawn as spheres: new scalars keep their BVH too.
  actor->GetProperty()->SetRepresentationToPoints();
  actor->GetProperty()->RenderPointsAsSpheresOn();
  actor->GetProperty()->SetPointSize(6);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1, "points as spheres: one sphere BVH built");
  mapper->Update();
  output = vtkPolyData::SafeDownCast(mapper->GetInput());
  scalars = output->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); i += 3)
  {
    scalars->SetTuple1(i, 1.0 - scalars->GetTuple1(i));
  }
  scalars->Modified();
  frame("points as spheres, scalar values modified", 0);
  NoGLError(win, "scalar change");
  NoVTKOutput("scalar change");
}

// Many actors (more than 8): the pass walks a top-level BVH over them. The
// image matches raster; the top level is built once, not for camera moves,
// again when an actor moves; the shared mesh is built once.
void TestManyActors()
{
  auto win = MakeWindow(300, 300);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.2, 0.2, 0.2);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 6; ++j)
    {
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->SetPosition(1.1 * i, 1.1 * j, 0.4 * ((i + j) % 3));
      actor->SetScale(1.0 + 0.1 * i, 1.0, 1.0 + 0.1 * j);
      actor->GetProperty()->SetColor(0.3 + 0.1 * i, 0.9 - 0.1 * j, 0.5);
      ren->AddActor(actor);
      actors.push_back(actor);
    }
  }
  ren->ResetCamera();
  ren->GetActiveCamera()->Elevation(35);
  ren->GetActiveCamera()->Azimuth(20);
  ren->ResetCameraClippingRange();
  auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
  const double error = Difference(traced, raster);
  const long differing = CountDifferingPixels(traced, raster, 24);
  std::ostringstream s;
  s << "36 actors: ray traced vs raster error " << error << " <= 40, " << differing
    << " pixels differ (<= 2%)";
  Check(error <= 40.0 && differing >= 0 && differing <= 300 * 300 / 50, s.str());
  Check(std::string(pass->GetLastFeatureKey()).find("X1") != std::string::npos,
    "36 actors: the shader walks a top-level BVH");
  Check(pass->GetLastBVHBuilds() == 1 && pass->GetLastTopLevelBuilds() == 1,
    "36 actors: one mesh BVH and one top-level BVH built");
  ren->GetActiveCamera()->Azimuth(30);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastTopLevelBuilds() == 0 &&
      pass->GetLastGeometryBytesUploaded() == 0,
    "36 actors, camera move: nothing built or uploaded but the instance records");
  actors[7]->AddPosition(0.0, 0.0, 0.5);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastTopLevelBuilds() == 1,
    "36 actors, one actor moved: the top level only is rebuilt");
  NoGLError(win, "many actors");
  NoVTKOutput("many actors");
}

// A scene of one mesh large enough for arrays of their own mappings: on
// llvmpipe the GL buffers take the pass's cached nodes, triangles, triangle
// vertices and normals as their storage instead of a copy. A second prop
// makes it copy everything (one buffer holds both); after its removal, a
// new mesh borrows the new arrays (the copies let go), and so does a new
// window. Each image equals that of a fresh pass that copies
// (VTKRT_NO_PINNED_MEMORY), in a second window.
void TestBorrowedGeometry()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkSphereSource> meshSource;
  meshSource->SetThetaResolution(1024);
  meshSource->SetPhiResolution(512);
  vtkNew<vtkPolyDataMapper> meshMapper;
  meshMapper->SetInputConnection(meshSource->GetOutputPort());
  vtkNew<vtkActor> mesh;
  mesh->SetMapper(meshMapper);
  ren->AddActor(mesh);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);

  win->Render();
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* noPinning = std::getenv("VTKRT_NO_PINNED_MEMORY");
  const bool borrows = renderer && std::strstr(renderer, "llvmpipe") && !(noPinning && *noPinning);
  auto freshWin = MakeWindow(200, 200);
  const auto sameAsCopying = [&](const std::string& what) {
    setenv("VTKRT_NO_PINNED_MEMORY", "1", 1);
    SameAsFreshPass(win, ren, freshWin, what);
    if (noPinning)
    {
      setenv("VTKRT_NO_PINNED_MEMORY", noPinning, 1);
    }
    else
    {
      unsetenv("VTKRT_NO_PINNED_MEMORY");
    }
  };
  // Nodes, triangles, vertices and normals borrowed: all but a few texels
  // (the empty sphere buffers' zero texel, an empty top level).
  const auto check = [&](const std::string& what, bool borrowed) {
    const vtkTypeInt64 uploaded = pass->GetLastGeometryBytesUploaded();
    const vtkTypeInt64 lent = pass->GetLastGeometryBytesBorrowed();
    std::ostringstream s;
    s << what << ": " << lent << " of " << uploaded << " geometry bytes borrowed";
    Check(uploaded > 0 && (borrowed ? lent > 0 && uploaded - lent <= 256 : lent == 0), s.str());
    sameAsCopying(what);
  };
  check("one mesh", borrows);

  vtkNew<vtkSphereSource> ballSource;
  ballSource->SetRadius(0.1);
  ballSource->SetCenter(0.5, 0.0, 0.0);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ballSource->GetOutputPort());
  vtkNew<vtkActor> ball;
  ball->SetMapper(ballMapper);
  ren->AddActor(ball);
  win->Render();
  check("a ball beside it", false);
  // Removed: its records stay unused in the buffers, nothing is written.
  ren->RemoveActor(ball);
  win->Render();
  Check(pass->GetLastGeometryBytesUploaded() == 0, "the ball removed: nothing written");
  sameAsCopying("the ball removed");

  meshSource->SetThetaResolution(1000);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1, "a new mesh is built");
  check("a new mesh", borrows);
  ren->GetActiveCamera()->Azimuth(30);
  win->Render();
  Check(pass->GetLastGeometryBytesUploaded() == 0, "a camera move uploads nothing");
  sameAsCopying("a camera move");

  win->RemoveRenderer(ren);
  win->Finalize();
  auto win2 = MakeWindow(200, 200);
  win2->AddRenderer(ren);
  win = win2;
  win->Render();
  check("a new window", borrows);
  NoGLError(win, "borrowed geometry");
  NoVTKOutput("borrowed geometry");
}

// Removing the pass gives raster back; the pass survives its window being
// destroyed and renders the same renderer in a new window.
void TestLifecycle()
{
  vtkNew<vtkRenderer> ren;
  ren->AddActor(MeshActor(ReadPolyData("bunny.vtp")));
  ren->SetBackground(0.1, 0.2, 0.3);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  vtkSmartPointer<vtkImageData> raster, traced;
  {
    auto win = MakeWindow(160, 160);
    win->AddRenderer(ren);
    win->Render();
    raster = Grab(win);
    ren->SetPass(pass);
    win->Render();
    traced = Grab(win);
    ren->SetPass(nullptr);
    win->Render();
    Check(Difference(Grab(win), raster) == 0.0, "pass removed: the raster image is back");
    ren->SetPass(pass);
    win->Render();
    win->RemoveRenderer(ren);
    win->Finalize();
  }
  auto win2 = MakeWindow(160, 160);
  win2->AddRenderer(ren);
  win2->Render();
  Check(pass->GetLastGeometryBytesUploaded() > 0 && pass->GetLastShaderCompiles() == 1,
    "new window: geometry uploaded and shader compiled again");
  Check(Difference(Grab(win2), traced) == 0.0, "new window: the same traced image");
  NoGLError(win2, "lifecycle");
  NoVTKOutput("lifecycle");
}

void TestMovedBetweenWindows()
{
  auto scene = [](vtkSmartPointer<vtkRenderer>& ren) {
    auto win = MakeWindow(120, 120);
    ren = vtkSmartPointer<vtkRenderer>::New();
    ren->AddActor(MeshActor(ReadPolyData("bunny.vtp")));
    ren->ResetCamera();
    win->AddRenderer(ren);
    return win;
  };
  vtkSmartPointer<vtkRenderer> ren1, ren2;
  auto win1 = scene(ren1);
  auto win2 = scene(ren2);
  win1->Render();
  auto raster1 = Grab(win1);
  // What a fresh pass traces in each window.
  auto tracedBy = [](vtkRenderWindow* win, vtkRenderer* ren) {
    vtkNew<vtkRayTracePass> fresh;
    ren->SetPass(fresh);
    win->Render();
    auto image = Grab(win);
    ren->SetPass(nullptr);
    win->Render();
    return image;
  };
  auto traced1 = tracedBy(win1, ren1);
  ren2->GetActiveCamera()->Azimuth(30);
  auto traced2 = tracedBy(win2, ren2);

  vtkNew<vtkRayTracePass> pass;
  ren1->SetPass(pass);
  win1->Render();
  Check(Difference(Grab(win1), traced1) == 0.0, "moved: traced in the first window");
  ren1->SetPass(nullptr);
  ren2->SetPass(pass);
  for (int frame = 0; frame < 3; ++frame)
  {
    win2->Render();
    Check(Difference(Grab(win2), traced2) == 0.0,
      "moved: frame " + std::to_string(frame) + " in the second window as a fresh pass's");
  }
  win1->Render();
  Check(Difference(Grab(win1), raster1) == 0.0, "moved: the first window's raster is unharmed");
  ren2->SetPass(nullptr);
  ren1->SetPass(pass);
  win1->Render();
  Check(Difference(Grab(win1), traced1) == 0.0, "moved back: traced in the first window again");
  // The first window goes while the pass is elsewhere: its objects go with
  // it, and raster and the pass go on elsewhere.
  ren1->SetPass(nullptr);
  ren2->SetPass(pass);
  win1->RemoveRenderer(ren1);
  win1 = nullptr;
  win2->Render();
  Check(Difference(Grab(win2), traced2) == 0.0, "first window deleted: the second still traced");
  vtkSmartPointer<vtkRenderer> ren3;
  auto win3 = scene(ren3);
  win3->Render();
  Check(Difference(Grab(win3), raster1) == 0.0, "first window deleted: raster elsewhere unharmed");
  NoGLError(win2, "moved");
  NoVTKOutput("moved");
}

void TestApp()
{
  if (AppPath.empty())
  {
    Check(false, "app: path of vtkrt-render given on the command line");
    return;
  }
  const std::string tmp = VTKRT_TEMP_DIR;
  // A file the app reads: a sphere and a cone in one PLY.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(20);
  vtkNew<vtkPLYWriter> writer;
  writer->SetInputConnection(sphere->GetOutputPort());
  const std::string ply = tmp + "/pass_app_sphere.ply";
  writer->SetFileName(ply.c_str());
  writer->Write();
  const std::pair<std::string, std::string> inputs[] = { { "demo", "--demo" }, { "file", "'" + ply + "'" } };
  for (const auto& input : inputs)
  {
    vtkSmartPointer<vtkImageData> images[2];
    const char* modes[2] = { "raster", "raytrace" };
    for (int m = 0; m < 2; ++m)
    {
      const std::string out = tmp + "/pass_app_" + input.first + "_" + modes[m] + ".png";
      const std::string cmd = "'" + AppPath + "' " + input.second + " --mode " + modes[m] +
        " --size 200x160 --frames 2 --output '" + out + "' > '" + out + ".log' 2>&1";
      const int rc = std::system(cmd.c_str());
      Check(rc == 0, "app " + input.first + " --mode " + modes[m] + ": exit status 0");
      vtkNew<vtkPNGReader> reader;
      reader->SetFileName(out.c_str());
      reader->Update();
      images[m] = vtkSmartPointer<vtkImageData>::New();
      images[m]->DeepCopy(reader->GetOutput());
    }
    const double error = Difference(images[1], images[0]);
    const long differing = CountDifferingPixels(images[1], images[0], 24);
    std::ostringstream s;
    s << "app " << input.first << ": raytrace vs raster error " << error << " <= 40, " << differing
      << " pixels differ (<= 3%)";
    Check(error <= 40.0 && differing >= 0 && differing <= 200 * 160 * 3 / 100, s.str());
  }
  NoVTKOutput("app");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Counters", TestCounters },
    { "ManyActors", TestManyActors },
    { "IncrementalUpload", TestIncrementalUpload },
    { "ScalarChange", TestScalarChange },
    { "BorrowedGeometry", TestBorrowedGeometry },
    { "Lifecycle", TestLifecycle },
    { "MovedBetweenWindows", TestMovedBetweenWindows },
    { "App", TestApp },
  };
  if (argc > 2)
  {
    AppPath = argv[2];
  }
  return RunCase(argc, argv, cases, " [vtkrt-render]");
}
