// Private to vtkRayTracePass: what one frame's units hand each other. The
// scene extraction fills Geometry (per data object, cached), Colors (per
// mapper and data) and Instance (per frame); Features say what the shader
// needs; FrameCounters what the frame did. No GL here.
#ifndef vtkRayTraceTypes_h
#define vtkRayTraceTypes_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/GpuLayout.h"
#include "vtkrt/core/HugePageArray.h"

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

class vtkObject;

namespace vtkrt
{
namespace pass
{
struct TextureEntry;

/// Seconds of the steady clock since `start`.
inline double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Times consecutive phases: Lap() is the seconds since the last lap (or
/// since construction), and starts the next.
class PhaseClock
{
public:
  double Lap()
  {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - this->Start).count();
    this->Start = now;
    return seconds;
  }

private:
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
};

/// A number unique to each cache entry made in the process: a rebuilt
/// entry may reuse an old one's address, never its serial (the uploaded
/// buffers keep their places by it).
inline std::uint64_t NextCacheSerial()
{
  static std::atomic<std::uint64_t> next{ 1 };
  return next++;
}

/// One bottom-level BVH with its primitives (triangles of one polydata, or
/// spheres or ellipsoids of one glyph set / point set) in the GPU's layout,
/// relative to its local origin, with local indices (the packer adds the
/// bases).
struct Geometry
{
  const std::uint64_t Serial = NextCacheSerial();
  bool Spheres = false;
  vtkMTimeType SourceTime = 0; ///< cache key part: MTime of what it was built from
  std::array<const void*, 8> SourceParts{}; ///< cache key part: the objects it was built from (triangles)
  /// Triangles rebuilt at least once: GeometryFingerprint of what they
  /// were built from (0: none taken), which a later rebuild compares.
  std::uint64_t SourceFingerprint = 0;
  std::string SourceKey;       ///< extra key (e.g. sphere radius settings)
  int Quality = -1;            ///< the build quality it was built with
  std::uint32_t LeafSize = 0;  ///< the maximum leaf size it was built with (triangles)
  /// Local coordinates are model coordinates relative to Origin, times
  /// Scale (a power of two bringing the data's size near 1, so float
  /// products of local coordinates neither overflow nor underflow).
  std::array<double, 3> Origin{ { 0, 0, 0 } }; ///< local origin (model coordinates)
  double Scale = 1.0;                          ///< local units per model unit
  std::array<double, 6> LocalBounds{ { 0, 0, 0, 0, 0, 0 } }; ///< local coordinates
  // Filled right after they are sized: no zero fill first; large ones on
  // huge pages, whose first touch costs less than that of 4 KiB pages.
  core::HugePageArray<core::gpu::Node> Nodes;
  core::HugePageArray<core::gpu::Triangle> Triangles; ///< leaf order
  core::HugePageArray<core::gpu::TriangleVertices> TriangleVertices;
  core::HugePageArray<core::gpu::Sphere> SphereRecords;       ///< leaf order
  core::HugePageArray<core::gpu::Ellipsoid> EllipsoidRecords; ///< leaf order
  core::HugePageArray<core::gpu::Segment> SegmentRecords;     ///< leaf order (tubes)
  core::HugePageArray<std::uint32_t> SphereIds; ///< VTK point id per sphere texel (leaf order)
  /// Points drawn as spheres where a sphere's VTK cell (the first cell
  /// that holds its point, as raster's selection reports) is not its point
  /// id: the cell id per sphere (leaf order); empty where every one is.
  core::HugePageArray<std::uint32_t> SphereCellIds;
  core::HugePageArray<core::gpu::Normal> Normals; ///< per point, empty if none
  core::HugePageArray<core::gpu::Normal> CellNormals; ///< per VTK cell id, empty if none
  std::size_t PrimitiveCount = 0;
  std::uint32_t MaximumId = 0; ///< the largest VTK id reported: cell (triangles, point spheres) or point (glyphs)
  std::size_t VertexCount = 0;
  std::size_t SkippedPrimitives = 0; ///< NaN or degenerate, never traced
  std::uint32_t MaxDepth = core::kMaxDepth; ///< its BVH's deepest node (the root: 0)
  double TriangulationSeconds = 0.0; ///< what making it took: points and triangles
  double BuildSeconds = 0.0;         ///< and the BVH with its records
  bool Used = false;
  /// Points drawn as spheres: the BVH is over the bare centers and the
  /// uploaded radii are 0; each frame gives the radii (ScreenSphereRadii).
  bool ScreenSized = false;
  /// Sphere glyphs scaled per component: ellipsoids (Spheres is set too).
  bool Ellipsoids = false;
  /// Lines drawn as tubes: segments in the sphere buffer, sized per frame
  /// as screen-sized spheres are (Spheres and ScreenSized are set too;
  /// SphereIds holds VTK cell ids).
  bool Tubes = false;
  vtkSmartPointer<vtkObject> Keep; ///< keeps the keyed object alive
  vtkSmartPointer<vtkObject> KeepData; ///< glyphs: the keyed dataset (key: mapper, dataset)

