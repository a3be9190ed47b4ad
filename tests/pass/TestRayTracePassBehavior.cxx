// vtkRayTracePass behaviour across frames and outside the pass itself:
//   Counters          what a frame builds, uploads and compiles across camera
//                     moves, property/light changes, data and feature changes
//   ManyActors        more than 8 actors: a top-level BVH, rebuilt only when
//                     an actor moves
//   BackgroundBuild   a mesh over BackgroundBuildThreshold: traced first on a
//                     fast tree, then on the tree built in the background
//                     (same images and picks as a pass that builds it at
//                     once); a mesh changed or a pass deleted while it builds
//   Lifecycle         the pass removed and installed again, its window
//                     destroyed and replaced
//   MovedBetweenWindows one pass moved between two live windows' renderers and
//                     back, then its first window deleted: every frame traced
//                     as by a fresh pass, raster unharmed
//   App <vtkrt-render> vtkrt-render --mode raytrace on the demo and on a file,
//                     against its raster mode
// (What a frame writes to the GL buffers: TestRayTracePassUpload.)
// TestRayTracePassBehavior <Case> [vtkrt-render path].
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkElevationFilter.h"
#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMultiBlockDataSet.h"
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
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSphereSource.h"
#include "vtkVariant.h"

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
  frame("glyphs hidden (their BVH kept, as raster keeps buffers)", 0, false, 1);
  const std::string source = pass->GetLastFragmentShaderSource();
  Check(source.find("raySphereRoots") == std::string::npos &&
      source.find("traverseTriangles") != std::string::npos,
    "a scene without spheres compiles no sphere code");
  glyphs->VisibilityOn();
  frame("glyphs shown again: nothing built or uploaded", 0, false, 0);
  pass->SetBuildQuality(0);
  frame("build quality changed: both BVHs rebuilt", 2, true, 0);
  frame("unchanged after the quality change", 0, false, 0);
  NoGLError(win, "counters");
  NoVTKOutput("counters");
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

/// The cell id under the window's center (hardware selection through the pass).
vtkIdType CenterCell(vtkRenderer* ren, vtkRenderWindow* win)
{
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(ren);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  const int* size = win->GetSize();
  const auto x = static_cast<unsigned int>(size[0] / 2);
  const auto y = static_cast<unsigned int>(size[1] / 2);
  selector->SetArea(x, y, x, y);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  vtkSelectionNode* node = selection && selection->GetNumberOfNodes() > 0 ? selection->GetNode(0) : nullptr;
  vtkAbstractArray* ids = node ? node->GetSelectionList() : nullptr;
  return ids && ids->GetNumberOfValues() > 0 ? ids->GetVariantValue(0).ToLongLong() : -1;
}

