// One triangulation for the pass and vtkBVHCellLocator on the same polydata
// (vtkSurfaceTriangulation): drawing then picking triangulates once, a
// modified geometry is triangulated again, a modified attribute is not, the
// triangulation goes with the polydata, and images and picks are the same
// with and without sharing.
#include "vtkrtPassTestUtils.h"

#include "vtkAppendPolyData.h"
#include "vtkBVHCellLocator.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkGenericCell.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkRegularPolygonSource.h"
#include "vtkSuperquadricSource.h"
#include "vtkSurfaceTriangulation.h"
#include "vtkWeakPointer.h"

#include <array>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
/// Triangles, quads, a seven-sided polygon and triangle strips side by side
/// (what the pass traces), and with `linesAndVerts` a polyline and vertices
/// too (what the locator tests by VTK's cells; the pass leaves such a mesh
/// to raster).
vtkSmartPointer<vtkPolyData> MixedMesh(bool linesAndVerts = false)
{
  vtkNew<vtkSphereSource> sphere; // triangles
  sphere->SetCenter(-1.2, 0.0, 0.0);
  sphere->SetRadius(0.5);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  vtkNew<vtkPlaneSource> plane; // quads
  plane->SetOrigin(-0.6, -1.6, -0.3);
  plane->SetPoint1(0.6, -1.6, -0.1);
  plane->SetPoint2(-0.6, -0.6, 0.2);
  plane->SetResolution(6, 5);
  vtkNew<vtkSuperquadricSource> quadric; // strips
  quadric->SetCenter(1.2, 0.0, 0.0);
  quadric->SetScale(0.5, 0.5, 0.5);
  quadric->SetPhiRoundness(0.3);
  quadric->SetThetaRoundness(0.7);
  vtkNew<vtkRegularPolygonSource> polygon; // a polygon and its outline as a polyline
  polygon->SetNumberOfSides(7);
  polygon->SetCenter(0.0, 1.2, 0.0);
  polygon->SetRadius(0.5);
  polygon->SetNormal(0.2, 0.1, 1.0);
  polygon->SetGeneratePolyline(linesAndVerts);
  polygon->GeneratePolygonOn();
  vtkNew<vtkAppendPolyData> append;
  append->AddInputConnection(sphere->GetOutputPort());
  append->AddInputConnection(plane->GetOutputPort());
  append->AddInputConnection(quadric->GetOutputPort());
  append->AddInputConnection(polygon->GetOutputPort());
  append->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(append->GetOutput());
  if (linesAndVerts)
  {
    vtkNew<vtkCellArray> verts;
    for (vtkIdType id : { 0, 5, 17 })
    {
      verts->InsertNextCell(1, &id);
    }
    mesh->SetVerts(verts);
  }
  return mesh;
}

/// The pass drawing `mesh` in a window of its own: the image.
vtkSmartPointer<vtkImageData> Draw(vtkPolyData* mesh)
{
  auto win = MakeWindow(160, 120);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->SetBackground(0.1, 0.1, 0.2);
  ren->ResetCamera();
  ren->GetActiveCamera()->Elevation(20.0);
  ren->GetActiveCamera()->Azimuth(25.0);
  ren->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  Check(pass->GetLastTracedInstances() == 1, "the pass traced the mesh");
  return Grab(win);
}

/// What a locator answers: nearest hits of segments and closest points.
struct Answers
{
  std::vector<std::array<double, 9>> Hits; ///< hit?, cellId, subId, t, x, y, z, r, s
  std::vector<std::array<double, 6>> Closest; ///< cellId, subId, dist2, x, y, z
  bool operator==(const Answers& o) const { return this->Hits == o.Hits && this->Closest == o.Closest; }
};

Answers Ask(vtkPolyData* mesh)
{
  vtkNew<vtkBVHCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(21);
  auto next = [&](double lo, double hi) {
    random->Next();
    return random->GetRangeValue(lo, hi);
  };
  vtkNew<vtkGenericCell> cell;
  Answers out;
  for (int i = 0; i < 2000; ++i)
  {
    double p1[3] = { next(-2, 2), next(-2, 2), -3.0 };
    double p2[3] = { next(-2, 2), next(-2, 2), 3.0 };
    if (i % 2)
    {
      std::swap(p1[1], p1[2]); // some along y
      std::swap(p2[1], p2[2]);
    }
    double t = 0, x[3] = { 0, 0, 0 }, pc[3] = { 0, 0, 0 };
    int sub = -1;
    vtkIdType cellId = -1;
    const int hit = locator->IntersectWithLine(p1, p2, i % 3 ? 0.0 : 1e-3, t, x, pc, sub, cellId, cell);
    out.Hits.push_back({ double(hit), double(cellId), double(sub), t, x[0], x[1], x[2], pc[0], pc[1] });
  }
  for (int i = 0; i < 500; ++i)
  {
    const double p[3] = { next(-2, 2), next(-2, 2), next(-1, 1) };
    double closest[3] = { 0, 0, 0 }, dist2 = 0;
    int sub = -1;
    vtkIdType cellId = -1;
    locator->FindClosestPoint(p, closest, cell, cellId, sub, dist2);
    out.Closest.push_back({ double(cellId), double(sub), dist2, closest[0], closest[1], closest[2] });
  }
  return out;
}

vtkIdType Made()
{
  return vtkSurfaceTriangulation::GetNumberOfTriangulations();
}

