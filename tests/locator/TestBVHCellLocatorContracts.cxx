// VTK-contract tests from the adversarial review (issue 24): cells with
// out-of-range point ids, concurrent first queries of an unbuilt locator,
// zero-length segments, FindCell on surfaces, cells VTK cannot read (points
// moved or replaced under UseExistingSearchStructure:
// TestBVHCellLocatorChangedPoints.cxx).
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"
#include "vtkCellLocator.h"
#include "vtkGenericCell.h"
#include "vtkSphereSource.h"
#include "vtkStaticCellLocator.h"
#include "vtkSurfaceTriangulation.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <thread>

using namespace locatortest;

namespace
{
/// Whether `ids` holds any id of [first, first + count).
bool HoldsAny(vtkIdList* ids, vtkIdType first, vtkIdType count)
{
  for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
  {
    if (ids->GetId(i) >= first && ids->GetId(i) < first + count)
    {
      return true;
    }
  }
  return false;
}

/// Exactly one warning, naming `count` skipped cells.
bool OneSkipWarning(const ErrorCatcher* catcher, vtkIdType count)
{
  return catcher->Errors.empty() && catcher->Warnings.size() == 1 &&
    catcher->Warnings[0].find(std::to_string(count) + " cell(s)") != std::string::npos &&
    catcher->Warnings[0].find("skipped") != std::string::npos;
}
} // namespace

/// Polydata cells naming a point id >= the number of points or negative
/// (triangles, a quad, a line, a vertex, a strip) are skipped with one
/// warning a build and never returned; the valid cells answer as without them.
int TestContractBadPointIdsPolyData()
{
  auto base = MakeBumpySphere(20);
  const vtkIdType nBase = base->GetNumberOfCells();
  const vtkIdType nPts = base->GetNumberOfPoints();
  vtkNew<vtkPolyData> pd;
  pd->DeepCopy(base);
  // Cell ids: verts, lines, polys, strips. The sphere has polys only; the
  // bad verts and lines come first, shifting its cell ids by 2.
  vtkNew<vtkCellArray> verts, lines, strips;
  const vtkIdType badVert[1] = { -7 };
  const vtkIdType badLine[2] = { 0, nPts + 1000 };
  verts->InsertNextCell(1, badVert);
  lines->InsertNextCell(2, badLine);
  const vtkIdType badTriHigh[3] = { 0, 1, nPts };
  const vtkIdType badTriNeg[3] = { 0, -1, 2 };
  const vtkIdType badQuad[4] = { 0, 1, 2, -100000 };
  pd->GetPolys()->InsertNextCell(3, badTriHigh);
  pd->GetPolys()->InsertNextCell(3, badTriNeg);
  pd->GetPolys()->InsertNextCell(4, badQuad);
  const vtkIdType badStrip[4] = { 0, 1, 2, nPts + 3 };
  strips->InsertNextCell(4, badStrip);
  pd->SetVerts(verts);
  pd->SetLines(lines);
  pd->SetStrips(strips);
  const vtkIdType shift = 2;
  const vtkIdType badPolysFirst = shift + nBase, nBad = 6;

  vtkNew<ErrorCatcher> catcher;
  vtkNew<vtkBVHCellLocator> loc;
  catcher->Watch(loc);
  loc->SetDataSet(pd);
  loc->CacheCellBoundsOn();
  loc->BuildLocator();
  LT_CHECK_MSG(OneSkipWarning(catcher, nBad),
    "warnings: " << catcher->Warnings.size() << (catcher->Warnings.empty() ? "" : catcher->Warnings[0]));
  LT_CHECK(loc->GetNumberOfPrimitives() > 0);
  vtkNew<vtkBVHCellLocator> clean;
  clean->SetDataSet(base);
  clean->BuildLocator();

  auto isBad = [&](vtkIdType c) { return c < shift || c >= badPolysFirst; };
  Random rng(241);
  vtkNew<vtkGenericCell> cell;
  int hits = 0;
  for (const auto& s : RandomSegments(base, 300, rng))
  {
    double t1, t2, x[3], pc[3];
    int sub;
    vtkIdType c1, c2;
    const int h1 = loc->IntersectWithLine(s.P1, s.P2, 0.0, t1, x, pc, sub, c1, cell);
    const int h2 = clean->IntersectWithLine(s.P1, s.P2, 0.0, t2, x, pc, sub, c2, cell);
    LT_CHECK(h1 == h2);
    if (h1)
    {
      ++hits;
      LT_CHECK(!isBad(c1) && c1 - shift == c2 && t1 == t2);
    }
    double cp[3], d2a, d2b;
    loc->FindClosestPoint(s.P1, cp, c1, sub, d2a);
    clean->FindClosestPoint(s.P1, cp, c2, sub, d2b);
    LT_CHECK(!isBad(c1) && d2a == d2b);
    vtkNew<vtkIdList> ids;
    loc->FindCellsAlongLine(s.P1, s.P2, 0.01, ids);
    LT_CHECK(!HoldsAny(ids, 0, shift) && !HoldsAny(ids, badPolysFirst, nBad));
  }
  LT_CHECK(hits > 0);
  vtkNew<vtkIdList> all;
  double everything[6] = { -1e30, 1e30, -1e30, 1e30, -1e30, 1e30 };
  loc->FindCellsWithinBounds(everything, all);
  LT_CHECK(all->GetNumberOfIds() == nBase);
  LT_CHECK(!HoldsAny(all, 0, shift) && !HoldsAny(all, badPolysFirst, nBad));

  // One warning per build: queries add none, a rebuild adds one.
  LT_CHECK(catcher->Warnings.size() == 1);
  loc->ForceBuildLocator();
  LT_CHECK(catcher->Warnings.size() == 2);
  return 0;
}