// A mesh over the pass's BackgroundBuildThreshold: the first frame builds a
// fast tree and starts the SAH tree's build; a frame after it is done takes
// it (no build, a new upload), with the same image and center pick as the
// fast tree and as a pass that builds SAH at once. A mesh changed while its
// build runs is built again (the stale build is let go); a pass deleted
// while it builds waits for it. BuildQuality 0 or a threshold of 0: none.
void TestBackgroundBuild()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(200);
  source->SetPhiResolution(100);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(20);
  vtkNew<vtkRayTracePass> pass;
  pass->SetBackgroundBuildThreshold(1000);
  ren->SetPass(pass);

  win->Render();
  Check(pass->GetLastBVHBuilds() == 1 && pass->GetLastBackgroundBuildsTaken() == 0 &&
      pass->GetNumberOfBackgroundBuilds() == 1 && pass->GetNumberOfBackgroundBuildsTaken() == 0,
    "first frame: the fast tree built, its background build not taken yet");
  auto fast = Grab(win);
  pass->WaitForBackgroundBuilds();
  win->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastBackgroundBuildsTaken() == 1 &&
      pass->GetLastGeometryBytesUploaded() > 0 && pass->GetNumberOfBackgroundBuilds() == 0 &&
      pass->GetNumberOfBackgroundBuildsTaken() == 1,
    "after the wait: the background tree taken and uploaded, nothing built, none left, one taken in all");
  auto refined = Grab(win);
  Check(RootMeanSquareError(fast, refined) == 0.0, "the same image on both trees");
  win->Render();
  Check(pass->GetLastBackgroundBuildsTaken() == 0 && pass->GetLastGeometryBytesUploaded() == 0 &&
      pass->GetNumberOfBackgroundBuildsTaken() == 1,
    "the next frame: nothing taken, nothing uploaded, still one taken in all");

  // The same scene, SAH built at once.
  vtkNew<vtkRayTracePass> atOnce;
  atOnce->SetBackgroundBuildThreshold(0);
  ren->SetPass(atOnce);
  win->Render();
  Check(atOnce->GetLastBVHBuilds() == 1, "threshold 0: built at once");
  Check(RootMeanSquareError(Grab(win), refined) == 0.0, "the background tree's image equals the SAH tree's");
  atOnce->WaitForBackgroundBuilds();
  win->Render();
  Check(atOnce->GetLastBackgroundBuildsTaken() == 0, "threshold 0: nothing built in the background");
  const vtkIdType atOnceCell = CenterCell(ren, win);
  ren->SetPass(pass);
  win->Render();
  const vtkIdType refinedCell = CenterCell(ren, win);
  Check(atOnceCell >= 0 && refinedCell == atOnceCell,
    "the same center pick as the SAH tree's (" + std::to_string(refinedCell) + ", " +
      std::to_string(atOnceCell) + ")");

  // Changed while its build runs: built again, the stale build let go.
  source->SetThetaResolution(180);
  win->Render();
  source->SetThetaResolution(190);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1, "changed twice: built again");
  pass->WaitForBackgroundBuilds();
  win->Render();
  Check(pass->GetLastBackgroundBuildsTaken() == 1, "the latest mesh's tree taken");
  auto changed = Grab(win);
  ren->SetPass(atOnce);
  win->Render();
  Check(RootMeanSquareError(Grab(win), changed) == 0.0, "changed mesh: the same image as the SAH tree's");
  ren->SetPass(pass);

  // Two actors on the mesh and a second mesh: two builds, one after the
  // other, each taken once, by the first of its instances in a frame.
  vtkNew<vtkActor> twin;
  twin->SetMapper(mapper);
  twin->SetPosition(0.2, 0.0, 0.0);
  vtkNew<vtkSphereSource> otherSource;
  otherSource->SetThetaResolution(150);
  otherSource->SetPhiResolution(80);
  otherSource->SetCenter(0.0, 0.6, 0.0);
  otherSource->SetRadius(0.2);
  vtkNew<vtkPolyDataMapper> otherMapper;
  otherMapper->SetInputConnection(otherSource->GetOutputPort());
  vtkNew<vtkActor> other;
  other->SetMapper(otherMapper);
  ren->AddActor(twin);
  ren->AddActor(other);
  source->SetThetaResolution(200);
  int built = 0, taken = 0;
  for (int frame = 0; frame < 4; ++frame)
  {
    win->Render(); // builds taken whenever they are done
    built += pass->GetLastBVHBuilds();
    taken += pass->GetLastBackgroundBuildsTaken();
  }
  pass->WaitForBackgroundBuilds();
  win->Render();
  taken += pass->GetLastBackgroundBuildsTaken();
  win->Render();
  Check(built == 2 && taken == 2 && pass->GetLastBackgroundBuildsTaken() == 0 && pass->GetLastBVHBuilds() == 0,
    "two actors and a second mesh: " + std::to_string(built) + " fast builds, " + std::to_string(taken) +
      " trees taken (2, 2), nothing left");
  auto both = Grab(win);
  ren->SetPass(atOnce);
  win->Render();
  Check(RootMeanSquareError(Grab(win), both) == 0.0, "two actors and a second mesh: the SAH trees' image");
  ren->SetPass(pass);
  ren->RemoveActor(twin);
  ren->RemoveActor(other);

  // BuildQuality 0: the fast tree is the one asked for.
  pass->SetBuildQuality(0);
  win->Render();
  pass->WaitForBackgroundBuilds();
  win->Render();
  Check(pass->GetLastBackgroundBuildsTaken() == 0, "BuildQuality 0: nothing built in the background");
  pass->SetBuildQuality(1);

  // Deleted while it builds: the pass waits for its build.
  {
    vtkNew<vtkRayTracePass> shortLived;
    shortLived->SetBackgroundBuildThreshold(1000);
    ren->SetPass(shortLived);
    win->Render();
    ren->SetPass(pass);
    ren->ReleaseGraphicsResources(win);
  }
  win->Render();
  Check(pass->GetLastTracedPrimitives() > 0, "a pass deleted while it builds: the other pass traces on");

  // Progressive accumulation goes on over a tree taken (the same hits, a
  // repack and a shader with another stack): frames 1, 2, 3, and the image
  // of a pass whose tree was built at once.
  vtkSmartPointer<vtkImageData> accumulated[2];
  for (const int threshold : { 1000, 0 })
  {
    vtkNew<vtkRayTracePass> progressive;
    progressive->SetBackgroundBuildThreshold(threshold);
    progressive->ProgressiveAccumulationOn();
    ren->SetPass(progressive);
    std::string frames;
    for (int frame = 0; frame < 3; ++frame)
    {
      win->Render();
      frames += std::to_string(progressive->GetAccumulatedFrames());
      progressive->WaitForBackgroundBuilds();
    }
    accumulated[threshold == 0 ? 1 : 0] = Grab(win);
    Check(frames == "123", "accumulating, background threshold " + std::to_string(threshold) +
        ": frames " + frames + " (want 123)");
  }
  Check(RootMeanSquareError(accumulated[0], accumulated[1]) == 0.0,
    "accumulated over a tree taken: the image of the tree built at once");
  ren->SetPass(pass);
  NoGLError(win, "background build");
  NoVTKOutput("background build");
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
// A camera move that takes a prop out of the view, where VTK's culler leaves
// it out of the frame, and brings it back builds and uploads nothing, as
// raster keeps a culled actor's buffers; the image back is raster's. A prop
// never in view is built when it first is.
void TestCulledProps()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkSphereSource> left, right;
  left->SetThetaResolution(64);
  left->SetPhiResolution(64);
  right->SetCenter(20.0, 0.0, 0.0);
  vtkNew<vtkPolyDataMapper> leftMapper, rightMapper;
  leftMapper->SetInputConnection(left->GetOutputPort());
  rightMapper->SetInputConnection(right->GetOutputPort());
  vtkNew<vtkActor> leftActor, rightActor;
  leftActor->SetMapper(leftMapper);
  rightActor->SetMapper(rightMapper);
  ren->AddActor(leftActor);
  ren->AddActor(rightActor);
  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetPosition(0.0, 0.0, 5.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  ren->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  const int tracedFirst = pass->GetNumberOfTracedProps();
  const vtkIdType builtFirst = pass->GetLastBVHBuilds();
  camera->SetPosition(20.0, 0.0, 5.0);
  camera->SetFocalPoint(20.0, 0.0, 0.0);
  ren->ResetCameraClippingRange();
  win->Render();
  Check(pass->GetLastBVHBuilds() == 1, "the prop first in view is built: " +
      std::to_string(pass->GetLastBVHBuilds()) + " builds");
  std::ostringstream s;
  for (double x : { 0.0, 20.0, 0.0 })
  {
    camera->SetPosition(x, 0.0, 5.0);
    camera->SetFocalPoint(x, 0.0, 0.0);
    ren->ResetCameraClippingRange();
    win->Render();
    s << " to x " << x << ": " << pass->GetNumberOfTracedProps() << " traced, "
      << pass->GetLastBVHBuilds() << " builds, " << pass->GetLastGeometryBytesUploaded() << " bytes;";
    Check(pass->GetNumberOfTracedProps() == 1 && pass->GetLastBVHBuilds() == 0 &&
        pass->GetLastGeometryBytesUploaded() == 0,
      "camera moved" + s.str());
  }
  Check(tracedFirst == 1 && builtFirst == 1, "the first frame traces and builds the prop in view alone (the other culled)");
  vtkSmartPointer<vtkImageData> traced = Grab(win);
  ren->SetPass(nullptr);
  win->Render();
  vtkSmartPointer<vtkImageData> raster = Grab(win);
  const long differing = CountDifferingPixels(traced, raster, 40);
  Check(differing <= 200 * 200 / 200, "back in view: " + std::to_string(differing) + " pixels differ from raster");
  // A culled prop whose data changes is not built until it is in view (as
  // raster, which does nothing for it), then built once.
  ren->SetPass(pass);
  right->SetThetaResolution(40);
  win->Render();
  const vtkIdType culledBuilds = pass->GetLastBVHBuilds();
  camera->SetPosition(20.0, 0.0, 5.0);
  camera->SetFocalPoint(20.0, 0.0, 0.0);
  ren->ResetCameraClippingRange();
  win->Render();
  const vtkIdType shownBuilds = pass->GetLastBVHBuilds();
  traced = Grab(win);
  ren->SetPass(nullptr);
  win->Render();
  raster = Grab(win);
  const long changedDiffering = CountDifferingPixels(traced, raster, 40);
  Check(culledBuilds == 0 && shownBuilds == 1 && changedDiffering <= 200 * 200 / 200,
    "a culled prop changed: " + std::to_string(culledBuilds) + " builds while culled, " +
      std::to_string(shownBuilds) + " when shown, " + std::to_string(changedDiffering) +
      " pixels differ from raster");
  NoVTKOutput("CulledProps");
}

