#include "vtkRayTracePacker.h"

#include "vtkRayTraceScene.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cstring>

namespace vtkrt
{
namespace pass
{

namespace
{
/// Records per chunk of a parallel copy.
constexpr vtkIdType kCopyGrain = 1 << 16;

/// Copies n records to dst, in parallel chunks on VTK's SMP pool.
template <class Record>
void copyRecords(const Record* src, std::size_t n, Record* dst)
{
  vtkSMPTools::For(0, static_cast<vtkIdType>(n), kCopyGrain, [=](vtkIdType b, vtkIdType e) {
    std::memcpy(dst + b, src + b, static_cast<std::size_t>(e - b) * sizeof(Record));
  });
}

/// Words to whole texels (four words each).
std::size_t paddedWords(std::size_t words)
{
  return (words + 3) / 4 * 4;
}

/// Zeros the words from `used` up to whole texels.
void padWords(std::uint32_t* words, std::size_t used)
{
  std::fill(words + used, words + paddedWords(used), 0u);
}
} // namespace

namespace
{
/// The sphere texels of `g`'s records, before its cell ids.
std::size_t sphereRecordTexelsOf(const Geometry& g)
{
  return g.SphereRecords.size() * core::gpu::texelsOf<core::gpu::Sphere>() +
    g.EllipsoidRecords.size() * core::gpu::texelsOf<core::gpu::Ellipsoid>() +
    g.SegmentRecords.size() * core::gpu::texelsOf<core::gpu::Segment>();
}

/// All of `g`'s sphere texels: its records, then its cell ids four a texel.
std::size_t sphereTexelsOf(const Geometry& g)
{
  return sphereRecordTexelsOf(g) + paddedWords(g.SphereCellIds.size()) / 4;
}

/// Places `g` at the ends of `sizes` and moves them past it. A sphere
/// geometry starts and ends on whole texels of ids (one id word a sphere
/// texel), so that appending one never rewrites another's texel.
GeometryPlacement placeAtEnd(const Geometry& g, GeometrySizes& sizes)
{
  GeometryPlacement place;
  place.Serial = g.Serial;
  place.Root = static_cast<std::uint32_t>(sizes.Nodes);
  sizes.Nodes += g.Nodes.size();
  if (g.Spheres)
  {
    place.PrimitiveBase = static_cast<std::uint32_t>(sizes.SphereTexels);
    sizes.SphereTexels = paddedWords(sizes.SphereTexels + sphereTexelsOf(g));
  }
  else
  {
    place.PrimitiveBase = static_cast<std::uint32_t>(sizes.Triangles);
    sizes.Triangles += g.Triangles.size();
    place.NormalBase = static_cast<std::uint32_t>(sizes.Normals);
    place.CellNormalBase = static_cast<std::uint32_t>(sizes.Normals + g.Normals.size());
    sizes.Normals += g.Normals.size() + g.CellNormals.size();
  }
  return place;
}

} // namespace

std::uint32_t SphereCellIdBase(const Geometry& g, const GeometryPlacement& place)
{
  // Word 4 (base + records) is the first cell id: less the base, so that
  // adding a sphere's texel index (base + k) reads the k-th.
  return g.SphereCellIds.empty()
    ? 0u
    : 4u * (place.PrimitiveBase + static_cast<std::uint32_t>(sphereRecordTexelsOf(g))) - place.PrimitiveBase;
}

namespace
{
/// The records a geometry takes, all buffers together (for the waste test).
std::size_t recordsOf(const Geometry& g)
{
  return g.Nodes.size() + g.Triangles.size() + sphereTexelsOf(g) + g.Normals.size() + g.CellNormals.size();
}

std::size_t recordsOf(const GeometrySizes& sizes)
{
  return sizes.Nodes + sizes.Triangles + sizes.SphereTexels + sizes.Normals;
}

/// `n` records from `records` to the buffer of `out`, whose pointer holds
/// record `from`, at record `at`.
template <class Record, class Target>
void copyAt(const Record* records, std::size_t n, Target* out, std::size_t from, std::size_t at)
{
  copyRecords(records, n, reinterpret_cast<Record*>(out + (at - from)));
}

/// Writes one placed geometry's records (and its sphere padding).
void writePlaced(const Geometry& g, const GeometryPlacement& place, const GeometryTargets& out)
{
  const GeometrySizes& from = out.From;
  if (g.Spheres)
  {
    std::size_t at = place.PrimitiveBase;
    copyAt(g.SphereRecords.data(), g.SphereRecords.size(), out.Spheres, from.SphereTexels, at);
    at += g.SphereRecords.size() * core::gpu::texelsOf<core::gpu::Sphere>();
    copyAt(g.EllipsoidRecords.data(), g.EllipsoidRecords.size(), out.Spheres, from.SphereTexels, at);
    at += g.EllipsoidRecords.size() * core::gpu::texelsOf<core::gpu::Ellipsoid>();
    copyAt(g.SegmentRecords.data(), g.SegmentRecords.size(), out.Spheres, from.SphereTexels, at);
    at += g.SegmentRecords.size() * core::gpu::texelsOf<core::gpu::Segment>();
    // Cell ids, four a texel, after the records (SphereCellIdBase).
    auto* cellIds = reinterpret_cast<std::uint32_t*>(out.Spheres + (at - from.SphereTexels));
    copyRecords(g.SphereCellIds.data(), g.SphereCellIds.size(), cellIds);
    padWords(cellIds, g.SphereCellIds.size());
    at += paddedWords(g.SphereCellIds.size()) / 4;
    std::fill(out.Spheres + (at - from.SphereTexels), out.Spheres + (paddedWords(at) - from.SphereTexels),
      core::gpu::Texel{});
    // One id word a sphere texel: the ids start at the same index (those of
    // the cell ids' texels are never read).
    std::uint32_t* ids = out.SphereIds + (place.PrimitiveBase - from.SphereTexels);
    copyRecords(g.SphereIds.data(), g.SphereIds.size(), ids);
    std::fill(ids + g.SphereIds.size(), ids + paddedWords(sphereTexelsOf(g)), 0u);
  }
  else
  {
    if (out.Triangles)
    {
      copyAt(g.Triangles.data(), g.Triangles.size(), out.Triangles, from.Triangles, place.PrimitiveBase);
    }
    if (out.TriangleVertices)
    {
      copyAt(g.TriangleVertices.data(), g.TriangleVertices.size(), out.TriangleVertices, from.Triangles,
        place.PrimitiveBase);
    }
    if (out.Normals)
    {
      copyAt(g.Normals.data(), g.Normals.size(), out.Normals, from.Normals, place.NormalBase);
      copyAt(g.CellNormals.data(), g.CellNormals.size(), out.Normals, from.Normals, place.CellNormalBase);
    }
  }
  if (!out.Nodes)
  {
    return;
  }
  // Local child / primitive indices become global ones.
  core::gpu::Node* nodes = out.Nodes + (place.Root - from.Nodes);
  vtkSMPTools::For(0, static_cast<vtkIdType>(g.Nodes.size()), kCopyGrain, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      nodes[i] = PlacedNode(g, place, static_cast<std::size_t>(i));
    }
  });
}

/// `used` plus room, in records of `texelsPerRecord` texels, within `limit`
/// texels; room for 32 appends like the last, up to a quarter of `scene`
/// (all buffers' records: one large change does not ask for 32 times itself).
std::size_t withRoom(std::size_t used, std::size_t texelsPerRecord, std::size_t limit, std::size_t lastAppend,
  std::size_t scene)
{
  const std::size_t room =
    used + std::max<std::size_t>({ used / 4, 1024, std::min(32 * lastAppend, scene / 4) });
  return std::max(used, std::min(room, limit / texelsPerRecord));
}
} // namespace