/// An unstructured grid with a tetrahedron and a triangle, valid, and a
/// tetrahedron and a triangle naming missing points: the valid ones are
/// found, the others skipped with one warning.
int TestContractBadPointIdsUnstructuredGrid()
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  const double xyz[7][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, 0, 2 },
    { 1, 0, 2 }, { 0, 1, 2 } };
  for (const auto& p : xyz)
  {
    pts->InsertNextPoint(p);
  }
  vtkNew<vtkUnstructuredGrid> ug;
  ug->SetPoints(pts);
  const vtkIdType badTet[4] = { 0, 1, 2, 99 };
  const vtkIdType badTri[3] = { 4, 5, -1 };
  const vtkIdType tet[4] = { 0, 1, 2, 3 };
  const vtkIdType tri[3] = { 4, 5, 6 };
  ug->InsertNextCell(VTK_TETRA, 4, badTet); // 0
  ug->InsertNextCell(VTK_TETRA, 4, tet);    // 1
  ug->InsertNextCell(VTK_TRIANGLE, 3, badTri); // 2
  ug->InsertNextCell(VTK_TRIANGLE, 3, tri); // 3

  vtkNew<ErrorCatcher> catcher;
  vtkNew<vtkBVHCellLocator> loc;
  catcher->Watch(loc);
  loc->SetDataSet(ug);
  loc->BuildLocator();
  LT_CHECK(OneSkipWarning(catcher, 2));

  double inTet[3] = { 0.1, 0.1, 0.1 };
  LT_CHECK(loc->FindCell(inTet) == 1);
  double outside[3] = { 5, 5, 5 };
  LT_CHECK(loc->FindCell(outside) == -1);
  double p1[3] = { 0.2, 0.2, 5 }, p2[3] = { 0.2, 0.2, -5 };
  double t, x[3], pc[3];
  int sub;
  vtkIdType cellId;
  LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t, x, pc, sub, cellId) == 1);
  LT_CHECK(cellId == 3 && std::abs(x[2] - 2.0) < 1e-12);
  vtkNew<vtkPoints> hitPts;
  vtkNew<vtkIdList> hitIds;
  loc->IntersectWithLine(p1, p2, 0.0, hitPts, hitIds, nullptr);
  LT_CHECK(hitIds->GetNumberOfIds() >= 2 && hitIds->GetId(0) == 3 && hitIds->GetId(1) == 1);
  LT_CHECK(!HoldsAny(hitIds, 0, 1) && !HoldsAny(hitIds, 2, 1));
  double cp[3], d2;
  double above[3] = { 0.2, 0.2, 3 };
  loc->FindClosestPoint(above, cp, cellId, sub, d2);
  LT_CHECK(cellId == 3 && std::abs(d2 - 1.0) < 1e-12);
  vtkNew<vtkIdList> all;
  double everything[6] = { -100, 100, -100, 100, -100, 100 };
  loc->FindCellsWithinBounds(everything, all);
  LT_CHECK(all->GetNumberOfIds() == 2 && all->GetId(0) == 1 && all->GetId(1) == 3);
  LT_CHECK(catcher->Warnings.size() == 1);
  return 0;
}

