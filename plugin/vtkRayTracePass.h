/**
 * @class   vtkRayTracePass
 * @brief   Ray traces a renderer's polygonal geometry with a GLSL BVH tracer.
 *
 * `renderer->SetPass(pass)` makes the renderer's polygonal geometry
 * ray traced; removing the pass gives raster back. The pass draws one
 * full-screen quad whose fragment shader builds each pixel's ray from the
 * inverse of VTK's own projection, walks a float copy of a two-level BVH
 * (vtkrt::core), shades like vtkOpenGLPolyDataMapper and writes the hit's
 * depth, so what it does not trace is drawn afterwards by the delegate
 * raster passes and composites by depth.
 *
 * Traced (everything else falls back to the delegate):
 * - vtkActor + vtkPolyDataMapper / vtkCompositePolyDataMapper(2) /
 *   vtkDataSetMapper (the surface its own polydata mapper draws), opaque
 *   or translucent (see SetTraceTranslucency), surface or wireframe
 *   representation (wireframe actors go to raster's hidden line removal
 *   under the renderer's UseHiddenLineRemoval), edges (opaque only), no
 *   PBR, no shader code, replacements or UpdateShaderEvent observers of
 *   the application's, not ForceOpaque with translucent colors; not
 *   vtkSkybox, vtkPointGaussianMapper (splats) or the molecule mapper's
 *   impostor mappers: polygons (fan triangulated, like VTK), triangle
 *   strips; composite block visibility and colors (inherited, replacing
 *   scalar colors); an actor texture (SetTexture: one 2D texture of
 *   8-bit colors, or scalars through its table, any wrap mode, nearest or
 *   interpolated, no mipmaps, transform or sRGB) at the data's texture
 *   coordinates, times the lit color as vtkOpenGLPolyDataMapper (not shown
 *   on back faces with ShowTexturesOnBackface off; without coordinates:
 *   untextured, as raster; fully transparent texels let rays through, as
 *   raster discards them); BackfaceCulling / FrontfaceCulling (camera rays
 *   pass culled triangles; shadow and occlusion rays do not); an opaque
 *   BackfaceProperty (its colors on back faces of actors without scalar
 *   colors). Cell edges as VTK 9.1 draws them, LineWidth pixels wide under
 *   any camera (measured in the window, on the cells' own edges: a
 *   polygon's outline, not its fan's diagonals; honouring point edge
 *   flags): EdgeVisibility blends EdgeColor over the surface as
 *   vtkOpenGLPolyDataMapper does (width at least 1.1 pixels); the
 *   wireframe representation shows only the wires (rays pass through the
 *   faces), in the actor's colors, lit with VTK's line normals. Edges of
 *   glyphs, edges drawn as tubes, and wireframes with a texture, culling or
 *   a backface property stay with raster.
 *   The actor's lines not drawn as tubes (below) and vertices not drawn
 *   as spheres are drawn by raster (a stand-in actor over those cells, with
 *   the actor's property, matrix and mapper settings); a composite with
 *   such cells, an actor with nothing else, and such an actor during a
 *   hardware selection fall back whole.
 * - Line and polyline cells of such an actor with RenderLinesAsTubes and a
 *   LineWidth over 1 (where VTK draws tubes) as analytic round tubes
 *   LineWidth pixels wide under every camera: each segment the hull of its
 *   two end spheres (radii as for points drawn as spheres), so polylines
 *   have round joints; point scalars interpolated along a segment, cell
 *   scalars per cell; their cell ids follow the vertices'. The BVH is over
 *   the bare segments, grown per frame by the largest radius.
 * - Points of such an actor with RenderPointsAsSpheres (vertices, or every
 *   point with the points representation) as analytic spheres PointSize
 *   pixels wide, as VTK draws them, under every camera: each frame gives a
 *   point at view depth z the world radius PointSize * tan(viewAngle/2) * z /
 *   viewport height (parallel: PointSize * parallelScale / height), which the
 *   shader evaluates per sphere; the BVH is over the bare points, its boxes
 *   grown by the largest radius, so camera moves and PointSize changes
 *   rebuild and upload no geometry. The actor's scale does not change
 *   their pixel size (as VTK's sprites).
 * - vtkGlyph3DMapper whose single source is a vtkSphereSource, or any
 *   source whose output is a closed sphere (points on one sphere about its
 *   bounds' center, faces near it: a filtered sphere, SetSourceData), as
 *   analytic spheres (scale array by magnitude or one component, scale factor,
 *   clamping, masking, colors through the mapper's LUT; orientation turns
 *   only an off-center source's center, a sphere being rotation invariant),
 *   or, scaled by vector components, as analytic ellipsoids (each ray is
 *   mapped onto the glyph's unit sphere; orientation by direction, rotation
 *   or quaternion, as vtkOpenGLGlyph3DMapper).
 * - vtkAssembly (nested too) whose visible parts are all such actors: each
 *   part under its path's matrix, as vtkAssembly draws it; selected and
 *   picked as the assembly, as raster reports it. An assembly with another
 *   part (a volume, shader code ...) falls back whole. A vtkLODProp3D: its
 *   chosen level's actor under the prop's matrix (chosen by hand, or by
 *   render time: traced props report their share of the tracing's GPU
 *   time, as raster props their draw times). A vtkPropAssembly of such
 *   props (not of LOD props, which choose while the group renders).
 * Shading: vtkProperty ambient/diffuse/specular, normals as
 * vtkOpenGLPolyDataMapper takes them (interpolated point normals unless flat,
 * else cell normals, else each triangle's geometric normal), point or cell
 * scalars mapped by the mapper's LUT (point scalars with
 * InterpolateScalarsBeforeMapping through its color texture, sampled like
 * raster; glyphs then take the property color, as VTK 9.1's), the renderer's
 * lights (VTK's lighting complexities 0-3), mapper clipping planes.
 * Background: VTK's own clear (solid, gradient) shows where rays miss.
 *
 * Geometry is cached per data object and rebuilt only when its MTime
 * changes (a mesh shared by several actors is stored once; more than 8
 * instances are walked through a top-level BVH); camera, light or property
 * changes upload only the per-instance records, whose matrices are made
 * camera-relative in double (see SetPrecisionMode). Works in any
 * vtkOpenGLRenderWindow (tested: vtkEGLHeadlessRenderWindow, and VTK's
 * default X11 window, vtkXOpenGLRenderWindow). Shaders are assembled from the scene's
 * features and cached by feature key. The per-frame counters say what the
 * last frame did. A pass set on several renderers keeps a scene, GL objects
 * and counters for each (the getters report the renderer rendered last).
 */
