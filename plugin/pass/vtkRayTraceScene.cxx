#include "vtkRayTraceScene.h"

#include "vtkRayTraceCompositePieces.h"
#include "vtkRayTraceGeometry.h"
#include "vtkRayTraceTubes.h"

#include "vtkActor.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataObject.h"
#include "vtkGlyph3DMapper.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <functional>
#include <sstream>
#include <unordered_set>

namespace vtkrt
{
namespace pass
{

namespace
{
/// The cells of `poly` only raster draws: lines not drawn as tubes,
/// vertices not drawn as spheres.
RasterCellKinds rasterCellKinds(vtkPolyData* poly, bool pointsAsSpheres, bool linesAsTubes)
{
  RasterCellKinds kinds;
  kinds.Lines = poly->GetNumberOfLines() > 0 && !linesAsTubes;
  kinds.Verts = poly->GetNumberOfVerts() > 0 && !pointsAsSpheres;
  return kinds;
}

/// Whether raster must draw `poly` as `actor` shows it, whole: translucent
/// tubes or points as spheres (raster draws one layer of them, the pass
/// would composite two); polygon edges or wires drawn as tubes (raster's
/// shaded fake tubes).
bool hasUntraceableCells(vtkPolyData* poly, vtkActor* actor, bool pointsAsSpheres, bool linesAsTubes)
{
  const bool lines = poly->GetNumberOfLines() > 0;
  const bool verts = poly->GetNumberOfVerts() > 0;
  vtkProperty* property = actor->GetProperty();
  const bool surfaces = poly->GetNumberOfPolys() > 0 || poly->GetNumberOfStrips() > 0;
  const bool spheres = pointsAsSpheres && (verts || property->GetRepresentation() == VTK_POINTS);
  if (actor->HasTranslucentPolygonalGeometry() && ((lines && linesAsTubes) || spheres))
  {
    return true;
  }
  const bool edges = property->GetEdgeVisibility() || property->GetRepresentation() == VTK_WIREFRAME;
  return edges && surfaces && property->GetRenderLinesAsTubes() && property->GetLineWidth() > 1.0f;
}

/// The second part of a tube geometry's cache key (a points-as-spheres
/// geometry of the same polydata has none).
const char kTubesKey = 0;

/// Whether `g` was built from `source` (its objects, at its time).
bool builtFrom(const Geometry& g, const GeometrySource& source)
{
  return g.SourceTime == source.Time && g.SourceParts == source.Parts;
}

void setBuiltFrom(Geometry& g, const GeometrySource& source)
{
  g.SourceTime = source.Time;
  g.SourceParts = source.Parts;
}

/// A cache entry's key and bookkeeping, from the geometry `to` takes the
/// place of.
void takeCachePlace(const Geometry& from, Geometry& to)
{
  to.SourceTime = from.SourceTime;
  to.SourceParts = from.SourceParts;
  to.SourceFingerprint = from.SourceFingerprint;
  to.SourceKey = from.SourceKey;
  to.Quality = from.Quality;
  to.LeafSize = from.LeafSize;
  to.Keep = from.Keep;
  to.KeepData = from.KeepData;
  to.Used = from.Used;
  to.TriangulationSeconds = from.TriangulationSeconds;
  to.BuildSeconds = from.BuildSeconds;
}

/// A triangle instance's cell edges as the property asks: VTK draws edges
/// over a surface (EdgeVisibility; not in the wireframe or points
/// representations) in EdgeColor, and the wireframe representation as the
/// cells' edges in the surface's colors; both LineWidth pixels wide
/// (vtkProperty clamps it to >= 0; the shader gives edges at least 1.1, as
/// VTK's, and wires at least 1, as OpenGL's lines).
void FillEdges(vtkProperty* property, Instance& inst)
{
  inst.Wireframe = property->GetRepresentation() == VTK_WIREFRAME;
  inst.SurfaceEdges = property->GetRepresentation() == VTK_SURFACE && property->GetEdgeVisibility();
  double c[3];
  property->GetEdgeColor(c);
  for (int k = 0; k < 3; ++k)
  {
    inst.EdgeColor[k] = static_cast<float>(c[k]);
  }
  inst.LineWidth = property->GetLineWidth();
}

} // namespace

const std::shared_ptr<Geometry>& Scene::TriangleGeometry(vtkPolyData* poly, FrameCounters& counters)
{
  if (this->Keeping)
  {
    static const std::shared_ptr<Geometry> none = std::make_shared<Geometry>();
    const auto it = this->TriangleCache.find(poly);
    if (it == this->TriangleCache.end())
    {
      return none;
    }
    it->second->Used = true;
    return it->second;
  }
  // Keyed by what the triangles are made of: new scalars (colors) keep
  // the BVH and its records.
  const GeometrySource source = GeometrySourceOf(poly);
  auto& entry = this->TriangleCache[poly];
  const bool sameBuild = entry && entry->Quality == this->BuildQuality && entry->LeafSize == this->LeafSize;
  std::uint64_t fingerprint = 0;
  if (sameBuild && !builtFrom(*entry, source))
  {
    // Data that changed once is likely to change again (a pipeline
    // running again, a time series over one mesh): from its first
    // rebuild on, its contents are fingerprinted, and the same contents
    // keep the BVH.
    fingerprint = GeometryFingerprint(poly);
    if (fingerprint != 0 && fingerprint == entry->SourceFingerprint)
    {
      setBuiltFrom(*entry, source);
    }
  }
  if (!sameBuild || !builtFrom(*entry, source))
  {
    const auto start = std::chrono::steady_clock::now();
    const bool background = this->BuildsInBackground(poly);
    const core::BuildOptions options = this->Options();
    core::BuildOptions now = options;
    now.quality = background ? core::BuildQuality::Fast : options.quality;
    RefinementInput refinement;
    entry = BuildTriangles(poly, now, background ? &refinement : nullptr);
    entry->SourceFingerprint = fingerprint;
    counters.AddBuild(*entry, SecondsSince(start));
    entry->Quality = this->BuildQuality;
    entry->LeafSize = this->LeafSize;
    setBuiltFrom(*entry, source);
    entry->Keep = poly;
    this->MarkPrimitivesChanged();
    if (background && !entry->Empty())
    {
      this->Refinements.Start(poly, entry, std::move(refinement), BackgroundBuildOptions(options));
    }
  }
  else if (!entry->Used)
  {
    // Taken at the geometry's first use in a frame only: every instance of
    // a frame traces the same tree.
    if (std::shared_ptr<Geometry> refined = this->Refinements.TakeDone(poly, *entry))
    {
      takeCachePlace(*entry, *refined);
      entry = std::move(refined);
      ++counters.BackgroundBuildsTaken;
      ++this->BackgroundBuildsTaken;
      this->GeometryDirty = true; // the same primitives: PrimitivesDirty stays
    }
  }
  entry->Used = true;
  return entry;
}

void Scene::KeepCachedForms(vtkMapper* mapper, vtkPolyData* poly)
{
  const void* data = poly;
  markCached(this->TriangleCache, poly);
  markCached(this->SphereCache, std::make_pair(data, static_cast<const void*>(nullptr)));
  markCached(this->SphereCache, std::make_pair(data, static_cast<const void*>(&kTubesKey)));
  markCached(this->ColorCache, std::make_pair(static_cast<const void*>(mapper), data));
}

bool Scene::AddPolyData(vtkActor* actor, vtkMapper* mapper, vtkPolyData* poly, int propIndex,
  FrameCounters& counters, const double* blockColor, double blockOpacity)
{
  vtkProperty* property = actor->GetProperty();
  const bool pointsAsSpheres = property->GetRenderPointsAsSpheres() &&
    (property->GetRepresentation() == VTK_POINTS || poly->GetNumberOfVerts() > 0);
  const vtkMTimeType time = poly->GetMTime();
  Instance inst;
  inst.PropIndex = propIndex;
  this->FillMaterial(actor, mapper, inst);
  // A block color replaces the scalar colors too, as
  // vtkCompositePolyDataMapper2 draws it, but not their alpha: translucent
  // scalar colors under a block color are left to raster.
  Colors* colors = nullptr;
  if (blockColor)
  {
    if (Colors* scalars = this->GetColors(mapper, poly, time))
    {
      const std::size_t first = scalars->Texture ? scalars->Packed[0] : 0;
      if (std::any_of(scalars->Packed.begin() + first, scalars->Packed.end(),
            [](std::uint32_t rgba) { return (rgba >> 24) < 255u; }))
      {
        return false;
      }
    }
    ApplyBlockColor(inst, property, blockColor, false);
  }
  else
  {
    colors = this->GetColors(mapper, poly, time);
  }
  if (blockOpacity >= 0.0)
  {
    // A translucent block's layers are composited; an opaque one's stop the
    // layer walk (alpha 1), as raster draws them in its opaque pass.
    inst.Opacity = static_cast<float>(std::min(blockOpacity, 1.0));
  }

  // Kept triangles of an actor drawn as points for now (KeepCulledProps).
  if ((property->GetRepresentation() != VTK_POINTS || this->Keeping) &&
    (poly->GetNumberOfPolys() > 0 || poly->GetNumberOfStrips() > 0))
  {
    const std::shared_ptr<Geometry>& entry = this->TriangleGeometry(poly, counters);
    if (!entry->Empty())
    {
      Instance tri = inst;
      tri.Geom = entry.get();
      tri.Color = colors;
      // As vtkOpenGLPolyDataMapper: point normals unless flat, else cell
      // normals, else the geometric normal.
      tri.UseVertexNormals = !entry->Normals.empty() && property->GetInterpolation() != VTK_FLAT;
      tri.UseCellNormals = !tri.UseVertexNormals && !entry->CellNormals.empty();
      if (!this->AddTexture(actor, poly, tri))
      {
        return false;
      }
      FillEdges(property, tri);
      this->Instances.push_back(tri);
    }
  }

  const auto sphereKey = std::make_pair(static_cast<const void*>(poly), static_cast<const void*>(nullptr));
  if (pointsAsSpheres && this->Keeping)
  {
    markCached(this->SphereCache, sphereKey);
  }
  else if (pointsAsSpheres)
  {
    // VTK draws these PointSize pixels wide at any distance: the BVH is
    // over the bare centers, the radii come with each frame's camera
    // (ScreenSphereRadii), so neither a camera move nor a new point size
    // rebuilds anything.
    std::ostringstream key;
    key << "points:" << property->GetRepresentation();
    // Keyed as the triangles (a superset of what the spheres are made of):
    // new scalars keep the spheres' BVH.
    const GeometrySource source = GeometrySourceOf(poly);
    auto& entry = this->SphereCache[sphereKey];
    if (!entry || !builtFrom(*entry, source) || entry->SourceKey != key.str() ||
      entry->Quality != this->BuildQuality)
    {
      const auto start = std::chrono::steady_clock::now();
      entry = BuildScreenSpheres(
        poly, property->GetRepresentation() == VTK_POINTS, this->SphereOptions());
      counters.AddBuild(*entry, SecondsSince(start));
      entry->Quality = this->BuildQuality;
      setBuiltFrom(*entry, source);
      entry->SourceKey = key.str();
      entry->Keep = poly;
      this->MarkPrimitivesChanged();
    }
    entry->Used = true;
    if (!entry->Empty())
    {
      Instance sph = inst;
      sph.Geom = entry.get();
      sph.PointSize = std::max(0.0, static_cast<double>(property->GetPointSize()));
      // Cell colors through each sphere's cell (SphereCellIds), as raster.
      sph.Color = colors;
      this->Instances.push_back(sph);
    }
  }
  if (DrawsLinesAsTubes(property) && poly->GetNumberOfLines() > 0)
  {
    this->AddTubes(poly, colors, inst, property->GetLineWidth(), counters);
  }
  // After the forms drawn now, whose first use in a frame may take a tree
  // built in the background.
  this->KeepCachedForms(mapper, poly);
  return true;
}

void Scene::AddTubes(
  vtkPolyData* poly, Colors* colors, const Instance& inst, double lineWidth, FrameCounters& counters)
{
  // LineWidth pixels wide at any distance, as VTK draws them: the BVH is
  // over the bare segments and the radii come with each frame's camera, as
  // for points drawn as spheres.
  const auto cacheKey = std::make_pair(static_cast<const void*>(poly), static_cast<const void*>(&kTubesKey));
  if (this->Keeping)
  {
    markCached(this->SphereCache, cacheKey);
    return;
  }
  auto& entry = this->SphereCache[cacheKey];
  const vtkMTimeType time = poly->GetMTime();
  if (!entry || entry->SourceTime != time || entry->Quality != this->BuildQuality)
  {
    const auto start = std::chrono::steady_clock::now();
    entry = BuildTubes(poly, this->SphereOptions());
    counters.AddBuild(*entry, SecondsSince(start));
    entry->Quality = this->BuildQuality;
    entry->SourceTime = time;
    entry->Keep = poly;
    this->MarkPrimitivesChanged();
  }
  entry->Used = true;
  if (!entry->Empty())
  {
    Instance tube = inst;
    tube.Geom = entry.get();
    tube.PointSize = lineWidth;
    tube.Color = colors;
    this->Instances.push_back(tube);
  }
}

bool Scene::AddPolyDataMapper(const PropPart& part, vtkMapper* mapper, int propIndex,
  FrameCounters& counters, std::vector<vtkProp*>& standIns)
{
  vtkActor* actor = part.Actor;
  if (!this->Keeping)
  {
    mapper->Update();
  }
  vtkDataObject* input = mapper->GetInputDataObject(0, 0);
  const bool pointsAsSpheres = actor->GetProperty()->GetRenderPointsAsSpheres();
  const bool linesAsTubes = DrawsLinesAsTubes(actor->GetProperty());
  std::vector<Piece> pieces;
  bool ok = true;
  if (auto* poly = vtkPolyData::SafeDownCast(input))
  {
    pieces.push_back({ poly, false, { { 0, 0, 0 } }, 1u });
  }
  else if (vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkCompositeDataDisplayAttributes* attributes = nullptr;
    if (auto* m2 = vtkCompositePolyDataMapper2::SafeDownCast(mapper))
    {
      attributes = m2->GetCompositeDataDisplayAttributes();
    }
    Piece root{ nullptr, false, { { 0, 0, 0 } }, 0u };
    unsigned int flatIndex = 0;
    ok = CollectPieces(input, attributes, true, root, flatIndex, pieces);
    ColorMissingArrays(mapper, pieces);
  }
  else if (input)
  {
    ok = false;
  }
  // Plain lines and points of a single polydata are drawn by a raster
  // stand-in; a composite with some goes to raster whole.
  const bool splittable = this->SplitRasterCells && vtkPolyData::SafeDownCast(input);
  for (const Piece& piece : pieces)
  {
    if (!piece.Visible)
    {
      continue;
    }
    const RasterCellKinds kinds = rasterCellKinds(piece.Poly, pointsAsSpheres, linesAsTubes);
    // Kept (its cached forms marked below) whatever raster draws it with now:
    // translucent spheres or tubes, say.
    ok = ok && (this->Keeping || ((!kinds.Any() || splittable) &&
      !hasUntraceableCells(piece.Poly, actor, pointsAsSpheres, linesAsTubes)));
    if (ok && kinds.Any())
    {
      standIns.push_back(
        this->RasterStandIns.Get(part.Owner, part.Index, actor, mapper, piece.Poly, kinds));
    }
  }
  if (ok)
  {
    for (const Piece& piece : pieces)
    {
      const std::size_t first = this->Instances.size();
      // A hidden block keeps what it has cached (showing it again builds
      // and uploads nothing, as raster keeps its buffers) and draws nothing.
      bool added = false;
      {
        const KeepingScope scope(*this, this->Keeping || !piece.Visible);
        added = this->AddPolyData(actor, mapper, piece.Poly, propIndex, counters,
          piece.HasColor ? piece.Color.data() : nullptr, piece.Opacity);
      }
      if (!piece.Visible)
      {
        this->Instances.resize(first);
        continue;
      }
      if (!added)
      {
        return false;
      }
      for (std::size_t i = first; i < this->Instances.size(); ++i)
      {
        this->Instances[i].CompositeIndex = piece.FlatIndex;
        this->Instances[i].Pickable = piece.Pickable;
      }
    }
  }
  return ok;
}

bool Scene::AddActor(const PropPart& part, int propIndex, FrameCounters& counters, std::vector<vtkProp*>& standIns)
{
  vtkActor* actor = part.Actor;
  vtkMapper* mapper = actor->GetMapper();
  if (actor->HasTranslucentPolygonalGeometry() && actor->GetProperty()->GetOpacity() <= 0.0 &&
    !this->Keeping)
  {
    // Invisible, and never selected (vtkOpenGLActor): traced as nothing,
    // what it has cached kept (as raster keeps its buffers).
    const std::size_t first = this->Instances.size();
    std::vector<vtkProp*> none;
    {
      const KeepingScope scope(*this, true);
      this->AddActor(part, propIndex, counters, none);
    }
    this->Instances.resize(first);
    return true;
  }
  if (auto* glyphs = vtkGlyph3DMapper::SafeDownCast(mapper))
  {
    return this->AddGlyphs(actor, glyphs, propIndex, counters);
  }
  return this->AddPolyDataMapper(part, this->Surfaces.MapperFor(mapper), propIndex, counters, standIns);
}

bool Scene::AddParts(const std::vector<PropPart>& parts, int propIndex, FrameCounters& counters,
  std::vector<vtkProp*>& standIns)
{
  /// As vtkAssembly renders a part: its path's matrix poked in, then its
  /// own restored (also when the build throws).
  struct PokedMatrix
  {
    const PropPart& Part;
    explicit PokedMatrix(const PropPart& part)
      : Part(part)
    {
      if (part.Matrix)
      {
        part.Actor->PokeMatrix(part.Matrix);
      }
    }
    ~PokedMatrix()
    {
      if (this->Part.Matrix)
      {
        this->Part.Actor->PokeMatrix(nullptr);
      }
    }
  };
  for (const PropPart& part : parts)
  {
    PokedMatrix poked(part);
    if (!this->AddActor(part, propIndex, counters, standIns))
    {
      return false;
    }
  }
  return true;
}

void Scene::Extract(vtkRenderer* ren, vtkProp** props, int count, std::vector<vtkProp*>& traced,
  std::vector<vtkProp*>& others, FrameCounters& counters)
{
  traced.clear();
  others.clear();
  this->Instances.clear();
  markUnused(this->TriangleCache);
  markUnused(this->SphereCache);
  markUnused(this->ColorCache);
  markUnused(this->GlyphSourceCache);
  this->Textures.BeginFrame();
  this->RasterStandIns.BeginFrame();
  this->Surfaces.BeginFrame();

  std::vector<PropPart> parts;
  for (int i = 0; i < count; ++i)
  {
    vtkProp* prop = props[i];
    if (!TraceableParts(prop, this->Rules, parts))
    {
      others.push_back(prop);
      continue;
    }
    const int propIndex = static_cast<int>(traced.size());
    const std::size_t firstInstance = this->Instances.size();
    std::vector<vtkProp*> standIns;
    // An actor whose every cell is raster's is left to raster whole.
    const bool ok = this->AddParts(parts, propIndex, counters, standIns) &&
      (standIns.empty() || this->Instances.size() > firstInstance);
    if (ok)
    {
      traced.push_back(prop);
      others.insert(others.end(), standIns.begin(), standIns.end());
    }
    else
    {
      this->Instances.resize(firstInstance);
      others.push_back(prop);
    }
  }

  // Forget what no prop uses any more (but for a selection frame, whose
  // actors with plain lines went to raster whole for this frame only).
  const bool keep = !this->SplitRasterCells;
  if (!keep)
  {
    std::unordered_set<vtkProp*> previous;
    previous.swap(this->Present);
    this->Present.insert(traced.begin(), traced.end());
    if (ren)
    {
      this->KeepCulledProps(ren, previous, counters);
    }
    this->RasterStandIns.EndFrame();
    this->Surfaces.EndFrame();
  }
  const bool trianglesDropped = !keep && dropUnused(this->TriangleCache);
  const bool spheresDropped = !keep && dropUnused(this->SphereCache);
  if (trianglesDropped || spheresDropped)
  {
    this->MarkPrimitivesChanged();
  }
  this->ColorsDirty = (!keep && dropUnused(this->ColorCache)) || this->ColorsDirty;
  dropUnused(this->GlyphSourceCache);
  this->Refinements.Tidy([this](const void* key) -> const Geometry* {
    const auto entry = this->TriangleCache.find(key);
    return entry == this->TriangleCache.end() ? nullptr : entry->second.get();
  });
  this->Textures.EndFrame();
  counters.TracedInstances = static_cast<int>(this->Instances.size());
  for (const Instance& inst : this->Instances)
  {
    counters.TracedPrimitives += inst.Geom->PrimitiveCount;
  }
}

bool Scene::HasTriangles() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->Spheres; });
}
bool Scene::HasSpheres() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->Spheres; });
}
bool Scene::HasScreenSpheres() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->IsScreenSphereSet(); });
}
bool Scene::HasSphereCellIds() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->SphereCellIds.empty(); });
}
bool Scene::HasTubes() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->Tubes; });
}
bool Scene::HasEllipsoids() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->Ellipsoids; });
}
bool Scene::HasVertexNormals() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.UseVertexNormals; });
}
bool Scene::HasCellNormals() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.UseCellNormals; });
}
bool Scene::HasColors() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Color != nullptr; });
}
bool Scene::HasColorTexture() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Color != nullptr && i.Color->Texture; });
}