namespace
{
struct ThreadAnswer
{
  int Hit = 0;
  double T = -1.0;
  vtkIdType HitCell = -1;
  vtkIdType ClosestCell = -1;
  double Dist2 = -1.0;
};

ThreadAnswer Ask(vtkBVHCellLocator* loc, const Segment& s, vtkGenericCell* cell)
{
  ThreadAnswer a;
  double x[3], pc[3], cp[3];
  int sub;
  a.Hit = loc->IntersectWithLine(s.P1, s.P2, 0.0, a.T, x, pc, sub, a.HitCell, cell);
  loc->FindClosestPoint(s.P1, cp, cell, a.ClosestCell, sub, a.Dist2);
  return a;
}

/// Queries loc from `threads` std::threads released at once (the first
/// query of each races the others into the build); mismatches against ref.
int RaceQueries(vtkBVHCellLocator* loc, const std::vector<Segment>& segs,
  const std::vector<ThreadAnswer>& ref, int threads)
{
  std::vector<ThreadAnswer> got(segs.size());
  std::atomic<int> waiting{ threads };
  std::vector<std::thread> workers;
  for (int w = 0; w < threads; ++w)
  {
    workers.emplace_back([&, w]() {
      vtkNew<vtkGenericCell> cell;
      --waiting;
      while (waiting.load() > 0)
      {
      }
      for (size_t i = w; i < segs.size(); i += threads)
      {
        got[i] = Ask(loc, segs[i], cell);
      }
    });
  }
  for (auto& th : workers)
  {
    th.join();
  }
  int mismatches = 0;
  for (size_t i = 0; i < segs.size(); ++i)
  {
    const ThreadAnswer& a = got[i];
    const ThreadAnswer& b = ref[i];
    mismatches += (a.Hit != b.Hit || a.T != b.T || a.HitCell != b.HitCell ||
                    a.ClosestCell != b.ClosestCell || a.Dist2 != b.Dist2)
      ? 1
      : 0;
  }
  return mismatches;
}

/// `threads` fresh locators on pd, each first queried from its own thread,
/// all released at once: their builds race into the polydata's shared
/// triangulation (vtkSurfaceTriangulation::Get); mismatches against ref.
int RaceLocators(vtkPolyData* pd, const std::vector<Segment>& segs,
  const std::vector<ThreadAnswer>& ref, int threads)
{
  std::vector<vtkSmartPointer<vtkBVHCellLocator>> locators;
  for (int w = 0; w < threads; ++w)
  {
    locators.push_back(vtkSmartPointer<vtkBVHCellLocator>::New());
    locators.back()->SetDataSet(pd);
  }
  std::vector<ThreadAnswer> got(segs.size());
  std::atomic<int> waiting{ threads };
  std::vector<std::thread> workers;
  for (int w = 0; w < threads; ++w)
  {
    workers.emplace_back([&, w]() {
      vtkNew<vtkGenericCell> cell;
      --waiting;
      while (waiting.load() > 0)
      {
      }
      for (size_t i = w; i < segs.size(); i += threads)
      {
        got[i] = Ask(locators[w], segs[i], cell);
      }
    });
  }
  for (auto& th : workers)
  {
    th.join();
  }
  int mismatches = 0;
  for (size_t i = 0; i < segs.size(); ++i)
  {
    mismatches += (got[i].Hit != ref[i].Hit || got[i].T != ref[i].T ||
                    got[i].HitCell != ref[i].HitCell || got[i].ClosestCell != ref[i].ClosestCell ||
                    got[i].Dist2 != ref[i].Dist2)
      ? 1
      : 0;
  }
  return mismatches;
}
} // namespace

