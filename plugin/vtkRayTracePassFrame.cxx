#include "vtkRayTracePassInternals.h"

#include "vtkOpenGLFramebufferObject.h"

#include "vtkrt/core/GpuTraversal.h"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>

using vtkrt::pass::Features;
using vtkrt::pass::Instance;

namespace
{
/// Row-major double 4x4 -> column-major float (what GLSL's mat4 expects).
void toGLSL(const vtkMatrix4x4* m, float out[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
    }
  }
}

/// Appends the bytes of trivially copyable values as floats (a signature
/// compares them bit for bit).
template <class T>
void appendAsFloats(std::vector<float>& out, const std::vector<T>& values)
{
  static_assert(sizeof(T) % sizeof(float) == 0, "whole floats");
  out.push_back(static_cast<float>(values.size()));
  const std::size_t first = out.size();
  out.resize(first + values.size() * sizeof(T) / sizeof(float));
  if (!values.empty())
  {
    std::memcpy(out.data() + first, values.data(), values.size() * sizeof(T));
  }
}

/// The scissor box in effect (or, with no scissor test on, the viewport).
std::array<int, 4> DrawingBound(vtkOpenGLState* ostate)
{
  std::array<int, 4> box;
  ostate->vtkglGetIntegerv(ostate->GetEnumState(GL_SCISSOR_TEST) ? GL_SCISSOR_BOX : GL_VIEWPORT, box.data());
  return box;
}

/// The window rectangle `rect` (x, y, width, height) within `bound`.
std::array<int, 4> Clipped(const int rect[4], const std::array<int, 4>& bound)
{
  const int x0 = std::max(rect[0], bound[0]), y0 = std::max(rect[1], bound[1]);
  const int x1 = std::min(rect[0] + rect[2], bound[0] + bound[2]);
  const int y1 = std::min(rect[1] + rect[3], bound[1] + bound[3]);
  return { x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0) };
}

/// Narrows drawing to the window rectangle `rect` within `bound`; returns
/// the pixels left.
std::size_t ScissorTo(vtkOpenGLState* ostate, const int rect[4], const std::array<int, 4>& bound)
{
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  const std::array<int, 4> r = Clipped(rect, bound);
  ostate->vtkglScissor(r[0], r[1], r[2], r[3]);
  return static_cast<std::size_t>(r[2]) * static_cast<std::size_t>(r[3]);
}

/// Narrows drawing to the window rectangle `rect` within the drawing bound.
std::size_t ScissorTo(vtkOpenGLState* ostate, const int rect[4])
{
  return ScissorTo(ostate, rect, DrawingBound(ostate));
}

/// Whether the frame is drawn into float colors: the framebuffer a
/// wrapping pass hands over (vtkToneMappingPass's) has a float color
/// texture.
bool DrawsFloatColors(const vtkRenderState* s)
{
  auto* fbo = vtkOpenGLFramebufferObject::SafeDownCast(s ? s->GetFrameBuffer() : nullptr);
  vtkTextureObject* color = fbo ? fbo->GetColorAttachmentAsTextureObject(0) : nullptr;
  return color && (color->GetVTKDataType() == VTK_FLOAT || color->GetVTKDataType() == VTK_DOUBLE);
}


/// False when the environment variable is 0: tests compare the pass with
/// and without a way of saving work, which must not change the image.
/// VTKRT_FOOTPRINT_TILES=0: camera rays over the traced footprint's
/// rectangle, not its tiles; VTKRT_TILE_ENTRIES=0: camera rays walk from
/// the tree's root, not from their tile's entries; VTKRT_LEAF_TREES=0:
/// one-leaf trees are walked as any tree; VTKRT_PACKED_STACK_ENTRIES=0:
/// walk stack entries of two words, as for the largest buffers;
/// VTKRT_FLAT_FRAME_CONSTANTS=0: every frame constant a uniform.
bool Allowed(const char* variable)
{
  const char* value = std::getenv(variable);
  return !value || std::strcmp(value, "0") != 0;
}

} // namespace

bool vtkRayTracePass::Internals::KeepsDepthBelow(vtkRenderer* ren, vtkOpenGLState* ostate)
{
  return (ren->GetPreserveDepthBuffer() || !(ren->GetRenderWindow()->GetErase() && ren->GetErase())) &&
    ostate->GetEnumState(GL_DEPTH_TEST);
}

