// Robustness and API-contract tests: extreme coordinates, degenerate / NaN
// cells, empty / null datasets, non-finite input, rebuild on MTime,
// thread-safe concurrent queries, representation and PrintSelf.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"
#include "vtkDoubleArray.h"
#include "vtkMath.h"
#include "vtkPointData.h"

#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <atomic>
#include <limits>
#include <sstream>
#include <thread>

using namespace locatortest;

namespace
{
struct Answer
{
  int Hit;
  double T;
  vtkIdType CellId;
};

Answer Query(vtkBVHCellLocator* loc, const double p1[3], const double p2[3], vtkGenericCell* cell)
{
  Answer a{ 0, -1.0, -1 };
  double x[3], pc[3];
  int sub;
  a.Hit = loc->IntersectWithLine(p1, p2, 0.0, a.T, x, pc, sub, a.CellId, cell);
  return a;
}
} // namespace

/// Far from the origin (1e8) and at scales 1e-6 / 1e6, the same rays (mapped
/// the same way) hit the same cells at the same t: the tree is built around a
/// local origin.
int TestRobustExtremeCoordinates()
{
  auto base = MakeBumpySphere(30);
  Random rng(51);
  std::vector<Segment> segs = RandomSegments(base, 400, rng);
  vtkNew<vtkBVHCellLocator> ref;
  ref->SetDataSet(base);
  ref->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  std::vector<Answer> refAnswers;
  int hits = 0;
  for (const auto& s : segs)
  {
    refAnswers.push_back(Query(ref, s.P1, s.P2, cell));
    hits += refAnswers.back().Hit;
  }
  LT_CHECK(hits > 100);

  struct Case
  {
    double Scale;
    double Offset[3];
    const char* Name;
  } cases[] = { { 1.0, { 1e8, -1e8, 1e8 }, "translated by 1e8" }, { 1e-6, { 0, 0, 0 }, "scaled 1e-6" },
    { 1e6, { 0, 0, 0 }, "scaled 1e6" }, { 1e-3, { 1e5, 2e5, -3e5 }, "scaled 1e-3 at 1e5" } };
  for (const auto& c : cases)
  {
    auto pd = Transformed(base, c.Scale, c.Offset);
    vtkNew<vtkBVHCellLocator> loc;
    loc->SetDataSet(pd);
    loc->BuildLocator();
    vtkNew<vtkStaticCellLocator> st;
    st->SetDataSet(pd);
    st->BuildLocator();
    int same = 0, staticMisses = 0;
    for (size_t i = 0; i < segs.size(); ++i)
    {
      double p1[3], p2[3];
      for (int k = 0; k < 3; ++k)
      {
        p1[k] = segs[i].P1[k] * c.Scale + c.Offset[k];
        p2[k] = segs[i].P2[k] * c.Scale + c.Offset[k];
      }
      const Answer a = Query(loc, p1, p2, cell);
      LT_CHECK_MSG(a.Hit == refAnswers[i].Hit, c.Name << " segment " << i);
      if (a.Hit && refAnswers[i].Hit)
      {
        // The mapped segment is rounded to the new scale; t moves by that much.
        LT_CHECK_MSG(std::abs(a.T - refAnswers[i].T) < 1e-6, c.Name << " t " << a.T << " vs " << refAnswers[i].T);
        same += a.CellId == refAnswers[i].CellId ? 1 : 0;
        double t, x[3], pc[3];
        int sub;
        vtkIdType sc;
        staticMisses += st->IntersectWithLine(p1, p2, 0.0, t, x, pc, sub, sc) ? 0 : 1;
      }
    }
    std::cout << c.Name << ": " << same << "/" << hits
              << " hits on the same cell as untransformed; vtkStaticCellLocator misses "
              << staticMisses << std::endl;
    // Rounding the mapped endpoints may move a ray across a shared edge.
    LT_CHECK(same >= hits * 98 / 100);
  }

  // A ray at 1e8 aimed at the center of a triangle hits exactly that one.
  double off[3] = { 1e8, 1e8, 1e8 };
  auto far = Transformed(base, 1.0, off);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(far);
  int exact = 0;
  for (vtkIdType c = 0; c < far->GetNumberOfCells(); c += 37)
  {
    vtkNew<vtkIdList> ids;
    far->GetCellPoints(c, ids);
    double a[3], b[3], d[3], center[3], n[3];
    far->GetPoint(ids->GetId(0), a);
    far->GetPoint(ids->GetId(1), b);
    far->GetPoint(ids->GetId(2), d);
    for (int k = 0; k < 3; ++k)
    {
      center[k] = (a[k] + b[k] + d[k]) / 3.0;
    }
    double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double e2[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    vtkMath::Cross(e1, e2, n);
    vtkMath::Normalize(n);
    double p1[3], p2[3];
    for (int k = 0; k < 3; ++k)
    {
      p1[k] = center[k] + 1e-3 * n[k];
      p2[k] = center[k] - 1e-3 * n[k];
    }
    const Answer r = Query(loc, p1, p2, cell);
    exact += (r.Hit && r.CellId == c) ? 1 : 0;
    LT_CHECK_MSG(r.Hit && r.CellId == c, "far triangle " << c);
  }
  std::cout << "1e8: " << exact << " rays at triangle centers hit their triangle" << std::endl;
  return 0;
}

/// NaN points, zero-area triangles, out-of-range input: no crash, no NaN
/// cell ever returned, the rest of the mesh answers as without them.
int TestRobustDegenerateCells()
{
  auto base = MakeBumpySphere(20);
  const vtkIdType nBase = base->GetNumberOfCells();
  vtkNew<vtkPolyData> pd;
  pd->DeepCopy(base);
  vtkPoints* pts = pd->GetPoints();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const vtkIdType pNan = pts->InsertNextPoint(nan, 0, 0);
  const vtkIdType pInf = pts->InsertNextPoint(0, inf, 0);
  const vtkIdType p0 = 0, p1 = 1, p2 = 2;
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType nanTri[3] = { p0, p1, pNan };
  vtkIdType infTri[3] = { p0, pInf, p2 };
  vtkIdType flat[3] = { p0, p0, p1 };   // zero area
  vtkIdType point[3] = { p2, p2, p2 };  // a point
  polys->InsertNextCell(3, nanTri);
  polys->InsertNextCell(3, infTri);
  polys->InsertNextCell(3, flat);
  polys->InsertNextCell(3, point);
  vtkIdType nanQuad[4] = { p0, p1, pNan, p2 };
  polys->InsertNextCell(4, nanQuad);
  pd->Modified();

  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(pd);
  loc->BuildLocator();
  vtkNew<vtkBVHCellLocator> clean;
  clean->SetDataSet(base);
  clean->BuildLocator();
  std::ostringstream print;
  loc->Print(print);
  LT_CHECK(print.str().find("skipped non-finite") != std::string::npos);

  Random rng(61);
  vtkNew<vtkGenericCell> cell;
  int hits = 0;
  for (const auto& s : RandomSegments(base, 300, rng))
  {
    const Answer a = Query(loc, s.P1, s.P2, cell);
    const Answer b = Query(clean, s.P1, s.P2, cell);
    LT_CHECK(a.Hit == b.Hit);
    if (a.Hit)
    {
      ++hits;
      LT_CHECK(std::isfinite(a.T));
      LT_CHECK(a.T == b.T);
      // Only a degenerate cell sharing the hit point could tie.
      LT_CHECK(a.CellId == b.CellId || a.CellId >= nBase);
      LT_CHECK(a.CellId != nBase && a.CellId != nBase + 1 && a.CellId != nBase + 4);
    }
    double cp[3], d2;
    vtkIdType c;
    int sub;
    loc->FindClosestPoint(s.P1, cp, c, sub, d2);
    LT_CHECK(c >= 0 && std::isfinite(d2));
    LT_CHECK(c != nBase && c != nBase + 1 && c != nBase + 4);
  }
  LT_CHECK(hits > 0);
  return 0;
}

/// Empty and null datasets, non-finite segments and points, bad ids: clean
/// 0 / -1 answers, VTK-style errors where VTK gives one, no crash.
int TestRobustBadInput()
{
  vtkNew<ErrorCatcher> catcher;
  vtkNew<vtkGenericCell> cell;
  double p1[3] = { 0, 0, -5 }, p2[3] = { 0, 0, 5 };
  double t, x[3], pc[3], cp[3], d2;
  int sub;
  vtkIdType cellId;

  // Null dataset: BuildLocator and queries report an error.
  {
    vtkNew<vtkBVHCellLocator> loc;
    catcher->Watch(loc);
    loc->BuildLocator();
    LT_CHECK(catcher->Errors.size() == 1);
    LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t, x, pc, sub, cellId, cell) == 0);
    LT_CHECK(cellId == -1);
    LT_CHECK(loc->FindCell(p1) == -1);
    LT_CHECK(catcher->Errors.size() == 3);
    catcher->Errors.clear();
  }
  // Empty dataset: BuildLocator errors ("No cells to build", as
  // vtkStaticCellLocator says); queries answer nothing without error.
  {
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkBVHCellLocator> loc;
    catcher->Watch(loc);
    loc->SetDataSet(empty);
    loc->BuildLocator();
    LT_CHECK(catcher->Errors.size() == 1);
    LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t, x, pc, sub, cellId, cell) == 0);
    loc->FindClosestPoint(p1, cp, cellId, sub, d2);
    LT_CHECK(cellId == -1);
    LT_CHECK(loc->FindClosestPointWithinRadius(p1, 1.0, cp, cellId, sub, d2) == 0);
    vtkNew<vtkIdList> ids;
    double box[6] = { -1, 1, -1, 1, -1, 1 };
    loc->FindCellsWithinBounds(box, ids);
    LT_CHECK(ids->GetNumberOfIds() == 0);
    LT_CHECK(loc->FindCell(p1) == -1);
    LT_CHECK(!loc->InsideCellBounds(p1, 0));
    LT_CHECK(catcher->Errors.size() == 1);
    catcher->Errors.clear();
  }
  // Non-finite input on a good mesh.
  {
    auto pd = MakeBumpySphere(12);
    vtkNew<vtkBVHCellLocator> loc;
    catcher->Watch(loc);
    loc->SetDataSet(pd);
    loc->BuildLocator();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    double bad1[3] = { nan, 0, 0 }, bad2[3] = { 0, inf, 0 };
    LT_CHECK(loc->IntersectWithLine(bad1, p2, 0.0, t, x, pc, sub, cellId, cell) == 0);
    LT_CHECK(loc->IntersectWithLine(p1, bad2, 0.0, t, x, pc, sub, cellId, cell) == 0);
    LT_CHECK(loc->IntersectWithLine(p1, p2, nan, t, x, pc, sub, cellId, cell) == 0);
    LT_CHECK(loc->IntersectWithLine(p1, p1, 0.0, t, x, pc, sub, cellId, cell) == 0);
    vtkNew<vtkPoints> hp;
    vtkNew<vtkIdList> hids;
    LT_CHECK(loc->IntersectWithLine(bad1, p2, hp, hids) == 0);
    LT_CHECK(hids->GetNumberOfIds() == 0);
    loc->FindClosestPoint(bad1, cp, cellId, sub, d2);
    LT_CHECK(cellId == -1);
    LT_CHECK(loc->FindClosestPointWithinRadius(p1, nan, cp, cellId, sub, d2) == 0);
    LT_CHECK(loc->FindCell(bad1) == -1);
    LT_CHECK(!loc->InsideCellBounds(p1, -1));
    LT_CHECK(!loc->InsideCellBounds(p1, pd->GetNumberOfCells()));
    // The segment through the sphere still works afterwards.
    LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t, x, pc, sub, cellId, cell) == 1);
    LT_CHECK(catcher->Errors.empty());
    LT_CHECK(catcher->Warnings.empty());
  }
  return 0;
}