/// A fresh, unbuilt locator (and one whose dataset was modified since its
/// build) queried first from 4 threads at once: one builds, the others
/// wait for the published tree; every answer is the single-threaded one.
/// And 4 fresh locators on one modified polydata built from 4 threads at
/// once, sharing its triangulation.
int TestContractFreshLocatorThreads()
{
  auto pd = MakeBumpySphere(60);
  Random rng(311);
  const std::vector<Segment> segs = RandomSegments(pd, 400, rng);
  vtkNew<vtkBVHCellLocator> refLoc;
  refLoc->SetDataSet(pd);
  refLoc->BuildLocator();
  std::vector<ThreadAnswer> ref;
  vtkNew<vtkGenericCell> cell;
  for (const auto& s : segs)
  {
    ref.push_back(Ask(refLoc, s, cell));
  }
  int mismatches = 0, staleMismatches = 0, sharedMismatches = 0, sharedTriangulations = 0;
  for (int round = 0; round < 8; ++round)
  {
    vtkNew<vtkBVHCellLocator> loc;
    loc->SetDataSet(pd);
    if (round % 2)
    {
      loc->PickingTreeOnDemandOff();
    }
    mismatches += RaceQueries(loc, segs, ref, 4);
    // Stale: the first queries after a Modified() race into the rebuild.
    pd->GetPoints()->Modified();
    staleMismatches += RaceQueries(loc, segs, ref, 4);
    pd->GetPoints()->Modified();
    const vtkIdType made = vtkSurfaceTriangulation::GetNumberOfTriangulations();
    sharedMismatches += RaceLocators(pd, segs, ref, 4);
    sharedTriangulations += static_cast<int>(vtkSurfaceTriangulation::GetNumberOfTriangulations() - made);
  }
  std::cout << "fresh locators, 4 threads: " << mismatches << " mismatches, after Modified(): "
            << staleMismatches << ", 4 locators on one polydata: " << sharedMismatches << ", over 8 x "
            << segs.size() << " queries each" << std::endl;
  LT_CHECK(mismatches == 0);
  LT_CHECK(staleMismatches == 0);
  LT_CHECK(sharedMismatches == 0);
  LT_CHECK(sharedTriangulations == 8); // one a round: the four locators share it
  return 0;
}

namespace
{
bool BoundsHold(const double b[6], const double p[3], double tol)
{
  return b[0] - tol <= p[0] && p[0] <= b[1] + tol && b[2] - tol <= p[1] && p[1] <= b[3] + tol &&
    b[4] - tol <= p[2] && p[2] <= b[5] + tol;
}

/// How many cells' bounds, grown by tol, hold p (brute force).
vtkIdType CellsWithBoundsHolding(vtkDataSet* ds, const double p[3], double tol)
{
  vtkIdType count = 0;
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    double b[6];
    ds->GetCellBounds(c, b);
    count += BoundsHold(b, p, tol) ? 1 : 0;
  }
  return count;
}
} // namespace

