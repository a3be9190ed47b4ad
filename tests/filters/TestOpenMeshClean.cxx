// vtkOpenMeshClean: welding, degenerate removal, orientation and the edge
// report, checked against OpenMesh's own verdict and vtkCleanPolyData.
#include "vtkrtFiltersTestUtilities.h"

#include "vtkOpenMeshClean.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkMassProperties.h"
#include "vtkPlatonicSolidSource.h"
#include "vtkPointData.h"
#include "vtkSphereSource.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <cstdio>
#include <limits>
#include <map>

using vtkrt_test::FieldCount;
using vtkrt_test::JudgeWithOpenMesh;

namespace
{

vtkSmartPointer<vtkPolyData> Sphere(int theta, int phi)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(theta);
  sphere->SetPhiResolution(phi);
  sphere->SetRadius(1.0);
  sphere->Update();
  return sphere->GetOutput();
}

// Every triangle's normal points away from the origin (a convex surface
// around it, oriented outward).
bool AllFacesOutward(vtkPolyData* pd)
{
  bool outward = true;
  vtkrt_test::ForEachTriangle(pd,
    [&](double p[3][3], double normal[3])
    {
      const double centroid[3] = { (p[0][0] + p[1][0] + p[2][0]) / 3,
        (p[0][1] + p[1][1] + p[2][1]) / 3, (p[0][2] + p[1][2] + p[2][2]) / 3 };
      outward = outward && vtkMath::Dot(normal, centroid) > 0.0;
    });
  return outward;
}

// Polygon soup: every triangle gets its own copies of its three points (what
// a shrink with factor 1 would give, without its rounding), and every third
// triangle is flipped.
vtkSmartPointer<vtkPolyData> SplitAndScramble(vtkPolyData* in)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataType(in->GetPoints()->GetDataType());
  vtkNew<vtkCellArray> polys;
  auto iter = vtk::TakeSmartPointer(in->GetPolys()->NewIterator());
  vtkIdType n;
  const vtkIdType* ids;
  vtkIdType cell = 0;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell(), ++cell)
  {
    iter->GetCurrentCell(n, ids);
    std::vector<vtkIdType> v;
    for (vtkIdType k = 0; k < n; ++k)
    {
      v.push_back(pts->InsertNextPoint(in->GetPoint(ids[k])));
    }
    if (cell % 3 == 0)
    {
      std::reverse(v.begin(), v.end());
    }
    polys->InsertNextCell(n, v.data());
  }
  out->SetPoints(pts);
  out->SetPolys(polys);
  return out;
}

