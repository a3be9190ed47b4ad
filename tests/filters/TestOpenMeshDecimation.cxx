// vtkOpenMeshDecimation: targets, error bound (measured as sampled surface
// distances both ways), boundaries, non-manifold and degenerate input,
// attributes, bad input, and a side-by-side with vtkQuadricDecimation.
#include "vtkrtFiltersTestUtilities.h"

#include "vtkOpenMeshClean.h"
#include "vtkOpenMeshDecimation.h"

#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataNormals.h"
#include "vtkQuadricDecimation.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkTriangleFilter.h"

#include <limits>
#include <map>

using vtkrt_test::FieldCount;
using vtkrt_test::JudgeWithOpenMesh;
using vtkrt_test::SurfaceDistance;

namespace
{

// Stated tolerances. A halfedge collapse removes two triangles (one on a
// boundary), so a count target is met to within 2.
constexpr vtkIdType CountTolerance = 2;
// MaximumError bounds the distance of every removed input vertex exactly;
// points inside input faces, and the decimated surface seen from the input,
// are allowed this factor over the bound.
constexpr double SampledErrorFactor = 1.25;
// At the same triangle count our Hausdorff distance (halfedge collapse keeps
// input vertices) stays within this factor of vtkQuadricDecimation's
// (which places vertices optimally).
constexpr double VersusVTKFactor = 2.5;

vtkSmartPointer<vtkPolyData> Sphere(int theta, int phi)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(theta);
  sphere->SetPhiResolution(phi);
  sphere->Update();
  return sphere->GetOutput();
}

// A wavy open grid: boundaries on all four sides.
vtkSmartPointer<vtkPolyData> WavyGrid(int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(resolution, resolution);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  auto grid = vtkSmartPointer<vtkPolyData>::New();
  grid->DeepCopy(triangles->GetOutput());
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double p[3];
    grid->GetPoint(i, p);
    p[2] = 0.05 * std::sin(6.0 * p[0]) * std::cos(4.0 * p[1]);
    grid->GetPoints()->SetPoint(i, p);
  }
  return grid;
}

// A sphere with a cap of faces removed (a hole), unused points kept.
vtkSmartPointer<vtkPolyData> SphereWithHole(int resolution)
{
  auto sphere = Sphere(resolution, resolution);
  vtkNew<vtkCellArray> polys;
  auto iter = vtk::TakeSmartPointer(sphere->GetPolys()->NewIterator());
  vtkIdType n;
  const vtkIdType* ids;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    iter->GetCurrentCell(n, ids);
    double c[3] = { 0, 0, 0 };
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[3];
      sphere->GetPoint(ids[k], p);
      c[0] += p[0] / n;
    }
    if (c[0] < 0.35)
    {
      polys->InsertNextCell(n, ids);
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(sphere->GetPoints());
  out->SetPolys(polys);
  return out;
}

vtkIdType BoundaryLoops(vtkPolyData* pd)
{
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(pd);
  clean->Update();
  return clean->GetNumberOfBoundaryLoops();
}

// Largest distance from the input's vertices to the output surface: the
// quantity MaximumError bounds exactly.
double VertexDistance(vtkPolyData* from, vtkPolyData* to)
{
  return SurfaceDistance(from, to, 0, 1).Max;
}

void TestTargets()
{
  auto sphere = Sphere(64, 64);
  const vtkIdType n = sphere->GetNumberOfPolys();
  vtkNew<vtkOpenMeshDecimation> decimate;
  decimate->SetInputData(sphere);
  for (vtkIdType target : { vtkIdType(2000), vtkIdType(501), vtkIdType(100) })
  {
    decimate->SetTargetModeToCount();
    decimate->SetTargetNumberOfTriangles(target);
    decimate->Update();
    const vtkIdType got = decimate->GetOutput()->GetNumberOfPolys();
    std::cout << "sphere " << n << " -> target " << target << ": " << got << std::endl;
    VTKRT_CHECK(got <= target && got >= target - CountTolerance, "count target " << target);
    VTKRT_CHECK(FieldCount(decimate->GetOutput(), "NumberOfOutputTriangles") == got, "reported");
    VTKRT_CHECK(JudgeWithOpenMesh(decimate->GetOutput()).ClosedManifold(), "still closed");
  }
  decimate->SetTargetModeToReduction();
  decimate->SetTargetReduction(0.75);
  decimate->Update();
  const vtkIdType wanted = static_cast<vtkIdType>(std::llround(0.25 * n));
  const vtkIdType got = decimate->GetOutput()->GetNumberOfPolys();
  VTKRT_CHECK(got <= wanted && got >= wanted - CountTolerance, "reduction target: " << got);
  // Reduction 0 leaves the mesh alone.
  decimate->SetTargetReduction(0.0);
  decimate->Update();
  VTKRT_CHECK(decimate->GetOutput()->GetNumberOfPolys() == n, "reduction 0 keeps all");
}