  bool Empty() const { return Nodes.empty(); }
  /// Points drawn as spheres (tubes share their per-frame sizing, not their
  /// shading).
  bool IsScreenSphereSet() const { return this->Spheres && this->ScreenSized && !this->Tubes; }
};

/// Colors of one (mapper, data) pair: RGBA8 per point or per cell.
struct Colors
{
  const std::uint64_t Serial = NextCacheSerial();
  vtkMTimeType SourceTime = 0;
  bool CellColors = false;
  /// InterpolateScalarsBeforeMapping: the mapper's color texture instead of
  /// colors. Packed then holds a header (texel offset from its base, texture
  /// width, height, coordinate components), the points' texture coordinates
  /// (float bits) and the texture's RGBA8 texels, row by row.
  bool Texture = false;
  std::vector<std::uint32_t> Packed;
  bool Used = false;
  vtkSmartPointer<vtkObject> Keep;
};

/// One traced instance of a geometry, rebuilt every frame (cheap).
struct Instance
{
  Geometry* Geom = nullptr;
  Colors* Color = nullptr;
  int PropIndex = 0;
  /// What vtkHardwareSelector's composite index pass reports for it: the
  /// block's flat index under a composite mapper, 1 under a plain one.
  unsigned int CompositeIndex = 1;
  /// False for a composite block made unpickable (block pickability): a
  /// selection looks through it, as raster's does.
  bool Pickable = true;
  std::array<double, 16> Matrix; ///< model to world, row-major (actor matrix)
  std::array<float, 3> Ambient{ { 0, 0, 0 } };
  std::array<float, 3> Diffuse{ { 0, 0, 0 } };
  std::array<float, 3> Specular{ { 0, 0, 0 } };
  float SpecularPower = 1.0f;
  float AmbientIntensity = 0.0f; ///< weights of scalar colors, which replace
  float DiffuseIntensity = 1.0f; ///< the ambient and diffuse colors (VTK 9.1)
  bool Lit = true;
  bool UseVertexNormals = false;
  bool UseCellNormals = false; ///< one normal per cell (none per point, or flat)
  double PointSize = 0.0; ///< > 0: screen-sized spheres (tubes: LineWidth) this many pixels wide
  std::vector<std::array<double, 4>> ClipPlanes; ///< world: n.x + d >= 0 kept
  /// The actor's texture and the data's texture coordinates (both or neither).
  const TextureEntry* Texture = nullptr;
  const TextureEntry* TextureCoordinates = nullptr;
  bool TextureOnBackface = true; ///< vtkProperty::ShowTexturesOnBackface
  /// The actor's BackfaceProperty: colors for back faces, each weighted by
  /// its coefficient (as the front ones).
  bool BackfaceProperty = false;
  std::array<float, 3> BackAmbient{ { 0, 0, 0 } };
  std::array<float, 3> BackDiffuse{ { 0, 0, 0 } };
  std::array<float, 3> BackSpecular{ { 0, 0, 0 } };
  float BackSpecularPower = 1.0f;
  bool CullBackfaces = false;  ///< vtkProperty::BackfaceCulling (wins over front, as raster)
  bool CullFrontfaces = false; ///< vtkProperty::FrontfaceCulling
  /// VTK draws the actor in its translucent pass (!vtkActor::GetIsOpaque()):
  /// its layers are composited with alpha Opacity x scalar alpha x texel alpha.
  bool Translucent = false;
  float Opacity = 1.0f; ///< vtkProperty::Opacity, in [0, 1]
  /// Cell edges: over the surface (EdgeVisibility) in EdgeColor, or alone
  /// (the wireframe representation), LineWidth pixels wide.
  bool SurfaceEdges = false;
  bool Wireframe = false;
  std::array<float, 3> EdgeColor{ { 0, 0, 0 } };
  float LineWidth = 1.0f;
};

/// What a frame needs from the shader; also the program cache key.
struct Features
{
  bool Triangles = false;
  bool Spheres = false;
  bool VertexNormals = false;
  bool CellNormals = false;
  bool Colors = false;
  bool ColorTexture = false; ///< some colors come through a color texture
  int ClipPlanes = 0;
  int Lights = 0;
  int LightComplexity = 0;
  bool IdMode = false;
  bool SelectIds = false; ///< prop, VTK id and composite index per pixel (hardware selection)
  bool Fp64 = false;
  bool TopLevel = false;
  bool SingleInstance = false; ///< one instance, its record in uniforms (no top level)
  bool ProjectiveRays = false;  ///< camera rays unprojected per pixel (CameraFrame::AffineRays false)
  /// Camera rays start their walk from their screen tile's entry list
  /// (TileEntryLists): one triangle instance, affine camera-relative rays.
  bool TileEntries = false;
  /// Every triangle tree is one leaf: the shader tests its triangles, no walk.
  bool LeafTrees = false;
  int SamplesPerPixel = 0; ///< 0: one centered ray straight to the framebuffer
  bool Shadows = false;
  int AmbientOcclusionSamples = 0;
  int MaximumTraversalSteps = 0; ///< 0: unlimited
  bool WorldCoordinates = false; ///< vtkRayTracePass::WORLD precision mode
  bool ScreenSpheres = false;    ///< points drawn as spheres (per-frame radii)
  bool SphereCellIds = false;    ///< some points drawn as spheres have cell ids apart from their point ids
  bool Ellipsoids = false;       ///< sphere glyphs scaled per component
  bool Tubes = false;            ///< lines drawn as tubes
  bool Textures = false;         ///< some triangles carry an actor texture
  bool FaceCulling = false;      ///< some triangles are culled on one side
  bool BackfaceProperties = false; ///< some triangles have a back-face material
  bool Specular = false;         ///< some lit surface has a specular color (else no specular term)
  /// The frame is drawn into float colors (a wrapping vtkToneMappingPass's
  /// buffer): colors above 1 are kept, as raster's fragments keep them.
  bool FloatColors = false;
  /// Camera rays end at the depth already in the renderer's viewport: that of
  /// the renderers before it (PreserveDepthBuffer, or Erase off), or of its
  /// own opaque raster props drawn before traced translucent layers.
  bool DepthBelow = false;
  bool TextureCutOuts = false;   ///< some textures have fully transparent texels
  bool Translucent = false;      ///< some instances are translucent (layers composited)
  /// With translucency and shadow or occlusion rays (the frame sets it only
  /// then): the camera ray's layer loop also walks the layers' visibility
  /// rays, one call of the walk (GPU compilers inline a copy per call),
  /// instead of a walk nested in shading (cheaper where pixels run in CPU
  /// SIMD lanes, as on llvmpipe).
  bool InterleavedWalks = false;
  bool SurfaceEdges = false;     ///< some triangles show their cell edges (EdgeVisibility)
  bool Wireframe = false;        ///< some triangles are drawn as their cell edges alone
  int StackSize = static_cast<int>(core::kMaxStackSize); ///< entries of the shader's BVH stacks (VTKRT_STACK_SIZE)
  /// Walk stack entries of one word: no buffer holds more records than a
  /// packed entry indexes (core::gpu::kMaxPackedStackIndex).
  bool PackedStackEntries = true;