namespace
{

/// Occlusion rays a sample when the pass's own knob is 0 and the
/// application turned on the renderer's SSAO (raster's screen-space
/// occlusion), which the pass traces instead.
constexpr int kSSAOSamples = 4;

/// The occlusion rays a sample: the pass's AmbientOcclusionSamples, or
/// kSSAOSamples where only the renderer's UseSSAO asks for occlusion.
int OcclusionSamplesIn(int passSamples, vtkRenderer* ren)
{
  return passSamples > 0 ? passSamples : (ren->GetUseSSAO() ? kSSAOSamples : 0);
}

/// The occlusion radius asked for (0: the default): the pass's, or the
/// renderer's SSAORadius (world units, as the pass's) where UseSSAO alone
/// turned occlusion on.
double OcclusionRadiusIn(int passSamples, double passRadius, vtkRenderer* ren)
{
  return passSamples == 0 && ren->GetUseSSAO() ? ren->GetSSAORadius() : passRadius;
}

/// Whether a frame casts shadow rays: the pass's Shadows, or the renderer's
/// UseShadows (raster's shadow maps) that an application turned on.
bool ShadowsIn(bool passShadows, vtkRenderer* ren)
{
  return passShadows || ren->GetUseShadows();
}

/// A tile's entry list (MakeTileEntryLists) holds at most this many nodes.
constexpr std::uint32_t kMaxTileEntries = 8;
/// Trees shallower than this walk from the root: their walks are short, and
/// the entries' setup costs what the levels skipped save.
constexpr std::uint32_t kTileEntriesMinimumDepth = 19;

/// Traced tiles (TracedTiles) are this many pixels wide; more than
/// kMaxFootprintDraws rectangles of them are traced as one rectangle.
constexpr int kFootprintTile = 32;
constexpr std::size_t kMaxFootprintDraws = 64;
/// Most frames a tile of a scaled screenshot accumulates, so that an image
/// left accumulating for hours does not make a screenshot take as long.
constexpr int kMaxTileFrames = 256;

/// Whether the translucent layers' walks are interleaved
/// (Features::InterleavedWalks): VTKRT_INTERLEAVED_WALKS=1 or 0 says, so that
/// tests compare both on one driver; unset, on every driver but Mesa's CPU
/// rasterizers, whose pixels run in SIMD lanes that interleaving puts out of
/// step with each other.
bool InterleaveWalks()
{
  const char* value = std::getenv("VTKRT_INTERLEAVED_WALKS");
  if (value && *value)
  {
    return std::strcmp(value, "0") != 0;
  }
  return !vtkrt::pass::RendersOnCPU();
}

/// VTKRT_GENERAL_SHADER set (not empty, not 0): no shader of one instance,
/// so that tests walk a one-mesh scene the general way too.
bool GeneralShaderOnly()
{
  const char* value = std::getenv("VTKRT_GENERAL_SHADER");
  return value && *value && std::strcmp(value, "0") != 0;
}
} // namespace

void vtkRayTracePass::Internals::DrawnViewport(const vtkRenderState* s, vtkRenderer* ren, int size[2], int origin[2])
{
  if (s && s->GetFrameBuffer())
  {
    s->GetWindowSize(size);
    origin[0] = origin[1] = 0;
    return;
  }
  ren->GetTiledSizeAndOrigin(size, size + 1, origin, origin + 1);
}

void vtkRayTracePass::Internals::Extract(
  const vtkRayTracePass& pass, const vtkRenderState* s, vtkOpenGLRenderer* ren)
{
  this->Scene.SetBuildQuality(pass.BuildQuality);
  this->Scene.SetBackgroundBuildThreshold(pass.BackgroundBuildThreshold);
  this->Scene.SetLeafSize(pass.LeafSize);
  this->Scene.SetTraceTranslucency(pass.TraceTranslucency);
  // The default delegate draws the renderer's hidden line removal (ids
  // need none).
  this->Scene.SetHiddenLineRemoval(ren->GetUseHiddenLineRemoval() && !pass.IdMode &&
    vtkRayTraceRasterSteps::SafeDownCast(pass.DelegatePass) != nullptr);
  // Hardware selection reports ids per prop: an actor's plain lines cannot
  // come from a stand-in of its own there.
  this->Scene.SetSplitRasterCells(ren->GetSelector() == nullptr || pass.IdMode);
  if (pass.IdMode || (!ShadowsIn(pass.Shadows, ren) && OcclusionSamplesIn(pass.AmbientOcclusionSamples, ren) == 0))
  {
    this->Scene.Extract(
      ren, s->GetPropArray(), s->GetPropArrayCount(), this->Traced, this->Others, this->Counters);
    return;
  }
  // Secondary rays see props out of view too (VTK's culler left them out of
  // the render state): trace every visible prop, and leave to raster only
  // the render state's own.
  std::vector<vtkProp*> all;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    if (prop->GetVisibility())
    {
      all.push_back(prop);
    }
  }
  std::vector<vtkProp*> others;
  this->Scene.Extract(ren, all.data(), static_cast<int>(all.size()), this->Traced, others, this->Counters);
  vtkProp** stateProps = s->GetPropArray();
  const int stateCount = s->GetPropArrayCount();
  this->Others.clear();
  for (vtkProp* prop : others)
  {
    vtkProp* owner = this->Scene.StandInOwner(prop);
    if (std::find(stateProps, stateProps + stateCount, owner ? owner : prop) != stateProps + stateCount)
    {
      this->Others.push_back(prop);
    }
  }
}