void TestErrorBound(vtkPolyData* mesh, const char* name, double relativeBound)
{
  const double bound = relativeBound * mesh->GetLength();
  vtkNew<vtkOpenMeshDecimation> decimate;
  decimate->SetInputData(mesh);
  decimate->SetTargetModeToErrorBound();
  decimate->SetMaximumError(bound);
  decimate->Update();
  vtkPolyData* out = decimate->GetOutput();
  const double vertexError = VertexDistance(mesh, out);
  const auto forward = SurfaceDistance(mesh, out, 10000, 3);
  const auto backward = SurfaceDistance(out, mesh, 10000, 4);
  std::cout << name << ": error bound " << bound << " -> " << mesh->GetNumberOfPolys() << " to "
            << out->GetNumberOfPolys() << " triangles; input vertices max " << vertexError
            << "; sampled input->output max " << forward.Max << " mean " << forward.Mean
            << "; output->input max " << backward.Max << " mean " << backward.Mean << std::endl;
  VTKRT_CHECK(out->GetNumberOfPolys() < mesh->GetNumberOfPolys() / 2, "it did decimate");
  VTKRT_CHECK(vertexError <= bound * (1 + 1e-9), "removed vertices within the bound");
  VTKRT_CHECK(forward.Max <= SampledErrorFactor * bound, "input surface within the bound");
  VTKRT_CHECK(backward.Max <= SampledErrorFactor * bound, "output surface within the bound");
}

void TestVersusVTK(vtkPolyData* mesh, const char* name, double reduction)
{
  vtkNew<vtkOpenMeshDecimation> ours;
  ours->SetInputData(mesh);
  ours->SetTargetReduction(reduction);
  ours->Update();
  vtkNew<vtkQuadricDecimation> theirs;
  theirs->SetInputData(mesh);
  theirs->SetTargetReduction(reduction);
  theirs->Update();
  vtkPolyData* a = ours->GetOutput();
  vtkPolyData* b = theirs->GetOutput();
  const auto aFwd = SurfaceDistance(mesh, a, 10000, 5), aBwd = SurfaceDistance(a, mesh, 10000, 6);
  const auto bFwd = SurfaceDistance(mesh, b, 10000, 5), bBwd = SurfaceDistance(b, mesh, 10000, 6);
  const double aHausdorff = std::max(aFwd.Max, aBwd.Max);
  const double bHausdorff = std::max(bFwd.Max, bBwd.Max);
  std::cout << name << " reduction " << reduction << ": " << mesh->GetNumberOfPolys()
            << " triangles -> vtkOpenMeshDecimation " << a->GetNumberOfPolys() << " (Hausdorff "
            << aHausdorff << ", mean " << aFwd.Mean << "/" << aBwd.Mean
            << "), vtkQuadricDecimation " << b->GetNumberOfPolys() << " (Hausdorff " << bHausdorff
            << ", mean " << bFwd.Mean << "/" << bBwd.Mean << "), ratio " << aHausdorff / bHausdorff
            << std::endl;
  const vtkIdType wanted =
    static_cast<vtkIdType>(std::llround((1 - reduction) * mesh->GetNumberOfPolys()));
  VTKRT_CHECK(std::abs(a->GetNumberOfPolys() - wanted) <= CountTolerance, "ours on target");
  VTKRT_CHECK(aHausdorff <= VersusVTKFactor * bHausdorff, "within the stated factor of VTK's");
}

