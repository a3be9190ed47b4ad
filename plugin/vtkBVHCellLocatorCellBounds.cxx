// vtkBVHCellLocator's cells of several triangles (quads, polygons, strips)
// by their own bounds: VTK's locators answer FindCell, FindCellsWithinBounds
// and FindCellsAlongLine from cell bounds, which for such a cell can reach
// where none of its triangles' boxes does (a tilted quad, an L-shaped
// polygon), so those queries also walk a tree over these cells' bounds.
#include "vtkBVHCellLocatorInternals.h"

#include "vtkDataSet.h"
#include "vtkSMPTools.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/Ray.h"

#include <cstdint>
#include <vector>

namespace vtkrt
{
namespace locator
{
namespace
{

/// A binary tree's nodes as core's walks read them, each box grown by a
/// tolerance (the segment queries' "bounds grown by tol").
struct GrownNodes
{
  using Scalar = double;
  const core::BVHNode* nodes = nullptr;
  std::size_t size = 0;
  Vec3d grow = Vec3d(0.0);

  Vec3d lo(std::uint32_t i) const { return this->nodes[i].min - this->grow; }
  Vec3d hi(std::uint32_t i) const { return this->nodes[i].max + this->grow; }
  std::uint32_t index(std::uint32_t i) const { return this->nodes[i].index; }
  std::uint32_t count(std::uint32_t i) const { return this->nodes[i].count; }
};

} // namespace

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
  // The bounds as VTK computes them (every point of the cell), in the local
  // coordinates of the triangles' boxes: a cell's box holds each of its
  // triangles' boxes exactly.
  const vtkIdType n = static_cast<vtkIdType>(this->MultiTriangleCells.size());
  m.Boxes.resize(this->MultiTriangleCells.size());
  vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
    double cb[6];
    for (vtkIdType i = b; i < e; ++i)
    {
      ds->GetCellBounds(this->MultiTriangleCells[i], cb);
      const Box world(Vec3d(cb[0], cb[2], cb[4]), Vec3d(cb[1], cb[3], cb[5]));
      m.Boxes[i] = world.isFinite() && !world.isEmpty()
        ? Box(this->ToLocal(world.min), this->ToLocal(world.max))
        : Box();
    }
  });
  m.Tree = core::buildBVH(
    m.Boxes.size(), [&m](std::size_t i) { return m.Boxes[i]; }, this->TreeOptions);
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
  const GrownNodes nodes{ m.Tree.nodes.data(), m.Tree.nodes.size(), grow };
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
