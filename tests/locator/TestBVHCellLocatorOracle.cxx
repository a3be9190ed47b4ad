// Oracle tests on surfaces: vtkBVHCellLocator against brute force over
// VTK's own cell tests and against vtkStaticCellLocator, vtkCellLocator and
// vtkModifiedBSPTree, for every query kind, on triangle meshes (generated,
// bunny) and on quads / strips / polygons. The checks are in
// LocatorTestUtils.cxx; volumes, lines and vertices in
// TestBVHCellLocatorOracleCells.cxx.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"

#include "vtkCellLocator.h"
#include "vtkCellType.h"
#include "vtkModifiedBSPTree.h"
#include "vtkPlaneSource.h"
#include "vtkStaticCellLocator.h"
#include "vtkStripper.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

using namespace locatortest;

namespace
{
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
