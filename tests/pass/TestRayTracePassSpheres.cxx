// Analytic spheres of vtkRayTracePass beyond the basic image tests (points
// drawn as spheres: TestRayTracePassScreenSpheres.cxx):
//   AxisAlignedSilhouettes  sphere silhouettes against an analytic mask when
//                       rays are exactly parallel to coordinate axes
//                       (parallel projection down -z; perspective center
//                       row and column), 0 mismatches
//   OrientedGlyphs      uniformly scaled sphere glyphs ignore orientation (a
//                       sphere is rotation invariant, traced as is); with an
//                       off-center source only the center turns
//   Ellipsoids          sphere glyphs scaled per component and oriented
//                       (DIRECTION, ROTATION, QUATERNION) are traced as
//                       analytic ellipsoids: silhouettes against an analytic
//                       mask built with vtkTransform as vtkGlyph3D does (0
//                       mismatches), id mode naming the analytic nearest
//                       ellipsoid, shading close to VTK's raster, shadows
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Sphere.h"

#include "vtkActor.h"
#include "vtkBitArray.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
const double kBlack[3] = { 0, 0, 0 };

/// Camera ray through pixel (i, j), from the inverse of VTK's projection.
vtkrt::core::Ray<double> PixelRay(vtkMatrix4x4* clipToWorld, int i, int j, int w, int h)
{
  const double x = 2.0 * (i + 0.5) / w - 1.0;
  const double y = 2.0 * (j + 0.5) / h - 1.0;
  double n[4] = { x, y, -1.0, 1.0 };
  double f[4] = { x, y, 1.0, 1.0 };
  clipToWorld->MultiplyPoint(n, n);
  clipToWorld->MultiplyPoint(f, f);
  const vtkrt::core::Vec3<double> o(n[0] / n[3], n[1] / n[3], n[2] / n[3]);
  const vtkrt::core::Vec3<double> e(f[0] / f[3], f[1] / f[3], f[2] / f[3]);
  return vtkrt::core::Ray<double>(o, e - o, 0.0, 1.0);
}

void TestAxisAlignedSilhouettes()
{
  // Odd sizes: the middle row and column have rays with exactly zero x / y.
  const int w = 241, h = 201;
  auto win = MakeWindow(w, h);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0, 0, 0);
  win->AddRenderer(ren);
  // Spheres touching the axes' planes, so axis-parallel rays graze boxes.
  const double spheres[6][4] = { { 0, 0, 0, 1.0 }, { 1.5, 0, -0.5, 0.5 }, { -1.25, 0.75, 0.5, 0.5 },
    { 0, 1.6, 0.3, 0.25 }, { 0.8, -1.3, -2.0, 0.7 }, { -1.0, -1.0, 1.0, 0.125 } };
  AddUnlitWhiteSphereGlyphs(ren, spheres);
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  for (int parallel = 0; parallel < 2; ++parallel)
  {
    vtkCamera* cam = ren->GetActiveCamera();
    cam->SetParallelProjection(parallel);
    cam->SetPosition(0, 0, 8);
    cam->SetFocalPoint(0, 0, 0);
    cam->SetViewUp(0, 1, 0);
    cam->SetViewAngle(35);
    cam->SetParallelScale(2.5);
    cam->SetClippingRange(2, 15);
    win->Render();
    auto image = Grab(win);
    const auto* px = static_cast<const unsigned char*>(image->GetScalarPointer());
    vtkNew<vtkMatrix4x4> clipToWorld;
    vtkMatrix4x4::Invert(
      cam->GetCompositeProjectionTransformMatrix(static_cast<double>(w) / h, -1, 1), clipToWorld);
    const double pixelAngle = 2.0 * std::tan(vtkMath::RadiansFromDegrees(17.5)) / h;
    long mismatches = 0, tolerated = 0, covered = 0, axisRays = 0;
    for (int j = 0; j < h; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const auto ray = PixelRay(clipToWorld, i, j, w, h);
        axisRays += (ray.dir.x == 0.0 || ray.dir.y == 0.0) ? 1 : 0;
        bool inside = false;
        double margin = std::numeric_limits<double>::infinity();
        for (const auto& s : spheres)
        {
          const vtkrt::core::Vec3<double> c(s[0], s[1], s[2]);
          double t;
          inside = inside || vtkrt::core::intersectRaySphere(ray, c, s[3], t);
          const vtkrt::core::Vec3<double> d = glm::normalize(ray.dir);
          const vtkrt::core::Vec3<double> f = c - ray.org;
          const double distance = glm::length(f - glm::dot(f, d) * d);
          const double pixel = parallel ? 2.0 * 2.5 / h : pixelAngle * glm::length(f);
          margin = std::min(margin, std::abs(distance - s[3]) / pixel);
        }
        const bool lit = px[3 * (j * w + i)] > 127;
        covered += lit ? 1 : 0;
        if (lit != inside)
        {
          // Only rays within 1/100 pixel of a silhouette may disagree.
          (margin < 0.01 ? tolerated : mismatches) += 1;
        }
      }
    }
    std::ostringstream s;
    s << (parallel ? "parallel" : "perspective") << " axis-aligned view: " << covered
      << " covered px, " << axisRays << " rays parallel to an axis, " << mismatches
      << " mismatches with the analytic mask (want 0), " << tolerated << " within 0.01 px";
    Check(covered > 1000 && axisRays >= w + h - 1 && mismatches == 0, s.str());
  }
  NoVTKOutput("axis-aligned silhouettes");
}

