// VTK-contract tests from the adversarial review (issue 24): cells with
// out-of-range point ids, concurrent first queries of an unbuilt locator,
// zero-length segments, float points moved under UseExistingSearchStructure.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
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
} // namespace

/// A fresh, unbuilt locator (and one whose dataset was modified since its
/// build) queried first from 4 threads at once: one builds, the others
/// wait for the published tree; every answer is the single-threaded one.
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
  int mismatches = 0, staleMismatches = 0;
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
  }
  std::cout << "fresh locators, 4 threads: " << mismatches << " mismatches, after Modified(): "
            << staleMismatches << ", over 8 x " << segs.size() << " queries each" << std::endl;
  LT_CHECK(mismatches == 0);
  LT_CHECK(staleMismatches == 0);
  return 0;
}
