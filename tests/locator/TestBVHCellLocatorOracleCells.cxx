// Oracle tests beyond surfaces: vtkBVHCellLocator's point location, lines,
// closest points and cell lists on unstructured grids (hexahedra,
// tetrahedra, both) and its tolerance picking of vertices and lines mixed
// with triangles, against brute force and VTK's locators (checks in
// LocatorTestUtils.cxx).
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"

#include "vtkAppendFilter.h"
#include "vtkCellLocator.h"
#include "vtkCellType.h"
#include "vtkDelaunay3D.h"
#include "vtkModifiedBSPTree.h"
#include "vtkStaticCellLocator.h"
#include "vtkUnstructuredGrid.h"

using namespace locatortest;

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

/// FindCell at points just off and just inside tetrahedra's faces (0.1%
/// to 2% of the tet's size: around vtkTetra::EvaluatePosition's tolerance
/// of 0.001 and the locator's cheap rejection at 0.01): the cell and
/// pcoords of the first cell in id order whose bounds hold the point and
/// whose EvaluatePosition accepts it, as brute force finds them.
void CheckFindCellNearFaces(vtkUnstructuredGrid* ug, const char* name)
{
  vtkNew<vtkBVHCellLocator> bvh;
  bvh->SetDataSet(ug);
  bvh->BuildLocator();
  Random rng(57);
  vtkNew<vtkGenericCell> cell, refCell;
  std::vector<double> w(static_cast<size_t>(ug->GetMaxCellSize())), refW(w.size());
  int located = 0, probes = 0;
  for (int i = 0; i < 150; ++i)
  {
    const vtkIdType c = static_cast<vtkIdType>(rng.Next(0, 0.999) * ug->GetNumberOfCells());
    ug->GetCell(c, cell);
    double p[4][3];
    for (int k = 0; k < 4; ++k)
    {
      cell->GetPoints()->GetPoint(k, p[k]);
    }
    // A point of face (0, 1, 2), pushed along the direction from the
    // opposite vertex by a fraction of the tet's extent.
    const double a = rng.Next(0.05, 0.9), b = rng.Next(0.05, 0.9) * (1 - a);
    for (double push : { -0.02, -0.008, -0.002, -0.0005, 0.0005, 0.002, 0.008, 0.02 })
    {
      double x[3];
      for (int k = 0; k < 3; ++k)
      {
        const double onFace = (1 - a - b) * p[0][k] + a * p[1][k] + b * p[2][k];
        x[k] = onFace + push * (onFace - p[3][k]);
      }
      double pc[3], refPc[3] = { 0, 0, 0 };
      const vtkIdType ours = bvh->FindCell(x, 0.0, cell, pc, w.data());
      const vtkIdType ref = BruteForceFindCell(ug, x, refCell, refW.data());
      if (ref >= 0)
      {
        double cp[3], d2;
        int sub;
        refCell->EvaluatePosition(x, cp, sub, refPc, d2, refW.data());
      }
      ++probes;
      located += ours >= 0 ? 1 : 0;
      LT_CHECK_MSG(ours == ref && (ours < 0 || (pc[0] == refPc[0] && pc[1] == refPc[1] && pc[2] == refPc[2])),
        name << " near a face: FindCell " << ours << ", brute force " << ref);
    }
  }
  std::cout << name << ": FindCell near faces located " << located << "/" << probes << std::endl;
  LT_CHECK(located > probes / 4 && located < probes);
}

int TestOracleUnstructuredGrid()
{
  CheckVolume(MakeHexGrid(8), "hexahedra");
  CheckVolume(MakeTetMesh(300), "tetrahedra");
  CheckFindCellNearFaces(MakeTetMesh(300), "tetrahedra");
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