/// A zero-length segment (p1 == p2) is a point: it hits a cell when the
/// cell's own IntersectWithLine(p, p) says so (VTK's triangles do when p
/// lies on them), as vtkStaticCellLocator answers; FindCellsAlongLine gives
/// the cells whose bounds, grown by tol, hold p.
int TestContractZeroLengthSegment()
{
  // A flat triangulated grid in z = 0 (dyadic coordinates: points on it lie
  // exactly in the plane), and a bumpy sphere whose vertices lie on their cells.
  vtkNew<vtkPoints> gridPts;
  gridPts->SetDataTypeToDouble();
  const int n = 16;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      gridPts->InsertNextPoint(i * 0.25, j * 0.25, 0.0);
    }
  }
  vtkNew<vtkCellArray> gridTris;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const vtkIdType a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      const vtkIdType t1[3] = { a, b, d }, t2[3] = { a, d, c };
      gridTris->InsertNextCell(3, t1);
      gridTris->InsertNextCell(3, t2);
    }
  }
  vtkNew<vtkPolyData> grid;
  grid->SetPoints(gridPts);
  grid->SetPolys(gridTris);
  auto sphere = MakeBumpySphere(24);

  Random rng(523);
  int onHits = 0, compared = 0;
  for (vtkPolyData* pd : { grid.Get(), sphere.Get() })
  {
    vtkNew<vtkBVHCellLocator> loc;
    loc->SetDataSet(pd);
    loc->BuildLocator();
    vtkNew<vtkStaticCellLocator> vtkLoc;
    vtkLoc->SetDataSet(pd);
    vtkLoc->BuildLocator();
    std::vector<std::array<double, 3>> points;
    for (int k = 0; k < 200; ++k)
    {
      const vtkIdType v = static_cast<vtkIdType>(rng.Next(0, pd->GetNumberOfPoints() - 1e-9));
      std::array<double, 3> p;
      pd->GetPoint(v, p.data());
      if (pd == grid.Get() && k % 2 == 0)
      {
        // Dyadic points inside the grid's cells, on and just off the plane.
        p = { std::floor(rng.Next(0, 4 * 64)) / 64.0 + 1.0 / 128.0,
          std::floor(rng.Next(0, 4 * 64)) / 64.0 + 1.0 / 256.0, k % 4 == 0 ? 0.0 : 1e-9 };
      }
      points.push_back(p);
    }
    vtkNew<vtkGenericCell> cell, vtkCell;
    for (auto& p : points)
    {
      for (double tol : { 0.0, 1e-6 })
      {
        double t = -1, x[3], pc[3], vt, vx[3], vpc[3];
        int sub, vsub;
        vtkIdType cellId, vtkCellId;
        const int hit = loc->IntersectWithLine(p.data(), p.data(), tol, t, x, pc, sub, cellId, cell);
        const int vtkHit =
          vtkLoc->IntersectWithLine(p.data(), p.data(), tol, vt, vx, vpc, vsub, vtkCellId, vtkCell);
        ++compared;
        LT_CHECK_MSG(hit == vtkHit, "p " << p[0] << " " << p[1] << " " << p[2] << " ours " << hit);
        vtkNew<vtkIdList> along, vtkAlong;
        loc->FindCellsAlongLine(p.data(), p.data(), tol, along);
        vtkLoc->FindCellsAlongLine(p.data(), p.data(), tol, vtkAlong);
        LT_CHECK(along->GetNumberOfIds() == CellsWithBoundsHolding(pd, p.data(), tol));
        for (vtkIdType i = 0; i < along->GetNumberOfIds(); ++i)
        {
          double b[6];
          pd->GetCellBounds(along->GetId(i), b);
          LT_CHECK(BoundsHold(b, p.data(), tol));
        }
        if (!hit)
        {
          continue;
        }
        ++onHits;
        LT_CHECK(vtkAlong->GetNumberOfIds() > 0);
        LT_CHECK(t == 0.0 && x[0] == p[0] && x[1] == p[1] && x[2] == p[2]);
        LT_CHECK(along->IsId(cellId) >= 0);
        // The cell answered is one p lies on, by VTK's own test; the filled
        // cell is it.
        vtkNew<vtkGenericCell> check;
        pd->GetCell(cellId, check);
        double ct, cx[3], cpc[3];
        int csub;
        LT_CHECK(check->IntersectWithLine(p.data(), p.data(), tol, ct, cx, cpc, csub) == 1);
        LT_CHECK(cell->GetCellType() == VTK_TRIANGLE && cell->GetPointId(0) == check->GetPointId(0));
        LT_CHECK(std::abs(pc[0] - cpc[0]) < 1e-12 && std::abs(pc[1] - cpc[1]) < 1e-12);
        vtkNew<vtkPoints> hitPts;
        vtkNew<vtkIdList> hitIds;
        LT_CHECK(loc->IntersectWithLine(p.data(), p.data(), hitPts, hitIds) == 1);
        LT_CHECK(hitIds->GetNumberOfIds() >= 1 && hitIds->IsId(cellId) >= 0);
      }
    }
  }
  std::cout << "zero-length segments: " << onHits << " hits of " << compared
            << " queries, all as vtkStaticCellLocator" << std::endl;
  LT_CHECK(onHits > 100);
  return 0;
}

