// Translucent props the pass leaves to raster (TraceTranslucency off) are
// drawn as the renderer draws them: depth peeling with the renderer's settings, order-independent
// blending without; also through a user's vtkRenderStepsPass delegate. The
// renderer's FXAA reaches the traced image as it reaches raster's.
// Each case compares with VTK's raster of the same scene (RGB RMSE; blending
// in actor order instead gives 10 with peeling and 6.7 without).
#include "vtkrtPassTestUtils.h"

#include "vtkActorCollection.h"
#include "vtkLightsPass.h"
#include "vtkOpaquePass.h"
#include "vtkOutlineSource.h"
#include "vtkOverlayPass.h"
#include "vtkRenderPassCollection.h"
#include "vtkSequencePass.h"
#include "vtkCubeSource.h"
#include "vtkLookupTable.h"
#include "vtkDualDepthPeelingPass.h"
#include "vtkPropAssembly.h"
#include "vtkRenderStepsPass.h"
#include "vtkScalarBarActor.h"
#include "vtkSphereRepresentation.h"
#include "vtkTranslucentPass.h"
#include "vtkrtImageRegression.h"

#include <cmath>
#include <sstream>

using namespace vtkrtPassTest;

namespace
{
/// Three overlapping translucent spheres in front of, and cutting into, an
/// opaque one (the only prop the pass traces).
struct Scene
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(320, 240);
  vtkNew<vtkRenderer> Renderer;

  Scene(bool peeling, int maximumPeels)
  {
    this->Window->AddRenderer(this->Renderer);
    this->Window->SetAlphaBitPlanes(1);
    this->Renderer->SetBackground(0.1, 0.1, 0.15);
    this->Renderer->SetUseDepthPeeling(peeling);
    this->Renderer->SetMaximumNumberOfPeels(maximumPeels);
    this->Renderer->SetOcclusionRatio(0.0);
    // The translucent ones nearest first: blending in actor order is wrong.
    const double spheres[4][7] = { { 0.0, 0.0, -0.8, 1.2, 0.9, 0.9, 0.9 },
      { 0.0, -0.4, 0.9, 0.7, 0.2, 0.3, 1.0 }, { 0.5, 0.2, 0.5, 0.8, 0.2, 1.0, 0.2 },
      { -0.5, 0.0, 0.3, 0.8, 1.0, 0.2, 0.2 } };
    for (int i = 0; i < 4; ++i)
    {
      const double* s = spheres[i];
      vtkSmartPointer<vtkActor> actor = SphereActor(s[0], s[1], s[2], s[3], 48);
      actor->GetProperty()->SetColor(s[4], s[5], s[6]);
      actor->GetProperty()->SetOpacity(i == 0 ? 1.0 : 0.4);
      this->Renderer->AddActor(actor);
    }
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(20);
    this->Renderer->GetActiveCamera()->Zoom(1.6);
  }
};

/// Checks the RMSE; on failure writes both images and the raster one as
/// <name>.raster.png beside the usual failure and diff images.
void CheckClose(const std::string& name, vtkImageData* raster, vtkImageData* traced, double maxRmse)
{
  const double rmse = RootMeanSquareError(raster, traced);
  std::ostringstream what;
  what << name << ": RGB RMSE " << rmse << " against raster (<= " << maxRmse << ")";
  Check(rmse <= maxRmse, what.str());
  if (rmse > maxRmse)
  {
    WriteFailedImages(name, raster, traced);
  }
}

/// Raster's image and the pass's (default delegate, translucent actors
/// left to it) of the same scene.
RasterAndTraced Compare(const std::string& name, bool peeling, int peels, double maxRmse)
{
  Scene scene(peeling, peels);
  RasterAndTraced frames;
  scene.Window->Render();
  frames.Raster = Grab(scene.Window);
  frames.Pass = vtkSmartPointer<vtkRayTracePass>::New();
  frames.Pass->TraceTranslucencyOff();
  scene.Renderer->SetPass(frames.Pass);
  scene.Window->Render();
  frames.Traced = Grab(scene.Window);
  Check(frames.Pass->GetNumberOfTracedProps() == 1, name + ": the opaque sphere is traced");
  CheckClose(name, frames.Raster, frames.Traced, maxRmse);
  NoVTKOutput(name);
  return frames;
}

