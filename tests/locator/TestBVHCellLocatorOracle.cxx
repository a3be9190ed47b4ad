// Oracle tests: vtkBVHCellLocator against brute force over VTK's own cell
// tests and against vtkStaticCellLocator, vtkCellLocator and
// vtkModifiedBSPTree, for every query kind, on triangle meshes (generated,
// bunny), quads / strips / polygons, unstructured grids and lines/vertices.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"

#include "vtkAppendFilter.h"
#include "vtkCellLocator.h"
#include "vtkCellType.h"
#include "vtkDelaunay3D.h"
#include "vtkModifiedBSPTree.h"
#include "vtkPlaneSource.h"
#include "vtkStaticCellLocator.h"
#include "vtkStripper.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangle.h"
#include "vtkUnstructuredGrid.h"

using namespace locatortest;

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

/// Nearest-hit queries: ours must agree with the brute-force reference on
/// every segment (including segments aimed exactly at shared vertices and
/// edges); VTK's locators are counted, not asserted.
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

/// Closest point (all overloads) against brute force (or, on big meshes,
/// vtkStaticCellLocator) and vtkCellLocator.
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
      std::vector<vtkIdType> ref;
      for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
      {
        double cb[6];
        ds->GetCellBounds(c, cb);
        for (int k = 0; k < 3; ++k)
        {
          cb[2 * k] -= tol;
          cb[2 * k + 1] += tol;
        }
        if (SegmentMeetsBox(s.P1, s.P2, cb))
        {
          ref.push_back(c);
        }
      }
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

/// All hits along a segment: same cells as brute force, sorted along it.
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

std::vector<Segment> SurfaceSegments(vtkPolyData* pd, int nRandom, int nAimed, int seed)
{
  Random rng(seed);
  std::vector<Segment> segs = RandomSegments(pd, nRandom, rng);
  std::vector<std::pair<vtkIdType, vtkIdType>> edges;
  std::vector<vtkIdType> verts;
  InteriorEdgesAndVertices(pd, edges, verts);
  for (int i = 0; i < nAimed && !verts.empty() && !edges.empty(); ++i)
  {
    double target[3];
    if (i % 2 == 0)
    {
      pd->GetPoint(verts[static_cast<size_t>(rng.Next(0, 0.999999) * verts.size())], target);
    }
    else
    {
      const auto& e = edges[static_cast<size_t>(rng.Next(0, 0.999999) * edges.size())];
      double a[3], b[3];
      pd->GetPoint(e.first, a);
      pd->GetPoint(e.second, b);
      const double w = (i % 4 == 1) ? 0.5 : rng.Next(0.1, 0.9);
      for (int k = 0; k < 3; ++k)
      {
        target[k] = a[k] + w * (b[k] - a[k]);
      }
    }
    segs.push_back(SegmentThrough(pd, target, rng));
  }
  return segs;
}

int CheckSurface(vtkPolyData* pd, int nRandom, int nAimed, int nClosest, bool bruteClosest, const char* name)
{
  vtkNew<vtkBVHCellLocator> bvh;
  bvh->SetDataSet(pd);
  bvh->BuildLocator();
  vtkNew<vtkStaticCellLocator> st;
  st->SetDataSet(pd);
  st->BuildLocator();
  vtkNew<vtkCellLocator> cl;
  cl->SetDataSet(pd);
  cl->BuildLocator();
  vtkNew<vtkModifiedBSPTree> bsp;
  bsp->SetDataSet(pd);
  bsp->BuildLocator();
  const double diag = Diagonal(pd);
  std::cout << name << ": " << pd->GetNumberOfCells() << " cells, " << bvh->GetNumberOfNodes()
            << " BVH nodes, depth " << bvh->GetTreeDepth() << std::endl;
  CheckIntersectWithLine(pd, bvh, { st, cl, bsp }, SurfaceSegments(pd, nRandom, nAimed, 3),
    1e-9 * diag, name);
  CheckClosestPoint(pd, bvh, st, cl, nClosest, bruteClosest, name);
  CheckBoxAndLineLists(pd, bvh, st, true, name);
  CheckAllHits(pd, bvh, bsp, 1e-12 * diag, name);
  return 0;
}
} // namespace

int TestOracleGeneratedMesh()
{
  auto pd = MakeBumpySphere(40);
  CheckSurface(pd, 300, 300, 150, true, "generated mesh");
  return 0;
}

int TestOracleBunny()
{
  auto pd = LoadBunny();
  if (!pd)
  {
    return 1;
  }
  CheckSurface(pd, 60, 80, 150, false, "bunny");
  return 0;
}

