// vtkRayTracePass: what raster draws around the trace, through the delegate:
// the opaque 3D props under traced translucent layers before it, the rest
// after it (split by steps for the default delegate and a
// vtkRenderStepsPass, by props for a delegate of another kind).
#include "vtkRayTracePassInternals.h"

#include <algorithm>
#include <iterator>

namespace
{
/// `out` (of s's renderer) for `props`, with s's framebuffer and keys.
void StateFor(vtkRenderState& out, const vtkRenderState* s, std::vector<vtkProp*>& props)
{
  out.SetPropArrayAndCount(props.data(), static_cast<int>(props.size()));
  out.SetFrameBuffer(s->GetFrameBuffer());
  out.SetRequiredKeys(s->GetRequiredKeys());
}
/// Whether `prop` draws 3D geometry only, so that raster may draw its opaque
/// parts before the trace (their depth ends the rays): 3D props but
/// volumes, assemblies of such props, and other props with 3D bounds (3D
/// widgets' representations). 2D props draw their opaque parts over
/// everything, which the trace would cover.
bool DrawsOnly3D(vtkProp* prop)
{
  if (prop->IsA("vtkVolume") || prop->IsA("vtkActor2D"))
  {
    return false;
  }
  if (prop->IsA("vtkProp3D"))
  {
    return true;
  }
  if (prop->IsA("vtkPropAssembly"))
  {
    const std::vector<vtkProp*> parts = PropAssemblyParts(prop);
    return !parts.empty() && std::all_of(parts.begin(), parts.end(), DrawsOnly3D);
  }
  const double* b = prop->GetBounds();
  return b && b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5];
}

/// Runs `step` (a vtkRenderStepsPass's, maybe unset) for `state`; the
/// number of props it rendered.
int RunStep(vtkRenderPass* step, const vtkRenderState* state)
{
  if (!step)
  {
    return 0;
  }
  step->Render(state);
  return step->GetNumberOfRenderedProps();
}
} // namespace

void vtkRayTracePass::Internals::RenderOthersBelow(
  vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren)
{
  this->OthersBelow.clear();
  // Without the depth test (a window that never erased) raster's props
  // would leave no depth to end the rays at: they are drawn after.
  auto* win = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  if (pass.IdMode || !pass.DelegatePass || this->Traced.empty() || !pass.TraceTranslucency ||
    !this->Scene.HasTranslucency() || !win->GetState()->GetEnumState(GL_DEPTH_TEST))
  {
    return;
  }
  auto* rasterSteps = vtkRayTraceRasterSteps::SafeDownCast(pass.DelegatePass);
  auto* steps = vtkRenderStepsPass::SafeDownCast(pass.DelegatePass);
  for (vtkProp* prop : this->Others)
  {
    // A delegate of another kind draws a prop whole (translucent parts,
    // overlays, volumes included), so only actors and image slices without
    // translucent parts go before the trace.
    const bool drawnWholeBelow = (prop->IsA("vtkActor") || prop->IsA("vtkImageSlice")) &&
      !prop->HasTranslucentPolygonalGeometry();
    if (DrawsOnly3D(prop) && prop->HasOpaqueGeometry() && (rasterSteps || steps || drawnWholeBelow))
    {
      this->OthersBelow.push_back(prop);
    }
  }
  if (this->OthersBelow.empty())
  {
    return;
  }
  vtkRenderState below(ren);
  StateFor(below, s, this->OthersBelow);
  if (rasterSteps)
  {
    rasterSteps->RenderOpaque(&below);
    pass.NumberOfRenderedProps += rasterSteps->GetNumberOfRenderedProps();
  }
  else if (steps)
  {
    pass.NumberOfRenderedProps += RunStep(steps->GetLightsPass(), &below);
    pass.NumberOfRenderedProps += RunStep(steps->GetOpaquePass(), &below);
  }
  else
  {
    pass.DelegatePass->Render(&below);
    pass.NumberOfRenderedProps += pass.DelegatePass->GetNumberOfRenderedProps();
  }
}

void vtkRayTracePass::Internals::RenderOthers(
  vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren)
{
  // With nothing left to raster the delegate still runs when it may apply
  // the renderer's FXAA over the traced image.
  if (pass.IdMode || !pass.DelegatePass || (this->Others.empty() && !ren->GetUseFXAA()))
  {
    return;
  }
  vtkRenderState rest(ren);
  StateFor(rest, s, this->Others);
  // The props not drawn before the trace: their opaque parts are still to
  // draw (a delegate of another kind drew the ones before it whole).
  std::vector<vtkProp*> above;
  std::copy_if(this->Others.begin(), this->Others.end(), std::back_inserter(above), [this](vtkProp* prop) {
    return std::find(this->OthersBelow.begin(), this->OthersBelow.end(), prop) == this->OthersBelow.end();
  });
  vtkRenderState over(ren);
  StateFor(over, s, above);
  auto* rasterSteps = vtkRayTraceRasterSteps::SafeDownCast(pass.DelegatePass);
  if (rasterSteps && !this->OthersBelow.empty())
  {
    rasterSteps->RenderOpaque(&over);
    pass.NumberOfRenderedProps += rasterSteps->GetNumberOfRenderedProps();
    rasterSteps->RenderAfterOpaque(&rest);
    pass.NumberOfRenderedProps += rasterSteps->GetNumberOfRenderedProps();
    return;
  }
  auto* steps = vtkRenderStepsPass::SafeDownCast(pass.DelegatePass);
  if (!steps)
  {
    pass.DelegatePass->Render(&over);
    pass.NumberOfRenderedProps += pass.DelegatePass->GetNumberOfRenderedProps();
    return;
  }
  // A vtkRenderStepsPass: its steps after the camera pass, whose clear would
  // wipe the traced image (and its post-processing, which wraps that pass).
  pass.NumberOfRenderedProps += RunStep(steps->GetLightsPass(), &rest);
  pass.NumberOfRenderedProps += RunStep(steps->GetOpaquePass(), &over);
  for (vtkRenderPass* step : { steps->GetTranslucentPass(), steps->GetVolumetricPass(), steps->GetOverlayPass() })
  {
    pass.NumberOfRenderedProps += RunStep(step, &rest);
  }
}
