// vtkBVHCellLocator's queries by cell bounds (FindCellsWithinBounds,
// FindCellsAlongLine, and FindCell's candidates): VTK's locators answer them
// from cell bounds, which for a cell of several triangles (a quad, polygon
// or strip) can reach where none of its triangles' boxes does (a tilted
// quad's corner, a star's notch). Such cells are looked for in a tree over
// their own bounds, built by the first query that needs it.
#include "vtkBVHCellLocatorInternals.h"
#include "vtkBVHCellLocatorPickingScene.h"

#include "vtkDataSet.h"
#include "vtkIdList.h"
#include "vtkNew.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/SegmentQueries.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace vtkrt
{
namespace locator
{
namespace
{
/// Cell ids in order, each once (a cell is met through each of its triangles).
void SortUnique(std::vector<vtkIdType>& cells)
{
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
}
} // namespace

//------------------------------------------------------------------------------
Box BVHCellLocatorData::CellBox(vtkDataSet* ds, vtkIdType cellId, vtkIdList* points) const
{
  // The cell's finite points in the local coordinates of its triangles'
  // boxes (the same points, rounded alike): its box holds each of theirs.
  ds->GetCellPoints(cellId, points);
  Box box;
  for (vtkIdType k = 0; k < points->GetNumberOfIds(); ++k)
  {
    const vtkIdType id = points->GetId(k);
    const Vec3d p = id >= 0 && id < this->NumberOfPoints ? this->LocalPoint(id) : Vec3d(NAN);
    if (core::isFinite(p))
    {
      box.extend(p);
    }
  }
  return box;
}

//------------------------------------------------------------------------------
bool BVHCellLocatorData::InMultiTriangleCell(std::uint32_t prim) const
{
  // A one-triangle polygon is not: its box is its cell's bounds.
  return static_cast<vtkIdType>(prim) < this->NumberOfTriangles() &&
    !(this->TriangleFlags(prim) & WholeTriangle) &&
    std::binary_search(this->MultiTriangleCells.begin(), this->MultiTriangleCells.end(), this->PrimitiveCell(prim));
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::CellsInLocalBox(const Box& q, std::vector<vtkIdType>& cells) const
{
  cells.clear();
  auto overlap = [&](std::uint32_t prim) {
    if (this->PrimitiveBox(prim).overlaps(q))
    {
      cells.push_back(this->PrimitiveCell(prim));
    }
  };
  PickingScene{ this }.forPrimitivesInBox(q, overlap);
  SortUnique(cells);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::CellsInBox(
  const double bbox[6], vtkDataSet* ds, std::vector<vtkIdType>& cells) const
{
  const Box q(this->ToLocal(Vec3d(bbox[0], bbox[2], bbox[4])),
    this->ToLocal(Vec3d(bbox[1], bbox[3], bbox[5])));
  if (!this->OnlyMultiTriangleCells || !ds)
  {
    this->CellsInLocalBox(q, cells);
  }
  else
  {
    cells.clear();
  }
  if (!this->MultiTriangleCells.empty() && ds)
  {
    this->MultiCellsInLocalBox(ds, q, cells);
    SortUnique(cells);
  }
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::CellsAlongLine(const double p1[3], const double p2[3], double tol,
  vtkDataSet* ds, std::vector<vtkIdType>& cells) const
{
  cells.clear();
  core::Ray<double> ray;
  if (!this->MakeSegment(p1, p2, ray))
  {
    if (IsFinitePoint(p1, p2))
    {
      // A point: the cells whose bounds, grown by tol, hold it.
      const double box[6] = { p1[0] - tol, p1[0] + tol, p1[1] - tol, p1[1] + tol, p1[2] - tol,
        p1[2] + tol };
      this->CellsInBox(box, ds, cells);
    }
    return;
  }
  const core::RayBoxPrecomputed<double> boxPre(ray);
  const core::RayTrianglePrecomputed<double> triPre(ray);
  // The segment's end in local coordinates, and the slab test's t there,
  // round by a few ulps: boxes grow by that much, so that a cell whose
  // bounds hold p2 exactly (a mesh vertex) is not lost, as it would be
  // from p1 alone.
  double magnitude = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    magnitude = std::max({ magnitude, std::abs(ray.org[k]), std::abs(ray.org[k] + ray.dir[k]) });
    magnitude += std::abs(ray.dir[k]);
  }
  const double localTol = this->ToLocalLength(tol) + 16.0 * std::numeric_limits<double>::epsilon() * magnitude;
  auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>&) {
    const Box b = this->PrimitiveBox(prim);
    double tnear;
    if (core::intersectRayAABB(boxPre, b.min - Vec3d(localTol), b.max + Vec3d(localTol), r.tmin, r.tmax, tnear))
    {
      cells.push_back(this->PrimitiveCell(prim));
    }
    return false;
  };
  // Cells by their bounds: every triangle of a leaf the segment reaches,
  // and the cells of several triangles by their own bounds.
  if (!this->OnlyMultiTriangleCells || !ds)
  {
    core::allHitsSegment(PickingScene{ this }, ray, triPre, localTol, false, isect);
  }
  if (ds)
  {
    this->MultiCellsAlongSegment(ds, ray, localTol, cells);
  }
  SortUnique(cells);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::EnsureMultiCells(vtkDataSet* ds) const
{
  MultiCellTree& m = this->MultiCells;
  if (this->MultiTriangleCells.empty() || !ds || m.Ready.load(std::memory_order_acquire))
  {
    return;
  }
  std::lock_guard<std::mutex> lock(m.Mutex);
  if (m.Ready.load(std::memory_order_relaxed))
  {
    return;
  }
  const vtkIdType n = static_cast<vtkIdType>(this->MultiTriangleCells.size());
  m.Boxes.resize(this->MultiTriangleCells.size());
  // On this thread alone: under the lock, a pool's waiting thread could
  // take another task of the caller's that asks for this tree again.
  vtkNew<vtkIdList> points;
  for (vtkIdType i = 0; i < n; ++i)
  {
    m.Boxes[i] = this->CellBox(ds, this->MultiTriangleCells[i], points);
  }
  core::BuildOptions options = this->TreeOptions;
  options.parallelFor = nullptr;
  options.numThreads = 1;
  options.maxLeafSize = 8; // a leaf's boxes lie side by side (below): larger leaves, a shallower walk
  m.Tree = core::buildBVH(m.Boxes.size(), [&m](std::size_t i) { return m.Boxes[i]; }, options);
  std::vector<Box> leafBoxes(m.Boxes.size());
  m.Cells.resize(m.Boxes.size());
  for (std::size_t j = 0; j < m.Tree.primIndex.size(); ++j)
  {
    const std::uint32_t i = m.Tree.primIndex[j];
    leafBoxes[j] = m.Boxes[i];
    m.Cells[j] = this->MultiTriangleCells[i];
    m.Tree.primIndex[j] = static_cast<std::uint32_t>(j);
  }
  m.Boxes.swap(leafBoxes);
  m.Nodes = core::packGpuNodes(m.Tree.nodes);
  m.Ready.store(true, std::memory_order_release);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::MultiCellsInLocalBox(
  vtkDataSet* ds, const Box& q, std::vector<vtkIdType>& cells) const
{
  this->EnsureMultiCells(ds);
  const MultiCellTree& m = this->MultiCells;
  if (!m.Ready.load(std::memory_order_acquire))
  {
    return;
  }
  core::queryBoxSlots(m.Nodes, q, [&](std::uint32_t i) { // leaf order: a slot is its box's index
    if (m.Boxes[i].overlaps(q))
    {
      cells.push_back(m.Cells[i]);
    }
  });
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::MultiCellsAlongSegment(vtkDataSet* ds, const core::Ray<double>& ray,
  double localTol, std::vector<vtkIdType>& cells) const
{
  this->EnsureMultiCells(ds);
  const MultiCellTree& m = this->MultiCells;
  if (!m.Ready.load(std::memory_order_acquire) || m.Tree.empty())
  {
    return;
  }
  const Vec3d grow(localTol);
  const core::GrownNodeSource nodes{ m.Tree.nodes.data(), m.Tree.nodes.size(), localTol };
  const core::RayBoxPrecomputed<double> pre(ray);
  auto meets = [&](std::uint32_t i, const core::Ray<double>& r, core::Hit<double>&) {
    double tnear;
    if (core::intersectRayAABB(pre, m.Boxes[i].min - grow, m.Boxes[i].max + grow, r.tmin, r.tmax, tnear))
    {
      cells.push_back(m.Cells[i]);
    }
    return false; // listed here; the walk goes on over the whole segment
  };
  core::allHits(nodes, m.Tree.primIndex.data(), ray, meets);
}

} // namespace locator
} // namespace vtkrt
