// Private to vtkBVHCellLocator: what the locator keeps of its dataset and
// the trees over it (plugin/core/vtkrt/core). Not installed. The work is in
// units by concern: vtkBVHCellLocatorExtraction.cxx (dataset -> primitives),
// vtkBVHCellLocatorBuild.cxx (the trees), vtkBVHCellLocatorQueries.cxx (the
// queries over the core's walks, answered in VTK's terms).
//
// Primitives are of two kinds sharing one tree:
// - triangles (fast path): polydata / unstructured-grid triangles, quads,
//   polygons (fans, as drawn) and triangle strips, stored as point-index triples
//   into the dataset's double points (or a double copy of them) and tested
//   without any vtkCell;
// - general cells: every other cell, tested by its own vtkCell methods.
#ifndef vtkBVHCellLocatorInternals_h
#define vtkBVHCellLocatorInternals_h

#include "vtkDataArray.h"
#include "vtkGenericCell.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"
#include "vtkSurfaceTriangulation.h"
#include "vtkType.h"

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h" // Hit
#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/WideBVH.h"
#include "vtkrt/core/WideNode.h"
#include "vtkrt/core/simd/Dispatch.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

class vtkCellArray;
class vtkDataSet;
class vtkIdList;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace vtkrt
{
namespace locator
{
using Vec3d = core::Vec3<double>;
using Box = core::AABB<double>;

/// A per-triangle array that picks read at random: no zero fill (a first
/// pick should not wait for a memset of it), huge pages when large.
template <class T>
using TriangleArray = core::HugePageArray<T>;
/// A per-triangle array of the build, written and read in order.
template <class T>
using ExtractionArray = core::NoFillArray<T>;

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
  const std::uint32_t* TrianglePointIds = nullptr; ///< set when the cell is that VTK_TRIANGLE
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

/// A vtkGenericCell for one query: the caller's when given, else a local one
/// created only when needed (non-triangle cells).
class QueryCell
{
public:
  explicit QueryCell(vtkGenericCell* given)
    : Given(given)
  {
  }
  ~QueryCell()
  {
    if (this->Own)
    {
      this->Own->Delete();
    }
  }
  QueryCell(const QueryCell&) = delete;
  QueryCell& operator=(const QueryCell&) = delete;
  vtkGenericCell* Get()
  {
    if (this->Given)
    {
      return this->Given;
    }
    if (!this->Own)
    {
      this->Own = vtkGenericCell::New();
    }
    return this->Own;
  }

private:
  vtkGenericCell* Given;
  vtkGenericCell* Own = nullptr;
};

class BVHCellLocatorData
{
public:
  /// Local coordinates are (world - Origin) * Scale, with Origin the center
  /// of the finite points' bounds and Scale the power of two that brings
  /// their half-size into [0.5, 1): the exact tests' products then stay in
  /// double's range at any scale a double holds, and a power-of-two scale
  /// rounds nothing, so every answer is the one an unscaled mesh gives.
  /// Scaling down multiplies before the shift (world - Origin could
  /// overflow), scaling up after it (world * Scale could):
  /// local = (world * PreScale - ScaledOrigin) * PostScale.
  Vec3d Origin = Vec3d(0.0);
  double Scale = 1.0;
  double PreScale = 1.0;
  double PostScale = 1.0;
  Vec3d ScaledOrigin = Vec3d(0.0); ///< Origin * PreScale
  Box PointBounds; ///< the finite points' bounds, local (fast path only)
  /// World coordinates of the points when the dataset's are not double
  /// (double ones are read in place, DataSetCoords): fast path only.
  std::vector<Vec3d> PointsCopy;
  vtkIdType NumberOfPoints = 0;
  ExtractionArray<std::uint32_t> TriVerts;   ///< 3 point ids per triangle, extraction order, when extracted here
  /// 3 point ids per triangle, extraction order (until placed): TriVerts, or
  /// those of the polydata's shared triangulation (SharedTriangulation).
  const std::uint32_t* SrcVerts = nullptr;
  /// The polydata's triangulation (vtkSurfaceTriangulation), shared with
  /// whoever draws it, when the triangles come from there (until placed).
  vtkSmartPointer<vtkSurfaceTriangulation> SharedTriangulation;
  TriangleArray<vtkIdType> SrcCell;        ///< TriCell, TriSub, TriFlags in extraction order (until placed)
  TriangleArray<std::int32_t> SrcSub;
  TriangleArray<std::uint8_t> SrcFlags;
  /// 3 point ids per triangle, leaf order: the exact test reads the double
  /// vertices through them from WorldCoords().
  TriangleArray<std::uint32_t> TriIds;
  /// Each leaf slot's triangle as 9 floats (vertex 0, 1, 2; x y z; the local
  /// point rounded to nearest), and one float of padding at the end (a
  /// vertex is read as four floats): what the float pre-test reads, which
  /// spares the double test nearly every miss. Stored per slot, not read
  /// through TriIds from a float copy of the points: a leaf's loads then
  /// wait for no other load, and a leaf is a few adjacent cache lines.
  TriangleArray<float> TrianglesF;
  double Extent = 0.0; ///< bound on |local vertex| (inf norm), for the float error bound
  /// >= 0: every triangle t is the VTK_TRIANGLE cell UniformCellBase + t
  /// (extraction order), subId 0 (set by the all-triangle polys path).
  vtkIdType UniformCellBase = -1;
  /// The dataset's double coordinates at build time, read in place (the
  /// exact tests compute the local point, the same doubles a local copy would
  /// hold, and the hit's cell fill then finds them in cache); null when not
  /// double. DataSetCoordsArray keeps them alive; CoordsUnchanged() tells
  /// whether the array still has them there.
  const double* DataSetCoords = nullptr;
  vtkSmartPointer<vtkDataArray> DataSetCoordsArray;
  /// The non-double points copied to PointsCopy, their array and where it
  /// held them, and the points' MTime at the copy: with
  /// UseExistingSearchStructure the copy follows moved points
  /// (RefreshPointsCopy). Copying copies the time, not the atomic.
  vtkSmartPointer<vtkPoints> CopiedPoints;
  vtkSmartPointer<vtkDataArray> CopiedCoordsArray;
  const void* CopiedCoordsPointer = nullptr;
  struct CopyTime
  {
    std::atomic<vtkMTimeType> Value{ 0 };
    CopyTime() = default;
    CopyTime(const CopyTime& o)
      : Value(o.Value.load())
    {
    }
    CopyTime& operator=(const CopyTime& o)
    {
      this->Value.store(o.Value.load());
      return *this;
    }
  };
  CopyTime CopiedCoordsTime;
  /// Cells made of several triangles (quads, polygons, strips), in id
  /// order. Their bounds can hold a point or meet a box or segment that no
  /// box of their triangles meets, so FindCell and the bounds queries also
  /// search MultiCells, a tree over these cells' own bounds.
  std::vector<vtkIdType> MultiTriangleCells;
  /// Whether every cell is one of those (a quad mesh: no VTK_TRIANGLE and
  /// no other cell): the queries by cell bounds then need only MultiCells.
  bool OnlyMultiTriangleCells = false;
  /// The tree over MultiTriangleCells' bounds (local coordinates), built by
  /// the first query that needs it (EnsureMultiCells). Copying copies
  /// nothing: a copy builds its own on demand.
  struct MultiCellTree
  {
    std::atomic<bool> Ready{ false };
    std::mutex Mutex;
    /// The cells' bounds and ids in the tree's leaf order (its primIndex is
    /// then the identity), so a leaf reads them in one run.
    std::vector<Box> Boxes;
    std::vector<vtkIdType> Cells;
    core::BVH Tree;
    /// Tree's nodes in float, rounded outward (core::packGpuNodes): what
    /// point and box queries walk (segments walk Tree).
    std::vector<core::gpu::Node> Nodes;
    MultiCellTree() = default;
    MultiCellTree(const MultiCellTree&) {}
    MultiCellTree& operator=(const MultiCellTree&)
    {
      this->Ready.store(false);
      this->Boxes.clear();
      this->Cells.clear();
      this->Tree = core::BVH();
      this->Nodes.clear();
      return *this;
    }
  };
  mutable MultiCellTree MultiCells;
  size_t MultiCellBytes() const
  {
    if (!this->MultiCells.Ready.load(std::memory_order_acquire))
    {
      return 0;
    }
    return this->MultiCells.Boxes.capacity() * sizeof(Box) +
      this->MultiCells.Cells.capacity() * sizeof(vtkIdType) + this->MultiCells.Tree.memoryBytes() +
      this->MultiCells.Nodes.capacity() * sizeof(core::gpu::Node);
  }
  /// Original cell id per triangle (in extraction order, sized but not
  /// written when UniformCellBase gives the ids).
  TriangleArray<vtkIdType> TriCell;
  /// subId and TriangleFlags per triangle (strips: subId is the triangle's
  /// index), in leaf order empty when UniformCellBase >= 0.
  TriangleArray<std::int32_t> TriSub;
  TriangleArray<std::uint8_t> TriFlags;
  std::vector<vtkIdType> GenCell;        ///< original cell id per general primitive
  std::vector<Box> GenBox;               ///< its bounds, local, slightly widened
  /// The binary tree: what the queries walk where float cannot be trusted
  /// (a flush-to-zero FPU mode), and what GenerateRepresentation and the
  /// statistics read. The fast build leaves it to the first of those:
  /// EnsureTree().
  mutable core::BVH Tree;
  /// The picking tree, eight children a node (core/WideNode.h). The fast
  /// build writes it directly over triangles (Lazy); the others re-lay the
  /// core's binary nodes (core/WideCollapse.h: no new split decisions).
  static constexpr int kWideArity = core::kWideArity;
  using WideNode = core::WideNode;
  std::vector<WideNode> Wide;
  mutable TreeStats Stats;
  vtkIdType SkippedCells = 0;   ///< cells in no leaf (non-finite or empty bounds)
  vtkIdType NonFiniteCells = 0; ///< surface cells dropped at extraction
  /// Cells naming a point id outside [0, NumberOfPoints): dropped at
  /// extraction, never handed to VTK (whose cell access would read past the
  /// points).
  vtkIdType InvalidPointIdCells = 0;
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
    if (!this->TreeBuilt.Ready.load(std::memory_order_acquire))
    {
      this->BuildDeferredTree();
    }
  }

