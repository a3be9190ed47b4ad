// The oracle checks of LocatorTestUtils.h: each query kind of
// vtkBVHCellLocator against brute force over VTK's own cell tests, with
// VTK's locators counted (or, where exact, asserted) alongside.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"

#include "vtkCellLocator.h"
#include "vtkCellType.h"
#include "vtkModifiedBSPTree.h"
#include "vtkStaticCellLocator.h"
#include "vtkTriangle.h"

namespace locatortest
{
namespace
{
double SegLength(const Segment& s)
{
  return std::sqrt(vtkMath::Distance2BetweenPoints(s.P1, s.P2));
}

/// For a segment aimed exactly at a vertex or edge: whether the surface is
/// really crossed there (not just touched at a silhouette): four segments
/// offset sideways by 1e-7 of the diagonal all hit near the same t.
bool CrossesAt(vtkDataSet* ds, const Segment& s, double t)
{
  const double diag = Diagonal(ds);
  double d[3], u[3], v[3];
  vtkMath::Subtract(s.P2, s.P1, d);
  vtkMath::Perpendiculars(d, u, v, 0.0);
  const double len = std::sqrt(vtkMath::Dot(d, d));
  for (int k = 0; k < 4; ++k)
  {
    const double* w = (k < 2) ? u : v;
    const double sign = (k % 2) ? -1.0 : 1.0;
    double a[3], b[3];
    for (int i = 0; i < 3; ++i)
    {
      a[i] = s.P1[i] + sign * 1e-7 * diag * w[i];
      b[i] = s.P2[i] + sign * 1e-7 * diag * w[i];
    }
    const RefHit h = BruteForceHit(ds, a, b, 0.0);
    if (!h.Hit || std::abs(h.T - t) * len > 1e-5 * diag)
    {
      return false;
    }
  }
  return true;
}

struct PeerStats
{
  const char* Name;
  int Misses = 0;   // the segment meets the surface, the peer reports nothing
  int Wrong = 0;    // the peer's hit is not the nearest one
  int Spurious = 0; // the peer reports a hit where there is none
};
} // namespace

void CheckIntersectWithLine(vtkDataSet* ds, vtkBVHCellLocator* bvh,
  std::vector<vtkAbstractCellLocator*> peers, const std::vector<Segment>& segments,
  double refTol, const char* name)
{
  const double diag = Diagonal(ds);
  std::vector<PeerStats> stats;
  for (auto* p : peers)
  {
    stats.push_back({ p->GetClassName() });
  }
  int ourMisses = 0, ourWrong = 0, ourSpurious = 0, hits = 0, aimed = 0, touches = 0;
  vtkNew<vtkGenericCell> cell;
  for (const Segment& s : segments)
  {
    const RefHit ref = BruteForceHit(ds, s.P1, s.P2, refTol);
    const double len = SegLength(s);
    double t = -1, x[3], pc[3];
    int sub = -1;
    vtkIdType cellId = -1;
    const int hit = bvh->IntersectWithLine(s.P1, s.P2, 0.0, t, x, pc, sub, cellId, cell);
    aimed += s.Aimed ? 1 : 0;
    // A segment that only touches the surface (silhouette vertex or edge)
    // may or may not count as a hit; everything else must agree.
    const bool mustHit = ref.Hit && (!s.Aimed || CrossesAt(ds, s, ref.T));
    if (ref.Hit && !mustHit)
    {
      ++touches;
      if (hit)
      {
        LT_CHECK(std::abs(t - ref.T) * len <= 1e-8 * diag);
      }
    }
    else if (ref.Hit)
    {
      ++hits;
      if (!hit)
      {
        ++ourMisses;
        double n[3] = { 0, 0, 0 }, d[3];
        vtkNew<vtkGenericCell> rc;
        ds->GetCell(ref.CellId, rc);
        if (rc->GetCellType() == VTK_TRIANGLE)
        {
          double a[3], b[3], c[3];
          rc->GetPoints()->GetPoint(0, a);
          rc->GetPoints()->GetPoint(1, b);
          rc->GetPoints()->GetPoint(2, c);
          vtkTriangle::ComputeNormal(a, b, c, n);
        }
        vtkMath::Subtract(s.P2, s.P1, d);
        vtkMath::Normalize(d);
        std::cerr << name << ": missed (aimed " << s.Aimed << ") ref cell " << ref.CellId << " t "
                  << ref.T << " cos(normal, dir) " << vtkMath::Dot(n, d) << std::endl;
      }
      else
      {
        if (std::abs(t - ref.T) * len > 1e-8 * diag)
        {
          ++ourWrong;
          std::cerr << name << ": t " << t << " vs reference " << ref.T << std::endl;
        }
        // Our point lies on our cell; our cell is the reference's, or the
        // reference cell passes through the same point (a tie on an edge).
        LT_CHECK(DistanceToCell2(ds, cellId, x) <= 1e-16 * diag * diag);
        LT_CHECK(cellId == ref.CellId || DistanceToCell2(ds, ref.CellId, x) <= 1e-16 * diag * diag);
        LT_CHECK(SameCellPoints(ds, cellId, cell));
        // pcoords/subId locate x in the returned cell.
        std::vector<double> w(static_cast<size_t>(cell->GetNumberOfPoints()) + 1);
        double xe[3];
        cell->EvaluateLocation(sub, pc, xe, w.data());
        // (vtkTriangleStrip::EvaluateLocation reorders odd triangles, unlike
        // its IntersectWithLine and EvaluatePosition: strips are checked
        // against IntersectWithLine instead.)
        LT_CHECK_MSG(cell->GetCellType() == VTK_TRIANGLE_STRIP ||
            std::sqrt(vtkMath::Distance2BetweenPoints(xe, x)) <= 1e-8 * diag,
          name << " pcoords do not map back to x in cell " << cellId << " sub " << sub << " pc "
               << pc[0] << " " << pc[1] << " " << pc[2] << " type " << cell->GetCellType()
               << " npts " << cell->GetNumberOfPoints() << " d "
               << std::sqrt(vtkMath::Distance2BetweenPoints(xe, x)));
        for (int k = 0; k < 3; ++k)
        {
          LT_CHECK(std::abs(x[k] - (s.P1[k] + t * (s.P2[k] - s.P1[k]))) <= 1e-9 * diag);
        }
      }
    }
    else if (hit)
    {
      ++ourSpurious;
      double t2, x2[3], pc2[3];
      int sub2;
      const int again = cell->IntersectWithLine(s.P1, s.P2, 1e-9 * diag, t2, x2, pc2, sub2);
      std::cerr << name << ": spurious hit on cell " << cellId << " t " << t << " d2 "
                << DistanceToCell2(ds, cellId, x) << " cell says " << again << " t " << t2 << std::endl;
    }
    for (size_t i = 0; i < peers.size(); ++i)
    {
      double pt = -1, px[3], ppc[3];
      int psub;
      vtkIdType pcell = -1;
      const int phit = peers[i]->IntersectWithLine(s.P1, s.P2, 0.0, pt, px, ppc, psub, pcell);
      if (ref.Hit && !mustHit)
      {
        continue;
      }
      if (ref.Hit && !phit)
      {
        ++stats[i].Misses;
      }
      else if (ref.Hit && std::abs(pt - ref.T) * len > 1e-8 * diag)
      {
        ++stats[i].Wrong;
      }
      else if (!ref.Hit && phit)
      {
        ++stats[i].Spurious;
      }
    }
  }
  std::cout << name << ": " << segments.size() << " segments (" << aimed
            << " aimed at shared vertices/edges), " << hits << " cross the surface, " << touches
            << " only touch it (silhouette, not counted)" << std::endl;
  std::cout << "  vtkBVHCellLocator: misses " << ourMisses << ", wrong " << ourWrong
            << ", spurious " << ourSpurious << std::endl;
  for (const auto& st : stats)
  {
    std::cout << "  " << st.Name << ": misses " << st.Misses << ", wrong " << st.Wrong
              << ", spurious " << st.Spurious << std::endl;
  }
  LT_CHECK(hits > 0);
  LT_CHECK(ourMisses == 0);
  LT_CHECK(ourWrong == 0);
  LT_CHECK(ourSpurious == 0);
}

void CheckClosestPoint(vtkDataSet* ds, vtkBVHCellLocator* bvh, vtkStaticCellLocator* st,
  vtkCellLocator* cl, int count, bool bruteForce, const char* name)
{
  Random rng(7);
  double b[6];
  ds->GetBounds(b);
  const double diag = Diagonal(ds);
  const double eps2 = 1e-14 * diag * diag;
  int checked = 0;
  vtkNew<vtkGenericCell> cell;
  for (int i = 0; i < count; ++i)
  {
    double x[3];
    for (int k = 0; k < 3; ++k)
    {
      const double c = 0.5 * (b[2 * k] + b[2 * k + 1]), h = 0.7 * (b[2 * k + 1] - b[2 * k]);
      x[k] = rng.Next(c - h, c + h);
    }
    double cp[3], d2 = -1;
    vtkIdType cellId = -1;
    int sub = -1;
    bvh->FindClosestPoint(x, cp, cell, cellId, sub, d2);
    LT_CHECK(cellId >= 0);
    if (cellId < 0)
    {
      continue;
    }
    LT_CHECK(SameCellPoints(ds, cellId, cell));
    LT_CHECK(std::abs(vtkMath::Distance2BetweenPoints(x, cp) - d2) <= eps2 + 1e-9 * d2);
    LT_CHECK(std::abs(DistanceToCell2(ds, cellId, x) - d2) <= eps2 + 1e-9 * d2);

    double refD2;
    if (bruteForce)
    {
      vtkIdType refCell;
      refD2 = BruteForceClosest(ds, x, refCell);
    }
    else
    {
      double scp[3];
      vtkIdType sc;
      int ssub;
      st->FindClosestPoint(x, scp, sc, ssub, refD2);
    }
    LT_CHECK_MSG(std::abs(d2 - refD2) <= eps2 + 1e-9 * refD2, name << " closest d2 " << d2 << " vs " << refD2);
    double ccp[3], cd2;
    vtkIdType cc;
    int csub;
    cl->FindClosestPoint(x, ccp, cc, csub, cd2);
    LT_CHECK(std::abs(d2 - cd2) <= eps2 + 1e-9 * cd2);

    // The overload without a cell, and the radius forms around the answer.
    double cp2[3], d22;
    vtkIdType c2;
    int s2;
    bvh->FindClosestPoint(x, cp2, c2, s2, d22);
    LT_CHECK(d22 == d2);
    const double r = std::sqrt(d2);
    int inside = -1;
    LT_CHECK(bvh->FindClosestPointWithinRadius(x, r * 1.001 + 1e-12 * diag, cp2, cell, c2, s2, d22, inside) == 1);
    LT_CHECK(d22 == d2);
    LT_CHECK(inside == 0 || inside == 1);
    LT_CHECK(bvh->FindClosestPointWithinRadius(x, r * 1.001 + 1e-12 * diag, cp2, c2, s2, d22) == 1);
    LT_CHECK(bvh->FindClosestPointWithinRadius(x, r * 1.001 + 1e-12 * diag, cp2, cell, c2, s2, d22) == 1);
    if (r > 1e-6 * diag)
    {
      LT_CHECK(bvh->FindClosestPointWithinRadius(x, r * 0.999, cp2, c2, s2, d22) == 0);
      LT_CHECK(c2 == -1);
    }
    ++checked;
  }
  std::cout << name << ": " << checked << " closest-point queries agree" << std::endl;
}

void CheckBoxAndLineLists(vtkDataSet* ds, vtkBVHCellLocator* bvh, vtkStaticCellLocator* st,
  bool cellBoxesArePrimitiveBoxes, const char* name)
{
  Random rng(11);
  double b[6];
  ds->GetBounds(b);
  const double diag = Diagonal(ds);
  vtkNew<vtkIdList> ours, theirs;
  for (int i = 0; i < 40; ++i)
  {
    double box[6];
    for (int k = 0; k < 3; ++k)
    {
      const double c = rng.Next(b[2 * k], b[2 * k + 1]), h = rng.Next(0.0, 0.15) * diag;
      box[2 * k] = c - h;
      box[2 * k + 1] = c + h;
    }
    bvh->FindCellsWithinBounds(box, ours);
    const std::vector<vtkIdType> ref = BruteForceCellsInBox(ds, box);
    if (cellBoxesArePrimitiveBoxes)
    {
      LT_CHECK_MSG(ToVector(ours) == ref, name << " FindCellsWithinBounds differs from brute force");
    }
    else
    {
      LT_CHECK(IsSubset(ToVector(ours), ref));
    }
    st->FindCellsWithinBounds(box, theirs);
    LT_CHECK(IsSubset(ToVector(ours), ToVector(theirs)));
  }
  const std::vector<Segment> segs = RandomSegments(ds, 40, rng);
  for (const Segment& s : segs)
  {
    for (double tol : { 0.0, 1e-3 * diag })
    {
      bvh->FindCellsAlongLine(s.P1, s.P2, tol, ours);
      const std::vector<vtkIdType> ref = BruteForceCellsAlongLine(ds, s.P1, s.P2, tol);
      if (cellBoxesArePrimitiveBoxes)
      {
        LT_CHECK_MSG(ToVector(ours) == ref, name << " FindCellsAlongLine differs from brute force");
      }
      else
      {
        LT_CHECK(IsSubset(ToVector(ours), ref));
      }
      // Every cell actually hit is listed.
      std::vector<vtkIdType> hitCells;
      for (const auto& h : BruteForceAllHits(ds, s.P1, s.P2, tol))
      {
        hitCells.push_back(h.first);
      }
      LT_CHECK(IsSubset(hitCells, ToVector(ours)));
    }
  }
  std::cout << name << ": FindCellsWithinBounds / FindCellsAlongLine agree" << std::endl;
}

void CheckAllHits(vtkDataSet* ds, vtkBVHCellLocator* bvh, vtkModifiedBSPTree* bsp, double refTol,
  const char* name)
{
  Random rng(13);
  const double diag = Diagonal(ds);
  const std::vector<Segment> segs = RandomSegments(ds, 40, rng);
  vtkNew<vtkPoints> pts, bspPts;
  pts->SetDataTypeToDouble(); // the hit points are exact in double
  vtkNew<vtkIdList> ids, bspIds;
  int bspDiffers = 0, total = 0;
  for (const Segment& s : segs)
  {
    const int r = bvh->IntersectWithLine(s.P1, s.P2, pts, ids);
    const auto ref = BruteForceAllHits(ds, s.P1, s.P2, refTol);
    total += static_cast<int>(ref.size());
    LT_CHECK((r != 0) == !ref.empty());
    LT_CHECK(ids->GetNumberOfIds() == static_cast<vtkIdType>(ref.size()));
    LT_CHECK(pts->GetNumberOfPoints() == ids->GetNumberOfIds());
    double lastT = -1.0;
    const double len = SegLength(s);
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
    {
      const vtkIdType c = ids->GetId(i);
      LT_CHECK(ref.count(c) == 1);
      double x[3];
      pts->GetPoint(i, x);
      const double t = std::sqrt(vtkMath::Distance2BetweenPoints(s.P1, x)) / len;
      LT_CHECK(t >= lastT - 1e-12);
      lastT = t;
      // At the cell's own crossing (a hexahedron's IntersectWithLine works on
      // triangulated faces, so x need not satisfy its EvaluatePosition).
      LT_CHECK(ref.count(c) == 0 || std::abs(t - ref.at(c)) * len <= 1e-9 * diag);
    }
    bsp->IntersectWithLine(s.P1, s.P2, 0.0, bspPts, bspIds);
    std::vector<vtkIdType> a = ToVector(ids), b = ToVector(bspIds);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    bspDiffers += a != b ? 1 : 0;
  }
  std::cout << name << ": all-hits agree with brute force on " << segs.size() << " segments ("
            << total << " crossings); vtkModifiedBSPTree's list differs on " << bspDiffers
            << std::endl;
}

vtkSmartPointer<vtkPolyData> Transformed(vtkPolyData* pd, double scale, const double offset[3])
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(pd);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(pd->GetNumberOfPoints());
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    pts->SetPoint(i, p[0] * scale + offset[0], p[1] * scale + offset[1], p[2] * scale + offset[2]);
  }
  out->SetPoints(pts);
  return out;
}
} // namespace locatortest