/// Quads (planar, rotated), polygons (hexagons) and triangle strips: the fast
/// path triangulates them and must still report the original cell with its
/// own pcoords/subId.
int TestOracleQuadsStripsPolygons()
{
  // Quads from a plane source, tilted.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  plane->SetResolution(12, 9);
  vtkNew<vtkTransform> xf;
  xf->RotateX(30);
  xf->RotateY(20);
  xf->Scale(2.0, 1.5, 1.0);
  vtkNew<vtkTransformPolyDataFilter> tf;
  tf->SetInputConnection(plane->GetOutputPort());
  tf->SetTransform(xf);
  tf->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  tf->Update();
  vtkNew<vtkPolyData> quads;
  quads->DeepCopy(tf->GetOutput());

  // Hexagons in the plane z = 0.3 x + 0.1 y, plus strips of a bumpy sphere.
  vtkNew<vtkPoints> hpts;
  hpts->SetDataTypeToDouble(); // planar to double precision, as vtkPolygon assumes
  vtkNew<vtkCellArray> hex;
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 6; ++j)
    {
      const double cx = 1.5 * i, cy = std::sqrt(3.0) * (j + 0.5 * (i % 2));
      vtkIdType ids[6];
      for (int k = 0; k < 6; ++k)
      {
        const double a = vtkMath::Pi() / 3.0 * k;
        const double x = cx + std::cos(a), y = cy + std::sin(a);
        ids[k] = hpts->InsertNextPoint(x, y, 0.3 * x + 0.1 * y);
      }
      hex->InsertNextCell(6, ids);
    }
  }
  vtkNew<vtkPolyData> hexes;
  hexes->SetPoints(hpts);
  hexes->SetPolys(hex);

  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(MakeBumpySphere(24));
  stripper->Update();
  vtkNew<vtkPolyData> strips;
  strips->DeepCopy(stripper->GetOutput());

  struct Case
  {
    vtkPolyData* Data;
    const char* Name;
  } cases[] = { { quads, "quads" }, { hexes, "hexagons" }, { strips, "triangle strips" } };
  for (const auto& c : cases)
  {
    vtkNew<vtkBVHCellLocator> bvh;
    bvh->SetDataSet(c.Data);
    bvh->BuildLocator();
    vtkNew<vtkStaticCellLocator> st;
    st->SetDataSet(c.Data);
    st->BuildLocator();
    vtkNew<vtkCellLocator> cl;
    cl->SetDataSet(c.Data);
    cl->BuildLocator();
    Random rng(5);
    const std::vector<Segment> segs = RandomSegments(c.Data, 300, rng);
    CheckIntersectWithLine(c.Data, bvh, { st }, segs, 1e-9 * Diagonal(c.Data), c.Name);
    CheckClosestPoint(c.Data, bvh, st, cl, 100, true, c.Name);
    LT_CHECK(bvh->GetNumberOfPrimitives() > c.Data->GetNumberOfCells());

    // Quads: pcoords are exactly those of vtkQuad.
    vtkNew<vtkGenericCell> cell;
    int compared = 0;
    for (const Segment& s : segs)
    {
      double t, x[3], pc[3];
      int sub;
      vtkIdType cellId;
      if (!bvh->IntersectWithLine(s.P1, s.P2, 0.0, t, x, pc, sub, cellId, cell))
      {
        continue;
      }
      double t2, x2[3], pc2[3];
      int sub2;
      if (CellIntersect(cell, s.P1, s.P2, 1e-9 * Diagonal(c.Data), t2, x2, pc2, sub2) &&
        std::abs(t2 - t) < 1e-9)
      {
        if (cell->GetCellType() == VTK_TRIANGLE_STRIP)
        {
          LT_CHECK(sub == sub2);
        }
        if (cell->GetCellType() == VTK_QUAD || cell->GetCellType() == VTK_TRIANGLE_STRIP)
        {
          for (int k = 0; k < 3; ++k)
          {
            LT_CHECK_MSG(std::abs(pc[k] - pc2[k]) < 1e-7, c.Name << " pcoords " << pc[k] << " vs " << pc2[k]);
          }
        }
        ++compared;
      }
    }
    LT_CHECK(compared > 0);
  }
  return 0;
}

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> MakeHexGrid(int n)
{
  Random rng(21);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (int k = 0; k <= n; ++k)
  {
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= n; ++i)
      {
        const double jitter = (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n) ? 0.2 : 0.0;
        pts->InsertNextPoint(i + rng.Next(-jitter, jitter), j + rng.Next(-jitter, jitter),
          k + rng.Next(-jitter, jitter));
      }
    }
  }
  auto ug = vtkSmartPointer<vtkUnstructuredGrid>::New();
  ug->SetPoints(pts);
  auto id = [n](int i, int j, int k) { return static_cast<vtkIdType>(i + (n + 1) * (j + (n + 1) * k)); };
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        vtkIdType h[8] = { id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
          id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1) };
        ug->InsertNextCell(VTK_HEXAHEDRON, 8, h);
      }
    }
  }
  return ug;
}