/// Zero-area triangles (collinear points, a repeated point) are never a
/// closest cell, as for VTK's locators (vtkTriangle::EvaluatePosition fails
/// on them); the nearest real triangle is.
int TestContractZeroAreaClosestPoint()
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  const double xyz[7][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 5, 5, 0 }, { 6, 6, 0 },
    { 7, 7, 0 }, { 5, 7, 0 } };
  for (const auto& p : xyz)
  {
    pts->InsertNextPoint(p);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType tri[3] = { 0, 1, 2 }, collinear[3] = { 3, 4, 5 }, repeated[3] = { 6, 6, 4 };
  polys->InsertNextCell(3, tri);
  polys->InsertNextCell(3, collinear);
  polys->InsertNextCell(3, repeated);
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(pd);
  loc->BuildLocator();
  vtkNew<vtkStaticCellLocator> vtkLoc;
  vtkLoc->SetDataSet(pd);
  vtkLoc->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  for (const auto& q : { std::array<double, 3>{ 6, 6, 0.5 }, std::array<double, 3>{ 5.5, 6.5, 0 },
         std::array<double, 3>{ 0.2, 0.2, 1 } })
  {
    double x[3] = { q[0], q[1], q[2] }, cp[3], vcp[3], d2, vd2;
    vtkIdType c, vc;
    int sub, vsub, inside = -1, vinside = -1;
    LT_CHECK(loc->FindClosestPointWithinRadius(x, 100, cp, cell, c, sub, d2, inside) == 1);
    LT_CHECK(vtkLoc->FindClosestPointWithinRadius(x, 100, vcp, cell, vc, vsub, vd2, vinside) == 1);
    LT_CHECK_MSG(c == vc && c == 0, "ours " << c << " VTK " << vc);
    LT_CHECK(std::abs(d2 - vd2) < 1e-12 && inside == vinside);
    loc->FindClosestPoint(x, cp, c, sub, d2);
    LT_CHECK(c == 0 && std::abs(d2 - vd2) < 1e-12);
  }
  return 0;
}

