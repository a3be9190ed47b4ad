#include "vtkRayTracePass.h"
#include "vtkRayTracePassInternals.h"

#include "vtkDataObject.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"

#include <algorithm>
#include <cmath>

using vtkrt::pass::FrameCounters;

namespace
{
/// Whether the camera's view transform maps every point onto one line of
/// the view (a view up parallel to the direction of projection, not
/// orthogonalized): raster's triangles then all have no area, and it draws
/// nothing.
bool ViewCollapses(vtkCamera* cam)
{
  vtkMatrix4x4* view = cam->GetViewTransformMatrix();
  double x[3], y[3], normal[3];
  for (int k = 0; k < 3; ++k)
  {
    x[k] = view->GetElement(0, k);
    y[k] = view->GetElement(1, k);
  }
  vtkMath::Cross(x, y, normal);
  return vtkMath::Norm(normal) == 0.0;
}
} // namespace

vtkStandardNewMacro(vtkRayTracePass);

vtkRayTracePass::vtkRayTracePass()
  : States(new RendererStates)
{
  this->Internal = this->States->Entries.front().State.get();
  // Default delegate: what the renderer draws without a pass, after its
  // clear (which would wipe the traced image).
  vtkNew<vtkRayTraceRasterSteps> steps;
  this->SetDelegatePass(steps);
}

vtkRayTracePass::~vtkRayTracePass()
{
  this->States->Detach(nullptr);
  if (this->DelegatePass)
  {
    this->DelegatePass->UnRegister(this);
  }
}

void vtkRayTracePass::SetDelegatePass(vtkRenderPass* pass)
{
  // nullptr brings back the default, the renderer's own steps: a pass
  // without a delegate would drop every prop it does not trace.
  if (pass == this->DelegatePass ||
    (!pass && vtkRayTraceRasterSteps::SafeDownCast(this->DelegatePass)))
  {
    return;
  }
  vtkSmartPointer<vtkRenderPass> kept = pass;
  if (!kept)
  {
    kept = vtkSmartPointer<vtkRayTraceRasterSteps>::New();
  }
  pass = kept;
  if (this->DelegatePass)
  {
    this->DelegatePass->UnRegister(this);
  }
  this->DelegatePass = pass;
  if (pass)
  {
    pass->Register(this);
  }
  this->Modified();
}

vtkRenderPass* vtkRayTracePass::GetDelegatePass()
{
  return this->DelegatePass;
}

void vtkRayTracePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "QualityPreset: " << this->GetQualityPresetAsString() << "\n";
  os << indent << "IdMode: " << this->IdMode << "\n";
  os << indent << "BuildQuality: " << this->BuildQuality << "\n";
  os << indent << "BackgroundBuildThreshold: " << this->BackgroundBuildThreshold << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "ProgressiveAccumulation: " << this->ProgressiveAccumulation << "\n";
  os << indent << "Shadows: " << this->Shadows << "\n";
  os << indent << "TraceTranslucency: " << this->TraceTranslucency << "\n";
  os << indent << "AmbientOcclusionSamples: " << this->AmbientOcclusionSamples << "\n";
  os << indent << "AmbientOcclusionRadius: " << this->AmbientOcclusionRadius << "\n";
  os << indent << "MaximumTraversalSteps: " << this->MaximumTraversalSteps << "\n";
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "PrecisionMode: " << this->GetPrecisionModeAsString() << "\n";
  os << indent << "AccumulatedFrames: " << this->Internal->Accumulated.GetFrames() << "\n";
  os << indent << "MaximumTextureBufferTexels: " << this->MaximumTextureBufferTexels << "\n";
  os << indent << "DelegatePass: " << this->DelegatePass << "\n";
  os << indent << "LastFeatureKey: " << this->Internal->Programs.GetLastKey() << "\n";
  const FrameCounters& c = this->Internal->Counters;
  os << indent << "Last frame: BVH builds " << c.BVHBuilds << " (background builds taken "
     << c.BackgroundBuildsTaken << "), geometry bytes " << c.GeometryBytesUploaded
     << " (borrowed " << c.GeometryBytesBorrowed << "), frame bytes " << c.FrameBytesUploaded
     << ", shader compiles " << c.ShaderCompiles << ", traced primitives " << c.TracedPrimitives << "\n";
  os << indent << "Last frame seconds: extraction " << c.ExtractionSeconds << ", triangulation "
     << c.TriangulationSeconds << ", build " << c.BuildSeconds << ", packing " << c.PackingSeconds
     << ", upload " << c.UploadSeconds << ", shader compile " << c.ShaderCompileSeconds << "\n";
}

