// VTK-contract tests from the adversarial review (issue 24): float points
// moved or replaced under UseExistingSearchStructure.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"
#include "vtkGenericCell.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cmath>

using namespace locatortest;

namespace
{
/// A float-points sphere moved along z by dz (and Modified()).
void MoveAlongZ(vtkPoints* pts, double dz)
{
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pts->GetPoint(i, p);
    pts->SetPoint(i, p[0], p[1], p[2] + dz);
  }
  pts->Modified();
}
} // namespace

/// UseExistingSearchStructure over float points: after the points move, the
/// kept tree tests the cells where they are now, as it does over double
/// points (read in place): the same answers as a locator over a double copy
/// moved the same way; a replaced, reallocated or shrunk points array gives
/// an error, no answer.
int TestContractMovedFloatPoints()
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(40);
  source->SetPhiResolution(40);
  source->Update();
  vtkNew<vtkPolyData> pd, pdDouble;
  pd->DeepCopy(source->GetOutput());
  pdDouble->DeepCopy(source->GetOutput());
  vtkNew<vtkPoints> doublePts;
  doublePts->SetDataTypeToDouble();
  doublePts->DeepCopy(pd->GetPoints());
  pdDouble->SetPoints(doublePts);
  LT_CHECK(pd->GetPoints()->GetDataType() == VTK_FLOAT);
  LT_CHECK(pdDouble->GetPoints()->GetDataType() == VTK_DOUBLE);
  vtkNew<ErrorCatcher> catcher;
  vtkNew<vtkBVHCellLocator> loc, locDouble;
  catcher->Watch(loc);
  for (vtkBVHCellLocator* l : { loc.Get(), locDouble.Get() })
  {
    l->SetDataSet(l == loc.Get() ? pd.Get() : pdDouble.Get());
    l->UseExistingSearchStructureOn();
    l->BuildLocator();
  }

  // Vertical segments from inside: moving the sphere along z keeps each
  // hit cell under the segment.
  Random rng(877);
  std::vector<Segment> segs;
  for (int k = 0; k < 200; ++k)
  {
    const double r = 0.3 * std::sqrt(rng.Next()), a = rng.Next(0, 2 * vtkMath::Pi());
    Segment s;
    s.P1[0] = s.P2[0] = r * std::cos(a);
    s.P1[1] = s.P2[1] = r * std::sin(a);
    s.P1[2] = 0.0; // the sphere's center (radius 0.5)
    s.P2[2] = 5.0;
    segs.push_back(s);
  }
  std::vector<double> before;
  for (const auto& s : segs)
  {
    double t = -1, x[3], pc[3];
    int sub;
    loc->IntersectWithLine(s.P1, s.P2, 0.0, t, x, pc, sub);
    before.push_back(t);
  }
  MoveAlongZ(pd->GetPoints(), 0.01);
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    doublePts->SetPoint(i, pd->GetPoint(i)); // the same (float) coordinates
  }
  doublePts->Modified();
  int same = 0, moved = 0;
  for (size_t i = 0; i < segs.size(); ++i)
  {
    const Segment& s = segs[i];
    double t1 = -1, t2 = -1, x[3], pc[3];
    int sub;
    vtkIdType c1, c2;
    const int h1 = loc->IntersectWithLine(s.P1, s.P2, 0.0, t1, x, pc, sub, c1);
    const int h2 = locDouble->IntersectWithLine(s.P1, s.P2, 0.0, t2, x, pc, sub, c2);
    same += (h1 == h2 && c1 == c2 && t1 == t2) ? 1 : 0;
    moved += (h1 == 1 && t1 != before[i]) ? 1 : 0;
  }
  std::cout << "moved float points: " << same << " of " << segs.size()
            << " answers as over double points, " << moved << " hits moved" << std::endl;
  LT_CHECK(same == static_cast<int>(segs.size()));
  LT_CHECK(moved == static_cast<int>(segs.size()));
  LT_CHECK(catcher->Errors.empty());

  // Shrunk, then reallocated (a new pointer), then replaced: an error each, no hit.
  const vtkIdType n = pd->GetNumberOfPoints();
  double t, x[3], pc[3];
  int sub;
  vtkIdType cellId;
  pd->GetPoints()->SetNumberOfPoints(n / 2);
  LT_CHECK(loc->IntersectWithLine(segs[0].P1, segs[0].P2, 0.0, t, x, pc, sub, cellId) == 0);
  LT_CHECK(catcher->Errors.size() == 1);
  pd->GetPoints()->SetNumberOfPoints(n);
  pd->GetPoints()->Resize(4 * n);
  LT_CHECK(loc->IntersectWithLine(segs[0].P1, segs[0].P2, 0.0, t, x, pc, sub, cellId) == 0);
  LT_CHECK(catcher->Errors.size() == 2);
  vtkNew<vtkPoints> other;
  other->DeepCopy(source->GetOutput()->GetPoints());
  pd->SetPoints(other);
  LT_CHECK(loc->IntersectWithLine(segs[0].P1, segs[0].P2, 0.0, t, x, pc, sub, cellId) == 0);
  LT_CHECK(catcher->Errors.size() == 3);
  // A rebuild follows the new points.
  loc->ForceBuildLocator();
  LT_CHECK(loc->IntersectWithLine(segs[0].P1, segs[0].P2, 0.0, t, x, pc, sub, cellId) == 1);
  LT_CHECK(catcher->Errors.size() == 3);
  return 0;
}