vtkSmartPointer<vtkUnstructuredGrid> MakeTetMesh(int nPoints)
{
  Random rng(23);
  vtkNew<vtkPoints> pts;
  for (int i = 0; i < nPoints; ++i)
  {
    pts->InsertNextPoint(rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1));
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(pts);
  vtkNew<vtkDelaunay3D> del;
  del->SetInputData(cloud);
  del->Update();
  auto ug = vtkSmartPointer<vtkUnstructuredGrid>::New();
  ug->DeepCopy(del->GetOutput());
  return ug;
}

void CheckVolume(vtkUnstructuredGrid* ug, const char* name)
{
  vtkNew<vtkBVHCellLocator> bvh;
  bvh->SetDataSet(ug);
  bvh->BuildLocator();
  vtkNew<vtkStaticCellLocator> st;
  st->SetDataSet(ug);
  st->BuildLocator();
  vtkNew<vtkCellLocator> cl;
  cl->SetDataSet(ug);
  cl->BuildLocator();
  vtkNew<vtkModifiedBSPTree> bsp;
  bsp->SetDataSet(ug);
  bsp->BuildLocator();
  std::cout << name << ": " << ug->GetNumberOfCells() << " cells" << std::endl;

  // Point location: ours is the lowest containing cell id; VTK's answer,
  // when it has one, contains the point too.
  Random rng(31);
  double b[6];
  ug->GetBounds(b);
  vtkNew<vtkGenericCell> cell;
  std::vector<double> w(static_cast<size_t>(ug->GetMaxCellSize()));
  int located = 0, staticDisagrees = 0;
  for (int i = 0; i < 300; ++i)
  {
    double x[3];
    for (int k = 0; k < 3; ++k)
    {
      x[k] = rng.Next(b[2 * k] - 0.1, b[2 * k + 1] + 0.1);
    }
    double pc[3];
    const vtkIdType ours = bvh->FindCell(x, 0.0, cell, pc, w.data());
    LT_CHECK(bvh->FindCell(x) == ours);
    vtkIdType ref = -1;
    vtkNew<vtkGenericCell> c2;
    for (vtkIdType c = 0; c < ug->GetNumberOfCells() && ref < 0; ++c)
    {
      ug->GetCell(c, c2);
      double cp[3], pc2[3], d2;
      int sub;
      if (c2->EvaluatePosition(x, cp, sub, pc2, d2, w.data()) == 1 && d2 <= 0.0)
      {
        ref = c;
      }
    }
    LT_CHECK_MSG(ours == ref, name << " FindCell " << ours << " vs brute force " << ref);
    if (ours >= 0)
    {
      ++located;
      LT_CHECK(SameCellPoints(ug, ours, cell));
      LT_CHECK(bvh->InsideCellBounds(x, ours));
    }
    const vtkIdType theirs = st->FindCell(x, 0.0, c2, pc, w.data());
    staticDisagrees += ((theirs >= 0) != (ours >= 0)) ? 1 : 0;
  }
  std::cout << name << ": FindCell located " << located << "/300 points; vtkStaticCellLocator "
            << "disagrees on inside/outside for " << staticDisagrees << std::endl;
  LT_CHECK(located > 0);
  LT_CHECK(staticDisagrees == 0);

  // Lines: the general path uses the cells' own tests, so t and the cell id
  // (lowest on ties) equal brute force exactly.
  const std::vector<Segment> segs = RandomSegments(ug, 150, rng);
  int hits = 0;
  for (const Segment& s : segs)
  {
    const RefHit ref = BruteForceHit(ug, s.P1, s.P2, 0.0);
    double t, x[3], pc[3];
    int sub;
    vtkIdType cellId;
    const int hit = bvh->IntersectWithLine(s.P1, s.P2, 0.0, t, x, pc, sub, cellId, cell);
    LT_CHECK(hit == (ref.Hit ? 1 : 0));
    if (hit && ref.Hit)
    {
      ++hits;
      LT_CHECK(t == ref.T);
      LT_CHECK(cellId == ref.CellId);
      LT_CHECK(SameCellPoints(ug, cellId, cell));
    }
    double st_t, st_x[3], st_pc[3];
    int st_sub;
    vtkIdType st_cell;
    if (st->IntersectWithLine(s.P1, s.P2, 0.0, st_t, st_x, st_pc, st_sub, st_cell) && hit)
    {
      LT_CHECK(std::abs(st_t - t) < 1e-12);
    }
  }
  LT_CHECK(hits > 0);
  CheckClosestPoint(ug, bvh, st, cl, 100, true, name);
  CheckBoxAndLineLists(ug, bvh, st, true, name);
  CheckAllHits(ug, bvh, bsp, 0.0, name);
}
} // namespace

