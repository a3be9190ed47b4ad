// Private to vtkBVHCellLocator: the dataset -> primitive extraction and the
// queries over the core's BVH (plugin/core/vtkrt/core). Not installed.
//
// Primitives are of two kinds sharing one tree:
// - triangles (fast path): polydata / unstructured-grid triangles, quads,
//   polygons (ear-cut) and triangle strips, stored as point-index triples
//   into a local-origin copy of the points and tested without any vtkCell;
// - general cells: every other cell, tested by its own vtkCell methods.
#ifndef vtkBVHCellLocatorInternals_h
#define vtkBVHCellLocatorInternals_h

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkDataSet.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/ConservativeFloat.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/WideBVH.h"

#if VTKRT_CORE_SSE
#include <xmmintrin.h> // _mm_prefetch
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h> // madvise
#endif

#if defined(__GNUC__) || defined(__clang__)
#define VTKRT_ALWAYS_INLINE __attribute__((always_inline))
#else
#define VTKRT_ALWAYS_INLINE
#endif

namespace vtkrt
{
namespace locator
{
using Vec3d = core::Vec3<double>;
using Box = core::AABB<double>;

/// std::allocator whose resize() leaves new elements default-initialized
/// (no zero fill): the per-triangle arrays are written element by element
/// right after, and a first pick should not wait for a memset of them
/// (60 MB at 1M triangles). Large arrays get a huge page hint (allocate()).
template <class T, bool HugePageHint = true>
struct NoFillAllocator : std::allocator<T>
{
  template <class U>
  struct rebind
  {
    using other = NoFillAllocator<U, HugePageHint>;
  };
  NoFillAllocator() = default;
  template <class U>
  NoFillAllocator(const NoFillAllocator<U, HugePageHint>&) noexcept
  {
  }
  template <class U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  /// Arrays of several MiB go on 2 MiB boundaries with a transparent huge
  /// page hint (Linux; as Embree does for its BVH): a pick reads them at
  /// random, and with 4 KiB pages nearly every such read also missed the
  /// TLB (1M triangles: picks 3-5% quicker with the hint, same locator and
  /// rays in one process, rounds alternating). Only a hint: memory is the
  /// same, and elsewhere or with THP off this is plain malloc.
  T* allocate(std::size_t n)
  {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T))
    {
      throw std::bad_alloc();
    }
    const std::size_t bytes = n * sizeof(T);
    void* p = nullptr;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::size_t kHugePage = std::size_t(2) << 20;
    if (HugePageHint && bytes >= 2 * kHugePage)
    {
      if (posix_memalign(&p, kHugePage, bytes) != 0)
      {
        throw std::bad_alloc();
      }
      madvise(p, bytes, MADV_HUGEPAGE);
      return static_cast<T*>(p);
    }
#endif
    p = std::malloc(bytes ? bytes : 1);
    if (!p)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) noexcept { std::free(p); }
};
/// A per-triangle array that picks read at random (see NoFillAllocator).
template <class T>
using TriangleArray = std::vector<T, NoFillAllocator<T>>;
/// A per-triangle array of the build, written and read in order: no huge
/// page hint (faulting huge pages in costs a first pick time for nothing).
template <class T>
using ExtractionArray = std::vector<T, NoFillAllocator<T, false>>;

/// One segment/cell intersection, in world coordinates.
struct LineHit
{
  double T = 0.0;
  double X[3] = { 0.0, 0.0, 0.0 };
  double PCoords[3] = { 0.0, 0.0, 0.0 };
  int SubId = 0;
  vtkIdType CellId = -1;
  bool NeedsEvaluate = false; ///< pcoords/subId must come from the cell's EvaluatePosition
  bool Leaving = false;       ///< the segment leaves through an outward-facing triangle
  const std::uint32_t* TrianglePointIds = nullptr; ///< set when the cell is that VTK_TRIANGLE
};

/// One closest-point result, in world coordinates.
struct PointHit
{
  double X[3] = { 0.0, 0.0, 0.0 };
  double Dist2 = 0.0;
  vtkIdType CellId = -1;
  int SubId = 0;
  int Inside = 0;
  bool NeedsEvaluate = false;
};

struct TreeStats
{
  vtkIdType Nodes = 0;
  vtkIdType Leaves = 0;
  int Depth = 0;
  double SAHCost = 0.0;
};

enum TriangleFlags : std::uint8_t
{
  FlipOrientation = 1, ///< odd triangle of a strip: its cell's winding is reversed
  EvaluateInCell = 2,  ///< part of a quad or polygon: pcoords come from the cell
  WholeTriangle = 4,   ///< a VTK_TRIANGLE cell, vertices in the cell's order
};

class BVHCellLocatorData
{
public:
  Vec3d Origin = Vec3d(0.0);
  Box PointBounds; ///< the finite points' bounds, local (fast path only)
  /// World coordinates of the points when the dataset's are not double
  /// (double ones are read in place, DataSetCoords): fast path only.
  std::vector<Vec3d> PointsCopy;
  vtkIdType NumberOfPoints = 0;
  ExtractionArray<std::uint32_t> TriVerts;   ///< 3 point ids per triangle, extraction order (until placed)
  TriangleArray<vtkIdType> SrcCell;        ///< TriCell, TriSub, TriFlags in extraction order (until placed)
  TriangleArray<std::int32_t> SrcSub;
  TriangleArray<std::uint8_t> SrcFlags;
  /// 3 point ids per triangle, leaf order: the exact test reads the double
  /// vertices through them from WorldCoords().
  TriangleArray<std::uint32_t> TriIds;
  /// Each leaf slot's triangle as 9 floats (vertex 0, 1, 2; x y z; point -
  /// Origin rounded to nearest), and one float of padding at the end (a
  /// vertex is read as four floats): what the float pre-test reads, which
  /// spares the double test nearly every miss. Stored per slot, not read
  /// through TriIds from a float copy of the points: a leaf's loads then
  /// wait for no other load, and a leaf is a few adjacent cache lines. That
  /// was measured 10-15% faster at 1M triangles for 30 more bytes a
  /// triangle.
  TriangleArray<float> TrianglesF;
  double Extent = 0.0; ///< bound on |local vertex| (inf norm), for the float error bound
  /// >= 0: every triangle t is the VTK_TRIANGLE cell UniformCellBase + t
  /// (extraction order), subId 0 (set by the all-triangle polys path).
  vtkIdType UniformCellBase = -1;
  /// The dataset's double coordinates at build time, read in place (the
  /// exact tests compute point - Origin, the same doubles a local copy would
  /// hold, and the hit's cell fill then finds them in cache); null when not
  /// double. DataSetCoordsArray keeps them alive; CoordsUnchanged() tells
  /// whether the array still has them there.
  const double* DataSetCoords = nullptr;
  vtkSmartPointer<vtkDataArray> DataSetCoordsArray;
  TriangleArray<vtkIdType> TriCell;        ///< original cell id per triangle
  /// subId and TriangleFlags per triangle (strips: subId is the triangle's
  /// index), in leaf order empty when UniformCellBase >= 0.
  TriangleArray<std::int32_t> TriSub;
  TriangleArray<std::uint8_t> TriFlags;
  std::vector<vtkIdType> GenCell;        ///< original cell id per general primitive
  std::vector<Box> GenBox;               ///< its bounds, local, slightly widened
  /// The binary tree of the point, box and all-hits queries (and of the
  /// closest hit where the float picking path cannot run). The fast build
  /// leaves it to the first query that needs it: EnsureTree().
  mutable core::BVH Tree;
  /// The picking tree, eight children a node (core/WideBVH.h). The fast
  /// build writes it directly over triangles; the others re-lay the core's
  /// binary nodes (no new split decisions).
  static constexpr int kWideArity = core::kWideArity;
  using WideNode = core::WideNode;
  std::vector<WideNode> Wide;
  mutable TreeStats Stats;
  vtkIdType SkippedCells = 0;   ///< cells in no leaf (non-finite or empty bounds)
  vtkIdType NonFiniteCells = 0; ///< surface cells dropped at extraction
  double BuildSeconds = 0.0;

  vtkIdType NumberOfTriangles() const { return static_cast<vtkIdType>(this->TriCell.size()); }
  vtkIdType NumberOfGeneralCells() const { return static_cast<vtkIdType>(this->GenCell.size()); }
  vtkIdType NumberOfPrimitives() const
  {
    return this->NumberOfTriangles() + this->NumberOfGeneralCells();
  }

  void Clear()
  {
    *this = BVHCellLocatorData();
  }