/// The tree follows the dataset: modified points are seen by the next query
/// (unless UseExistingSearchStructure), ForceBuildLocator always rebuilds,
/// LazyEvaluation defers the build to the first query.
int TestRobustRebuild()
{
  auto pd = MakeBumpySphere(16);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(pd);
  loc->BuildLocator();
  const double p1[3] = { -5, 0.01, 0.02 }, p2[3] = { 5, 0.01, 0.02 };
  double t0, t1, x[3], pc[3];
  int sub;
  vtkIdType c0, c1;
  LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t0, x, pc, sub, c0) == 1);
  // Scale the mesh by 2 in place.
  vtkPoints* pts = pd->GetPoints();
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pts->GetPoint(i, p);
    pts->SetPoint(i, 2 * p[0], 2 * p[1], 2 * p[2]);
  }
  pts->Modified();
  loc->UseExistingSearchStructureOn();
  const vtkMTimeType kept = loc->GetBuildTime();
  // The old tree, the cells where they are now (as VTK's locators): the
  // doubled sphere lies outside the old boxes along this segment.
  const int keptHit = loc->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1);
  LT_CHECK(loc->GetBuildTime() == kept); // not rebuilt
  LT_CHECK(keptHit == 0 || DistanceToCell2(pd, c1, x) < 1e-20);
  loc->UseExistingSearchStructureOff();
  LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1) == 1);
  LT_CHECK(t1 < t0); // rebuilt: the bigger sphere is met earlier
  LT_CHECK(DistanceToCell2(pd, c1, x) < 1e-20); // on the modified mesh

  vtkNew<vtkBVHCellLocator> lazy;
  lazy->LazyEvaluationOn();
  lazy->SetDataSet(pd);
  lazy->BuildLocator();
  LT_CHECK(lazy->GetNumberOfNodes() == 0);
  LT_CHECK(lazy->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1) == 1);
  LT_CHECK(lazy->GetNumberOfNodes() > 0);

  const vtkMTimeType before = loc->GetBuildTime();
  loc->BuildLocator();
  LT_CHECK(loc->GetBuildTime() == before); // up to date: nothing to do

  // A new or modified attribute array moves no cell: the polydata's MTime
  // changes, the tree is kept. A modified cell array rebuilds it.
  {
    vtkNew<vtkDoubleArray> scalars;
    scalars->SetNumberOfTuples(pd->GetNumberOfPoints());
    scalars->Fill(1.0);
    const vtkMTimeType dataTime = pd->GetMTime();
    pd->GetPointData()->SetScalars(scalars);
    scalars->Modified();
    LT_CHECK(pd->GetMTime() > dataTime);
    double t2;
    vtkIdType c2;
    LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t2, x, pc, sub, c2) == 1);
    LT_CHECK(loc->GetBuildTime() == before);
    LT_CHECK(t2 == t1 && c2 == c1);
    pd->GetPolys()->Modified();
    LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t2, x, pc, sub, c2) == 1);
    LT_CHECK(loc->GetBuildTime() > before);
    LT_CHECK(t2 == t1 && c2 == c1);
    pd->GetPointData()->SetScalars(nullptr);
  }
  loc->BuildLocator();
  const vtkMTimeType afterAttributes = loc->GetBuildTime();
  loc->ForceBuildLocator();
  LT_CHECK(loc->GetBuildTime() > afterAttributes);

  // Knobs: leaf size and quality change the tree; answers stay the same.
  for (int q : { vtkBVHCellLocator::FAST, vtkBVHCellLocator::SAH, vtkBVHCellLocator::HIGH })
  {
    for (int leaf : { 1, 4, 16 })
    {
      loc->SetBuildQuality(q);
      loc->SetNumberOfCellsPerNode(leaf);
      loc->BuildLocator();
      LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1) == 1);
      LT_CHECK(loc->GetNumberOfPrimitives() == pd->GetNumberOfCells());
      LT_CHECK(c1 >= 0);
    }
  }

  // Representation: level 0 is the root box; negative levels give the leaves.
  vtkNew<vtkPolyData> rep;
  loc->GenerateRepresentation(0, rep);
  LT_CHECK(rep->GetNumberOfCells() == 6);
  double rb[6], db[6];
  rep->GetBounds(rb);
  pd->GetBounds(db);
  for (int k = 0; k < 6; ++k)
  {
    LT_CHECK(std::abs(rb[k] - db[k]) < 1e-12);
  }
  loc->GenerateRepresentation(-1, rep);
  std::ostringstream print;
  loc->Print(print);
  LT_CHECK(print.str().find("Nodes:") != std::string::npos);
  LT_CHECK(print.str().find("SAH cost:") != std::string::npos);
  LT_CHECK(print.str().find("Depth:") != std::string::npos);
  LT_CHECK(print.str().find("Build time:") != std::string::npos);
  const vtkIdType leaves = (loc->GetNumberOfNodes() + 1) / 2;
  LT_CHECK(rep->GetNumberOfCells() == 6 * leaves);

  loc->FreeSearchStructure();
  LT_CHECK(loc->GetNumberOfNodes() == 0);
  LT_CHECK(loc->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1) == 1); // rebuilt on demand

  // The points array shrunk, then regrown (reallocated), without a
  // Modified(): the locator reads its coordinates in place, so it must
  // notice and never read the old storage.
  {
    auto mesh = MakeBumpySphere(16);
    vtkDataArray* coords = mesh->GetPoints()->GetData();
    vtkNew<vtkDoubleArray> saved;
    saved->DeepCopy(coords);
    vtkNew<vtkBVHCellLocator> moved;
    moved->SetDataSet(mesh);
    moved->BuildLocator();
    double tRef;
    LT_CHECK(moved->IntersectWithLine(p1, p2, 0.0, tRef, x, pc, sub, c0) == 1);
    vtkNew<ErrorCatcher> catcher;
    catcher->Watch(moved);
    moved->UseExistingSearchStructureOn();
    const vtkMTimeType meshTime = mesh->GetMTime();
    coords->SetNumberOfTuples(saved->GetNumberOfTuples() / 2);
    LT_CHECK(mesh->GetMTime() == meshTime); // VTK does not see a change
    LT_CHECK(moved->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1) == 0);
    LT_CHECK(catcher->Errors.size() == 1);
    coords->SetNumberOfTuples(saved->GetNumberOfTuples());
    for (vtkIdType i = 0; i < saved->GetNumberOfTuples(); ++i)
    {
      coords->SetTuple(i, saved->GetTuple(i));
    }
    moved->UseExistingSearchStructureOff();
    LT_CHECK(moved->IntersectWithLine(p1, p2, 0.0, t1, x, pc, sub, c1) == 1); // rebuilt
    LT_CHECK(t1 == tRef && c1 == c0);
    LT_CHECK(catcher->Errors.size() == 1);
  }
  return 0;
}

