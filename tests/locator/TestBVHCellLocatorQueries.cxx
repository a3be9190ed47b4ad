// The point and box queries over the picking tree: closest points against
// brute force over probes as a user's (on the surface, near it, around it,
// far away, the center of a sphere), through the float walk and the double
// one; segments parallel to an axis; and that no query after BuildLocator()
// builds the binary tree; closest points among blanked cells; cells of
// several triangles found by their own bounds.
#include "LocatorTestUtils.h"

#include "vtkBVHCellLocator.h"
#include "vtkCellArray.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStructuredGrid.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <thread>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

using namespace locatortest;

namespace
{
/// Probes around pd: a mix as vtkrtBenchLocator's (see its query part).
std::vector<std::array<double, 3>> Probes(vtkPolyData* pd, int count, Random& rng)
{
  double b[6];
  pd->GetBounds(b);
  const double diag = Diagonal(pd);
  std::vector<std::array<double, 3>> out;
  out.push_back({ 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) });
  for (int i = 0; i < count; ++i)
  {
    std::array<double, 3> x;
    if (i % 3 == 0)
    {
      // On a random cell or within 1% of the diagonal of it.
      const vtkIdType c = std::min<vtkIdType>(pd->GetNumberOfCells() - 1,
        static_cast<vtkIdType>(rng.Next(0, static_cast<double>(pd->GetNumberOfCells()))));
      double p[3][3], n[3];
      vtkIdType npts;
      const vtkIdType* ids;
      pd->GetCellPoints(c, npts, ids);
      for (int k = 0; k < 3; ++k)
      {
        pd->GetPoint(ids[k], p[k]);
      }
      vtkTriangle::ComputeNormal(p[0], p[1], p[2], n);
      const double u = rng.Next(0, 0.5), v = rng.Next(0, 0.5);
      const double off = (i % 2) ? rng.Next(-0.01, 0.01) * diag : 0.0;
      for (int a = 0; a < 3; ++a)
      {
        x[a] = p[0][a] + u * (p[1][a] - p[0][a]) + v * (p[2][a] - p[0][a]) + off * n[a];
      }
    }
    else
    {
      // In the bounds grown by half, or 1 to 3 diagonals away.
      const double grow = (i % 3 == 1) ? 0.75 : 3.0;
      for (int a = 0; a < 3; ++a)
      {
        const double c = 0.5 * (b[2 * a] + b[2 * a + 1]), h = grow * (b[2 * a + 1] - b[2 * a]);
        x[a] = rng.Next(c - h, c + h);
      }
    }
    out.push_back(x);
  }
  return out;
}

/// FindClosestPoint (every overload) and FindClosestPointWithinRadius on
/// each probe against brute force over VTK's cells.
void CheckProbes(vtkPolyData* pd, vtkBVHCellLocator* loc, int count, const char* name)
{
  Random rng(5);
  const double diag = Diagonal(pd);
  const double eps2 = 1e-14 * diag * diag;
  const double radius = 0.02 * diag;
  vtkNew<vtkGenericCell> cell;
  int checked = 0, inRadius = 0;
  for (auto& q : Probes(pd, count, rng))
  {
    double x[3] = { q[0], q[1], q[2] }, cp[3], d2 = -1;
    vtkIdType cellId = -1, refCell;
    int sub;
    const double ref = BruteForceClosest(pd, x, refCell);
    loc->FindClosestPoint(x, cp, cell, cellId, sub, d2);
    LT_CHECK_MSG(std::abs(d2 - ref) <= eps2 + 1e-9 * ref, name << " d2 " << d2 << " brute force " << ref);
    LT_CHECK(cellId >= 0 && SameCellPoints(pd, cellId, cell));
    LT_CHECK(cellId < 0 || std::abs(DistanceToCell2(pd, cellId, x) - d2) <= eps2 + 1e-9 * d2);
    LT_CHECK(std::abs(vtkMath::Distance2BetweenPoints(x, cp) - d2) <= eps2 + 1e-9 * d2);
    double rd2 = -1;
    vtkIdType rc = -2;
    const vtkIdType found = loc->FindClosestPointWithinRadius(x, radius, cp, cell, rc, sub, rd2);
    if (ref <= radius * radius * (1 - 1e-9))
    {
      LT_CHECK_MSG(found == 1 && rd2 == d2, name << " within radius: " << found << " d2 " << rd2 << " vs " << d2);
      ++inRadius;
    }
    else if (ref > radius * radius * (1 + 1e-9))
    {
      LT_CHECK(found == 0 && rc == -1);
    }
    ++checked;
  }
  LT_CHECK(inRadius > count / 10);
  std::cout << name << ": " << checked << " probes agree with brute force (" << inRadius
            << " within the radius)" << std::endl;
}