  /// Whether Tree is there (or not wanted): once set, never cleared before
  /// Clear(). Copying copies the state, not the mutex.
  struct TreeState
  {
    std::atomic<bool> Ready{ true };
    std::mutex Mutex;
    TreeState() = default;
    TreeState(const TreeState& o)
      : Ready(o.Ready.load())
    {
    }
    TreeState& operator=(const TreeState& o)
    {
      this->Ready.store(o.Ready.load());
      return *this;
    }
  };
  mutable TreeState TreeBuilt;
  core::BuildOptions TreeOptions; ///< what EnsureTree builds with

  /// Builds the binary tree if the fast build left it for later; safe to
  /// call from several query threads at once (one builds, the others wait).
  void EnsureTree() const
  {
    if (this->TreeBuilt.Ready.load(std::memory_order_acquire))
    {
      return;
    }
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

  size_t MemorySize() const
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
      this->Wide.capacity() * sizeof(WideNode);
  }

  //----------------------------------------------------------------------------
  // Extraction
  //----------------------------------------------------------------------------
  void Extract(vtkDataSet* ds)
  {
    if (auto* pd = vtkPolyData::SafeDownCast(ds))
    {
      this->BindPoints(pd->GetPoints());
      this->ExtractPolyData(pd);
    }
    else if (auto* ug = vtkUnstructuredGrid::SafeDownCast(ds))
    {
      this->BindPoints(ug->GetPoints());
      this->ExtractUnstructuredGrid(ug);
    }
    else
    {
      this->ComputeOrigin(ds);
      const vtkIdType n = ds->GetNumberOfCells();
      for (vtkIdType c = 0; c < n; ++c)
      {
        this->GenCell.push_back(c);
      }
    }
    this->ComputeGeneralBoxes(ds);
  }

