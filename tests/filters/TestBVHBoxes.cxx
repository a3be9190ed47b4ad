// vtkBVHBoxes: the boxes of each level partition the triangles, nest inside
// the level above, contain their triangles, and the root box is the mesh's
// bounds; both output styles; bad input.
#include "vtkrtFiltersTestUtilities.h"

#include "vtkBVHBoxes.h"

#include "vtkCellData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <limits>
#include <vector>

namespace
{

struct Box
{
  double lo[3];
  double hi[3];
  vtkIdType primitives;
  int depth;
  bool leaf;
};

// One box per group of cells sharing a BVHNodeId (cells of a box are consecutive).
std::vector<Box> Boxes(vtkPolyData* pd)
{
  std::vector<Box> boxes;
  auto* ids = vtkIdTypeArray::SafeDownCast(pd->GetCellData()->GetArray("BVHNodeId"));
  auto* counts = vtkIdTypeArray::SafeDownCast(pd->GetCellData()->GetArray("BVHPrimitiveCount"));
  auto* depths = vtkIntArray::SafeDownCast(pd->GetCellData()->GetArray("BVHDepth"));
  auto* leaves = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("BVHIsLeaf"));
  if (!ids || !counts || !depths || !leaves)
  {
    return boxes;
  }
  const vtkIdType numPoints = pd->GetNumberOfPoints();
  const vtkIdType numBoxes = numPoints / 8;
  const vtkIdType cellsPerBox = numBoxes ? pd->GetNumberOfCells() / numBoxes : 0;
  for (vtkIdType b = 0; b < numBoxes; ++b)
  {
    Box box;
    for (int k = 0; k < 3; ++k)
    {
      box.lo[k] = VTK_DOUBLE_MAX;
      box.hi[k] = -VTK_DOUBLE_MAX;
    }
    for (int c = 0; c < 8; ++c)
    {
      double p[3];
      pd->GetPoint(8 * b + c, p);
      for (int k = 0; k < 3; ++k)
      {
        box.lo[k] = std::min(box.lo[k], p[k]);
        box.hi[k] = std::max(box.hi[k], p[k]);
      }
    }
    const vtkIdType cell = b * cellsPerBox;
    box.primitives = counts->GetValue(cell);
    box.depth = depths->GetValue(cell);
    box.leaf = leaves->GetValue(cell) != 0;
    boxes.push_back(box);
  }
  return boxes;
}

bool Inside(const double lo[3], const double hi[3], const Box& outer)
{
  for (int k = 0; k < 3; ++k)
  {
    if (lo[k] < outer.lo[k] || hi[k] > outer.hi[k])
    {
      return false;
    }
  }
  return true;
}

// Every triangle's bounds lie inside at least one box.
bool EveryTriangleInABox(vtkPolyData* mesh, const std::vector<Box>& boxes)
{
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    double b[6];
    mesh->GetCellBounds(c, b);
    const double lo[3] = { b[0], b[2], b[4] }, hi[3] = { b[1], b[3], b[5] };
    bool found = false;
    for (const Box& box : boxes)
    {
      if (Inside(lo, hi, box))
      {
        found = true;
        break;
      }
    }
    if (!found)
    {
      return false;
    }
  }
  return true;
}