/// FindCellsWithinBounds against brute force over small and large boxes.
void CheckBoxes(vtkPolyData* pd, vtkBVHCellLocator* loc, int count, const char* name)
{
  Random rng(9);
  double b[6];
  pd->GetBounds(b);
  const double diag = Diagonal(pd);
  vtkNew<vtkIdList> ids;
  for (int i = 0; i < count; ++i)
  {
    double box[6];
    const double half = (i % 4 == 0 ? 0.2 : 0.01) * diag;
    for (int a = 0; a < 3; ++a)
    {
      const double c = rng.Next(b[2 * a], b[2 * a + 1]);
      box[2 * a] = c - half;
      box[2 * a + 1] = c + half;
    }
    loc->FindCellsWithinBounds(box, ids);
    LT_CHECK_MSG(ToVector(ids) == BruteForceCellsInBox(pd, box), name << " box " << i);
  }
}

bool BinaryTreeBuilt(vtkBVHCellLocator* loc)
{
  std::ostringstream os;
  loc->PrintSelf(os, vtkIndent());
  return os.str().find("binary tree not built yet") == std::string::npos;
}
} // namespace

/// Closest points, radius queries and boxes against brute force, through
/// the float walk and (in a flush-to-zero FPU mode) the double one.
int TestQueriesClosestPointProbes()
{
  auto pd = MakeBumpySphere(60);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(pd);
  loc->BuildLocator();
  CheckProbes(pd, loc, 600, "bumpy sphere");
  CheckBoxes(pd, loc, 200, "bumpy sphere");
  LT_CHECK(!BinaryTreeBuilt(loc));

#if defined(__SSE2__)
  // A flush-to-zero FPU mode (some applications set it): the float walks
  // refuse it, the binary tree is walked in double.
  const unsigned csr = _mm_getcsr();
  _mm_setcsr(csr | 0x8040u);
  vtkNew<vtkBVHCellLocator> ftzLoc;
  ftzLoc->SetDataSet(pd);
  ftzLoc->BuildLocator();
  CheckProbes(pd, ftzLoc, 200, "flush-to-zero mode (double walk)");
  CheckBoxes(pd, ftzLoc, 50, "flush-to-zero mode (double walk)");
  LT_CHECK(BinaryTreeBuilt(ftzLoc));
  _mm_setcsr(csr);
#endif
  return 0;
}