#ifndef vtkRayTracePass_h
#define vtkRayTracePass_h

#include "vtkRenderPass.h"
#include "vtkrtPluginModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkOpenGLRenderWindow;
class vtkProp;

class VTKRTPLUGIN_EXPORT vtkRayTracePass : public vtkRenderPass
{
public:
  static vtkRayTracePass* New();
  vtkTypeMacro(vtkRayTracePass, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /**
   * The pass that renders the props this pass does not trace, after the
   * traced image (and its depth) is in place, composited by depth; under
   * traced translucent layers, the opaque 3D props go before the trace so
   * the layers cover them (a pass that is neither the default nor a
   * vtkRenderStepsPass is then called twice a frame: first with the actors
   * and image slices among them that have no translucent part, then with
   * the rest). By
   * default the renderer's own steps: lights, opaque (through VTK's hidden
   * line removal pass under the renderer's UseHiddenLineRemoval, which
   * then takes lone wireframe actors from the tracer), translucent geometry
   * as the renderer says (order-independent blending, or depth peeling with
   * UseDepthPeeling, MaximumNumberOfPeels, OcclusionRatio and
   * UseDepthPeelingForVolumes), volumes, overlays. A vtkRenderStepsPass
   * runs without its camera pass (which would clear the traced image) and
   * post-processing; any other pass must not clear. nullptr gives back the
   * renderer's own steps (keeping the current delegate when it is one).
   */
  void SetDelegatePass(vtkRenderPass* pass);
  vtkRenderPass* GetDelegatePass();
  ///@}

  ///@{
  /**
   * Id mode: instead of shading, each pixel gets the VTK cell id (point id
   * for spheres) of its hit in R, G, B (24 bits, little end in R) and the
   * traced prop's index + 1 in A (0: no hit). Decode with DecodeId(). Props
   * that are not traced are not drawn in this mode.
   */
  vtkSetMacro(IdMode, bool);
  vtkGetMacro(IdMode, bool);
  vtkBooleanMacro(IdMode, bool);
  ///@}

  /**
   * Decodes an RGBA pixel of an id-mode image: returns false for "no hit",
   * else the traced prop index (see GetTracedProp) and the id.
   */
  static bool DecodeId(const unsigned char rgba[4], int& propIndex, vtkIdType& id);

  ///@{
  /**
   * The props traced in the last frame, in prop index order.
   */
  int GetNumberOfTracedProps() const;
  vtkProp* GetTracedProp(int index) const;
  ///@}

  ///@{
  /**
   * What the last frame did: bottom-level BVH builds, bytes of geometry
   * (nodes, primitives, normals, colors) uploaded, bytes of per-frame
   * records uploaded (camera-relative instances; 0 when they did not change:
   * a still frame, or a camera move in WORLD precision mode), shader
   * programs compiled,
   * primitives in the traced instances, traced instances.
   * GetLastBackgroundBuildsTaken() counts the trees built in the background
   * (BackgroundBuildThreshold) that took their fast tree's place.
   * Of the geometry bytes, GetLastGeometryBytesBorrowed() counts those the
   * GL buffers took from the pass's geometry cache as they are instead of
   * a copy (a CPU renderer that takes user memory, as llvmpipe, and a
   * scene of one traced geometry).
   */
  int GetLastBVHBuilds() const;
  int GetLastBackgroundBuildsTaken() const;
  vtkTypeInt64 GetLastGeometryBytesUploaded() const;
  vtkTypeInt64 GetLastGeometryBytesBorrowed() const;
  vtkTypeInt64 GetLastFrameBytesUploaded() const;
  int GetLastShaderCompiles() const;
  vtkTypeInt64 GetLastTracedPrimitives() const;
  int GetLastTracedInstances() const;
  /**
   * Pixels given camera rays in the last frame (once each, whatever the
   * samples per pixel): those where a traced instance can be (the tiles
   * that the projections of the upper boxes of its BVH touch, or the
   * rectangle around its box), not the whole viewport. After a selection
   * render, the pixels of the selector's area in the viewport, traced by
   * the first pass of its capture (0 after its later passes, which read
   * that trace again).
   */
  vtkTypeInt64 GetLastTracedPixels() const;
  /**
   * Top-level BVH builds of the last frame: scenes with more than 8
   * instances walk a BVH over the instances' world boxes, rebuilt when an
   * instance moves or changes (never for a camera move).
   */
  int GetLastTopLevelBuilds() const;
  ///@}

  ///@{
  /**
   * Where the last frame's CPU time went, in seconds (a first frame's, or
   * one after a data change; about 0 for a camera move): scene extraction
   * (without the next two), reading points and triangulating, bottom-level
   * BVH builds with their GPU records, packing into the upload layout,
   * uploading (texture buffers, instance records, the top level), shader
   * compilation. The GPU's own trace time is not among them.
   */
  double GetLastExtractionSeconds() const;
  double GetLastTriangulationSeconds() const;
  double GetLastBuildSeconds() const;
  double GetLastPackingSeconds() const;
  double GetLastUploadSeconds() const;
  double GetLastShaderCompileSeconds() const;
  ///@}

  /**
   * The feature key of the last frame's shader (what the scene needed,
   * then "f" and the varying slots its frame constants were given).
   */
  const char* GetLastFeatureKey() const;

  /**
   * The fragment shader source of the last frame (for inspection and tests).
   */
  const char* GetLastFragmentShaderSource() const;

  /**
   * Largest texture buffer (texels) the pass may use; 0 (default) means
   * GL_MAX_TEXTURE_BUFFER_SIZE. A scene that needs more fails with an error
   * instead of drawing garbage. A negative value is an error and changes
   * nothing.
   */
  virtual void SetMaximumTextureBufferTexels(vtkTypeInt64 texels);
  vtkGetMacro(MaximumTextureBufferTexels, vtkTypeInt64);

  ///@{
  /**
   * Quality of the bottom-level BVHs: 0 fast build (LBVH, for data that
   * changes often), 1 binned SAH (default), 2 full-sweep SAH (slowest build,
   * fastest frames). Changing it rebuilds the geometry on the next frame.
   */
  vtkSetClampMacro(BuildQuality, int, 0, 2);
  vtkGetMacro(BuildQuality, int);
  ///@}

  ///@{
  /**
   * Meshes of at least this many triangles (default 1,000,000; 0: never)
   * are first traced on a fast tree (LBVH) while the tree of BuildQuality
   * is built on a low-priority thread of the pass's own, one mesh at a
   * time; a later frame takes it in its place. The triangles are the same,
   * so are the images and picks (with MaximumTraversalSteps 0, the
   * default: a step cap cuts walks by tree). Their first frame is shorter
   * by most of the build; the frames before the better tree is taken trace
   * the fast one. No effect with BuildQuality 0.
   * WaitForBackgroundBuilds() waits for the builds (the next frame takes
   * them); GetNumberOfBackgroundBuilds() counts the meshes whose build is
   * not taken yet (waiting, running or done), GetNumberOfBackgroundBuildsTaken()
   * the trees frames have taken since the pass was made; the pass waits for
   * running builds when it is deleted.
   */
  vtkSetClampMacro(BackgroundBuildThreshold, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(BackgroundBuildThreshold, vtkIdType);
  void WaitForBackgroundBuilds();
  int GetNumberOfBackgroundBuilds() const;
  vtkIdType GetNumberOfBackgroundBuildsTaken() const;
  ///@}

  ///@{
  /**
   * Rays per pixel per frame (default 1, at most 256): above 1, each pixel
   * is the average of jittered sub-pixel samples (a deterministic R2
   * low-discrepancy sequence over the pixel square whose first point is the
   * pixel center), accumulated in a float buffer owned by the pass and
   * blended over the background by coverage, so silhouettes are
   * anti-aliased (not in id mode: ids do not average; id mode traces one
   * centered ray). With 1 and ProgressiveAccumulation off the pass draws
   * straight to the framebuffer (no accumulation buffer, no sampling code in
   * the shader).
   */
  vtkSetClampMacro(SamplesPerPixel, int, 1, 256);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /**
   * Progressive accumulation (default off): successive frames continue the
   * sample sequence and average into the accumulation buffer for as long as
   * nothing the traced image depends on changes (camera, lights, props and
   * their properties or matrices, data, viewport size, knobs); any change
   * starts again from one frame. N frames of 1 sample give the image of one
   * frame of N samples. The depth written is the nearest hit among the
   * first accumulated frame's samples (which include the pixel center).
   */
  vtkSetMacro(ProgressiveAccumulation, bool);
  vtkGetMacro(ProgressiveAccumulation, bool);
  vtkBooleanMacro(ProgressiveAccumulation, bool);
  ///@}

  /**
   * Frames averaged into the last image: 0 when the pass drew straight to
   * the framebuffer, 1 after a reset, n after n unchanged progressive frames.
   */
  int GetAccumulatedFrames() const;

  ///@{
  /**
   * Hard shadows (default off): each light's contribution at a hit is
   * dropped when an any-hit ray toward the light (the whole segment to a
   * positional light, an unbounded ray for a directional one or the
   * headlight) meets traced geometry. Ray origins are offset off the surface
   * along the geometric normal by float-ulp integer arithmetic (Wächter &
   * Binder, Ray Tracing Gems ch. 6), so surfaces do not shadow themselves.
   * Props drawn by raster neither cast nor receive shadows. The renderer's
   * UseShadows (raster's shadow maps) turns them on too, whatever this
   * says (and whatever a preset set).
   */
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  ///@}

  ///@{
  /**
   * Trace translucent actors (default on): vtkProperty::Opacity < 1, scalar
   * colors with alpha, textures with translucent texels, on polygonal
   * surfaces (not glyphs, points as spheres or actors with a
   * BackfaceProperty, which stay with raster). Every layer a
   * camera ray crosses is composited front to back with its alpha (opacity x
   * scalar alpha x texel alpha), as depth peeling with no peel limit; both
   * faces are drawn and lit as raster's two-sided lighting; shadow and
   * occlusion rays let through the product of (1 - alpha) of the layers they
   * cross. A pixel keeps the depth of the layer that made it opaque, or the
   * far plane (translucent layers write no depth, as VTK's translucent pass).
   * Off: they are left to the delegate's translucent pass, as before.
   * Hardware selection and id mode see the nearest layer, as raster's.
   */
  vtkSetMacro(TraceTranslucency, bool);
  vtkGetMacro(TraceTranslucency, bool);
  vtkBooleanMacro(TraceTranslucency, bool);
  ///@}

  ///@{
  /**
   * Ambient occlusion rays per sample (default 0: off; at most 64): the
   * ambient and diffuse terms of a lit hit are scaled by the fraction of
   * cosine-weighted hemisphere rays (about the geometric normal, on the
   * viewer's side) that meet no traced geometry within
   * AmbientOcclusionRadius. The rays are deterministic per pixel and sample,
   * so progressive accumulation converges.
   */
  vtkSetClampMacro(AmbientOcclusionSamples, int, 0, 64);
  vtkGetMacro(AmbientOcclusionSamples, int);
  ///@}

  ///@{
  /**
   * Length of the ambient occlusion rays in world units; 0 (default) means
   * a tenth of the diagonal of the traced props' bounds. Clamped to
   * [0, VTK_DOUBLE_MAX]; NaN is an error and changes nothing.
   */
  virtual void SetAmbientOcclusionRadius(double radius);
  vtkGetMacro(AmbientOcclusionRadius, double);
  ///@}

  ///@{
  /**
   * Cap on the node visits of each bottom-level BVH traversal (default 0:
   * unlimited). A ray that reaches the cap keeps the closest hit found so
   * far (or misses): cheaper frames, missing or wrong pixels. A speed /
   * accuracy trade measured by the benchmarks; 0 compiles no counter.
   */
  vtkSetClampMacro(MaximumTraversalSteps, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumTraversalSteps, int);
  ///@}

  ///@{
  /**
   * Maximum triangles per leaf of the triangle BVHs (default 8, 1 to 64).
   * Small leaves: deeper trees, more node visits; large leaves: more
   * triangle tests per visit. Images do not depend on it. Changing it
   * rebuilds the triangle geometry on the next frame (sphere BVHs keep
   * their own leaf size, 16).
   */
  vtkSetClampMacro(LeafSize, int, 1, 64);
  vtkGetMacro(LeafSize, int);
  ///@}

  /**
   * Coordinates the GPU computes in (see SetPrecisionMode).
   */
  enum PrecisionModes
  {
    CAMERA_RELATIVE = 0, ///< float, relative to the eye (made in double on the CPU)
    WORLD = 1            ///< plain float world coordinates
  };

  ///@{
  /**
   * CAMERA_RELATIVE (default): the shader works in world coordinates minus
   * the eye position, computed in double on the CPU every frame (meshes are
   * stored relative to their own centers), so a scene far from the origin
   * renders like the same scene at the origin; the per-instance records are
   * uploaded again whenever the camera moves.
   * WORLD: the shader works in plain float world coordinates (camera,
   * instance matrices, lights, clip planes rounded to float as world
   * values): the naive approach, fine near the origin and visibly wrong far
   * from it (float has 24 bits: 1e6 units away a float step is 0.06), but a
   * camera move uploads nothing (the records do not depend on the camera).
   * Switching modes uploads no geometry; it compiles another shader.
   */
  vtkSetClampMacro(PrecisionMode, int, CAMERA_RELATIVE, WORLD);
  vtkGetMacro(PrecisionMode, int);
  void SetPrecisionModeToCameraRelative() { this->SetPrecisionMode(CAMERA_RELATIVE); }
  void SetPrecisionModeToWorld() { this->SetPrecisionMode(WORLD); }
  const char* GetPrecisionModeAsString() const;
  ///@}

  /**
   * Named settings of the speed/accuracy knobs (see SetQualityPreset).
   */
  enum QualityPresets
  {
    CUSTOM = 0,      ///< the knobs as set one by one (no preset)
    INTERACTIVE = 1, ///< cheapest frames that stay right; converges while the view is still
    BALANCED = 2,    ///< shadows and ambient occlusion at a few times the cost, converging when still
    EXACT = 3        ///< every effect, converging to the reference image the others are measured against
  };

  ///@{
  /**
   * Sets the knobs the trade benchmark (vtkrtBenchTrade, docs/trade.md)
   * recommends for a preset in one call: BuildQuality, LeafSize,
   * SamplesPerPixel, ProgressiveAccumulation, Shadows,
   * AmbientOcclusionSamples, MaximumTraversalSteps (0 in every preset) and
   * PrecisionMode (CAMERA_RELATIVE in every preset); the other settings
   * (AmbientOcclusionRadius, IdMode, ...) are left as they are. CUSTOM sets
   * nothing. A knob set after a preset overrides that preset's value.
   * GetQualityPreset() says which preset the knobs hold now: the preset
   * last set until a knob is changed to another value, then CUSTOM (and
   * the preset again if the knob is set back). A new pass is CUSTOM: its
   * defaults are none of the presets.
   *
   * - INTERACTIVE: BuildQuality 0 (fast build), LeafSize 8, 1 sample per
   *   pixel with ProgressiveAccumulation, no shadows, no ambient occlusion:
   *   the cheapest frame, anti-aliased over still frames.
   * - BALANCED: BuildQuality 1, LeafSize 8, 1 sample per pixel with
   *   ProgressiveAccumulation, shadows, 2 ambient occlusion rays per sample:
   *   about 3x an INTERACTIVE frame, near EXACT after a few still frames.
   * - EXACT: BuildQuality 1, LeafSize 8, 4 samples per pixel with
   *   ProgressiveAccumulation, shadows, 4 ambient occlusion rays per sample:
   *   the reference the benchmark measures every other setting against.
   */
  void SetQualityPreset(int preset);
  int GetQualityPreset() const;
  void SetQualityPresetToInteractive() { this->SetQualityPreset(INTERACTIVE); }
  void SetQualityPresetToBalanced() { this->SetQualityPreset(BALANCED); }
  void SetQualityPresetToExact() { this->SetQualityPreset(EXACT); }
  const char* GetQualityPresetAsString() const;
  ///@}

protected:
  vtkRayTracePass();
  ~vtkRayTracePass() override;

  bool IdMode = false;
  int BuildQuality = 1;
  vtkIdType BackgroundBuildThreshold = 1000000;
  int SamplesPerPixel = 1;
  bool ProgressiveAccumulation = false;
  bool Shadows = false;
  bool TraceTranslucency = true;
  int AmbientOcclusionSamples = 0;
  double AmbientOcclusionRadius = 0.0;
  int MaximumTraversalSteps = 0;
  int LeafSize = 8;
  int PrecisionMode = CAMERA_RELATIVE;
  vtkTypeInt64 MaximumTextureBufferTexels = 0;
  vtkRenderPass* DelegatePass = nullptr;

private:
  vtkRayTracePass(const vtkRayTracePass&) = delete;
  void operator=(const vtkRayTracePass&) = delete;

  struct Internals;
  struct RendererStates;
  /// A state (scene, GL objects, counters) per renderer the pass serves.
  std::unique_ptr<RendererStates> States;
  /// The state of the renderer rendered last, which the getters report.
  Internals* Internal = nullptr;
};

#endif