  std::string Key() const;
  /// Key() without how the walks go (stack size, entries, leaf trees, stack
  /// entry layout): shaders of one image key trace the same hits, so a
  /// refined tree's shader continues an accumulation.
  std::string ImageKey() const;
  /// What of the edge code the shader holds: the surface edges' colors (not
  /// in shaders that write ids), the wires' hit test.
  bool SurfaceEdgeCode() const { return this->Triangles && this->SurfaceEdges && !this->IdMode && !this->SelectIds; }
  bool WireframeCode() const { return this->Triangles && this->Wireframe; }
};

/// Counters of the work one frame did.
struct FrameCounters
{
  int BVHBuilds = 0;      ///< bottom level (per data object)
  int BackgroundBuildsTaken = 0; ///< refined trees taking their fast tree's place
  int TopLevelBuilds = 0; ///< over the instances
  std::size_t GeometryBytesUploaded = 0;
  std::size_t GeometryBytesBorrowed = 0; ///< of those, taken from the cache as they are
  std::size_t RetreeBytesUploaded = 0;   ///< of those, for refined trees taken, nothing else changed
  std::size_t FrameBytesUploaded = 0;
  int ShaderCompiles = 0;
  std::size_t TracedPrimitives = 0;
  int TracedInstances = 0;
  std::size_t TracedPixels = 0; ///< pixels given camera rays (the footprint's)