/// BuildLocator() leaves no structure for a first query to build: on
/// demand (the default) the queries of every kind reach only the picking
/// tree (the binary tree stays unbuilt); with PickingTreeOnDemand off no
/// query builds anything (same memory, same build time), a segment
/// parallel to an axis (which the float walk refuses) included.
int TestQueriesFirstQueryBuildsNothing()
{
  auto pd = MakeBumpySphere(80);
  double b[6];
  pd->GetBounds(b);
  double mid[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  double far[3] = { b[1] + 3, b[3] + 2, b[5] + 1 }, off[3] = { b[0] - 1, mid[1] + 0.1, mid[2] - 0.05 };
  double box[6] = { mid[0] - 0.1, mid[0] + 0.1, b[2] - 0.1, b[2] + 0.2, mid[2] - 0.1, mid[2] + 0.1 };
  const double axisP1[3] = { mid[0] + 0.01, mid[1] + 0.02, b[4] - 1 }, axisP2[3] = { mid[0] + 0.01, mid[1] + 0.02, b[5] + 1 };
  auto askAll = [&](vtkBVHCellLocator* loc, bool axisParallel) {
    vtkNew<vtkGenericCell> cell;
    vtkNew<vtkIdList> ids;
    vtkNew<vtkPoints> pts;
    double x[3], pc[3], t, d2, w[8];
    int sub;
    vtkIdType c;
    loc->FindClosestPoint(far, x, cell, c, sub, d2);
    LT_CHECK(c >= 0);
    LT_CHECK(loc->FindClosestPointWithinRadius(off, 2.0, x, cell, c, sub, d2) == 1);
    loc->FindCellsWithinBounds(box, ids);
    LT_CHECK(ids->GetNumberOfIds() > 0);
    LT_CHECK(loc->IntersectWithLine(off, far, 0.0, t, x, pc, sub, c, cell) == 1 || c == -1);
    LT_CHECK(loc->IntersectWithLine(off, mid, pts, ids) != 0);
    loc->FindCellsAlongLine(off, mid, 0.0, ids);
    LT_CHECK(ids->GetNumberOfIds() > 0);
    LT_CHECK(loc->FindCell(mid, 0.0, cell, pc, w) == -1);
    if (axisParallel)
    {
      LT_CHECK(loc->IntersectWithLine(axisP1, axisP2, 0.0, t, x, pc, sub, c, cell) == 1);
    }
  };

  vtkNew<vtkBVHCellLocator> onDemand;
  onDemand->SetDataSet(pd);
  onDemand->BuildLocator();
  const vtkMTimeType built = onDemand->GetBuildTime();
  askAll(onDemand, false);
  LT_CHECK(!BinaryTreeBuilt(onDemand));
  LT_CHECK(onDemand->GetBuildTime() == built);

  vtkNew<vtkBVHCellLocator> whole;
  whole->SetPickingTreeOnDemand(false);
  whole->SetDataSet(pd);
  whole->BuildLocator();
  LT_CHECK(!BinaryTreeBuilt(whole));
  const vtkMTimeType wholeBuilt = whole->GetBuildTime();
  const size_t bytes = whole->GetMemorySize();
  askAll(whole, true);
  LT_CHECK(whole->GetBuildTime() == wholeBuilt);
  LT_CHECK_MSG(whole->GetMemorySize() == bytes, whole->GetMemorySize() << " bytes after the queries, " << bytes << " before");
  LT_CHECK(!BinaryTreeBuilt(whole));
  return 0;
}

/// Segments parallel to an axis, which the float walk refuses (the wide
/// tree is then walked in double): nearest hit, all hits and cells along
/// the line against brute force, for the fast build and the SAH build (its
/// wide tree re-laid from the binary one), at tolerance 0 and above.
int TestQueriesAxisParallelSegments()
{
  auto pd = MakeBumpySphere(40);
  double b[6];
  pd->GetBounds(b);
  Random rng(21);
  std::vector<Segment> segs;
  for (int i = 0; i < 240; ++i)
  {
    const int axis = i % 3;
    Segment s;
    for (int a = 0; a < 3; ++a)
    {
      const double c = 0.5 * (b[2 * a] + b[2 * a + 1]), h = 0.6 * (b[2 * a + 1] - b[2 * a]);
      s.P1[a] = s.P2[a] = rng.Next(c - h, c + h);
    }
    s.P1[axis] = b[2 * axis] - 0.5 * (i % 2);
    s.P2[axis] = b[2 * axis + 1] + 0.25;
    if (i % 4 == 0)
    {
      std::swap(s.P1, s.P2);
    }
    segs.push_back(s);
  }
  for (int quality : { vtkBVHCellLocator::FAST, vtkBVHCellLocator::SAH })
  {
    vtkNew<vtkBVHCellLocator> loc;
    loc->SetBuildQuality(quality);
    loc->SetDataSet(pd);
    loc->BuildLocator();
    const char* name = quality == vtkBVHCellLocator::FAST ? "axis-parallel, fast build" : "axis-parallel, SAH build";
    CheckIntersectWithLine(pd, loc, {}, segs, 0.0, name);
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    vtkNew<vtkIdList> ids;
    for (const Segment& s : segs)
    {
      for (double tol : { 0.0, 1e-3 })
      {
        loc->IntersectWithLine(s.P1, s.P2, tol, pts, ids);
        std::set<vtkIdType> ours;
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
        {
          ours.insert(ids->GetId(k));
        }
        std::set<vtkIdType> ref;
        for (const auto& h : BruteForceAllHits(pd, s.P1, s.P2, tol))
        {
          ref.insert(h.first);
        }
        LT_CHECK_MSG(ours == ref, name << " all hits: " << ours.size() << " cells, brute force " << ref.size());
        loc->FindCellsAlongLine(s.P1, s.P2, tol, ids);
        const std::vector<vtkIdType> along = BruteForceCellsAlongLine(pd, s.P1, s.P2, tol);
        LT_CHECK_MSG(ToVector(ids) == along, name << " along line: " << ids->GetNumberOfIds() << " cells, brute force " << along.size());
      }
    }
    LT_CHECK(!BinaryTreeBuilt(loc) || quality != vtkBVHCellLocator::FAST);
  }
  return 0;
}

/// Segments in the plane of flat meshes (triangles, quads, a polygon): the
/// watertight test never hits them, VTK's cells do where the segment enters
/// them (vtkTriangle's coplanar case). First hit and all hits equal the
/// cells' own answers, t and cell id exactly.
int TestQueriesSegmentsInPlane()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(0, 0, 0);
  plane->SetPoint1(10, 0, 0);
  plane->SetPoint2(0, 10, 0);
  plane->SetResolution(10, 10);
  plane->Update();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  vtkNew<vtkPolyData> polygon; // one hexagon beside the grids
  vtkNew<vtkPoints> polygonPoints;
  vtkNew<vtkCellArray> polygonCells;
  polygonCells->InsertNextCell(6);
  for (int k = 0; k < 6; ++k)
  {
    const double a = k * vtkMath::Pi() / 3.0;
    polygonCells->InsertCellPoint(polygonPoints->InsertNextPoint(5 + 4 * std::cos(a), 5 + 4 * std::sin(a), 0));
  }
  polygon->SetPoints(polygonPoints);
  polygon->SetPolys(polygonCells);
  Random rng(7);
  std::vector<Segment> segs;
  for (int i = 0; i < 160; ++i)
  {
    Segment s;
    for (int a = 0; a < 2; ++a)
    {
      s.P1[a] = rng.Next(-2.0, 12.0);
      s.P2[a] = rng.Next(-2.0, 12.0);
    }
    s.P1[2] = s.P2[2] = 0.0;
    segs.push_back(s);
  }
  for (int i = 0; i <= 10; i += 5)
  {
    // Along grid lines: on the cells' shared edges.
    segs.push_back(Segment{ { static_cast<double>(i), -1.0, 0.0 }, { static_cast<double>(i), 11.0, 0.0 } });
  }
  int hits = 0;
  for (vtkPolyData* pd : { plane->GetOutput(), triangles->GetOutput(), polygon.Get() })
  {
    vtkNew<vtkBVHCellLocator> loc;
    loc->SetDataSet(pd);
    loc->BuildLocator();
    vtkNew<vtkGenericCell> cell;
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    vtkNew<vtkIdList> ids;
    for (const Segment& s : segs)
    {
      for (double tol : { 0.0, 1e-3 })
      {
        const RefHit ref = BruteForceHit(pd, s.P1, s.P2, tol);
        double t = -1, x[3], pc[3];
        int sub = -1;
        vtkIdType cellId = -1;
        const int hit = loc->IntersectWithLine(s.P1, s.P2, tol, t, x, pc, sub, cellId, cell);
        hits += hit ? 1 : 0;
        LT_CHECK_MSG(hit == (ref.Hit ? 1 : 0) && (!hit || (t == ref.T && cellId == ref.CellId)),
          pd->GetNumberOfCells() << " cells, tol " << tol << ": hit " << hit << " cell " << cellId << " t " << t
                                 << ", the cells' own " << ref.Hit << " " << ref.CellId << " " << ref.T);
        loc->IntersectWithLine(s.P1, s.P2, tol, pts, ids);
        const std::map<vtkIdType, double> all = BruteForceAllHits(pd, s.P1, s.P2, tol);
        std::map<vtkIdType, double> ours;
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
        {
          double p[3];
          pts->GetPoint(k, p);
          ours[ids->GetId(k)] = std::hypot(p[0] - s.P1[0], p[1] - s.P1[1]) /
            std::hypot(s.P2[0] - s.P1[0], s.P2[1] - s.P1[1]);
        }
        bool same = ours.size() == all.size();
        for (const auto& h : all)
        {
          // With a tolerance, VTK's hit point lies on the cell's edge, off
          // the segment by up to tol: the cells alone are compared.
          same = same && ours.count(h.first) && (tol > 0.0 || std::abs(ours[h.first] - h.second) <= 1e-12);
        }
        LT_CHECK_MSG(same, pd->GetNumberOfCells() << " cells, tol " << tol << ": all hits " << ours.size()
                                                 << " cells, the cells' own " << all.size());
      }
    }
  }
  LT_CHECK_MSG(hits > 300, hits << " first hits (most segments cross the meshes)");
  return 0;
}

