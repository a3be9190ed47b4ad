// Private to vtkRayTracePass: scene extraction (renderer props -> cached
// per-data geometry with its BVH, per-frame instances), and the packing of
// every cached geometry into the flat arrays the GLSL reads. No GL here.
#ifndef vtkRayTraceScene_h
#define vtkRayTraceScene_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "vtkrt/core/BVH.h"

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkActor;
class vtkDataArray;
class vtkDataObject;
class vtkDataSet;
class vtkGlyph3DMapper;
class vtkMapper;
class vtkObject;
class vtkPolyData;
class vtkProp;
class vtkRenderer;

namespace vtkrt
{
namespace pass
{

/// One bottom-level BVH with its primitives (triangles of one polydata, or
/// spheres of one glyph set / point set), relative to its local origin.
struct Geometry
{
  bool Spheres = false;
  vtkMTimeType SourceTime = 0; ///< cache key part: MTime of what it was built from
  std::string SourceKey;       ///< extra key (e.g. sphere radius settings)
  int Quality = -1;            ///< the build quality it was built with
  std::uint32_t LeafSize = 0;  ///< the maximum leaf size it was built with (triangles)
  std::array<double, 3> Origin{ { 0, 0, 0 } }; ///< local origin (model coordinates)
  std::array<double, 6> LocalBounds{ { 0, 0, 0, 0, 0, 0 } }; ///< relative to Origin
  std::vector<float> Nodes;      ///< packNodesForGpu, local indices
  std::vector<float> Primitives; ///< triangles: 12 floats each; spheres: 4 floats each (leaf order)
  std::vector<float> TriangleVertices; ///< 4 floats per triangle: bits(i0, i1, i2, 0)
  std::vector<std::uint32_t> SphereIds; ///< VTK point id per sphere (leaf order)
  std::vector<float> Normals;          ///< 4 floats per vertex, empty if none
  std::size_t PrimitiveCount = 0;
  std::size_t VertexCount = 0;
  std::size_t SkippedPrimitives = 0; ///< NaN or degenerate, never traced
  bool Used = false;
  /// Points drawn as spheres: the BVH is over the bare centers and the
  /// uploaded radii are 0; each frame gives the radii (ScreenSphereRadii).
  bool ScreenSized = false;
  /// Sphere glyphs scaled per component: ellipsoids, three texels each (the
  /// rows of the map onto their unit sphere); Spheres is set too.
  bool Ellipsoids = false;
  vtkSmartPointer<vtkObject> Keep; ///< keeps the keyed object alive
  vtkSmartPointer<vtkObject> KeepData; ///< glyphs: the keyed dataset (key: mapper, dataset)

  // Placement in the packed arrays (global offsets).
  std::uint32_t NodeBase = 0;
  std::uint32_t PrimitiveBase = 0;
  std::uint32_t NormalBase = 0;

