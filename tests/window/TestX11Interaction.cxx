// vtkRayTracePass under VTK's interaction in an X11 window: each case builds
// the same scene (a fine sphere mesh, a cube, sphere glyphs) twice, in two
// vtkXOpenGLRenderWindows with a vtkXRenderWindowInteractor each (initialized,
// no event loop), one rasterized and one traced, sends both interactors the
// same synthesized events, and compares what VTK's interactor styles did:
// the camera (TrackballCamera), the moved actor (TrackballActor), the picked
// prop (a vtkPropPicker observer and the style's 'p' key), and the frames the
// interactors rendered.
// Run under an X server (CTest uses run-under-xvfb.sh: `xvfb-run -a`);
// without one (no DISPLAY) it exits 77, which CTest reports as skipped.
#include "vtkrtPassTestUtils.h"

#include "vtkAbstractPropPicker.h"
#include "vtkActorCollection.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkInteractorStyleTrackballActor.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkPropPicker.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
constexpr int W = 300;
constexpr int H = 200;

/// One side of a comparison: an X11 window with an initialized interactor
/// and the scene, traced or rasterized.
struct View
{
  vtkSmartPointer<vtkRenderWindow> Window = vtk::TakeSmartPointer(vtkRenderWindow::New());
  vtkSmartPointer<vtkRenderWindowInteractor> Interactor =
    vtk::TakeSmartPointer(vtkRenderWindowInteractor::New());
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRayTracePass> Pass;
  vtkNew<vtkCallbackCommand> FrameCounter;
  std::vector<vtkSmartPointer<vtkActor>> Actors; ///< mesh, cube, glyphs
  std::vector<vtkSmartPointer<vtkObject>> Keep;
  int Frames = 0; ///< frames the window rendered (its EndEvent)