/// Sphere glyphs scaled by `scale` (1 or 3 components) with an orientation
/// array, orientation on or off.
vtkSmartPointer<vtkActor> OrientedGlyphActor(bool orient, bool perComponent)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> scale;
  scale->SetName("scale");
  scale->SetNumberOfComponents(perComponent ? 3 : 1);
  vtkNew<vtkDoubleArray> direction;
  direction->SetName("direction");
  direction->SetNumberOfComponents(3);
  for (int i = 0; i < 12; ++i)
  {
    const double a = 0.9 * i;
    points->InsertNextPoint(std::cos(a) * (1.0 + 0.1 * i), std::sin(a) * (1.0 + 0.1 * i), 0.2 * i - 1.0);
    const double r = 0.2 + 0.02 * i;
    if (perComponent)
    {
      scale->InsertNextTuple3(r, 0.5 * r, 1.5 * r);
    }
    else
    {
      scale->InsertNextValue(r);
    }
    direction->InsertNextTuple3(std::cos(2.0 * a), 0.3 * i - 1.5, std::sin(a));
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->GetPointData()->AddArray(scale);
  poly->GetPointData()->AddArray(direction);
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(24);
  source->SetPhiResolution(24);
  source->SetRadius(1.0);
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(poly);
  mapper->SetSourceConnection(source->GetOutputPort());
  mapper->SetScaleArray("scale");
  if (perComponent)
  {
    mapper->SetScaleModeToScaleByVectorComponents();
  }
  else
  {
    mapper->SetScaleModeToScaleByMagnitude();
  }
  mapper->SetOrientationArray("direction");
  mapper->SetOrient(orient);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.6, 0.3);
  return actor;
}