void DrawThenPick()
{
  vtkSmartPointer<vtkPolyData> mesh = MixedMesh();
  const vtkMTimeType meshTime = mesh->GetMTime();
  const vtkIdType before = Made();
  Draw(mesh);
  Check(Made() == before + 1, "drawing triangulates the mesh once");
  Check(mesh->GetMTime() == meshTime, "keeping the triangulation leaves the polydata's MTime");
  vtkNew<vtkBVHCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  Check(Made() == before + 1, "a locator built on the drawn mesh triangulates nothing more");
  vtkSmartPointer<vtkSurfaceTriangulation> shared = vtkSurfaceTriangulation::Get(mesh);
  Check(shared->GetNumberOfTriangles() > 0 && shared->GetNumberOfDegenerateCells() == 0 &&
      shared->GetNumberOfInvalidPointIdCells() == 0,
    "the mesh's triangulation covers its polygons and strips");
  Check(Made() == before + 1, "asking again finds the same triangulation");
  // Picking first, drawing then: once too.
  vtkSmartPointer<vtkPolyData> other = MixedMesh();
  const vtkIdType before2 = Made();
  vtkNew<vtkBVHCellLocator> first;
  first->SetDataSet(other);
  first->BuildLocator();
  Draw(other);
  Check(Made() == before2 + 1, "building a locator, then drawing, triangulates once");
  NoVTKOutput("DrawThenPick");
}

void Invalidation()
{
  vtkSmartPointer<vtkPolyData> mesh = MixedMesh();
  vtkSmartPointer<vtkSurfaceTriangulation> a = vtkSurfaceTriangulation::Get(mesh);
  vtkIdType made = Made();
  // Attributes move no cell.
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(mesh->GetNumberOfPoints());
  scalars->Fill(1.0f);
  mesh->GetPointData()->SetScalars(scalars);
  Check(vtkSurfaceTriangulation::Get(mesh) == a && Made() == made, "new scalars keep the triangulation");
  // Moved points.
  double p[3];
  mesh->GetPoints()->GetPoint(3, p);
  p[2] += 0.01;
  mesh->GetPoints()->SetPoint(3, p);
  mesh->GetPoints()->Modified();
  vtkSmartPointer<vtkSurfaceTriangulation> b = vtkSurfaceTriangulation::Get(mesh);
  Check(b != a && Made() == made + 1, "modified points: triangulated again");
  Check(a->GetNumberOfTriangles() == b->GetNumberOfTriangles(), "the old triangulation is left whole");
  // Modified cells: one quad fewer.
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(mesh->GetPolys());
  polys->ResizeExact(polys->GetNumberOfCells() - 1, polys->GetNumberOfConnectivityIds() - 7);
  mesh->SetPolys(polys);
  vtkSmartPointer<vtkSurfaceTriangulation> c = vtkSurfaceTriangulation::Get(mesh);
  Check(c != b && Made() == made + 2, "new cells: triangulated again");
  Check(c->GetNumberOfTriangles() == b->GetNumberOfTriangles() - 5, "the seven-sided polygon's five triangles are gone");
  mesh->GetPolys()->Modified();
  Check(vtkSurfaceTriangulation::Get(mesh) != c && Made() == made + 3, "modified cell array: triangulated again");
  // A locator rebuilt after the points moved uses the new triangulation.
  vtkNew<vtkBVHCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  Check(Made() == made + 3, "the locator takes the current triangulation");
  mesh->GetPoints()->Modified();
  locator->BuildLocator();
  Check(Made() == made + 4, "the rebuilt locator triangulates the moved mesh once");
  // Released with the polydata.
  vtkWeakPointer<vtkSurfaceTriangulation> kept = vtkSurfaceTriangulation::Get(mesh).GetPointer();
  a = b = c = nullptr;
  locator->FreeSearchStructure();
  locator->SetDataSet(nullptr);
  Check(kept != nullptr, "the polydata keeps its triangulation");
  mesh = nullptr;
  Check(kept == nullptr, "the triangulation goes with its polydata");
  NoVTKOutput("Invalidation");
}

void SameResults()
{
  vtkSmartPointer<vtkPolyData> mesh = MixedMesh();
  vtkSmartPointer<vtkPolyData> withLines = MixedMesh(true);
  vtkSmartPointer<vtkImageData> sharedImage = Draw(mesh);
  const Answers shared = Ask(mesh);
  const Answers sharedWithLines = Ask(withLines);
  vtkSurfaceTriangulation::Release(mesh);
  vtkSurfaceTriangulation::Release(withLines);
  vtkSurfaceTriangulation::SetCaching(false);
  const vtkIdType made = Made();
  vtkSmartPointer<vtkImageData> ownImage = Draw(mesh);
  const Answers own = Ask(mesh);
  const Answers ownWithLines = Ask(withLines);
  Check(Made() == made + 1, "without caching the pass triangulates for itself and the locator extracts its own");
  vtkSurfaceTriangulation::SetCaching(true);
  Check(CountDifferingPixels(sharedImage, ownImage, 0) == 0, "the same image with and without sharing");
  for (const Answers* a : { &shared, &sharedWithLines })
  {
    long hits = 0;
    for (const auto& h : a->Hits)
    {
      hits += h[0] != 0.0 ? 1 : 0;
    }
    Check(hits > 400, "the segments hit the mesh (" + std::to_string(hits) + " hits)");
  }
  Check(shared == own, "the same hits and closest points, bit for bit, with and without sharing");
  Check(sharedWithLines == ownWithLines,
    "with a polyline and vertices too: the same hits and closest points, bit for bit");
  NoVTKOutput("SameResults");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "DrawThenPick", DrawThenPick }, { "Invalidation", Invalidation }, { "SameResults", SameResults } });
}
