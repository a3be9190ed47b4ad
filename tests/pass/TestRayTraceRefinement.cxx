// The pass's background build from the inside (pass/vtkRayTraceRefinement):
//   SameTree  the tree and records a background build hands over are, bit
//             for bit, those BuildTriangles makes at that quality at once,
//             on a sphere with a NaN point and a degenerate triangle and on
//             the bunny; and the fast tree they replace is another tree
// TestRayTraceRefinement <Case>.
#include "vtkrtPassTestUtils.h"

#include "vtkRayTraceGeometry.h"
#include "vtkRayTraceRefinement.h"

#include "vtkCellArray.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>

using namespace vtkrtPassTest;

namespace
{
template <class Array>
bool SameBytes(const Array& a, const Array& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

/// Builds `poly` fast with a refinement to `quality`, and at `quality` at
/// once; checks the refinement's geometry against the one built at once.
void CheckSameTree(vtkPolyData* poly, const std::string& what)
{
  using namespace vtkrt;
  core::BuildOptions options;
  options.quality = core::BuildQuality::Medium;
  options.maxLeafSize = 4;
  core::BuildOptions fastOptions = options;
  fastOptions.quality = core::BuildQuality::Fast;
  pass::RefinementInput input;
  std::shared_ptr<const pass::Geometry> fast = pass::BuildTriangles(poly, fastOptions, &input);
  const std::unique_ptr<pass::Geometry> atOnce = pass::BuildTriangles(poly, options);
  pass::BVHRefinement refinement(fast, std::move(input), pass::BackgroundBuildOptions(options));
  Check(!refinement.Launched() && !refinement.Done(), what + ": a refinement waits to be launched");
  refinement.Wait();
  const std::shared_ptr<pass::Geometry> refined = refinement.Take();
  if (!refined)
  {
    Check(false, what + ": the refinement hands a geometry over");
    return;
  }
  Check(!SameBytes(fast->Nodes, atOnce->Nodes), what + ": the fast tree is another tree (" +
      std::to_string(fast->Nodes.size()) + " and " + std::to_string(atOnce->Nodes.size()) + " nodes)");
  Check(SameBytes(refined->Nodes, atOnce->Nodes), what + ": the same nodes as built at once");
  Check(SameBytes(refined->Triangles, atOnce->Triangles) &&
      SameBytes(refined->TriangleVertices, atOnce->TriangleVertices),
    what + ": the same triangle records, in the same order");
  Check(SameBytes(refined->Normals, atOnce->Normals) && SameBytes(refined->CellNormals, atOnce->CellNormals),
    what + ": the same normals");
  Check(refined->Origin == atOnce->Origin && refined->Scale == atOnce->Scale &&
      refined->LocalBounds == atOnce->LocalBounds,
    what + ": the same frame and bounds");
  Check(refined->MaxDepth == atOnce->MaxDepth && refined->PrimitiveCount == atOnce->PrimitiveCount &&
      refined->SkippedPrimitives == atOnce->SkippedPrimitives && refined->MaximumId == atOnce->MaximumId &&
      refined->VertexCount == atOnce->VertexCount,
    what + ": the same depth, counts and ids (" + std::to_string(refined->SkippedPrimitives) + " skipped)");
}

void TestSameTree()
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(120);
  source->SetPhiResolution(60);
  source->Update();
  vtkNew<vtkPolyData> sphere;
  sphere->DeepCopy(source->GetOutput());
  // A triangle through a NaN point and a zero-area one: left out of both trees.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vtkIdType p = sphere->GetPoints()->InsertNextPoint(nan, 0.0, 0.0);
  const vtkIdType nanTriangle[3] = { 0, 1, p };
  const vtkIdType flatTriangle[3] = { 2, 2, 3 };
  sphere->GetPolys()->InsertNextCell(3, nanTriangle);
  sphere->GetPolys()->InsertNextCell(3, flatTriangle);
  sphere->GetPointData()->SetNormals(nullptr);
  CheckSameTree(sphere, "sphere with a NaN and a degenerate triangle");
  CheckSameTree(ReadPolyData("bunny.vtp"), "bunny");
  NoVTKOutput("same tree");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "SameTree", TestSameTree },
  };
  return RunCase(argc, argv, cases);
}
