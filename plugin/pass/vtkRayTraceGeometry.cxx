#include "vtkRayTraceGeometry.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/LocalFrame.h"
#include "vtkrt/core/Mesh.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>

namespace vtkrt
{
namespace pass
{

using core::Vec3;

namespace
{
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

/// Takes a BVH built in `frame`'s coordinates into `g`: its skipped-primitive
/// count and, when it is not empty, the local origin (the center of what is
/// traced: NaN primitives are not in the tree; in model coordinates with
/// the frame's scale), the bounds relative to it and the GPU nodes. Returns
/// the origin in the frame's coordinates, or nothing for an empty tree.
std::optional<Vec3<double>> adoptBVH(Geometry& g, const core::BVH& bvh, const core::ScaledFrame& frame)
{
  g.SkippedPrimitives = bvh.stats.skippedPrimitives;
  // A tree of more than a root whose depth says 0 did not count it: the
  // deepest any may be.
  g.MaxDepth = bvh.nodes.size() > 1 && bvh.stats.maxDepth == 0 ? core::kMaxDepth : bvh.stats.maxDepth;
  if (bvh.empty())
  {
    return std::nullopt;
  }
  const core::AABB<double> b = bvh.bounds();
  const Vec3<double> origin = b.center();
  const Vec3<double> modelOrigin = frame.toModel(origin);
  g.Origin = { { modelOrigin.x, modelOrigin.y, modelOrigin.z } };
  g.Scale = frame.scale;
  for (int k = 0; k < 3; ++k)
  {
    g.LocalBounds[2 * k] = b.min[k] - origin[k];
    g.LocalBounds[2 * k + 1] = b.max[k] - origin[k];
  }
  g.Nodes = core::packGpuNodes(bvh.nodes, origin);
  return origin;
}

/// The fan triangulation of polys and the triangles of strips, as point id
/// triples with their VTK cell ids.
void triangulate(vtkPolyData* poly, std::vector<std::uint32_t>& indices, std::vector<std::uint32_t>& cellIds)
{
  vtkIdType cellId = poly->GetNumberOfVerts() + poly->GetNumberOfLines();
  vtkIdType npts;
  const vtkIdType* pts;
  auto polys = vtk::TakeSmartPointer(poly->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell(), ++cellId)
  {
    polys->GetCurrentCell(npts, pts);
    for (vtkIdType k = 1; k + 1 < npts; ++k)
    {
      indices.insert(indices.end(), { std::uint32_t(pts[0]), std::uint32_t(pts[k]), std::uint32_t(pts[k + 1]) });
      cellIds.push_back(std::uint32_t(cellId));
    }
  }
  auto strips = vtk::TakeSmartPointer(poly->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell(), ++cellId)
  {
    strips->GetCurrentCell(npts, pts);
    for (vtkIdType i = 0; i + 2 < npts; ++i)
    {
      indices.insert(indices.end(),
        { std::uint32_t(pts[i]), std::uint32_t(pts[i + 1 + i % 2]), std::uint32_t(pts[i + 1 + (i + 1) % 2]) });
      cellIds.push_back(std::uint32_t(cellId));
    }
  }
}

/// `normals` as GPU records when it holds `count` vectors (one per point, or
/// per cell); else nothing.
void readNormals(vtkDataArray* normals, std::size_t count, std::vector<core::gpu::Normal>& out)
{
  if (!normals || normals->GetNumberOfComponents() != 3 ||
    normals->GetNumberOfTuples() != static_cast<vtkIdType>(count))
  {
    return;
  }
  out.resize(count);
  double nv[3];
  for (std::size_t i = 0; i < count; ++i)
  {
    normals->GetTuple(static_cast<vtkIdType>(i), nv);
    out[i] = { { static_cast<float>(nv[0]), static_cast<float>(nv[1]), static_cast<float>(nv[2]) }, 0.0f };
  }
}
} // namespace

void ReadPoints(vtkPoints* pts, std::vector<Vec3<double>>& out)
{
  const vtkIdType n = pts ? pts->GetNumberOfPoints() : 0;
  out.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    pts->GetPoint(i, &out[static_cast<std::size_t>(i)].x);
  }
}

std::unique_ptr<Geometry> BuildTriangles(vtkPolyData* poly, const core::BuildOptions& options)
{
  auto g = std::make_unique<Geometry>();
  const auto start = std::chrono::steady_clock::now();
  std::vector<Vec3<double>> points;
  ReadPoints(poly->GetPoints(), points);
  const core::ScaledFrame frame = buildFrame(
    points.size(), [&](std::size_t i) { return core::AABB<double>(points[i], points[i]); });
  for (Vec3<double>& p : points)
  {
    p = frame.toLocal(p);
  }
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> cellIds;
  triangulate(poly, indices, cellIds);
  g->TriangulationSeconds = SecondsSince(start);

  core::TriangleMesh<double> mesh(points, indices);
  core::BVH bvh = core::buildTriangleBVH(mesh, options);
  g->Spheres = false;
  g->VertexCount = points.size();
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh, frame);
  if (!adopted)
  {
    return g;
  }
  const std::vector<Vec3<float>> rel = core::relativeFloatPoints(points.data(), points.size(), *adopted);
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->Triangles.resize(n);
  g->TriangleVertices.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::uint32_t tri = bvh.primIndex[k];
    core::gpu::Triangle& t = g->Triangles[k];
    core::gpu::vec3* corners[3] = { &t.v0, &t.v1, &t.v2 };
    for (int v = 0; v < 3; ++v)
    {
      const std::uint32_t vi = indices[3 * tri + v];
      *corners[v] = rel[vi];
      g->TriangleVertices[k].ids[v] = vi;
    }
    t.cellId = cellIds[tri];
    g->MaximumId = std::max(g->MaximumId, t.cellId);
    t.unused1 = t.unused2 = 0.0f;
    g->TriangleVertices[k].unused = 0;
  }
  readNormals(poly->GetPointData()->GetNormals(), points.size(), g->Normals);
  readNormals(poly->GetCellData()->GetNormals(), static_cast<std::size_t>(poly->GetNumberOfCells()),
    g->CellNormals);
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
    const Vec3<double> r(modelRadii[i]);
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
  core::BVH bvh = core::buildSphereBVH(set, options);
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
  std::vector<Vec3<double>> all;
  ReadPoints(poly->GetPoints(), all);
  std::vector<char> used(all.size(), 0);
  vtkIdType npts;
  const vtkIdType* pts;
  auto mark = [&](vtkCellArray* cells) {
    auto it = vtk::TakeSmartPointer(cells->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 0; k < npts; ++k)
      {
        if (pts[k] >= 0 && static_cast<std::size_t>(pts[k]) < used.size())
        {
          used[static_cast<std::size_t>(pts[k])] = 1;
        }
      }
    }
  };
  mark(poly->GetVerts());
  if (everyCellPoint)
  {
    mark(poly->GetPolys());
    mark(poly->GetStrips());
    mark(poly->GetLines());
  }
  std::vector<Vec3<double>> centers;
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    if (used[i])
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
  core::BVH bvh = core::buildBVH(boxes, options);
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
