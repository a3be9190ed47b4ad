// Private to vtkRayTracePass: scene extraction. Renderer props become the
// frame's instances, over geometry cached per data object (rebuilt only when
// its MTime, build quality or leaf size changes) and colors cached per
// (mapper, data). No GL here.
#ifndef vtkRayTraceScene_h
#define vtkRayTraceScene_h

#include "vtkRayTraceDataSetSurfaces.h"
#include "vtkRayTraceGlyphs.h"
#include "vtkRayTraceRasterCells.h"
#include "vtkRayTraceRefinement.h"
#include "vtkRayTraceTextures.h"
#include "vtkRayTraceTypes.h"

#include "vtkrt/core/BVH.h"

#include "vtkMatrix4x4.h" // PropPart
#include "vtkSmartPointer.h"

#include <map>
#include <memory>
#include <unordered_set>
#include <utility>
#include <vector>

class vtkActor;
class vtkGlyph3DMapper;
class vtkMapper;
class vtkPolyData;
class vtkProp;
class vtkProperty;
class vtkRenderer;

namespace vtkrt
{
namespace pass
{

/// A block color in place of the property's colors, each still weighted by
/// its coefficient (the specular one too when `specularToo`).
void ApplyBlockColor(Instance& inst, vtkProperty* property, const double color[3], bool specularToo);

/// The options of the triangle BVHs for the pass's BuildQuality and
/// LeafSize, their parallel work on VTK's SMP pool.
core::BuildOptions TriangleBuildOptions(int buildQuality, std::uint32_t leafSize);

/// An actor that a renderer prop draws: the prop itself, a visible actor at
/// a leaf of a vtkAssembly's paths with the path's matrix (which vtkAssembly
/// pokes into the actor while it renders it), or the level a vtkLODProp3D
/// chose (by hand or by render time) with the prop's matrix.
struct PropPart
{
  vtkProp* Owner = nullptr; ///< the renderer's prop
  int Index = 0;            ///< which of its parts
  vtkActor* Actor = nullptr;
  vtkSmartPointer<vtkMatrix4x4> Matrix; ///< null: the actor's own
};

/// The actors `prop` draws, in the order raster draws them: an actor alone,
/// the visible leaves of a vtkAssembly (nested ones too), the level chosen
/// for a vtkLODProp3D, or the parts of a vtkPropAssembly's visible props
/// (actors and assemblies); false when it is none of these, a vtkLODProp3D
/// has chosen no level yet or is in a vtkPropAssembly (it chooses while the
/// group renders), or some visible leaf (or the level) is not an actor (a
/// volume, say). Actors without a mapper draw nothing and are left out.
bool PartsOf(vtkProp* prop, std::vector<PropPart>& parts);

/// What the renderer and the pass's settings leave to raster beside what
/// the tracer cannot draw.
struct TraceRules
{
  bool Translucency = true;       ///< translucent actors can be traced
  bool HiddenLineRemoval = false; ///< lone wireframe actors go to raster's pass for it
  /// What KeepCulledProps keeps counts as traceable: hidden props, and any
  /// looks, for the data a mapper of the pass's kinds draws.
  bool Kept = false;
};

/// Renderer props -> instances, with geometry cached by (data object, MTime).
class Scene
{
public:
  /// Extracts the props; `traced` receives the props the pass draws (a prop
  /// index in an instance indexes it), `others` the ones left to raster and
  /// the stand-ins drawing the plain lines and points of traced actors.
  void Extract(vtkRenderer* ren, vtkProp** props, int count, std::vector<vtkProp*>& traced,
    std::vector<vtkProp*>& others, FrameCounters& counters);

  /// True when the cached geometry or colors changed since MarkPacked().
  bool GeometryChanged() const { return this->GeometryDirty; }
  bool ColorsChanged() const { return this->ColorsDirty; }
  /// True when the only geometry change is refined trees taken in place of
  /// their fast trees: the same primitives, so the same hits.
  bool OnlyTreesChanged() const { return this->GeometryDirty && !this->PrimitivesDirty; }
  void MarkGeometryPacked()
  {
    this->GeometryDirty = false;
    this->PrimitivesDirty = false;
  }
  void MarkColorsPacked() { this->ColorsDirty = false; }

  /// Every cached, non-empty geometry (triangles first, then spheres), in
  /// a stable order.
  template <class Fn>
  void ForEachGeometry(Fn&& fn) const
  {
    this->ForEachSharedGeometry([&fn](const std::shared_ptr<Geometry>& g) { fn(*g); });
  }
  /// The only geometry ForEachGeometry visits, when there is exactly one,
  /// else null.
  std::shared_ptr<const Geometry> SoleGeometry() const;

  /// Every cached colors entry, in a stable order.
  template <class Fn>
  void ForEachColors(Fn&& fn) const
  {
    for (const auto& e : this->ColorCache)
    {
      fn(*e.second);
    }
  }

