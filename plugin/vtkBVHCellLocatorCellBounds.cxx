// vtkBVHCellLocator's queries by cell bounds (FindCellsWithinBounds,
// FindCellsAlongLine, and FindCell's candidates): VTK's locators answer them
// from cell bounds, which for a cell of several triangles (a quad, polygon
// or strip) can reach where none of its triangles' boxes does (a tilted
// quad's corner, a star's notch). Such cells are looked for as far around
// as they reach, or, where a few reach much farther than the mesh's
// triangles, in a tree over their own bounds.
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
#include <functional>
#include <vector>

namespace vtkrt
{
namespace locator
{

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
bool BVHCellLocatorData::IsMultiTrianglePrimitive(std::uint32_t prim) const
{
  // A one-triangle polygon counts too: its box is its cell's bounds.
  return static_cast<vtkIdType>(prim) < this->NumberOfTriangles() &&
    !(this->TriangleFlags(prim) & WholeTriangle);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::AddCellsMeeting(std::vector<std::pair<vtkIdType, Box>>& nearby,
  const std::function<bool(const Box&)>& meets, std::vector<vtkIdType>& cells)
{
  // A cell that meets the query lies within reach of it, so the walk met
  // all its triangles: the union of their boxes is its bounds. A cell whose
  // union does not meet the query does not meet it either.
  std::sort(nearby.begin(), nearby.end(),
    [](const std::pair<vtkIdType, Box>& x, const std::pair<vtkIdType, Box>& y) { return x.first < y.first; });
  std::sort(cells.begin(), cells.end());
  const std::size_t listed = cells.size();
  for (std::size_t i = 0; i < nearby.size();)
  {
    const vtkIdType cellId = nearby[i].first;
    Box bounds;
    for (; i < nearby.size() && nearby[i].first == cellId; ++i)
    {
      bounds.extend(nearby[i].second);
    }
    if (!std::binary_search(cells.begin(), cells.begin() + listed, cellId) && meets(bounds))
    {
      cells.push_back(cellId);
    }
  }
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
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::CellsInBox(
  const double bbox[6], vtkDataSet* ds, std::vector<vtkIdType>& cells) const
{
  const Box q(this->ToLocal(Vec3d(bbox[0], bbox[2], bbox[4])),
    this->ToLocal(Vec3d(bbox[1], bbox[3], bbox[5])));
  if (this->MultiTriangleCells.empty() || !ds)
  {
    this->CellsInLocalBox(q, cells);
    return;
  }
  if (!this->QueriesLookByReach)
  {
    this->CellsInLocalBox(q, cells);
    this->MultiCellsInLocalBox(ds, q, cells);
  }
  else
  {
    // Triangles within reach of the box: their cells' own bounds decide.
    const Vec3d reach(this->MultiTriangleCellReach);
    const Box grown(q.min - reach, q.max + reach);
    std::vector<std::pair<vtkIdType, Box>> nearby;
    cells.clear();
    auto overlap = [&](std::uint32_t prim) {
      const Box b = this->PrimitiveBox(prim);
      if (b.overlaps(q))
      {
        cells.push_back(this->PrimitiveCell(prim));
      }
      else if (b.overlaps(grown) && this->IsMultiTrianglePrimitive(prim))
      {
        nearby.emplace_back(this->PrimitiveCell(prim), b);
      }
    };
    PickingScene{ this }.forPrimitivesInBox(grown, overlap);
    AddCellsMeeting(nearby, [&q](const Box& b) { return b.overlaps(q); }, cells);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
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
  const double localTol = this->ToLocalLength(tol);
  // Cells of several triangles within reach of the segment: their own
  // bounds decide (or MultiCells, where a few reach far).
  const bool reaching = !this->MultiTriangleCells.empty() && ds && this->QueriesLookByReach;
  const double walkTol = localTol + (reaching ? this->MultiTriangleCellReach : 0.0);
  std::vector<std::pair<vtkIdType, Box>> nearby;
  auto meets = [&](const Box& b, double grow, const core::Ray<double>& r) {
    double tnear;
    return core::intersectRayAABB(boxPre, b.min - Vec3d(grow), b.max + Vec3d(grow), r.tmin, r.tmax, tnear);
  };
  auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>&) {
    const Box b = this->PrimitiveBox(prim);
    if (meets(b, localTol, r))
    {
      cells.push_back(this->PrimitiveCell(prim));
    }
    else if (reaching && meets(b, walkTol, r) && this->IsMultiTrianglePrimitive(prim))
    {
      nearby.emplace_back(this->PrimitiveCell(prim), b);
    }
    return false;
  };
  // Cells by their bounds: every triangle of a leaf the segment reaches.
  core::allHitsSegment(PickingScene{ this }, ray, triPre, walkTol, false, isect);
  if (reaching)
  {
    AddCellsMeeting(nearby, [&](const Box& b) { return meets(b, localTol, ray); }, cells);
  }
  else if (ds)
  {
    this->MultiCellsAlongSegment(ds, ray, localTol, cells);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
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
  m.Tree = core::buildBVH(m.Boxes.size(), [&m](std::size_t i) { return m.Boxes[i]; }, options);
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
  core::queryBox(m.Tree, q, [&](std::uint32_t i) {
    if (m.Boxes[i].overlaps(q))
    {
      cells.push_back(this->MultiTriangleCells[i]);
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
      cells.push_back(this->MultiTriangleCells[i]);
    }
    return false; // listed here; the walk goes on over the whole segment
  };
  core::allHits(nodes, m.Tree.primIndex.data(), ray, meets);
}

} // namespace locator
} // namespace vtkrt