void TestSplitSphereIsWeldedAndOriented()
{
  auto sphere = Sphere(24, 16);
  auto soup = SplitAndScramble(sphere);
  // Per-point and per-cell ids to follow the data through the filter.
  vtkNew<vtkIdTypeArray> pointIds;
  pointIds->SetName("InputPointId");
  for (vtkIdType i = 0; i < soup->GetNumberOfPoints(); ++i)
  {
    pointIds->InsertNextValue(i);
  }
  soup->GetPointData()->AddArray(pointIds);
  vtkNew<vtkIdTypeArray> cellIds;
  cellIds->SetName("InputCellId");
  for (vtkIdType i = 0; i < soup->GetNumberOfCells(); ++i)
  {
    cellIds->InsertNextValue(i);
  }
  soup->GetCellData()->AddArray(cellIds);

  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(soup);
  clean->GenerateOriginalCellIdsOn();
  clean->Update();
  vtkPolyData* out = clean->GetOutput();

  vtkNew<vtkCleanPolyData> vtkClean;
  vtkClean->SetInputData(soup);
  vtkClean->Update();
  std::cout << "split sphere: " << soup->GetNumberOfPoints() << " points in, "
            << out->GetNumberOfPoints()
            << " out (vtkCleanPolyData: " << vtkClean->GetOutput()->GetNumberOfPoints()
            << ", sphere source: " << sphere->GetNumberOfPoints() << "), "
            << clean->GetNumberOfFlippedFaces() << " faces flipped" << std::endl;

  VTKRT_CHECK(out->GetNumberOfPoints() == sphere->GetNumberOfPoints(), "weld restores the sphere");
  VTKRT_CHECK(out->GetNumberOfPoints() == vtkClean->GetOutput()->GetNumberOfPoints(),
    "same point count as vtkCleanPolyData");
  VTKRT_CHECK(out->GetNumberOfPolys() == sphere->GetNumberOfPolys(), "no face lost");
  VTKRT_CHECK(clean->IsClosedManifold(), "closed manifold after cleaning");
  VTKRT_CHECK(FieldCount(out, "IsClosedManifold") == 1, "field data says closed");
  VTKRT_CHECK(FieldCount(out, "NumberOfBoundaryEdges") == 0, "no boundary edge");
  VTKRT_CHECK(clean->GetNumberOfComponents() == 1, "one component");
  VTKRT_CHECK(
    clean->GetNumberOfMergedPoints() == soup->GetNumberOfPoints() - sphere->GetNumberOfPoints(),
    "merged count");
  const vtkIdType scrambled = (sphere->GetNumberOfPolys() + 2) / 3;
  VTKRT_CHECK(clean->GetNumberOfFlippedFaces() == scrambled,
    "flips exactly the scrambled faces: " << clean->GetNumberOfFlippedFaces() << " vs "
                                          << scrambled);
  VTKRT_CHECK(AllFacesOutward(out), "outward orientation");
  auto verdict = JudgeWithOpenMesh(out);
  VTKRT_CHECK(verdict.ClosedManifold(), "OpenMesh agrees: closed manifold");
  VTKRT_CHECK(verdict.EulerCharacteristic() == 2, "sphere topology, V-E+F=2");
  VTKRT_CHECK(clean->GetProblemEdges()->GetNumberOfCells() == 0, "no problem edge");

  // Point data through the weld: each output point carries the data of the
  // lowest-id input point at its position.
  auto* outPointIds = vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("InputPointId"));
  VTKRT_CHECK(outPointIds != nullptr, "point array carried");
  std::map<std::array<double, 3>, vtkIdType> lowestAt;
  for (vtkIdType i = soup->GetNumberOfPoints() - 1; i >= 0; --i)
  {
    double p[3];
    soup->GetPoint(i, p);
    lowestAt[{ p[0], p[1], p[2] }] = i;
  }
  bool pointDataOk = outPointIds != nullptr;
  for (vtkIdType i = 0; pointDataOk && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    pointDataOk = lowestAt[{ p[0], p[1], p[2] }] == outPointIds->GetValue(i);
  }
  VTKRT_CHECK(pointDataOk, "point data follows the weld");
  // Cell data follows the faces.
  auto* outCellIds = vtkIdTypeArray::SafeDownCast(out->GetCellData()->GetArray("InputCellId"));
  auto* origIds = vtkIdTypeArray::SafeDownCast(out->GetCellData()->GetArray("vtkOriginalCellIds"));
  bool cellDataOk = outCellIds && origIds;
  for (vtkIdType i = 0; cellDataOk && i < out->GetNumberOfCells(); ++i)
  {
    cellDataOk = outCellIds->GetValue(i) == origIds->GetValue(i);
  }
  VTKRT_CHECK(cellDataOk, "cell data follows the faces");
}