Features vtkRayTracePass::Internals::FrameFeatures(const vtkRayTracePass& pass,
  vtkOpenGLRenderer* ren, const vtkrt::pass::CameraFrame& camera, const vtkrt::pass::FrameRecords& frame,
  std::size_t lights, bool topLevel, bool floatColors) const
{
  Features f;
  f.FloatColors = floatColors && !pass.IdMode;
  // Id mode clears the depth, and selection renders trace their ids alone.
  f.DepthBelow = !pass.IdMode && !ren->GetSelector() && (this->KeepsBelow || !this->OthersBelow.empty());
  f.Triangles = this->Scene.HasTriangles();
  f.Spheres = this->Scene.HasSpheres();
  f.VertexNormals = this->Scene.HasVertexNormals();
  f.CellNormals = this->Scene.HasCellNormals();
  f.Colors = this->Scene.HasColors();
  f.ColorTexture = this->Scene.HasColorTexture();
  f.ClipPlanes = static_cast<int>(frame.ClipPlanes.size() / 4);
  f.Lights = static_cast<int>(lights);
  f.LightComplexity = f.Lights > 0 ? ren->GetLightingComplexity() : 0;
  f.IdMode = pass.IdMode;
  f.TopLevel = topLevel;
  f.SingleInstance = !topLevel && frame.Records.size() == 1 && !GeneralShaderOnly();
  f.ProjectiveRays = !camera.AffineRays;
  // Sub-pixel sampling goes through the accumulation buffer (not in id
  // mode: ids do not average).
  const bool sampled = !pass.IdMode && (pass.SamplesPerPixel > 1 || pass.ProgressiveAccumulation);
  f.SamplesPerPixel = sampled ? pass.SamplesPerPixel : 0;
  // Secondary rays only where they change the image: shaded, lit frames.
  const bool shaded = !pass.IdMode && f.LightComplexity > 0;
  f.Shadows = shaded && ShadowsIn(pass.Shadows, ren);
  f.Specular = shaded && this->Scene.HasSpecular();
  f.AmbientOcclusionSamples = shaded ? OcclusionSamplesIn(pass.AmbientOcclusionSamples, ren) : 0;
  f.MaximumTraversalSteps = pass.MaximumTraversalSteps;
  f.WorldCoordinates = pass.PrecisionMode == WORLD;
  f.ScreenSpheres = this->Scene.HasScreenSpheres();
  f.SphereCellIds = this->Scene.HasSphereCellIds();
  f.Ellipsoids = this->Scene.HasEllipsoids();
  f.Tubes = this->Scene.HasTubes();
  f.Textures = this->Scene.HasTextures();
  f.FaceCulling = this->Scene.HasFaceCulling();
  f.BackfaceProperties = this->Scene.HasBackfaceProperties();
  f.TextureCutOuts = this->Scene.HasTextureCutOuts();
  // Ids are the nearest layer's, translucent or not (as raster selection).
  f.Translucent = !pass.IdMode && this->Scene.HasTranslucency();
  f.InterleavedWalks = f.Translucent && (f.Shadows || f.AmbientOcclusionSamples > 0) && InterleaveWalks();
  f.SurfaceEdges = this->Scene.HasSurfaceEdges();
  f.Wireframe = this->Scene.HasWireframe();
  // The stack as deep as the deepest bottom-level tree needs; the top-level
  // walk shares it, so with one it is the largest.
  std::uint32_t depth = 0, triangleDepth = 0;
  for (const Instance& inst : this->Scene.GetInstances())
  {
    depth = std::max(depth, inst.Geom->MaxDepth);
    triangleDepth = inst.Geom->Spheres ? triangleDepth : std::max(triangleDepth, inst.Geom->MaxDepth);
  }
  f.StackSize = static_cast<int>(
    topLevel ? vtkrt::core::kMaxStackSize : vtkrt::core::gpu::stackSizeForDepth(depth));
  // A stack entry packs a node's index and count into one word while every
  // index a walk pushes (nodes, triangles, sphere texels) fits.
  const vtkrt::pass::GeometrySizes& placed = this->Places.Geometry;
  f.PackedStackEntries = Allowed("VTKRT_PACKED_STACK_ENTRIES") &&
    std::max({ placed.Nodes, placed.Triangles, placed.SphereTexels }) <= vtkrt::core::gpu::kMaxPackedStackIndex;
  // Camera rays start from their tile's nodes where one deep triangle tree
  // is walked by affine camera-relative rays with unsized boxes (wires grow
  // them), and no step cap (it counts from the root).
  f.TileEntries = Allowed("VTKRT_TILE_ENTRIES") && f.SingleInstance && f.Triangles && !f.Spheres && !f.Wireframe &&
    !f.WorldCoordinates && !f.ProjectiveRays && f.MaximumTraversalSteps == 0 &&
    depth >= kTileEntriesMinimumDepth;
  // Meshes of a few triangles (planes, quads) are one leaf each: nothing to walk.
  f.LeafTrees = f.Triangles && triangleDepth == 0 && Allowed("VTKRT_LEAF_TREES");
  GLint major = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  f.Fp64 = major >= 4;
  return f;
}

