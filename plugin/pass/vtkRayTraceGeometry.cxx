#include "vtkRayTraceGeometry.h"

#include "vtkRayTraceRefinement.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSurfaceTriangulation.h"
#include "vtkUnsignedCharArray.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/LocalFrame.h"
#include "vtkrt/core/Mesh.h"
#include "vtkrt/core/SurfaceTriangulation.h"

#include <algorithm>
#include <cstring>
#include <atomic>
#include <functional>
#include <numeric>
#include <limits>
#include <optional>

namespace vtkrt
{
namespace pass
{

using core::Vec3;

namespace
{
/// fn(begin, end) over [0, n) on VTK's SMP pool.
template <class Fn>
void smpFor(std::size_t n, Fn&& fn)
{
  vtkSMPTools::For(0, static_cast<vtkIdType>(n),
    [&fn](vtkIdType b, vtkIdType e) { fn(static_cast<std::size_t>(b), static_cast<std::size_t>(e)); });
}
} // namespace

/// The frame the primitives are built in: that of the finite boxes' union
/// (model coordinates), so the BVH and every GPU record are in units near 1
/// whatever the data's size and offset.
core::ScaledFrame buildFrame(std::size_t count, const std::function<core::AABB<double>(std::size_t)>& boxOf)
{
  core::AABB<double> all;
  for (std::size_t i = 0; i < count; ++i)
  {
    const core::AABB<double> b = boxOf(i);
    if (!b.isEmpty() && b.isFinite())
    {
      all.extend(b.min);
      all.extend(b.max);
    }
  }
  return core::ScaledFrame::of(all);
}

/// Takes a tree built in `frame`'s coordinates into `g`: its skipped-primitive
/// count and, when it is not empty, the local origin (the center of what is
/// traced: NaN primitives are not in the tree; in model coordinates with
/// the frame's scale), the bounds relative to it and the GPU nodes (moved
/// out of `bvh`). Returns the origin in the frame's coordinates, or nothing
/// for an empty tree.
std::optional<Vec3<double>> adoptBVH(Geometry& g, core::GpuBVH& bvh, const core::ScaledFrame& frame)
{
  g.SkippedPrimitives = bvh.stats.skippedPrimitives;
  // A tree of more than a root whose depth says 0 did not count it: the
  // deepest any may be.
  g.MaxDepth = bvh.nodes.size() > 1 && bvh.stats.maxDepth == 0 ? core::kMaxDepth : bvh.stats.maxDepth;
  if (bvh.empty())
  {
    return std::nullopt;
  }
  const Vec3<double> origin = bvh.origin();
  const Vec3<double> modelOrigin = frame.toModel(origin);
  g.Origin = { { modelOrigin.x, modelOrigin.y, modelOrigin.z } };
  g.Scale = frame.scale;
  for (int k = 0; k < 3; ++k)
  {
    g.LocalBounds[2 * k] = bvh.bounds.min[k] - origin[k];
    g.LocalBounds[2 * k + 1] = bvh.bounds.max[k] - origin[k];
  }
  g.Nodes = std::move(bvh.nodes);
  return origin;
}

namespace
{
/// `edges` of fan triangle `t` less those from a point whose edge flag is 0.
std::uint8_t fanEdges(const core::SurfaceTriangles& triangles, std::size_t t, std::uint32_t edges,
  const unsigned char* edgeFlags, std::size_t edgeFlagCount)
{
  using namespace core::gpu;
  if (edgeFlags)
  {
    const std::uint32_t* tri = &triangles.pointIds[3 * t];
    const auto flagged = [&](std::uint32_t point) { return point >= edgeFlagCount || edgeFlags[point] != 0; };
    edges &= (flagged(tri[0]) ? kEdge01 : 0u) | (flagged(tri[1]) ? kEdge12 : 0u) | (flagged(tri[2]) ? kEdge20 : 0u);
  }
  return static_cast<std::uint8_t>(edges);
}

/// The point edge flags VTK's raster reads (unsigned chars, one per point), or null.
const unsigned char* pointEdgeFlags(vtkPolyData* poly)
{
  auto* flags = vtkUnsignedCharArray::SafeDownCast(poly->GetPointData()->GetAttribute(vtkDataSetAttributes::EDGEFLAG));
  return flags && flags->GetNumberOfTuples() >= poly->GetNumberOfPoints() && flags->GetNumberOfComponents() == 1
    ? flags->GetPointer(0)
    : nullptr;
}

/// The cell edges triangle `t` shows (vtkOpenGLIndexBufferObject's edge
/// values): a fan's triangles keep the polygon's outline, not its
/// diagonals (its first and last triangles hold the polygon's first and
/// last edges, every one its outer edge v1-v2), masked by the points' edge
/// flags when given (VTK's EDGEFLAG: the edge from a point whose flag is 0
/// is not drawn); a strip's triangles keep all three, as raster draws them.
std::uint8_t cellEdgesOf(const core::SurfaceTriangles& triangles, std::size_t t,
  const unsigned char* edgeFlags, std::size_t edgeFlagCount)
{
  using namespace core::gpu;
  const std::uint8_t part = triangles.part(t);
  if ((part & core::FanTriangle) == 0)
  {
    return (part & core::WholeTriangle) != 0 && edgeFlags ? fanEdges(triangles, t, kAllEdges, edgeFlags, edgeFlagCount)
                                                           : std::uint8_t(kAllEdges);
  }
  const std::int64_t cell = triangles.cellId(t);
  const bool first = t == 0 || triangles.cellId(t - 1) != cell;
  const bool last = t + 1 == triangles.count || triangles.cellId(t + 1) != cell;
  const std::uint32_t edges = kEdge12 | (first ? kEdge01 : 0u) | (last ? kEdge20 : 0u);
  return fanEdges(triangles, t, edges, edgeFlags, edgeFlagCount);
}

/// `normals`' first `count` vectors (one per point, or per cell; `of` says
/// which) as GPU records, as raster reads them by point or cell id. Normals
/// not of 3 components are left out; an array of too few tuples gives those
/// past its end a zero normal (raster reads past the end). Both with a
/// warning.
void readNormals(vtkDataArray* normals, std::size_t count, const char* of,
  core::HugePageArray<core::gpu::Normal>& out)
{
  if (!normals)
  {
    return;
  }
  const std::size_t given = static_cast<std::size_t>(normals->GetNumberOfTuples());
  const bool vectors = normals->GetNumberOfComponents() == 3;
  if (!vectors || given < count)
  {
    vtkGenericWarningMacro("vtkRayTracePass: the " << of << " normals '"
                                                   << (normals->GetName() ? normals->GetName() : "") << "' have "
                                                   << given << " tuples of " << normals->GetNumberOfComponents()
                                                   << " components for " << count << " " << of << "s: "
                                                   << (vectors ? "the rest have none" : "shaded without them")
                                                   << ".");
  }
  if (!vectors)
  {
    return;
  }
  out.resize(count);
  smpFor(count, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      double nv[3] = { 0.0, 0.0, 0.0 };
      if (i < given)
      {
        normals->GetTuple(static_cast<vtkIdType>(i), nv);
      }
      out[i] = { { static_cast<float>(nv[0]), static_cast<float>(nv[1]), static_cast<float>(nv[2]) }, 0.0f };
    }
  });
}
} // namespace