  void Build(int quality, int leafSize)
  {
    const size_t nTri = this->TriCell.size();
    const size_t n = nTri + this->GenCell.size();
    core::BuildOptions options;
    options.quality = quality == 0 ? core::BuildQuality::Fast
                                   : (quality == 2 ? core::BuildQuality::High : core::BuildQuality::Medium);
    options.maxLeafSize = static_cast<std::uint32_t>(std::max(leafSize, 1));
    // The builder's parallel work goes to VTK's SMP pool: its own
    // std::threads would compete with the pool's workers, which keep
    // spinning after the parallel loops around this call (measured 1.4-1.8x
    // slower builds with 2 threads than with 1 on a 2-core machine).
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
        return this->TriangleBox(&this->TriVerts[3 * i]);
      },
      options);
    this->Reorder(nTri);
    this->BuildWide();
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

  void SetTreeStats() const
  {
    this->Stats.Nodes = static_cast<vtkIdType>(this->Tree.stats.nodeCount);
    this->Stats.Leaves = static_cast<vtkIdType>(this->Tree.stats.leafCount);
    this->Stats.Depth = static_cast<int>(this->Tree.stats.maxDepth);
    this->Stats.SAHCost = this->Tree.stats.sahCost;
  }

  /// The fast build (triangles only): the picking tree straight over the
  /// triangles (core::LazyWideBVH): the levels above its buckets now, each
  /// bucket's subtree when a query first reaches it (which puts its
  /// triangles in their leaf slots: point ids, cell id). No
  /// binary tree, no re-layout: a first pick waits for little more than the
  /// extraction.
  void BuildPickingTree(size_t nTri)
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

  /// The triangles as LazyWideBVH sees them (by extraction index).
  struct PickingTriangles
  {
    BVHCellLocatorData* Data;
    Box bounds(std::uint32_t id) const
    {
      return this->Data->TriangleBox(&this->Data->TriVerts[3 * static_cast<size_t>(id)]);
    }
    void placeLeaf(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t end, float lo[3], float hi[3])
    {
      Box box;
      for (std::uint32_t t = begin; t < end; ++t)
      {
        box.extend(this->Data->PlaceTriangle(ids[t - begin], t));
      }
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = core::detail::floorFloat(box.min[a]);
        hi[a] = core::detail::ceilFloat(box.max[a]);
      }
    }
    void prefetch(std::uint32_t id, int stage) const { this->Data->PrefetchTriangle(id, stage); }
  };
  using LazyPickingTree = core::LazyWideBVH<PickingTriangles>;
  /// The fast build's picking tree; null for the other builds (Wide).
  std::unique_ptr<LazyPickingTree> Lazy;

  /// The per-triangle arrays in leaf order, sized for nTri slots, and the
  /// extraction-order ones they are filled from (Src*, TriVerts), kept
  /// until every triangle is placed.
  void MakeLeafOrderArrays(size_t nTri)
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

  /// Every triangle placed: the extraction-order arrays can go.
  void DropExtractionArrays()
  {
    ExtractionArray<std::uint32_t>().swap(this->TriVerts);
    TriangleArray<vtkIdType>().swap(this->SrcCell);
    TriangleArray<std::int32_t>().swap(this->SrcSub);
    TriangleArray<std::uint8_t>().swap(this->SrcFlags);
    // Points stay: the exact tests read the double vertices through TriIds.
  }

  /// Triangle p (extraction order) goes to leaf slot t; returns its box.
  /// Slots are written from several threads at once, each slot by one.
  Box PlaceTriangle(std::uint32_t p, std::uint32_t t)
  {
    const std::uint32_t* v = &this->TriVerts[3 * static_cast<size_t>(p)];
    std::copy(v, v + 3, &this->TriIds[3 * static_cast<size_t>(t)]);
    Box box;
    float* f = &this->TrianglesF[9 * static_cast<size_t>(t)];
    for (int k = 0; k < 3; ++k)
    {
      const Vec3d local = this->LocalPoint(v[k]);
      box.extend(local);
      for (int a = 0; a < 3; ++a)
      {
        f[3 * k + a] = static_cast<float>(local[a]);
      }
    }
    if (this->UniformCellBase >= 0)
    {
      this->TriCell[t] = this->UniformCellBase + p; // no random reads of the per-triangle arrays
    }
    else
    {
      this->TriCell[t] = this->SrcCell[p];
      this->TriSub[t] = this->SrcSub[p];
      this->TriFlags[t] = this->SrcFlags[p];
    }
    return box;
  }

  /// Fetches triangle p's (extraction order) data ahead of a random read:
  /// stage 0 its point ids, stage 1 (later, once they have arrived) the
  /// points they name.
  void PrefetchTriangle(std::uint32_t p, int stage) const
  {
#if VTKRT_CORE_SSE
    const std::uint32_t* v = &this->TriVerts[3 * static_cast<size_t>(p)];
    if (stage == 0)
    {
      _mm_prefetch(reinterpret_cast<const char*>(v), _MM_HINT_T0);
      return;
    }
    for (int k = 0; k < 3; ++k)
    {
      _mm_prefetch(reinterpret_cast<const char*>(this->WorldCoords() + 3 * static_cast<std::size_t>(v[k])), _MM_HINT_T0);
    }
#else
    (void)p;
    (void)stage;
#endif
  }

  /// Triangle prim's subId and flags (leaf order). Those of all-triangle
  /// polys are whole VTK_TRIANGLE cells, subId 0: known without a random
  /// read of TriSub / TriFlags.
  int TriangleSubId(std::uint32_t prim) const
  {
    return this->UniformCellBase >= 0 ? 0 : this->TriSub[prim];
  }
  std::uint8_t TriangleFlags(std::uint32_t prim) const
  {
    return this->UniformCellBase >= 0 ? std::uint8_t(WholeTriangle) : this->TriFlags[prim];
  }

  /// The box of the triangle whose point ids are v[0], v[1], v[2].
  Box TriangleBox(const std::uint32_t* v) const
  {
    Box box;
    for (int k = 0; k < 3; ++k)
    {
      box.extend(this->LocalPoint(v[k]));
    }
    return box;
  }

  /// Nodes, leaves and depth of the picking tree (so far, for the fast build).
  size_t PickingNodeCount() const { return this->Lazy ? this->Lazy->nodeCount() : this->Wide.size(); }
  const WideNode* PickingRoot() const
  {
    return this->Lazy ? (this->Lazy->nodes().empty() ? nullptr : this->Lazy->nodes().data())
                      : (this->Wide.empty() ? nullptr : this->Wide.data());
  }

  /// The up to kWideArity binary nodes a wide node over binary interior node
  /// `b` holds: its children, then repeatedly the interior one of largest
  /// area replaced by its two children.
  int WideChildren(std::uint32_t b, std::uint32_t kids[kWideArity]) const
  {
    const auto& nodes = this->Tree.nodes;
    kids[0] = nodes[b].index;
    kids[1] = nodes[b].index + 1;
    int n = 2;
    while (n < kWideArity)
    {
      int best = -1;
      double bestArea = -1.0;
      for (int i = 0; i < n; ++i)
      {
        const core::BVHNode& c = nodes[kids[i]];
        if (!c.isLeaf())
        {
          const double area = c.bounds().halfArea();
          if (area > bestArea)
          {
            bestArea = area;
            best = i;
          }
        }
      }
      if (best < 0)
      {
        break;
      }
      const std::uint32_t first = nodes[kids[best]].index;
      kids[best] = first;
      kids[n++] = first + 1;
    }
    return n;
  }

  /// Appends the wide subtree over binary interior node `b` to `out`
  /// (depth first, indices local to `out`); returns its root's index.
  std::uint32_t Collapse(std::uint32_t b, std::vector<WideNode>& out) const
  {
    std::uint32_t kids[kWideArity];
    const int n = this->WideChildren(b, kids);
    const std::uint32_t w = static_cast<std::uint32_t>(out.size());
    out.emplace_back();
    core::WideNodeDraft node;
    node.clear();
#if VTKRT_CORE_SSE
    // The interior kids' own children are what their collapse reads first:
    // fetch them all now (a tree of millions of nodes is a cache miss per
    // read otherwise).
    for (int i = 0; i < n; ++i)
    {
      const core::BVHNode& c = this->Tree.nodes[kids[i]];
      if (!c.isLeaf())
      {
        const char* pair = reinterpret_cast<const char*>(&this->Tree.nodes[c.index]);
        _mm_prefetch(pair, _MM_HINT_T0);
        _mm_prefetch(pair + sizeof(core::BVHNode), _MM_HINT_T0);
      }
    }
#endif
    for (int i = 0; i < n; ++i)
    {
      const core::BVHNode& c = this->Tree.nodes[kids[i]];
      node.setBox(i, c.bounds());
      if (c.isLeaf())
      {
        node.child[i] = c.index;
        node.count[i] = c.count;
      }
      else
      {
        node.child[i] = this->Collapse(kids[i], out);
      }
    }
    out[w] = node.pack();
    return w;
  }

  /// The wide view: the root's wide node here, the subtrees below its
  /// interior slots in parallel, then appended in slot order.
  void BuildWide()
  {
    this->Wide.clear();
    if (this->Tree.empty())
    {
      return;
    }
    core::WideNodeDraft root;
    root.clear();
    std::uint32_t kids[kWideArity];
    int n = 1;
    if (this->Tree.nodes[0].isLeaf())
    {
      kids[0] = 0; // one slot holding the root leaf
    }
    else
    {
      n = this->WideChildren(0, kids);
    }
    // Storage from this thread (a worker thread's malloc arena would hand
    // large blocks back to the system after every build).
    std::vector<WideNode> sub[kWideArity];
    for (int i = 0; i < n; ++i)
    {
      sub[i].reserve(this->Tree.nodes.size() / 2 + 16);
    }
    vtkSMPTools::For(0, n, 1, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType i = b; i < e; ++i)
      {
        if (!this->Tree.nodes[kids[i]].isLeaf())
        {
          this->Collapse(kids[i], sub[i]);
        }
      }
    });
    size_t total = 1;
    for (const auto& v : sub)
    {
      total += v.size();
    }
    this->Wide.reserve(total);
    this->Wide.emplace_back(); // the root, packed once its slots are known
    for (int i = 0; i < n; ++i)
    {
      const core::BVHNode& c = this->Tree.nodes[kids[i]];
      root.setBox(i, c.bounds());
      if (c.isLeaf())
      {
        root.child[i] = c.index;
        root.count[i] = c.count;
        continue;
      }
      const std::uint32_t offset = static_cast<std::uint32_t>(this->Wide.size());
      root.child[i] = offset; // the subtree's root comes first
      for (WideNode w : sub[i])
      {
        for (int k = 0; k < kWideArity; ++k)
        {
          w.child[k] += w.count[k] == 0 ? offset : 0;
        }
        this->Wide.push_back(w);
      }
      std::vector<WideNode>().swap(sub[i]);
    }
    this->Wide[0] = root.pack();
  }

  /// Renumbers the primitives in leaf order (triangles first, then general
  /// cells) and stores each triangle's vertices inline, so that a leaf's
  /// primitives are adjacent in memory and a triangle test reads one cache
  /// line run instead of chasing point ids. Skipped primitives are dropped.
  void Reorder(size_t nTri)
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

  //----------------------------------------------------------------------------
  // Queries, over the core's traversals. GetCellFn returns the
  // vtkGenericCell this query may use as scratch for general cells.
  //----------------------------------------------------------------------------
  template <class GetCellFn>
  bool ClosestHit(const double p1[3], const double p2[3], double tol, vtkDataSet* ds,
    GetCellFn&& getCell, LineHit& out) const
  {
    core::Ray<double> ray;
    if (!this->MakeSegment(p1, p2, ray))
    {
      return false;
    }
    const core::RayTrianglePrecomputed<double> triPre(ray);
    const vtkIdType nTri = this->NumberOfTriangles();
    vtkIdType bestCell = -1;
    bool generalBest = false; ///< out holds a general cell's hit (a triangle's is filled after the walk)

    // Ties (same t) go to the lowest cell id, so the answer does not depend
    // on the traversal order.
    auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>& hit) {
      const bool haveBest = hit.found();
      if (static_cast<vtkIdType>(prim) < nTri)
      {
        double t, u, v;
        if (!this->IntersectTriangle(prim, triPre, r, tol, t, u, v))
        {
          return false;
        }
        const vtkIdType cellId = this->TriCell[prim];
        if (haveBest && t == hit.t && cellId > bestCell)
        {
          return false;
        }
        hit.t = t;
        hit.u = u;
        hit.v = v;
        bestCell = cellId;
        generalBest = false;
        return true;
      }
      const vtkIdType cellId = this->GenCell[prim - nTri];
      double t, x[3], pc[3];
      int sub;
      if (!IntersectCell(ds, cellId, getCell(), p1, p2, tol, r, t, x, pc, sub))
      {
        return false;
      }
      if (haveBest && t == hit.t && cellId > bestCell)
      {
        return false;
      }
      hit.t = t;
      bestCell = cellId;
      generalBest = true;
      out.T = t;
      out.SubId = sub;
      out.CellId = cellId;
      for (int k = 0; k < 3; ++k)
      {
        out.X[k] = x[k];
        out.PCoords[k] = pc[k];
      }
      out.NeedsEvaluate = false;
      out.TrianglePointIds = nullptr;
      return true;
    };
    core::Hit<double> hit;
    if (!this->WalkSegment<0>(ray, tol, isect, hit, &triPre))
    {
      return false;
    }
    if (generalBest)
    {
      return true;
    }
    const std::uint32_t prim = hit.prim;
    out.T = hit.t;
    out.CellId = this->TriCell[prim];
    for (int k = 0; k < 3; ++k)
    {
      out.X[k] = p1[k] + hit.t * ray.dir[k];
    }
    const std::uint8_t flags = this->TriangleFlags(prim);
    out.NeedsEvaluate = (flags & EvaluateInCell) != 0;
    out.TrianglePointIds =
      (flags & WholeTriangle) ? this->TriIds.data() + 3 * static_cast<std::size_t>(prim) : nullptr;
    out.SubId = this->TriangleSubId(prim);
    out.PCoords[0] = hit.u;
    out.PCoords[1] = hit.v;
    out.PCoords[2] = 0.0;
    return true;
  }

  template <class GetCellFn>
  void AllHits(const double p1[3], const double p2[3], double tol, vtkDataSet* ds,
    GetCellFn&& getCell, std::vector<LineHit>& hits) const
  {
    hits.clear();
    core::Ray<double> ray;
    if (!this->MakeSegment(p1, p2, ray))
    {
      return;
    }
    const core::RayTrianglePrecomputed<double> triPre(ray);
    const vtkIdType nTri = this->NumberOfTriangles();
    auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>&) {
      LineHit h;
      if (static_cast<vtkIdType>(prim) < nTri)
      {
        double t, u, v;
        if (!this->IntersectTriangle(prim, triPre, r, tol, t, u, v))
        {
          return false;
        }
        h.T = t;
        h.CellId = this->TriCell[prim];
        for (int k = 0; k < 3; ++k)
        {
          h.X[k] = p1[k] + t * r.dir[k];
        }
        const Vec3d v0 = this->Vertex(prim, 0);
        const Vec3d v1 = this->Vertex(prim, 1);
        const Vec3d v2 = this->Vertex(prim, 2);
        double side = glm::dot(core::triangleNormal(v0, v1, v2), r.dir);
        if (this->TriangleFlags(prim) & FlipOrientation)
        {
          side = -side;
        }
        h.Leaving = side > 0.0;
      }
      else
      {
        const vtkIdType cellId = this->GenCell[prim - nTri];
        double t, x[3], pc[3];
        int sub;
        if (!IntersectCell(ds, cellId, getCell(), p1, p2, tol, r, t, x, pc, sub))
        {
          return false;
        }
        h.T = t;
        h.CellId = cellId;
        for (int k = 0; k < 3; ++k)
        {
          h.X[k] = x[k];
        }
      }
      hits.push_back(h);
      return false; // collected here; nothing for the traversal to keep
    };
    core::Hit<double> hit;
    this->WalkSegment<2>(ray, tol, isect, hit);
    // One hit per cell (its nearest), then along the segment.
    std::sort(hits.begin(), hits.end(), [](const LineHit& a, const LineHit& b) {
      return a.CellId != b.CellId ? a.CellId < b.CellId : a.T < b.T;
    });
    hits.erase(std::unique(hits.begin(), hits.end(),
                 [](const LineHit& a, const LineHit& b) { return a.CellId == b.CellId; }),
      hits.end());
    std::stable_sort(hits.begin(), hits.end(),
      [](const LineHit& a, const LineHit& b) { return a.T < b.T; });
  }

  void CellsAlongLine(
    const double p1[3], const double p2[3], double tol, std::vector<vtkIdType>& cells) const
  {
    cells.clear();
    core::Ray<double> ray;
    if (!this->MakeSegment(p1, p2, ray))
    {
      return;
    }
    const core::RayBoxPrecomputed<double> boxPre(ray);
    auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>&) {
      const Box b = this->PrimitiveBox(prim);
      double tnear;
      if (core::intersectRayAABB(boxPre, b.min - Vec3d(tol), b.max + Vec3d(tol), r.tmin, r.tmax, tnear))
      {
        cells.push_back(this->PrimitiveCell(prim));
      }
      return false;
    };
    core::Hit<double> hit;
    this->WalkSegment<2>(ray, tol, isect, hit);
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  }

  void CellsInBox(const double bbox[6], std::vector<vtkIdType>& cells) const
  {
    cells.clear();
    const Box q(this->ToLocal(Vec3d(bbox[0], bbox[2], bbox[4])),
      this->ToLocal(Vec3d(bbox[1], bbox[3], bbox[5])));
    this->EnsureTree();
    core::queryBox(this->Tree, q, [&](std::uint32_t prim) {
      if (this->PrimitiveBox(prim).overlaps(q))
      {
        cells.push_back(this->PrimitiveCell(prim));
      }
    });
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  }

  template <class GetCellFn>
  bool ClosestPoint(
    const double xw[3], double radius, vtkDataSet* ds, GetCellFn&& getCell, PointHit& out) const
  {
    const Vec3d x = this->ToLocal(xw);
    const vtkIdType nTri = this->NumberOfTriangles();
    std::vector<double> weights(static_cast<size_t>(std::max(ds ? ds->GetMaxCellSize() : 1, 1)));
    // Per general primitive, what EvaluatePosition said (read back for the winner).
    PointHit general;
    std::uint32_t generalPrim = core::kInvalidIndex;
    auto fn = [&](std::uint32_t prim, const Vec3d& p, core::PointHit<double>& cand) {
      if (static_cast<vtkIdType>(prim) < nTri)
      {
        const Vec3d v0 = this->Vertex(prim, 0);
        const Vec3d v1 = this->Vertex(prim, 1);
        const Vec3d v2 = this->Vertex(prim, 2);
        cand.point = core::closestPointOnTriangle(p, v0, v1, v2);
        const Vec3d d = p - cand.point;
        cand.dist2 = glm::dot(d, d);
        return true;
      }
      const vtkIdType cellId = this->GenCell[prim - nTri];
      vtkGenericCell* cell = getCell();
      ds->GetCell(cellId, cell);
      double cp[3], pc[3], d2;
      int sub;
      double xx[3] = { xw[0], xw[1], xw[2] };
      const int r = cell->EvaluatePosition(xx, cp, sub, pc, d2, weights.data());
      if (r < 0 || !std::isfinite(d2))
      {
        return false;
      }
      if (r == 1 && cell->GetCellDimension() == 3)
      {
        std::copy(xx, xx + 3, cp); // inside a 3D cell: x itself
      }
      cand.point = this->ToLocal(cp);
      cand.dist2 = d2;
      // Keep the cell's own answer in case this candidate wins.
      if (d2 < general.Dist2 || generalPrim == core::kInvalidIndex)
      {
        general.CellId = cellId;
        general.SubId = sub;
        general.Dist2 = d2;
        general.Inside = r;
        std::copy(cp, cp + 3, general.X);
        generalPrim = prim;
      }
      return true;
    };
    core::PointHit<double> best;
    this->EnsureTree();
    if (!core::closestPoint(this->Tree, x, radius, fn, best))
    {
      return false;
    }
    if (best.prim == generalPrim)
    {
      out = general;
      return true;
    }
    const std::uint32_t prim = best.prim;
    out.CellId = this->TriCell[prim];
    out.Dist2 = best.dist2;
    for (int k = 0; k < 3; ++k)
    {
      out.X[k] = best.point[k] + this->Origin[k];
    }
    out.SubId = this->TriangleSubId(prim);
    out.NeedsEvaluate = (this->TriangleFlags(prim) & EvaluateInCell) != 0;
    out.Inside = this->ProjectsInside(prim, x) ? 1 : 0;
    return true;
  }

  vtkIdType FindCell(const double xw[3], double tol2, vtkDataSet* ds, vtkGenericCell* cell,
    double pcoords[3], double* weights) const
  {
    const Vec3d x = this->ToLocal(xw);
    const Vec3d tol(std::sqrt(tol2));
    const Box q(x - tol, x + tol);
    std::vector<vtkIdType> candidates;
    this->EnsureTree();
    core::queryBox(this->Tree, q, [&](std::uint32_t prim) {
      if (this->PrimitiveBox(prim).overlaps(q))
      {
        candidates.push_back(this->PrimitiveCell(prim));
      }
    });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    double xx[3] = { xw[0], xw[1], xw[2] };
    for (const vtkIdType cellId : candidates)
    {
      ds->GetCell(cellId, cell);
      double cp[3], dist2;
      int sub;
      if (cell->EvaluatePosition(xx, cp, sub, pcoords, dist2, weights) == 1 && dist2 <= tol2)
      {
        return cellId;
      }
    }
    return -1;
  }

  /// Boxes (local coordinates) of the nodes at depth `level` and of the
  /// leaves above it; all leaves for a negative level.
  void BoxesAtLevel(int level, std::vector<Box>& boxes) const
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

  /// x y z of each point, world coordinates.
  const double* WorldCoords() const
  {
    static_assert(sizeof(Vec3d) == 3 * sizeof(double), "x y z, packed");
    return this->DataSetCoords ? this->DataSetCoords : reinterpret_cast<const double*>(this->PointsCopy.data());
  }
  /// Point id relative to Origin (rounded once, as a stored local copy would be).
  Vec3d LocalPoint(vtkIdType id) const
  {
    const double* c = this->WorldCoords() + 3 * static_cast<std::size_t>(id);
    return Vec3d(c[0] - this->Origin.x, c[1] - this->Origin.y, c[2] - this->Origin.z);
  }
  /// False when the dataset's double coordinates array no longer holds the
  /// build's points where they were (reallocated or shrunk, perhaps without
  /// a Modified()): the tree must not read them.
  bool CoordsUnchanged() const
  {
    return !this->DataSetCoordsArray ||
      (this->DataSetCoordsArray->GetVoidPointer(0) == this->DataSetCoords &&
        this->DataSetCoordsArray->GetNumberOfTuples() >= this->NumberOfPoints);
  }