void TestTexturedSphereSeam()
{
  // The textured sphere duplicates its seam and pole points (for texture
  // coordinates) and has zero-area triangles at its poles.
  vtkNew<vtkTexturedSphereSource> source;
  source->SetThetaResolution(20);
  source->SetPhiResolution(12);
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputConnection(source->GetOutputPort());
  clean->Update();
  // Its seam points differ by rounding (sin(2 pi) is not 0): an exact weld
  // cannot close it, a tolerance of 1e-9 of the diagonal does.
  VTKRT_CHECK(!clean->IsClosedManifold(), "exact weld leaves the rounded seam open");
  clean->SetTolerance(1e-9);
  clean->Update();
  vtkPolyData* in = source->GetOutput();
  vtkPolyData* out = clean->GetOutput();
  auto before = JudgeWithOpenMesh(in);
  auto after = JudgeWithOpenMesh(out);
  std::cout << "textured sphere: " << in->GetNumberOfPoints() << " -> " << out->GetNumberOfPoints()
            << " points, " << in->GetNumberOfPolys() << " -> " << out->GetNumberOfPolys()
            << " triangles, boundary halfedges " << before.BoundaryHalfedges << " -> "
            << after.BoundaryHalfedges << ", degenerate " << clean->GetNumberOfDegenerateFaces()
            << std::endl;
  VTKRT_CHECK(!before.ClosedManifold(), "the source has an open seam");
  VTKRT_CHECK(after.ClosedManifold(), "OpenMesh: closed manifold after cleaning");
  VTKRT_CHECK(after.EulerCharacteristic() == 2, "sphere topology");
  VTKRT_CHECK(clean->IsClosedManifold(), "filter reports closed");
  // theta+1 columns x (phi+1) rows, seam column and pole rows collapse.
  VTKRT_CHECK(out->GetNumberOfPoints() == 20 * (12 - 1) + 2, "seam and poles welded");
  VTKRT_CHECK(
    clean->GetNumberOfDegenerateFaces() == in->GetNumberOfPolys() - out->GetNumberOfPolys(),
    "faces lost are exactly the degenerate ones");
  VTKRT_CHECK(out->GetPointData()->GetTCoords() != nullptr, "texture coordinates carried");
}

void TestToleranceWeld()
{
  // Points of a split sphere jittered by 1e-7 of the diagonal: an exact weld
  // leaves cracks, a 1e-5 tolerance closes them.
  auto soup = SplitAndScramble(Sphere(16, 10));
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  const double jitter = 1e-7 * soup->GetLength();
  for (vtkIdType i = 0; i < soup->GetNumberOfPoints(); ++i)
  {
    double p[3];
    soup->GetPoint(i, p);
    for (double& c : p)
    {
      c += random->GetNextRangeValue(-jitter, jitter);
    }
    soup->GetPoints()->SetPoint(i, p);
  }
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(soup);
  clean->Update();
  VTKRT_CHECK(!clean->IsClosedManifold(), "exact weld cannot close a jittered soup");
  VTKRT_CHECK(clean->GetNumberOfBoundaryEdges() > 0, "boundary edges reported");
  VTKRT_CHECK(clean->GetProblemEdges()->GetNumberOfCells() == clean->GetNumberOfBoundaryEdges(),
    "problem edges output lists them");
  clean->SetTolerance(1e-5);
  clean->Update();
  VTKRT_CHECK(clean->IsClosedManifold(), "tolerance weld closes it");
  VTKRT_CHECK(JudgeWithOpenMesh(clean->GetOutput()).ClosedManifold(), "OpenMesh agrees");
  clean->ToleranceIsAbsoluteOn();
  clean->SetAbsoluteTolerance(1e-5 * soup->GetLength());
  clean->Update();
  VTKRT_CHECK(clean->IsClosedManifold(), "absolute tolerance closes it too");
}