void TestBoundaries()
{
  auto grid = WavyGrid(40);
  vtkNew<vtkOpenMeshDecimation> decimate;
  decimate->SetInputData(grid);
  decimate->SetTargetReduction(0.9);
  decimate->PreserveBoundariesOn();
  decimate->Update();
  vtkPolyData* out = decimate->GetOutput();
  // Every boundary point of the grid is still there, at the same place.
  std::map<std::array<double, 3>, int> outPoints;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    outPoints[{ p[0], p[1], p[2] }] = 1;
  }
  int boundaryPoints = 0, kept = 0;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double p[3];
    grid->GetPoint(i, p);
    if (std::abs(std::abs(p[0]) - 0.5) < 1e-12 || std::abs(std::abs(p[1]) - 0.5) < 1e-12)
    {
      ++boundaryPoints;
      kept += outPoints.count({ p[0], p[1], p[2] }) ? 1 : 0;
    }
  }
  std::cout << "wavy grid: " << grid->GetNumberOfPolys() << " -> " << out->GetNumberOfPolys()
            << " triangles, boundary points kept " << kept << "/" << boundaryPoints << ", locked "
            << decimate->GetNumberOfLockedVertices() << std::endl;
  VTKRT_CHECK(boundaryPoints == 160 && kept == boundaryPoints, "boundary preserved");
  VTKRT_CHECK(decimate->GetNumberOfLockedVertices() == boundaryPoints, "boundary locked");
  VTKRT_CHECK(out->GetNumberOfPolys() < grid->GetNumberOfPolys() / 2, "interior decimated");
  VTKRT_CHECK(BoundaryLoops(out) == 1, "still one boundary loop");

  // Without preservation the boundary decimates too, but stays within the bound.
  const double bound = 0.002 * grid->GetLength();
  decimate->PreserveBoundariesOff();
  decimate->SetTargetModeToErrorBound();
  decimate->SetMaximumError(bound);
  decimate->Update();
  VTKRT_CHECK(VertexDistance(grid, out) <= bound * (1 + 1e-9), "grid within bound");
  VTKRT_CHECK(BoundaryLoops(out) == 1, "open grid stays open");

  // A sphere with a hole keeps its hole.
  auto holed = SphereWithHole(48);
  decimate->SetInputData(holed);
  decimate->SetTargetModeToReduction();
  decimate->SetTargetReduction(0.8);
  decimate->SetMaximumError(VTK_DOUBLE_MAX);
  decimate->Update();
  const vtkIdType wanted = std::llround(0.2 * holed->GetNumberOfPolys());
  std::cout << "sphere with hole: " << holed->GetNumberOfPolys() << " -> "
            << out->GetNumberOfPolys() << " triangles, " << BoundaryLoops(out) << " hole(s)"
            << std::endl;
  VTKRT_CHECK(std::abs(out->GetNumberOfPolys() - wanted) <= CountTolerance, "holed on target");
  VTKRT_CHECK(BoundaryLoops(out) == 1, "hole kept");
  VTKRT_CHECK(JudgeWithOpenMesh(out).RejectedFaces == 0, "still a manifold");
}