bool vtkRayTracePass::DecodeId(const unsigned char rgba[4], int& propIndex, vtkIdType& id)
{
  if (rgba[3] == 0)
  {
    propIndex = -1;
    id = -1;
    return false;
  }
  propIndex = static_cast<int>(rgba[3]) - 1;
  id = static_cast<vtkIdType>(rgba[0]) | (static_cast<vtkIdType>(rgba[1]) << 8) |
    (static_cast<vtkIdType>(rgba[2]) << 16);
  return true;
}

int vtkRayTracePass::GetNumberOfTracedProps() const
{
  return static_cast<int>(this->Internal->Traced.size());
}

vtkProp* vtkRayTracePass::GetTracedProp(int index) const
{
  const auto& t = this->Internal->Traced;
  return index >= 0 && index < static_cast<int>(t.size()) ? t[index] : nullptr;
}

const char* vtkRayTracePass::GetPrecisionModeAsString() const
{
  return this->PrecisionMode == WORLD ? "World" : "CameraRelative";
}

namespace
{
/// The knobs a quality preset sets (docs/trade.md says why these values).
struct PresetKnobs
{
  int Preset;
  const char* Name;
  int BuildQuality;
  int LeafSize;
  int SamplesPerPixel;
  bool ProgressiveAccumulation;
  bool Shadows;
  int AmbientOcclusionSamples;
};

const PresetKnobs Presets[] = {
  { vtkRayTracePass::INTERACTIVE, "Interactive", 0, 8, 1, true, false, 0 },
  { vtkRayTracePass::BALANCED, "Balanced", 1, 8, 1, true, true, 2 },
  { vtkRayTracePass::EXACT, "Exact", 1, 8, 4, true, true, 4 },
};
}

void vtkRayTracePass::SetMaximumTextureBufferTexels(vtkTypeInt64 texels)
{
  if (texels < 0)
  {
    vtkErrorMacro("SetMaximumTextureBufferTexels(" << texels
                                                   << "): a texel count is 0 (the GL limit) or more; unchanged.");
    return;
  }
  if (this->MaximumTextureBufferTexels != texels)
  {
    this->MaximumTextureBufferTexels = texels;
    this->Modified();
  }
}

void vtkRayTracePass::SetAmbientOcclusionRadius(double radius)
{
  if (std::isnan(radius))
  {
    vtkErrorMacro("SetAmbientOcclusionRadius(nan): a radius is a length (0: a tenth of the "
                  "traced bounds' diagonal); unchanged.");
    return;
  }
  radius = std::min(std::max(radius, 0.0), VTK_DOUBLE_MAX);
  if (this->AmbientOcclusionRadius != radius)
  {
    this->AmbientOcclusionRadius = radius;
    this->Modified();
  }
}

void vtkRayTracePass::SetQualityPreset(int preset)
{
  if (preset == CUSTOM)
  {
    return;
  }
  for (const PresetKnobs& p : Presets)
  {
    if (p.Preset == preset)
    {
      this->SetBuildQuality(p.BuildQuality);
      this->SetLeafSize(p.LeafSize);
      this->SetSamplesPerPixel(p.SamplesPerPixel);
      this->SetProgressiveAccumulation(p.ProgressiveAccumulation);
      this->SetShadows(p.Shadows);
      this->SetAmbientOcclusionSamples(p.AmbientOcclusionSamples);
      this->SetMaximumTraversalSteps(0);
      this->SetPrecisionMode(CAMERA_RELATIVE);
      return;
    }
  }
  vtkErrorMacro("No quality preset " << preset << ": expected CUSTOM, INTERACTIVE, BALANCED or EXACT.");
}

int vtkRayTracePass::GetQualityPreset() const
{
  for (const PresetKnobs& p : Presets)
  {
    if (this->BuildQuality == p.BuildQuality && this->LeafSize == p.LeafSize &&
      this->SamplesPerPixel == p.SamplesPerPixel &&
      this->ProgressiveAccumulation == p.ProgressiveAccumulation && this->Shadows == p.Shadows &&
      this->AmbientOcclusionSamples == p.AmbientOcclusionSamples &&
      this->MaximumTraversalSteps == 0 && this->PrecisionMode == CAMERA_RELATIVE)
    {
      return p.Preset;
    }
  }
  return CUSTOM;
}

const char* vtkRayTracePass::GetQualityPresetAsString() const
{
  const int preset = this->GetQualityPreset();
  for (const PresetKnobs& p : Presets)
  {
    if (p.Preset == preset)
    {
      return p.Name;
    }
  }
  return "Custom";
}

