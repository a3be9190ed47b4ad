// What vtkRayTracePass writes to its GL buffers from frame to frame:
//   IncrementalUpload a small prop changed beside a colored mesh writes only
//                     its own records and colors (appended, then packed anew
//                     when out of room or under a lowered texel limit);
//                     images and picks equal a fresh pass's
//   ScalarChange      new scalars keep a mesh's BVH (only colors written);
//                     new normals or points rebuild it
//   BorrowedGeometry  a scene of one mesh: on llvmpipe its cached arrays are
//                     the GL buffers' storage (no copy); a rebuilt mesh, a
//                     second prop, appends beside a partly borrowed layout
//                     and a new window switch between that and copies, each
//                     image the same as a copying pass's
//   SingleInstance    a scene of one traced instance reads its record from
//                     uniforms (not per pixel from the instance buffer): the
//                     images and picks are those of the general shader, as
//                     the instance moves, changes its colors and lighting
// TestRayTracePassUpload <Case>.
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
/// Whether the current context is one the pass lends memory of its own
/// (as vtkRayTraceBuffers decides): llvmpipe with GL_AMD_pinned_memory,
/// and VTKRT_NO_PINNED_MEMORY unset, empty or 0.
bool PassPinsMemory()
{
  const char* noPinning = std::getenv("VTKRT_NO_PINNED_MEMORY");
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if ((noPinning && *noPinning && std::strcmp(noPinning, "0") != 0) || !renderer ||
    !std::strstr(renderer, "llvmpipe"))
  {
    return false;
  }
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
  {
    const char* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (extension && std::strcmp(extension, "GL_AMD_pinned_memory") == 0)
    {
      return true;
    }
  }
  return false;
}

/// A sphere colored by its height (point scalars over [-0.5, 0.5] in y),
/// the pipeline kept so that a case can change its stages.
struct ElevationSphere
{
  vtkNew<vtkSphereSource> Source;
  vtkNew<vtkElevationFilter> Colors;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;

  ElevationSphere(int theta, int phi)
  {
    this->Source->SetThetaResolution(theta);
    this->Source->SetPhiResolution(phi);
    this->Colors->SetInputConnection(this->Source->GetOutputPort());
    this->Colors->SetLowPoint(0.0, -0.5, 0.0);
    this->Colors->SetHighPoint(0.0, 0.5, 0.0);
    this->Mapper->SetInputConnection(this->Colors->GetOutputPort());
    this->Actor->SetMapper(this->Mapper);
  }
};

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

  // Hidden: nothing to write (its records stay, unused). Shown again: its
  // cache entry was kept with them (as raster keeps an invisible actor's
  // buffers), so nothing is built or written.
  ball->VisibilityOff();
  win->Render();
  Check(pass->GetLastGeometryBytesUploaded() == 0,
    "ball hidden: nothing written (" + std::to_string(pass->GetLastGeometryBytesUploaded()) + " bytes)");
  sameAsFresh("ball hidden");
  ball->VisibilityOn();
  win->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0,
    "ball shown again: nothing built or written (" + std::to_string(pass->GetLastGeometryBytesUploaded()) +
      " bytes)");
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
  ElevationSphere sphere(120, 120);
  vtkSphereSource* source = sphere.Source;
  vtkElevationFilter* elevation = sphere.Colors;
  vtkPolyDataMapper* mapper = sphere.Mapper;
  vtkActor* actor = sphere.Actor;
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
  // Each mesh's arrays as built, not a tree taken later from a background
  // build (TestRayTracePassBehavior BackgroundBuild).
  pass->SetBackgroundBuildThreshold(0);
  ren->SetPass(pass);

  win->Render();
  const bool borrows = PassPinsMemory();
  const char* noPinningValue = std::getenv("VTKRT_NO_PINNED_MEMORY");
  const std::string noPinning = noPinningValue ? noPinningValue : "";
  auto freshWin = MakeWindow(200, 200);
  const auto sameAsCopying = [&](const std::string& what) {
    setenv("VTKRT_NO_PINNED_MEMORY", "1", 1);
    SameAsFreshPass(win, ren, freshWin, what);
    if (noPinningValue)
    {
      setenv("VTKRT_NO_PINNED_MEMORY", noPinning.c_str(), 1);
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
  // Rebuilt: the cache lets go of the borrowed arrays first, the buffers
  // keep them until they borrow the new ones.
  meshSource->SetThetaResolution(1000);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1, "a rebuilt mesh is built");
  check("a rebuilt mesh", borrows);

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

  meshSource->SetThetaResolution(1024);
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

  // A mesh of about 100k triangles: its nodes and triangles are lent, its
  // smaller arrays (triangle vertices, normals) copied. Then points drawn
  // as spheres beside it: every geometry needs nodes, and the borrowed
  // nodes buffer has no room, so everything is packed anew, copied (where
  // nothing is borrowed, the spheres are appended into the room).
  meshSource->SetThetaResolution(250);
  meshSource->SetPhiResolution(200);
  win->Render();
  const vtkTypeInt64 partly = pass->GetLastGeometryBytesBorrowed();
  const vtkTypeInt64 smaller = pass->GetLastGeometryBytesUploaded();
  Check(borrows ? partly > smaller / 2 && smaller - partly > 256 : partly == 0,
    "a smaller mesh: partly borrowed (" + std::to_string(partly) + " of " + std::to_string(smaller) +
      " bytes)");
  sameAsCopying("a smaller mesh");
  vtkNew<vtkPolyDataMapper> pointsMapper;
  pointsMapper->SetInputConnection(ballSource->GetOutputPort());
  vtkNew<vtkActor> points;
  points->SetMapper(pointsMapper);
  points->GetProperty()->SetRepresentationToPoints();
  points->GetProperty()->RenderPointsAsSpheresOn();
  points->GetProperty()->SetPointSize(6);
  ren->AddActor(points);
  win->Render();
  const vtkTypeInt64 written = pass->GetLastGeometryBytesUploaded();
  Check(pass->GetLastTracedPrimitives() > 250 * 198 * 2 && pass->GetLastGeometryBytesBorrowed() == 0 &&
      (borrows ? written > smaller : written < smaller / 10),
    std::string("points as spheres beside it: ") + (borrows ? "all packed anew" : "appended") + " (" +
      std::to_string(written) + " bytes)");
  sameAsCopying("points as spheres beside it");
  NoGLError(win, "borrowed geometry");
  NoVTKOutput("borrowed geometry");
}

