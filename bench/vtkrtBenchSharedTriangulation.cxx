// vtkrtBenchSharedTriangulation: what sharing one triangulation
// (vtkSurfaceTriangulation) between vtkRayTracePass and vtkBVHCellLocator
// saves when a mesh is drawn and then picked: the pass's first frame of a
// new mesh, then BuildLocator on the same polydata, with caching on (shared)
// and off (each triangulates for itself, as before), rounds alternating,
// process CPU time (every thread, llvmpipe's included).
//
//   vtkrtBenchSharedTriangulation [--triangles N] [--rounds R] [--size S]
#include "vtkrtBenchTiming.h"

#include "vtkActor.h"
#include "vtkBVHCellLocator.h"
#include "vtkCamera.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRayTracePass.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkSurfaceTriangulation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace
{
struct Sample
{
  double Frame = 0.0;   ///< the pass's first frame of the mesh, s
  double Locator = 0.0; ///< BuildLocator after it, s
  double Triangulation = 0.0; ///< the pass's own report (GetLastTriangulationSeconds), s
};

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

/// One window, renderer and pass for every round: a round's frame is the
/// first frame of a new mesh (extraction, triangulation, BVH, upload, draw),
/// without the context's or the shader's start.
class Stage
{
public:
  explicit Stage(int size)
  {
    this->Window->SetSize(size, size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Mapper->ScalarVisibilityOff();
    this->Actor->SetMapper(this->Mapper);
    this->Renderer->AddActor(this->Actor);
    this->Renderer->SetPass(this->Pass);
  }

  Sample Run(vtkPolyData* source, bool shared)
  {
    vtkSurfaceTriangulation::SetCaching(shared);
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->DeepCopy(source); // a new polydata: nothing kept from other rounds
    this->Mapper->SetInputData(mesh);
    this->Renderer->ResetCamera();
    Sample s;
    double t0 = vtkrtBench::ProcessSeconds();
    this->Window->Render();
    s.Frame = vtkrtBench::ProcessSeconds() - t0;
    s.Triangulation = this->Pass->GetLastTriangulationSeconds();
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(mesh);
    t0 = vtkrtBench::ProcessSeconds();
    locator->BuildLocator();
    s.Locator = vtkrtBench::ProcessSeconds() - t0;
    vtkSurfaceTriangulation::SetCaching(true);
    return s;
  }

private:
  vtkNew<vtkEGLHeadlessRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkRayTracePass> Pass;
};

void Measure(Stage& stage, const std::string& name, vtkPolyData* mesh, int rounds)
{
  stage.Run(mesh, true); // warm-up: heap pages, the SMP pool, the shader
  stage.Run(mesh, false);
  std::vector<double> frame[2], locator[2], total[2], tri[2];
  for (int r = 0; r < rounds; ++r)
  {
    for (int k = 0; k < 2; ++k)
    {
      const bool shared = (r + k) % 2 == 0; // alternate which goes first
      const Sample s = stage.Run(mesh, shared);
      frame[shared].push_back(s.Frame);
      locator[shared].push_back(s.Locator);
      total[shared].push_back(s.Frame + s.Locator);
      tri[shared].push_back(s.Triangulation);
    }
  }
  auto ms = [](double s) { return 1e3 * s; };
  std::cout << std::fixed << std::setprecision(1);
  std::cout << "| " << name << " | " << ms(Median(frame[0])) << " / " << ms(Median(frame[1])) << " | "
            << ms(Median(tri[0])) << " / " << ms(Median(tri[1])) << " | " << ms(Median(locator[0]))
            << " / " << ms(Median(locator[1])) << " | " << ms(Median(total[0])) << " / "
            << ms(Median(total[1])) << " | " << std::setprecision(2)
            << Median(total[0]) / Median(total[1]) << "x |\n";
}
} // namespace

int main(int argc, char* argv[])
{
  long triangles = 1000000;
  int rounds = 5;
  int size = 512;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--triangles"))
    {
      triangles = std::atol(argv[i + 1]);
    }
    else if (!std::strcmp(argv[i], "--rounds"))
    {
      rounds = std::atoi(argv[i + 1]);
    }
    else if (!std::strcmp(argv[i], "--size"))
    {
      size = std::atoi(argv[i + 1]);
    }
  }
  const int res = static_cast<int>(std::sqrt(triangles / 2.0)) + 2;
  vtkNew<vtkSphereSource> sphere; // triangles
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  sphere->Update();
  vtkNew<vtkPlaneSource> plane; // quads, two triangles each
  const int side = static_cast<int>(std::sqrt(triangles / 2.0));
  plane->SetResolution(side, side);
  plane->Update();
  Stage stage(size);
  std::cout << "process CPU ms, median of " << rounds << " alternating rounds, " << size << "x" << size
            << "; each cell: own (caching off) / shared\n\n";
  std::cout << "| mesh | first frame | pass triangulation (its report) | BuildLocator after it | both | own / shared |\n";
  std::cout << "|---|---:|---:|---:|---:|---:|\n";
  Measure(stage, "sphere, " + std::to_string(sphere->GetOutput()->GetNumberOfPolys()) + " triangles",
    sphere->GetOutput(), rounds);
  Measure(stage, "plane, " + std::to_string(plane->GetOutput()->GetNumberOfPolys()) + " quads",
    plane->GetOutput(), rounds);
  return EXIT_SUCCESS;
}