bool Scene::HasTextures() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Texture != nullptr; });
}
bool Scene::HasFaceCulling() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->Spheres && (i.CullBackfaces || i.CullFrontfaces); });
}
bool Scene::HasBackfaceProperties() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->Spheres && i.BackfaceProperty; });
}

bool Scene::HasSpecular() const
{
  // Not black: raster darkens with a negative specular color too.
  const auto notBlack = [](const std::array<float, 3>& c) { return c[0] != 0.0f || c[1] != 0.0f || c[2] != 0.0f; };
  return std::any_of(this->Instances.begin(), this->Instances.end(), [&notBlack](const Instance& i) {
    return i.Lit && (notBlack(i.Specular) || (i.BackfaceProperty && notBlack(i.BackSpecular)));
  });
}

bool Scene::HasTranslucency() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Translucent; });
}

bool Scene::HasSurfaceEdges() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->Spheres && i.SurfaceEdges; });
}
bool Scene::HasWireframe() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->Spheres && i.Wireframe; });
}

bool Scene::HasTextureCutOuts() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Texture && i.Texture->CutOuts; });
}

core::BuildOptions Scene::Options() const
{
  return TriangleBuildOptions(this->BuildQuality, this->LeafSize);
}

core::BuildOptions TriangleBuildOptions(int buildQuality, std::uint32_t leafSize)
{
  core::BuildOptions options;
  options.quality = buildQuality == 0
    ? core::BuildQuality::Fast
    : (buildQuality == 2 ? core::BuildQuality::High : core::BuildQuality::Medium);
  // The shader's walk stack packs a leaf's count into a few bits.
  options.maxLeafSize = std::min(leafSize, core::gpu::kMaxPackedStackCount);
  // The builder's parallel work goes to VTK's SMP pool, as the locator's:
  // threads of its own would compete with the pool's spinning workers.
  options.parallelFor = [](std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
    // Few large items (subtrees, chunks) one at a time; many by VTK's grain.
    const vtkIdType grain = n <= 256 ? 1 : 0;
    vtkSMPTools::For(0, static_cast<vtkIdType>(n), grain,
      [&body](vtkIdType b, vtkIdType e) { body(static_cast<std::size_t>(b), static_cast<std::size_t>(e)); });
  };
  return options;
}