void TestOrientedGlyphs()
{
  const int w = 240, h = 240;
  auto win = MakeWindow(w, h);
  auto render = [&](vtkActor* actor, vtkRayTracePass* pass) {
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0, 0, 0);
    ren->AddActor(actor);
    ren->GetActiveCamera()->SetPosition(0.5, -1.0, 8.0);
    ren->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    // Fixed: oriented glyphs have other bounds, hence another automatic range.
    ren->GetActiveCamera()->SetClippingRange(3, 14);
    if (pass)
    {
      ren->SetPass(pass);
    }
    win->AddRenderer(ren);
    win->Render();
    auto image = Grab(win);
    win->RemoveRenderer(ren);
    return image;
  };
  vtkNew<vtkRayTracePass> pass;
  auto oriented = render(OrientedGlyphActor(true, false), pass);
  Check(pass->GetLastTracedInstances() == 1, "oriented uniform glyphs: traced as spheres");
  vtkNew<vtkRayTracePass> pass2;
  auto plain = render(OrientedGlyphActor(false, false), pass2);
  const long differ = CountDifferingPixels(oriented, plain, 0);
  Check(CountForegroundPixels(plain, kBlack) > 1000 && differ == 0,
    "oriented uniform glyphs: identical to unoriented ones (" + std::to_string(differ) +
      " pixels differ, want 0)");

  // An off-center source: the rotation moves the sphere's center.
  auto shifted = OrientedGlyphActor(true, false);
  auto* shiftedMapper = vtkGlyph3DMapper::SafeDownCast(shifted->GetMapper());
  vtkNew<vtkSphereSource> offCenter;
  offCenter->SetThetaResolution(24);
  offCenter->SetPhiResolution(24);
  offCenter->SetCenter(0.8, 0.0, 0.0);
  shiftedMapper->SetSourceConnection(offCenter->GetOutputPort());
  vtkNew<vtkRayTracePass> pass3;
  auto tracedShifted = render(shifted, pass3);
  auto rasterShifted = render(shifted, nullptr);
  const long shiftedDiffer = CountDifferingPixels(tracedShifted, rasterShifted, 40);
  Check(pass3->GetLastTracedInstances() == 1 && shiftedDiffer < 400,
    "oriented off-center sphere glyphs: centers turned as raster's (" +
      std::to_string(shiftedDiffer) + " pixels differ by more than 40, want < 400)");
  NoVTKOutput("oriented glyphs");
}
/// One ellipsoid glyph's source-to-world transform as vtkGlyph3D builds it
/// (translate, orient, scale), an oracle independent of the pass's code.
vtkSmartPointer<vtkTransform> GlyphTransform(const double x[3], int mode, const double o[4],
  const double scale[3])
{
  auto t = vtkSmartPointer<vtkTransform>::New();
  t->PostMultiply();
  t->Scale(scale[0], scale[1], scale[2]);
  if (mode == vtkGlyph3DMapper::DIRECTION)
  {
    if (o[1] == 0.0 && o[2] == 0.0)
    {
      if (o[0] < 0.0)
      {
        t->RotateWXYZ(180.0, 0.0, 1.0, 0.0);
      }
    }
    else
    {
      const double m = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
      t->RotateWXYZ(180.0, (o[0] + m) / 2.0, o[1] / 2.0, o[2] / 2.0);
    }
  }
  else if (mode == vtkGlyph3DMapper::ROTATION)
  {
    t->RotateY(o[1]); // VTK: z, then x, then y applied to the glyph last
    t->RotateX(o[0]);
    t->RotateZ(o[2]);
  }
  else
  {
    const double angle = 2.0 * std::acos(std::max(-1.0, std::min(1.0, o[0])));
    t->RotateWXYZ(vtkMath::DegreesFromRadians(angle), o[1], o[2], o[3]);
  }
  t->Translate(x[0], x[1], x[2]);
  return t;
}