void ReadPoints(vtkPoints* pts, core::NoFillArray<Vec3<double>>& out)
{
  const vtkIdType n = pts ? pts->GetNumberOfPoints() : 0;
  out.resize(static_cast<std::size_t>(n));
  if (n == 0)
  {
    return;
  }
  vtkDataArray* data = pts->GetData();
  auto* floats = vtkFloatArray::FastDownCast(data);
  auto* doubles = vtkDoubleArray::FastDownCast(data);
  smpFor(out.size(), [&](std::size_t b, std::size_t e) {
    if (floats || doubles)
    {
      for (std::size_t i = b; i < e; ++i)
      {
        out[i] = floats ? Vec3<double>(floats->GetPointer(0)[3 * i], floats->GetPointer(0)[3 * i + 1],
                            floats->GetPointer(0)[3 * i + 2])
                        : Vec3<double>(doubles->GetPointer(0)[3 * i], doubles->GetPointer(0)[3 * i + 1],
                            doubles->GetPointer(0)[3 * i + 2]);
      }
      return;
    }
    for (std::size_t i = b; i < e; ++i)
    {
      data->GetTuple(static_cast<vtkIdType>(i), &out[i].x);
    }
  });
}

GeometrySource GeometrySourceOf(vtkPolyData* poly)
{
  GeometrySource s;
  vtkDataArray* normals = poly->GetPointData()->GetNormals();
  vtkDataArray* cellNormals = poly->GetCellData()->GetNormals();
  vtkDataArray* edgeFlags = poly->GetPointData()->GetAttribute(vtkDataSetAttributes::EDGEFLAG);
  s.Parts = { { poly->GetPoints(), poly->GetVerts(), poly->GetLines(), poly->GetPolys(), poly->GetStrips(),
    normals, cellNormals, edgeFlags } };
  // The point and cell data's own MTimes too: normals edited in place and
  // announced by their point data's Modified() (as vtkPolyData::GetMTime
  // would see it). A new scalar array bumps them as well; the fingerprint
  // then keeps the BVH.
  s.Time = std::max({ vtkSurfaceTriangulation::GetGeometryMTime(poly),
    poly->GetPointData()->vtkObject::GetMTime(), poly->GetCellData()->vtkObject::GetMTime() });
  for (vtkDataArray* array : { normals, cellNormals, edgeFlags })
  {
    if (array)
    {
      s.Time = std::max(s.Time, array->GetMTime());
    }
  }
  return s;
}