/// A structured grid with blanked cells (VTK's empty cells): closest points
/// come from visible cells only, as brute force over them finds, and never
/// with a negative distance.
int TestQueriesBlankedCells()
{
  vtkNew<vtkStructuredGrid> grid;
  grid->SetDimensions(10, 10, 4);
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 4; ++k)
  {
    for (int j = 0; j < 10; ++j)
    {
      for (int i = 0; i < 10; ++i)
      {
        const double r = 1.0 + 0.2 * i, theta = 0.2 * j;
        points->InsertNextPoint(r * std::cos(theta), r * std::sin(theta), 0.3 * k);
      }
    }
  }
  grid->SetPoints(points);
  vtkNew<vtkStructuredGrid> whole; // the same cells, none blanked
  whole->DeepCopy(grid);
  const vtkIdType blanked[] = { 5, 40, 100, 150, 151, 152 };
  for (vtkIdType c : blanked)
  {
    grid->BlankCell(c);
  }
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(grid);
  loc->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  Random rng(5);
  int blankedBest = 0;
  for (int probe = 0; probe < 400; ++probe)
  {
    // Around a blanked cell, in it or beside it.
    double b[6];
    whole->GetCellBounds(blanked[probe % 6], b);
    double x[3];
    for (int a = 0; a < 3; ++a)
    {
      const double h = b[2 * a + 1] - b[2 * a];
      x[a] = rng.Next(b[2 * a] - h, b[2 * a + 1] + h);
    }
    double closest[3];
    vtkIdType cellId = -1;
    int subId = 0;
    double dist2 = -1.0;
    loc->FindClosestPoint(x, closest, cell, cellId, subId, dist2);
    double best = VTK_DOUBLE_MAX;
    vtkIdType bestId = -1;
    double bestAll = VTK_DOUBLE_MAX;
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    {
      whole->GetCell(c, cell);
      double cp[3], pc[3], d2, w[8];
      int sub;
      if (cell->EvaluatePosition(x, cp, sub, pc, d2, w) >= 0 && d2 >= 0.0)
      {
        if (!grid->IsCellVisible(c))
        {
          bestAll = std::min(bestAll, d2);
          continue;
        }
        if (d2 < best)
        {
          best = d2;
          bestId = c;
        }
      }
    }
    blankedBest += bestAll < best ? 1 : 0;
    LT_CHECK_MSG(cellId >= 0 && grid->IsCellVisible(cellId) && dist2 >= 0.0 && std::abs(dist2 - best) <= 1e-12 * (1.0 + best),
      "probe " << probe << ": cell " << cellId << " dist2 " << dist2 << ", brute force over visible cells "
               << bestId << " " << best);
  }
  // Probes whose nearest cell is a blanked one: the case that matters.
  LT_CHECK_MSG(blankedBest > 20, blankedBest << " probes nearest a blanked cell");
  return 0;
}