private:
  /// Local double vertex k of (leaf-ordered) triangle prim.
  Vec3d Vertex(std::uint32_t prim, int k) const
  {
    return this->LocalPoint(this->TriIds[3 * static_cast<std::size_t>(prim) + k]);
  }

  Vec3d ToLocal(const double p[3]) const
  {
    return Vec3d(p[0] - this->Origin.x, p[1] - this->Origin.y, p[2] - this->Origin.z);
  }
  Vec3d ToLocal(const Vec3d& p) const { return p - this->Origin; }

  Box PrimitiveBox(std::uint32_t prim) const
  {
    const vtkIdType nTri = this->NumberOfTriangles();
    if (static_cast<vtkIdType>(prim) < nTri)
    {
      return this->TriangleBox(&this->TriIds[3 * static_cast<size_t>(prim)]);
    }
    return this->GenBox[prim - nTri];
  }

  vtkIdType PrimitiveCell(std::uint32_t prim) const
  {
    const vtkIdType nTri = this->NumberOfTriangles();
    return static_cast<vtkIdType>(prim) < nTri ? this->TriCell[prim] : this->GenCell[prim - nTri];
  }

  /// The core's nodes with every box grown by tol (a cell within tol of the
  /// segment may lie outside its box by up to tol).
  struct GrownNodeSource
  {
    using Scalar = double;
    const core::BVHNode* nodes = nullptr;
    std::size_t size = 0;
    double grow = 0.0;
    Vec3d lo(std::uint32_t i) const { return nodes[i].min - Vec3d(grow); }
    Vec3d hi(std::uint32_t i) const { return nodes[i].max + Vec3d(grow); }
    std::uint32_t index(std::uint32_t i) const { return nodes[i].index; }
    std::uint32_t count(std::uint32_t i) const { return nodes[i].count; }
  };

  bool MakeSegment(const double p1[3], const double p2[3], core::Ray<double>& ray) const
  {
    if (!this->PickingRoot()) // every build with primitives makes the picking tree
    {
      return false;
    }
    const Vec3d dir(p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]);
    // VTK cells never hit a zero-length segment either.
    ray = core::Ray<double>(this->ToLocal(p1), dir, 0.0, 1.0);
    return ray.isValid();
  }

  /// Mode 0: closest hit, 2: every primitive (the intersector collects).
  template <int Mode, class Isect>
  bool WalkSegment(const core::Ray<double>& ray, double tol, Isect& isect, core::Hit<double>& hit,
    const core::RayTrianglePrecomputed<double>* triPre = nullptr) const
  {
    if (Mode == 0)
    {
      const int walked =
        this->ClosestHitWide(ray, triPre ? *triPre : core::RayTrianglePrecomputed<double>(ray), tol, isect, hit);
      if (walked >= 0)
      {
        return walked != 0;
      }
    }
    // Axis-parallel or extreme segments, and every hit: the core's double
    // traversal of the binary tree.
    this->EnsureTree();
    const std::uint32_t* primIndex = this->Tree.primIndex.data();
    const GrownNodeSource nodes{ this->Tree.nodes.data(), this->Tree.nodes.size(), tol };
    if (Mode == 0)
    {
      return core::closestHit(nodes, primIndex, ray, isect, hit);
    }
    core::allHits(nodes, primIndex, ray, isect);
    return false;
  }

  /// The picking hot path: the core's closest-hit contract (ordered,
  /// nearest first, the intersector shrinks ray.tmax) over the eight-wide
  /// view of the same tree, culling in float with the conservative
  /// pre-tests of core/ConservativeFloat.h: a node's eight boxes and a
  /// leaf's triangles (tol 0) eight per AVX2 step where the CPU has it,
  /// else four per SSE step, so that only triangles the exact double test
  /// might accept reach it.
  /// Returns 1 (hit), 0 (none), or -1 when the float walk cannot take the
  /// segment (ConservativeRay4::init refuses it: the caller walks in double).
  template <class Isect>
  int ClosestHitWide(const core::Ray<double>& ray, const core::RayTrianglePrecomputed<double>& triPre,
    double tol, Isect& isect, core::Hit<double>& hit) const
  {
#if VTKRT_CORE_AVX2
    if (core::useAvx2())
    {
      return this->ClosestHitWideAvx2(ray, triPre, tol, isect, hit);
    }
#endif
    core::ConservativeRay4 fray;
    if (!fray.init(ray, triPre, tol, this->Extent))
    {
      return -1;
    }
    return this->WalkWide<SseKernels>(fray, ray, tol, isect, hit) ? 1 : 0;
  }

  /// The float pre-tests of the walk, four lanes a step (SSE, or plain
  /// loops without it) or eight (AVX2): the same bits either way.
  struct SseKernels
  {
    using BoxRay = core::ConservativeBoxRay4;
    static constexpr int kTriangleLanes = 4;
    static int Boxes(const BoxRay& r, const WideNode& w, float tmaxScaled, float tnear[kWideArity])
    {
      return core::intersectBoxes8(r, w.box, tmaxScaled, tnear);
    }
    static int Triangles(const core::ConservativeRay4& r, const float* tri, int n)
    {
      return core::triangleCandidates4(r, tri, n);
    }
    /// Starts the loads of node w's children: both lines of each child node,
    /// the first two lines of each leaf's slots (leafBase + slot * leafStride).
    /// Without branches: an unused slot fetches node 0 of the array, a slot
    /// built on demand some line of the leaf data, both harmless. Addresses
    /// are integers: a prefetch never faults, and no pointer is formed out of
    /// its array.
    static void PrefetchChildren(
      const WideNode& w, std::uintptr_t nodeBase, std::uintptr_t leafBase, std::uintptr_t leafStride)
    {
#if VTKRT_CORE_SSE
      for (int i = 0; i < kWideArity; ++i)
      {
        const std::uintptr_t c = w.child[i];
        const std::uintptr_t p = w.count[i] == 0 ? nodeBase + c * sizeof(WideNode) : leafBase + c * leafStride;
        _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(p + 64), _MM_HINT_T0);
      }
#else
      (void)w;
      (void)nodeBase;
      (void)leafBase;
      (void)leafStride;
#endif
    }
  };