/// Props and composite blocks hidden and shown again (VisibilityOff, block
/// visibility, opacity 0), or left to raster for a frame for their looks,
/// build and upload nothing when traced again, as raster keeps their
/// buffers, and each frame equals raster's.
void TestHiddenProps()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkActor> single;
  single->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::Take(vtkPolyDataMapper::New()));
  vtkPolyDataMapper::SafeDownCast(single->GetMapper())->SetInputData(Sphere(-1.2, 48));
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, Sphere(0.0, 48));
  blocks->SetBlock(1, Sphere(1.2, 48));
  vtkNew<vtkCompositePolyDataMapper2> composite;
  composite->SetInputDataObject(blocks);
  vtkNew<vtkCompositeDataDisplayAttributes> attributes;
  composite->SetCompositeDataDisplayAttributes(attributes);
  vtkNew<vtkActor> blocksActor;
  blocksActor->SetMapper(composite);
  // Points drawn as spheres above the spheres, a polyline drawn as a tube
  // below them.
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> cloudPoints;
  vtkNew<vtkCellArray> cloudVerts;
  vtkNew<vtkPolyData> line;
  vtkNew<vtkPoints> linePoints;
  vtkNew<vtkCellArray> lineCells;
  lineCells->InsertNextCell(7);
  for (int i = 0; i < 7; ++i)
  {
    cloudVerts->InsertNextCell(1);
    cloudVerts->InsertCellPoint(cloudPoints->InsertNextPoint(-1.5 + 0.5 * i, 1.0, 0.0));
    lineCells->InsertCellPoint(linePoints->InsertNextPoint(-1.5 + 0.5 * i, -1.0 - 0.2 * (i % 2), 0.0));
  }
  cloud->SetPoints(cloudPoints);
  cloud->SetVerts(cloudVerts);
  line->SetPoints(linePoints);
  line->SetLines(lineCells);
  vtkNew<vtkActor> cloudActor, lineActor;
  cloudActor->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::Take(vtkPolyDataMapper::New()));
  vtkPolyDataMapper::SafeDownCast(cloudActor->GetMapper())->SetInputData(cloud);
  cloudActor->GetProperty()->RenderPointsAsSpheresOn();
  cloudActor->GetProperty()->SetPointSize(12);
  lineActor->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::Take(vtkPolyDataMapper::New()));
  vtkPolyDataMapper::SafeDownCast(lineActor->GetMapper())->SetInputData(line);
  lineActor->GetProperty()->RenderLinesAsTubesOn();
  lineActor->GetProperty()->SetLineWidth(6);
  ren->AddActor(single);
  ren->AddActor(blocksActor);
  ren->AddActor(cloudActor);
  ren->AddActor(lineActor);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 5, "first frame: " + std::to_string(pass->GetLastBVHBuilds()) + " builds");
  struct Step
  {
    std::string Label;
    std::function<void()> Change;
    int Traced;
    bool Builds = false; ///< a form drawn for the first time
  };
  const Step steps[] = {
    { "the actor hidden", [&] { single->VisibilityOff(); }, 3 },
    { "the actor shown", [&] { single->VisibilityOn(); }, 4 },
    { "a block hidden", [&] { attributes->SetBlockVisibility(blocks->GetBlock(1), false); }, 4 },
    { "the block shown", [&] { attributes->SetBlockVisibility(blocks->GetBlock(1), true); }, 4 },
    { "the actor at opacity 0", [&] { single->GetProperty()->SetOpacity(0.0); }, 4 }, // traced as nothing
    { "the actor at opacity 1", [&] { single->GetProperty()->SetOpacity(1.0); }, 4 },
    // Left to raster for its looks, then traced again.
    { "the actor as points (raster)", [&] { single->GetProperty()->SetRepresentationToPoints(); }, 3 },
    { "the actor as a surface again", [&] { single->GetProperty()->SetRepresentationToSurface(); }, 4 },
    { "the blocks in PBR (raster)", [&] { blocksActor->GetProperty()->SetInterpolationToPBR(); }, 3 },
    { "the blocks in Gouraud again", [&] { blocksActor->GetProperty()->SetInterpolationToGouraud(); }, 4 },
    { "the spheres at opacity 0.5 (raster)", [&] { cloudActor->GetProperty()->SetOpacity(0.5); }, 3 },
    { "the spheres at opacity 1", [&] { cloudActor->GetProperty()->SetOpacity(1.0); }, 4 },
    { "the points as squares (raster)", [&] { cloudActor->GetProperty()->RenderPointsAsSpheresOff(); }, 3 },
    { "the points as spheres again", [&] { cloudActor->GetProperty()->RenderPointsAsSpheresOn(); }, 4 },
    { "the tube at opacity 0.5 (raster)", [&] { lineActor->GetProperty()->SetOpacity(0.5); }, 3 },
    { "the tube at opacity 1", [&] { lineActor->GetProperty()->SetOpacity(1.0); }, 4 },
    { "the line as a line (raster)", [&] { lineActor->GetProperty()->RenderLinesAsTubesOff(); }, 3 },
    { "the line as a tube again", [&] { lineActor->GetProperty()->RenderLinesAsTubesOn(); }, 4 },
    { "the actor as points drawn as spheres", [&] {
        single->GetProperty()->SetRepresentationToPoints();
        single->GetProperty()->RenderPointsAsSpheresOn();
      }, 4, true },
    { "the actor as a surface again (its triangles kept)",
      [&] { single->GetProperty()->SetRepresentationToSurface(); }, 4 },
    { "the actor as spheres again (its spheres kept)",
      [&] { single->GetProperty()->SetRepresentationToPoints(); }, 4 },
  };
  for (const Step& step : steps)
  {
    step.Change();
    composite->Modified();
    win->Render();
    std::ostringstream s;
    s << step.Label << ": " << pass->GetNumberOfTracedProps() << " traced, " << pass->GetLastBVHBuilds()
      << " builds, " << pass->GetLastGeometryBytesUploaded() << " geometry bytes";
    const bool nothingNew = pass->GetLastBVHBuilds() == 0 && pass->GetLastGeometryBytesUploaded() == 0;
    vtkSmartPointer<vtkImageData> traced = Grab(win);
    ren->SetPass(nullptr);
    win->Render();
    vtkSmartPointer<vtkImageData> raster = Grab(win);
    ren->SetPass(pass);
    const long differing = CountDifferingPixels(traced, raster, 40);
    s << ", " << differing << " pixels differ from raster";
    Check(pass->GetNumberOfTracedProps() == step.Traced && (nothingNew || step.Builds) && differing <= 200,
      s.str());
    // A second frame in each state: what is kept lasts beyond one frame.
    win->Render();
  }
  NoVTKOutput("HiddenProps");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Counters", TestCounters },
    { "ManyActors", TestManyActors },
    { "BackgroundBuild", TestBackgroundBuild },
    { "Lifecycle", TestLifecycle },
    { "MovedBetweenWindows", TestMovedBetweenWindows },
    { "CulledProps", TestCulledProps },
    { "HiddenProps", TestHiddenProps },
    { "App", TestApp },
  };
  if (argc > 2)
  {
    AppPath = argv[2];
  }
  return RunCase(argc, argv, cases, " [vtkrt-render]");
}