core::gpu::Node PlacedNode(const Geometry& g, const GeometryPlacement& place, std::size_t i)
{
  core::gpu::Node node = g.Nodes[i];
  node.index += node.count == 0 ? place.Root : place.PrimitiveBase;
  return node;
}

GeometrySizes WithRoom(const GeometrySizes& used, std::size_t limit, const GeometrySizes& lastAppend)
{
  using namespace core::gpu;
  GeometrySizes out;
  const std::size_t scene = recordsOf(used);
  out.Nodes = withRoom(used.Nodes, texelsOf<Node>(), limit, lastAppend.Nodes, scene);
  out.Triangles = std::min(withRoom(used.Triangles, texelsOf<Triangle>(), limit, lastAppend.Triangles, scene),
    withRoom(used.Triangles, texelsOf<core::gpu::TriangleVertices>(), limit, lastAppend.Triangles, scene));
  out.SphereTexels = std::max(withRoom(used.SphereTexels, 1, limit, lastAppend.SphereTexels, scene) / 4 * 4,
    used.SphereTexels);
  out.Normals = withRoom(used.Normals, texelsOf<Normal>(), limit, lastAppend.Normals, scene);
  return out;
}

GeometrySizes SizesPast(const GeometrySizes& from, const GeometrySizes& to)
{
  GeometrySizes out;
  out.Nodes = to.Nodes - from.Nodes;
  out.Triangles = to.Triangles - from.Triangles;
  out.SphereTexels = to.SphereTexels - from.SphereTexels;
  out.Normals = to.Normals - from.Normals;
  return out;
}

namespace
{
template <class Record>
LentArray lentArrayOf(const core::HugePageArray<Record>& records)
{
  LentArray out;
  if (!records.empty())
  {
    out.Data = records.data();
    out.Texels = records.size() * core::gpu::texelsOf<Record>();
    out.ReadablePastEnd = core::readableBytesPastEnd(records);
  }
  return out;
}
} // namespace