namespace
{
std::uint64_t mix64(std::uint64_t h)
{
  // splitmix64's finalizer: every input bit reaches every output bit.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

/// The fingerprint of `bytes` bytes: 1 MiB chunks hashed on VTK's SMP pool,
/// combined in order.
std::uint64_t fingerprintBytes(const unsigned char* data, std::size_t bytes)
{
  constexpr std::size_t kChunk = std::size_t(1) << 20;
  const std::size_t chunks = (bytes + kChunk - 1) / kChunk;
  std::vector<std::uint64_t> hashes(chunks);
  smpFor(chunks, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c)
    {
      const unsigned char* p = data + c * kChunk;
      const std::size_t n = std::min(kChunk, bytes - c * kChunk);
      std::uint64_t h = mix64(c + 0x9e3779b97f4a7c15ull);
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
      {
        std::uint64_t w;
        std::memcpy(&w, p + i, 8);
        h = (h ^ (w * 0x9e3779b97f4a7c15ull)) * 0xc2b2ae3d27d4eb4full;
        h ^= h >> 29;
      }
      std::uint64_t tail = 0;
      std::memcpy(&tail, p + i, n - i);
      hashes[c] = mix64(h ^ tail ^ n);
    }
  });
  std::uint64_t h = mix64(bytes);
  for (std::uint64_t c : hashes)
  {
    h = mix64(h ^ c);
  }
  return h;
}

/// Folds `array` (absent, or its type, shape and values, in one block) into `h`.
void fingerprintArray(vtkDataArray* array, std::uint64_t& h)
{
  if (!array)
  {
    h = mix64(h ^ 0x5bd1e995u);
    return;
  }
  const std::size_t bytes = static_cast<std::size_t>(array->GetNumberOfValues()) *
    static_cast<std::size_t>(array->GetDataTypeSize());
  h = mix64(h ^ (static_cast<std::uint64_t>(array->GetDataType()) << 32) ^
    static_cast<std::uint64_t>(array->GetNumberOfComponents()));
  h = mix64(h ^ (bytes ? fingerprintBytes(static_cast<const unsigned char*>(array->GetVoidPointer(0)), bytes)
                       : 0u));
}
} // namespace

std::uint64_t GeometryFingerprint(vtkPolyData* poly)
{
  std::vector<vtkDataArray*> arrays;
  arrays.push_back(poly->GetPoints() ? poly->GetPoints()->GetData() : nullptr);
  for (vtkCellArray* cells : { poly->GetVerts(), poly->GetLines(), poly->GetPolys(), poly->GetStrips() })
  {
    arrays.push_back(cells->GetOffsetsArray());
    arrays.push_back(cells->GetConnectivityArray());
  }
  arrays.push_back(poly->GetPointData()->GetNormals());
  arrays.push_back(poly->GetCellData()->GetNormals());
  arrays.push_back(poly->GetPointData()->GetAttribute(vtkDataSetAttributes::EDGEFLAG));
  // Bit arrays (no byte size) and arrays not in one block: no fingerprint,
  // decided before hashing anything.
  for (vtkDataArray* array : arrays)
  {
    if (array && (!array->HasStandardMemoryLayout() || array->GetDataType() == VTK_BIT))
    {
      return 0;
    }
  }
  std::uint64_t h = 0x243f6a8885a308d3ull;
  for (vtkDataArray* array : arrays)
  {
    fingerprintArray(array, h);
  }
  return h == 0 ? 1 : h;
}