core::BuildOptions Scene::SphereOptions() const
{
  core::BuildOptions options = this->Options();
  // A sphere test (one texel fetch, a few flops) costs the shader far less
  // than a node visit (four fetches, two box tests): shallower trees with
  // larger leaves trace faster (docs/pass.md).
  options.traversalCost = 3.0;
  options.maxLeafSize = 16;
  return options;
}

std::shared_ptr<const Geometry> Scene::SoleGeometry() const
{
  std::shared_ptr<const Geometry> sole;
  std::size_t count = 0;
  this->ForEachSharedGeometry([&](const std::shared_ptr<Geometry>& g) {
    sole = g;
    ++count;
  });
  return count == 1 ? sole : nullptr;
}

bool Scene::BuildsInBackground(vtkPolyData* poly) const
{
  if (this->BackgroundBuildThreshold <= 0 || this->BuildQuality == 0)
  {
    return false;
  }
  // A cell of k points is k - 2 triangles, fan or strip.
  vtkIdType triangles = 0;
  for (vtkCellArray* cells : { poly->GetPolys(), poly->GetStrips() })
  {
    triangles += cells->GetNumberOfConnectivityIds() - 2 * cells->GetNumberOfCells();
  }
  return triangles >= this->BackgroundBuildThreshold;
}

void Scene::Clear()
{
  this->Refinements.LetGoAll();
  this->TriangleCache.clear();
  this->SphereCache.clear();
  this->ColorCache.clear();
  this->GlyphSourceCache.clear();
  this->Textures.Clear();
  this->Instances.clear();
  this->MarkPrimitivesChanged();
  this->ColorsDirty = true;
}

} // namespace pass
} // namespace vtkrt