  View(bool traced, vtkInteractorObserver* style)
  {
    this->Window->SetSize(W, H);
    this->Window->SetMultiSamples(0);
    this->Window->SetWindowName(traced ? "vtkrt: traced" : "vtkrt: raster");
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.32, 0.34, 0.43);
    this->BuildScene();
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Zoom(1.5);
    if (traced)
    {
      this->Renderer->SetPass(this->Pass);
    }
    this->FrameCounter->SetClientData(&this->Frames);
    this->FrameCounter->SetCallback(
      [](vtkObject*, unsigned long, void* frames, void*) { ++*static_cast<int*>(frames); });
    this->Window->AddObserver(vtkCommand::EndEvent, this->FrameCounter);
    this->Interactor->SetRenderWindow(this->Window);
    this->Interactor->SetInteractorStyle(style);
    this->Interactor->Initialize();
    Check(this->Window->IsA("vtkXOpenGLRenderWindow") &&
        this->Interactor->IsA("vtkXRenderWindowInteractor"),
      std::string("an X11 window and interactor (") + this->Window->GetClassName() + ", " +
        this->Interactor->GetClassName() + ")");
    this->Window->Render();
    // The X events of the new window (map, expose, configure), as an event
    // loop would take them; ProcessEvents never waits.
    this->Interactor->ProcessEvents();
  }

  ~View()
  {
    this->Renderer->SetPass(nullptr);
    this->Window->Finalize();
  }

  void BuildScene()
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(32);
    this->Add(sphere->GetOutputPort());
    vtkNew<vtkCubeSource> cube;
    cube->SetCenter(2.5, 0.3, 0.0);
    this->Add(cube->GetOutputPort());
    this->Actors.back()->GetProperty()->SetColor(0.9, 0.7, 0.5);
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(-3, -2, 0);
    plane->SetPoint1(-1, -2, 0);
    plane->SetPoint2(-3, 2, 0);
    plane->SetResolution(3, 4);
    vtkNew<vtkSphereSource> glyph;
    glyph->SetRadius(0.2);
    glyph->SetThetaResolution(24);
    glyph->SetPhiResolution(24);
    vtkNew<vtkGlyph3DMapper> glyphs;
    glyphs->SetInputConnection(plane->GetOutputPort());
    glyphs->SetSourceConnection(glyph->GetOutputPort());
    glyphs->ScalingOff();
    this->AddMapper(glyphs);
    this->Actors.back()->GetProperty()->SetColor(0.5, 0.8, 0.6);
    this->Keep.insert(this->Keep.end(), { sphere.Get(), cube.Get(), plane.Get(), glyph.Get() });
  }

  void Add(vtkAlgorithmOutput* port)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(port);
    this->AddMapper(mapper);
  }

  void AddMapper(vtkMapper* mapper)
  {
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    this->Renderer->AddActor(actor);
    this->Actors.push_back(actor);
  }

  int IndexOf(vtkObjectBase* prop) const
  {
    for (std::size_t i = 0; i < this->Actors.size(); ++i)
    {
      if (this->Actors[i] == prop)
      {
        return static_cast<int>(i);
      }
    }
    return -1;
  }

  /// Display coordinates of a world point.
  std::array<int, 2> Project(const double p[3])
  {
    this->Renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
    this->Renderer->WorldToDisplay();
    const double* d = this->Renderer->GetDisplayPoint();
    return { { static_cast<int>(std::floor(d[0])), static_cast<int>(std::floor(d[1])) } };
  }

  /// One synthesized event at (x, y), as vtkXRenderWindowInteractor sends it.
  void Event(unsigned long event, int x, int y, int ctrl = 0, int shift = 0, char key = 0,
    const char* keysym = nullptr)
  {
    this->Interactor->SetEventInformation(x, y, ctrl, shift, key, 0, keysym);
    this->Interactor->InvokeEvent(event, nullptr);
  }

  /// A key typed at (x, y): press, char, release.
  void Key(char key, int x, int y)
  {
    const char keysym[2] = { key, '\0' };
    this->Event(vtkCommand::KeyPressEvent, x, y, 0, 0, key, keysym);
    this->Event(vtkCommand::CharEvent, x, y, 0, 0, key, keysym);
    this->Event(vtkCommand::KeyReleaseEvent, x, y, 0, 0, key, keysym);
  }

  /// A press at `from`, `steps` moves to `to`, a release there.
  void Drag(unsigned long press, unsigned long release, std::array<int, 2> from,
    std::array<int, 2> to, int ctrl = 0, int shift = 0, int steps = 5)
  {
    this->Event(press, from[0], from[1], ctrl, shift);
    for (int s = 1; s <= steps; ++s)
    {
      this->Event(vtkCommand::MouseMoveEvent, from[0] + (to[0] - from[0]) * s / steps,
        from[1] + (to[1] - from[1]) * s / steps, ctrl, shift);
    }
    this->Event(release, to[0], to[1], ctrl, shift);
  }
};

/// The frame the traced window shows is raster's, up to shading: RGB RMSE
/// at most `maxError`/255, at most 2% of the pixels off by more than 24/255
/// (edges); the pass traced the mesh, the cube and the glyphs. Returns the
/// image.
vtkSmartPointer<vtkImageData> SameImage(
  View& raster, View& traced, const std::string& stage, double maxError = 4.0)
{
  auto r = Grab(raster.Window);
  auto t = Grab(traced.Window);
  const double rmse = RootMeanSquareError(r, t);
  const long differing = CountDifferingPixels(t, r, 24);
  const long covered = CountForegroundPixels(t, traced.Renderer->GetBackground());
  const bool same = rmse >= 0.0 && rmse <= maxError && differing <= W * H / 50;
  std::ostringstream what;
  what << stage << ": the traced frame is raster's (RGB RMSE " << rmse << ", " << differing
       << " pixels off by > 24, " << covered << " foreground)";
  Check(same && covered > W * H / 40, what.str());
  if (!same)
  {
    const std::string name = std::string(VTKRT_TEMP_DIR) + "/window_X11Interaction_";
    WritePNG(r, name + "raster.png");
    WritePNG(t, name + "traced.png");
  }
  Check(traced.Pass->GetNumberOfTracedProps() == 3,
    stage + ": the pass traced the mesh, the cube and the glyphs (" +
      std::to_string(traced.Pass->GetNumberOfTracedProps()) + ")");
  return t;
}

/// Largest absolute difference of two 3-vectors.
double MaxDifference(const double* a, const double* b)
{
  return std::max({ std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2]) });
}

