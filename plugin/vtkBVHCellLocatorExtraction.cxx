// vtkBVHCellLocator's primitives from a vtkDataSet: the points bound in
// place (or copied to double), the local origin, surface cells triangulated
// onto the fast path, every other cell a general primitive with its box.
#include "vtkBVHCellLocatorInternals.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellType.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include "vtkrt/core/LocalFrame.h"
#include "vtkrt/core/SurfaceTriangulation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace
{
/// Whether every point id of a cell names one of the dataset's points.
bool PointIdsInRange(vtkIdType npts, const vtkIdType* pts, vtkIdType nPoints)
{
  for (vtkIdType i = 0; i < npts; ++i)
  {
    if (pts[i] < 0 || pts[i] >= nPoints)
    {
      return false;
    }
  }
  return true;
}
} // namespace

namespace vtkrt
{
namespace locator
{

//------------------------------------------------------------------------------
void BVHCellLocatorData::Extract(vtkDataSet* ds)
{
  if (auto* pd = vtkPolyData::SafeDownCast(ds))
  {
    const bool shared = this->ShareTriangles(pd);
    this->BindPoints(pd->GetPoints(), this->SharedTriangulation);
    this->ExtractPolyData(pd, shared);
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
      // Blanked cells of structured data are empty cells: nothing to find.
      if (ds->GetCellType(c) != VTK_EMPTY_CELL)
      {
        this->GenCell.push_back(c);
      }
    }
  }
  if (!this->SharedTriangulation)
  {
    this->SrcVerts = this->TriVerts.data();
  }
  this->ListMultiTriangleCells();
  this->WarmUpCellAccess(ds);
  this->ComputeGeneralBoxes(ds);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::ListMultiTriangleCells()
{
  this->MultiTriangleCells.clear();
  this->OnlyMultiTriangleCells = false;
  const vtkIdType n = this->NumberOfTriangles();
  if (this->UniformCellBase >= 0)
  {
    return; // one triangle a cell
  }
  int cellTriangles = 0;
  vtkIdType multiCellTriangles = 0;
  auto endCell = [&]() {
    if (cellTriangles < 2)
    {
      this->MultiTriangleCells.pop_back(); // one triangle: its box is the cell's bounds
      return;
    }
    multiCellTriangles += cellTriangles;
  };
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (this->TriFlags[i] & WholeTriangle)
    {
      continue;
    }
    const vtkIdType cellId = this->TriCell[i];
    if (this->MultiTriangleCells.empty() || this->MultiTriangleCells.back() != cellId || cellTriangles == 0)
    {
      if (cellTriangles > 0)
      {
        endCell();
      }
      this->MultiTriangleCells.push_back(cellId);
      cellTriangles = 0;
    }
    ++cellTriangles;
  }
  if (cellTriangles > 0)
  {
    endCell();
  }
  this->OnlyMultiTriangleCells = n > 0 && multiCellTriangles == n && this->GenCell.empty();
  // Cells are extracted in id order; sorted anyway, as the queries assume.
  if (!std::is_sorted(this->MultiTriangleCells.begin(), this->MultiTriangleCells.end()))
  {
    std::sort(this->MultiTriangleCells.begin(), this->MultiTriangleCells.end());
    this->MultiTriangleCells.erase(
      std::unique(this->MultiTriangleCells.begin(), this->MultiTriangleCells.end()),
      this->MultiTriangleCells.end());
  }
}

//------------------------------------------------------------------------------
/// Takes the polydata's shared triangulation (vtkSurfaceTriangulation) when
/// it gives exactly the triangles the extraction here would: every polygon
/// and strip with three or more points, all of them in range, all points
/// finite (cells of other input are kept, dropped or tested by VTK cell by
/// cell here, as before). False, with caching off, or for such input.
bool BVHCellLocatorData::ShareTriangles(vtkPolyData* pd)
{
  this->SharedTriangulation = nullptr;
  vtkPoints* pts = pd->GetPoints();
  const vtkIdType nPoints = pts ? pts->GetNumberOfPoints() : 0;
  if (!vtkSurfaceTriangulation::GetCaching() || nPoints == 0 ||
    static_cast<std::uint64_t>(nPoints) >= std::numeric_limits<std::uint32_t>::max() ||
    pd->GetNumberOfPolys() + pd->GetNumberOfStrips() == 0)
  {
    return false;
  }
  vtkSmartPointer<vtkSurfaceTriangulation> shared = vtkSurfaceTriangulation::Get(pd);
  if (shared->GetNumberOfTriangles() == 0 || shared->GetNumberOfDegenerateCells() > 0 ||
    shared->GetNumberOfInvalidPointIdCells() > 0 || shared->GetNumberOfNonFinitePoints() > 0)
  {
    return false;
  }
  this->SharedTriangulation = shared;
  return true;
}

//------------------------------------------------------------------------------
/// The shared triangles as the extraction's: point ids read in place, cell
/// ids, subIds and flags copied (none for polys of triangles only, whose
/// cell ids UniformCellBase gives).
void BVHCellLocatorData::AdoptSharedTriangles()
{
  static_assert(int(FlipOrientation) == int(core::FlippedStripTriangle) &&
      int(EvaluateInCell) == int(core::FanTriangle) && int(WholeTriangle) == int(core::WholeTriangle),
    "the locator's triangle flags are the shared triangulation's parts");
  static_assert(sizeof(vtkIdType) == sizeof(std::int64_t), "cell ids copy as they are");
  const core::SurfaceTriangles& t = this->SharedTriangulation->GetTriangles();
  this->SrcVerts = t.pointIds.data();
  this->TriCell.resize(t.count); // unfilled when uniform: UniformCellBase gives the ids
  if (t.uniform)
  {
    this->UniformCellBase = t.firstCellId;
    return;
  }
  this->UniformCellBase = -1;
  this->TriSub.resize(t.count);
  this->TriFlags.resize(t.count);
  vtkSMPTools::For(0, static_cast<vtkIdType>(t.count), [&](vtkIdType b, vtkIdType e) {
    std::copy(t.cellIds.data() + b, t.cellIds.data() + e, this->TriCell.data() + b);
    std::copy(t.subIds.data() + b, t.subIds.data() + e, this->TriSub.data() + b);
    std::copy(t.parts.data() + b, t.parts.data() + e, this->TriFlags.data() + b);
  });
}

//------------------------------------------------------------------------------
/// Has the dataset build what GetCell / GetCellBounds build lazily (not
/// thread-safe) on a cell the locator keeps, before threads call them.
void BVHCellLocatorData::WarmUpCellAccess(vtkDataSet* ds)
{
  const vtkIdType firstTriangleCell = this->UniformCellBase >= 0
    ? this->UniformCellBase
    : (this->TriCell.empty() ? vtkIdType(-1) : this->TriCell[0]);
  const vtkIdType cellId = !this->GenCell.empty() ? this->GenCell.front() : firstTriangleCell;
  if (cellId < 0)
  {
    return;
  }
  vtkNew<vtkGenericCell> warmup;
  ds->GetCell(cellId, warmup);
  double b[6];
  ds->GetCellBounds(cellId, b);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::ComputeOrigin(vtkDataSet* ds)
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
  this->SetLocalFrame(b);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::SetLocalFrame(const Box& b)
{
  const core::ScaledFrame frame = core::ScaledFrame::of(b);
  this->Origin = frame.origin;
  this->Scale = frame.scale;
  // As ScaledFrame::toLocal: scale down before the shift, up after it.
  this->PreScale = this->Scale < 1.0 ? this->Scale : 1.0;
  this->PostScale = this->Scale < 1.0 ? 1.0 : this->Scale;
  this->ScaledOrigin = this->Origin * this->PreScale;
}

//------------------------------------------------------------------------------
/// The points: double coordinates read in place (else a double copy of
/// them), the local frame from their finite bounds (NaN/inf points would
/// poison it), given by the shared triangulation when there is one.
void BVHCellLocatorData::BindPoints(vtkPoints* pts, const vtkSurfaceTriangulation* shared)
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
    this->CopyPoints(pts);
  }
  if (shared)
  {
    double sb[6];
    shared->GetFinitePointBounds(sb);
    const Box b = sb[0] <= sb[1] ? Box(Vec3d(sb[0], sb[2], sb[4]), Vec3d(sb[1], sb[3], sb[5])) : Box();
    this->SetLocalFrame(b);
    this->PointBounds = b.isEmpty() ? Box() : Box(this->ToLocal(b.min), this->ToLocal(b.max));
    return;
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
  this->SetLocalFrame(b);
  this->PointBounds = b.isEmpty() ? Box() : Box(this->ToLocal(b.min), this->ToLocal(b.max));
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::CopyPoints(vtkPoints* pts)
{
  const vtkMTimeType copied = std::max(pts->GetMTime(), pts->GetData()->GetMTime());
  vtkSMPTools::For(0, this->NumberOfPoints, [&](vtkIdType b, vtkIdType e) {
    double p[3];
    for (vtkIdType i = b; i < e; ++i)
    {
      pts->GetPoint(i, p);
      this->PointsCopy[i] = Vec3d(p[0], p[1], p[2]);
    }
  });
  this->CopiedPoints = pts;
  this->CopiedCoordsArray = pts->GetData();
  this->CopiedCoordsPointer = pts->GetData()->GetVoidPointer(0);
  this->CopiedCoordsTime.Value.store(copied, std::memory_order_release);
}

//------------------------------------------------------------------------------
bool BVHCellLocatorData::PointsReplaced(vtkDataSet* ds) const
{
  auto* pointSet = vtkPointSet::SafeDownCast(ds);
  if (!pointSet || this->NumberOfPoints == 0)
  {
    return false;
  }
  vtkPoints* pts = pointSet->GetPoints();
  if (!pts)
  {
    return true;
  }
  // The coordinates' array is what counts: a new vtkPoints around the same
  // array holds the same points.
  return pts->GetData() != (this->DataSetCoordsArray ? this->DataSetCoordsArray.Get() : this->CopiedCoordsArray.Get());
}

//------------------------------------------------------------------------------
bool BVHCellLocatorData::PointsCopyStale() const
{
  vtkPoints* pts = this->CopiedPoints;
  if (!pts)
  {
    return false;
  }
  vtkDataArray* a = pts->GetData();
  return a != this->CopiedCoordsArray || a->GetVoidPointer(0) != this->CopiedCoordsPointer ||
    a->GetNumberOfTuples() < this->NumberOfPoints ||
    std::max(pts->GetMTime(), a->GetMTime()) >
    this->CopiedCoordsTime.Value.load(std::memory_order_acquire);
}

//------------------------------------------------------------------------------
bool BVHCellLocatorData::RefreshPointsCopy()
{
  vtkPoints* pts = this->CopiedPoints;
  vtkDataArray* a = pts->GetData();
  if (a != this->CopiedCoordsArray || a->GetVoidPointer(0) != this->CopiedCoordsPointer ||
    a->GetNumberOfTuples() < this->NumberOfPoints)
  {
    return false;
  }
  this->CopyPoints(pts);
  return true;
}

//------------------------------------------------------------------------------
template <class IdT>
bool BVHCellLocatorData::ExtractTriangles(const IdT* offsets, const IdT* conn, vtkIdType n, vtkIdType cellBase)
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

//------------------------------------------------------------------------------
/// Polys that are all triangles, read straight from the connectivity in
/// parallel (no per-cell iterator, no push_back). False, with nothing
/// added, when a cell is not a triangle or has an out-of-range or
/// non-finite point: the cell-by-cell path then handles the polys.
bool BVHCellLocatorData::ExtractTrianglePolys(vtkCellArray* polys, vtkIdType cellBase)
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

//------------------------------------------------------------------------------
void BVHCellLocatorData::AddTriangle(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cellId, int sub, std::uint8_t flags)
{
  this->TriVerts.push_back(static_cast<std::uint32_t>(a));
  this->TriVerts.push_back(static_cast<std::uint32_t>(b));
  this->TriVerts.push_back(static_cast<std::uint32_t>(c));
  this->TriCell.push_back(cellId);
  this->UniformCellBase = -1;
  this->TriSub.push_back(sub);
  this->TriFlags.push_back(flags);
}

//------------------------------------------------------------------------------
/// Triangulates a surface cell onto the fast path; false when it must take
/// the general path.
bool BVHCellLocatorData::AddSurfaceCell(int type, vtkIdType npts, const vtkIdType* pts, vtkIdType cellId)
{
  if (type != VTK_TRIANGLE && type != VTK_QUAD && type != VTK_POLYGON && type != VTK_TRIANGLE_STRIP)
  {
    return false;
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
      this->AddPolygon(npts, pts, cellId);
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

//------------------------------------------------------------------------------
void BVHCellLocatorData::AddQuad(const vtkIdType* pts, vtkIdType cellId)
{
  // A fan from point 0, as VTK's raster mapper and vtkRayTracePass draw it,
  // so that a pick lands on the drawn surface (vtkQuad's own tests split a
  // warped quad along its shorter diagonal).
  this->AddTriangle(pts[0], pts[1], pts[2], cellId, 0, EvaluateInCell);
  this->AddTriangle(pts[0], pts[2], pts[3], cellId, 0, EvaluateInCell);
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::AddPolygon(vtkIdType npts, const vtkIdType* pts, vtkIdType cellId)
{
  // A fan from point 0, as VTK's raster mapper and vtkRayTracePass draw it
  // (vtkPolygon's own tests ear-cut it).
  for (vtkIdType k = 1; k + 1 < npts; ++k)
  {
    this->AddTriangle(pts[0], pts[k], pts[k + 1], cellId, 0, EvaluateInCell);
  }
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::ExtractPolyData(vtkPolyData* pd, bool shared)
{
  const bool indexable = this->PointsIndexable();
  vtkIdType cellId = 0;
  vtkCellArray* arrays[4] = { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() };
  if (shared)
  {
    this->AdoptSharedTriangles();
  }
  else
  {
    this->ReserveTriangles(arrays[2], arrays[3]);
  }
  // Verts and lines cell by cell; polys and strips too unless shared.
  for (int a = 0; a < (shared ? 2 : 4); ++a)
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
      if (!PointIdsInRange(npts, pts, this->NumberOfPoints))
      {
        ++this->InvalidPointIdCells; // VTK would read past the points for it
        continue;
      }
      int type = -1;
      if (a == 2)
      {
        type = npts == 3 ? VTK_TRIANGLE : (npts == 4 ? VTK_QUAD : VTK_POLYGON);
      }
      else if (a == 3)
      {
        type = VTK_TRIANGLE_STRIP;
      }
      if (!(indexable && type >= 0 && this->AddSurfaceCell(type, npts, pts, cellId)))
      {
        this->GenCell.push_back(cellId);
      }
    }
  }
}

//------------------------------------------------------------------------------
/// Room for the triangles of polys (n-2 per polygon) and strips.
void BVHCellLocatorData::ReserveTriangles(vtkCellArray* polys, vtkCellArray* strips)
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

//------------------------------------------------------------------------------
void BVHCellLocatorData::ExtractUnstructuredGrid(vtkUnstructuredGrid* ug)
{
  const bool indexable = this->PointsIndexable();
  const vtkIdType n = ug->GetNumberOfCells();
  for (vtkIdType c = 0; c < n; ++c)
  {
    vtkIdType npts;
    const vtkIdType* pts;
    const int type = ug->GetCellType(c);
    ug->GetCellPoints(c, npts, pts);
    if (!PointIdsInRange(npts, pts, this->NumberOfPoints))
    {
      ++this->InvalidPointIdCells; // VTK would read past the points for it
      continue;
    }
    if (!(indexable && this->AddSurfaceCell(type, npts, pts, c)))
    {
      this->GenCell.push_back(c);
    }
  }
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::ComputeGeneralBoxes(vtkDataSet* ds)
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
      Vec3d lo = this->ToLocal(box.min), hi = this->ToLocal(box.max);
      const Vec3d farOrigin = glm::min(glm::abs(this->ScaledOrigin) * (2.0 * this->PostScale),
        Vec3d(std::numeric_limits<double>::max()));
      const Vec3d slack = eps * (glm::abs(lo) + glm::abs(hi) + farOrigin);
      this->GenBox[i] = Box(lo - slack, hi + slack);
    }
  });
}

} // namespace locator
} // namespace vtkrt