// One colored, lit, moved and scaled mesh: the shader of one instance
// ("i1" in its feature key); with a small ball hidden inside it (the
// general shader, "i0") every image is the same and a pick on the mesh
// finds it with either. Back to one instance, the kept program is used.
void TestSingleInstance()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ElevationSphere sphere(64, 32);
  vtkActor* mesh = sphere.Actor;
  mesh->SetPosition(0.3, -0.2, 0.1);
  mesh->SetScale(1.5, 1.0, 0.75);
  mesh->RotateZ(30.0);
  mesh->GetProperty()->SetSpecular(0.5);
  mesh->GetProperty()->SetSpecularPower(20.0);
  ren->AddActor(mesh);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);

  // Inside the closed mesh, at its center: it changes neither the image
  // nor the clipping range, and VTK's culling keeps it.
  vtkNew<vtkSphereSource> ballSource;
  ballSource->SetRadius(0.01);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ballSource->GetOutputPort());
  vtkNew<vtkActor> ball;
  ball->SetMapper(ballMapper);
  // The key, and the shader it names: the define is there or not.
  const auto shaderIs = [&](const char* part, bool single) {
    const bool defined =
      std::string(pass->GetLastFragmentShaderSource()).find("#define VTKRT_SINGLE_INSTANCE\n") != std::string::npos;
    return std::string(pass->GetLastFeatureKey()).find(part) != std::string::npos && defined == single;
  };
  const auto pickCenter = [&]() {
    const double* center = mesh->GetCenter();
    ren->SetWorldPoint(center[0], center[1], center[2], 1.0);
    ren->WorldToDisplay();
    double display[3];
    ren->GetDisplayPoint(display);
    vtkNew<vtkPropPicker> picker;
    picker->Pick(display[0], display[1], 0.0, ren);
    return picker->GetActor() == mesh;
  };
  const auto sameAsGeneral = [&](const std::string& what) {
    win->Render();
    Check(shaderIs("i1", true) && pass->GetLastTracedInstances() == 1,
      what + ": one instance, its record in uniforms (key " + pass->GetLastFeatureKey() + ")");
    auto single = Grab(win);
    Check(pickCenter(), what + ": a pick on the mesh finds it (one instance)");
    ball->SetPosition(mesh->GetCenter());
    ren->AddActor(ball);
    win->Render();
    Check(shaderIs("i0", false) && pass->GetLastTracedInstances() == 2,
      what + ": two instances, the general shader (key " + pass->GetLastFeatureKey() + ")");
    // Same values, same operations: the same image (a driver may contract
    // the two programs' arithmetic differently: a step of 1 at most).
    auto general = Grab(win);
    const long differing = CountDifferingPixels(single, general, 1);
    Check(differing == 0,
      what + ": the same image as the general shader's (" + std::to_string(differing) +
        " pixels differ by more than 1; RGB RMSE " + std::to_string(RootMeanSquareError(single, general)) + ")");
    Check(pickCenter(), what + ": a pick on the mesh finds it (two instances)");
    ren->RemoveActor(ball);
    win->Render();
    Check(shaderIs("i1", true) && pass->GetLastShaderCompiles() == 0, what + ": one instance again, nothing compiled");
  };
  sameAsGeneral("one mesh");
  mesh->SetPosition(-0.2, 0.1, 0.0);
  mesh->RotateX(40.0);
  sameAsGeneral("moved and turned");
  mesh->GetProperty()->SetAmbient(0.3);
  mesh->GetProperty()->SetDiffuseColor(0.9, 0.5, 0.1);
  sphere.Mapper->ScalarVisibilityOff();
  sameAsGeneral("new colors");
  ren->GetActiveCamera()->Elevation(35.0);
  ren->GetActiveCamera()->OrthogonalizeViewUp();
  sameAsGeneral("a camera move");
  NoGLError(win, "single instance");
  NoVTKOutput("single instance");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "IncrementalUpload", TestIncrementalUpload },
    { "ScalarChange", TestScalarChange },
    { "BorrowedGeometry", TestBorrowedGeometry },
    { "SingleInstance", TestSingleInstance },
  };
  return RunCase(argc, argv, cases);
}