GeometryLoans LendableArrays(const Geometry& sole)
{
  GeometryLoans out;
  out.Nodes = lentArrayOf(sole.Nodes);
  if (!sole.Spheres)
  {
    out.Triangles = lentArrayOf(sole.Triangles);
    out.TriangleVertices = lentArrayOf(sole.TriangleVertices);
    if (sole.CellNormals.empty())
    {
      out.Normals = lentArrayOf(sole.Normals);
    }
    else if (sole.Normals.empty())
    {
      out.Normals = lentArrayOf(sole.CellNormals);
    }
  }
  return out;
}

GeometryLayout LayOutGeometry(const Scene& scene)
{
  GeometryLayout out;
  scene.ForEachGeometry([&out](const Geometry& g) { out.Placements[&g] = placeAtEnd(g, out); });
  return out;
}

void WriteGeometry(const Scene& scene, const GeometryLayout& layout, const GeometryTargets& out)
{
  scene.ForEachGeometry([&](const Geometry& g) { writePlaced(g, layout.Placements.at(&g), out); });
}

bool ExtendLayout(const Scene& scene, const GeometryLayout& current, const GeometrySizes& capacity,
  GeometryLayout& next, std::vector<const Geometry*>& appended)
{
  next = GeometryLayout();
  static_cast<GeometrySizes&>(next) = current;
  appended.clear();
  std::size_t live = 0;
  scene.ForEachGeometry([&](const Geometry& g) {
    const auto kept = current.Placements.find(&g);
    if (kept != current.Placements.end() && kept->second.Serial == g.Serial)
    {
      next.Placements[&g] = kept->second;
      live += recordsOf(g);
    }
    else
    {
      appended.push_back(&g);
    }
  });
  for (const Geometry* g : appended)
  {
    next.Placements[g] = placeAtEnd(*g, next);
    live += recordsOf(*g);
  }
  const bool fits = next.Nodes <= capacity.Nodes && next.Triangles <= capacity.Triangles &&
    next.SphereTexels <= capacity.SphereTexels && next.Normals <= capacity.Normals;
  return fits && recordsOf(next) <= 2 * live;
}

void WriteAppended(
  const std::vector<const Geometry*>& appended, const GeometryLayout& layout, const GeometryTargets& out)
{
  for (const Geometry* g : appended)
  {
    writePlaced(*g, layout.Placements.at(g), out);
  }
}

namespace
{
/// Places `c` at the end of `layout`, on a whole texel.
void placeColorsAtEnd(const Colors& c, ColorsLayout& layout)
{
  layout.Placements[&c] = { c.Serial, static_cast<std::uint32_t>(layout.Words) };
  layout.Words = paddedWords(layout.Words + c.Packed.size());
}

/// Writes one placed entry and its padding; `out` holds word `from`.
void writeColorsPlaced(const Colors& c, std::uint32_t base, std::uint32_t* out, std::size_t from)
{
  copyRecords(c.Packed.data(), c.Packed.size(), out + (base - from));
  padWords(out + (base - from), c.Packed.size());
}
} // namespace

ColorsLayout LayOutColors(const Scene& scene)
{
  ColorsLayout out;
  scene.ForEachColors([&out](const Colors& c) { placeColorsAtEnd(c, out); });
  return out;
}

void WriteColors(const Scene& scene, const ColorsLayout& layout, std::uint32_t* out)
{
  scene.ForEachColors([&](const Colors& c) { writeColorsPlaced(c, layout.Placements.at(&c).Base, out, 0); });
}

bool ExtendColors(const Scene& scene, const ColorsLayout& current, std::size_t capacity, ColorsLayout& next,
  std::vector<const Colors*>& appended)
{
  next = ColorsLayout();
  next.Words = current.Words;
  appended.clear();
  std::size_t live = 0;
  scene.ForEachColors([&](const Colors& c) {
    const auto kept = current.Placements.find(&c);
    if (kept != current.Placements.end() && kept->second.Serial == c.Serial)
    {
      next.Placements[&c] = kept->second;
      live += paddedWords(c.Packed.size());
    }
    else
    {
      appended.push_back(&c);
    }
  });
  for (const Colors* c : appended)
  {
    placeColorsAtEnd(*c, next);
    live += paddedWords(c->Packed.size());
  }
  return next.Words <= capacity && next.Words <= 2 * live;
}

void WriteAppendedColors(
  const std::vector<const Colors*>& appended, const ColorsLayout& layout, std::uint32_t* out, std::size_t from)
{
  for (const Colors* c : appended)
  {
    writeColorsPlaced(*c, layout.Placements.at(c).Base, out, from);
  }
}

std::size_t ColorWordsWithRoom(std::size_t words, std::size_t limit, std::size_t lastAppend)
{
  return 4 * withRoom(words / 4, 1, limit, (lastAppend + 3) / 4, words / 4);
}

} // namespace pass
} // namespace vtkrt