void TestPolygonsStripsAndDroppedCells()
{
  // A cube of 6 quads, 24 points (split per face for normals).
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputConnection(cube->GetOutputPort());
  clean->Update();
  vtkPolyData* out = clean->GetOutput();
  VTKRT_CHECK(out->GetNumberOfPolys() == 12, "6 quads -> 12 triangles");
  VTKRT_CHECK(out->GetNumberOfPoints() == 8, "24 -> 8 points");
  VTKRT_CHECK(clean->IsClosedManifold(), "cube is closed");
  VTKRT_CHECK(AllFacesOutward(out), "cube faces outward");

  // A non-convex pentagon, a strip, a line and a vertex.
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> pts;
  const double coords[][3] = { { 0, 0, 0 }, { 4, 0, 0 }, { 4, 4, 0 }, { 2, 1, 0 }, { 0, 4, 0 },
    { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 }, { 0, 2, 1 }, { 1, 2, 1 } };
  for (const auto& c : coords)
  {
    pts->InsertNextPoint(c);
  }
  pd->SetPoints(pts);
  vtkNew<vtkCellArray> polys, strips, lines, verts;
  const vtkIdType pentagon[] = { 0, 1, 2, 3, 4 };
  polys->InsertNextCell(5, pentagon);
  const vtkIdType strip[] = { 5, 6, 7, 8, 9, 10 };
  strips->InsertNextCell(6, strip);
  const vtkIdType line[] = { 0, 5 };
  lines->InsertNextCell(2, line);
  const vtkIdType vert[] = { 1 };
  verts->InsertNextCell(1, vert);
  pd->SetPolys(polys);
  pd->SetStrips(strips);
  pd->SetLines(lines);
  pd->SetVerts(verts);
  clean->SetInputData(pd);
  clean->Update();
  out = clean->GetOutput();
  VTKRT_CHECK(out->GetNumberOfPolys() == 3 + 4, "pentagon -> 3, strip of 6 -> 4 triangles");
  VTKRT_CHECK(FieldCount(out, "NumberOfDroppedLines") == 1, "line dropped and noted");
  VTKRT_CHECK(FieldCount(out, "NumberOfDroppedVerts") == 1, "vertex dropped and noted");
  vtkNew<vtkMassProperties> mass;
  vtkNew<vtkPolyData> pentagonOnly;
  pentagonOnly->SetPoints(out->GetPoints());
  vtkNew<vtkCellArray> first3;
  for (vtkIdType c = 0; c < 3; ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    out->GetPolys()->GetCellAtId(c, n, ids);
    first3->InsertNextCell(n, ids);
  }
  pentagonOnly->SetPolys(first3);
  mass->SetInputData(pentagonOnly);
  mass->Update();
  // 4x4 square minus the notch triangle (4,4),(2,1),(0,4): area 16 - 6 = 10.
  VTKRT_CHECK(std::abs(mass->GetSurfaceArea() - 10.0) < 1e-9,
    "non-convex pentagon triangulated exactly: area " << mass->GetSurfaceArea());
  // The strip's alternating winding is made consistent: nothing flipped.
  VTKRT_CHECK(clean->GetNumberOfFlippedFaces() == 0, "strip winding preserved");
  VTKRT_CHECK(clean->GetNumberOfInconsistentEdges() == 0, "strip consistent");
}