/// A mesh big enough for the picking path's large-data measures: the
/// per-triangle arrays take the huge page allocation (4 MiB and more) and
/// the walk fetches children ahead. Nearest hits as a brute-force reference
/// over VTK's own cell tests, the cell's exact coordinates, and the same
/// answers with the whole tree built up front.
int TestRobustLargeMesh()
{
  auto pd = MakeBumpySphere(260); // 134k triangles, 4.8 MB of float triangles
  LT_CHECK(pd->GetNumberOfCells() > 130000);
  vtkNew<vtkBVHCellLocator> loc, whole;
  loc->SetDataSet(pd);
  loc->BuildLocator();
  whole->SetDataSet(pd);
  whole->PickingTreeOnDemandOff();
  whole->BuildLocator();
  LT_CHECK(whole->GetMemorySize() > (8u << 20));
  Random rng(83);
  vtkNew<vtkGenericCell> cell;
  const double diag = Diagonal(pd);
  int hits = 0;
  for (const auto& s : RandomSegments(pd, 40, rng))
  {
    const RefHit ref = BruteForceHit(pd, s.P1, s.P2, 0.0);
    double t, x[3], pc[3];
    int sub;
    vtkIdType cellId;
    const int hit = loc->IntersectWithLine(s.P1, s.P2, 0.0, t, x, pc, sub, cellId, cell);
    LT_CHECK(hit == (ref.Hit ? 1 : 0));
    if (!hit || !ref.Hit)
    {
      continue;
    }
    ++hits;
    const double len = std::sqrt(vtkMath::Distance2BetweenPoints(s.P1, s.P2));
    LT_CHECK(std::abs(t - ref.T) * len <= 1e-9 * diag);
    LT_CHECK(cellId == ref.CellId || DistanceToCell2(pd, ref.CellId, x) <= 1e-16 * diag * diag);
    LT_CHECK(SameCellPoints(pd, cellId, cell));
    const Answer w = Query(whole, s.P1, s.P2, cell);
    LT_CHECK(w.Hit == 1 && w.T == t && w.CellId == cellId);
  }
  LT_CHECK(hits >= 10);
  std::cout << "large mesh: " << pd->GetNumberOfCells() << " triangles, " << hits
            << " of 40 segments hit, all as brute force" << std::endl;
  return 0;
}