/// The cameras of the two views agree to 1e-9.
void SameCamera(View& raster, View& traced, const std::string& stage)
{
  vtkCamera* r = raster.Renderer->GetActiveCamera();
  vtkCamera* t = traced.Renderer->GetActiveCamera();
  const double d = std::max({ MaxDifference(r->GetPosition(), t->GetPosition()),
    MaxDifference(r->GetFocalPoint(), t->GetFocalPoint()),
    MaxDifference(r->GetViewUp(), t->GetViewUp()),
    std::abs(r->GetClippingRange()[0] - t->GetClippingRange()[0]),
    std::abs(r->GetClippingRange()[1] - t->GetClippingRange()[1]) });
  std::ostringstream what;
  what << stage << ": the camera is raster's (position, focal point, view up, clipping range;"
       << " largest difference " << d << ")";
  Check(d <= 1e-9, what.str());
}

/// A camera as the test compares it: position, focal point, view up.
std::array<double, 9> CameraState(View& view)
{
  vtkCamera* c = view.Renderer->GetActiveCamera();
  std::array<double, 9> s;
  std::copy(c->GetPosition(), c->GetPosition() + 3, s.begin());
  std::copy(c->GetFocalPoint(), c->GetFocalPoint() + 3, s.begin() + 3);
  std::copy(c->GetViewUp(), c->GetViewUp() + 3, s.begin() + 6);
  return s;
}

/// TrackballCamera: rotate, zoom (wheel), pan, dolly, spin, then 'r'.
void TestCamera()
{
  vtkNew<vtkInteractorStyleTrackballCamera> rasterStyle, tracedStyle;
  View raster(false, rasterStyle);
  View traced(true, tracedStyle);
  vtkSmartPointer<vtkImageData> previous = SameImage(raster, traced, "first frame");
  SameCamera(raster, traced, "first frame");

  struct Stage
  {
    const char* Name;
    void (*Play)(View&);
  };
  const Stage stages[] = {
    { "rotate (left drag)",
      [](View& v) {
        v.Drag(vtkCommand::LeftButtonPressEvent, vtkCommand::LeftButtonReleaseEvent, { 150, 100 },
          { 190, 125 });
      } },
    { "zoom (wheel forward 3, backward 1)",
      [](View& v) {
        for (unsigned long e : { vtkCommand::MouseWheelForwardEvent,
               vtkCommand::MouseWheelForwardEvent, vtkCommand::MouseWheelForwardEvent,
               vtkCommand::MouseWheelBackwardEvent })
        {
          v.Event(e, 150, 100);
        }
      } },
    { "pan (middle drag)",
      [](View& v) {
        v.Drag(vtkCommand::MiddleButtonPressEvent, vtkCommand::MiddleButtonReleaseEvent,
          { 150, 100 }, { 120, 85 });
      } },
    { "dolly (right drag)",
      [](View& v) {
        v.Drag(vtkCommand::RightButtonPressEvent, vtkCommand::RightButtonReleaseEvent,
          { 150, 100 }, { 150, 80 });
      } },
    { "spin (ctrl + left drag)",
      [](View& v) {
        v.Drag(vtkCommand::LeftButtonPressEvent, vtkCommand::LeftButtonReleaseEvent, { 220, 150 },
          { 180, 170 }, 1);
      } },
    { "reset ('r' key)", [](View& v) { v.Key('r', 150, 100); } },
  };
  for (const Stage& stage : stages)
  {
    const std::array<double, 9> before = CameraState(traced);
    const int framesBefore = traced.Frames;
    const int rasterFramesBefore = raster.Frames;
    stage.Play(raster);
    stage.Play(traced);
    const std::array<double, 9> after = CameraState(traced);
    Check(MaxDifference(before.data(), after.data()) + MaxDifference(&before[3], &after[3]) +
          MaxDifference(&before[6], &after[6]) > 1e-3,
      std::string(stage.Name) + ": the camera moved");
    SameCamera(raster, traced, stage.Name);
    Check(traced.Frames > framesBefore &&
        traced.Frames - framesBefore == raster.Frames - rasterFramesBefore,
      std::string(stage.Name) + ": the interactor rendered the traced window as often as raster's (" +
        std::to_string(traced.Frames - framesBefore) + " frames)");
    vtkSmartPointer<vtkImageData> now = SameImage(raster, traced, stage.Name);
    Check(CountDifferingPixels(now, previous, 24) > W * H / 100,
      std::string(stage.Name) + ": the traced frame changed");
    Check(traced.Pass->GetLastBVHBuilds() == 0 && traced.Pass->GetLastGeometryBytesUploaded() == 0,
      std::string(stage.Name) + ": no BVH build, no geometry upload");
    previous = now;
  }
  Check(traced.Frames == raster.Frames,
    "as many frames traced as rasterized (" + std::to_string(traced.Frames) + ")");
  NoVTKOutput("TrackballCamera");
}