int vtkRayTracePass::GetAccumulatedFrames() const
{
  return this->Internal->Accumulated.GetFrames();
}

int vtkRayTracePass::GetLastBVHBuilds() const
{
  return this->Internal->Counters.BVHBuilds;
}
int vtkRayTracePass::GetLastBackgroundBuildsTaken() const
{
  return this->Internal->Counters.BackgroundBuildsTaken;
}
void vtkRayTracePass::WaitForBackgroundBuilds()
{
  for (const RendererStates::Entry& e : this->States->Entries)
  {
    e.State->Scene.WaitForBackgroundBuilds();
  }
}
int vtkRayTracePass::GetNumberOfBackgroundBuilds() const
{
  return this->Internal->Scene.GetNumberOfBackgroundBuilds();
}
vtkIdType vtkRayTracePass::GetNumberOfBackgroundBuildsTaken() const
{
  return this->Internal->Scene.GetNumberOfBackgroundBuildsTaken();
}
vtkTypeInt64 vtkRayTracePass::GetLastGeometryBytesUploaded() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.GeometryBytesUploaded);
}
vtkTypeInt64 vtkRayTracePass::GetLastGeometryBytesBorrowed() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.GeometryBytesBorrowed);
}
vtkTypeInt64 vtkRayTracePass::GetLastFrameBytesUploaded() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.FrameBytesUploaded);
}
double vtkRayTracePass::GetLastExtractionSeconds() const
{
  return this->Internal->Counters.ExtractionSeconds;
}
double vtkRayTracePass::GetLastTriangulationSeconds() const
{
  return this->Internal->Counters.TriangulationSeconds;
}
double vtkRayTracePass::GetLastBuildSeconds() const
{
  return this->Internal->Counters.BuildSeconds;
}
double vtkRayTracePass::GetLastPackingSeconds() const
{
  return this->Internal->Counters.PackingSeconds;
}
double vtkRayTracePass::GetLastUploadSeconds() const
{
  return this->Internal->Counters.UploadSeconds;
}
double vtkRayTracePass::GetLastShaderCompileSeconds() const
{
  return this->Internal->Counters.ShaderCompileSeconds;
}

int vtkRayTracePass::GetLastShaderCompiles() const
{
  return this->Internal->Counters.ShaderCompiles;
}
vtkTypeInt64 vtkRayTracePass::GetLastTracedPrimitives() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.TracedPrimitives);
}
int vtkRayTracePass::GetLastTopLevelBuilds() const
{
  return this->Internal->Counters.TopLevelBuilds;
}
int vtkRayTracePass::GetLastTracedInstances() const
{
  return this->Internal->Counters.TracedInstances;
}
vtkTypeInt64 vtkRayTracePass::GetLastTracedPixels() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.TracedPixels);
}
const char* vtkRayTracePass::GetLastFeatureKey() const
{
  return this->Internal->Programs.GetLastKey().c_str();
}
const char* vtkRayTracePass::GetLastFragmentShaderSource() const
{
  return this->Internal->Programs.GetLastSource().c_str();
}

void vtkRayTracePass::ReleaseGraphicsResources(vtkWindow* w)
{
  // The window may be going away: the next Render there starts afresh.
  this->States->Detach(w);
  if (this->DelegatePass)
  {
    this->DelegatePass->ReleaseGraphicsResources(w);
  }
}

namespace
{
/// Each traced prop of the frame's props gets its share of the tracing's
/// GPU time, as raster props report their draw times (vtkLODProp3D chooses
/// its level by them): builds and uploads, once per geometry, are not in
/// it, and props traced while culled (for shadows) are not the frame's.
void ReportRenderTimes(
  const std::vector<vtkProp*>& traced, double seconds, const vtkRenderState* s, vtkRenderer* ren)
{
  const std::unordered_set<vtkProp*> inFrame(s->GetPropArray(), s->GetPropArray() + s->GetPropArrayCount());
  const auto count = static_cast<double>(std::count_if(
    traced.begin(), traced.end(), [&inFrame](vtkProp* prop) { return inFrame.count(prop) > 0; }));
  // VTK's mappers report at least 0.1 ms (zero means "never rendered").
  const double share = std::max(seconds / std::max(count, 1.0), 1e-4);
  for (vtkProp* prop : traced)
  {
    if (inFrame.count(prop))
    {
      prop->AddEstimatedRenderTime(share, ren);
    }
  }
}
} // namespace