namespace
{
/// Planar cells of several triangles whose bounds reach where no box of
/// their triangles does: tilted non-convex stars (8-point polygons), tilted
/// quads and, with `triangles`, plain triangles (their ids interleaved),
/// then zig-zag strips; a large tilted quad under them all with `largeQuad`.
vtkSmartPointer<vtkPolyData> SeveralTriangleCells(Random& rng, bool largeQuad, bool triangles)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys, strips;
  auto tilted = [&](double cx, double cy, double u, double v, double tx, double ty) {
    return pts->InsertNextPoint(cx + u, cy + v, 0.7 * tx * u + 0.5 * ty * v);
  };
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 6; ++j)
    {
      const double cx = 3.0 * i, cy = 3.0 * j, tx = rng.Next(-1, 1), ty = rng.Next(-1, 1);
      vtkIdType ids[8];
      for (int k = 0; k < 8; ++k)
      {
        const double a = vtkMath::Pi() / 4.0 * k, r = (k % 2 == 0) ? 1.2 : 0.35;
        ids[k] = tilted(cx, cy, r * std::cos(a), r * std::sin(a), tx, ty);
      }
      polys->InsertNextCell(8, ids);
      const vtkIdType quad[4] = { tilted(cx + 1.4, cy, 0, 0, tx, ty), tilted(cx + 1.4, cy, 0.9, 0.3, tx, ty),
        tilted(cx + 1.4, cy, 1.2, 1.3, tx, ty), tilted(cx + 1.4, cy, 0.2, 1.0, tx, ty) };
      polys->InsertNextCell(4, quad);
      const vtkIdType tri[3] = { tilted(cx, cy + 1.5, 0, 0, tx, ty), tilted(cx, cy + 1.5, 0.8, 0.1, tx, ty),
        tilted(cx, cy + 1.5, 0.3, 0.9, tx, ty) };
      if (triangles)
      {
        polys->InsertNextCell(3, tri);
      }
      vtkIdType strip[7];
      for (int k = 0; k < 7; ++k)
      {
        strip[k] = pts->InsertNextPoint(cx + 0.3 * k, cy - 1.2 + 0.5 * (k % 2) + 0.08 * k * k, 0.2 * k * (k % 2));
      }
      strips->InsertNextCell(7, strip);
    }
  }
  if (largeQuad)
  {
    const vtkIdType quad[4] = { pts->InsertNextPoint(-2, -2, -1.5), pts->InsertNextPoint(17, -2, -0.5),
      pts->InsertNextPoint(18, 17, 0.5), pts->InsertNextPoint(-1, 16, -0.5) };
    polys->InsertNextCell(4, quad);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  pd->SetStrips(strips);
  return pd;
}