namespace
{
/// Where the shader's camera rays come from: three rays unprojected once
/// (affine cameras) or the inverse projection, unprojected per pixel.
void SetCameraRayUniforms(vtkShaderProgram* program, const Features& f, const vtkrt::pass::CameraFrame& camera)
{
  if (f.ProjectiveRays)
  {
    float m[16];
    toGLSL(camera.CameraToClip, m);
    program->SetUniformMatrix4x4("uCameraToClip", m);
    toGLSL(camera.ClipToCamera, m);
    program->SetUniformMatrix4x4("uClipToCamera", m);
    return;
  }
  float origin[3][3], direction[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      origin[r][k] = static_cast<float>(camera.RayOrigin[r][k]);
      direction[r][k] = static_cast<float>(camera.RayDirection[r][k]);
    }
  }
  program->SetUniform3fv("uRayOrigin", 3, origin);
  program->SetUniform3fv("uRayDirection", 3, direction);
  const float depth[4] = { static_cast<float>(camera.RayDepth[0]), static_cast<float>(camera.RayDepth[1]),
    static_cast<float>(camera.RayDepth[2]), static_cast<float>(camera.RayDepth[3]) };
  program->SetUniform4f("uRayDepth", depth);
}

/// The instances the shader walks: their count for the loop over them, or
/// the one instance's record as uniforms (the same for every pixel, so not
/// fetched per pixel); with a top level, the records' buffer alone.
void SetInstanceUniforms(vtkShaderProgram* program, const Features& f, const vtkrt::pass::FrameRecords& frame)
{
  if (f.SingleInstance)
  {
    using vtkrt::core::gpu::kInstanceHeadTexels;
    const GLuint* record = reinterpret_cast<const GLuint*>(frame.Records.data());
    glUniform4uiv(program->FindUniform("uInstance"), static_cast<GLsizei>(kInstanceHeadTexels), record);
    glUniform4uiv(program->FindUniform("uInstanceTail"),
      static_cast<GLsizei>(vtkrt::core::gpu::kInstanceTailTexels), record + 4 * kInstanceHeadTexels);
    glUniform4uiv(program->FindUniform("uRootNode"),
      static_cast<GLsizei>(vtkrt::core::gpu::texelsOf<vtkrt::core::gpu::Node>()),
      reinterpret_cast<const GLuint*>(frame.RootNodes.data()));
  }
  else if (!f.TopLevel)
  {
    program->SetUniformi("uNumberOfInstances", static_cast<int>(frame.Records.size()));
  }
}
} // namespace

void vtkRayTracePass::Internals::SetUniforms(vtkShaderProgram* program, const Features& f,
  const vtkrt::pass::CameraFrame& camera, const vtkrt::pass::FrameRecords& frame,
  const std::vector<vtkrt::core::gpu::Light>& lights, double occlusionRadius) const
{
  SetCameraRayUniforms(program, f, camera);
  const double* dop = camera.DirectionOfProjection;
  const float viewBack[3] = { static_cast<float>(-dop[0]), static_cast<float>(-dop[1]),
    static_cast<float>(-dop[2]) };
  program->SetUniform3f("uViewBack", viewBack);
  SetInstanceUniforms(program, f, frame);
  if (f.WorldCoordinates)
  {
    double eyeInShader[3];
    camera.ToShader(camera.Eye, eyeInShader);
    const float eye[3] = { static_cast<float>(eyeInShader[0]), static_cast<float>(eyeInShader[1]),
      static_cast<float>(eyeInShader[2]) };
    program->SetUniform3f("uEye", eye);
  }
  if (f.AmbientOcclusionSamples > 0)
  {
    program->SetUniformf("uAmbientOcclusionRadius",
      static_cast<float>(std::min(occlusionRadius * camera.Scale, 1e30))); // in float's range
  }
  if (f.TopLevel)
  {
    const vtkrt::core::Vec3<double>& anchor = this->Top.GetAnchor();
    // The top level is built over the world boxes times the shader scale.
    const float toAnchor[3] = { static_cast<float>(camera.Origin[0] * camera.Scale - anchor.x),
      static_cast<float>(camera.Origin[1] * camera.Scale - anchor.y),
      static_cast<float>(camera.Origin[2] * camera.Scale - anchor.z) };
    program->SetUniform3f("uCameraToAnchor", toAnchor);
  }
  if (f.ClipPlanes > 0)
  {
    program->SetUniform4fv("uClipPlanes", f.ClipPlanes, frame.ClipPlanes.data());
  }
  if (f.SurfaceEdgeCode() || f.WireframeCode())
  {
    float m[16];
    toGLSL(camera.CameraToPixels, m);
    program->SetUniformMatrix4x4("uCameraToPixels", m);
  }
  vtkrt::pass::SetLightUniforms(program, lights);
}