  const std::vector<Instance>& GetInstances() const { return this->Instances; }
  bool HasTriangles() const;
  bool HasSpheres() const;
  bool HasScreenSpheres() const;
  bool HasSphereCellIds() const; ///< some points drawn as spheres report cells apart from their points
  bool HasEllipsoids() const;
  bool HasTubes() const;
  bool HasVertexNormals() const;
  bool HasCellNormals() const;
  bool HasColors() const;
  bool HasColorTexture() const;
  bool HasTextures() const;
  bool HasFaceCulling() const;
  bool HasBackfaceProperties() const;
  /// Some lit instance has a specular color (front or back face).
  bool HasSpecular() const;
  bool HasTextureCutOuts() const;
  bool HasTranslucency() const;
  bool HasSurfaceEdges() const;
  bool HasWireframe() const;

  /// The actors' texture images and texture coordinates.
  const TextureCache& GetTextures() const { return this->Textures; }
  TextureCache& GetTextures() { return this->Textures; }

  void Clear();

  /// 0: fast (LBVH), 1: binned SAH (default), 2: full-sweep SAH. Geometry
  /// built with another quality is rebuilt on its next use.
  void SetBuildQuality(int quality) { this->BuildQuality = quality; }

  /// Triangle meshes of at least this many triangles (0: none) are built
  /// fast first and with BuildQuality in the background (BackgroundBuilds).
  void SetBackgroundBuildThreshold(vtkIdType triangles) { this->BackgroundBuildThreshold = triangles; }
  /// Waits for the background builds; the next Extract takes them.
  void WaitForBackgroundBuilds() { this->Refinements.WaitAll(); }
  int GetNumberOfBackgroundBuilds() const { return this->Refinements.Size(); }
  /// Trees built in the background that frames have taken, since the scene
  /// was made.
  vtkIdType GetNumberOfBackgroundBuildsTaken() const { return this->BackgroundBuildsTaken; }

  /// Maximum triangles per leaf of the triangle BVHs (>= 1, default 8, as the pass).
  /// Triangle geometry built with another leaf size is rebuilt on its next
  /// use; sphere BVHs keep their own leaf size.
  void SetLeafSize(int size) { this->LeafSize = static_cast<std::uint32_t>(size < 1 ? 1 : size); }

  /// Whether translucent actors are traced (default) or left to raster.
  void SetTraceTranslucency(bool trace) { this->Rules.Translucency = trace; }
  /// Whether lone wireframe actors go to raster for its hidden line removal.
  void SetHiddenLineRemoval(bool raster) { this->Rules.HiddenLineRemoval = raster; }

  /// Whether this prop would be traced (public for documentation/tests):
  /// an actor, or an assembly whose every visible part is a traceable
  /// actor, under `rules`.
  static bool IsTraceable(vtkProp* prop, const TraceRules& rules = TraceRules());