/// The actors' matrices: mesh, cube, glyphs.
std::vector<std::array<double, 16>> Matrices(View& view)
{
  std::vector<std::array<double, 16>> out;
  for (vtkActor* actor : view.Actors)
  {
    std::array<double, 16> m;
    vtkMatrix4x4::DeepCopy(m.data(), actor->GetMatrix());
    out.push_back(m);
  }
  return out;
}

double MaxDifference(const std::array<double, 16>& a, const std::array<double, 16>& b)
{
  double d = 0.0;
  for (int i = 0; i < 16; ++i)
  {
    d = std::max(d, std::abs(a[i] - b[i]));
  }
  return d;
}

/// The world points the tests press on: the mesh, the cube, a glyph (their
/// front, as the camera first looks down -z) and an empty pixel.
const double Targets[4][3] = { { 0, 0, 0.5 }, { 2.5, 0.3, 0.5 }, { -1.667, 0, 0.2 },
  { 0, 1.9, 0 } };
const char* const TargetNames[4] = { "the mesh", "the cube", "a glyph", "an empty pixel" };

/// One drag of the TrackballActor cases: `Press`/`Release` buttons with
/// modifiers, from target `Target` by `By` pixels; it moves actor `Moved`.
struct ActorDrag
{
  const char* Name;
  int Moved; ///< index of the actor the drag moves, -1 none
  unsigned long Press, Release;
  int Target, Ctrl, Shift;
  std::array<int, 2> By;
};

const ActorDrag ActorDrags[] = {
  { "left drag from an empty pixel", -1, vtkCommand::LeftButtonPressEvent,
    vtkCommand::LeftButtonReleaseEvent, 3, 0, 0, { 30, 20 } },
  { "rotate the cube (left drag)", 1, vtkCommand::LeftButtonPressEvent,
    vtkCommand::LeftButtonReleaseEvent, 1, 0, 0, { 30, 20 } },
  { "pan the mesh (middle drag)", 0, vtkCommand::MiddleButtonPressEvent,
    vtkCommand::MiddleButtonReleaseEvent, 0, 0, 0, { 25, -15 } },
  { "scale the glyphs (right drag)", 2, vtkCommand::RightButtonPressEvent,
    vtkCommand::RightButtonReleaseEvent, 2, 0, 0, { 0, 20 } },
  { "spin the cube (ctrl + left drag)", 1, vtkCommand::LeftButtonPressEvent,
    vtkCommand::LeftButtonReleaseEvent, 1, 1, 0, { -20, 25 } },
  { "move the glyphs (shift + left drag)", 2, vtkCommand::LeftButtonPressEvent,
    vtkCommand::LeftButtonReleaseEvent, 2, 0, 1, { 20, 10 } },
};

/// The drag moved its actor only, as it moved raster's, and both windows
/// rendered as many frames (none when nothing was picked).
void CheckDrag(View& raster, View& traced, const ActorDrag& drag,
  const std::vector<std::array<double, 16>>& before, int frames, int rasterFrames)
{
  const auto after = Matrices(traced);
  const auto rasterAfter = Matrices(raster);
  for (int a = 0; a < 3; ++a)
  {
    const std::string what = std::string(drag.Name) + ": " + TargetNames[a];
    const bool moved = MaxDifference(before[a], after[a]) > 1e-3;
    Check(moved == (a == drag.Moved) && (moved || before[a] == after[a]),
      what + (a == drag.Moved ? " moved" : " did not move"));
    Check(MaxDifference(after[a], rasterAfter[a]) <= 1e-9, what + ": its matrix is raster's");
  }
  Check(frames == rasterFrames && (frames > 0) == (drag.Moved >= 0),
    std::string(drag.Name) + ": the interactor rendered the traced window as often as raster's (" +
      std::to_string(frames) + " frames)");
}