/// IntersectWithLine and FindClosestPoint from several vtkSMPTools threads
/// (and std::threads) at once give the serial answers.
int TestRobustThreads()
{
  // Big enough for 64 buckets: the picking tree's parts are built on demand
  // by whichever threads reach them first (fresh locators below), against
  // a reference built whole up front.
  auto pd = MakeBumpySphere(200);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(pd);
  loc->PickingTreeOnDemandOff();
  loc->BuildLocator();
  vtkNew<vtkBVHCellLocator> smpLoc, threadLoc;
  for (vtkBVHCellLocator* l : { smpLoc.Get(), threadLoc.Get() })
  {
    l->SetDataSet(pd);
    l->BuildLocator();
  }
  Random rng(71);
  const std::vector<Segment> segs = RandomSegments(pd, 4000, rng);
  const vtkIdType n = static_cast<vtkIdType>(segs.size());
  std::vector<Answer> serial(segs.size()), parallel(segs.size()), threaded(segs.size());
  std::vector<vtkIdType> serialClosest(segs.size()), parallelClosest(segs.size());
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType i = 0; i < n; ++i)
  {
    serial[i] = Query(loc, segs[i].P1, segs[i].P2, cell);
    double cp[3], d2;
    int sub;
    loc->FindClosestPoint(segs[i].P1, cp, cell, serialClosest[i], sub, d2);
  }
  vtkSMPThreadLocalObject<vtkGenericCell> cells;
  vtkSMPTools::For(0, n, 16, [&](vtkIdType b, vtkIdType e) {
    vtkGenericCell* c = cells.Local();
    for (vtkIdType i = b; i < e; ++i)
    {
      parallel[i] = Query(smpLoc, segs[i].P1, segs[i].P2, c);
      double cp[3], d2;
      int sub;
      // Completes the tree (once, under a lock) while other threads pick.
      smpLoc->FindClosestPoint(segs[i].P1, cp, c, parallelClosest[i], sub, d2);
    }
  });
  std::vector<std::thread> workers;
  for (int w = 0; w < 4; ++w)
  {
    workers.emplace_back([&, w]() {
      vtkNew<vtkGenericCell> c;
      for (vtkIdType i = w; i < n; i += 4)
      {
        threaded[i] = Query(threadLoc, segs[i].P1, segs[i].P2, c);
      }
    });
  }
  for (auto& th : workers)
  {
    th.join();
  }
  int mismatches = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    mismatches += (parallel[i].Hit != serial[i].Hit || parallel[i].T != serial[i].T ||
                    parallel[i].CellId != serial[i].CellId || threaded[i].T != serial[i].T ||
                    threaded[i].CellId != serial[i].CellId ||
                    parallelClosest[i] != serialClosest[i])
      ? 1
      : 0;
  }
  std::cout << "threads (" << vtkSMPTools::GetBackend() << ", " << vtkSMPTools::GetEstimatedNumberOfThreads()
            << " threads + 4 std::threads): " << mismatches << " mismatches over " << n << " queries"
            << std::endl;
  LT_CHECK(mismatches == 0);
  return 0;
}