void TestNonManifoldAndDegenerate()
{
  // A sphere plus a fin on one of its edges (three faces on that edge), a
  // face with a repeated point and a zero-area face.
  auto sphere = Sphere(32, 32);
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere);
  vtkIdType n;
  const vtkIdType* ids;
  mesh->GetPolys()->GetCellAtId(100, n, ids);
  const vtkIdType a = ids[0], b = ids[1];
  double pa[3], pb[3];
  mesh->GetPoint(a, pa);
  mesh->GetPoint(b, pb);
  const vtkIdType apex = mesh->GetPoints()->InsertNextPoint(
    1.5 * (pa[0] + pb[0]), 1.5 * (pa[1] + pb[1]), 1.5 * (pa[2] + pb[2]));
  const vtkIdType fin[] = { a, b, apex };
  mesh->GetPolys()->InsertNextCell(3, fin);
  const vtkIdType repeated[] = { a, a, b };
  mesh->GetPolys()->InsertNextCell(3, repeated);
  const vtkIdType mid = mesh->GetPoints()->InsertNextPoint(
    0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2]));
  const vtkIdType flat[] = { a, mid, b };
  mesh->GetPolys()->InsertNextCell(3, flat);
  mesh->BuildCells();

  vtkNew<vtkrt_test::ErrorCatcher> catcher;
  vtkNew<vtkOpenMeshDecimation> decimate;
  catcher->Watch(decimate);
  decimate->SetInputData(mesh);
  decimate->SetTargetModeToCount();
  decimate->SetTargetNumberOfTriangles(300);
  decimate->Update();
  vtkPolyData* out = decimate->GetOutput();
  std::cout << "sphere + fin + degenerate: " << mesh->GetNumberOfPolys() << " -> "
            << out->GetNumberOfPolys() << ", passed through "
            << decimate->GetNumberOfPassedThroughFaces() << ", locked "
            << decimate->GetNumberOfLockedVertices() << std::endl;
  VTKRT_CHECK(catcher->Errors.empty() && catcher->Warnings.empty(), "no message");
  VTKRT_CHECK(decimate->GetNumberOfPassedThroughFaces() >= 1, "the third face on the edge");
  // The sphere's normals were not extended to the two added points: a
  // malformed array is dropped and named, never read past its end.
  auto* dropped =
    vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("DroppedArrays"));
  VTKRT_CHECK(
    dropped && dropped->GetNumberOfValues() == 1 && dropped->GetValue(0) == "point:Normals",
    "short normals array dropped");
  VTKRT_CHECK(out->GetPointData()->GetNormals() == nullptr, "and not in the output");
  VTKRT_CHECK(std::abs(out->GetNumberOfPolys() - 300) <= CountTolerance, "on target");
  // The points of the passed-through faces survive.
  bool apexKept = false;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    out->GetPoint(i, p);
    mesh->GetPoint(apex, q);
    apexKept = apexKept || vtkMath::Distance2BetweenPoints(p, q) == 0.0;
  }
  VTKRT_CHECK(apexKept, "fin apex kept");

  // Three triangles on one edge and nothing else.
  vtkNew<vtkPolyData> fan;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, 0);
  pts->InsertNextPoint(1, 0, 0);
  pts->InsertNextPoint(0.5, 1, 0);
  pts->InsertNextPoint(0.5, -1, 0);
  pts->InsertNextPoint(0.5, 0, 1);
  vtkNew<vtkCellArray> polys;
  const vtkIdType f0[] = { 0, 1, 2 }, f1[] = { 1, 0, 3 }, f2[] = { 0, 1, 4 };
  polys->InsertNextCell(3, f0);
  polys->InsertNextCell(3, f1);
  polys->InsertNextCell(3, f2);
  fan->SetPoints(pts);
  fan->SetPolys(polys);
  decimate->SetInputData(fan);
  decimate->SetTargetNumberOfTriangles(0);
  decimate->Update();
  VTKRT_CHECK(catcher->Errors.empty(), "fan: no error");
  VTKRT_CHECK(decimate->GetOutput()->GetNumberOfPolys() >= 1, "fan: the passed face stays");
}