core::GpuBVH BuildTriangleBVH(const core::SurfaceTriangles& triangles,
  const core::NoFillArray<Vec3<double>>& points, const core::BuildOptions& options)
{
  core::TriangleMesh<double> mesh;
  mesh.vertices = points.data();
  mesh.vertexCount = points.size();
  mesh.indices = triangles.pointIds.data();
  mesh.triangleCount = triangles.count;
  return core::buildGpuBVHConcurrentBounds(
    mesh.triangleCount, [&mesh](std::size_t i) { return core::triangleBox(mesh, i); }, options);
}

std::unique_ptr<Geometry> BuildTriangles(
  vtkPolyData* poly, const core::BuildOptions& options, RefinementInput* refinement)
{
  auto g = std::make_unique<Geometry>();
  const auto start = std::chrono::steady_clock::now();
  // Shared with vtkBVHCellLocator on the same polydata.
  const vtkSmartPointer<vtkSurfaceTriangulation> shared = vtkSurfaceTriangulation::Get(poly);
  const core::SurfaceTriangles& triangles = shared->GetTriangles();
  if (shared->GetNumberOfInvalidPointIdCells() > 0)
  {
    // Once a build: the other cells are drawn (raster reads past the points).
    vtkGenericWarningMacro("vtkRayTracePass: " << shared->GetNumberOfInvalidPointIdCells()
                                               << " cell(s) of polydata " << poly
                                               << " refer to point ids outside [0, " << poly->GetNumberOfPoints()
                                               << "): not drawn");
  }
  double bounds[6];
  shared->GetFinitePointBounds(bounds);
  const core::ScaledFrame frame = core::ScaledFrame::of(vtkMath::AreBoundsInitialized(bounds)
      ? core::AABB<double>(Vec3<double>(bounds[0], bounds[2], bounds[4]), Vec3<double>(bounds[1], bounds[3], bounds[5]))
      : core::AABB<double>());
  core::NoFillArray<Vec3<double>> points;
  ReadPoints(poly->GetPoints(), points);
  smpFor(points.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      points[i] = frame.toLocal(points[i]);
    }
  });
  const unsigned char* edgeFlags = pointEdgeFlags(poly);
  const auto edgeFlagCount = static_cast<std::size_t>(poly->GetNumberOfPoints());
  g->TriangulationSeconds = SecondsSince(start);

  core::GpuBVH bvh = BuildTriangleBVH(triangles, points, options);
  g->Spheres = false;
  g->VertexCount = points.size();
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh, frame);
  if (!adopted)
  {
    return g;
  }
  core::HugePageArray<Vec3<float>> rel(points.size());
  smpFor(points.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      rel[i] = Vec3<float>(points[i] - *adopted);
    }
  });
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->Triangles.resize(n);
  g->TriangleVertices.resize(n);
  std::atomic<std::uint32_t> maximumId{ 0 };
  smpFor(n, [&](std::size_t b, std::size_t e) {
    std::uint32_t chunkMaximum = 0;
    for (std::size_t k = b; k < e; ++k)
    {
      const std::uint32_t tri = bvh.primIndex[k];
      // Odd strip triangles are drawn with their last two points swapped
      // (VTK's winding).
      const std::uint32_t* ids = &triangles.pointIds[3 * static_cast<std::size_t>(tri)];
      const bool flip = (triangles.part(tri) & core::FlippedStripTriangle) != 0;
      const std::uint32_t a = ids[0], b1 = flip ? ids[2] : ids[1], c = flip ? ids[1] : ids[2];
      core::gpu::Triangle& t = g->Triangles[k];
      t.v0 = rel[a];
      t.v1 = rel[b1];
      t.v2 = rel[c];
      t.cellId = static_cast<std::uint32_t>(triangles.cellId(tri));
      t.cellEdges = cellEdgesOf(triangles, tri, edgeFlags, edgeFlagCount);
      t.unused2 = 0.0f;
      g->TriangleVertices[k] = { { a, b1, c }, 0u };
      chunkMaximum = std::max(chunkMaximum, t.cellId);
    }
    std::uint32_t seen = maximumId.load();
    while (seen < chunkMaximum && !maximumId.compare_exchange_weak(seen, chunkMaximum))
    {
    }
  });
  g->MaximumId = maximumId.load();
  readNormals(poly->GetPointData()->GetNormals(), points.size(), "point", g->Normals);
  readNormals(poly->GetCellData()->GetNormals(), static_cast<std::size_t>(poly->GetNumberOfCells()),
    "cell", g->CellNormals);
  if (refinement)
  {
    refinement->Triangulation = shared;
    refinement->Frame = frame;
    refinement->Points = std::move(points);
    refinement->Order = std::move(bvh.primIndex);
  }
  return g;
}

