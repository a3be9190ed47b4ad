/**
 * @class   vtkBVHCellLocator
 * @brief   cell locator over a bounding volume hierarchy, exact in double
 *
 * vtkBVHCellLocator is a vtkAbstractCellLocator backed by vtkrt's BVH core
 * (plugin/core/vtkrt/core): the same tree layout the GLSL ray tracer walks,
 * here walked in double precision. It can stand in wherever VTK takes a cell
 * locator: vtkCellPicker::AddLocator, filters that accept a locator, or user
 * code calling IntersectWithLine / FindClosestPoint / FindCell.
 *
 * Two paths share one tree:
 * - fast path (vtkPolyData triangles, quads, polygons and triangle strips):
 *   cells are triangulated once at build time, keeping the original cell id
 *   (and, for strips, the triangle index as subId); a polydata's
 *   triangulation is vtkSurfaceTriangulation's, kept with the polydata and
 *   shared with vtkRayTracePass drawing it; rays are tested with a
 *   watertight ray/triangle test, so a ray through a shared edge or vertex
 *   never slips between two triangles. No vtkCell and no virtual call is
 *   touched per candidate; the returned cell, pcoords and subId are those of
 *   the original VTK cell (pcoords of a quad or polygon hit come from the
 *   cell's own EvaluatePosition).
 * - general path (lines, vertices, and every cell of any other vtkDataSet,
 *   e.g. tetrahedra or hexahedra of a vtkUnstructuredGrid): the tree is built
 *   over cell bounds and each candidate is tested exactly by the cell's own
 *   IntersectWithLine / EvaluatePosition, so semantics are VTK's.
 *
 * Geometry is handled relative to a local origin (the dataset's bounds
 * center) so that meshes far from the world origin keep full precision.
 * Cells with non-finite coordinates are skipped. Double point coordinates
 * are read in place (no copy); others are copied to double at build.
 *
 * Tolerance: as in vtkCell::IntersectWithLine, tol is a world distance: a
 * triangle is hit when the line's crossing of its plane lies within tol of
 * it; lines and vertices are hit within tol.
 *
 * Build: BuildLocator() rebuilds when the dataset (or this locator) was
 * modified since the last build, unless UseExistingSearchStructure is on and
 * a tree exists. For vtkPolyData that means the polydata itself, its points
 * or its cell arrays: a modified attribute array (scalars, normals) moves no
 * cell and triggers no rebuild. With LazyEvaluation on, BuildLocator() only marks the
 * locator and the first query builds. Every query builds the tree when it is
 * missing or stale (vtkCellPicker never calls BuildLocator itself). With
 * UseExistingSearchStructure, as with VTK's locators, the tree is kept and
 * cells are tested where the dataset's double points are now: moved cells
 * outside their old boxes are missed (rebuild for exact answers). A points
 * array that was reallocated or shrunk since the build (even without a
 * Modified()) is never read: the query rebuilds, or with
 * UseExistingSearchStructure reports an error and finds nothing.
 * ForceBuildLocator() always rebuilds. The FAST build of a surface leaves
 * most of its picking tree to the queries that reach it
 * (PickingTreeOnDemand); every query walks that tree, so none builds more
 * than the parts it reaches.
 *
 * Thread safety: once built (and while the dataset is unmodified) all queries
 * may run concurrently from several threads: they only read shared state,
 * except the parts of the tree built on demand, each built once by the first
 * thread that needs it while the others wait. Each thread passes its own
 * vtkGenericCell (the overloads
 * taking `cell`), and its own output lists. Overloads without a `cell`
 * argument use an internal cell only when they need one (non-triangle cells),
 * so they should not be called concurrently on a general dataset.
 *
 * NumberOfCellsPerNode is the BVH leaf size (default 8 here: on 1M triangles
 * fewer, fuller leaves mean fewer cache misses per ray).
 *
 * @sa vtkAbstractCellLocator vtkStaticCellLocator vtkCellPicker
 */

#ifndef vtkBVHCellLocator_h
#define vtkBVHCellLocator_h

#include "vtkAbstractCellLocator.h"
#include "vtkVersionMacros.h"  // For VTK_VERSION_NUMBER
#include "vtkrtPluginModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkIdList;
class vtkPoints;