void TestAttributes()
{
  auto sphere = Sphere(40, 40);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(sphere);
  normals->ComputeCellNormalsOn();
  normals->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(normals->GetOutput());
  vtkNew<vtkIdTypeArray> pointIds, cellIds;
  pointIds->SetName("InputPointId");
  cellIds->SetName("InputCellId");
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    pointIds->InsertNextValue(i);
  }
  for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i)
  {
    cellIds->InsertNextValue(i);
  }
  mesh->GetPointData()->AddArray(pointIds);
  mesh->GetCellData()->AddArray(cellIds);

  vtkNew<vtkOpenMeshDecimation> decimate;
  decimate->SetInputData(mesh);
  decimate->SetTargetReduction(0.9);
  decimate->Update();
  vtkPolyData* out = decimate->GetOutput();
  auto* outIds = vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("InputPointId"));
  bool pointsOk = outIds && out->GetPointData()->GetNormals();
  for (vtkIdType i = 0; pointsOk && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    out->GetPoint(i, p);
    mesh->GetPoint(outIds->GetValue(i), q);
    pointsOk = p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  }
  VTKRT_CHECK(pointsOk, "point data carried exactly (points are input points)");
  auto* outCellIds = vtkIdTypeArray::SafeDownCast(out->GetCellData()->GetArray("InputCellId"));
  VTKRT_CHECK(
    outCellIds && outCellIds->GetNumberOfValues() == out->GetNumberOfPolys(), "cell data carried");
  VTKRT_CHECK(out->GetCellData()->GetNormals() == nullptr, "cell normals dropped");
  auto* dropped =
    vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("DroppedArrays"));
  VTKRT_CHECK(dropped && dropped->GetNumberOfValues() == 1 &&
      dropped->GetValue(0).find("Normals") != std::string::npos,
    "the dropped array is named");
}

// Angle in degrees between a face's normal and the radial direction at its
// centroid, over all faces of a unit sphere approximation.
double WorstRadialDeviation(vtkPolyData* pd)
{
  double worst = 0.0;
  vtkrt_test::ForEachTriangle(pd,
    [&](double p[3][3], double normal[3])
    {
      double c[3];
      for (int k = 0; k < 3; ++k)
      {
        c[k] = (p[0][k] + p[1][k] + p[2][k]) / 3.0;
      }
      worst =
        std::max(worst, vtkMath::DegreesFromRadians(vtkMath::AngleBetweenVectors(normal, c)));
    });
  return worst;
}

// Worst longest-edge-over-height of a triangle mesh.
double WorstAspectRatio(vtkPolyData* pd)
{
  double worst = 0.0;
  vtkrt_test::ForEachTriangle(pd,
    [&](double p[3][3], double normal[3])
    {
      const double longest2 = std::max({ vtkMath::Distance2BetweenPoints(p[0], p[1]),
        vtkMath::Distance2BetweenPoints(p[1], p[2]), vtkMath::Distance2BetweenPoints(p[2], p[0]) });
      worst = std::max(worst, longest2 / vtkMath::Norm(normal));
    });
  return worst;
}

void TestShapeLimits()
{
  auto sphere = Sphere(64, 64);
  vtkNew<vtkOpenMeshDecimation> decimate;
  decimate->SetInputData(sphere);
  decimate->SetTargetReduction(0.99);
  decimate->Update();
  const double freeDeviation = WorstRadialDeviation(decimate->GetOutput());
  const vtkIdType freeCount = decimate->GetOutput()->GetNumberOfPolys();
  decimate->SetMaximumNormalDeviation(10.0);
  decimate->Update();
  const double limitedDeviation = WorstRadialDeviation(decimate->GetOutput());
  std::cout << "normal deviation from the sphere: unlimited " << freeDeviation << " deg ("
            << freeCount << " triangles), limit 10 deg -> " << limitedDeviation << " deg ("
            << decimate->GetOutput()->GetNumberOfPolys() << " triangles)" << std::endl;
  VTKRT_CHECK(freeDeviation > 15.0, "the unlimited run deviates (the check can fail)");
  VTKRT_CHECK(
    limitedDeviation <= 10.0 + WorstRadialDeviation(sphere) + 1.0, "normals stay within the limit");
  decimate->SetMaximumNormalDeviation(180.0);

  // Aspect ratio: no triangle worse than the limit, unless the input had one.
  auto grid = WavyGrid(40);
  decimate->SetInputData(grid);
  decimate->SetTargetReduction(0.95);
  decimate->Update();
  const double freeAspect = WorstAspectRatio(decimate->GetOutput());
  decimate->SetMaximumAspectRatio(6.0);
  decimate->Update();
  const double limitedAspect = WorstAspectRatio(decimate->GetOutput());
  std::cout << "aspect ratio: input " << WorstAspectRatio(grid) << ", unlimited " << freeAspect
            << ", limit 6 -> " << limitedAspect << std::endl;
  VTKRT_CHECK(freeAspect > 6.0, "the unlimited run makes slivers (the check can fail)");
  VTKRT_CHECK(limitedAspect <= std::max(6.0, WorstAspectRatio(grid)) * (1 + 1e-6),
    "no triangle worse than the limit");
}