/// FindCell answers as VTK 9.1's locators, which do not use tol2: the
/// lowest-id cell whose bounds hold the point and whose EvaluatePosition
/// says inside, so on a surface a point near a triangle, within its bounds,
/// is located; vtkCellLocator returns the same cells (vtkStaticCellLocator
/// tests its bin's cells without their bounds and locates more).
int TestContractFindCellOnSurfaces()
{
  auto pd = MakeBumpySphere(30);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(pd);
  loc->BuildLocator();
  vtkNew<vtkCellLocator> vtkLoc;
  vtkLoc->SetDataSet(pd);
  vtkLoc->BuildLocator();
  Random rng(4242);
  vtkNew<vtkGenericCell> cell, c2;
  std::vector<double> w(static_cast<size_t>(pd->GetMaxCellSize()));
  int located = 0, asBruteForce = 0, asVTK = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
  {
    // A point near a random vertex, off the surface by up to 2% of the radius.
    double x[3];
    pd->GetPoint(static_cast<vtkIdType>(rng.Next(0, pd->GetNumberOfPoints() - 1)), x);
    for (int k = 0; k < 3; ++k)
    {
      x[k] += rng.Next(-0.02, 0.02);
    }
    double pc[3];
    const vtkIdType ours = loc->FindCell(x, 0.0, cell, pc, w.data());
    LT_CHECK(loc->FindCell(x, 1.0, cell, pc, w.data()) == ours); // tol2 not used
    const vtkIdType ref = BruteForceFindCell(pd, x, c2, w.data());
    located += ours >= 0 ? 1 : 0;
    asBruteForce += ours == ref ? 1 : 0;
    asVTK += ours == vtkLoc->FindCell(x) ? 1 : 0;
  }
  std::cout << "FindCell near a surface: located " << located << "/" << n << ", as brute force " << asBruteForce
            << ", as vtkCellLocator " << asVTK << std::endl;
  LT_CHECK(located > n / 10);
  LT_CHECK(asBruteForce == n);
  LT_CHECK(asVTK == n);

  // A tilted quad whose bounds hold a point that neither box of its two
  // fan triangles holds, and that projects into the quad.
  vtkNew<vtkPoints> corners;
  const double quadPoints[4][3] = { { 0, 0, 0 }, { 10, 1, 1 }, { 5, 5, 5 }, { 1, 10, 10 } };
  for (const auto& c : quadPoints)
  {
    corners->InsertNextPoint(c);
  }
  vtkNew<vtkCellArray> quads;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  quads->InsertNextCell(4, quad);
  vtkNew<vtkPolyData> tilted;
  tilted->SetPoints(corners);
  tilted->SetPolys(quads);
  vtkNew<vtkBVHCellLocator> quadLoc;
  quadLoc->SetDataSet(tilted);
  quadLoc->BuildLocator();
  vtkNew<vtkCellLocator> quadVTK;
  quadVTK->SetDataSet(tilted);
  quadVTK->BuildLocator();
  double x[3] = { 7.0, 0.5, 5.5 };
  std::cout << "tilted quad: FindCell " << quadLoc->FindCell(x) << ", vtkCellLocator " << quadVTK->FindCell(x)
            << std::endl;
  LT_CHECK(quadVTK->FindCell(x) == 0 && quadLoc->FindCell(x) == 0);
  return 0;
}

/// A polygon, strip or line VTK cannot represent (fewer points than its
/// kind needs): vtkPolyData cannot build its cell map, so VTK's GetCell
/// would crash; the build reports one error, no query answers, none crashes.
int TestContractCellsVTKCannotRead()
{
  for (const int kind : { 0, 1, 2 })
  {
    vtkNew<vtkPoints> pts;
    const double corners[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } };
    for (const auto& c : corners)
    {
      pts->InsertNextPoint(c);
    }
    vtkNew<vtkCellArray> polys, strips;
    const vtkIdType tri[3] = { 0, 1, 2 }, two[2] = { 1, 3 };
    polys->InsertNextCell(3, tri);
    if (kind == 0)
    {
      polys->InsertNextCell(2, two);
    }
    else if (kind == 1)
    {
      polys->InsertNextCell(0, two);
    }
    else
    {
      strips->InsertNextCell(2, two);
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(pts);
    pd->SetPolys(polys);
    pd->SetStrips(strips);
    vtkNew<ErrorCatcher> catcher;
    vtkNew<vtkBVHCellLocator> loc;
    catcher->Watch(loc);
    loc->SetDataSet(pd);
    loc->BuildLocator();
    LT_CHECK(catcher->Errors.size() == 1 && catcher->Errors[0].find("cannot represent") != std::string::npos);
    double p1[3] = { 0.2, 0.2, 1 }, p2[3] = { 0.2, 0.2, -1 }, t, x[3], pc[3], d2;
    int sub;
    vtkIdType cellId = 7;
    LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t, x, pc, sub, cellId) == 0);
    loc->FindClosestPoint(p1, x, cellId, sub, d2);
    LT_CHECK(cellId == -1);
    LT_CHECK(loc->FindCell(p1) == -1);
    LT_CHECK(catcher->Errors.size() == 1);
  }
  return 0;
}