  /// Where the frame's CPU time went, in seconds (a first frame's cost).
  double ExtractionSeconds = 0.0;    ///< props to instances, without the two below
  double TriangulationSeconds = 0.0; ///< points read, polygons and strips to triangles
  double BuildSeconds = 0.0;         ///< bottom-level BVHs and their GPU records
  double PackingSeconds = 0.0;       ///< the upload layout
  double UploadSeconds = 0.0;        ///< texture buffers, records, top level
  double ShaderCompileSeconds = 0.0;

  /// Counts a geometry just made: a build, and its time.
  void AddBuild(const Geometry& g, double seconds)
  {
    ++this->BVHBuilds;
    this->TriangulationSeconds += g.TriangulationSeconds;
    this->BuildSeconds += seconds - g.TriangulationSeconds;
  }
};

// The frame caches' bookkeeping: an entry is marked used by the props of a
// frame that need it, and what no prop used is dropped after the frame.

/// A cache entry's "used this frame" flag (entries held by pointer or by value).
template <class Pointer>
auto usedFlag(Pointer& entry) -> decltype((entry->Used))
{
  return entry->Used;
}
template <class T>
auto usedFlag(T& entry) -> decltype((entry.Used))
{
  return entry.Used;
}

/// Marks every entry of a cache unused (the frame's props mark theirs).
template <class Cache>
void markUnused(Cache& cache)
{
  for (auto& e : cache)
  {
    usedFlag(e.second) = false;
  }
}

/// Marks the cache's entry for `key` used, if there is one; whether there is.
template <class Cache, class Key>
bool markCached(Cache& cache, const Key& key)
{
  const auto it = cache.find(key);
  if (it == cache.end())
  {
    return false;
  }
  usedFlag(it->second) = true;
  return true;
}

/// Drops the entries no prop used this frame; returns whether any went.
template <class Cache>
bool dropUnused(Cache& cache)
{
  bool dropped = false;
  for (auto it = cache.begin(); it != cache.end();)
  {
    if (usedFlag(it->second))
    {
      ++it;
      continue;
    }
    it = cache.erase(it);
    dropped = true;
  }
  return dropped;
}

} // namespace pass
} // namespace vtkrt

#endif