bool vtkRayTracePass::Internals::Prepare(const vtkRayTracePass& pass, const vtkRenderState* s,
  vtkOpenGLRenderer* ren, vtkOpenGLRenderWindow* win, vtkOpenGLCamera* cam,
  const std::vector<bool>* traced, bool selectIds, Prepared& p)
{
  const std::vector<Instance>& instances = this->Scene.GetInstances();
  int size[2] = { 0, 0 }, origin[2] = { 0, 0 };
  DrawnViewport(s, ren, size, origin);
  p.Camera.Set(ren, cam, pass.PrecisionMode == WORLD, vtkrt::pass::ViewScale(cam), size, origin);
  vtkrt::pass::FrameRecords& frame = p.Frame;
  if (!vtkrt::pass::MakeFrameRecords(instances, this->Places, p.Camera, ren, frame))
  {
    vtkErrorWithObjectMacro(&pass, "vtkRayTracePass: a traced instance has no uploaded geometry.");
    return false;
  }
  if (traced)
  {
    vtkrt::pass::KeepPickableInstances(*traced, instances, frame);
  }
  else if (frame.TooSmallProps != this->WarnedTooSmallProps)
  {
    // Once per change of what cannot be shaded, not every frame.
    this->WarnedTooSmallProps = frame.TooSmallProps;
    if (!frame.TooSmallProps.empty())
    {
      vtkWarningWithObjectMacro(&pass, "vtkRayTracePass: "
          << frame.TooSmallProps.size() << " prop(s) (the first at prop index "
          << frame.TooSmallProps.front() << ") are under 2^-60 of the view's depth: "
          << "float cannot shade them, their pixels may be black or missing.");
    }
  }
  if (frame.Records.empty())
  {
    return false;
  }
  const auto uploadStart = std::chrono::steady_clock::now();
  const bool topLevel = vtkrt::pass::TopLevel::IsNeeded(frame.Records.size());
  if (topLevel)
  {
    std::vector<vtkrt::core::AABB<double>> scaledBoxes(frame.WorldBoxes);
    for (vtkrt::core::AABB<double>& b : scaledBoxes)
    {
      b = vtkrt::core::AABB<double>(b.min * p.Camera.Scale, b.max * p.Camera.Scale);
    }
    this->Top.Update(win, scaledBoxes, this->Buffers.TopNodes, this->Counters);
    this->Top.Reorder(frame.Records);
  }
  // Unchanged records (a still frame; any camera move in WORLD mode) are
  // not uploaded again.
  const std::size_t recordBytes = frame.Records.size() * sizeof(vtkrt::core::gpu::InstanceRecord);
  if (frame.Records.size() != this->LastRecords.size() || !this->Buffers.Instances.GetTexels() ||
    std::memcmp(frame.Records.data(), this->LastRecords.data(), recordBytes) != 0)
  {
    this->Counters.FrameBytesUploaded += this->Buffers.Instances.Upload(win, frame.Records);
    this->LastRecords = frame.Records;
  }
  this->Counters.UploadSeconds += vtkrt::pass::SecondsSince(uploadStart);
  p.Lights = vtkrt::pass::CollectLights(ren, p.Camera.Origin, p.Camera.Scale);
  p.F = this->FrameFeatures(pass, ren, p.Camera, frame, p.Lights.size(), topLevel, DrawsFloatColors(s));
  if (selectIds)
  {
    // Ids only: one centered ray a pixel, nothing shaded.
    p.F.SelectIds = true;
    p.F.IdMode = false;
    p.F.FloatColors = false;
    p.F.Translucent = false;
    p.F.InterleavedWalks = false;
    p.F.SamplesPerPixel = 0;
    p.F.Shadows = false;
    p.F.Specular = false;
    p.F.AmbientOcclusionSamples = 0;
    p.F.Lights = 0;
    p.F.LightComplexity = 0;
    p.F.TileEntries = false;
    p.Lights.clear();
  }
  // Occlusion rays start on traced props and meet only them, so nothing
  // lies farther than the props' diagonal: a longer radius (up to
  // VTK_DOUBLE_MAX, past float's range) is traced as that diagonal.
  // (SetUniforms keeps what is left within float's range.)
  const double diagonal = frame.SceneDiagonal();
  const double radius = OcclusionRadiusIn(pass.AmbientOcclusionSamples, pass.AmbientOcclusionRadius, ren);
  p.OcclusionRadius = radius > 0.0 && diagonal > 0.0
    ? std::min(radius, diagonal)
    : (radius > 0.0 ? radius : frame.DefaultOcclusionRadius());

  const int compilesBefore = this->Counters.ShaderCompiles;
  const auto compileStart = std::chrono::steady_clock::now();
  p.Tracer = this->Programs.Ready(win, p.F, Allowed("VTKRT_FLAT_FRAME_CONSTANTS"), this->Counters);
  if (this->Counters.ShaderCompiles > compilesBefore)
  {
    this->Counters.ShaderCompileSeconds += vtkrt::pass::SecondsSince(compileStart);
  }
  if (!p.Tracer)
  {
    if (this->Counters.ShaderCompiles > compilesBefore)
    {
      vtkErrorWithObjectMacro(&pass, "vtkRayTracePass: the ray tracing shader (features "
          << this->Programs.GetLastKey() << ") failed to compile.");
    }
    return false;
  }
  this->SetUniforms(p.Tracer->Program, p.F, p.Camera, frame, p.Lights, p.OcclusionRadius);
  if (p.F.TileEntries)
  {
    this->SetTileEntries(ren, win, p);
  }
  p.Active = this->Buffers.Bind(p.Tracer->Program);
  return true;
}