void TestLevels()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(30);
  sphere->SetCenter(1, 2, 3);
  sphere->Update();
  vtkPolyData* mesh = sphere->GetOutput();
  const vtkIdType numTris = mesh->GetNumberOfPolys();

  vtkNew<vtkBVHBoxes> boxes;
  boxes->SetInputData(mesh);
  boxes->Update();
  auto root = Boxes(boxes->GetOutput());
  double bounds[6];
  mesh->GetBounds(bounds);
  VTKRT_CHECK(root.size() == 1, "level 0 is the root");
  VTKRT_CHECK(!root.empty() && root[0].lo[0] == bounds[0] && root[0].hi[0] == bounds[1] &&
      root[0].lo[1] == bounds[2] && root[0].hi[1] == bounds[3] && root[0].lo[2] == bounds[4] &&
      root[0].hi[2] == bounds[5],
    "the root box is the mesh's bounds");
  VTKRT_CHECK(!root.empty() && root[0].primitives == numTris, "the root holds every triangle");
  VTKRT_CHECK(boxes->GetOutput()->GetNumberOfLines() == 12, "12 edges per box");
  std::cout << "sphere " << numTris << " triangles: " << boxes->GetNumberOfNodes() << " nodes, "
            << boxes->GetNumberOfLeaves() << " leaves, depth " << boxes->GetMaximumDepth()
            << std::endl;
  VTKRT_CHECK(
    vtkrt_test::FieldCount(boxes->GetOutput(), "BVHNodeCount") == boxes->GetNumberOfNodes(),
    "field data");
  VTKRT_CHECK(boxes->GetNumberOfNodes() == 2 * boxes->GetNumberOfLeaves() - 1, "binary tree");

  std::vector<Box> previous = root;
  for (int level = 1; level <= boxes->GetMaximumDepth(); ++level)
  {
    boxes->SetLevel(level);
    boxes->Update();
    auto current = Boxes(boxes->GetOutput());
    vtkIdType sum = 0;
    int atLevel = 0;
    bool nested = true;
    for (const Box& box : current)
    {
      sum += box.primitives;
      atLevel += box.depth == level ? 1 : 0;
      VTKRT_CHECK(box.depth == level || (box.leaf && box.depth < level), "level rule");
      bool inParent = false;
      for (const Box& parent : previous)
      {
        inParent = inParent || Inside(box.lo, box.hi, parent);
      }
      nested = nested && inParent;
    }
    VTKRT_CHECK(sum == numTris, "level " << level << " partitions the triangles: " << sum);
    VTKRT_CHECK(atLevel <= (1 << std::min(level, 30)), "at most 2^level nodes");
    VTKRT_CHECK(nested, "level " << level << " nests in the level above");
    VTKRT_CHECK(EveryTriangleInABox(mesh, current), "level " << level << " holds the triangles");
    previous = current;
  }

  boxes->LeavesOnlyOn();
  boxes->SetOutputStyleToFaces();
  boxes->SetMaximumLeafSize(2);
  boxes->Update();
  auto leaves = Boxes(boxes->GetOutput());
  vtkIdType sum = 0;
  bool small = true;
  for (const Box& box : leaves)
  {
    sum += box.primitives;
    small = small && box.leaf && box.primitives <= 2;
  }
  VTKRT_CHECK(static_cast<vtkIdType>(leaves.size()) == boxes->GetNumberOfLeaves(), "every leaf");
  VTKRT_CHECK(sum == numTris && small, "leaves hold <= 2 triangles each, all of them");
  VTKRT_CHECK(boxes->GetOutput()->GetNumberOfPolys() == 6 * boxes->GetNumberOfLeaves(), "6 sides");
  VTKRT_CHECK(EveryTriangleInABox(mesh, leaves), "leaves hold the triangles");
  // Sides face outward: normal . (side center - box center) > 0.
  bool outward = true;
  vtkPolyData* out = boxes->GetOutput();
  for (vtkIdType c = 0; c < out->GetNumberOfCells() && outward; ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    out->GetPolys()->GetCellAtId(c, n, ids);
    double p[4][3], center[3] = { 0, 0, 0 }, side[3] = { 0, 0, 0 };
    for (int k = 0; k < 4; ++k)
    {
      out->GetPoint(ids[k], p[k]);
    }
    const vtkIdType first = (ids[0] / 8) * 8;
    for (int k = 0; k < 8; ++k)
    {
      double q[3];
      out->GetPoint(first + k, q);
      for (int j = 0; j < 3; ++j)
      {
        center[j] += q[j] / 8;
      }
    }
    for (int k = 0; k < 4; ++k)
    {
      for (int j = 0; j < 3; ++j)
      {
        side[j] += p[k][j] / 4;
      }
    }
    double u[3], v[3], nrm[3], d[3];
    vtkMath::Subtract(p[1], p[0], u);
    vtkMath::Subtract(p[3], p[0], v);
    vtkMath::Cross(u, v, nrm);
    vtkMath::Subtract(side, center, d);
    // Flat leaves (a box of zero thickness) have no outside to face.
    outward = vtkMath::Dot(nrm, d) >= 0.0;
  }
  VTKRT_CHECK(outward, "box sides face outward");
}

void TestBadInput()
{
  vtkNew<vtkrt_test::ErrorCatcher> catcher;
  vtkNew<vtkBVHBoxes> boxes;
  catcher->Watch(boxes);
  vtkNew<vtkPolyData> empty;
  boxes->SetInputData(empty);
  boxes->Update();
  VTKRT_CHECK(catcher->Errors.find("no points") != std::string::npos, "empty: " << catcher->Errors);
  VTKRT_CHECK(boxes->GetOutput()->GetNumberOfPoints() == 0, "empty output");
  catcher->Clear();

  vtkSmartPointer<vtkPolyData> linesOnly = vtkrt_test::LinesOnly();
  boxes->SetInputData(linesOnly);
  boxes->Update();
  VTKRT_CHECK(
    catcher->Errors.find("no polygons") != std::string::npos, "lines only: " << catcher->Errors);
  catcher->Clear();

  vtkNew<vtkPolyData> corrupt;
  corrupt->SetPoints(linesOnly->GetPoints());
  vtkNew<vtkCellArray> badPolys;
  const vtkIdType bad[] = { 0, 1, 5 };
  badPolys->InsertNextCell(3, bad);
  corrupt->SetPolys(badPolys);
  boxes->SetInputData(corrupt);
  boxes->Update();
  VTKRT_CHECK(catcher->Errors.find("no valid polygon") != std::string::npos,
    "bad point ids: " << catcher->Errors);
  catcher->Clear();

  // NaN triangles are skipped by the builder, not an error.
  vtkNew<vtkPolyData> withNaN;
  vtkNew<vtkPoints> p2;
  p2->InsertNextPoint(0, 0, 0);
  p2->InsertNextPoint(1, 0, 0);
  p2->InsertNextPoint(0, 1, 0);
  p2->InsertNextPoint(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  withNaN->SetPoints(p2);
  vtkNew<vtkCellArray> tris;
  const vtkIdType t0[] = { 0, 1, 2 }, t1[] = { 0, 1, 3 };
  tris->InsertNextCell(3, t0);
  tris->InsertNextCell(3, t1);
  withNaN->SetPolys(tris);
  boxes->SetInputData(withNaN);
  boxes->SetLevel(0);
  boxes->Update();
  VTKRT_CHECK(catcher->Errors.empty(), "NaN triangle is no error");
  VTKRT_CHECK(boxes->GetNumberOfSkippedTriangles() == 1, "NaN triangle skipped");
  auto root = Boxes(boxes->GetOutput());
  VTKRT_CHECK(root.size() == 1 && root[0].primitives == 1 && root[0].hi[0] == 1.0,
    "the box holds the finite triangle only");
}

} // namespace

int main()
{
  TestLevels();
  TestBadInput();
  std::cout << (vtkrt_test::Failures() ? "FAILED: " : "passed, failures: ")
            << vtkrt_test::Failures() << std::endl;
  return vtkrt_test::Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
