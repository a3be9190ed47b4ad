#include "vtkBVHCellLocator.h"

#include "vtkCell.h"
#include "vtkCellArray.h"
#include "vtkDataSet.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "vtkBVHCellLocatorInternals.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

vtkStandardNewMacro(vtkBVHCellLocator);

using vtkrt::locator::Vec3d;
using vtkrt::locator::BVHCellLocatorData;

struct vtkBVHCellLocator::vtkInternals
{
  BVHCellLocatorData Data;
  // The BuildTime of the tree queries may read, 0 when there is none:
  // stored (release) once the tree is complete, so a query that loads it
  // (acquire) sees the whole tree without taking BuildMutex.
  std::atomic<vtkMTimeType> TreeTime{ 0 };
  std::mutex BuildMutex;
  // The polydata the tree was built over (when the dataset is one): its
  // staleness is judged by GeometryMTime(). Atomic: queries read it while
  // the first of them to see a stale tree rebuilds.
  std::atomic<vtkPolyData*> BuiltPolyData{ nullptr };

  bool HasTree() const { return this->TreeTime.load(std::memory_order_acquire) != 0; }
  // Scratch cell for the overloads that take none; never used concurrently
  // by the thread-safe forms.
  vtkNew<vtkGenericCell> ScratchCell;
};