void vtkRayTracePass::Internals::SetTileEntries(vtkOpenGLRenderer* ren, vtkOpenGLRenderWindow* win, Prepared& p)
{
  const vtkrt::pass::TileEntryLists lists = vtkrt::pass::MakeTileEntryLists(
    p.Camera, p.Frame, ren, kFootprintTile, kMaxTileEntries, static_cast<std::uint32_t>(p.F.StackSize));
  // A still camera keeps its lists on the GPU.
  if (lists.Words != this->LastTileEntries || !this->Buffers.TileEntries.GetTexels())
  {
    this->Counters.FrameBytesUploaded +=
      this->Buffers.TileEntries.Upload(win, lists.Words.data(), lists.Words.size() / 4);
    this->LastTileEntries = lists.Words;
  }
  p.Tracer->Program->SetUniform4f("uTileGrid", lists.Grid);
}

namespace
{
/// A prop's redraw time, and a vtkPropAssembly's parts' (its own covers
/// their MTimes only, not their data).
void AppendRedrawTimes(vtkProp* prop, std::vector<double>& out)
{
  out.push_back(static_cast<double>(prop->GetRedrawMTime()));
  for (vtkProp* part : PropAssemblyParts(prop))
  {
    AppendRedrawTimes(part, out);
  }
}
} // namespace

/// What an accumulated image is traced from: any change restarts
/// accumulating, but a refined tree taken in place of a fast one (the same
/// primitives, the same hits), whose upload is a repack that moves where
/// geometries lie: the records' geometry offsets give way to what each
/// instance traces (its source data, kept by the refined tree too).
vtkrt::pass::ImageSignature vtkRayTracePass::Internals::AccumulationSignature(const Prepared& p) const
{
  vtkrt::pass::ImageSignature out;
  out.Camera.resize(32);
  toGLSL(p.Camera.ClipToCamera, out.Camera.data());
  toGLSL(p.Camera.CameraToClip, out.Camera.data() + 16);
  std::vector<float>& signature = out.Scene;
  std::vector<vtkrt::core::gpu::InstanceRecord> records = p.Frame.Records;
  for (vtkrt::core::gpu::InstanceRecord& r : records)
  {
    r.root = 0;
    r.normalBase = 0;
    r.sphereCellIdBase = 0;
  }
  appendAsFloats(signature, records);
  std::vector<const void*> sources;
  for (const vtkrt::pass::Instance& inst : this->Scene.GetInstances())
  {
    sources.push_back(inst.Geom ? inst.Geom->Keep.Get() : nullptr);
    sources.push_back(inst.Geom ? inst.Geom->KeepData.Get() : nullptr);
  }
  appendAsFloats(signature, sources);
  // The depth below moves with these props' geometry: their redraw times
  // (an assembly's do not cover its parts' data) and bounds.
  std::vector<double> below;
  for (vtkProp* prop : this->OthersBelow)
  {
    below.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(prop)));
    AppendRedrawTimes(prop, below);
    const double* bounds = prop->GetBounds();
    below.insert(below.end(), bounds, bounds + (bounds ? 6 : 0));
  }
  appendAsFloats(signature, below);
  appendAsFloats(signature, p.Frame.ClipPlanes);
  appendAsFloats(signature, p.Lights);
  signature.push_back(static_cast<float>(p.OcclusionRadius));
  const std::string key = p.F.ImageKey();
  signature.insert(signature.end(), key.begin(), key.end());
  return out;
}