void TestDegenerateAndNonManifold()
{
  // Fan of three triangles on edge 0-1 (non-manifold), plus degenerate faces:
  // a repeated vertex, a collinear triple, a NaN point, a duplicate face.
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> pts;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double coords[][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, 1, 0 }, { 0.5, -1, 0 },
    { 0.5, 0, 1 }, { 2, 0, 0 }, { nan, 0, 0 } };
  for (const auto& c : coords)
  {
    pts->InsertNextPoint(c);
  }
  pd->SetPoints(pts);
  vtkNew<vtkCellArray> polys;
  const vtkIdType faces[][3] = {
    { 0, 1, 2 }, { 1, 0, 3 }, { 0, 1, 4 }, // three faces on edge 0-1
    { 0, 0, 2 },                           // repeated vertex
    { 0, 1, 5 },                           // collinear
    { 0, 6, 2 },                           // NaN point
    { 2, 1, 0 },                           // duplicate of the first (reversed)
  };
  for (const auto& f : faces)
  {
    polys->InsertNextCell(3, f);
  }
  const vtkIdType corrupt[] = { 0, 1, 99, 2 }; // a point id out of range
  polys->InsertNextCell(4, corrupt);
  pd->SetPolys(polys);
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(pd);
  clean->Update();
  vtkPolyData* out = clean->GetOutput();
  VTKRT_CHECK(out->GetNumberOfPolys() == 3, "three faces kept, got " << out->GetNumberOfPolys());
  VTKRT_CHECK(clean->GetNumberOfDegenerateFaces() == 2, "repeated + collinear");
  VTKRT_CHECK(clean->GetNumberOfNonFiniteFaces() == 1, "NaN face");
  VTKRT_CHECK(clean->GetNumberOfNonFinitePoints() == 1, "NaN point");
  VTKRT_CHECK(clean->GetNumberOfDuplicateFaces() == 1, "duplicate face");
  VTKRT_CHECK(clean->GetNumberOfInvalidCells() == 1, "the cell with a bad point id");
  VTKRT_CHECK(clean->GetNumberOfNonManifoldEdges() == 1, "edge 0-1 is non-manifold");
  VTKRT_CHECK(clean->GetNumberOfBoundaryEdges() == 6, "six open edges");
  VTKRT_CHECK(clean->GetNumberOfRejectedFaces() == 1, "OpenMesh holds two of the three faces");
  VTKRT_CHECK(!clean->IsClosedManifold(), "not closed");
  VTKRT_CHECK(out->GetNumberOfPoints() == 5, "unused points (collinear apex, NaN) dropped");
  vtkPolyData* edges = clean->GetProblemEdges();
  auto* types = vtkUnsignedCharArray::SafeDownCast(edges->GetCellData()->GetArray("EdgeType"));
  VTKRT_CHECK(edges->GetNumberOfCells() == 7 && types, "7 problem edges");
  int counts[4] = { 0, 0, 0, 0 };
  for (vtkIdType i = 0; types && i < types->GetNumberOfValues(); ++i)
  {
    ++counts[types->GetValue(i) & 3];
  }
  VTKRT_CHECK(counts[1] == 6 && counts[2] == 1, "6 boundary + 1 non-manifold edge lines");
}

