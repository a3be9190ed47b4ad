#include "RenderCamera.h"

#include "RenderOptions.h"
#include "RenderScene.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace vtkrtRender
{
namespace
{
// ResetCamera fits the bounding sphere, which leaves most scenes small: zoom
// (or, to keep a view angle that was asked for, dolly) until the scene's
// projected points (mesh vertices, glyph spheres' boxes) fill 90% of the
// image's tighter side.
void FrameScene(
  vtkRenderer* renderer, const std::vector<double>& points, double aspect, bool keepAngle)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  renderer->ResetCameraClippingRange();
  if (points.empty())
  {
    return;
  }
  for (int iteration = 0; iteration < (keepAngle ? 8 : 4); ++iteration)
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
    if (keepAngle)
    {
      camera->Dolly(0.9 / extent);
      renderer->ResetCameraClippingRange();
    }
    else
    {
      camera->Zoom(0.9 / extent);
    }
  }
  renderer->ResetCameraClippingRange();
}

// The points FrameScene fits: the mesh's vertices and each glyph sphere's box.
std::vector<double> FramingPoints(const Scene& scene)
{
  std::vector<double> points;
  for (const SceneMesh& mesh : scene.Meshes)
  {
    const vtkIdType n = mesh.Mesh->GetNumberOfPoints();
    points.reserve(points.size() + 3 * static_cast<size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      mesh.Mesh->GetPoint(i, p);
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

// Looks at the scene with `up` (+X ... -Z) as the view up: from +Z when up
// is X or Y, from -Y when up is Z (so X points right for +Y and +Z up).
void OrientForUp(vtkCamera* camera, const std::string& up)
{
  const double sign = up[0] == '-' ? -1.0 : 1.0;
  const int axis = up[1] - 'X';
  double viewUp[3] = { 0.0, 0.0, 0.0 };
  viewUp[axis] = sign;
  double toEye[3] = { 0.0, 0.0, 1.0 };
  if (axis == 2)
  {
    toEye[1] = -sign;
    toEye[2] = 0.0;
  }
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(toEye);
  camera->SetViewUp(viewUp);
}

// A view up along the view direction leaves the image's up undefined (VTK
// draws nothing). One the user gave is a usage error; another (the
// default up, or any after an orbit) is replaced by the axis least along
// the direction, with a note.
void KeepViewUpOffViewDirection(vtkCamera* camera, bool userGiven)
{
  double dop[3], up[3], cross[3];
  camera->GetDirectionOfProjection(dop);
  camera->GetViewUp(up);
  vtkMath::Normalize(up);
  vtkMath::Cross(dop, up, cross);
  if (vtkMath::Norm(cross) > 1e-6)
  {
    return;
  }
  if (userGiven)
  {
    throw UsageError{ "--camera-view-up is parallel to the view direction: the image's up is undefined" };
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
  {
    axis = std::abs(dop[k]) < std::abs(dop[axis]) ? k : axis;
  }
  double replacement[3] = { 0.0, 0.0, 0.0 };
  replacement[axis] = 1.0;
  camera->SetViewUp(replacement);
  std::cerr << "vtkrt-render: note: the view up is along the view direction; using +" << char('X' + axis)
            << " as the view up\n";
}

// The explicit placement of --camera-*: what is given replaces what the
// orbit chose.
void PlaceCamera(vtkCamera* camera, const CameraOptions& c)
{
  if (c.FocalPointGiven)
  {
    camera->SetFocalPoint(c.FocalPoint.data());
  }
  if (c.PositionGiven)
  {
    camera->SetPosition(c.Position.data());
  }
  if (c.ViewUpGiven)
  {
    camera->SetViewUp(c.ViewUp.data());
  }
  KeepViewUpOffViewDirection(camera, c.ViewUpGiven);
  camera->OrthogonalizeViewUp();
}
} // namespace

void AimCamera(Scene& scene, const Options& opt)
{
  const CameraOptions& c = opt.Camera;
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  OrientForUp(camera, c.Up);
  scene.Renderer->ResetCamera();
  camera->SetViewAngle(c.ViewAngle); // after ResetCamera, which sets 30
  const bool placed = c.PositionGiven || c.FocalPointGiven || c.ViewUpGiven;
  // An explicit placement is kept as given: the default orbit would move it.
  if (!placed || c.OrbitGiven)
  {
    if (placed)
    {
      PlaceCamera(camera, c);
    }
    camera->Azimuth(opt.Azimuth);
    camera->Elevation(opt.Elevation);
    KeepViewUpOffViewDirection(camera, false);
    camera->OrthogonalizeViewUp();
  }
  else
  {
    PlaceCamera(camera, c);
  }
  if (!c.PositionGiven)
  {
    FrameScene(scene.Renderer, FramingPoints(scene), static_cast<double>(opt.Width) / opt.Height,
      c.ViewAngle != 30.0);
  }
  camera->Zoom(c.Zoom);
  scene.Renderer->ResetCameraClippingRange();
}
} // namespace vtkrtRender