namespace
{
/// Viewport, scissor and VTK's own clear (solid or gradient background), as
/// vtkCameraPass sets them: the renderer's tiled viewport, or all of the
/// framebuffer a wrapping pass (vtkSSAAPass, an image processing pass)
/// hands over in the render state (`size` and `origin`: the drawn viewport).
void BeginDrawing(const vtkRenderState* s, vtkOpenGLRenderer* ren, vtkOpenGLCamera* cam,
  const int size[2], const int origin[2])
{
  if (!s->GetFrameBuffer())
  {
    cam->Render(ren);
    return;
  }
  vtkOpenGLState* ostate = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())->GetState();
  ostate->vtkglViewport(origin[0], origin[1], size[0], size[1]);
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  ostate->vtkglScissor(origin[0], origin[1], size[0], size[1]);
  if (ren->GetRenderWindow()->GetErase() && ren->GetErase())
  {
    ren->Clear();
  }
}
} // namespace

void vtkRayTracePass::Render(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  vtkOpenGLRenderer* ren = vtkOpenGLRenderer::SafeDownCast(s->GetRenderer());
  vtkOpenGLRenderWindow* win = ren ? vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()) : nullptr;
  if (!win)
  {
    this->Internal->Counters = FrameCounters();
    vtkErrorMacro("vtkRayTracePass needs a vtkOpenGLRenderer in a vtkOpenGLRenderWindow.");
    return;
  }
  bool released = false;
  this->Internal = &this->States->For(ren, released);
  Internals& in = *this->Internal;
  if (released)
  {
    win->MakeCurrent();
  }
  in.Counters = FrameCounters();
  in.Attach(win);
  vtkOpenGLCamera* cam = vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera());
  if (!cam)
  {
    vtkErrorMacro("vtkRayTracePass needs a vtkOpenGLCamera.");
    return;
  }
  int size[2] = { 0, 0 }, origin[2] = { 0, 0 };
  Internals::DrawnViewport(s, ren, size, origin);
  BeginDrawing(s, ren, cam, size, origin);
  in.KeepsBelow = Internals::KeepsDepthBelow(ren, win->GetState());
  // Lights follow the camera and VTK computes the lighting complexity.
  in.Lights->Render(s);

  const auto extractStart = std::chrono::steady_clock::now();
  in.Extract(*this, s, ren);
  in.Counters.ExtractionSeconds = std::max(0.0,
    vtkrt::pass::SecondsSince(extractStart) - in.Counters.TriangulationSeconds -
      in.Counters.BuildSeconds);
  if (this->IdMode)
  {
    vtkOpenGLState* ostate = win->GetState();
    vtkOpenGLState::ScopedglClearColor clearColor(ostate);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  in.Upload(*this, win);
  // A trace of selection ids made before this frame rebuilt or uploaded
  // geometry would report the old cells.
  const FrameCounters& c = in.Counters;
  if (c.BVHBuilds > 0 || c.TopLevelBuilds > 0 || c.BackgroundBuildsTaken > 0 || c.GeometryBytesUploaded > 0)
  {
    in.Selecting.Invalidate();
  }
  // A collapsed view: raster draws what it draws of those props (nothing),
  // where rays from it would draw garbage at depth 0.
  if (!in.GeometryValid || !in.ColorsValid || !in.TexturesValid || ViewCollapses(cam))
  {
    in.LeaveTracedToRaster(s);
  }
  vtkHardwareSelector* selector = ren->GetSelector();
  if (selector && !this->IdMode)
  {
    in.Select(*this, s, ren, win, cam, selector);
    // Points are drawn by raster, whose mappers report their own times.
    if (selector->GetFieldAssociation() != vtkDataObject::FIELD_ASSOCIATION_POINTS)
    {
      ReportRenderTimes(in.Traced, in.TraceTimer->GetReusableElapsedSeconds(), s, ren);
    }
    vtkOpenGLCheckErrorMacro("failed after vtkRayTracePass::Render (selection)");
    return;
  }
  // A selection render (above) leaves the accumulated image as it was.
  const int framesBefore = in.Accumulated.BeginFrame();
  in.RenderOthersBelow(*this, s, ren);
  if (!in.Traced.empty())
  {
    in.TraceTimer->ReusableStart();
    in.Trace(*this, s, ren, win, cam, framesBefore);
    in.TraceTimer->ReusableStop();
    ReportRenderTimes(in.Traced, in.TraceTimer->GetReusableElapsedSeconds(), s, ren);
  }
  this->NumberOfRenderedProps += static_cast<int>(in.Traced.size());
  in.RenderOthers(*this, s, ren);
  vtkOpenGLCheckErrorMacro("failed after vtkRayTracePass::Render");
}