/// TrackballActor: a press picks the actor under it (the style's cell
/// picker) and the drag moves that actor only, as with raster; the traced
/// frames show each move. With progressive accumulation, each move
/// restarts the average, and still frames add up without a stale image.
void TestActor(bool accumulate)
{
  vtkNew<vtkInteractorStyleTrackballActor> rasterStyle, tracedStyle;
  View raster(false, rasterStyle);
  View traced(true, tracedStyle);
  traced.Pass->SetProgressiveAccumulation(accumulate);
  traced.Interactor->Render();
  vtkSmartPointer<vtkImageData> previous = SameImage(raster, traced, "first frame");
  std::array<std::array<int, 2>, 4> at;
  for (int t = 0; t < 4; ++t)
  {
    at[t] = raster.Project(Targets[t]);
  }
  for (const ActorDrag& drag : ActorDrags)
  {
    const std::string name = drag.Name;
    const auto before = Matrices(traced);
    const int framesBefore = traced.Frames;
    const int rasterFramesBefore = raster.Frames;
    const int accumulatedBefore = traced.Pass->GetAccumulatedFrames();
    for (View* view : { &raster, &traced })
    {
      const std::array<int, 2> from = at[drag.Target];
      view->Drag(drag.Press, drag.Release, from, { from[0] + drag.By[0], from[1] + drag.By[1] },
        drag.Ctrl, drag.Shift);
    }
    CheckDrag(raster, traced, drag, before, traced.Frames - framesBefore,
      raster.Frames - rasterFramesBefore);
    vtkSmartPointer<vtkImageData> now = SameImage(raster, traced, name);
    const long changed = CountDifferingPixels(now, previous, 24);
    Check(drag.Moved >= 0 ? changed > W * H / 200 : changed == 0,
      name + (drag.Moved >= 0 ? ": the traced frame shows the move (" :
        ": the traced frame is unchanged (") + std::to_string(changed) + " pixels changed)");
    Check(traced.Pass->GetLastBVHBuilds() == 0 && traced.Pass->GetLastGeometryBytesUploaded() == 0,
      name + ": no BVH build, no geometry upload");
    if (accumulate)
    {
      // A move restarts the average: the drag's last frame and the release's.
      const int accumulated = traced.Pass->GetAccumulatedFrames();
      Check(accumulated == (drag.Moved >= 0 ? 2 : accumulatedBefore),
        name + ": frames averaged " + std::to_string(accumulated));
      for (int k = 0; k < 3; ++k)
      {
        raster.Interactor->Render();
        traced.Interactor->Render();
      }
      Check(traced.Pass->GetAccumulatedFrames() == accumulated + 3,
        name + ": three still frames add to the average");
      // Averaged sub-pixel samples smooth the edges raster leaves aliased.
      now = SameImage(raster, traced, name + ", three still frames later", 6.0);
    }
    previous = now;
  }
  NoVTKOutput(accumulate ? "TrackballActor, accumulating" : "TrackballActor");
}

/// The actor a vtkPropPicker picks in an observer of LeftButtonPressEvent
/// (as vedo and other applications pick on click).
struct ClickPicker
{
  View* Target = nullptr;
  vtkNew<vtkPropPicker> Picker;
  int Picked = -2; ///< index in Target's actors, -1 nothing, -2 no click seen

  static void OnPress(vtkObject* caller, unsigned long, void* self, void*)
  {
    auto* p = static_cast<ClickPicker*>(self);
    auto* rwi = static_cast<vtkRenderWindowInteractor*>(caller);
    const int* xy = rwi->GetEventPosition();
    p->Picked = p->Picker->PickProp(xy[0], xy[1], p->Target->Renderer)
      ? p->Target->IndexOf(p->Picker->GetViewProp())
      : -1;
  }
};