class VTKRTPLUGIN_EXPORT vtkBVHCellLocator : public vtkAbstractCellLocator
{
public:
  static vtkBVHCellLocator* New();
  vtkTypeMacro(vtkBVHCellLocator, vtkAbstractCellLocator);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  using vtkAbstractCellLocator::FindCell;
  using vtkAbstractCellLocator::FindClosestPoint;
  using vtkAbstractCellLocator::FindClosestPointWithinRadius;
  using vtkAbstractCellLocator::IntersectWithLine;

  /**
   * BVH builder quality, mapped to the core's builders: FAST (the default:
   * quickest build, lowest first-pick latency and memory, and in
   * vtkrtBenchLocator picking as fast as the others or faster), SAH (binned
   * surface area heuristic) or HIGH (full-sweep SAH, slowest build).
   */
  enum BuildQualityType
  {
    FAST = 0,
    SAH = 1,
    HIGH = 2
  };
  vtkSetClampMacro(BuildQuality, int, FAST, HIGH);
  vtkGetMacro(BuildQuality, int);
  void SetBuildQualityToFast() { this->SetBuildQuality(FAST); }
  void SetBuildQualityToSAH() { this->SetBuildQuality(SAH); }
  void SetBuildQualityToHigh() { this->SetBuildQuality(HIGH); }

  ///@{
  /**
   * FAST build of a polygonal surface (all cells triangulated): build each
   * part of the picking tree (the subtree over one cell of a coarse grid)
   * when a query first reaches it. On (the default),
   * BuildLocator() returns once the levels above those parts are built, so
   * that a first pick waits for little more than reading the mesh; the
   * parts a query reaches are built then, once, and safely from several
   * threads. Off: BuildLocator() builds the whole tree, and every query
   * takes its steady time from the first one. The same tree either way.
   * GenerateRepresentation() and the tree statistics first complete the
   * tree (and build a binary one over it).
   */
  vtkSetMacro(PickingTreeOnDemand, bool);
  vtkGetMacro(PickingTreeOnDemand, bool);
  vtkBooleanMacro(PickingTreeOnDemand, bool);
  ///@}

  ///@{
  /**
   * Build the tree if it is missing or stale (see class documentation);
   * ForceBuildLocator() always rebuilds. FreeSearchStructure() releases it.
   */
  void BuildLocator() override;
  virtual void ForceBuildLocator();
  void FreeSearchStructure() override;
  ///@}

  /**
   * Polydata of the BVH boxes (quads, 6 per box) of the nodes at depth
   * `level` (0 is the root), plus the leaves above that depth; a negative
   * level gives all leaves.
   */
  void GenerateRepresentation(int level, vtkPolyData* pd) override;

  /**
   * Nearest intersection of the segment p1->p2 with the cells, within tol.
   * t is the segment parameter in [0, 1], x the world point, pcoords/subId
   * the parametric coordinates in cell `cellId`. If `cell` is given it holds
   * cell `cellId` on return (vtkCellPicker relies on that).
   */
  int IntersectWithLine(const double p1[3], const double p2[3], double tol, double& t, double x[3],
    double pcoords[3], int& subId, vtkIdType& cellId, vtkGenericCell* cell) override;
  int IntersectWithLine(const double p1[3], const double p2[3], double tol, double& t, double x[3],
    double pcoords[3], int& subId, vtkIdType& cellId) override;
  int IntersectWithLine(const double p1[3], const double p2[3], double tol, double& t, double x[3],
    double pcoords[3], int& subId) override;

  /**
   * Every intersection of the segment with the cells (tolerance 0 for the
   * 4-argument form), one per cell (its nearest), sorted along the segment:
   * a crossing through an edge or vertex shared by n cells is listed n
   * times, as VTK's cell locators list it (vtkOBBTree lists it once);
   * merge hits at the same point before counting crossings for parity.
   * Either list may be null. Returns 0 when nothing is hit; otherwise -1 if
   * p1 is inside a closed, outward-oriented surface (the first crossing
   * leaves it) and +1 otherwise, as vtkOBBTree does.
   */
  int IntersectWithLine(
    const double p1[3], const double p2[3], vtkPoints* points, vtkIdList* cellIds) override;
  virtual int IntersectWithLine(const double p1[3], const double p2[3], double tol,
    vtkPoints* points, vtkIdList* cellIds, vtkGenericCell* cell = nullptr);

  /**
   * Ids of the cells whose bounds (grown by tolerance) meet the segment, in
   * increasing id order: every cell the segment may hit, and exactly those
   * whose bounds it meets (VTK's locators list the cells of the buckets
   * the segment passes, a superset).
   */
  void FindCellsAlongLine(
    const double p1[3], const double p2[3], double tolerance, vtkIdList* cells) override;