void TestDepthPeeling()
{
  Compare("DepthPeeling", true, 20, 3.0);
}

void TestBlended()
{
  Compare("Blended", false, 4, 3.0);
}

/// MaximumNumberOfPeels reaches the peeling: one peel differs from twenty,
/// and matches raster's one peel.
void TestPeelCount()
{
  RasterAndTraced one = Compare("OnePeel", true, 1, 3.0);
  RasterAndTraced many = Compare("TwentyPeels", true, 20, 3.0);
  Check(RootMeanSquareError(one.Traced, many.Traced) > 1.0, "one peel and twenty peels differ");
}

/// A user's vtkRenderStepsPass whose translucent step is dual depth peeling
/// (as VTK's documentation shows), given as the delegate.
void TestRenderStepsDelegate()
{
  Scene scene(true, 20);
  scene.Window->Render();
  auto raster = Grab(scene.Window);
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkDualDepthPeelingPass> peeling;
  vtkNew<vtkTranslucentPass> translucent;
  peeling->SetTranslucentPass(translucent);
  peeling->SetMaximumNumberOfPeels(20);
  peeling->SetOcclusionRatio(0.0);
  steps->SetTranslucentPass(peeling);
  vtkNew<vtkRayTracePass> pass;
  pass->TraceTranslucencyOff();
  pass->SetDelegatePass(steps);
  scene.Renderer->SetPass(pass);
  scene.Window->Render();
  Check(pass->GetNumberOfTracedProps() == 1, "RenderStepsDelegate: the opaque sphere is traced");
  CheckClose("RenderStepsDelegate", raster, Grab(scene.Window), 3.0);
  // nullptr brings back the default delegate, which peels as the renderer says.
  pass->SetDelegatePass(nullptr);
  scene.Window->Render();
  Check(pass->GetDelegatePass() && pass->GetDelegatePass()->IsA("vtkRayTraceRasterSteps"),
    "RenderStepsDelegate: nullptr restores the default delegate");
  CheckClose("RenderStepsDelegate, default restored", raster, Grab(scene.Window), 3.0);
  NoVTKOutput("RenderStepsDelegate");
}
/// The renderer's UseFXAA applies to the traced image as to raster's: with
/// the translucent spheres left to raster and with every visible prop traced
/// (nothing left for the raster steps, which still run for the FXAA).
void TestFXAA()
{
  for (bool othersLeft : { true, false })
  {
    const std::string name = othersLeft ? "FXAA" : "FXAATracedOnly";
    Scene scene(false, 4);
    vtkActorCollection* actors = scene.Renderer->GetActors();
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor())
    {
      actor->SetVisibility(othersLeft || actor->GetProperty()->GetOpacity() >= 1.0);
    }
    vtkSmartPointer<vtkImageData> images[2][2]; // [traced?][fxaa?]
    for (int traced = 0; traced < 2; ++traced)
    {
      vtkNew<vtkRayTracePass> pass;
      pass->TraceTranslucencyOff();
      scene.Renderer->SetPass(traced ? pass.Get() : nullptr);
      for (int fxaa = 0; fxaa < 2; ++fxaa)
      {
        scene.Renderer->SetUseFXAA(fxaa == 1);
        scene.Window->Render();
        images[traced][fxaa] = Grab(scene.Window);
      }
    }
    const double rasterChange = RootMeanSquareError(images[0][0], images[0][1]);
    const double tracedChange = RootMeanSquareError(images[1][0], images[1][1]);
    std::ostringstream what;
    what << name << ": FXAA changes raster's image by RMSE " << rasterChange
         << " and the traced one by " << tracedChange << " (both > 0.1)";
    Check(rasterChange > 0.1 && tracedChange > 0.1, what.str());
    // Nearer raster's FXAA image with FXAA than without (where raster and
    // pass agree exactly, the traced FXAA image is raster's).
    const double with = RootMeanSquareError(images[0][1], images[1][1]);
    const double without = RootMeanSquareError(images[0][1], images[1][0]);
    std::ostringstream nearer;
    nearer << name << ": the traced FXAA image is RMSE " << with << " from raster's, "
           << "the traced image without FXAA " << without << " (at most half)";
    Check(with <= 0.5 * without, nearer.str());
    CheckClose(name, images[0][1], images[1][1], 3.0);
    NoVTKOutput(name);
  }
}
/// A translucent blue unit sphere (opacity 0.4, traced) about the origin.
void AddShell(vtkRenderer* ren)
{
  vtkSmartPointer<vtkActor> shell = SphereActor(0.0, 0.0, 0.0, 1.0, 64);
  shell->GetProperty()->SetColor(0.3, 0.5, 1.0);
  shell->GetProperty()->SetOpacity(0.4);
  ren->AddActor(shell);
}