/// A large tilted diamond under a fine triangle mesh (a bumpy sphere): the
/// diamond is the only cell of several triangles, and its two triangles'
/// boxes leave a quarter of its bounds uncovered.
vtkSmartPointer<vtkPolyData> TrianglesOverLargeQuad()
{
  auto sphere = MakeBumpySphere(40, 3.0);
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->DeepCopy(sphere);
  vtkPoints* pts = pd->GetPoints();
  const vtkIdType quad[4] = { pts->InsertNextPoint(0, -6, -4), pts->InsertNextPoint(6, 0, -2.2),
    pts->InsertNextPoint(0, 6, -4), pts->InsertNextPoint(-6, 0, -5.8) };
  pd->GetPolys()->InsertNextCell(4, quad);
  return pd;
}

/// The queries by cell bounds against brute force over the cells' bounds:
/// 400 boxes, 200 segments at two tolerances, 600 FindCell points. Returns
/// the cells listed in the boxes and the points located.
/// Per cell, the bounds of each of its triangles (vtkCell::Triangulate).
std::vector<std::vector<std::array<double, 6>>> TriangleBounds(vtkPolyData* pd)
{
  std::vector<std::vector<std::array<double, 6>>> out(pd->GetNumberOfCells());
  vtkNew<vtkGenericCell> cell;
  vtkNew<vtkIdList> ids;
  vtkNew<vtkPoints> pts;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
  {
    pd->GetCell(c, cell);
    cell->Triangulate(0, ids, pts);
    for (vtkIdType t = 0; t + 2 < pts->GetNumberOfPoints(); t += 3)
    {
      std::array<double, 6> bb = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
        VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
      for (int k = 0; k < 3; ++k)
      {
        const double* x = pts->GetPoint(t + k);
        for (int a = 0; a < 3; ++a)
        {
          bb[2 * a] = std::min(bb[2 * a], x[a]);
          bb[2 * a + 1] = std::max(bb[2 * a + 1], x[a]);
        }
      }
      out[c].push_back(bb);
    }
  }
  return out;
}