/// Picking on click through the X11 interactor: a vtkPropPicker observer
/// and the style's 'p' key (the interactor's vtkPropPicker, then an outline
/// around the picked prop) pick what raster picks; the frames between show
/// the scene, not the selector's ids.
void TestPick()
{
  vtkNew<vtkInteractorStyleTrackballCamera> rasterStyle, tracedStyle;
  View raster(false, rasterStyle);
  View traced(true, tracedStyle);
  ClickPicker pickers[2];
  vtkNew<vtkCallbackCommand> observers[2];
  View* views[2] = { &raster, &traced };
  for (int v = 0; v < 2; ++v)
  {
    pickers[v].Target = views[v];
    observers[v]->SetClientData(&pickers[v]);
    observers[v]->SetCallback(ClickPicker::OnPress);
    views[v]->Interactor->AddObserver(vtkCommand::LeftButtonPressEvent, observers[v], 1.0);
  }
  const vtkSmartPointer<vtkImageData> first = SameImage(raster, traced, "first frame");
  for (int t = 0; t < 4; ++t)
  {
    const std::array<int, 2> xy = raster.Project(Targets[t]);
    const std::string what = std::string("click on ") + TargetNames[t];
    for (View* view : views)
    {
      view->Event(vtkCommand::LeftButtonPressEvent, xy[0], xy[1]);
      view->Event(vtkCommand::LeftButtonReleaseEvent, xy[0], xy[1]);
    }
    const int expected = t < 3 ? t : -1;
    Check(pickers[0].Picked == expected, what + ": raster's vtkPropPicker picks it");
    Check(pickers[1].Picked == expected, what + ": the pass's vtkPropPicker picks it (" +
        std::to_string(pickers[1].Picked) + ")");
    const vtkSmartPointer<vtkImageData> now = SameImage(raster, traced, what);
    Check(CountDifferingPixels(now, first, 0) == 0,
      what + ": the frame after the click is the scene as before");
  }

  // 'p': the interactor's own picker, then the style outlines the prop.
  const std::array<int, 2> cube = raster.Project(Targets[1]);
  for (View* view : views)
  {
    view->Key('p', cube[0], cube[1]);
  }
  Check(raster.Renderer->GetActors()->GetNumberOfItems() == 4 &&
      traced.Renderer->GetActors()->GetNumberOfItems() == 4,
    "'p' on the cube: the style adds its outline, as with raster");
  auto pathOf = [](View& view) {
    auto* picker = vtkAbstractPropPicker::SafeDownCast(view.Interactor->GetPicker());
    return picker ? picker->GetPath() : nullptr;
  };
  vtkAssemblyPath* rasterPath = pathOf(raster);
  vtkAssemblyPath* tracedPath = pathOf(traced);
  Check(rasterPath && tracedPath &&
      raster.IndexOf(rasterPath->GetFirstNode()->GetViewProp()) == 1 &&
      traced.IndexOf(tracedPath->GetFirstNode()->GetViewProp()) == 1,
    "'p' on the cube: the interactor's picker picks the cube, as raster's");
  const vtkSmartPointer<vtkImageData> outlined = SameImage(raster, traced, "'p' on the cube");
  // The outline's edges lie on the cube's faces: raster draws them over its
  // own coincident triangles, so must the pass over the traced ones.
  const unsigned char red[3] = { 255, 0, 0 };
  const long rasterOutline = CountColor(Grab(raster.Window), red);
  const long tracedOutline = CountColor(outlined, red);
  Check(rasterOutline > 60 && tracedOutline >= rasterOutline,
    "'p' on the cube: the outline shows over the traced cube (" + std::to_string(tracedOutline) +
      " pixels) as over raster's (" + std::to_string(rasterOutline) + ")");
  const std::array<int, 2> empty = raster.Project(Targets[3]);
  for (View* view : views)
  {
    view->Key('p', empty[0], empty[1]);
  }
  const vtkSmartPointer<vtkImageData> cleared = SameImage(raster, traced, "'p' on an empty pixel");
  Check(traced.Renderer->GetActors()->GetNumberOfItems() == 3 &&
      CountDifferingPixels(cleared, first, 0) == 0,
    "'p' on an empty pixel: the outline is gone, the frame is the first one");
  NoVTKOutput("picking");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    std::cout << "SKIP: no X display (DISPLAY unset); run under xvfb-run\n";
    return 77;
  }
  return RunCase(argc, argv, { { "Camera", TestCamera }, { "Actor", [] { TestActor(false); } },
      { "ActorAccumulating", [] { TestActor(true); } }, { "Pick", TestPick } });
}