std::unique_ptr<Geometry> BuildSpheres(const std::vector<Vec3<double>>& modelCenters,
  const std::vector<double>& modelRadii, const std::vector<std::uint32_t>& ids,
  const core::BuildOptions& options)
{
  auto g = std::make_unique<Geometry>();
  g->Spheres = true;
  const std::size_t count = std::min(modelCenters.size(), modelRadii.size());
  const core::ScaledFrame frame = buildFrame(count, [&](std::size_t i) {
    // A bare center's smallest radius is no size: around a zero coordinate
    // it would make a box of 2^-1022 and scale the frame by 2^1000.
    const Vec3<double> r(modelRadii[i] > std::numeric_limits<double>::min() ? modelRadii[i] : 0.0);
    return core::AABB<double>(modelCenters[i] - r, modelCenters[i] + r);
  });
  std::vector<Vec3<double>> centers(count);
  std::vector<double> radii(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    centers[i] = frame.toLocal(modelCenters[i]);
    // A positive radius stays positive (bare centers have the smallest one).
    radii[i] = modelRadii[i] > 0.0
      ? std::max(modelRadii[i] * frame.scale, std::numeric_limits<double>::min())
      : modelRadii[i];
  }
  core::SphereSet<double> set(centers, radii);
  core::GpuBVH bvh = core::buildGpuBVH(core::sphereBounds(set), options);
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh, frame);
  if (!adopted)
  {
    return g;
  }
  const Vec3<double> origin = *adopted;
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->SphereRecords.resize(n);
  g->SphereIds.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::uint32_t s = bvh.primIndex[k];
    const Vec3<double> c = centers[s] - origin;
    g->SphereRecords[k] = { { static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z) },
      static_cast<float>(radii[s]) };
    g->SphereIds[k] = ids[s];
    g->MaximumId = std::max(g->MaximumId, ids[s]);
  }
  return g;
}

std::unique_ptr<Geometry> BuildScreenSpheres(
  vtkPolyData* poly, bool everyCellPoint, const core::BuildOptions& options)
{
  core::NoFillArray<Vec3<double>> all;
  ReadPoints(poly->GetPoints(), all);
  // The last cell (VTK's numbering and drawing order: verts, lines,
  // polygons, strips) that holds each drawn point: raster draws the point
  // once for each, and its GL_LEQUAL depth test keeps the last, for
  // selection and for colors by cell.
  constexpr std::uint32_t kNoCell = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> drawnCell(all.size(), kNoCell);
  std::uint32_t cellId = 0;
  vtkIdType npts;
  const vtkIdType* pts;
  auto mark = [&](vtkCellArray* cells, bool drawn) {
    if (!drawn)
    {
      cellId += static_cast<std::uint32_t>(cells->GetNumberOfCells());
      return;
    }
    auto it = vtk::TakeSmartPointer(cells->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
    {
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 0; k < npts; ++k)
      {
        if (pts[k] >= 0 && static_cast<std::size_t>(pts[k]) < drawnCell.size())
        {
          drawnCell[static_cast<std::size_t>(pts[k])] = cellId;
        }
      }
    }
  };
  mark(poly->GetVerts(), true);
  mark(poly->GetLines(), everyCellPoint);
  mark(poly->GetPolys(), everyCellPoint);
  mark(poly->GetStrips(), everyCellPoint);
  std::vector<Vec3<double>> centers;
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    if (drawnCell[i] != kNoCell)
    {
      centers.push_back(all[i]);
      ids.push_back(static_cast<std::uint32_t>(i));
    }
  }
  // Bare centers: the smallest radius the builder accepts (boxes of
  // points); the shader adds each frame's radius.
  const std::vector<double> radii(centers.size(), std::numeric_limits<double>::min());
  std::unique_ptr<Geometry> g = BuildSpheres(centers, radii, ids, options);
  g->ScreenSized = true;
  for (core::gpu::Sphere& s : g->SphereRecords)
  {
    s.radius = 0.0f;
  }
  const bool cellsAreThePoints = std::all_of(
    g->SphereIds.begin(), g->SphereIds.end(), [&](std::uint32_t point) { return drawnCell[point] == point; });
  if (!cellsAreThePoints)
  {
    g->SphereCellIds.resize(g->SphereIds.size());
    std::transform(g->SphereIds.begin(), g->SphereIds.end(), g->SphereCellIds.begin(),
      [&](std::uint32_t point) { return drawnCell[point]; });
    // What selection reports: its high-24-bit pass runs only past 2^24.
    g->MaximumId = *std::max_element(g->SphereCellIds.begin(), g->SphereCellIds.end());
  }
  return g;
}