std::pair<int, int> CheckCellBounds(vtkPolyData* pd, vtkBVHCellLocator* loc, Random& rng)
{
  double b[6];
  pd->GetBounds(b);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  vtkNew<vtkIdList> ids;
  int boxCells = 0;
  // Cells a box meets by their bounds while none of their triangles' boxes
  // does: what answering from the triangles alone would miss.
  const auto triangles = TriangleBounds(pd);
  int boundsOnly = 0;
  for (int i = 0; i < 400; ++i)
  {
    double box[6];
    for (int a = 0; a < 3; ++a)
    {
      const double c = rng.Next(b[2 * a], b[2 * a + 1]), h = rng.Next(0.0, 0.015 * size);
      box[2 * a] = c - h;
      box[2 * a + 1] = c + h;
    }
    loc->FindCellsWithinBounds(box, ids);
    const std::vector<vtkIdType> ref = BruteForceCellsInBox(pd, box);
    LT_CHECK_MSG(ToVector(ids) == ref, "box " << i << ": " << ids->GetNumberOfIds() << " cells, "
                                              << ref.size() << " by brute force");
    boxCells += static_cast<int>(ref.size());
    for (const vtkIdType c : ref)
    {
      boundsOnly += std::none_of(triangles[c].begin(), triangles[c].end(), [&box](const std::array<double, 6>& t) {
        return t[0] <= box[1] && box[0] <= t[1] && t[2] <= box[3] && box[2] <= t[3] && t[4] <= box[5] &&
          box[4] <= t[5];
      });
    }
  }
  LT_CHECK_MSG(boundsOnly > 0, "no box meets a cell by its bounds alone");
  int segmentCells = 0;
  for (const Segment& s : RandomSegments(pd, 200, rng))
  {
    for (double tol : { 0.0, 0.003 * size })
    {
      loc->FindCellsAlongLine(s.P1, s.P2, tol, ids);
      const std::vector<vtkIdType> ref = BruteForceCellsAlongLine(pd, s.P1, s.P2, tol);
      LT_CHECK_MSG(ToVector(ids) == ref, "segment: " << ids->GetNumberOfIds() << " cells, " << ref.size()
                                                     << " by brute force, tolerance " << tol);
      segmentCells += static_cast<int>(ref.size());
    }
  }
  LT_CHECK(segmentCells > 400);
  // FindCell: the lowest-id cell whose bounds hold x and into which x
  // projects, as VTK 9.1's locators answer for surface cells.
  vtkNew<vtkGenericCell> cell;
  std::vector<double> w(16);
  int located = 0;
  for (int i = 0; i < 600; ++i)
  {
    double x[3] = { rng.Next(b[0], b[1]), rng.Next(b[2], b[3]), rng.Next(b[4], b[5]) }, pc[3];
    const vtkIdType ref = BruteForceFindCell(pd, x, cell, w.data());
    const vtkIdType ours = loc->FindCell(x, 0.0, cell, pc, w.data());
    LT_CHECK_MSG(ours == ref, "FindCell gives " << ours << ", brute force " << ref);
    located += ref >= 0 ? 1 : 0;
  }
  return { boxCells, located };
}
} // namespace