/// A points array replaced (SetPoints) under UseExistingSearchStructure,
/// turned on before or after the build, float or double points: one error a
/// query and no hit where the old points were (the kept trees are over
/// them); a rebuild follows the new points.
int TestContractReplacedPoints()
{
  for (const bool doublePoints : { false, true })
  {
    for (const bool onBeforeBuild : { false, true })
    {
      vtkNew<vtkSphereSource> source;
      source->SetOutputPointsPrecision(doublePoints ? vtkAlgorithm::DOUBLE_PRECISION : vtkAlgorithm::SINGLE_PRECISION);
      source->Update();
      vtkNew<vtkPolyData> pd;
      pd->DeepCopy(source->GetOutput());
      vtkNew<ErrorCatcher> catcher;
      vtkNew<vtkBVHCellLocator> loc;
      catcher->Watch(loc);
      loc->SetDataSet(pd);
      loc->SetUseExistingSearchStructure(onBeforeBuild);
      loc->BuildLocator();
      loc->UseExistingSearchStructureOn();
      double t, x[3], pc[3];
      int sub;
      vtkIdType cellId;
      double oldP1[3] = { 0, 0, 2 }, oldP2[3] = { 0, 0, -2 }, newP1[3] = { 0, 0, 12 }, newP2[3] = { 0, 0, 8 };
      LT_CHECK(loc->IntersectWithLine(oldP1, oldP2, 0.0, t, x, pc, sub, cellId) == 1);
      // A new vtkPoints around the same coordinates array: the same points.
      vtkNew<vtkPoints> wrapper;
      wrapper->SetData(pd->GetPoints()->GetData());
      pd->SetPoints(wrapper);
      LT_CHECK(loc->IntersectWithLine(oldP1, oldP2, 0.0, t, x, pc, sub, cellId) == 1 && catcher->Errors.empty());
      vtkNew<vtkPoints> moved;
      moved->SetDataType(pd->GetPoints()->GetDataType());
      moved->DeepCopy(pd->GetPoints());
      MoveAlongZ(moved, 10.0);
      pd->SetPoints(moved);
      const int oldHit = loc->IntersectWithLine(oldP1, oldP2, 0.0, t, x, pc, sub, cellId);
      std::cout << (doublePoints ? "double" : "float") << " points, UseExisting "
                << (onBeforeBuild ? "before" : "after") << " the build: hit at the old place " << oldHit
                << ", " << catcher->Errors.size() << " error(s)" << std::endl;
      LT_CHECK(oldHit == 0);
      LT_CHECK(catcher->Errors.size() == 1 &&
        catcher->Errors[0].find("replaced") != std::string::npos);
      loc->ForceBuildLocator();
      LT_CHECK(loc->IntersectWithLine(newP1, newP2, 0.0, t, x, pc, sub, cellId) == 1 &&
        std::abs(x[2] - 10.5) < 1e-3);
      LT_CHECK(catcher->Errors.size() == 1);
    }
  }
  return 0;
}