void TestMoebiusStripIsInconsistent()
{
  // A Moebius strip has no consistent orientation: at least one edge stays
  // inconsistent whatever the filter does.
  const int n = 24;
  vtkNew<vtkPoints> pts;
  for (int i = 0; i < n; ++i)
  {
    const double t = 2.0 * vtkMath::Pi() * i / n;
    for (int s = -1; s <= 1; s += 2)
    {
      const double w = 0.3 * s;
      pts->InsertNextPoint((1 + w * std::cos(t / 2)) * std::cos(t),
        (1 + w * std::cos(t / 2)) * std::sin(t), w * std::sin(t / 2));
    }
  }
  vtkNew<vtkCellArray> polys;
  for (int i = 0; i < n; ++i)
  {
    vtkIdType a = 2 * i, b = 2 * i + 1;
    vtkIdType c = 2 * ((i + 1) % n), d = 2 * ((i + 1) % n) + 1;
    if (i == n - 1)
    {
      std::swap(c, d); // the half twist
    }
    const vtkIdType t1[] = { a, c, b };
    const vtkIdType t2[] = { b, c, d };
    polys->InsertNextCell(3, t1);
    polys->InsertNextCell(3, t2);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(pd);
  clean->Update();
  VTKRT_CHECK(clean->GetNumberOfInconsistentEdges() >= 1, "Moebius strip is non-orientable");
  VTKRT_CHECK(clean->GetNumberOfComponents() == 1, "one patch");
  VTKRT_CHECK(clean->GetNumberOfBoundaryLoops() >= 1, "it has a boundary");
}

void TestPlatonicSolidsFaceOutward()
{
  // VTK's tetrahedron and icosahedron are wound inward; every solid comes
  // out closed and facing outward.
  for (int type = VTK_SOLID_TETRAHEDRON; type <= VTK_SOLID_DODECAHEDRON; ++type)
  {
    vtkNew<vtkPlatonicSolidSource> solid;
    solid->SetSolidType(type);
    vtkNew<vtkOpenMeshClean> clean;
    clean->SetInputConnection(solid->GetOutputPort());
    clean->Update();
    std::cout << "platonic solid " << type << ": " << clean->GetNumberOfFlippedFaces()
              << " faces flipped" << std::endl;
    VTKRT_CHECK(clean->IsClosedManifold(), "solid " << type << " closed");
    VTKRT_CHECK(AllFacesOutward(clean->GetOutput()), "solid " << type << " faces outward");
    VTKRT_CHECK(JudgeWithOpenMesh(clean->GetOutput()).EulerCharacteristic() == 2, "sphere-like");
  }
}

void TestNonManifoldVertices()
{
  // Two closed tetrahedra sharing one apex: every edge is manifold, the
  // shared vertex is not (two fans).
  vtkNew<vtkPoints> pts;
  const double coords[][3] = { { 0, 0, 0 }, { 1, 0, -1 }, { -1, 1, -1 }, { -1, -1, -1 },
    { 1, 0, 1 }, { -1, 1, 1 }, { -1, -1, 1 } };
  for (const auto& c : coords)
  {
    pts->InsertNextPoint(c);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType faces[][3] = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 3, 1 }, { 1, 3, 2 }, { 0, 5, 4 },
    { 0, 6, 5 }, { 0, 4, 6 }, { 4, 5, 6 } };
  for (const auto& f : faces)
  {
    polys->InsertNextCell(3, f);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(pd);
  clean->Update();
  VTKRT_CHECK(clean->GetNumberOfNonManifoldVertices() == 1, "the shared apex");
  VTKRT_CHECK(clean->GetNumberOfNonManifoldEdges() == 0 && clean->GetNumberOfBoundaryEdges() == 0,
    "edges are fine");
  VTKRT_CHECK(clean->GetNumberOfComponents() == 2, "two patches");
  VTKRT_CHECK(!clean->IsClosedManifold(), "not a manifold");
  // Both outward: the signed volume is the sum of the two (2/3 each).
  double volume = 0.0;
  vtkPolyData* out = clean->GetOutput();
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    out->GetPolys()->GetCellAtId(c, n, ids);
    double a[3], b[3], d[3];
    out->GetPoint(ids[0], a);
    out->GetPoint(ids[1], b);
    out->GetPoint(ids[2], d);
    volume += vtkMath::Determinant3x3(a, b, d) / 6.0;
  }
  VTKRT_CHECK(std::abs(volume - 4.0 / 3.0) < 1e-12, "both tetrahedra face outward: " << volume);
  VTKRT_CHECK(clean->GetOutput()->GetNumberOfPolys() == 8, "all faces kept");
}

void TestTeapot()
{
  vtkSmartPointer<vtkPolyData> teapot = vtkrt_test::ReadDataMesh("teapot.obj", "teapot");
  if (!teapot)
  {
    return;
  }
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(teapot);
  clean->Update();
  std::cout << "teapot: " << clean->GetOutput()->GetNumberOfPolys() << " triangles, "
            << clean->GetNumberOfBoundaryLoops() << " boundary loops, "
            << clean->GetNumberOfNonManifoldVertices() << " non-manifold vertices, "
            << clean->GetNumberOfRejectedFaces() << " faces OpenMesh cannot hold, "
            << clean->GetNumberOfComponents() << " components" << std::endl;
  VTKRT_CHECK(!clean->IsClosedManifold() && clean->GetNumberOfBoundaryLoops() > 0,
    "the teapot is open (spout and lid gaps)");
  // OpenMesh rejects a face only at a non-manifold edge or vertex.
  VTKRT_CHECK(clean->GetNumberOfRejectedFaces() == 0 ||
      clean->GetNumberOfNonManifoldVertices() + clean->GetNumberOfNonManifoldEdges() > 0,
    "rejections are explained");
  VTKRT_CHECK(JudgeWithOpenMesh(clean->GetOutput()).RejectedFaces ==
      static_cast<size_t>(clean->GetNumberOfRejectedFaces()),
    "rejections agree with OpenMesh");
}

