#include "RenderCamera.h"

#include "RenderOptions.h"
#include "RenderScene.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vtkrtRender
{
namespace
{
// ResetCamera fits the bounding sphere, which leaves most scenes small: zoom
// until the scene's projected points (mesh vertices, glyph spheres' boxes)
// fill 90% of the image's tighter side.
void FrameScene(vtkRenderer* renderer, const std::vector<double>& points, double aspect)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  renderer->ResetCameraClippingRange();
  if (points.empty())
  {
    return;
  }
  for (int iteration = 0; iteration < 4; ++iteration)
  {
    vtkMatrix4x4* m = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
    double extent = 0.0;
    for (size_t i = 0; i + 2 < points.size(); i += 3)
    {
      const double p[4] = { points[i], points[i + 1], points[i + 2], 1.0 };
      double q[4];
      m->MultiplyPoint(p, q);
      if (q[3] <= 0.0)
      {
        return; // a point behind the eye: keep ResetCamera's framing
      }
      extent = std::max({ extent, std::abs(q[0] / q[3]), std::abs(q[1] / q[3]) });
    }
    if (extent <= 0.0 || std::abs(extent - 0.9) < 0.005)
    {
      break;
    }
    camera->Zoom(0.9 / extent);
  }
  renderer->ResetCameraClippingRange();
}

// The points FrameScene fits: the mesh's vertices and each glyph sphere's box.
std::vector<double> FramingPoints(const Scene& scene)
{
  std::vector<double> points;
  if (scene.Mesh)
  {
    const vtkIdType n = scene.Mesh->GetNumberOfPoints();
    points.reserve(3 * static_cast<size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      scene.Mesh->GetPoint(i, p);
      points.insert(points.end(), p, p + 3);
    }
  }
  if (scene.SphereCentres)
  {
    vtkDataArray* radius = scene.SphereCentres->GetPointData()->GetArray("radius");
    for (vtkIdType i = 0; i < scene.SphereCentres->GetNumberOfPoints(); ++i)
    {
      double c[3];
      scene.SphereCentres->GetPoint(i, c);
      const double r = radius->GetTuple1(i);
      for (int corner = 0; corner < 8; ++corner)
      {
        points.push_back(c[0] + ((corner & 1) ? r : -r));
        points.push_back(c[1] + ((corner & 2) ? r : -r));
        points.push_back(c[2] + ((corner & 4) ? r : -r));
      }
    }
  }
  return points;
}
} // namespace

void AimCamera(Scene& scene, const Options& opt)
{
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  scene.Renderer->ResetCamera();
  camera->Azimuth(opt.Azimuth);
  camera->Elevation(opt.Elevation);
  camera->OrthogonalizeViewUp();
  FrameScene(scene.Renderer, FramingPoints(scene), static_cast<double>(opt.Width) / opt.Height);
}
} // namespace vtkrtRender