  bool Empty() const { return Nodes.empty(); }
};

/// Colors of one (mapper, data) pair: RGBA8 per point or per cell.
struct Colors
{
  vtkMTimeType SourceTime = 0;
  bool CellColors = false;
  /// InterpolateScalarsBeforeMapping: the mapper's color texture instead of
  /// colors. Packed then holds a header (texel offset from Base, texture
  /// width, height, coordinate components), the points' texture coordinates
  /// (float bits) and the texture's RGBA8 texels, row by row.
  bool Texture = false;
  std::vector<std::uint32_t> Packed;
  bool Used = false;
  vtkSmartPointer<vtkObject> Keep;
  std::uint32_t Base = 0;
};

/// One traced instance of a geometry, rebuilt every frame (cheap).
struct Instance
{
  Geometry* Geom = nullptr;
  Colors* Color = nullptr;
  int PropIndex = 0;
  std::array<double, 16> Matrix; ///< model to world, row-major (actor matrix)
  std::array<float, 3> Ambient{ { 0, 0, 0 } };
  std::array<float, 3> Diffuse{ { 0, 0, 0 } };
  std::array<float, 3> Specular{ { 0, 0, 0 } };
  float SpecularPower = 1.0f;
  float AmbientIntensity = 0.0f; ///< weights of scalar colors, which replace
  float DiffuseIntensity = 1.0f; ///< the ambient and diffuse colors (VTK 9.1)
  bool Lit = true;
  bool UseVertexNormals = false;
  double PointSize = 0.0; ///< > 0: screen-sized spheres this many pixels wide
  std::vector<std::array<double, 4>> ClipPlanes; ///< world: n.x + d >= 0 kept
};

/// What a frame needs from the shader; also the program cache key.
struct Features
{
  bool Triangles = false;
  bool Spheres = false;
  bool VertexNormals = false;
  bool Colors = false;
  bool ColorTexture = false; ///< some colors come through a color texture
  int ClipPlanes = 0;
  int Lights = 0;
  int LightComplexity = 0;
  bool IdMode = false;
  bool Fp64 = false;
  bool TopLevel = false;
  int SamplesPerPixel = 0; ///< 0: one centered ray straight to the framebuffer
  bool Shadows = false;
  int AmbientOcclusionSamples = 0;
  int MaximumTraversalSteps = 0; ///< 0: unlimited
  bool WorldCoordinates = false; ///< vtkRayTracePass::WORLD precision mode
  bool ScreenSpheres = false;    ///< points drawn as spheres (per-frame radii)
  bool Ellipsoids = false;       ///< sphere glyphs scaled per component

  std::string Key() const;
};

/// Counters of the work one frame did.
struct FrameCounters
{
  int BVHBuilds = 0;      ///< bottom level (per data object)
  int TopLevelBuilds = 0; ///< over the instances
  std::size_t GeometryBytesUploaded = 0;
  std::size_t FrameBytesUploaded = 0;
  int ShaderCompiles = 0;
  std::size_t TracedPrimitives = 0;
  int TracedInstances = 0;
};

/// The sphere a glyph mapper's source is: every glyph scales it.
struct GlyphSphere
{
  std::array<double, 3> Center{ { 0, 0, 0 } };
  double Radius = 0.0;
  vtkMTimeType Time = 0; ///< MTime of the source it was read from
};

/// One dataset a glyph mapper draws: its plain input, or one visible leaf
/// of its composite input, with the arrays its glyphs read.
struct GlyphSet
{
  vtkDataSet* Data = nullptr;
  vtkDataArray* Scale = nullptr; ///< null: unscaled (Scaling off or no array)
  bool PerComponent = false;     ///< scaled per component: ellipsoids
  vtkDataArray* Orientation = nullptr;
  bool HasBlockColor = false; ///< the leaf's block color replaces the property's colors
  std::array<double, 3> BlockColor{ { 0, 0, 0 } };
};

/// Radii of screen-sized spheres (points drawn as spheres) for one frame.
/// VTK draws such a point PointSize pixels wide whatever its distance, so
/// the pass gives it the world radius PointSize * tan(viewAngle / 2) * z / H
/// at view depth z (perspective; H: the viewport's height in pixels) or
/// PointSize * parallelScale / H (parallel). That radius is affine in the
/// center, so the shader evaluates it per sphere from one plane, and the
/// BVH over the bare centers stays valid for every camera: its boxes grow by
/// the largest radius over the geometry's box. A camera move builds nothing.
struct ScreenSphereRadii
{
  std::array<double, 4> Plane{ { 0, 0, 0, 0 } }; ///< local radius: max(0, Plane . (c, 1))
  double MaxLocal = 0.0; ///< bound of that radius over the geometry's local box
  double MaxWorld = 0.0; ///< the same bound in world units
};

/// `localToShader`: row-major local (Geometry::Origin-relative) to shader
/// coordinates, `eyeInShader`: the camera position in shader coordinates.
ScreenSphereRadii ComputeScreenSphereRadii(const Instance& inst, vtkRenderer* ren,
  const double localToShader[16], const double eyeInShader[3]);

/// Renderer props -> instances, with geometry cached by (data object, MTime).
class Scene
{
public:
  /// Extracts the props; `traced` receives the props the pass draws (a prop
  /// index in an instance indexes it), `others` the ones left to raster.
  void Extract(vtkRenderer* ren, vtkProp** props, int count, std::vector<vtkProp*>& traced,
    std::vector<vtkProp*>& others, FrameCounters& counters);