  size_t MemorySize() const;

  // Extraction (vtkBVHCellLocatorExtraction.cxx)
  void Extract(vtkDataSet* ds);

  // Builds (vtkBVHCellLocatorBuild.cxx)
  void Build(int quality, int leafSize);
  void SetTreeStats() const;
  /// Every triangle placed: the extraction-order arrays can go.
  void DropExtractionArrays();

  /// The triangles as LazyWideBVH sees them (by extraction index).
  struct PickingTriangles
  {
    BVHCellLocatorData* Data;
    Box bounds(std::uint32_t id) const
    {
      return this->Data->TriangleBox(this->Data->SrcVerts + 3 * static_cast<size_t>(id));
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

  /// Triangle p (extraction order) goes to leaf slot t; returns its box.
  /// Slots are written from several threads at once, each slot by one.
  Box PlaceTriangle(std::uint32_t p, std::uint32_t t)
  {
    const std::uint32_t* v = this->SrcVerts + 3 * static_cast<size_t>(p);
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
    const std::uint32_t* v = this->SrcVerts + 3 * static_cast<size_t>(p);
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

  // Queries (vtkBVHCellLocatorQueries.cxx), each in local coordinates
  // inside and world coordinates at its ends. `cell`: the caller's
  // vtkGenericCell (may be null), also the query's scratch for general
  // cells.

  /// vtkAbstractCellLocator::IntersectWithLine's nearest hit: pcoords and
  /// subId as the hit cell reports them, `cell` (when given) that cell.
  bool IntersectWithLine(const double p1[3], const double p2[3], double tol, vtkDataSet* ds,
    vtkGenericCell* cell, LineHit& out) const;
  /// Every cell the segment hits, its nearest hit each, along the segment.
  void AllHits(const double p1[3], const double p2[3], double tol, vtkDataSet* ds,
    vtkGenericCell* cell, std::vector<LineHit>& hits) const;
  /// The cells whose bounds, grown by tol, the segment meets (sorted ids).
  void CellsAlongLine(const double p1[3], const double p2[3], double tol, vtkDataSet* ds,
    std::vector<vtkIdType>& cells) const;
  /// The cells whose bounds overlap bbox (sorted ids).
  void CellsInBox(const double bbox[6], vtkDataSet* ds, std::vector<vtkIdType>& cells) const;
  /// The cells with a triangle or general cell whose box overlaps q (local
  /// coordinates; sorted ids): every cell that meets q, but not every cell
  /// of several triangles whose bounds do.
  void CellsInLocalBox(const Box& q, std::vector<vtkIdType>& cells) const;
  /// The cells a zero-length segment at p hits (VTK's cells decide), t = 0.
  void CellsThroughPoint(const double p[3], double tol, vtkDataSet* ds, vtkGenericCell* cell,
    bool firstOnly, std::vector<LineHit>& hits) const;
  /// The closest point of any cell within radius of xw: subId and inside as
  /// the cell reports them, `cell` (when given) that cell.
  bool FindClosestPoint(
    const double xw[3], double radius, vtkDataSet* ds, vtkGenericCell* cell, PointHit& out) const;
  /// As VTK 9.1's locators: the lowest-id cell whose bounds hold xw and
  /// whose EvaluatePosition says inside (a surface cell: xw projects into
  /// it); no tolerance. weights: the caller's, or null (sized per candidate
  /// cell here).
  vtkIdType FindCell(
    const double xw[3], vtkDataSet* ds, vtkGenericCell* cell, double pcoords[3], double* weights) const;

  /// Boxes (local coordinates) of the nodes at depth `level` and of the
  /// leaves above it; all leaves for a negative level.
  void BoxesAtLevel(int level, std::vector<Box>& boxes) const;

  /// x y z of each point, world coordinates.
  const double* WorldCoords() const
  {
    static_assert(sizeof(Vec3d) == 3 * sizeof(double), "x y z, packed");
    return this->DataSetCoords ? this->DataSetCoords : reinterpret_cast<const double*>(this->PointsCopy.data());
  }
  /// Point id in local coordinates (rounded once, as a stored local copy would be).
  Vec3d LocalPoint(vtkIdType id) const
  {
    return this->ToLocal(this->WorldCoords() + 3 * static_cast<std::size_t>(id));
  }
  /// World to local coordinates and back (see Scale).
  Vec3d ToLocal(const double p[3]) const
  {
    const Vec3d& o = this->ScaledOrigin;
    const double pre = this->PreScale, post = this->PostScale;
    return Vec3d((p[0] * pre - o.x) * post, (p[1] * pre - o.y) * post, (p[2] * pre - o.z) * post);
  }
  Vec3d ToLocal(const Vec3d& p) const
  {
    const double c[3] = { p.x, p.y, p.z };
    return this->ToLocal(c);
  }
  Vec3d ToWorld(const Vec3d& local) const
  {
    return (local / this->PostScale + this->ScaledOrigin) / this->PreScale;
  }
  /// A world length (tolerance, radius) in local units, and back.
  double ToLocalLength(double world) const { return world * this->Scale; }
  double ToWorldLength(double local) const { return local / this->Scale; }
  /// The local frame of a mesh whose finite points have these (world) bounds.
  void SetLocalFrame(const Box& worldBounds);
  /// False when the dataset's double coordinates array no longer holds the
  /// build's points where they were (reallocated or shrunk, perhaps without
  /// a Modified()): the tree must not read them.
  bool CoordsUnchanged() const
  {
    return !this->DataSetCoordsArray ||
      (this->DataSetCoordsArray->GetVoidPointer(0) == this->DataSetCoords &&
        this->DataSetCoordsArray->GetNumberOfTuples() >= this->NumberOfPoints);
  }

  /// Whether `ds` now holds another coordinates array than the build read
  /// (SetPoints of other points, or another array in its vtkPoints): the
  /// trees are not over them.
  bool PointsReplaced(vtkDataSet* ds) const;
  /// Whether the copied (non-double) points were modified, reallocated or
  /// shrunk since the copy.
  bool PointsCopyStale() const;
  /// Re-reads moved points into PointsCopy, the trees kept (tests then see
  /// the points where they are, as VTK's locators do with
  /// UseExistingSearchStructure); false, reading nothing, when the points
  /// array was replaced, reallocated or shrunk.
  bool RefreshPointsCopy();

private:
  /// Local double vertex k of (leaf-ordered) triangle prim.
  Vec3d Vertex(std::uint32_t prim, int k) const
  {
    return this->LocalPoint(this->TriIds[3 * static_cast<std::size_t>(prim) + k]);
  }

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

  /// Sets MultiTriangleCells from the extraction's triangles (a cell's are
  /// consecutive there).
  void ListMultiTriangleCells();

  // The cells of several triangles by their own bounds
  // (vtkBVHCellLocatorCellBounds.cxx); ds is the dataset built from.
  /// Builds MultiCells if a query has not yet; safe from several threads.
  void EnsureMultiCells(vtkDataSet* ds) const;
  /// Appends the cells of several triangles whose bounds overlap q (local).
  void MultiCellsInLocalBox(vtkDataSet* ds, const Box& q, std::vector<vtkIdType>& cells) const;
  /// Appends those whose bounds, grown by localTol, the segment `ray` meets.
  void MultiCellsAlongSegment(vtkDataSet* ds, const core::Ray<double>& ray, double localTol,
    std::vector<vtkIdType>& cells) const;
  /// The box (local) of the cell's finite points; `points` is scratch.
  Box CellBox(vtkDataSet* ds, vtkIdType cellId, vtkIdList* points) const;
  /// Whether triangle prim is part of a cell of several triangles (one of
  /// MultiTriangleCells: MultiCells finds it by its bounds).
  bool InMultiTriangleCell(std::uint32_t prim) const;

  // Builds
  void BuildDeferredTree() const;
  void BuildPickingTree(size_t nTri);
  void MakeLeafOrderArrays(size_t nTri);
  void Reorder(size_t nTri);

  // Queries (vtkBVHCellLocatorQueries.cxx; the inline ones are defined and
  // used only there, inlined into the queries).
  struct PickingScene;
  bool ClosestPoint(
    const double xw[3], double radius, vtkDataSet* ds, QueryCell& cell, PointHit& out) const;
  inline void SetTriangleHit(
    const core::Hit<double>& hit, const double p1[3], const core::Ray<double>& ray, LineHit& out) const;
  inline bool MakeSegment(const double p1[3], const double p2[3], core::Ray<double>& ray) const;
  inline bool IntersectTriangle(std::uint32_t prim, const core::RayTrianglePrecomputed<double>& pre,
    const core::Ray<double>& ray, double tol, double& t, double& u, double& v) const;
  inline bool ProjectsInside(std::uint32_t prim, const Vec3d& x) const;
  inline bool MayLieInPlane(std::uint32_t prim, const core::Ray<double>& ray) const;

  // Extraction
  void ComputeOrigin(vtkDataSet* ds);
  void BindPoints(vtkPoints* pts, const vtkSurfaceTriangulation* shared = nullptr);
  /// PointsCopy from pts (sized already), and what PointsCopyStale compares.
  void CopyPoints(vtkPoints* pts);
  /// Whether every point id fits the 32-bit ids of the triangle arrays.
  bool PointsIndexable() const
  {
    return static_cast<std::uint64_t>(this->NumberOfPoints) < std::numeric_limits<std::uint32_t>::max();
  }
  bool ExtractTrianglePolys(vtkCellArray* polys, vtkIdType cellBase);
  bool ShareTriangles(vtkPolyData* pd);
  void AdoptSharedTriangles();
  template <class IdT>
  bool ExtractTriangles(const IdT* offsets, const IdT* conn, vtkIdType n, vtkIdType cellBase);
  void AddTriangle(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cellId, int sub, std::uint8_t flags);
  bool AddSurfaceCell(int type, vtkIdType npts, const vtkIdType* pts, vtkIdType cellId);
  void AddQuad(const vtkIdType* pts, vtkIdType cellId);
  void AddPolygon(vtkIdType npts, const vtkIdType* pts, vtkIdType cellId);
  void ExtractPolyData(vtkPolyData* pd, bool shared);
  void ReserveTriangles(vtkCellArray* polys, vtkCellArray* strips);
  void ExtractUnstructuredGrid(vtkUnstructuredGrid* ug);
  void WarmUpCellAccess(vtkDataSet* ds);
  void ComputeGeneralBoxes(vtkDataSet* ds);
};

} // namespace locator
} // namespace vtkrt

#endif