#if VTKRT_CORE_AVX2
  struct Avx2Kernels
  {
    using BoxRay = core::ConservativeBoxRay8;
    static constexpr int kTriangleLanes = 8;
    VTKRT_TARGET_AVX2 static int Boxes(const BoxRay& r, const WideNode& w, float tmaxScaled, float tnear[kWideArity])
    {
      return core::intersectBoxes8(r, w.box, tmaxScaled, tnear);
    }
    VTKRT_TARGET_AVX2 static int Triangles(const core::ConservativeRay4& r, const float* tri, int n)
    {
      return core::triangleCandidates8(r, tri, n);
    }
    /// PrefetchChildren's eight addresses in two AVX2 steps.
    VTKRT_TARGET_AVX2 static void PrefetchChildren(
      const WideNode& w, std::uintptr_t nodeBase, std::uintptr_t leafBase, std::uintptr_t leafStride)
    {
      static_assert(sizeof(WideNode) == 128, "a child node's offset is its index shifted by 7");
      const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(w.child));
      const __m256i interior =
        _mm256_cmpeq_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(w.count)), _mm256_setzero_si256());
      alignas(32) std::uint64_t address[kWideArity];
      for (int half = 0; half < 2; ++half)
      {
        const __m256i c = _mm256_cvtepu32_epi64(
          half ? _mm256_extracti128_si256(child, 1) : _mm256_castsi256_si128(child));
        const __m256i isNode = _mm256_cvtepi32_epi64(
          half ? _mm256_extracti128_si256(interior, 1) : _mm256_castsi256_si128(interior));
        const __m256i node = _mm256_add_epi64(_mm256_set1_epi64x(static_cast<long long>(nodeBase)), _mm256_slli_epi64(c, 7));
        const __m256i leaf = _mm256_add_epi64(_mm256_set1_epi64x(static_cast<long long>(leafBase)),
          _mm256_mul_epu32(c, _mm256_set1_epi64x(static_cast<long long>(leafStride))));
        _mm256_store_si256(reinterpret_cast<__m256i*>(address + 4 * half), _mm256_blendv_epi8(leaf, node, isNode));
      }
      for (const std::uint64_t p : address)
      {
        _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(p + 64), _MM_HINT_T0);
      }
    }
  };

  /// The ray's float constants and the walk compiled for AVX2 (WalkWide is
  /// inlined here, with the caller's exact test): only called when the CPU
  /// has it. ClosestHitWide's return values.
  template <class Isect>
  VTKRT_TARGET_AVX2 int ClosestHitWideAvx2(const core::Ray<double>& ray,
    const core::RayTrianglePrecomputed<double>& triPre, double tol, Isect& isect, core::Hit<double>& hit) const
  {
    core::ConservativeRay4 fray;
    if (!fray.initAvx2(ray, triPre, tol, this->Extent))
    {
      return -1;
    }
    return this->WalkWide<Avx2Kernels>(fray, ray, tol, isect, hit) ? 1 : 0;
  }
