#include "vtkRayTraceTubes.h"

#include "vtkRayTraceGeometry.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"

#include "vtkrt/core/BVHBuild.h"

#include <algorithm>

namespace vtkrt
{
namespace pass
{

using core::Vec3;

bool DrawsLinesAsTubes(vtkProperty* property)
{
  return property->GetRenderLinesAsTubes() && property->GetLineWidth() > 1.0f &&
    property->GetRepresentation() == VTK_SURFACE;
}

namespace
{
/// A segment to trace: its point ids and its line's VTK cell id.
struct SegmentIds
{
  std::uint32_t Point0;
  std::uint32_t Point1;
  std::uint32_t Cell;
};

/// The traceable segments of the lines, and how many were not.
std::vector<SegmentIds> CollectSegments(
  vtkPolyData* poly, const core::NoFillArray<Vec3<double>>& points, std::size_t& skipped)
{
  std::vector<SegmentIds> out;
  skipped = 0;
  const auto valid = [&](vtkIdType id) {
    return id >= 0 && static_cast<std::size_t>(id) < points.size() &&
      core::isFinite(points[static_cast<std::size_t>(id)]);
  };
  auto cellId = static_cast<std::uint32_t>(poly->GetNumberOfVerts());
  vtkIdType npts;
  const vtkIdType* pts;
  auto it = vtk::TakeSmartPointer(poly->GetLines()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
  {
    it->GetCurrentCell(npts, pts);
    if (npts < 2)
    {
      ++skipped;
      continue;
    }
    for (vtkIdType k = 0; k + 1 < npts; ++k)
    {
      if (!valid(pts[k]) || !valid(pts[k + 1]) ||
        points[static_cast<std::size_t>(pts[k])] == points[static_cast<std::size_t>(pts[k + 1])])
      {
        ++skipped;
        continue;
      }
      out.push_back({ static_cast<std::uint32_t>(pts[k]), static_cast<std::uint32_t>(pts[k + 1]), cellId });
    }
  }
  return out;
}
} // namespace

std::unique_ptr<Geometry> BuildTubes(vtkPolyData* poly, const core::BuildOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  auto g = std::make_unique<Geometry>();
  g->Spheres = true;
  g->ScreenSized = true;
  g->Tubes = true;
  core::NoFillArray<Vec3<double>> points;
  ReadPoints(poly->GetPoints(), points);
  std::size_t skipped = 0;
  const std::vector<SegmentIds> segments = CollectSegments(poly, points, skipped);
  const auto modelBox = [&](std::size_t i) {
    core::AABB<double> box;
    box.extend(points[segments[i].Point0]);
    box.extend(points[segments[i].Point1]);
    return box;
  };
  const core::ScaledFrame frame = buildFrame(segments.size(), modelBox);
  std::vector<core::AABB<double>> boxes(segments.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    const core::AABB<double> b = modelBox(i);
    boxes[i] = core::AABB<double>(frame.toLocal(b.min), frame.toLocal(b.max));
  }
  g->TriangulationSeconds = SecondsSince(start);
  // Bare segments: each frame's radii grow the boxes in the shader.
  core::GpuBVH bvh = core::buildGpuBVH(boxes, options);
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh, frame);
  g->SkippedPrimitives += skipped;
  g->VertexCount = points.size();
  if (!adopted)
  {
    return g;
  }
  // Leaves index texels of the sphere buffer: two per segment.
  for (core::gpu::Node& node : g->Nodes)
  {
    if (node.count > 0)
    {
      node.index *= core::gpu::kSegmentTexels;
    }
  }
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->SegmentRecords.resize(n);
  g->SphereIds.resize(core::gpu::kSegmentTexels * n);
  const auto local = [&](std::uint32_t id) {
    return core::gpu::vec3(frame.toLocal(points[id]) - *adopted);
  };
  for (std::size_t k = 0; k < n; ++k)
  {
    const SegmentIds& s = segments[bvh.primIndex[k]];
    g->SegmentRecords[k] = { local(s.Point0), s.Point0, local(s.Point1), s.Point1 };
    // The shader reads a segment's cell id at either of its texels.
    std::fill_n(&g->SphereIds[core::gpu::kSegmentTexels * k], core::gpu::kSegmentTexels, s.Cell);
    g->MaximumId = std::max(g->MaximumId, s.Cell);
  }
  return g;
}

} // namespace pass
} // namespace vtkrt