namespace
{
inline bool IsFinite3(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// Whether finite query points lie beyond what the local frame holds (over
/// ~1e300 mesh sizes from the mesh): such a query cannot be answered. Asked
/// only once a query found nothing.
bool BeyondLocalFrame(const vtkrt::locator::BVHCellLocatorData& d, const double* p1,
  const double* p2 = nullptr)
{
  for (const double* p : { p1, p2 })
  {
    if (p && IsFinite3(p) && !vtkrt::core::isFinite(d.ToLocal(p)))
    {
      return true;
    }
  }
  return false;
}

constexpr const char* kBeyondLocalFrame = "a query point lies over ~1e300 times the mesh's "
                                          "size from it, beyond double's range in the mesh's "
                                          "frame: no answer";
} // namespace

//------------------------------------------------------------------------------
vtkBVHCellLocator::vtkBVHCellLocator()
  : BuildQuality(FAST)
  , Internals(new vtkInternals)
{
  // Small leaves suit a BVH (VTK's default of 32 suits bucket locators).
  this->NumberOfCellsPerNode = 8;
  this->CacheCellBounds = 0;
}

//------------------------------------------------------------------------------
vtkBVHCellLocator::~vtkBVHCellLocator()
{
  this->FreeSearchStructure();
}

namespace
{
/// Whether a cell of `pd` has fewer points than its kind needs (a vertex 1,
/// a line 2, a polygon or strip 3): vtkPolyData cannot build its cell map
/// past one, and its GetCell then dereferences the map it lacks.
bool HasCellsVTKCannotRepresent(vtkPolyData* pd)
{
  vtkCellArray* arrays[4] = { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() };
  const vtkIdType least[4] = { 1, 2, 3, 3 };
  auto shortCell = [](const auto* offsets, vtkIdType n, vtkIdType least) {
    for (vtkIdType c = 0; c < n; ++c)
    {
      if (offsets[c + 1] - offsets[c] < least)
      {
        return true;
      }
    }
    return false;
  };
  for (int k = 0; k < 4; ++k)
  {
    const vtkIdType n = arrays[k] ? arrays[k]->GetNumberOfCells() : 0;
    if (n > 0 &&
      (arrays[k]->IsStorage64Bit() ? shortCell(arrays[k]->GetOffsetsArray64()->GetPointer(0), n, least[k])
                                   : shortCell(arrays[k]->GetOffsetsArray32()->GetPointer(0), n, least[k])))
    {
      return true;
    }
  }
  return false;
}
} // namespace

//------------------------------------------------------------------------------
bool vtkBVHCellLocator::NeedsBuild() const
{
  const vtkMTimeType built = this->Internals->TreeTime.load(std::memory_order_acquire);
  if (built == 0)
  {
    return true;
  }
  if (this->UseExistingSearchStructure)
  {
    return false;
  }
  return this->MTime.GetMTime() > built || (this->DataSet && this->GeometryMTime() > built);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkBVHCellLocator::GeometryMTime() const
{
  vtkPolyData* pd = this->Internals->BuiltPolyData.load(std::memory_order_relaxed);
  if (pd != this->DataSet)
  {
    return this->DataSet->GetMTime();
  }
  // Attributes move no cell, and visiting every attribute array was a fifth
  // of a pick's fixed cost.
  return vtkSurfaceTriangulation::GetGeometryMTime(pd);
}

//------------------------------------------------------------------------------
bool vtkBVHCellLocator::HasCellsToBuild()
{
  if (!this->DataSet)
  {
    vtkErrorMacro(<< "No dataset to build a locator for");
    return false;
  }
  if (this->DataSet->GetNumberOfCells() < 1)
  {
    vtkErrorMacro(<< "No cells to build");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::BuildLocator()
{
  if (this->LazyEvaluation)
  {
    // Built by the first query.
    return;
  }
  if (!this->HasCellsToBuild())
  {
    return;
  }
  std::lock_guard<std::mutex> lock(this->Internals->BuildMutex);
  if (this->NeedsBuild())
  {
    this->BuildTree();
  }
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::ForceBuildLocator()
{
  if (!this->HasCellsToBuild())
  {
    return;
  }
  std::lock_guard<std::mutex> lock(this->Internals->BuildMutex);
  this->BuildTree();
}

//------------------------------------------------------------------------------
bool vtkBVHCellLocator::PrepareQuery()
{
  if (!this->DataSet && !(this->Internals->HasTree() && this->UseExistingSearchStructure))
  {
    vtkErrorMacro(<< "No dataset: set one with SetDataSet() before querying");
    return false;
  }
  if (this->DataSet && this->NeedsBuild())
  {
    std::lock_guard<std::mutex> lock(this->Internals->BuildMutex);
    if (this->NeedsBuild())
    {
      this->BuildTree();
    }
  }
  if (!this->Internals->Data.CoordsUnchanged())
  {
    // The points array was reallocated or shrunk under the tree (perhaps
    // without a Modified()): its old coordinates are gone.
    if (this->UseExistingSearchStructure)
    {
      vtkErrorMacro(<< "The dataset's points were reallocated since the locator was built; "
                       "rebuild it (ForceBuildLocator) or turn UseExistingSearchStructure off");
      return false;
    }
    std::lock_guard<std::mutex> lock(this->Internals->BuildMutex);
    if (this->DataSet && !this->Internals->Data.CoordsUnchanged())
    {
      this->BuildTree();
    }
  }
  if (this->UseExistingSearchStructure && this->DataSet && this->Internals->Data.PointsReplaced(this->DataSet))
  {
    // The kept trees are over the old points, which the dataset no longer holds.
    vtkErrorMacro(<< "The dataset's points were replaced since the locator was built; rebuild it "
                     "(ForceBuildLocator) or turn UseExistingSearchStructure off");
    return false;
  }
  if (this->UseExistingSearchStructure && this->Internals->Data.PointsCopyStale())
  {
    // Float (non-double) points are read from the build's copy: re-read
    // them where they are now, or refuse when the array no longer matches.
    std::lock_guard<std::mutex> lock(this->Internals->BuildMutex);
    if (this->Internals->Data.PointsCopyStale() && !this->Internals->Data.RefreshPointsCopy())
    {
      vtkErrorMacro(<< "The dataset's points were replaced, reallocated or shrunk since the "
                       "locator was built; rebuild it (ForceBuildLocator) or turn "
                       "UseExistingSearchStructure off");
      return false;
    }
  }
  return this->Internals->HasTree() && this->Internals->Data.NumberOfPrimitives() > 0;
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::BuildTree()
{
  this->Internals->TreeTime.store(0);
  this->FreeCellBounds();
  this->Internals->Data.Clear();
  this->Internals->BuiltPolyData.store(vtkPolyData::SafeDownCast(this->DataSet), std::memory_order_relaxed);
  if (!this->DataSet || this->DataSet->GetNumberOfCells() < 1)
  {
    this->BuildTime.Modified();
    if (this->DataSet)
    {
      this->Internals->TreeTime.store(this->BuildTime.GetMTime(), std::memory_order_release);
    }
    return;
  }
  const auto start = std::chrono::steady_clock::now();

  // Random-access cell structures must exist before threads call GetCell
  // (it builds them lazily, which is not thread-safe; Extract warms the
  // rest up on a cell it keeps).
  if (auto* pd = vtkPolyData::SafeDownCast(this->DataSet))
  {
    if (HasCellsVTKCannotRepresent(pd))
    {
      // VTK's GetCell would dereference the cell map it could not build.
      vtkErrorMacro("BuildLocator: the polydata has a cell VTK cannot represent (a polygon or "
                    "strip of fewer than 3 points, a line of fewer than 2, an empty vertex), so "
                    "no cell of it can be read: nothing is located until the data is fixed");
      this->BuildTime.Modified();
      this->Internals->TreeTime.store(this->BuildTime.GetMTime(), std::memory_order_release);
      return;
    }
    if (pd->NeedToBuildCells())
    {
      pd->BuildCells();
    }
  }
  this->Internals->Data.Extract(this->DataSet);
  const vtkIdType invalid = this->Internals->Data.InvalidPointIdCells;
  if (invalid > 0)
  {
    vtkWarningMacro(<< invalid << " cell(s) name a point id outside [0, "
                    << this->DataSet->GetNumberOfPoints()
                    << "): skipped, no query returns them");
  }
  // VTK's StoreCellBounds would read every cell, the invalid ones too.
  if (this->CacheCellBounds && invalid == 0)
  {
    this->StoreCellBounds();
  }
  this->Internals->Data.Build(this->BuildQuality, this->NumberOfCellsPerNode);
  if (!this->PickingTreeOnDemand && this->Internals->Data.Lazy)
  {
    this->Internals->Data.Lazy->buildAll();
    this->Internals->Data.DropExtractionArrays();
  }

  this->Internals->Data.BuildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  this->BuildTime.Modified();
  this->Internals->TreeTime.store(this->BuildTime.GetMTime(), std::memory_order_release);
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::FreeSearchStructure()
{
  this->Internals->Data.Clear();
  this->Internals->TreeTime.store(0);
  this->Internals->BuiltPolyData.store(nullptr);
  this->FreeCellBounds();
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::GenerateRepresentation(int level, vtkPolyData* pd)
{
  if (!pd)
  {
    return;
  }
  if (this->DataSet && !this->PrepareQuery() && !this->Internals->HasTree())
  {
    return;
  }
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> quads;
  std::vector<vtkrt::locator::Box> boxes;
  this->Internals->Data.BoxesAtLevel(level, boxes);
  static const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  const auto& data = this->Internals->Data;
  for (const auto& b : boxes)
  {
    vtkIdType base = pts->GetNumberOfPoints();
    for (int k = 0; k < 8; ++k)
    {
      const Vec3d corner((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
        (k & 4) ? b.max.z : b.min.z);
      const Vec3d p = data.ToWorld(corner);
      pts->InsertNextPoint(p.x, p.y, p.z);
    }
    for (const auto& f : faces)
    {
      vtkIdType ids[4] = { base + f[0], base + f[1], base + f[2], base + f[3] };
      quads->InsertNextCell(4, ids);
    }
  }
  pd->Initialize();
  pd->SetPoints(pts);
  pd->SetPolys(quads);
}

//------------------------------------------------------------------------------
int vtkBVHCellLocator::IntersectWithLine(const double p1[3], const double p2[3], double tol,
  double& t, double x[3], double pcoords[3], int& subId, vtkIdType& cellId, vtkGenericCell* cell)
{
  cellId = -1;
  // Non-finite endpoints make an invalid segment, which ClosestHit refuses
  // (no separate test on the picking path).
  if (!this->PrepareQuery() || !std::isfinite(tol))
  {
    return 0;
  }
  vtkrt::locator::LineHit hit;
  if (!this->Internals->Data.IntersectWithLine(p1, p2, std::abs(tol), this->DataSet, cell, hit))
  {
    if (BeyondLocalFrame(this->Internals->Data, p1, p2))
    {
      vtkErrorMacro("IntersectWithLine: " << kBeyondLocalFrame);
    }
    return 0;
  }
  t = hit.T;
  cellId = hit.CellId;
  subId = hit.SubId;
  for (int i = 0; i < 3; ++i)
  {
    x[i] = hit.X[i];
    pcoords[i] = hit.PCoords[i];
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkBVHCellLocator::IntersectWithLine(const double p1[3], const double p2[3], double tol,
  double& t, double x[3], double pcoords[3], int& subId, vtkIdType& cellId)
{
  return this->IntersectWithLine(p1, p2, tol, t, x, pcoords, subId, cellId, nullptr);
}

//------------------------------------------------------------------------------
int vtkBVHCellLocator::IntersectWithLine(const double p1[3], const double p2[3], double tol,
  double& t, double x[3], double pcoords[3], int& subId)
{
  vtkIdType cellId;
  return this->IntersectWithLine(p1, p2, tol, t, x, pcoords, subId, cellId, nullptr);
}

//------------------------------------------------------------------------------
int vtkBVHCellLocator::IntersectWithLine(
  const double p1[3], const double p2[3], vtkPoints* points, vtkIdList* cellIds)
{
  return this->IntersectWithLine(p1, p2, 0.0, points, cellIds, nullptr);
}

//------------------------------------------------------------------------------
int vtkBVHCellLocator::IntersectWithLine(const double p1[3], const double p2[3], double tol,
  vtkPoints* points, vtkIdList* cellIds, vtkGenericCell* cell)
{
  if (points)
  {
    points->Reset();
  }
  if (cellIds)
  {
    cellIds->Reset();
  }
  if (!this->PrepareQuery() || !IsFinite3(p1) || !IsFinite3(p2) || !std::isfinite(tol))
  {
    return 0;
  }
  std::vector<vtkrt::locator::LineHit> hits;
  this->Internals->Data.AllHits(p1, p2, std::abs(tol), this->DataSet, cell, hits);
  if (hits.empty())
  {
    if (BeyondLocalFrame(this->Internals->Data, p1, p2))
    {
      vtkErrorMacro("IntersectWithLine: " << kBeyondLocalFrame);
    }
    return 0;
  }
  for (const auto& h : hits)
  {
    if (points)
    {
      points->InsertNextPoint(h.X);
    }
    if (cellIds)
    {
      cellIds->InsertNextId(h.CellId);
    }
  }
  return hits.front().Leaving ? -1 : 1;
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::FindCellsAlongLine(
  const double p1[3], const double p2[3], double tolerance, vtkIdList* cells)
{
  if (!cells)
  {
    return;
  }
  cells->Reset();
  if (!this->PrepareQuery() || !IsFinite3(p1) || !IsFinite3(p2) || !std::isfinite(tolerance))
  {
    return;
  }
  std::vector<vtkIdType> ids;
  this->Internals->Data.CellsAlongLine(p1, p2, std::abs(tolerance), this->DataSet, ids);
  if (ids.empty() && BeyondLocalFrame(this->Internals->Data, p1, p2))
  {
    vtkErrorMacro("FindCellsAlongLine: " << kBeyondLocalFrame);
  }
  cells->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), cells->GetPointer(0));
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::FindCellsWithinBounds(double* bbox, vtkIdList* cells)
{
  if (!cells)
  {
    return;
  }
  cells->Reset();
  if (!bbox || !this->PrepareQuery())
  {
    return;
  }
  std::vector<vtkIdType> ids;
  this->Internals->Data.CellsInBox(bbox, this->DataSet, ids);
  cells->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), cells->GetPointer(0));
}

//------------------------------------------------------------------------------
vtkIdType vtkBVHCellLocator::FindClosestPointWithinRadius(double x[3], double radius,
  double closestPoint[3], vtkGenericCell* cell, vtkIdType& cellId, int& subId, double& dist2,
  int& inside)
{
  cellId = -1;
  subId = 0;
  inside = 0;
  dist2 = VTK_DOUBLE_MAX;
  if (!this->PrepareQuery() || !x || !IsFinite3(x) || std::isnan(radius) || radius < 0.0)
  {
    return 0;
  }
  vtkrt::locator::PointHit hit;
  if (!this->Internals->Data.FindClosestPoint(x, radius, this->DataSet, cell, hit))
  {
    if (BeyondLocalFrame(this->Internals->Data, x))
    {
      vtkErrorMacro("FindClosestPoint: " << kBeyondLocalFrame);
    }
    return 0;
  }
  cellId = hit.CellId;
  subId = hit.SubId;
  dist2 = hit.Dist2;
  inside = hit.Inside;
  for (int i = 0; i < 3; ++i)
  {
    closestPoint[i] = hit.X[i];
  }
  return 1;
}

//------------------------------------------------------------------------------
vtkIdType vtkBVHCellLocator::FindClosestPointWithinRadius(double x[3], double radius,
  double closestPoint[3], vtkGenericCell* cell, vtkIdType& cellId, int& subId, double& dist2)
{
  int inside;
  return this->FindClosestPointWithinRadius(
    x, radius, closestPoint, cell, cellId, subId, dist2, inside);
}

//------------------------------------------------------------------------------
vtkIdType vtkBVHCellLocator::FindClosestPointWithinRadius(
  double x[3], double radius, double closestPoint[3], vtkIdType& cellId, int& subId, double& dist2)
{
  int inside;
  return this->FindClosestPointWithinRadius(
    x, radius, closestPoint, nullptr, cellId, subId, dist2, inside);
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::FindClosestPoint(const double x[3], double closestPoint[3],
  vtkGenericCell* cell, vtkIdType& cellId, int& subId, double& dist2)
{
  int inside;
  double p[3] = { x[0], x[1], x[2] };
  this->FindClosestPointWithinRadius(
    p, vtkMath::Inf(), closestPoint, cell, cellId, subId, dist2, inside);
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::FindClosestPoint(
  const double x[3], double closestPoint[3], vtkIdType& cellId, int& subId, double& dist2)
{
  this->FindClosestPoint(x, closestPoint, nullptr, cellId, subId, dist2);
}

//------------------------------------------------------------------------------
vtkIdType vtkBVHCellLocator::FindCell(
  double x[3], double vtkNotUsed(tol2), vtkGenericCell* cell, double pcoords[3], double* weights)
{
  // tol2 is not used, as by VTK's locators (see Internals' FindCell).
  if (!this->PrepareQuery() || !x || !IsFinite3(x))
  {
    return -1;
  }
  vtkrt::locator::QueryCell qc(cell);
  double localPcoords[3];
  if (!pcoords)
  {
    pcoords = localPcoords;
  }
  const vtkIdType found = this->Internals->Data.FindCell(x, this->DataSet, qc.Get(), pcoords, weights);
  if (found < 0 && BeyondLocalFrame(this->Internals->Data, x))
  {
    vtkErrorMacro("FindCell: " << kBeyondLocalFrame);
  }
  return found;
}

//------------------------------------------------------------------------------
vtkIdType vtkBVHCellLocator::FindCell(double x[3])
{
  double pcoords[3];
  return this->FindCell(x, 0.0, nullptr, pcoords, nullptr);
}

//------------------------------------------------------------------------------
bool vtkBVHCellLocator::InsideCellBounds(double x[3], vtkIdType cellId)
{
  if (!this->DataSet || !x || cellId < 0 || cellId >= this->DataSet->GetNumberOfCells())
  {
    return false;
  }
  double b[6];
  if (this->CellBounds && this->Internals->HasTree() && !this->NeedsBuild())
  {
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 0)
    // VTK 9.2 stores the cached bounds flat (6 per cell).
    std::copy_n(this->CellBounds + 6 * cellId, 6, b);
#else
    std::copy(this->CellBounds[cellId], this->CellBounds[cellId] + 6, b);
#endif
  }
  else
  {
    this->DataSet->GetCellBounds(cellId, b);
  }
  return b[0] <= x[0] && x[0] <= b[1] && b[2] <= x[1] && x[1] <= b[3] && b[4] <= x[2] &&
    x[2] <= b[5];
}

//------------------------------------------------------------------------------
vtkIdType vtkBVHCellLocator::GetNumberOfNodes() const
{
  this->Internals->Data.EnsureTree();
  return this->Internals->Data.Stats.Nodes;
}
vtkIdType vtkBVHCellLocator::GetNumberOfPrimitives() const
{
  return this->Internals->Data.NumberOfPrimitives();
}
int vtkBVHCellLocator::GetTreeDepth() const
{
  this->Internals->Data.EnsureTree();
  return this->Internals->Data.Stats.Depth;
}
double vtkBVHCellLocator::GetSAHCost() const
{
  this->Internals->Data.EnsureTree();
  return this->Internals->Data.Stats.SAHCost;
}
double vtkBVHCellLocator::GetBuildTimeSeconds() const
{
  return this->Internals->Data.BuildSeconds;
}
size_t vtkBVHCellLocator::GetMemorySize() const
{
  size_t bytes = this->Internals->Data.MemorySize();
  if (this->CellBounds && this->DataSet)
  {
    bytes += static_cast<size_t>(this->DataSet->GetNumberOfCells()) * 6 * sizeof(double);
  }
  return bytes;
}

//------------------------------------------------------------------------------
void vtkBVHCellLocator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* qualityNames[] = { "Fast", "SAH", "High" };
  os << indent << "BuildQuality: " << qualityNames[this->BuildQuality] << "\n";
  os << indent << "PickingTreeOnDemand: " << (this->PickingTreeOnDemand ? "On" : "Off") << "\n";
  os << indent << "Built: " << (this->Internals->HasTree() ? "yes" : "no") << "\n";
  const auto& d = this->Internals->Data;
  os << indent << "Leaf size (NumberOfCellsPerNode): " << this->NumberOfCellsPerNode << "\n";
  os << indent << "Primitives: " << d.NumberOfPrimitives() << " (" << d.NumberOfTriangles()
     << " triangles, " << d.NumberOfGeneralCells() << " general cells, " << d.SkippedCells
     << " skipped non-finite cells, " << d.InvalidPointIdCells
     << " skipped cells with out-of-range point ids)\n";
  os << indent << "Picking tree (" << vtkrt::locator::BVHCellLocatorData::kWideArity
     << " children a node): " << d.PickingNodeCount() << " nodes";
  if (d.Lazy)
  {
    // The fast build makes each bucket's subtree at the first query that reaches it.
    os << ", " << d.Lazy->builtBuckets() << " of " << d.Lazy->subtreeCount()
       << " buckets built so far";
  }
  os << "\n";
  // How cells of several triangles are found by their own bounds.
  os << indent << "Cells of several triangles: " << d.MultiTriangleCells.size();
  if (!d.MultiTriangleCells.empty())
  {
    os << (d.OnlyMultiTriangleCells ? " (every cell)" : "") << ", found by their bounds in a tree "
       << (d.MultiCells.Ready.load() ? "built" : "not built yet (the first FindCell or bounds query builds it)");
  }
  os << "\n";
  // PrintSelf does not build: the fast build makes the binary tree only
  // when something needs it.
  if (d.TreeBuilt.Ready.load())
  {
    os << indent << "Nodes: " << d.Stats.Nodes << "\n";
    os << indent << "Leaves: " << d.Stats.Leaves << "\n";
    os << indent << "Depth: " << d.Stats.Depth << "\n";
    os << indent << "SAH cost: " << d.Stats.SAHCost << "\n";
  }
  else
  {
    const char* later = "(binary tree not built yet: GenerateRepresentation, the tree "
                        "statistics, or a query the float walk cannot answer builds it)";
    os << indent << "Nodes: " << later << "\n";
    os << indent << "Leaves: " << (d.Lazy ? d.Lazy->leafCount() : 0) << " (picking tree, so far)\n";
    os << indent << "Depth: " << (d.Lazy ? d.Lazy->depth() : 0) << " (picking tree levels, so far)\n";
    os << indent << "SAH cost: " << later << "\n";
  }
  os << indent << "Build time: " << d.BuildSeconds << " s\n";
  os << indent << "Memory: " << this->GetMemorySize() << " bytes\n";
  os << indent << "Local origin: (" << d.Origin.x << ", " << d.Origin.y << ", " << d.Origin.z
     << ")\n";
  os << indent << "Local scale: " << d.Scale << "\n";
}