  /**
   * Ids of the cells whose bounds meet bbox (xmin,xmax,ymin,ymax,zmin,
   * zmax), in increasing id order, as vtkCellTreeLocator answers
   * (vtkStaticCellLocator and vtkCellLocator list the cells of the buckets
   * the box overlaps, a superset).
   */
  void FindCellsWithinBounds(double* bbox, vtkIdList* cells) override;

  ///@{
  /**
   * Closest point on any cell to x (within radius for the WithinRadius
   * forms, which return 1 when found and 0 otherwise, with cellId -1).
   * `inside` is the closest cell's EvaluatePosition result at x.
   */
  void FindClosestPoint(const double x[3], double closestPoint[3], vtkGenericCell* cell,
    vtkIdType& cellId, int& subId, double& dist2) override;
  void FindClosestPoint(
    const double x[3], double closestPoint[3], vtkIdType& cellId, int& subId, double& dist2) override;
  vtkIdType FindClosestPointWithinRadius(double x[3], double radius, double closestPoint[3],
    vtkGenericCell* cell, vtkIdType& cellId, int& subId, double& dist2, int& inside) override;
  vtkIdType FindClosestPointWithinRadius(double x[3], double radius, double closestPoint[3],
    vtkGenericCell* cell, vtkIdType& cellId, int& subId, double& dist2) override;
  vtkIdType FindClosestPointWithinRadius(double x[3], double radius, double closestPoint[3],
    vtkIdType& cellId, int& subId, double& dist2) override;
  ///@}

  ///@{
  /**
   * Point location, as VTK 9.1's locators answer it: the lowest id of a
   * cell whose bounds hold x and whose EvaluatePosition says inside, or -1.
   * tol2 is not used (nor by vtkStaticCellLocator or vtkCellLocator); a
   * surface cell holds every point of its bounds that projects into it.
   */
  vtkIdType FindCell(double x[3]) override;
  vtkIdType FindCell(
    double x[3], double tol2, vtkGenericCell* cell, double pcoords[3], double* weights) override;
  ///@}

  /**
   * Whether x lies inside the bounds of cell cellId (false for a bad id).
   */
  bool InsideCellBounds(double x[3], vtkIdType cellId) override;

  ///@{
  /**
   * Tree statistics of the last build.
   */
  vtkIdType GetNumberOfNodes() const;
  vtkIdType GetNumberOfPrimitives() const;
  int GetTreeDepth() const;
  double GetSAHCost() const;
  double GetBuildTimeSeconds() const;
  /** Bytes held by the search structure (tree, primitives, geometry copy). */
  size_t GetMemorySize() const;
  ///@}

protected:
  vtkBVHCellLocator();
  ~vtkBVHCellLocator() override;

  // True when the tree is missing or older than the dataset / this object.
  bool NeedsBuild() const;
  // The dataset's MTime as far as the tree depends on it: for the polydata
  // it was built over, its own, its points' and its cells' (not its
  // attributes'); for other datasets GetMTime().
  vtkMTimeType GeometryMTime() const;
  // Builds when needed; returns false (after an error where VTK gives one)
  // when there is nothing to query.
  bool PrepareQuery();
  // A dataset with cells; otherwise the error BuildLocator gives, and false.
  bool HasCellsToBuild();
  void BuildTree();

  int BuildQuality;
  bool PickingTreeOnDemand = true;

#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 0)
  // VTK 9.2 (ParaView 5.11) dropped vtkAbstractCellLocator's LazyEvaluation
  // (its setters are no-ops there): this locator keeps its own.
public:
  void SetLazyEvaluation(vtkTypeBool lazy) override
  {
    if (this->LazyEvaluation != lazy)
    {
      this->LazyEvaluation = lazy;
      this->Modified();
    }
  }
  vtkTypeBool GetLazyEvaluation() override { return this->LazyEvaluation; }
  void LazyEvaluationOn() override { this->SetLazyEvaluation(1); }
  void LazyEvaluationOff() override { this->SetLazyEvaluation(0); }

protected:
  vtkTypeBool LazyEvaluation = 0;
#endif

private:
  vtkBVHCellLocator(const vtkBVHCellLocator&) = delete;
  void operator=(const vtkBVHCellLocator&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