void TestEllipsoids()
{
  const int w = 260, h = 220;
  auto win = MakeWindow(w, h);
  const int modes[3] = { vtkGlyph3DMapper::DIRECTION, vtkGlyph3DMapper::ROTATION,
    vtkGlyph3DMapper::QUATERNION };
  for (int mode : modes)
  {
    const int count = 9;
    vtkNew<vtkPoints> points;
    vtkNew<vtkDoubleArray> scale;
    scale->SetName("scale");
    scale->SetNumberOfComponents(3);
    vtkNew<vtkDoubleArray> orientation;
    orientation->SetName("orientation");
    orientation->SetNumberOfComponents(mode == vtkGlyph3DMapper::QUATERNION ? 4 : 3);
    std::vector<vtkSmartPointer<vtkTransform>> oracle;
    for (int i = 0; i < count; ++i)
    {
      const double x[3] = { 1.1 * (i % 3) - 1.1, 1.0 * (i / 3) - 1.0, 0.3 * i - 1.2 };
      const double sc[3] = { 0.45 + 0.02 * i, 0.18 + 0.01 * i, 0.3 };
      double o[4] = { 0.0, 0.0, 0.0, 0.0 };
      if (mode == vtkGlyph3DMapper::DIRECTION)
      {
        o[0] = std::cos(0.7 * i);
        o[1] = std::sin(0.7 * i);
        o[2] = 0.5 - 0.1 * i;
      }
      else if (mode == vtkGlyph3DMapper::ROTATION)
      {
        o[0] = 20.0 * i;
        o[1] = 35.0 - 9.0 * i;
        o[2] = 13.0 * i;
      }
      else
      {
        const double half = 0.2 * i;
        double axis[3] = { 1.0, 0.5 * i, -0.3 * i };
        vtkMath::Normalize(axis);
        o[0] = std::cos(half);
        o[1] = std::sin(half) * axis[0];
        o[2] = std::sin(half) * axis[1];
        o[3] = std::sin(half) * axis[2];
      }
      points->InsertNextPoint(x);
      scale->InsertNextTuple(sc);
      orientation->InsertNextTuple(o);
      oracle.push_back(GlyphTransform(x, mode, o, sc));
    }
    vtkNew<vtkPolyData> poly;
    poly->SetPoints(points);
    poly->GetPointData()->AddArray(scale);
    poly->GetPointData()->AddArray(orientation);
    vtkNew<vtkSphereSource> source;
    source->SetThetaResolution(48);
    source->SetPhiResolution(48);
    source->SetRadius(1.0);
    vtkNew<vtkGlyph3DMapper> mapper;
    mapper->SetInputData(poly);
    mapper->SetSourceConnection(source->GetOutputPort());
    mapper->SetScaleArray("scale");
    mapper->SetScaleModeToScaleByVectorComponents();
    mapper->SetOrientationArray("orientation");
    mapper->SetOrientationMode(mode);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.9, 0.7, 0.4);
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0, 0, 0);
    ren->AddActor(actor);
    win->AddRenderer(ren);
    vtkCamera* cam = ren->GetActiveCamera();
    cam->SetPosition(0.4, -0.6, 9.0);
    cam->SetFocalPoint(0, 0, 0);
    cam->SetViewUp(0, 1, 0);
    cam->SetViewAngle(35);
    cam->SetClippingRange(3, 16);
    const std::string name = std::string("ellipsoids, ") + mapper->GetOrientationModeAsString();

    // Shaded: close to VTK's raster of 48x48 spheres.
    vtkNew<vtkRayTracePass> pass;
    ren->SetPass(pass);
    win->Render();
    auto traced = Grab(win);
    const int tracedInstances = pass->GetLastTracedInstances();
    ren->SetPass(nullptr);
    win->Render();
    auto raster = Grab(win);
    const double error = Difference(traced, raster);
    const long tracedPixels = CountForegroundPixels(traced, kBlack);
    const long rasterPixels = CountForegroundPixels(raster, kBlack);
    std::ostringstream shaded;
    shaded << name << ": traced " << tracedInstances << " instance(s), " << tracedPixels
           << " px vs raster " << rasterPixels << " px, image error " << error
           << " (want 1, within 2%, <= 40)";
    Check(tracedInstances == 1 && rasterPixels > 2000 &&
        std::abs(tracedPixels - rasterPixels) <= 0.02 * rasterPixels && error <= 40.0,
      shaded.str());
    if (error > 40.0)
    {
      WritePNG(traced, "pass_Ellipsoids_traced.png");
      WritePNG(raster, "pass_Ellipsoids_raster.png");
    }

    // Unlit white: the silhouettes against the analytic mask.
    actor->GetProperty()->LightingOff();
    actor->GetProperty()->SetColor(1, 1, 1);
    ren->SetPass(pass);
    win->Render();
    auto mask = Grab(win);
    actor->GetProperty()->LightingOn();
    const auto* px = static_cast<const unsigned char*>(mask->GetScalarPointer());
    vtkNew<vtkMatrix4x4> clipToWorld;
    vtkMatrix4x4::Invert(
      cam->GetCompositeProjectionTransformMatrix(static_cast<double>(w) / h, -1, 1), clipToWorld);
    std::vector<vtkSmartPointer<vtkMatrix4x4>> toUnit;
    for (const auto& t : oracle)
    {
      auto m = vtkSmartPointer<vtkMatrix4x4>::New();
      vtkMatrix4x4::Invert(t->GetMatrix(), m);
      toUnit.push_back(m);
    }
    long mismatches = 0, tolerated = 0, covered = 0;
    // Per pixel: the nearest ellipsoid's index (-1: none, -2: ambiguous,
    // a silhouette or two surfaces at almost the same depth).
    std::vector<int> nearest(static_cast<std::size_t>(w) * h, -1);
    for (int j = 0; j < h; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const auto ray = PixelRay(clipToWorld, i, j, w, h);
        bool inside = false;
        double margin = std::numeric_limits<double>::infinity();
        double tNearest = std::numeric_limits<double>::infinity();
        double tSecond = std::numeric_limits<double>::infinity();
        int& best = nearest[static_cast<std::size_t>(j) * w + i];
        for (std::size_t g = 0; g < toUnit.size(); ++g)
        {
          const auto& m = toUnit[g];
          double o[4] = { ray.org.x, ray.org.y, ray.org.z, 1.0 };
          double e[4] = { ray.org.x + ray.dir.x, ray.org.y + ray.dir.y, ray.org.z + ray.dir.z,
            1.0 };
          m->MultiplyPoint(o, o);
          m->MultiplyPoint(e, e);
          const vtkrt::core::Vec3<double> uo(o[0], o[1], o[2]);
          const vtkrt::core::Vec3<double> ue(e[0], e[1], e[2]);
          const vtkrt::core::Ray<double> unit(uo, ue - uo, 0.0, 1.0);
          double t;
          if (vtkrt::core::intersectRaySphere(unit, vtkrt::core::Vec3<double>(0.0), 1.0, t))
          {
            inside = true;
            if (t < tNearest)
            {
              tSecond = tNearest;
              tNearest = t;
              best = static_cast<int>(g);
            }
            else
            {
              tSecond = std::min(tSecond, t);
            }
          }
          // Distance of the mapped line from the unit sphere's center.
          const vtkrt::core::Vec3<double> d = glm::normalize(unit.dir);
          const double distance = glm::length(uo - glm::dot(uo, d) * d);
          margin = std::min(margin, std::abs(distance - 1.0));
        }
        if (margin < 1e-3 || tSecond - tNearest < 1e-4)
        {
          best = -2;
        }
        const bool lit = px[3 * (j * w + i)] > 127;
        covered += lit ? 1 : 0;
        if (lit != inside)
        {
          // Within about 1/100 pixel of a silhouette (the smallest axis is
          // about 8 px wide, so 1e-3 of the unit radius).
          (margin < 1e-3 ? tolerated : mismatches) += 1;
        }
      }
    }
    std::ostringstream s;
    s << name << ": " << covered << " covered px, " << mismatches
      << " mismatches with the analytic mask (want 0), " << tolerated << " at a silhouette";
    Check(covered > 2000 && mismatches == 0, s.str());

    // Id mode: each pixel names the nearest ellipsoid's point id.
    pass->IdModeOn();
    win->Render();
    auto ids = Grab(win, true);
    pass->IdModeOff();
    const auto* ip = static_cast<const unsigned char*>(ids->GetScalarPointer());
    long idChecked = 0, idWrong = 0;
    for (std::size_t k = 0; k < nearest.size(); ++k)
    {
      if (nearest[k] == -2)
      {
        continue;
      }
      const unsigned char* c = ip + 4 * k;
      const long id = c[3] == 0 ? -1 : long(c[0]) | (long(c[1]) << 8) | (long(c[2]) << 16);
      idChecked += 1;
      idWrong += id != nearest[k] ? 1 : 0;
    }
    std::ostringstream idText;
    idText << name << ": id mode, " << idChecked << " pixels away from silhouettes and "
           << "intersections, " << idWrong << " name another ellipsoid than the analytic "
           << "nearest (want 0)";
    Check(idChecked > 0.9 * w * h && idWrong == 0, idText.str());

    // Shadows: ellipsoids shadow each other under the headlight's any-hit rays.
    actor->GetProperty()->SetColor(0.9, 0.7, 0.4);
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPosition(4, 5, 6);
    light->SetFocalPoint(0, 0, 0);
    light->PositionalOff();
    ren->AddLight(light);
    win->Render();
    auto unshadowed = Grab(win);
    pass->ShadowsOn();
    win->Render();
    auto shadowed = Grab(win);
    pass->ShadowsOff();
    const long darker = CountDifferingPixels(unshadowed, shadowed, 20);
    Check(darker > 50, name + ": shadows darken " + std::to_string(darker) + " pixels (want > 50)");
    win->RemoveRenderer(ren);
  }
  NoVTKOutput("ellipsoids");
}
/// Glyph masking as vtkOpenGLGlyph3DMapper does it: a one-component bit
/// array hides the glyphs of its zero entries; an array of another type is
/// ignored (raster draws every glyph), so the pass draws every glyph too.
void TestMasking()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(5, 5);
  plane->Update();
  vtkNew<vtkPolyData> points;
  points->SetPoints(plane->GetOutput()->GetPoints());
  const vtkIdType n = points->GetNumberOfPoints();
  vtkNew<vtkBitArray> bits;
  bits->SetName("bits");
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName("bytes");
  for (vtkIdType i = 0; i < n; ++i)
  {
    bits->InsertNextValue(i % 3 == 0 ? 1 : 0);
    bytes->InsertNextValue(i % 3 == 0 ? 1 : 0);
  }
  points->GetPointData()->AddArray(bits);
  points->GetPointData()->AddArray(bytes);
  vtkNew<vtkSphereSource> source;
  source->SetRadius(0.06);
  source->SetThetaResolution(24);
  source->SetPhiResolution(24);
  // The points' sphere glyphs masked by the array `mask`, in a window of their own.
  struct MaskedGlyphs
  {
    vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(240, 240);
    vtkNew<vtkRenderer> Renderer;
  };
  auto maskedGlyphs = [&](const char* mask) {
    auto scene = std::make_unique<MaskedGlyphs>();
    scene->Window->AddRenderer(scene->Renderer);
    vtkNew<vtkGlyph3DMapper> mapper;
    mapper->SetInputData(points);
    mapper->SetSourceConnection(source->GetOutputPort());
    mapper->ScalingOff();
    mapper->ScalarVisibilityOff();
    mapper->MaskingOn();
    mapper->SetMaskArray(mask);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    scene->Renderer->AddActor(actor);
    scene->Renderer->ResetCamera();
    return scene;
  };
  const double black[3] = { 0, 0, 0 };
  long drawn[2] = { 0, 0 };
  for (const bool bitMask : { true, false })
  {
    const std::string name = bitMask ? "bit-array mask" : "unsigned char mask (ignored, as raster)";
    const auto scene = maskedGlyphs(bitMask ? "bits" : "bytes");
    const RasterAndTraced frames =
      CompareBlurred(scene->Window, scene->Renderer, name, 1, 3.0, bitMask ? "MaskingBits" : "MaskingBytes");
    drawn[bitMask ? 0 : 1] = CountForegroundPixels(frames.Traced, black);
    NoVTKOutput(name);
  }
  Check(drawn[0] > 0 && drawn[1] > 2 * drawn[0],
    "the bit mask hides two glyphs in three (" + std::to_string(drawn[0]) + " pixels against " +
      std::to_string(drawn[1]) + " unmasked)");

  // A bit mask of two components: VTK reports an error and draws no glyph;
  // the pass leaves the actor to it.
  vtkNew<vtkBitArray> pairs;
  pairs->SetName("pairs");
  pairs->SetNumberOfComponents(2);
  pairs->SetNumberOfTuples(n);
  points->GetPointData()->AddArray(pairs);
  const auto scene = maskedGlyphs("pairs");
  vtkNew<vtkRayTracePass> pass;
  scene->Renderer->SetPass(pass);
  scene->Window->Render();
  Check(pass->GetNumberOfTracedProps() == 0 && Output->GetNumberOfErrors() >= 1,
    "a two-component bit mask: left to raster, which reports VTK's error (" +
      std::to_string(pass->GetNumberOfTracedProps()) + " traced, " + std::to_string(Output->GetNumberOfErrors()) +
      " error(s))");
  Output->Clear();
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "AxisAlignedSilhouettes", TestAxisAlignedSilhouettes },
      { "OrientedGlyphs", TestOrientedGlyphs }, { "Ellipsoids", TestEllipsoids },
      { "Masking", TestMasking } });
}
