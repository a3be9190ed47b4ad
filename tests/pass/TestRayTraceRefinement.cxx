// The pass's background build from the inside (pass/vtkRayTraceRefinement):
//   SameTree  the tree and records a background build hands over are, bit
//             for bit, those the scene builds at that quality and leaf size
//             at once, on a sphere with a NaN point and a degenerate
//             triangle and on the bunny; the fast tree they replace is
//             another tree
//   Queue     one build runs at a time, in the order they came; a stale
//             geometry takes nothing; builds let go or left waiting are
//             dropped safely
// TestRayTraceRefinement <Case>.
#include "vtkrtPassTestUtils.h"

#include "vtkRayTraceGeometry.h"
#include "vtkRayTraceRefinement.h"
#include "vtkRayTraceScene.h"

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

/// Builds `poly` fast with a refinement to `quality` and `leafSize`, and so
/// at once, as the scene does; checks the refinement's geometry against the
/// one built at once.
void CheckSameTree(vtkPolyData* poly, int quality, std::uint32_t leafSize, const std::string& name)
{
  using namespace vtkrt;
  const std::string what = name + ", quality " + std::to_string(quality) + ", leaves of " + std::to_string(leafSize);
  const core::BuildOptions options = pass::TriangleBuildOptions(quality, leafSize);
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
  vtkSmartPointer<vtkPolyData> bunny = ReadPolyData("bunny.vtp");
  for (int quality : { 1, 2 })
  {
    for (std::uint32_t leafSize : { 4u, 7u })
    {
      CheckSameTree(sphere, quality, leafSize, "sphere with a NaN and a degenerate triangle");
      CheckSameTree(bunny, quality, leafSize, "bunny");
    }
  }
  NoVTKOutput("same tree");
}

/// A sphere built fast, with what its refinement needs.
struct FastMesh
{
  std::shared_ptr<const vtkrt::pass::Geometry> Geometry;
  vtkrt::pass::RefinementInput Input;
};

FastMesh FastSphere(int resolution)
{
  using namespace vtkrt;
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(resolution);
  source->SetPhiResolution(resolution);
  source->Update();
  FastMesh mesh;
  mesh.Geometry = pass::BuildTriangles(source->GetOutput(), pass::TriangleBuildOptions(0, 4), &mesh.Input);
  return mesh;
}

/// Queues `mesh`'s refinement under `key` (the meshes are built first, so
/// that the builds are queued back to back).
void Start(vtkrt::pass::BackgroundBuilds& builds, const void* key, FastMesh& mesh)
{
  using namespace vtkrt;
  const core::BuildOptions options = pass::BackgroundBuildOptions(pass::TriangleBuildOptions(1, 4));
  builds.Start(key, mesh.Geometry, std::move(mesh.Input), options);
}

void TestQueue()
{
  using namespace vtkrt;
  const int keys[3] = { 0, 1, 2 };
  {
    pass::BackgroundBuilds builds;
    FastMesh m0 = FastSphere(60), m1 = FastSphere(70);
    Start(builds, &keys[0], m0);
    Start(builds, &keys[1], m1);
    Check(builds.Size() == 2 && builds.IsLaunched(&keys[0]) && !builds.IsLaunched(&keys[1]),
      "two builds: the first launched, the second waiting");
    builds.WaitAll();
    Check(builds.Size() == 2 && builds.IsLaunched(&keys[1]), "after the wait: both ran, neither taken");
    Check(!builds.TakeDone(&keys[1], *m0.Geometry), "a geometry it does not refine takes nothing");
    const std::shared_ptr<pass::Geometry> t1 = builds.TakeDone(&keys[1], *m1.Geometry);
    const std::shared_ptr<pass::Geometry> t0 = builds.TakeDone(&keys[0], *m0.Geometry);
    Check(t0 && t1 && t0->PrimitiveCount == m0.Geometry->PrimitiveCount &&
        t1->PrimitiveCount == m1.Geometry->PrimitiveCount && builds.Size() == 0,
      "each taken by its own geometry, in any order; none left");
  }
  {
    pass::BackgroundBuilds builds;
    FastMesh m0 = FastSphere(400), m1 = FastSphere(60), m2 = FastSphere(60), m0b = FastSphere(80);
    Start(builds, &keys[0], m0);
    Start(builds, &keys[1], m1);
    Start(builds, &keys[2], m2);
    // The first key's build let go (running, or done and dropped), a new
    // one queued behind the others; the second key's geometry gone.
    Start(builds, &keys[0], m0b);
    builds.Tidy([&](const void* key) -> const pass::Geometry* {
      return key == &keys[0] ? m0b.Geometry.get() : key == &keys[2] ? m2.Geometry.get() : nullptr;
    });
    Check(builds.Size() == 2, "a build replaced and one whose geometry went: two left");
    builds.WaitAll();
    Check(builds.TakeDone(&keys[0], *m0b.Geometry) && builds.TakeDone(&keys[2], *m2.Geometry) &&
        builds.Size() == 0,
      "the replacing build and the remaining one taken");
  }
  {
    pass::BackgroundBuilds builds;
    FastMesh m0 = FastSphere(300), m1 = FastSphere(60);
    Start(builds, &keys[0], m0);
    Start(builds, &keys[1], m1);
    // Destroyed with one build launched and one never launched: it waits
    // for the first, drops the second (ASan and TSan runs see the rest).
    Check(builds.IsLaunched(&keys[0]) && !builds.IsLaunched(&keys[1]),
      "destroyed with one build launched, one waiting");
  }
  NoVTKOutput("queue");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "SameTree", TestSameTree },
    { "Queue", TestQueue },
  };
  return RunCase(argc, argv, cases);
}
