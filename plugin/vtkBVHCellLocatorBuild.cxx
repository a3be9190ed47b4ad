// vtkBVHCellLocator's trees over its primitives: the fast build's picking
// tree made directly (core::LazyWideBVH, the binary tree left for the first
// query that needs it), or the core's binary tree, its primitives put in
// leaf order and its eight-wide view (core::collapseToWide).
#include "vtkBVHCellLocatorInternals.h"

#include "vtkSMPTools.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/WideCollapse.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

namespace vtkrt
{
namespace locator
{

//------------------------------------------------------------------------------
void BVHCellLocatorData::Build(int quality, int leafSize)
{
  const size_t nTri = this->TriCell.size();
  const size_t n = nTri + this->GenCell.size();
  core::BuildOptions options;
  options.quality = quality == 0 ? core::BuildQuality::Fast
                                 : (quality == 2 ? core::BuildQuality::High : core::BuildQuality::Medium);
  options.maxLeafSize = static_cast<std::uint32_t>(std::max(leafSize, 1));
  // The builder's parallel work goes to VTK's SMP pool: its own
  // std::threads would compete with the pool's workers, which keep
  // spinning after the parallel loops around this call.
  options.parallelFor = [](std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
    // Few large items (subtrees, chunks) one at a time; many by VTK's grain.
    const vtkIdType grain = n <= 256 ? 1 : 0;
    vtkSMPTools::For(0, static_cast<vtkIdType>(n), grain, [&body](vtkIdType b, vtkIdType e) {
      body(static_cast<std::size_t>(b), static_cast<std::size_t>(e));
    });
  };
  // Boxes straight into the builder's references: no intermediate array
  // of n boxes (fresh pages cost more than the arithmetic here).
  // The box callable only reads: the builder may call it from several threads.
  this->TreeOptions = options;
  if (options.quality == core::BuildQuality::Fast && this->GenCell.empty() && nTri > 0)
  {
    this->BuildPickingTree(nTri);
    return;
  }
  this->Tree = core::buildBVHConcurrentBounds(
    n,
    [this, nTri](size_t i) {
      if (i >= nTri)
      {
        return this->GenBox[i - nTri];
      }
      // Non-finite or empty: the builder skips it.
      return this->TriangleBox(this->SrcVerts + 3 * i);
    },
    options);
  this->Reorder(nTri);
  this->Wide = core::collapseToWide(this->Tree, this->TreeOptions);
  this->Extent = 0.0;
  if (!this->Tree.empty())
  {
    const Box root = this->Tree.nodes[0].bounds();
    for (int k = 0; k < 3; ++k)
    {
      this->Extent = std::max(this->Extent, std::max(std::abs(root.min[k]), std::abs(root.max[k])));
    }
  }
  this->SetTreeStats();
  this->SkippedCells =
    this->NonFiniteCells + static_cast<vtkIdType>(this->Tree.stats.skippedPrimitives);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::SetTreeStats() const
{
  this->Stats.Nodes = static_cast<vtkIdType>(this->Tree.stats.nodeCount);
  this->Stats.Leaves = static_cast<vtkIdType>(this->Tree.stats.leafCount);
  this->Stats.Depth = static_cast<int>(this->Tree.stats.maxDepth);
  this->Stats.SAHCost = this->Tree.stats.sahCost;
}

//------------------------------------------------------------------------------
/// EnsureTree's build: one thread builds, the others wait for it.
void BVHCellLocatorData::BuildDeferredTree() const
{
  std::lock_guard<std::mutex> lock(this->TreeBuilt.Mutex);
  if (this->TreeBuilt.Ready.load(std::memory_order_relaxed))
  {
    return;
  }
  // Every triangle in its slot first: the binary tree is over the
  // picking tree's slots (leaf order), prim = slot as there.
  if (this->Lazy)
  {
    this->Lazy->buildAll();
    const_cast<BVHCellLocatorData*>(this)->DropExtractionArrays(); // no bucket build reads them now
  }
  this->Tree = core::buildBVHConcurrentBounds(
    this->TriCell.size(), [this](size_t i) { return this->PrimitiveBox(static_cast<std::uint32_t>(i)); },
    this->TreeOptions);
  this->SetTreeStats();
  this->TreeBuilt.Ready.store(true, std::memory_order_release);
}

//------------------------------------------------------------------------------
/// The fast build (triangles only): the picking tree straight over the
/// triangles (core::LazyWideBVH): the levels above its buckets now, each
/// bucket's subtree when a query first reaches it (which puts its
/// triangles in their leaf slots: point ids, cell id). No
/// binary tree, no re-layout: a first pick waits for little more than the
/// extraction.
void BVHCellLocatorData::BuildPickingTree(size_t nTri)
{
  this->MakeLeafOrderArrays(nTri);
  this->Lazy.reset(new LazyPickingTree(PickingTriangles{ this }, this->TreeOptions));
  this->Lazy->build(nTri, this->PointBounds);
  this->Tree = core::BVH();
  this->Stats = TreeStats();
  this->TreeBuilt.Ready.store(false);
  this->Extent = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    this->Extent = std::max(this->Extent, std::max(std::abs(this->PointBounds.min[k]), std::abs(this->PointBounds.max[k])));
  }
  this->SkippedCells = this->NonFiniteCells;
}

//------------------------------------------------------------------------------
/// The per-triangle arrays in leaf order, sized for nTri slots, and the
/// extraction-order ones they are filled from (Src*, SrcVerts), kept
/// until every triangle is placed.
void BVHCellLocatorData::MakeLeafOrderArrays(size_t nTri)
{
  this->SrcCell.swap(this->TriCell);
  this->SrcSub.swap(this->TriSub);
  this->SrcFlags.swap(this->TriFlags);
  this->TriIds.resize(3 * nTri);
  this->TrianglesF.resize(9 * nTri + 1);
  this->TrianglesF[9 * nTri] = 0.0f;
  this->TriCell.resize(nTri);
  if (this->UniformCellBase < 0) // else TriangleSubId / TriangleFlags need no array
  {
    this->TriSub.resize(nTri);
    this->TriFlags.resize(nTri);
  }
}

//------------------------------------------------------------------------------
/// Every triangle placed: the extraction-order arrays can go.
void BVHCellLocatorData::DropExtractionArrays()
{
  ExtractionArray<std::uint32_t>().swap(this->TriVerts);
  this->SrcVerts = nullptr;
  this->SharedTriangulation = nullptr; // the polydata keeps it for others
  TriangleArray<vtkIdType>().swap(this->SrcCell);
  TriangleArray<std::int32_t>().swap(this->SrcSub);
  TriangleArray<std::uint8_t>().swap(this->SrcFlags);
  // Points stay: the exact tests read the double vertices through TriIds.
}

//------------------------------------------------------------------------------
/// Renumbers the primitives in leaf order (triangles first, then general
/// cells) and stores each triangle's vertices inline, so that a leaf's
/// primitives are adjacent in memory and a triangle test reads one cache
/// line run instead of chasing point ids. Skipped primitives are dropped.
void BVHCellLocatorData::Reorder(size_t nTri)
{
  std::vector<std::uint32_t>& order = this->Tree.primIndex;
  size_t builtTri = 0;
  for (const std::uint32_t p : order)
  {
    builtTri += p < nTri ? 1 : 0;
  }
  this->MakeLeafOrderArrays(builtTri);
  std::vector<vtkIdType> genCell(order.size() - builtTri);
  std::vector<Box> genBox(order.size() - builtTri);
  std::uint32_t t = 0, g = 0;
  if (builtTri == order.size())
  {
    // Triangles only (the common case): slot j is triangle j, so the
    // gather runs in parallel.
    // The gather reads the triangles in leaf order, at random: fetch the
    // point ids 16 slots ahead and, 8 slots ahead, the points they name
    // (millions of triangles are a cache miss per read otherwise). Only
    // within this chunk: other chunks rewrite their slots of `order`.
    vtkSMPTools::For(0, static_cast<vtkIdType>(order.size()), [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType j = b; j < e; ++j)
      {
        if (j + 16 < e)
        {
          this->PrefetchTriangle(order[j + 16], 0);
        }
        if (j + 8 < e)
        {
          this->PrefetchTriangle(order[j + 8], 1);
        }
        this->PlaceTriangle(order[j], static_cast<std::uint32_t>(j));
        order[j] = static_cast<std::uint32_t>(j);
      }
    });
  }
  else
  {
    for (std::uint32_t& p : order)
    {
      if (p < nTri)
      {
        this->PlaceTriangle(p, t);
        p = t++;
      }
      else
      {
        genCell[g] = this->GenCell[p - nTri];
        genBox[g] = this->GenBox[p - nTri];
        p = static_cast<std::uint32_t>(builtTri) + g++;
      }
    }
  }
  this->DropExtractionArrays();
  this->GenCell.swap(genCell);
  this->GenBox.swap(genBox);
}

//------------------------------------------------------------------------------
size_t BVHCellLocatorData::MemorySize() const
{
  return this->PointsCopy.capacity() * sizeof(Vec3d) + this->TrianglesF.capacity() * sizeof(float) +
    this->TriVerts.capacity() * sizeof(std::uint32_t) + this->SrcCell.capacity() * sizeof(vtkIdType) +
    this->SrcSub.capacity() * sizeof(std::int32_t) + this->SrcFlags.capacity() +
    (this->Lazy ? this->Lazy->memoryBytes() : 0) +
    this->TriIds.capacity() * sizeof(std::uint32_t) +
    this->TriCell.capacity() * sizeof(vtkIdType) +
    this->TriSub.capacity() * sizeof(std::int32_t) + this->TriFlags.capacity() +
    this->GenCell.capacity() * sizeof(vtkIdType) + this->GenBox.capacity() * sizeof(Box) +
    this->Tree.memoryBytes() +
    this->Wide.capacity() * sizeof(WideNode) +
    this->MultiTriangleCells.capacity() * sizeof(vtkIdType) + this->MultiCellBytes();
}

//------------------------------------------------------------------------------
/// Boxes (local coordinates) of the nodes at depth `level` and of the
/// leaves above it; all leaves for a negative level.
void BVHCellLocatorData::BoxesAtLevel(int level, std::vector<Box>& boxes) const
{
  boxes.clear();
  this->EnsureTree();
  if (this->Tree.empty())
  {
    return;
  }
  struct Entry
  {
    std::uint32_t Node;
    int Depth;
  };
  std::vector<Entry> stack{ { 0, 0 } };
  while (!stack.empty())
  {
    const Entry e = stack.back();
    stack.pop_back();
    const core::BVHNode& node = this->Tree.nodes[e.Node];
    if (node.isLeaf() || (level >= 0 && e.Depth >= level))
    {
      boxes.push_back(node.bounds());
      continue;
    }
    stack.push_back({ node.index + 1, e.Depth + 1 });
    stack.push_back({ node.index, e.Depth + 1 });
  }
}

} // namespace locator
} // namespace vtkrt
