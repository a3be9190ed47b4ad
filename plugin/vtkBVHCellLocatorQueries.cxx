// vtkBVHCellLocator's queries: each over the core's walks
// (core/SegmentQueries.h, core/BVHTraversal.h) with the locator's exact
// tests (a triangle's watertight test, a general cell's own methods), and
// the answer in VTK's terms (the cell's pcoords and subId, the caller's
// vtkGenericCell filled).
#include "vtkBVHCellLocatorInternals.h"
#include "vtkBVHCellLocatorPickingScene.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/SegmentQueries.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/WidePointQueries.h"
#include "vtkrt/core/WideTraversal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace vtkrt
{
namespace locator
{
namespace
{

/// A general cell's own IntersectWithLine on the segment p1 -> p2, kept
/// only within the walk's current range [r.tmin, r.tmax].
inline bool IntersectCell(vtkDataSet* ds, vtkIdType cellId, vtkGenericCell* cell,
  const double p1[3], const double p2[3], double tol, const core::Ray<double>& r, double& t,
  double x[3], double pc[3], int& sub)
{
  ds->GetCell(cellId, cell);
  return cell->IntersectWithLine(p1, p2, tol, t, x, pc, sub) && t >= r.tmin && t <= r.tmax;
}


/// vtkTriangle::EvaluatePosition fails (-1) on a zero-area triangle, so
/// VTK's locators never give one as a closest point.
inline bool ZeroArea(const Vec3d& v0, const Vec3d& v1, const Vec3d& v2)
{
  const Vec3d n = glm::cross(v1 - v0, v2 - v0);
  return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

inline void Barycentric(
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

/// Whether world point x lies clearly outside tetrahedron cellId of `grid`
/// (`coords`: its points' x y z): a barycentric coordinate below -0.01 or
/// above 1.01, ten times vtkTetra::EvaluatePosition's tolerance, so that
/// VTK's test rejects it too. False when it cannot tell cheaply (storage
/// not shared, a nearly flat tetrahedron): then VTK's test decides. Spares
/// the cell's GetCell and EvaluatePosition, whose outside branch computes a
/// closest point on every face.
inline bool TetraClearlyMisses(vtkUnstructuredGrid* grid, vtkIdType cellId, const double* coords, const double x[3])
{
  vtkCellArray* cells = grid->GetCells();
  if (!cells->IsStorageShareable() || grid->GetCellType(cellId) != VTK_TETRA)
  {
    return false;
  }
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  cells->GetCellAtId(cellId, n, ids); // a pointer into shared storage: thread safe
  const vtkIdType points = grid->GetNumberOfPoints();
  if (n != 4 || std::any_of(ids, ids + 4, [points](vtkIdType id) { return id < 0 || id >= points; }))
  {
    return false; // VTK's own test reports what it makes of such a cell
  }
  const Vec3d p0(coords[3 * ids[0]], coords[3 * ids[0] + 1], coords[3 * ids[0] + 2]);
  Vec3d e[3];
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double* p = coords + 3 * ids[k + 1];
    e[k] = Vec3d(p[0], p[1], p[2]) - p0;
    longest = std::max(longest, glm::length(e[k]));
  }
  const Vec3d r = Vec3d(x[0], x[1], x[2]) - p0;
  const double det = glm::dot(e[0], glm::cross(e[1], e[2]));
  if (!(std::abs(det) > 1e-6 * longest * longest * longest))
  {
    return false;
  }
  const double b1 = glm::dot(r, glm::cross(e[1], e[2])) / det;
  const double b2 = glm::dot(e[0], glm::cross(r, e[2])) / det;
  const double b3 = glm::dot(e[0], glm::cross(e[1], r)) / det;
  const double b0 = 1.0 - b1 - b2 - b3;
  const double lo = std::min({ b0, b1, b2, b3 }), hi = std::max({ b0, b1, b2, b3 });
  return lo < -0.01 || hi > 1.01;
}

/// The weights EvaluatePosition writes for a cell: on the stack for cells
/// of up to 64 points, else on the heap (no per-query allocation, and not
/// vtkDataSet::GetMaxCellSize, which visits every cell of a polydata).
class CellWeights
{
public:
  double* For(vtkCell* c)
  {
    const size_t n = static_cast<size_t>(std::max<vtkIdType>(c->GetNumberOfPoints(), 1));
    if (n <= sizeof(this->Small) / sizeof(double))
    {
      return this->Small;
    }
    this->Large.resize(std::max(this->Large.size(), n));
    return this->Large.data();
  }

private:
  double Small[64];
  std::vector<double> Large;
};

// What DataSet->GetCell(cellId, cell) gives for a triangle, from the point
// ids kept with it and the coordinates the exact test read (the dataset's
// double points in place, else the build's double copy): no cell lookup and
// no virtual call a point. A cell that already holds three double points
// (the previous pick's triangle, as in vtkCellPicker's loop) is overwritten
// in place: resizing its arrays again was most of a hit's cost. As with
// vtkPolyData::GetCell, nothing is marked modified.
void FillTriangleCell(vtkGenericCell* cell, const std::uint32_t* ids, const double* coords)
{
  cell->SetCellTypeToTriangle();
  if (cell->PointIds->GetNumberOfIds() != 3)
  {
    cell->PointIds->SetNumberOfIds(3);
  }
  vtkDoubleArray* cellCoords = vtkDoubleArray::FastDownCast(cell->Points->GetData());
  if (!cellCoords || cellCoords->GetNumberOfComponents() != 3 || cellCoords->GetNumberOfTuples() != 3)
  {
    cell->Points->SetNumberOfPoints(3);
    cellCoords = vtkDoubleArray::FastDownCast(cell->Points->GetData());
  }
  double* dst = cellCoords && cellCoords->GetNumberOfComponents() == 3 ? cellCoords->GetPointer(0) : nullptr;
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType id = ids[k];
    const double* p = coords + 3 * id;
    cell->PointIds->SetId(k, id);
    if (dst)
    {
      dst[3 * k] = p[0]; // not std::copy_n: a memcpy call for three doubles
      dst[3 * k + 1] = p[1];
      dst[3 * k + 2] = p[2];
    }
    else
    {
      cell->Points->SetPoint(k, p);
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
/// Watertight hit, or (tol > 0) VTK's rule: the crossing of the plane lies
/// within tol of the triangle. u, v: VTK triangle pcoords of the hit.
inline bool BVHCellLocatorData::IntersectTriangle(std::uint32_t prim, const core::RayTrianglePrecomputed<double>& pre,
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

//------------------------------------------------------------------------------
/// Whether the segment may lie in the triangle's plane, which the watertight
/// test never hits: VTK's cells then hit where the segment enters them
/// (vtkTriangle's coplanar case, decided by its own exact test), so such a
/// triangle's cell is asked. A superset: parallel and on the plane within
/// rounding of the local frame.
inline bool BVHCellLocatorData::MayLieInPlane(std::uint32_t prim, const core::Ray<double>& ray) const
{
  constexpr double kRelative = 1e-9;
  const Vec3d v0 = this->Vertex(prim, 0);
  const Vec3d n = glm::cross(this->Vertex(prim, 1) - v0, this->Vertex(prim, 2) - v0);
  const double scale = glm::length(n);
  const Vec3d toOrigin = ray.org - v0;
  return scale > 0.0 && std::abs(glm::dot(n, ray.dir)) <= kRelative * scale * glm::length(ray.dir) &&
    std::abs(glm::dot(n, toOrigin)) <= kRelative * scale * (glm::length(toOrigin) + glm::length(v0));
}

//------------------------------------------------------------------------------
/// Whether x projects into the triangle (vtkTriangle::EvaluatePosition == 1).
inline bool BVHCellLocatorData::ProjectsInside(std::uint32_t prim, const Vec3d& x) const
{
  const Vec3d v0 = this->Vertex(prim, 0);
  const Vec3d v1 = this->Vertex(prim, 1);
  const Vec3d v2 = this->Vertex(prim, 2);
  double u, v;
  Barycentric(x, v0, v1 - v0, v2 - v0, u, v);
  return u >= 0.0 && v >= 0.0 && u + v <= 1.0;
}

//------------------------------------------------------------------------------
/// The walk's nearest triangle hit as a LineHit (world coordinates; VTK
/// triangle pcoords, to be evaluated in the cell for quads and polygons).
inline void BVHCellLocatorData::SetTriangleHit(
  const core::Hit<double>& hit, const double p1[3], const core::Ray<double>& ray, LineHit& out) const
{
  const std::uint32_t prim = hit.prim;
  out.T = hit.t;
  out.CellId = this->TriCell[prim];
  for (int k = 0; k < 3; ++k)
  {
    out.X[k] = p1[k] + hit.t * this->ToWorldLength(ray.dir[k]);
  }
  const std::uint8_t flags = this->TriangleFlags(prim);
  out.NeedsEvaluate = (flags & EvaluateInCell) != 0;
  out.TrianglePointIds =
    (flags & WholeTriangle) ? this->TriIds.data() + 3 * static_cast<std::size_t>(prim) : nullptr;
  out.SubId = this->TriangleSubId(prim);
  out.PCoords[0] = hit.u;
  out.PCoords[1] = hit.v;
  out.PCoords[2] = 0.0;
}

//------------------------------------------------------------------------------
/// The nearest triangle or general cell the segment hits, then pcoords and
/// subId as that cell reports them and the caller's cell filled.
bool BVHCellLocatorData::IntersectWithLine(const double p1[3], const double p2[3], double tol,
  vtkDataSet* ds, vtkGenericCell* given, LineHit& out) const
{
  QueryCell cell(given);
  core::Ray<double> ray;
  if (!this->MakeSegment(p1, p2, ray))
  {
    std::vector<LineHit> hits;
    if (IsFinitePoint(p1, p2))
    {
      // The scratch cell is left holding the hit cell (the caller's, if given).
      this->CellsThroughPoint(p1, tol, ds, cell.Get(), true, hits);
    }
    if (hits.empty())
    {
      return false;
    }
    out = hits.front();
    return true;
  }
  const core::RayTrianglePrecomputed<double> triPre(ray);
  const double localTol = this->ToLocalLength(tol); // general cells take tol in world units
  const vtkIdType nTri = this->NumberOfTriangles();
  vtkIdType bestCell = -1;
  bool generalBest = false; ///< out holds a general cell's hit (a triangle's is filled after the walk)

  // Ties (same t) go to the lowest cell id, so the answer does not depend
  // on the traversal order.
  auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>& hit) {
    const bool haveBest = hit.found();
    const bool triangle = static_cast<vtkIdType>(prim) < nTri;
    if (triangle)
    {
      double t, u, v;
      if (this->IntersectTriangle(prim, triPre, r, localTol, t, u, v))
      {
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
      if (!ds || !this->MayLieInPlane(prim, r))
      {
        return false;
      }
    }
    // A general cell, or a triangle's cell in whose plane the segment lies:
    // the cell's own test.
    const vtkIdType cellId = triangle ? this->TriCell[prim] : this->GenCell[prim - nTri];
    double t, x[3], pc[3];
    int sub;
    if (!IntersectCell(ds, cellId, cell.Get(), p1, p2, tol, r, t, x, pc, sub))
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
  if (!core::closestHitSegment(PickingScene{ this }, ray, triPre, localTol, isect, hit))
  {
    return false;
  }
  if (!generalBest) // a general cell's hit is in `out` already
  {
    this->SetTriangleHit(hit, p1, ray, out);
  }
  if (out.NeedsEvaluate)
  {
    // Quad or polygon hit through its triangulation: parametric coordinates
    // in the original cell.
    vtkGenericCell* c = cell.Get();
    ds->GetCell(out.CellId, c);
    double closest[3], dist2;
    CellWeights weights;
    c->EvaluatePosition(out.X, closest, out.SubId, out.PCoords, dist2, weights.For(c));
  }
  if (given && out.TrianglePointIds)
  {
    FillTriangleCell(given, out.TrianglePointIds, this->WorldCoords());
  }
  else if (given)
  {
    ds->GetCell(out.CellId, given);
  }
  return true;
}

//------------------------------------------------------------------------------
void BVHCellLocatorData::AllHits(const double p1[3], const double p2[3], double tol, vtkDataSet* ds,
  vtkGenericCell* given, std::vector<LineHit>& hits) const
{
  hits.clear();
  QueryCell cell(given);
  core::Ray<double> ray;
  if (!this->MakeSegment(p1, p2, ray))
  {
    if (IsFinitePoint(p1, p2))
    {
      this->CellsThroughPoint(p1, tol, ds, cell.Get(), false, hits);
    }
    return;
  }
  const core::RayTrianglePrecomputed<double> triPre(ray);
  const double localTol = this->ToLocalLength(tol); // general cells take tol in world units
  const vtkIdType nTri = this->NumberOfTriangles();
  auto isect = [&](std::uint32_t prim, const core::Ray<double>& r, core::Hit<double>&) {
    LineHit h;
    double t, u, v;
    const bool triangle = static_cast<vtkIdType>(prim) < nTri;
    if (triangle && this->IntersectTriangle(prim, triPre, r, localTol, t, u, v))
    {
      h.T = t;
      h.CellId = this->TriCell[prim];
      for (int k = 0; k < 3; ++k)
      {
        h.X[k] = p1[k] + t * this->ToWorldLength(r.dir[k]);
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
      // A general cell, or a triangle's cell in whose plane the segment
      // lies: the cell's own test.
      if (triangle && (!ds || !this->MayLieInPlane(prim, r)))
      {
        return false;
      }
      const vtkIdType cellId = triangle ? this->TriCell[prim] : this->GenCell[prim - nTri];
      double x[3], pc[3];
      int sub;
      if (!IntersectCell(ds, cellId, cell.Get(), p1, p2, tol, r, t, x, pc, sub))
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
  core::allHitsSegment(PickingScene{ this }, ray, triPre, localTol, true, isect);
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

//------------------------------------------------------------------------------
/// A zero-length segment is a point: it hits the cells whose own
/// IntersectWithLine(p, p) says so (VTK's cells do when p lies on them), at
/// t = 0, x = p, pcoords and subId as EvaluatePosition gives them; in cell
/// id order, the first only when firstOnly (then `cell` holds it).
void BVHCellLocatorData::CellsThroughPoint(const double p[3], double tol, vtkDataSet* ds,
  vtkGenericCell* cell, bool firstOnly, std::vector<LineHit>& hits) const
{
  // A point on a cell lies on one of its triangles: their boxes suffice.
  std::vector<vtkIdType> candidates;
  this->CellsInLocalBox(
    Box(this->ToLocal(Vec3d(p[0] - tol, p[1] - tol, p[2] - tol)), this->ToLocal(Vec3d(p[0] + tol, p[1] + tol, p[2] + tol))),
    candidates);
  if (!ds || candidates.empty())
  {
    return;
  }
  CellWeights weights;
  double x[3] = { p[0], p[1], p[2] };
  for (const vtkIdType cellId : candidates)
  {
    ds->GetCell(cellId, cell);
    double t, cx[3], pc[3], d2;
    int sub;
    if (!cell->IntersectWithLine(x, x, tol, t, cx, pc, sub))
    {
      continue;
    }
    LineHit h;
    h.CellId = cellId;
    std::copy(x, x + 3, h.X);
    cell->EvaluatePosition(x, cx, h.SubId, h.PCoords, d2, weights.For(cell));
    hits.push_back(h);
    if (firstOnly)
    {
      return;
    }
  }
}

//------------------------------------------------------------------------------
/// The closest point of a triangle or general cell within radius of xw: a
/// triangle's as its own test found it (NeedsEvaluate: subId and inside
/// still to come from its cell), a general cell's as that cell reported it.
bool BVHCellLocatorData::ClosestPoint(
  const double xw[3], double radius, vtkDataSet* ds, QueryCell& cell, PointHit& out) const
{
  const Vec3d x = this->ToLocal(xw);
  const vtkIdType nTri = this->NumberOfTriangles();
  CellWeights weights;
  // Per general primitive, what EvaluatePosition said (read back for the winner).
  PointHit general;
  std::uint32_t generalPrim = core::kInvalidIndex;
  auto fn = [&](std::uint32_t prim, const Vec3d& p, core::PointHit<double>& cand) {
    if (static_cast<vtkIdType>(prim) < nTri)
    {
      const Vec3d v0 = this->Vertex(prim, 0);
      const Vec3d v1 = this->Vertex(prim, 1);
      const Vec3d v2 = this->Vertex(prim, 2);
      if (ZeroArea(v0, v1, v2))
      {
        return false;
      }
      cand.point = core::closestPointOnTriangle(p, v0, v1, v2);
      const Vec3d d = p - cand.point;
      cand.dist2 = glm::dot(d, d);
      return true;
    }
    const vtkIdType cellId = this->GenCell[prim - nTri];
    vtkGenericCell* c = cell.Get();
    ds->GetCell(cellId, c);
    double cp[3], pc[3], d2;
    int sub;
    double xx[3] = { xw[0], xw[1], xw[2] };
    const int r = c->EvaluatePosition(xx, cp, sub, pc, d2, weights.For(c));
    if (r < 0 || !(d2 >= 0.0) || !std::isfinite(d2))
    {
      return false;
    }
    if (r == 1 && c->GetCellDimension() == 3)
    {
      std::copy(xx, xx + 3, cp); // inside a 3D cell: x itself
    }
    cand.point = this->ToLocal(cp);
    cand.dist2 = d2 * this->Scale * this->Scale; // in local units, as the triangles'
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
  const double localRadius = this->ToLocalLength(radius);
  const int wide = core::closestPointWide(PickingScene{ this }, x, localRadius, fn, best);
  if (wide < 0)
  {
    this->EnsureTree(); // beyond the float walk's reach: the double walk
  }
  if (wide == 0 || (wide < 0 && !core::closestPoint(this->Tree, x, localRadius, fn, best)))
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
  out.Dist2 = best.dist2 / this->Scale / this->Scale;
  const Vec3d xWorld = this->ToWorld(best.point);
  for (int k = 0; k < 3; ++k)
  {
    out.X[k] = xWorld[k];
  }
  out.SubId = this->TriangleSubId(prim);
  const std::uint8_t flags = this->TriangleFlags(prim);
  out.NeedsEvaluate = (flags & EvaluateInCell) != 0;
  out.TrianglePointIds =
    (flags & WholeTriangle) ? this->TriIds.data() + 3 * static_cast<std::size_t>(prim) : nullptr;
  out.Inside = this->ProjectsInside(prim, x) ? 1 : 0;
  return true;
}

//------------------------------------------------------------------------------
bool BVHCellLocatorData::FindClosestPoint(
  const double xw[3], double radius, vtkDataSet* ds, vtkGenericCell* cell, PointHit& hit) const
{
  QueryCell qc(cell);
  if (!this->ClosestPoint(xw, radius, ds, qc, hit))
  {
    return false;
  }
  if (hit.NeedsEvaluate)
  {
    // subId and inside as the original cell reports them.
    vtkGenericCell* c = qc.Get();
    ds->GetCell(hit.CellId, c);
    double cp[3], d2, pc[3];
    CellWeights weights;
    const int r = c->EvaluatePosition(xw, cp, hit.SubId, pc, d2, weights.For(c));
    hit.Inside = r == 1 ? 1 : 0;
  }
  if (cell && hit.TrianglePointIds)
  {
    FillTriangleCell(cell, hit.TrianglePointIds, this->WorldCoords());
  }
  else if (cell)
  {
    ds->GetCell(hit.CellId, cell);
  }
  return true;
}

//------------------------------------------------------------------------------
vtkIdType BVHCellLocatorData::FindCell(
  const double xw[3], vtkDataSet* ds, vtkGenericCell* cell, double pcoords[3], double* weights) const
{
  const Vec3d x = this->ToLocal(xw);
  // VTK tests the cells' bounds in world coordinates: candidates are
  // gathered with its rounding there allowed, then tested on those bounds.
  double m = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    m = std::max({ m, std::abs(xw[k]), std::abs(this->Origin[k]) });
  }
  const Vec3d slack(this->ToLocalLength(3e-6 * m));
  const Box q(x - slack, x + slack);
  // Candidates (cell id, primitive) in cell id order: a VTK_TRIANGLE cell
  // is filled from its kept point ids, not looked up in the dataset; a cell
  // of several triangles comes from MultiCells, by its own bounds (a tilted
  // quad's bounds hold points no box of its two triangles holds). The list
  // is the thread's own, kept between queries (no allocation a query).
  thread_local std::vector<std::pair<vtkIdType, std::uint32_t>> candidates;
  candidates.clear();
  auto overlap = [&](std::uint32_t prim) {
    if (this->PrimitiveBox(prim).overlaps(q) && !this->InMultiTriangleCell(prim))
    {
      candidates.emplace_back(this->PrimitiveCell(prim), prim);
    }
  };
  if (!this->OnlyMultiTriangleCells || !ds)
  {
    PickingScene{ this }.forPrimitivesInBox(q, overlap);
  }
  thread_local std::vector<vtkIdType> multi;
  multi.clear();
  this->MultiCellsInLocalBox(ds, q, multi);
  for (const vtkIdType cellId : multi)
  {
    candidates.emplace_back(cellId, core::kInvalidIndex); // no triangle: the cell itself
  }
  std::sort(candidates.begin(), candidates.end());
  double xx[3] = { xw[0], xw[1], xw[2] };
  auto* grid = vtkUnstructuredGrid::SafeDownCast(ds);
  const double* coords = grid ? this->WorldCoords() : nullptr;
  CellWeights ownWeights;
  const vtkIdType nTri = this->NumberOfTriangles();
  for (size_t k = 0; k < candidates.size(); ++k)
  {
    const vtkIdType cellId = candidates[k].first;
    const std::uint32_t prim = candidates[k].second;
    if (k > 0 && candidates[k - 1].first == cellId)
    {
      continue; // another triangle of a cell already tested
    }
    if (static_cast<vtkIdType>(prim) < nTri && (this->TriangleFlags(prim) & WholeTriangle))
    {
      FillTriangleCell(cell, this->TriIds.data() + 3 * static_cast<std::size_t>(prim), this->WorldCoords());
    }
    else if (coords && TetraClearlyMisses(grid, cellId, coords, xx))
    {
      continue;
    }
    else
    {
      ds->GetCell(cellId, cell);
    }
    const double* b = cell->GetBounds();
    if (xx[0] < b[0] || xx[0] > b[1] || xx[1] < b[2] || xx[1] > b[3] || xx[2] < b[4] || xx[2] > b[5])
    {
      continue;
    }
    double cp[3], dist2;
    int sub;
    double* w = weights ? weights : ownWeights.For(cell);
    if (cell->EvaluatePosition(xx, cp, sub, pcoords, dist2, w) == 1)
    {
      return cellId;
    }
  }
  return -1;
}

} // namespace locator
} // namespace vtkrt