  /// Whether an actor's plain lines and points go to raster through a
  /// stand-in while its surfaces are traced (off: such an actor goes to
  /// raster whole, as hardware selection needs, whose ids are per prop).
  void SetSplitRasterCells(bool split) { this->SplitRasterCells = split; }
  /// The traced actor a stand-in of Extract's `others` draws for, or null.
  vtkProp* StandInOwner(vtkProp* prop) const { return this->RasterStandIns.OwnerOf(prop); }

private:
  /// ForEachGeometry's walk, giving each entry as the caches hold it.
  template <class Fn>
  void ForEachSharedGeometry(Fn&& fn) const
  {
    for (const auto& e : this->TriangleCache)
    {
      if (!e.second->Empty())
      {
        fn(e.second);
      }
    }
    for (const auto& e : this->SphereCache)
    {
      if (!e.second->Empty())
      {
        fn(e.second);
      }
    }
  }
  /// poly's triangles, from the cache when they are current (with the tree
  /// built in the background once it is done), else built; marked used.
  const std::shared_ptr<Geometry>& TriangleGeometry(vtkPolyData* poly, FrameCounters& counters);
  /// Marks what `poly` has cached in any form (triangles, points as
  /// spheres, lines as tubes, `mapper`'s colors) used, building nothing:
  /// a prop drawn in another form for now, or left to raster, keeps them,
  /// as raster keeps its buffers.
  void KeepCachedForms(vtkMapper* mapper, vtkPolyData* poly);
  /// One polydata of `actor`; a composite block's color and opacity
  /// (negative: none) replace the property's.
  bool AddPolyData(vtkActor* actor, vtkMapper* mapper, vtkPolyData* poly, int propIndex,
    FrameCounters& counters, const double* blockColor = nullptr, double blockOpacity = -1.0);
  /// Whether a lone actor, or an assembly's part, would be traced.
  static bool IsTraceableActor(vtkActor* actor, const TraceRules& rules);
  /// IsTraceable, with the prop's parts (PartsOf) in `parts`.
  static bool TraceableParts(vtkProp* prop, const TraceRules& rules, std::vector<PropPart>& parts);
  /// A traceable prop's parts through AddActor, each under its matrix;
  /// false when some part is left to raster (and so is the prop, whole).
  bool AddParts(const std::vector<PropPart>& parts, int propIndex, FrameCounters& counters,
    std::vector<vtkProp*>& standIns);
  /// A traceable part's glyphs (AddGlyphs) or polydata pieces
  /// (AddPolyDataMapper, through its vtkDataSetMapper's polydata mapper if
  /// it has one); false when it is left to raster.
  bool AddActor(const PropPart& part, int propIndex, FrameCounters& counters, std::vector<vtkProp*>& standIns);
  /// Keeps the cached geometry of the renderer's props that the last frame
  /// traced or kept (`previous`) and this one (Present) does not trace:
  /// culled by VTK (outside the view, or too small), hidden, or left to
  /// raster for their looks (points representation, PBR, ...), so that
  /// tracing them again builds and uploads nothing, as raster keeps an
  /// actor's buffers; adds them to Present.
  void KeepCulledProps(
    vtkRenderer* ren, const std::unordered_set<vtkProp*>& previous, FrameCounters& counters);
  /// The polydata pieces `mapper` draws for the actor (its own mapper, or
  /// the polydata mapper of its vtkDataSetMapper), each through
  /// AddPolyData; false (left to raster) when some piece cannot be traced.
  /// `standIns` receives the raster stand-ins of its plain lines and points.
  bool AddPolyDataMapper(const PropPart& part, vtkMapper* mapper, int propIndex,
    FrameCounters& counters, std::vector<vtkProp*>& standIns);
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
  /// The polydata's line cells as tubes `lineWidth` pixels wide (cached per
  /// polydata), and their instance, which takes `inst`'s material and
  /// `colors`.
  void AddTubes(
    vtkPolyData* poly, Colors* colors, const Instance& inst, double lineWidth, FrameCounters& counters);
  Colors* GetColors(vtkMapper* mapper, vtkDataSet* data, vtkMTimeType time);
  void FillMaterial(vtkActor* actor, vtkMapper* mapper, Instance& inst) const;
  /// The actor's texture on a triangle instance; false (left to raster)
  /// when raster samples it in a way the shader does not.
  bool AddTexture(vtkActor* actor, vtkPolyData* poly, Instance& inst);

  core::BuildOptions Options() const;
  core::BuildOptions SphereOptions() const; ///< Options() tuned for cheap sphere tests
  /// Whether poly's triangles are built fast first, BuildQuality's tree in
  /// the background.
  bool BuildsInBackground(vtkPolyData* poly) const;

  int BuildQuality = 1;
  vtkIdType BackgroundBuildThreshold = 0;
  TraceRules Rules;
  std::uint32_t LeafSize = 8;
  // Shared: the GPU buffers may hold a geometry's arrays as their storage
  // after the cache lets go of it (SoleGeometry()).
  std::map<const void*, std::shared_ptr<Geometry>> TriangleCache;
  /// Points as spheres: (polydata, null); glyphs: (mapper, dataset).
  std::map<std::pair<const void*, const void*>, std::shared_ptr<Geometry>> SphereCache;
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
  TextureCache Textures;
  bool SplitRasterCells = true;
  RasterCells RasterStandIns;
  DataSetSurfaces Surfaces;
  /// The props the last frame traced or kept (KeepCulledProps).
  std::unordered_set<vtkProp*> Present;
  /// While KeepCulledProps runs: cache entries are marked used, never built.
  bool Keeping = false;
  /// Keeping set for a scope, restored after it (exceptions included).
  struct KeepingScope
  {
    KeepingScope(Scene& scene, bool keeping)
      : Owner(scene)
      , Saved(scene.Keeping)
    {
      scene.Keeping = keeping;
    }
    ~KeepingScope() { this->Owner.Keeping = this->Saved; }
    KeepingScope(const KeepingScope&) = delete;
    KeepingScope& operator=(const KeepingScope&) = delete;
    Scene& Owner;
    bool Saved;
  };
  std::vector<Instance> Instances;
  bool GeometryDirty = true;
  bool PrimitivesDirty = true; ///< a geometry built, dropped or cleared, not only a tree taken
  void MarkPrimitivesChanged()
  {
    this->GeometryDirty = true;
    this->PrimitivesDirty = true;
  }
  bool ColorsDirty = true;
  BackgroundBuilds Refinements; ///< waits for its builds when destroyed
  vtkIdType BackgroundBuildsTaken = 0;
};

} // namespace pass
} // namespace vtkrt

#endif