std::unique_ptr<Geometry> BuildEllipsoids(const std::vector<std::array<double, 12>>& modelMaps,
  const std::vector<core::AABB<double>>& modelBoxes, const std::vector<std::uint32_t>& ids,
  const core::BuildOptions& options)
{
  auto g = std::make_unique<Geometry>();
  g->Spheres = true;
  g->Ellipsoids = true;
  const core::ScaledFrame frame =
    buildFrame(modelBoxes.size(), [&](std::size_t i) { return modelBoxes[i]; });
  std::vector<core::AABB<double>> boxes(modelBoxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    const core::AABB<double>& b = modelBoxes[i];
    boxes[i] = b.isEmpty() ? b : core::AABB<double>(frame.toLocal(b.min), frame.toLocal(b.max));
  }
  // A p + b with p = p' / scale + origin: (A / scale) p' + (A origin + b).
  std::vector<std::array<double, 12>> maps(modelMaps);
  for (std::array<double, 12>& m : maps)
  {
    for (int r = 0; r < 3; ++r)
    {
      m[4 * r + 3] += m[4 * r] * frame.origin.x + m[4 * r + 1] * frame.origin.y +
        m[4 * r + 2] * frame.origin.z;
      for (int c = 0; c < 3; ++c)
      {
        m[4 * r + c] /= frame.scale;
      }
    }
  }
  core::GpuBVH bvh = core::buildGpuBVH(boxes, options);
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh, frame);
  if (!adopted)
  {
    return g;
  }
  const Vec3<double> origin = *adopted;
  // Leaves index texels of the sphere buffer: three per ellipsoid.
  for (core::gpu::Node& node : g->Nodes)
  {
    if (node.count > 0)
    {
      node.index *= core::gpu::kEllipsoidTexels;
    }
  }
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->EllipsoidRecords.resize(n);
  g->SphereIds.resize(core::gpu::kEllipsoidTexels * n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::array<double, 12>& m = maps[bvh.primIndex[k]];
    core::gpu::Ellipsoid& e = g->EllipsoidRecords[k];
    for (int r = 0; r < 3; ++r)
    {
      e.rows[r][0] = static_cast<float>(m[4 * r + 0]);
      e.rows[r][1] = static_cast<float>(m[4 * r + 1]);
      e.rows[r][2] = static_cast<float>(m[4 * r + 2]);
      e.rows[r][3] = static_cast<float>(m[4 * r + 3] + m[4 * r + 0] * origin.x +
        m[4 * r + 1] * origin.y + m[4 * r + 2] * origin.z);
      // The shader reads an ellipsoid's id at any of its texels.
      g->SphereIds[core::gpu::kEllipsoidTexels * k + r] = ids[bvh.primIndex[k]];
    }
    g->MaximumId = std::max(g->MaximumId, ids[bvh.primIndex[k]]);
  }
  return g;
}

} // namespace pass
} // namespace vtkrt