void vtkRayTracePass::Internals::Trace(const vtkRayTracePass& pass, const vtkRenderState* s,
  vtkOpenGLRenderer* ren, vtkOpenGLRenderWindow* win, vtkOpenGLCamera* cam, int framesBefore)
{
  Prepared p;
  if (!this->Prepare(pass, s, ren, win, cam, nullptr, false, p))
  {
    return;
  }
  vtkOpenGLQuadHelper* tracer = p.Tracer;
  vtkOpenGLState* ostate = win->GetState();
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  // A renderer that keeps the depth below it (a layer over another, say)
  // hides what lies behind it there, as its raster geometry would be: its
  // camera rays end there (uDepthBelow) and write no depth behind it, so
  // the depth test passes every traced fragment.
  ostate->vtkglDepthFunc(GL_ALWAYS);
  if (p.F.DepthBelow)
  {
    vtkTextureObject* below = this->Below.Take(win, p.Camera.ViewportSize, p.Camera.ViewportOrigin);
    below->Activate();
    tracer->Program->SetUniformi("uDepthBelow", below->GetTextureUnit());
    // Coincidences go to the renderers below where there are some, else to
    // this one's raster props.
    tracer->Program->SetUniformf("uDepthBelowSide", this->KeepsBelow ? 1.0f : -1.0f);
    p.Active.push_back(below);
  }
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglDisable(GL_BLEND);
  if (p.F.Translucent && p.F.SamplesPerPixel == 0)
  {
    // Premultiplied colors over VTK's background (the accumulation's
    // resolve blends the same way).
    ostate->vtkglEnable(GL_BLEND);
    ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  // Rays only where the traced instances can be: the rest keeps VTK's clear
  // (under IceT, each rank traces its own piece's share). The footprint is
  // a pixel wider than the boxes' projections, so it holds every sub-pixel
  // sample that can hit too.
  vtkOpenGLState::ScopedglScissor scissor(ostate);
  vtkOpenGLState::ScopedglEnableDisable scissorTest(ostate, GL_SCISSOR_TEST);
  int footprint[4];
  const bool narrowed = vtkrt::pass::TracedFootprint(p.Camera, p.Frame, ren, footprint);
  if (p.F.SamplesPerPixel == 0)
  {
    // Finer still: only the tiles the instances' upper tree boxes reach.
    // Tiles need camera-relative rays (WORLD mode's float rays far from the
    // origin stray more than their margin) and VTK's affine camera rays.
    const bool tiled = Allowed("VTKRT_FOOTPRINT_TILES") && !p.F.WorldCoordinates && p.Camera.AffineRays;
    std::vector<std::array<int, 4>> rects = tiled
      ? vtkrt::pass::TracedTiles(
          p.Camera, p.Frame, ren, narrowed ? footprint : nullptr, kFootprintTile, kMaxFootprintDraws)
      : std::vector<std::array<int, 4>>();
    const std::array<int, 4> bound = DrawingBound(ostate);
    if (rects.empty())
    {
      rects.push_back(narrowed ? std::array<int, 4>{ footprint[0], footprint[1], footprint[2], footprint[3] } : bound);
    }
    for (const std::array<int, 4>& rect : rects)
    {
      this->Counters.TracedPixels += ScissorTo(ostate, rect.data(), bound);
      tracer->Render();
    }
  }
  else
  {
    vtkrt::pass::ImageSignature signature = this->AccumulationSignature(p);
    // The depth that renderers before this one left may change with nothing
    // of this renderer's scene (its own props below are in the signature).
    const bool restart = !pass.ProgressiveAccumulation || (p.F.DepthBelow && this->KeepsBelow) ||
      this->Counters.GeometryBytesUploaded > this->Counters.RetreeBytesUploaded;
    // The accumulation traces the footprint (or the viewport) into its own buffer.
    const int* size = p.Camera.ViewportSize;
    // A scaled screenshot (vtkWindowToImageFilter::SetScale above 1) renders
    // tiles with cameras of their own: each tile accumulates, in its one
    // render, as many frames as the image on screen had.
    const int* tileScale = win->GetTileScale();
    const bool tile = tileScale[0] > 1 || tileScale[1] > 1;
    const int frames =
      tile && pass.ProgressiveAccumulation ? std::min(this->UntiledFrames, kMaxTileFrames) : 1;
    this->Counters.TracedPixels += static_cast<std::size_t>(frames) *
      (narrowed ? static_cast<std::size_t>(footprint[2]) * footprint[3]
                : static_cast<std::size_t>(size[0]) * size[1]);
    for (int f = 0; f < frames; ++f)
    {
      this->Accumulated.Trace(win, size, p.Camera.ViewportOrigin, tracer,
        f + 1 < frames ? vtkrt::pass::ImageSignature(signature) : std::move(signature), restart && f == 0,
        f == 0 ? framesBefore : this->Accumulated.GetFrames(), pass.SamplesPerPixel,
        narrowed ? footprint : nullptr);
    }
    if (!tile)
    {
      this->UntiledFrames = this->Accumulated.GetFrames();
    }
    for (vtkTextureObject* t : p.Active)
    {
      t->Deactivate();
    }
    p.Active.clear();
    // Outside the footprint the accumulation holds no hit: nothing to resolve.
    if (narrowed)
    {
      ScissorTo(ostate, footprint);
    }
    if (!this->Accumulated.Resolve(win, pass.SamplesPerPixel, this->Counters))
    {
      vtkErrorWithObjectMacro(&pass, "vtkRayTracePass: the accumulation resolve shader failed to compile.");
    }
  }
  for (vtkTextureObject* t : p.Active)
  {
    t->Deactivate();
  }
}

void vtkRayTracePass::Internals::Select(vtkRayTracePass& pass, const vtkRenderState* s,
  vtkOpenGLRenderer* ren, vtkOpenGLRenderWindow* win, vtkOpenGLCamera* cam,
  vtkHardwareSelector* selector)
{
  // Selection renders draw no raster props below the trace, and the list
  // of the last frame's may hold props deleted since.
  this->OthersBelow.clear();
  std::vector<vtkProp*> props =
    vtkrt::pass::SelectionProps(ren, s->GetPropArray(), s->GetPropArrayCount());
  if (selector->GetFieldAssociation() == vtkDataObject::FIELD_ASSOCIATION_POINTS)
  {
    // Points: every prop draws its points as raster does, depth-tested
    // against the depth of the traced frame the selector rendered first.
    pass.NumberOfRenderedProps =
      selector->Render(ren, props.data(), static_cast<int>(props.size()));
    return;
  }
  // Only the pickable traced props in the selection's props are traced,
  // so that the others hide nothing.
  const std::vector<vtkrt::pass::SelectableProp> selectable =
    vtkrt::pass::SelectablePropsOf(this->Traced, this->Scene.GetInstances());
  std::vector<bool> traced(this->Traced.size(), false);
  for (std::size_t i = 0; i < this->Traced.size(); ++i)
  {
    traced[i] = this->Traced[i]->GetPickable() &&
      std::find(props.begin(), props.end(), this->Traced[i]) != props.end();
  }
  Prepared p;
  if (this->Traced.empty() || !this->Prepare(pass, s, ren, win, cam, &traced, true, p))
  {
    // Nothing traced for this capture: no earlier trace may stand in.
    this->Selecting.Invalidate();
  }
  else
  {
    const int* origin = p.Camera.ViewportOrigin;
    const int* size = p.Camera.ViewportSize;
    const std::array<int, 4> area = vtkrt::pass::Selection::AreaInViewport(selector, origin, size);
    // What the ids depend on: the scene and camera, which props are
    // selectable, the viewport (frames that rebuild or upload geometry
    // invalidate the trace: Render).
    vtkrt::pass::ImageSignature signature = this->AccumulationSignature(p);
    std::vector<float> key(traced.begin(), traced.end());
    key.insert(key.end(), { static_cast<float>(size[0]), static_cast<float>(size[1]),
                            static_cast<float>(origin[0]), static_cast<float>(origin[1]) });
    signature.Scene.insert(signature.Scene.end(), key.begin(), key.end());
    if (!this->Selecting.Holds(signature, area))
    {
      this->Selecting.TraceIds(win, origin, size, area, p.Tracer, std::move(signature));
      this->Counters.TracedPixels += static_cast<std::size_t>(area[2]) * static_cast<std::size_t>(area[3]);
    }
    for (vtkTextureObject* t : p.Active)
    {
      t->Deactivate();
    }
  }
  pass.NumberOfRenderedProps =
    this->Selecting.RenderPass(win, ren, selector, props, selectable, this->Counters);
}