#endif

  template <class Kernels, class Isect>
  VTKRT_ALWAYS_INLINE inline bool WalkWide(const core::ConservativeRay4& fray, core::Ray<double> ray, double tol,
    Isect& isect, core::Hit<double>& hit) const
  {
    hit = core::Hit<double>();
    const std::uint32_t nTri = static_cast<std::uint32_t>(this->TriCell.size());
    const bool allTriangles = this->GenCell.empty();
    // Slots are primitives when all are triangles (the binary tree may be
    // under construction then: not read); otherwise through its primIndex.
    const std::uint32_t* primIndex = allTriangles ? nullptr : this->Tree.primIndex.data();
    const bool preTest = tol == 0.0; // the float triangle test knows no tolerance
    // Below the top levels of a large tree, a node's children are fetched
    // while its boxes are tested (Kernels::PrefetchChildren): the step to
    // the next node or leaf then seldom waits on memory.
    const bool prefetchChildren = nTri + this->GenCell.size() >= kPrefetchChildrenMinPrimitives;
    // A leaf slot leads to its float triangles (all triangles) or to its
    // primIndex entries.
    const std::uintptr_t leafBase = allTriangles ? reinterpret_cast<std::uintptr_t>(this->TrianglesF.data())
                                                 : reinterpret_cast<std::uintptr_t>(primIndex);
    const std::uintptr_t leafStride = allTriangles ? 9 * sizeof(float) : sizeof(std::uint32_t);
    struct Entry
    {
      const WideNode* Nodes; ///< the node array Ref indexes (interior children)
      std::uint32_t Ref;
      std::uint32_t Count; ///< > 0: a leaf (Ref = first primIndex slot); kWideSubtree: not built yet
      float Dist;
      std::uint32_t Depth; ///< wide levels below the root
    };
    // Each wide level pushes at most kWideArity - 1 entries; there are at
    // most kMaxDepth levels.
    Entry stack[(kWideArity - 1) * core::kMaxStackSize + 4];
    std::uint32_t sp = 0;
    float tmaxF = core::ConservativeRay4::scaledTmax(ray.tmax);
    bool found = false;
    auto test = [&](std::uint32_t prim) VTKRT_ALWAYS_INLINE {
      core::Hit<double> candidate = hit;
      if (isect(prim, ray, candidate))
      {
        candidate.prim = prim;
        found = true;
        hit = candidate;
        ray.tmax = hit.t;
        tmaxF = core::ConservativeRay4::scaledTmax(ray.tmax);
      }
    };
    // Triangles [first, end) in leaf order, Kernels::kTriangleLanes at a time.
    // Inlined, so that in the AVX2 walk they are compiled for AVX2 too.
    auto testTriangles = [&](std::uint32_t first, std::uint32_t end) VTKRT_ALWAYS_INLINE {
      if (!preTest)
      {
        for (std::uint32_t prim = first; prim < end; ++prim)
        {
          test(prim);
        }
        return;
      }
#if VTKRT_CORE_SSE
      // A survivor's exact test reads its point ids: fetched now, beside
      // the float triangles, not after the float test.
      this->PrefetchRange(this->TriIds.data() + 3 * static_cast<std::size_t>(first),
        this->TriIds.data() + 3 * static_cast<std::size_t>(end));
#endif
      for (std::uint32_t t = first; t < end; t += Kernels::kTriangleLanes)
      {
        const int n = static_cast<int>(std::min<std::uint32_t>(Kernels::kTriangleLanes, end - t));
        int mask = Kernels::Triangles(fray, this->TrianglesF.data() + 9 * static_cast<std::size_t>(t), n) & ((1 << n) - 1);
#if VTKRT_CORE_SSE
        // The exact test reads the double points (which then fill the
        // caller's cell), a hit its cell id, subId and flags: start every
        // survivor's loads before the first exact test.
        const double* coords = this->WorldCoords();
        for (int m = mask; m; m &= m - 1)
        {
          const std::size_t prim = t + static_cast<std::size_t>(CountTrailingZeros(static_cast<unsigned>(m)));
          for (int k = 0; k < 3; ++k)
          {
            _mm_prefetch(reinterpret_cast<const char*>(coords + 3 * static_cast<std::size_t>(this->TriIds[3 * prim + k])), _MM_HINT_T0);
          }
          _mm_prefetch(reinterpret_cast<const char*>(&this->TriCell[prim]), _MM_HINT_T0);
          if (this->UniformCellBase < 0) // else TriangleSubId / TriangleFlags read neither
          {
            _mm_prefetch(reinterpret_cast<const char*>(&this->TriSub[prim]), _MM_HINT_T0);
            _mm_prefetch(reinterpret_cast<const char*>(&this->TriFlags[prim]), _MM_HINT_T0);
          }
        }
#endif
        while (mask)
        {
          const int lane = CountTrailingZeros(static_cast<unsigned>(mask));
          mask &= mask - 1;
          test(t + static_cast<std::uint32_t>(lane));
        }
      }
    };
    // A child that waits on the stack: its node's lines, or a leaf's float
    // triangles (what the float test reads), fetched meanwhile.
    auto prefetchEntry = [&](const Entry& c) VTKRT_ALWAYS_INLINE {
#if VTKRT_CORE_SSE
      if (c.Count == 0)
      {
        const char* next = reinterpret_cast<const char*>(&c.Nodes[c.Ref]);
        for (std::size_t line = 0; line < sizeof(WideNode); line += 64)
        {
          _mm_prefetch(next + line, _MM_HINT_T0);
        }
      }
      else if (allTriangles && c.Count != core::kWideSubtree)
      {
        this->PrefetchRange(this->TrianglesF.data() + 9 * static_cast<std::size_t>(c.Ref),
          this->TrianglesF.data() + 9 * static_cast<std::size_t>(c.Ref + c.Count));
      }
#else
      (void)c;
#endif
    };
    const typename Kernels::BoxRay boxRay(fray);
    Entry cur{ this->PickingRoot(), 0, 0, 0.0f, 0 };
    for (;;)
    {
      if (cur.Count == core::kWideSubtree)
      {
        // A bucket of the fast build that no query has reached yet: built
        // now (once; thread-safe), then walked as if it had been there.
        const LazyPickingTree::Subtree sub = this->Lazy->subtree(cur.Ref);
        cur = { sub.nodes, sub.child, sub.count, cur.Dist, cur.Depth };
      }
      if (cur.Count == 0)
      {
        const WideNode& w = cur.Nodes[cur.Ref];
        if (prefetchChildren && cur.Depth >= kPrefetchChildrenDepth)
        {
          Kernels::PrefetchChildren(w, reinterpret_cast<std::uintptr_t>(cur.Nodes), leafBase, leafStride);
        }
        alignas(32) float tnear[kWideArity];
        int mask = Kernels::Boxes(boxRay, w, tmaxF, tnear);
        if (mask)
        {
          // The nearest hit child is walked next (one hit, the most common
          // case, is just that); the others go on the stack farthest first,
          // their first loads started now (again, below the top levels: a
          // leaf's whole slot range here, and skipping it measured no
          // quicker and 11 instructions a pick more).
          int i = CountTrailingZeros(static_cast<unsigned>(mask));
          mask &= mask - 1;
          Entry nearest{ cur.Nodes, w.child[i], w.count[i], tnear[i], cur.Depth + 1 };
          const std::uint32_t base = sp;
          while (mask)
          {
            i = CountTrailingZeros(static_cast<unsigned>(mask));
            mask &= mask - 1;
            Entry c{ cur.Nodes, w.child[i], w.count[i], tnear[i], cur.Depth + 1 };
            if (c.Dist < nearest.Dist)
            {
              std::swap(c, nearest);
            }
            prefetchEntry(c);
            std::uint32_t j = sp++;
            while (j > base && stack[j - 1].Dist < c.Dist)
            {
              stack[j] = stack[j - 1];
              --j;
            }
            stack[j] = c;
          }
          cur = nearest;
          continue;
        }
      }
      else if (allTriangles)
      {
        testTriangles(cur.Ref, cur.Ref + cur.Count); // primIndex is the identity
      }
      else
      {
        for (std::uint32_t k = 0; k < cur.Count; ++k)
        {
          const std::uint32_t prim = primIndex[cur.Ref + k];
          if (prim < nTri)
          {
            testTriangles(prim, prim + 1);
          }
          else
          {
            test(prim);
          }
        }
      }
      do
      {
        if (sp == 0)
        {
          return found;
        }
        cur = stack[--sp];
      } while (cur.Dist > tmaxF);
    }
  }

  /// The walk fetches children ahead (PrefetchChildren) for trees over this
  /// many primitives (their float triangles alone, 36 bytes each, outgrow a
  /// core's L2 of about 1 MiB), below this many wide levels (the first three
  /// levels and their children, 8^3 nodes or 64 KiB, stay in L2 anyway).
  /// Measured with the same locator and rays in one process, rounds
  /// alternating with and without: 1M triangles 1.22x quicker picks, 100k
  /// 1.08-1.17x; 7,000 triangles 13% slower with it, hence the size.
  static constexpr std::size_t kPrefetchChildrenMinPrimitives = 32768;
  static constexpr std::uint32_t kPrefetchChildrenDepth = 3;

#if VTKRT_CORE_SSE
  /// Fetches the cache lines of [begin, end) (non-empty) into L1.
  template <class T>
  static void PrefetchRange(const T* begin, const T* end)
  {
    const char* p = reinterpret_cast<const char*>(begin);
    const char* last = reinterpret_cast<const char*>(end) - 1;
    for (; p < last; p += 64)
    {
      _mm_prefetch(p, _MM_HINT_T0);
    }
    _mm_prefetch(last, _MM_HINT_T0);
  }