void TestNestedShells()
{
  // Three concentric spheres (radius 3, 2, 1) and one beside them, all
  // wound outward by their source: the radius-2 shell is the wall of a
  // cavity and must face inward; the others outward.
  vtkNew<vtkAppendPolyData> append;
  const double radii[] = { 3.0, 2.0, 1.0, 0.5 };
  const double centers[][3] = { { 0, 0, 0 }, { 0.1, 0, 0 }, { 0.2, 0.1, 0 }, { 10, 0, 0 } };
  vtkIdType facesPerSphere = 0;
  for (int i = 0; i < 4; ++i)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetRadius(radii[i]);
    sphere->SetCenter(centers[i][0], centers[i][1], centers[i][2]);
    sphere->SetThetaResolution(24);
    sphere->SetPhiResolution(12);
    sphere->Update();
    facesPerSphere = sphere->GetOutput()->GetNumberOfPolys();
    append->AddInputData(sphere->GetOutput());
  }
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputConnection(append->GetOutputPort());
  clean->Update();
  vtkPolyData* out = clean->GetOutput();
  VTKRT_CHECK(clean->GetNumberOfComponents() == 4, "four shells");
  VTKRT_CHECK(clean->IsClosedManifold(), "all closed");
  VTKRT_CHECK(clean->GetNumberOfFlippedFaces() == facesPerSphere, "only the cavity wall flipped");
  // Per shell, faces point away from (+1) or toward (-1) its center.
  for (int i = 0; i < 4; ++i)
  {
    int away = 0, toward = 0;
    for (vtkIdType c = i * facesPerSphere; c < (i + 1) * facesPerSphere; ++c)
    {
      vtkIdType n;
      const vtkIdType* ids;
      out->GetPolys()->GetCellAtId(c, n, ids);
      double a[3], b[3], d[3], u[3], v[3], nrm[3], r[3];
      out->GetPoint(ids[0], a);
      out->GetPoint(ids[1], b);
      out->GetPoint(ids[2], d);
      vtkMath::Subtract(b, a, u);
      vtkMath::Subtract(d, a, v);
      vtkMath::Cross(u, v, nrm);
      vtkMath::Subtract(a, centers[i], r);
      (vtkMath::Dot(nrm, r) > 0 ? away : toward)++;
    }
    const bool wantAway = i != 1;
    VTKRT_CHECK((wantAway ? away : toward) == facesPerSphere,
      "shell " << i << (wantAway ? " faces outward" : " (cavity wall) faces inward") << ": " << away
               << " away, " << toward << " toward");
  }
}