void TestBadInput()
{
  vtkNew<vtkrt_test::ErrorCatcher> catcher;
  vtkNew<vtkOpenMeshDecimation> decimate;
  catcher->Watch(decimate);

  vtkNew<vtkPolyData> empty;
  decimate->SetInputData(empty);
  decimate->Update();
  VTKRT_CHECK(catcher->Errors.find("no points") != std::string::npos, "empty: " << catcher->Errors);
  VTKRT_CHECK(decimate->GetOutput()->GetNumberOfPoints() == 0, "empty output");
  catcher->Clear();

  vtkSmartPointer<vtkPolyData> linesOnly = vtkrt_test::LinesOnly();
  decimate->SetInputData(linesOnly);
  decimate->Update();
  VTKRT_CHECK(
    catcher->Errors.find("no polygons") != std::string::npos, "lines only: " << catcher->Errors);
  VTKRT_CHECK(decimate->GetOutput()->GetNumberOfCells() == 0, "empty output");
  catcher->Clear();

  vtkNew<vtkPolyData> corrupt;
  corrupt->SetPoints(linesOnly->GetPoints());
  vtkNew<vtkCellArray> badPolys;
  const vtkIdType bad[] = { 0, 1, 7 };
  badPolys->InsertNextCell(3, bad);
  corrupt->SetPolys(badPolys);
  decimate->SetInputData(corrupt);
  decimate->Update();
  VTKRT_CHECK(catcher->Errors.find("no valid polygon") != std::string::npos,
    "bad point ids: " << catcher->Errors);
  VTKRT_CHECK(decimate->GetOutput()->GetNumberOfPoints() == 0, "empty output");
  catcher->Clear();

  auto withNaN = vtkSmartPointer<vtkPolyData>::New();
  withNaN->DeepCopy(Sphere(8, 8));
  withNaN->GetPoints()->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  decimate->SetInputData(withNaN);
  decimate->Update();
  VTKRT_CHECK(catcher->Errors.find("non-finite") != std::string::npos, "NaN: " << catcher->Errors);
  VTKRT_CHECK(decimate->GetOutput()->GetNumberOfPoints() == 0, "empty output");
  catcher->Clear();

  decimate->SetInputData(Sphere(8, 8));
  decimate->SetTargetModeToErrorBound();
  decimate->Update();
  VTKRT_CHECK(catcher->Errors.find("MaximumError") != std::string::npos,
    "error mode without bound: " << catcher->Errors);
  catcher->Clear();

  vtkNew<vtkOpenMeshDecimation> unconnected;
  catcher->Watch(unconnected);
  unconnected->Update();
  VTKRT_CHECK(!catcher->Errors.empty(), "missing input reported");
  catcher->Clear();

  decimate->SetMaximumError(0.01);
  decimate->Update();
  VTKRT_CHECK(catcher->Errors.empty() && decimate->GetOutput()->GetNumberOfPolys() > 0, "recovers");
}

} // namespace

int main()
{
  TestTargets();
  TestErrorBound(Sphere(64, 64), "sphere", 0.002);
  TestErrorBound(WavyGrid(60), "wavy grid", 0.001);
  TestVersusVTK(Sphere(64, 64), "sphere", 0.9);
  TestBoundaries();
  TestNonManifoldAndDegenerate();
  TestAttributes();
  TestShapeLimits();
  TestBadInput();
  if (auto bunnyFile = vtkrt_test::ReadDataMesh("bunny.ply", "bunny"))
  {
    vtkNew<vtkOpenMeshClean> clean;
    clean->SetInputData(bunnyFile);
    clean->Update();
    vtkPolyData* bunny = clean->GetOutput();
    TestErrorBound(bunny, "bunny", 0.001);
    TestVersusVTK(bunny, "bunny", 0.9);
  }
  std::cout << (vtkrt_test::Failures() ? "FAILED: " : "passed, failures: ")
            << vtkrt_test::Failures() << std::endl;
  return vtkrt_test::Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