  /// True when the packed geometry arrays changed since the last Pack().
  bool GeometryChanged() const { return this->GeometryDirty; }
  bool ColorsChanged() const { return this->ColorsDirty; }

  /// Concatenates every used geometry (global indices) into the arrays.
  void PackGeometry(std::vector<float>& nodes, std::vector<float>& triangles,
    std::vector<float>& triangleVertices, std::vector<float>& spheres,
    std::vector<float>& sphereIds, std::vector<float>& normals);
  void PackColors(std::vector<float>& colors);

  const std::vector<Instance>& GetInstances() const { return this->Instances; }
  bool HasTriangles() const;
  bool HasSpheres() const;
  bool HasScreenSpheres() const;
  bool HasEllipsoids() const;
  bool HasVertexNormals() const;
  bool HasColors() const;
  bool HasColorTexture() const;
  int MaxClipPlanes() const;

  void Clear();

  /// 0: fast (LBVH), 1: binned SAH (default), 2: full-sweep SAH. Geometry
  /// built with another quality is rebuilt on its next use.
  void SetBuildQuality(int quality) { this->BuildQuality = quality; }

  /// Maximum triangles per leaf of the triangle BVHs (>= 1, default 4).
  /// Triangle geometry built with another leaf size is rebuilt on its next
  /// use; sphere BVHs keep their own leaf size.
  void SetLeafSize(int size) { this->LeafSize = static_cast<std::uint32_t>(size < 1 ? 1 : size); }

  /// Whether this prop would be traced (public for documentation/tests).
  static bool IsTraceable(vtkProp* prop);

private:
  bool AddPolyData(vtkActor* actor, vtkMapper* mapper, vtkPolyData* poly, int propIndex,
    vtkRenderer* ren, FrameCounters& counters, const double* blockColor = nullptr);
  /// A glyph mapper's plain input or every visible, non-empty leaf of its
  /// composite input (as vtkOpenGLGlyph3DMapper), each through AddGlyphSet;
  /// false (left to raster) when the source is not a sphere or some set's
  /// arrays are not traceable.
  bool AddGlyphs(vtkActor* actor, vtkGlyph3DMapper* mapper, int propIndex, FrameCounters& counters);
  /// The sphere the mapper's single source is; false when it is not one.
  bool GetGlyphSphere(vtkGlyph3DMapper* mapper, GlyphSphere& sphere);
  /// One set's spheres or ellipsoids, cached per (mapper, dataset), and its instance.
  void AddGlyphSet(vtkActor* actor, vtkGlyph3DMapper* mapper, const GlyphSphere& sphere,
    const GlyphSet& set, int propIndex, FrameCounters& counters);
  Colors* GetColors(vtkMapper* mapper, vtkPolyData* data, vtkMTimeType time);
  void FillMaterial(vtkActor* actor, vtkMapper* mapper, Instance& inst) const;

  core::BuildOptions Options() const;
  core::BuildOptions SphereOptions() const; ///< Options() tuned for cheap sphere tests

  int BuildQuality = 1;
  std::uint32_t LeafSize = 4;
  std::map<const void*, std::unique_ptr<Geometry>> TriangleCache;
  /// Points as spheres: (polydata, null); glyphs: (mapper, dataset).
  std::map<std::pair<const void*, const void*>, std::unique_ptr<Geometry>> SphereCache;
  std::map<std::pair<const void*, const void*>, std::unique_ptr<Colors>> ColorCache;
  /// Whether a glyph source that is not a vtkSphereSource is a sphere, per
  /// mapper, decided once per (source data, MTime).
  struct GlyphSourceShape
  {
    const void* Data = nullptr;
    bool Sphere = false;
    GlyphSphere Shape; ///< its Time is the source data's MTime
    bool Used = false;
  };
  std::map<const void*, GlyphSourceShape> GlyphSourceCache;
  std::vector<Instance> Instances;
  bool GeometryDirty = true;
  bool ColorsDirty = true;
};

} // namespace pass
} // namespace vtkrt

#endif