void TestBadInput()
{
  vtkNew<vtkrt_test::ErrorCatcher> catcher;
  vtkNew<vtkOpenMeshClean> clean;
  catcher->Watch(clean);

  vtkNew<vtkPolyData> empty;
  clean->SetInputData(empty);
  clean->Update();
  VTKRT_CHECK(catcher->Errors.find("no points") != std::string::npos,
    "empty input error: " << catcher->Errors);
  VTKRT_CHECK(clean->GetOutput()->GetNumberOfPoints() == 0, "empty output");
  catcher->Clear();

  clean->SetInputData(vtkrt_test::LinesOnly());
  clean->Update();
  VTKRT_CHECK(catcher->Errors.find("no polygons or triangle strips") != std::string::npos,
    "lines-only error: " << catcher->Errors);
  VTKRT_CHECK(clean->GetOutput()->GetNumberOfCells() == 0, "empty output");
  catcher->Clear();

  vtkNew<vtkPolyData> allNan;
  vtkNew<vtkPoints> nanPts;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 3; ++i)
  {
    nanPts->InsertNextPoint(nan, i, 0);
  }
  allNan->SetPoints(nanPts);
  vtkNew<vtkCellArray> tri;
  const vtkIdType t[] = { 0, 1, 2 };
  tri->InsertNextCell(3, t);
  allNan->SetPolys(tri);
  clean->SetInputData(allNan);
  clean->Update();
  VTKRT_CHECK(
    catcher->Errors.find("non-finite") != std::string::npos, "all-NaN error: " << catcher->Errors);
  VTKRT_CHECK(clean->GetOutput()->GetNumberOfPoints() == 0, "empty output");
  catcher->Clear();

  vtkNew<vtkOpenMeshClean> unconnected;
  catcher->Watch(unconnected);
  unconnected->Update();
  VTKRT_CHECK(!catcher->Errors.empty(), "missing input reported");
  catcher->Clear();

  // Good input after bad input works again, without errors.
  clean->SetInputData(Sphere(8, 6));
  clean->Update();
  VTKRT_CHECK(catcher->Errors.empty() && clean->IsClosedManifold(), "recovers");
}

void TestBunny()
{
  vtkSmartPointer<vtkPolyData> in = vtkrt_test::ReadDataMesh("bunny.ply", "bunny");
  if (!in)
  {
    return;
  }
  vtkNew<vtkOpenMeshClean> clean;
  clean->SetInputData(in);
  clean->Update();
  vtkNew<vtkCleanPolyData> vtkClean;
  vtkClean->SetInputData(in);
  vtkClean->Update();
  vtkPolyData* out = clean->GetOutput();
  std::cout << "bunny: " << in->GetNumberOfPoints() << " points / " << in->GetNumberOfPolys()
            << " faces in; out " << out->GetNumberOfPoints() << " / " << out->GetNumberOfPolys()
            << " (vtkCleanPolyData " << vtkClean->GetOutput()->GetNumberOfPoints() << " points); "
            << clean->GetNumberOfBoundaryEdges() << " boundary edges in "
            << clean->GetNumberOfBoundaryLoops() << " loops, "
            << clean->GetNumberOfNonManifoldEdges() << " non-manifold edges, "
            << clean->GetNumberOfFlippedFaces() << " flipped, "
            << clean->GetNumberOfDegenerateFaces() << " degenerate" << std::endl;
  VTKRT_CHECK(out->GetNumberOfPolys() > 0.99 * in->GetNumberOfPolys(), "bunny kept its faces");
  VTKRT_CHECK(out->GetNumberOfPoints() <= vtkClean->GetOutput()->GetNumberOfPoints(),
    "no more points than vtkCleanPolyData");
  VTKRT_CHECK(clean->GetNumberOfBoundaryLoops() > 0, "the bunny has holes");
  auto verdict = JudgeWithOpenMesh(out);
  VTKRT_CHECK(verdict.RejectedFaces == static_cast<size_t>(clean->GetNumberOfRejectedFaces()),
    "rejections agree with OpenMesh");
  VTKRT_CHECK(verdict.BoundaryHalfedges > 0, "OpenMesh sees the holes");
}

} // namespace

int main()
{
  TestSplitSphereIsWeldedAndOriented();
  TestTexturedSphereSeam();
  TestToleranceWeld();
  TestPolygonsStripsAndDroppedCells();
  TestDegenerateAndNonManifold();
  TestMoebiusStripIsInconsistent();
  TestPlatonicSolidsFaceOutward();
  TestNonManifoldVertices();
  TestNestedShells();
  TestBadInput();
  TestBunny();
  TestTeapot();
  std::cout << (vtkrt_test::Failures() ? "FAILED: " : "passed, failures: ")
            << vtkrt_test::Failures() << std::endl;
  return vtkrt_test::Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