#endif

  /// A general cell's own IntersectWithLine on the segment p1 -> p2, kept
  /// only within the walk's current range [r.tmin, r.tmax].
  static bool IntersectCell(vtkDataSet* ds, vtkIdType cellId, vtkGenericCell* cell,
    const double p1[3], const double p2[3], double tol, const core::Ray<double>& r, double& t,
    double x[3], double pc[3], int& sub)
  {
    ds->GetCell(cellId, cell);
    return cell->IntersectWithLine(p1, p2, tol, t, x, pc, sub) && t >= r.tmin && t <= r.tmax;
  }

  static int CountTrailingZeros(unsigned x)
  {
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctz(x);
#else
    int n = 0;
    while (!(x & 1u))
    {
      x >>= 1;
      ++n;
    }
    return n;
#endif
  }

  /// Watertight hit, or (tol > 0) VTK's rule: the crossing of the plane lies
  /// within tol of the triangle. u, v: VTK triangle pcoords of the hit.
  bool IntersectTriangle(std::uint32_t prim, const core::RayTrianglePrecomputed<double>& pre,
    const core::Ray<double>& ray, double tol, double& t, double& u, double& v) const
  {
    const Vec3d v0 = this->Vertex(prim, 0);
    const Vec3d v1 = this->Vertex(prim, 1);
    const Vec3d v2 = this->Vertex(prim, 2);
    core::TriangleHit<double> hit;
    if (core::intersectRayTriangle(pre, v0, v1, v2, ray.tmin, ray.tmax, hit))
    {
      t = hit.t;
      u = hit.u;
      v = hit.v;
      return true;
    }
    if (tol <= 0.0)
    {
      return false;
    }
    const Vec3d e1 = v1 - v0, e2 = v2 - v0;
    const Vec3d n = glm::cross(e1, e2);
    const double denom = glm::dot(n, ray.dir);
    if (denom == 0.0)
    {
      return false;
    }
    const double tt = glm::dot(n, v0 - ray.org) / denom;
    if (!(tt >= ray.tmin && tt <= ray.tmax))
    {
      return false;
    }
    const Vec3d x = ray.org + tt * ray.dir;
    const Vec3d cp = core::closestPointOnTriangle(x, v0, v1, v2);
    const Vec3d d = x - cp;
    if (glm::dot(d, d) > tol * tol)
    {
      return false;
    }
    t = tt;
    Barycentric(x, v0, e1, e2, u, v);
    return true;
  }

  static void Barycentric(
    const Vec3d& x, const Vec3d& v0, const Vec3d& e1, const Vec3d& e2, double& u, double& v)
  {
    const Vec3d w = x - v0;
    const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
    const double w1 = glm::dot(w, e1), w2 = glm::dot(w, e2);
    const double det = d11 * d22 - d12 * d12;
    if (det == 0.0)
    {
      u = v = 0.0;
      return;
    }
    u = (d22 * w1 - d12 * w2) / det;
    v = (d11 * w2 - d12 * w1) / det;
  }

  /// Whether x projects into the triangle (vtkTriangle::EvaluatePosition == 1).
  bool ProjectsInside(std::uint32_t prim, const Vec3d& x) const
  {
    const Vec3d v0 = this->Vertex(prim, 0);
    const Vec3d v1 = this->Vertex(prim, 1);
    const Vec3d v2 = this->Vertex(prim, 2);
    double u, v;
    Barycentric(x, v0, v1 - v0, v2 - v0, u, v);
    return u >= 0.0 && v >= 0.0 && u + v <= 1.0;
  }

  void ComputeOrigin(vtkDataSet* ds)
  {
    // Center of the finite points' bounds (NaN/inf points would poison it).
    Box b;
    const vtkIdType n = ds->GetNumberOfPoints();
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      ds->GetPoint(i, p);
      const Vec3d v(p[0], p[1], p[2]);
      if (core::isFinite(v))
      {
        b.extend(v);
      }
    }
    this->Origin = b.isEmpty() ? Vec3d(0.0) : b.center();
  }

  /// The points: double coordinates read in place (else a double copy of
  /// them), the Origin at the center of their finite bounds (NaN/inf
  /// points would poison it).
  void BindPoints(vtkPoints* pts)
  {
    const vtkIdType n = pts ? pts->GetNumberOfPoints() : 0;
    this->NumberOfPoints = n;
    if (n == 0)
    {
      return;
    }
    auto* d = vtkDoubleArray::FastDownCast(pts->GetData());
    if (d && d->GetNumberOfComponents() == 3)
    {
      this->DataSetCoordsArray = d;
      this->DataSetCoords = d->GetPointer(0);
    }
    else
    {
      this->PointsCopy.resize(static_cast<size_t>(n));
      vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
        double p[3];
        for (vtkIdType i = b; i < e; ++i)
        {
          pts->GetPoint(i, p);
          this->PointsCopy[i] = Vec3d(p[0], p[1], p[2]);
        }
      });
    }
    const Vec3d* src = reinterpret_cast<const Vec3d*>(this->WorldCoords());
    // Bounds of the finite points, in fixed chunks (same result for any
    // thread count).
    constexpr vtkIdType kChunks = 64;
    std::vector<Box> chunkBox(kChunks);
    vtkSMPTools::For(0, kChunks, [&](vtkIdType cb, vtkIdType ce) {
      for (vtkIdType c = cb; c < ce; ++c)
      {
        Box box;
        for (vtkIdType i = c * n / kChunks, e = (c + 1) * n / kChunks; i < e; ++i)
        {
          if (core::isFinite(src[i]))
          {
            box.extend(src[i]);
          }
        }
        chunkBox[c] = box;
      }
    });
    Box b;
    for (const Box& box : chunkBox)
    {
      b.extend(box);
    }
    this->Origin = b.isEmpty() ? Vec3d(0.0) : b.center();
    const Vec3d o = this->Origin;
    this->PointBounds = b.isEmpty() ? Box() : Box(b.min - o, b.max - o);
  }

  /// Whether every point id fits the 32-bit ids of the triangle arrays.
  bool PointsIndexable() const
  {
    return static_cast<std::uint64_t>(this->NumberOfPoints) < std::numeric_limits<std::uint32_t>::max();
  }

  /// Polys that are all triangles, read straight from the connectivity in
  /// parallel (no per-cell iterator, no push_back). False, with nothing
  /// added, when a cell is not a triangle or has an out-of-range or
  /// non-finite point: the cell-by-cell path then handles the polys.
  bool ExtractTrianglePolys(vtkCellArray* polys, vtkIdType cellBase)
  {
    const vtkIdType n = polys ? polys->GetNumberOfCells() : 0;
    if (n < 1 || polys->GetNumberOfConnectivityIds() != 3 * n ||
      !this->PointsIndexable())
    {
      return false;
    }
    if (polys->IsStorage64Bit())
    {
      return this->ExtractTriangles(polys->GetOffsetsArray64()->GetPointer(0),
        polys->GetConnectivityArray64()->GetPointer(0), n, cellBase);
    }
    return this->ExtractTriangles(polys->GetOffsetsArray32()->GetPointer(0),
      polys->GetConnectivityArray32()->GetPointer(0), n, cellBase);
  }

  template <class IdT>
  bool ExtractTriangles(const IdT* offsets, const IdT* conn, vtkIdType n, vtkIdType cellBase)
  {
    const size_t first = this->TriCell.size();
    this->TriVerts.resize(3 * (first + n));
    this->TriCell.resize(first + n);
    this->TriSub.resize(first + n);
    this->TriFlags.resize(first + n);
    const IdT nPoints = static_cast<IdT>(this->NumberOfPoints);
    std::atomic<bool> ok{ true };
    vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
      bool good = true;
      for (vtkIdType i = b; i < e; ++i)
      {
        good = good && offsets[i] == static_cast<IdT>(3 * i);
        for (int k = 0; k < 3; ++k)
        {
          const IdT id = conn[3 * i + k];
          good = good && id >= 0 && id < nPoints && core::isFinite(this->LocalPoint(id));
          this->TriVerts[3 * (first + i) + k] = static_cast<std::uint32_t>(good ? id : 0);
        }
        this->TriCell[first + i] = cellBase + i;
        this->TriSub[first + i] = 0;
        this->TriFlags[first + i] = WholeTriangle;
      }
      if (!good)
      {
        ok = false;
      }
    });
    if (!ok)
    {
      this->TriVerts.resize(3 * first);
      this->TriCell.resize(first);
      this->TriSub.resize(first);
      this->TriFlags.resize(first);
    }
    else if (first == 0)
    {
      this->UniformCellBase = cellBase; // until another triangle is added
    }
    return ok;
  }

  void AddTriangle(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cellId, int sub, std::uint8_t flags)
  {
    this->TriVerts.push_back(static_cast<std::uint32_t>(a));
    this->TriVerts.push_back(static_cast<std::uint32_t>(b));
    this->TriVerts.push_back(static_cast<std::uint32_t>(c));
    this->TriCell.push_back(cellId);
    this->UniformCellBase = -1;
    this->TriSub.push_back(sub);
    this->TriFlags.push_back(flags);
  }

  /// Triangulates a surface cell onto the fast path; false when it must take
  /// the general path.
  bool AddSurfaceCell(int type, vtkIdType npts, const vtkIdType* pts, vtkIdType cellId,
    vtkPolygon* polygon, vtkIdList* tris)
  {
    if (type != VTK_TRIANGLE && type != VTK_QUAD && type != VTK_POLYGON && type != VTK_TRIANGLE_STRIP)
    {
      return false;
    }
    const vtkIdType nPoints = this->NumberOfPoints;
    for (vtkIdType i = 0; i < npts; ++i)
    {
      if (pts[i] < 0 || pts[i] >= nPoints)
      {
        return false; // let the general path (and VTK) deal with it
      }
    }
    for (vtkIdType i = 0; i < npts; ++i)
    {
      if (!core::isFinite(this->LocalPoint(pts[i])))
      {
        ++this->NonFiniteCells; // a cell with a NaN/inf point is never hit
        return true;
      }
    }
    switch (type)
    {
      case VTK_TRIANGLE:
        if (npts != 3)
        {
          return false;
        }
        this->AddTriangle(pts[0], pts[1], pts[2], cellId, 0, WholeTriangle);
        return true;
      case VTK_QUAD:
        if (npts != 4)
        {
          return false;
        }
        this->AddQuad(pts, cellId);
        return true;
      case VTK_POLYGON:
        if (npts < 3)
        {
          return false;
        }
        if (npts == 3)
        {
          this->AddTriangle(pts[0], pts[1], pts[2], cellId, 0, EvaluateInCell);
          return true;
        }
        if (npts == 4)
        {
          this->AddQuad(pts, cellId);
          return true;
        }
        this->AddPolygon(npts, pts, cellId, polygon, tris);
        return true;
      case VTK_TRIANGLE_STRIP:
        if (npts < 3)
        {
          return false;
        }
        for (vtkIdType k = 0; k + 2 < npts; ++k)
        {
          // subId k and pcoords on (k, k+1, k+2), as vtkTriangleStrip's
          // IntersectWithLine and EvaluatePosition report them.
          this->AddTriangle(pts[k], pts[k + 1], pts[k + 2], cellId, static_cast<int>(k),
            (k & 1) ? FlipOrientation : 0);
        }
        return true;
      default:
        return false;
    }
  }

  void AddQuad(const vtkIdType* pts, vtkIdType cellId)
  {
    // Split along the shorter diagonal, as vtkQuad::IntersectWithLine does.
    const Vec3d d02 = this->LocalPoint(pts[2]) - this->LocalPoint(pts[0]);
    const Vec3d d13 = this->LocalPoint(pts[3]) - this->LocalPoint(pts[1]);
    if (glm::dot(d02, d02) <= glm::dot(d13, d13))
    {
      this->AddTriangle(pts[0], pts[1], pts[2], cellId, 0, EvaluateInCell);
      this->AddTriangle(pts[0], pts[2], pts[3], cellId, 0, EvaluateInCell);
    }
    else
    {
      this->AddTriangle(pts[0], pts[1], pts[3], cellId, 0, EvaluateInCell);
      this->AddTriangle(pts[1], pts[2], pts[3], cellId, 0, EvaluateInCell);
    }
  }

  void AddPolygon(
    vtkIdType npts, const vtkIdType* pts, vtkIdType cellId, vtkPolygon* polygon, vtkIdList* tris)
  {
    polygon->GetPointIds()->SetNumberOfIds(npts);
    polygon->GetPoints()->SetNumberOfPoints(npts);
    for (vtkIdType i = 0; i < npts; ++i)
    {
      polygon->GetPointIds()->SetId(i, pts[i]);
      const Vec3d p = this->LocalPoint(pts[i]);
      polygon->GetPoints()->SetPoint(i, p.x, p.y, p.z);
    }
    tris->Reset();
    if (polygon->Triangulate(tris) && tris->GetNumberOfIds() >= 3)
    {
      for (vtkIdType k = 0; k + 2 < tris->GetNumberOfIds(); k += 3)
      {
        this->AddTriangle(pts[tris->GetId(k)], pts[tris->GetId(k + 1)], pts[tris->GetId(k + 2)],
          cellId, 0, EvaluateInCell);
      }
      return;
    }
    for (vtkIdType k = 1; k + 1 < npts; ++k) // fan for polygons ear-cutting rejects
    {
      this->AddTriangle(pts[0], pts[k], pts[k + 1], cellId, 0, EvaluateInCell);
    }
  }

  void ExtractPolyData(vtkPolyData* pd)
  {
    vtkNew<vtkPolygon> polygon;
    vtkNew<vtkIdList> tris;
    const bool indexable = this->PointsIndexable();
    vtkIdType cellId = 0;
    vtkCellArray* arrays[4] = { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() };
    this->ReserveTriangles(arrays[2], arrays[3]);
    for (int a = 0; a < 4; ++a)
    {
      vtkCellArray* ca = arrays[a];
      if (!ca || ca->GetNumberOfCells() == 0)
      {
        continue;
      }
      if (a == 2 && this->ExtractTrianglePolys(ca, cellId))
      {
        cellId += ca->GetNumberOfCells();
        continue;
      }
      auto it = vtk::TakeSmartPointer(ca->NewIterator());
      for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
      {
        vtkIdType npts;
        const vtkIdType* pts;
        it->GetCurrentCell(npts, pts);
        int type = -1;
        if (a == 2)
        {
          type = npts == 3 ? VTK_TRIANGLE : (npts == 4 ? VTK_QUAD : VTK_POLYGON);
        }
        else if (a == 3)
        {
          type = VTK_TRIANGLE_STRIP;
        }
        if (!(indexable && type >= 0 && this->AddSurfaceCell(type, npts, pts, cellId, polygon, tris)))
        {
          this->GenCell.push_back(cellId);
        }
      }
    }
  }

  /// Room for the triangles of polys (n-2 per polygon) and strips.
  void ReserveTriangles(vtkCellArray* polys, vtkCellArray* strips)
  {
    size_t tris = 0;
    for (vtkCellArray* ca : { polys, strips })
    {
      if (ca)
      {
        const vtkIdType conn = ca->GetNumberOfConnectivityIds();
        const vtkIdType cells = ca->GetNumberOfCells();
        tris += static_cast<size_t>(std::max<vtkIdType>(conn - 2 * cells, 0));
      }
    }
    this->TriVerts.reserve(3 * tris);
    this->TriCell.reserve(tris);
    this->TriSub.reserve(tris);
    this->TriFlags.reserve(tris);
  }

  void ExtractUnstructuredGrid(vtkUnstructuredGrid* ug)
  {
    vtkNew<vtkPolygon> polygon;
    vtkNew<vtkIdList> tris;
    const bool indexable = this->PointsIndexable();
    const vtkIdType n = ug->GetNumberOfCells();
    for (vtkIdType c = 0; c < n; ++c)
    {
      vtkIdType npts;
      const vtkIdType* pts;
      const int type = ug->GetCellType(c);
      ug->GetCellPoints(c, npts, pts);
      if (!(indexable && this->AddSurfaceCell(type, npts, pts, c, polygon, tris)))
      {
        this->GenCell.push_back(c);
      }
    }
  }

  void ComputeGeneralBoxes(vtkDataSet* ds)
  {
    this->GenBox.resize(this->GenCell.size());
    constexpr double eps = 4.0 * std::numeric_limits<double>::epsilon();
    vtkSMPTools::For(0, static_cast<vtkIdType>(this->GenCell.size()), [&](vtkIdType b, vtkIdType e) {
      double cb[6];
      for (vtkIdType i = b; i < e; ++i)
      {
        ds->GetCellBounds(this->GenCell[i], cb);
        Box box(Vec3d(cb[0], cb[2], cb[4]), Vec3d(cb[1], cb[3], cb[5]));
        if (!box.isFinite() || box.isEmpty())
        {
          this->GenBox[i] = Box();
          continue;
        }
        // Cells are tested in world coordinates and the ray is walked in
        // local ones: widen by the rounding of the shift.
        Vec3d lo = box.min - this->Origin, hi = box.max - this->Origin;
        const Vec3d slack = eps *
          (glm::abs(box.min) + glm::abs(box.max) + glm::abs(this->Origin) * 2.0);
        this->GenBox[i] = Box(lo - slack, hi + slack);
      }
    });
  }
};

} // namespace locator
} // namespace vtkrt

#endif