/// Opaque props raster draws that are not vtkProp3Ds, inside a traced
/// translucent shell: a 3D widget's representation and a vtkPropAssembly of
/// an actor show through the shell as under raster's peeling (they were
/// drawn over it); a scalar bar, 2D, stays over everything.
void TestOpaqueWidgetsInside()
{
  auto win = MakeWindow(320, 240);
  vtkNew<vtkRenderer> ren;
  SetUpDepthPeeling(win, ren);
  AddShell(ren);
  vtkNew<vtkSphereRepresentation> handle;
  handle->SetRenderer(ren);
  double handleBounds[6] = { -0.6, -0.1, -0.25, 0.25, -0.25, 0.25 };
  handle->PlaceWidget(handleBounds);
  handle->SetRepresentationToSurface();
  ren->AddViewProp(handle);
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(0.4, 0.0, 0.0);
  cube->SetXLength(0.35);
  cube->SetYLength(0.35);
  cube->SetZLength(0.35);
  cube->Update();
  vtkSmartPointer<vtkActor> cubeActor = MeshActor(cube->GetOutput());
  cubeActor->GetProperty()->SetColor(1.0, 0.8, 0.2);
  cubeActor->GetProperty()->SetInterpolationToPBR(); // left to raster, and its assembly with it
  vtkNew<vtkPropAssembly> group;
  group->AddPart(cubeActor);
  ren->AddViewProp(group);
  // A 2D prop that draws in the opaque pass, over the shell: the trace
  // would cover it if it were drawn before.
  vtkNew<vtkScalarBarActor> bar;
  vtkNew<vtkLookupTable> table;
  table->Build();
  bar->SetLookupTable(table);
  bar->SetPosition(0.4, 0.2);
  bar->SetWidth(0.15);
  bar->SetHeight(0.6);
  ren->AddViewProp(bar);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(20);
  ren->GetActiveCamera()->Elevation(15);
  ren->ResetCameraClippingRange();
  RasterAndTraced frames = RenderRasterThenTraced(win, ren);
  const double rmse = RootMeanSquareError(frames.Raster, frames.Traced);
  const long differing = CountDifferingPixels(frames.Raster, frames.Traced, 40);
  std::ostringstream what;
  what << "opaque widget and prop assembly inside a traced shell: " << frames.Pass->GetNumberOfTracedProps()
       << " prop traced (1), RGB RMSE " << rmse << " (<= 3), " << differing << " pixels off by > 40";
  const bool ok = frames.Pass->GetNumberOfTracedProps() == 1 && rmse <= 3.0;
  Check(ok, what.str());
  if (!ok)
  {
    WriteFailedImages("Translucency_OpaqueWidgetsInside", frames.Raster, frames.Traced);
  }
  NoVTKOutput("OpaqueWidgetsInside");
}
/// The delegate the pass is given: a vtkRenderStepsPass with dual depth
/// peeling, or a vtkSequencePass of VTK's steps (a pass of another kind).
vtkSmartPointer<vtkRenderPass> UserDelegate(bool renderSteps)
{
  vtkNew<vtkTranslucentPass> translucent;
  vtkNew<vtkDualDepthPeelingPass> peeling;
  peeling->SetTranslucentPass(translucent);
  peeling->SetMaximumNumberOfPeels(200);
  peeling->SetOcclusionRatio(0.0);
  if (renderSteps)
  {
    auto steps = vtkSmartPointer<vtkRenderStepsPass>::New();
    steps->SetTranslucentPass(peeling);
    return steps;
  }
  vtkNew<vtkRenderPassCollection> passes;
  vtkNew<vtkLightsPass> lights;
  vtkNew<vtkOpaquePass> opaque;
  vtkNew<vtkOverlayPass> overlay;
  passes->AddItem(lights);
  passes->AddItem(opaque);
  passes->AddItem(peeling);
  passes->AddItem(overlay);
  auto sequence = vtkSmartPointer<vtkSequencePass>::New();
  sequence->SetPasses(passes);
  return sequence;
}