int TestOracleUnstructuredGrid()
{
  CheckVolume(MakeHexGrid(8), "hexahedra");
  CheckVolume(MakeTetMesh(300), "tetrahedra");
  // Mixed: hexahedra and tetrahedra appended into one grid.
  vtkNew<vtkAppendFilter> append;
  auto tets = MakeTetMesh(200);
  append->AddInputData(MakeHexGrid(4));
  append->AddInputData(tets);
  append->Update();
  CheckVolume(append->GetOutput(), "hexahedra + tetrahedra");
  return 0;
}

/// Vertices, poly-vertices, lines and poly-lines (picked within tol as
/// vtkCellPicker expects) mixed with triangles.
int TestOracleLinesAndVertices()
{
  Random rng(41);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> verts, lines, polys;
  for (int i = 0; i < 60; ++i)
  {
    vtkIdType id = pts->InsertNextPoint(rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1));
    verts->InsertNextCell(1, &id);
  }
  for (int i = 0; i < 10; ++i)
  {
    vtkIdType ids[3];
    for (auto& id : ids)
    {
      id = pts->InsertNextPoint(rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1));
    }
    verts->InsertNextCell(3, ids);
  }
  for (int i = 0; i < 60; ++i)
  {
    vtkIdType ids[2];
    for (auto& id : ids)
    {
      id = pts->InsertNextPoint(rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1));
    }
    lines->InsertNextCell(2, ids);
  }
  for (int i = 0; i < 10; ++i)
  {
    vtkIdType ids[5];
    for (auto& id : ids)
    {
      id = pts->InsertNextPoint(rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1));
    }
    lines->InsertNextCell(5, ids);
  }
  for (int i = 0; i < 20; ++i)
  {
    vtkIdType ids[3];
    const double c[3] = { rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1) };
    for (auto& id : ids)
    {
      id = pts->InsertNextPoint(
        c[0] + rng.Next(-0.2, 0.2), c[1] + rng.Next(-0.2, 0.2), c[2] + rng.Next(-0.2, 0.2));
    }
    polys->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetVerts(verts);
  pd->SetLines(lines);
  pd->SetPolys(polys);

  vtkNew<vtkBVHCellLocator> bvh;
  bvh->SetDataSet(pd);
  bvh->BuildLocator();
  vtkNew<vtkStaticCellLocator> st;
  st->SetDataSet(pd);
  st->BuildLocator();
  vtkNew<vtkCellLocator> cl;
  cl->SetDataSet(pd);
  cl->BuildLocator();
  const std::vector<Segment> segs = RandomSegments(pd, 400, rng);
  vtkNew<vtkGenericCell> cell;
  int hitLines = 0, hitVerts = 0, hitTris = 0;
  for (double tol : { 0.02, 0.05 })
  {
    for (const Segment& s : segs)
    {
      const RefHit ref = BruteForceHit(pd, s.P1, s.P2, tol);
      double t, x[3], pc[3];
      int sub;
      vtkIdType cellId;
      const int hit = bvh->IntersectWithLine(s.P1, s.P2, tol, t, x, pc, sub, cellId, cell);
      LT_CHECK_MSG(hit == (ref.Hit ? 1 : 0), "tol " << tol << " ours " << hit << " ref cell " << ref.CellId);
      if (!(hit && ref.Hit))
      {
        continue;
      }
      LT_CHECK_MSG(std::abs(t - ref.T) < 1e-9, "t " << t << " vs " << ref.T);
      LT_CHECK(cellId == ref.CellId || std::abs(t - ref.T) < 1e-12);
      LT_CHECK(SameCellPoints(pd, cellId, cell));
      const int type = pd->GetCellType(cellId);
      hitLines += (type == VTK_LINE || type == VTK_POLY_LINE) ? 1 : 0;
      hitVerts += (type == VTK_VERTEX || type == VTK_POLY_VERTEX) ? 1 : 0;
      hitTris += type == VTK_TRIANGLE ? 1 : 0;
    }
  }
  std::cout << "lines and vertices: hits on lines " << hitLines << ", vertices " << hitVerts
            << ", triangles " << hitTris << std::endl;
  LT_CHECK(hitLines > 0 && hitVerts > 0 && hitTris > 0);
  CheckClosestPoint(pd, bvh, st, cl, 100, true, "lines and vertices");
  return 0;
}
