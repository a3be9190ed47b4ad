#include "RenderPick.h"

#include "RenderOptions.h"
#include "RenderReport.h"
#include "RenderScene.h"

#include "vtkCellPicker.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include "vtkrt/core/Sphere.h"

#ifdef VTKRT_HAVE_BVH_LOCATOR
#include "vtkBVHCellLocator.h"
#endif

#include <iomanip>
#include <limits>
#include <sstream>

namespace vtkrtRender
{
namespace
{
using PickRay = vtkrt::core::Ray<double>;
using Vec3 = vtkrt::core::Vec3<double>;

// Adds a BVH locator over each mesh to the picker when the build has one.
// Returns a description of what picks.
std::string PrepareLocators(vtkCellPicker* picker, const Scene& scene)
{
#ifdef VTKRT_HAVE_BVH_LOCATOR
  for (const SceneMesh& mesh : scene.Meshes)
  {
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(mesh.Mesh);
    locator->BuildLocator();
    picker->AddLocator(locator);
  }
  if (!scene.Meshes.empty())
  {
    return "vtkCellPicker + vtkBVHCellLocator";
  }
#else
  (void)picker;
  (void)scene;
#endif
  return "vtkCellPicker";
}

// " on the mesh" when the picker's actor draws a file of the scene (naming
// the file when there are several).
std::string OnWhichMesh(const Scene& scene, vtkProp* actor)
{
  for (const SceneMesh& mesh : scene.Meshes)
  {
    if (mesh.Actor == actor)
    {
      return " on the mesh" + (scene.Meshes.size() > 1 ? " '" + mesh.File + "'" : std::string());
    }
  }
  return "";
}

// The ray through a display pixel from the near (t = 0) to the far (t = 1)
// clipping plane.
PickRay MakePickRay(vtkRenderer* renderer, double x, double y)
{
  double ends[2][3];
  for (int i = 0; i < 2; ++i)
  {
    renderer->SetDisplayPoint(x, y, i);
    renderer->DisplayToWorld();
    const double* w = renderer->GetWorldPoint();
    for (int k = 0; k < 3; ++k)
    {
      ends[i][k] = w[k] / w[3];
    }
  }
  const Vec3 a(ends[0][0], ends[0][1], ends[0][2]);
  const Vec3 b(ends[1][0], ends[1][1], ends[1][2]);
  return PickRay(a, b - a, 0.0, 1.0);
}

// Glyph spheres have no cells for vtkCellPicker: intersect the pick ray with
// them as analytic spheres, with the core's kernel, as the ray tracer sees
// them. Returns the nearest one hit before `t` (and lowers `t` to it), or -1.
vtkIdType NearestSphere(const PickRay& ray, vtkPolyData* centres, double& t)
{
  vtkIdType sphereId = -1;
  if (centres)
  {
    vtkDataArray* radius = centres->GetPointData()->GetArray("radius");
    for (vtkIdType i = 0; i < centres->GetNumberOfPoints(); ++i)
    {
      double c[3];
      centres->GetPoint(i, c);
      double hit;
      if (vtkrt::core::intersectRaySphere(ray, Vec3(c[0], c[1], c[2]), radius->GetTuple1(i), hit) &&
        hit < t)
      {
        t = hit;
        sphereId = i;
      }
    }
  }
  return sphereId;
}
} // namespace

std::string PickPixel(const Scene& scene, const Pixel& pixel, int height)
{
  std::ostringstream report;
  // Every digit a double holds: a pick far from the origin (1e8) keeps its place.
  report << std::setprecision(std::numeric_limits<double>::max_digits10);
  // Image rows run top down, VTK's display coordinates bottom up; the ray
  // goes through the pixel's centre, as the image's own rays do.
  const double x = pixel.X + 0.5, y = height - 1 - pixel.Y + 0.5;
  vtkNew<vtkCellPicker> picker;
  picker->SetTolerance(0.0);
  const auto p0 = Clock::now();
  const std::string how = PrepareLocators(picker, scene);
  const auto p1 = Clock::now();
  const bool meshHit = picker->Pick(x, y, 0.0, scene.Renderer) && picker->GetCellId() >= 0;
  const auto p2 = Clock::now();

  // The mesh hit and the spheres compared along the same ray.
  const PickRay ray = MakePickRay(scene.Renderer, x, y);
  double meshT = std::numeric_limits<double>::infinity();
  if (meshHit)
  {
    const double* p = picker->GetPickPosition();
    const Vec3 d = ray.dir;
    meshT = glm::dot(Vec3(p[0], p[1], p[2]) - ray.org, d) / glm::dot(d, d);
  }
  double sphereT = meshT;
  const vtkIdType sphereId = NearestSphere(ray, scene.SphereCentres, sphereT);

  report << "pick (" << pixel.X << ", " << pixel.Y << "): ";
  if (sphereId >= 0)
  {
    const Vec3 p = ray.at(sphereT);
    report << "sphere " << sphereId << " at world (" << p.x << ", " << p.y << ", " << p.z
           << ") [analytic glyph sphere]";
  }
  else if (meshHit)
  {
    const double* p = picker->GetPickPosition();
    report << "cell " << picker->GetCellId() << " at world (" << p[0] << ", " << p[1] << ", "
           << p[2] << ")" << OnWhichMesh(scene, picker->GetActor()) << " [" << how << "]";
  }
  else
  {
    report << "nothing [" << how << "]";
  }
  report << std::fixed << std::setprecision(2) << " (locator build " << Milliseconds(p0, p1)
         << " ms, mesh pick " << Milliseconds(p1, p2) << " ms)";
  return report.str();
}
} // namespace vtkrtRender