/// Opaque raster props (points, an outline) inside a traced translucent
/// shell, drawn by a user's delegate: they show through the shell as under
/// raster's peeling (the delegate drew them over it, RMSE 8.7 in a trial).
void TestUserDelegateBelow()
{
  for (bool renderSteps : { true, false })
  {
    const std::string name = renderSteps ? "UserDelegateBelow, vtkRenderStepsPass" : "UserDelegateBelow, vtkSequencePass";
    auto win = MakeWindow(320, 240);
    vtkNew<vtkRenderer> ren;
    SetUpDepthPeeling(win, ren);
    AddShell(ren);
    ren->AddActor(PointCloudActor(-0.7, 0.035, 0.2, 6.0));
    vtkNew<vtkOutlineSource> outline;
    outline->SetBounds(-0.45, 0.45, -0.45, 0.45, -0.45, 0.45);
    outline->Update();
    vtkSmartPointer<vtkActor> box = MeshActor(outline->GetOutput());
    box->GetProperty()->SetLineWidth(2.0);
    box->GetProperty()->SetColor(1.0, 0.3, 0.3);
    ren->AddActor(box);
    ren->ResetCamera();
    ren->GetActiveCamera()->Azimuth(20);
    ren->GetActiveCamera()->Elevation(15);
    ren->ResetCameraClippingRange();
    win->Render();
    vtkSmartPointer<vtkImageData> raster = Grab(win);
    vtkNew<vtkRayTracePass> pass;
    pass->SetDelegatePass(UserDelegate(renderSteps));
    ren->SetPass(pass);
    win->Render();
    vtkSmartPointer<vtkImageData> traced = Grab(win);
    const double rmse = RootMeanSquareError(raster, traced);
    const long differing = CountDifferingPixels(raster, traced, 40);
    std::ostringstream what;
    what << name << ": " << pass->GetNumberOfTracedProps() << " prop traced (1), RGB RMSE " << rmse
         << " (<= 3), " << differing << " pixels off by > 40";
    const bool ok = pass->GetNumberOfTracedProps() == 1 && rmse <= 3.0 && differing <= 20;
    Check(ok, what.str() + " (<= 20)");
    if (!ok)
    {
      WriteFailedImages(renderSteps ? "Translucency_UserDelegateBelowSteps" : "Translucency_UserDelegateBelowSequence",
        raster, traced);
    }
    NoVTKOutput(name);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "DepthPeeling", TestDepthPeeling }, { "Blended", TestBlended },
      { "PeelCount", TestPeelCount }, { "RenderStepsDelegate", TestRenderStepsDelegate },
      { "FXAA", TestFXAA }, { "OpaqueWidgetsInside", TestOpaqueWidgetsInside },
      { "UserDelegateBelow", TestUserDelegateBelow } });
}