/// FindCellsWithinBounds, FindCellsAlongLine and FindCell answer from the
/// cells' own bounds, as VTK's locators do, for polygons, quads and strips
/// whose bounds reach beyond their triangles' boxes, found in a tree over
/// those cells' bounds that the first such query builds: a mesh of such
/// cells only (the triangles' tree then not asked), and a large quad under
/// small stars or under a fine triangle mesh, for the fast build and the
/// SAH build; then the same queries from four threads at once on a fresh
/// locator.
int TestQueriesCellsOfSeveralTriangles()
{
  Random rng(5);
  struct Case
  {
    const char* Name;
    vtkSmartPointer<vtkPolyData> Data;
    bool Only; ///< every cell of several triangles
  };
  const Case cases[] = { { "stars, quads and strips", SeveralTriangleCells(rng, false, false), true },
    { "with triangles, a large quad under them", SeveralTriangleCells(rng, true, true), false },
    { "a large quad under triangles", TrianglesOverLargeQuad(), false } };
  for (const Case& c : cases)
  {
    for (int quality : { vtkBVHCellLocator::FAST, vtkBVHCellLocator::SAH })
    {
      vtkNew<vtkBVHCellLocator> loc;
      loc->SetBuildQuality(quality);
      loc->SetDataSet(c.Data);
      loc->BuildLocator();
      std::ostringstream before, after;
      loc->Print(before);
      const std::string only = "(every cell), found by their bounds in a tree ";
      LT_CHECK_MSG((before.str().find(only) != std::string::npos) == c.Only, c.Name << ": " << before.str());
      LT_CHECK(before.str().find("tree not built yet") != std::string::npos);
      const std::pair<int, int> found = CheckCellBounds(c.Data, loc, rng);
      loc->Print(after);
      LT_CHECK(after.str().find("in a tree built") != std::string::npos);
      LT_CHECK(found.first > 100 && found.second > 30);
      std::cout << c.Name << ", quality " << quality << ": " << found.first << " cells in 400 boxes, "
                << found.second << " of 600 points located, as brute force" << std::endl;
      // Segments that end exactly on a mesh point: every cell whose bounds
      // hold it is listed, as from the other end (rounding at t = 1 lost
      // them before).
      double db[6];
      c.Data->GetBounds(db);
      int ending = 0;
      vtkNew<vtkIdList> ids;
      for (int i = 0; i < 200; ++i)
      {
        double end[3], start[3];
        c.Data->GetPoint(static_cast<vtkIdType>(rng.Next(0, c.Data->GetNumberOfPoints() - 1)), end);
        for (int k = 0; k < 3; ++k)
        {
          start[k] = rng.Next(db[2 * k] - 1.0, db[2 * k + 1] + 1.0);
        }
        loc->FindCellsAlongLine(start, end, 0.0, ids);
        const std::vector<vtkIdType> listed = ToVector(ids);
        bool all = true;
        for (vtkIdType cell = 0; cell < c.Data->GetNumberOfCells(); ++cell)
        {
          double cb[6];
          c.Data->GetCellBounds(cell, cb);
          const bool holds = end[0] >= cb[0] && end[0] <= cb[1] && end[1] >= cb[2] && end[1] <= cb[3] &&
            end[2] >= cb[4] && end[2] <= cb[5];
          all = all && (!holds || std::binary_search(listed.begin(), listed.end(), cell));
        }
        ending += all ? 1 : 0;
      }
      LT_CHECK_MSG(ending == 200, c.Name << ": " << ending << " of 200 segments ending on a point list its cells");
    }
    // Four threads asking a fresh locator the same questions as one thread.
    vtkNew<vtkBVHCellLocator> serial, shared;
    for (vtkBVHCellLocator* loc : { serial.Get(), shared.Get() })
    {
      loc->SetDataSet(c.Data);
      loc->BuildLocator();
    }
    double b[6];
    c.Data->GetBounds(b);
    auto ask = [&b](vtkBVHCellLocator* loc, int seed) {
      Random r(seed);
      std::vector<vtkIdType> answers;
      vtkNew<vtkIdList> ids;
      vtkNew<vtkGenericCell> cell;
      double pc[3], w[16];
      for (int i = 0; i < 200; ++i)
      {
        double x[3] = { r.Next(b[0], b[1]), r.Next(b[2], b[3]), r.Next(b[4], b[5]) };
        answers.push_back(loc->FindCell(x, 0.0, cell, pc, w));
        const double box[6] = { x[0] - 0.05, x[0] + 0.05, x[1] - 0.05, x[1] + 0.05, x[2] - 0.05, x[2] + 0.05 };
        loc->FindCellsWithinBounds(const_cast<double*>(box), ids);
        const std::vector<vtkIdType> v = ToVector(ids);
        answers.insert(answers.end(), v.begin(), v.end());
      }
      return answers;
    };
    std::vector<vtkIdType> threaded[4];
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
    {
      threads.emplace_back([&, t] { threaded[t] = ask(shared, 100 + t); });
    }
    for (std::thread& t : threads)
    {
      t.join();
    }
    for (int t = 0; t < 4; ++t)
    {
      LT_CHECK_MSG(threaded[t] == ask(serial, 100 + t), c.Name << ": thread " << t << " answers otherwise");
    }
  }
  return 0;
}
