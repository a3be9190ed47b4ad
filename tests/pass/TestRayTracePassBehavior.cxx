// vtkRayTracePass behaviour beyond raster look-alike images:
//   Counters          what a frame builds, uploads and compiles across camera
//                     moves, property/light changes, data and feature changes
//   FarFromOrigin     a scene translated by 1e8 renders like the same scene
//                     at the origin
//   Degenerate        empty renderer, empty polydata, NaN points: clean image,
//                     no GL error, no VTK error
//   TooLarge          buffers over the texture-buffer limit: a clear error
//                     and nothing traced (never garbage)
//   SphereSilhouettes analytic spheres against an analytic per-pixel mask
//   IdPick            id mode vs a CPU pick (core closest hit, double) along
//                     every pixel's ray
//   App <vtkrt-render> vtkrt-render --mode raytrace on the demo and on a file,
//                     against its raster mode
// TestRayTracePassBehavior <Case> [vtkrt-render path].
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkBVHCellLocator.h"
#include "vtkCellArray.h"
#include "vtkCellPicker.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkConeSource.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPLYWriter.h"
#include "vtkPNGReader.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"
#include "vtk_glew.h"

#include "vtkrt/core/Core.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
std::string AppPath;

void NoGLError(vtkRenderWindow* win, const std::string& label)
{
  win->MakeCurrent();
  GLenum error = glGetError();
  Check(error == GL_NO_ERROR, label + ": no GL error");
  while (error != GL_NO_ERROR)
  {
    error = glGetError();
  }
}

vtkSmartPointer<vtkActor> MeshActor(vtkPolyData* poly)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.7, 0.5);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(20);
  return actor;
}

vtkSmartPointer<vtkActor> GlyphActor(vtkPolyData* points)
{
  points->GetPointData()->SetActiveScalars("scalar");
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(points);
  mapper->SetSourceConnection(sphere->GetOutputPort());
  mapper->SetScaleArray("radius");
  mapper->SetScaleModeToScaleByMagnitude();
  mapper->SetScaleFactor(2.0);
  mapper->SetScalarRange(0.0, 1.0);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

void TestCounters()
{
  auto win = MakeWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  auto bunnyData = ReadPolyData("bunny.vtp");
  auto bunny = MeshActor(bunnyData);
  auto glyphs = GlyphActor(ReadPolyData("demo-spheres.vtp"));
  ren->AddActor(bunny);
  ren->AddActor(glyphs);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);

  auto frame = [&](const std::string& what, int builds, bool geometry, int compiles) {
    win->Render();
    std::ostringstream s;
    s << what << ": " << pass->GetLastBVHBuilds() << " BVH builds (want " << builds << "), "
      << pass->GetLastGeometryBytesUploaded() << " geometry bytes (want "
      << (geometry ? "> 0" : "0") << "), " << pass->GetLastShaderCompiles()
      << " shader compiles (want " << compiles << "), " << pass->GetLastFrameBytesUploaded()
      << " per-frame bytes, " << pass->GetLastTracedPrimitives() << " primitives traced";
    Check(pass->GetLastBVHBuilds() == builds &&
        (pass->GetLastGeometryBytesUploaded() > 0) == geometry &&
        pass->GetLastShaderCompiles() == compiles,
      s.str());
  };
  frame("first frame", 2, true, 1);
  Check(pass->GetLastTracedPrimitives() ==
      bunnyData->GetNumberOfCells() + ReadPolyData("demo-spheres.vtp")->GetNumberOfPoints(),
    "first frame traces every triangle and sphere");
  Check(pass->GetLastFrameBytesUploaded() > 0 && pass->GetLastFrameBytesUploaded() < 1024,
    "per-frame upload is the two instance records only");
  const std::string twoKinds = pass->GetLastFeatureKey();
  for (int i = 0; i < 3; ++i)
  {
    ren->GetActiveCamera()->Azimuth(25);
    ren->GetActiveCamera()->Elevation(5);
    ren->ResetCameraClippingRange();
    frame("camera move " + std::to_string(i + 1), 0, false, 0);
  }
  ren->GetActiveCamera()->ParallelProjectionOn();
  frame("parallel projection", 0, false, 0);
  ren->GetActiveCamera()->ParallelProjectionOff();
  bunny->GetProperty()->SetColor(0.2, 0.8, 0.3);
  bunny->GetProperty()->SetSpecularPower(5);
  frame("property change", 0, false, 0);
  bunny->SetPosition(0.01, 0.0, 0.0);
  frame("actor moved", 0, false, 0);
  vtkLight* light = vtkLight::SafeDownCast(ren->GetLights()->GetItemAsObject(0));
  light->SetIntensity(0.7);
  frame("light intensity change", 0, false, 0);

  // Data change: the bunny's points move; only its BVH is rebuilt.
  vtkPoints* points = bunnyData->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, p[0] * 1.1, p[1], p[2]);
  }
  points->Modified();
  frame("bunny data change", 1, true, 0);
  frame("unchanged after data change", 0, false, 0);

  // A new feature (a clipping plane) compiles one new program; going back
  // finds the cached one.
  vtkNew<vtkPlane> plane;
  plane->SetNormal(1, 0, 0);
  bunny->GetMapper()->AddClippingPlane(plane);
  frame("clipping plane added", 0, false, 1);
  Check(std::string(pass->GetLastFeatureKey()) != twoKinds, "the feature key names the clip plane");
  bunny->GetMapper()->RemoveAllClippingPlanes();
  frame("clipping plane removed", 0, false, 0);

  // Without spheres the shader has no sphere code at all.
  glyphs->VisibilityOff();
  frame("glyphs hidden", 0, true, 1);
  const std::string source = pass->GetLastFragmentShaderSource();
  Check(source.find("raySphereRoots") == std::string::npos &&
      source.find("traverseTriangles") != std::string::npos,
    "a scene without spheres compiles no sphere code");
  glyphs->VisibilityOn();
  frame("glyphs shown again (their BVH was dropped with them)", 1, true, 0);
  pass->SetBuildQuality(0);
  frame("build quality changed: both BVHs rebuilt", 2, true, 0);
  frame("unchanged after the quality change", 0, false, 0);
  NoGLError(win, "counters");
  NoVTKOutput("counters");
}

void TestFarFromOrigin()
{
  const double offset[3] = { 1e8, -1e8, 1e8 };
  auto bunny = ReadPolyData("bunny.vtp");
  auto spheres = ReadPolyData("demo-spheres.vtp");
  vtkSmartPointer<vtkImageData> images[3];
  double clipping[2] = { 0, 0 };
  double position[3], focal[3], up[3];
  for (int pass = 0; pass < 3; ++pass)
  {
    // 0: traced at the origin; 1: traced at 1e8 (data and actor offsets);
    // 2: raster at 1e8 (for information only).
    const bool far = pass > 0;
    const double zero[3] = { 0, 0, 0 };
    const double half[3] = { offset[0] / 2, offset[1] / 2, offset[2] / 2 };
    auto win = MakeWindow(300, 300);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    ren->SetBackground(0.1, 0.2, 0.3);
    // Bunny: offset in its (double) points; glyphs: half in the points,
    // half in the actor matrix.
    ren->AddActor(MeshActor(Shifted(bunny, far ? offset : zero)));
    auto glyphs = GlyphActor(Shifted(spheres, far ? half : zero));
    if (far)
    {
      glyphs->SetPosition(half[0], half[1], half[2]);
    }
    ren->AddActor(glyphs);
    vtkCamera* cam = ren->GetActiveCamera();
    if (pass == 0)
    {
      ren->ResetCamera();
      cam->Azimuth(30);
      cam->Elevation(10);
      ren->ResetCameraClippingRange();
      cam->GetClippingRange(clipping);
      cam->GetPosition(position);
      cam->GetFocalPoint(focal);
      cam->GetViewUp(up);
    }
    else
    {
      cam->SetPosition(position[0] + offset[0], position[1] + offset[1], position[2] + offset[2]);
      cam->SetFocalPoint(focal[0] + offset[0], focal[1] + offset[1], focal[2] + offset[2]);
      cam->SetViewUp(up);
      cam->SetClippingRange(clipping);
    }
    vtkNew<vtkRayTracePass> rt;
    if (pass < 2)
    {
      ren->SetPass(rt);
    }
    win->Render();
    images[pass] = Grab(win);
    NoGLError(win, "far from origin");
  }
  const double error = Difference(images[1], images[0]);
  const long differing = CountDifferingPixels(images[1], images[0], 24);
  std::ostringstream s;
  s << "traced at 1e8 vs traced at the origin: error " << error << " <= 5, " << differing
    << " pixels differ (<= 0.2%)";
  Check(error <= 5.0 && differing >= 0 && differing <= 300 * 300 / 500, s.str());
  std::cout << "info: raster at 1e8 vs traced at the origin: error "
            << Difference(images[2], images[0]) << " ("
            << CountDifferingPixels(images[2], images[0], 24) << " pixels differ)\n";
  if (error > 5.0)
  {
    WritePNG(images[0], std::string(VTKRT_TEMP_DIR) + "/pass_far_origin.png");
    WritePNG(images[1], std::string(VTKRT_TEMP_DIR) + "/pass_far_1e8.png");
  }
  NoVTKOutput("far from origin");
}

void TestDegenerate()
{
  const double background[3] = { 0.25, 0.5, 0.75 };
  auto expectBackground = [&](vtkRenderWindow* win, const std::string& what, bool empty) {
    auto image = Grab(win);
    const long fg = CountForegroundPixels(image, background);
    Check(empty ? fg == 0 : fg > 0, what + (empty ? ": background only" : ": something drawn"));
    NoGLError(win, what);
    NoVTKOutput(what);
  };
  auto win = MakeWindow(120, 100);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(background[0], background[1], background[2]);
  win->AddRenderer(ren);
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  expectBackground(win, "empty renderer", true);

  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPolyDataMapper> emptyMapper;
  emptyMapper->SetInputData(empty);
  vtkNew<vtkActor> emptyActor;
  emptyActor->SetMapper(emptyMapper);
  ren->AddActor(emptyActor);
  win->Render();
  expectBackground(win, "actor with empty polydata", true);

  // Triangles with NaN points: those triangles are skipped, the rest drawn.
  vtkNew<vtkPoints> points;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double coords[6][3] = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 },
    { nan, 0, 0 }, { 0, nan, nan } };
  for (const auto& c : coords)
  {
    points->InsertNextPoint(c);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType tris[4][3] = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 1, 4 }, { 4, 5, 2 } };
  for (const auto& t : tris)
  {
    polys->InsertNextCell(3, t);
  }
  vtkNew<vtkPolyData> withNaN;
  withNaN->SetPoints(points);
  withNaN->SetPolys(polys);
  vtkNew<vtkPolyDataMapper> nanMapper;
  nanMapper->SetInputData(withNaN);
  vtkNew<vtkActor> nanActor;
  nanActor->SetMapper(nanMapper);
  ren->AddActor(nanActor);
  // Glyphs with a NaN center and a zero radius among valid ones.
  vtkNew<vtkPolyData> centers;
  vtkNew<vtkPoints> centerPoints;
  centerPoints->InsertNextPoint(0, 0, 0.5);
  centerPoints->InsertNextPoint(nan, 0, 0);
  centerPoints->InsertNextPoint(0.5, 0.5, 0.5);
  centers->SetPoints(centerPoints);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  radius->InsertNextValue(0.2);
  radius->InsertNextValue(0.2);
  radius->InsertNextValue(0.0);
  centers->GetPointData()->AddArray(radius);
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkGlyph3DMapper> glyphMapper;
  glyphMapper->SetInputData(centers);
  glyphMapper->SetSourceConnection(sphere->GetOutputPort());
  glyphMapper->SetScaleArray("radius");
  glyphMapper->SetScaleModeToScaleByMagnitude();
  glyphMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphMapper);
  ren->AddActor(glyphActor);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetPosition(0, 0, 5);
  cam->SetFocalPoint(0, 0, 0);
  cam->SetClippingRange(1, 10);
  win->Render();
  expectBackground(win, "NaN points and zero radii", false);
  Check(pass->GetLastTracedInstances() == 2, "NaN scene: the mesh and the glyphs are traced");
  Check(pass->GetLastTracedPrimitives() == 2 + 1,
    "NaN scene: 2 valid triangles and 1 valid sphere traced (traced " +
      std::to_string(pass->GetLastTracedPrimitives()) + ")");
}

void TestTooLarge()
{
  auto win = MakeWindow(100, 100);
  vtkNew<vtkRenderer> ren;
  const double background[3] = { 0, 0, 0 };
  win->AddRenderer(ren);
  ren->AddActor(MeshActor(ReadPolyData("bunny.vtp")));
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  pass->SetMaximumTextureBufferTexels(10000);
  ren->SetPass(pass);
  Output->SetEcho(false);
  win->Render();
  Output->SetEcho(true);
  Check(Output->HasErrorContaining("more than the limit"), "too large: a clear error message");
  Output->Clear();
  Check(CountForegroundPixels(Grab(win), background) == 0, "too large: nothing traced, no garbage");
  NoGLError(win, "too large");
  // The same frame again: no repeated error, still nothing traced.
  win->Render();
  Check(Output->GetNumberOfErrors() == 0, "too large: the error is not repeated every frame");
  Check(CountForegroundPixels(Grab(win), background) == 0, "too large: still nothing traced");
  // The limit lifted, the same pass renders (nothing changed but the limit).
  pass->SetMaximumTextureBufferTexels(0);
  win->Render();
  Check(CountForegroundPixels(Grab(win), background) > 0, "limit lifted: the scene renders");
  NoVTKOutput("too large");
}

void TestSphereSilhouettes()
{
  const int w = 240, h = 200;
  auto win = MakeWindow(w, h);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0, 0, 0);
  const double spheres[5][4] = { { 0, 0, 0, 1.0 }, { 1.7, 0.3, -0.5, 0.55 },
    { -1.5, -0.6, 0.8, 0.31 }, { 0.2, 1.4, 0.3, 0.173 }, { -0.9, 1.1, -2.0, 0.7 } };
  AddUnlitWhiteSphereGlyphs(ren, spheres);
  for (int parallel = 0; parallel < 2; ++parallel)
  {
    vtkCamera* cam = ren->GetActiveCamera();
    cam->SetParallelProjection(parallel);
    cam->SetPosition(0.3, 0.2, 7);
    cam->SetFocalPoint(0, 0.1, 0);
    cam->SetViewUp(0, 1, 0);
    cam->SetViewAngle(40);
    cam->SetParallelScale(2.2);
    cam->SetClippingRange(2, 15);
    vtkNew<vtkRayTracePass> pass;
    ren->SetPass(pass);
    win->Render();
    auto image = Grab(win);
    const auto* px = static_cast<const unsigned char*>(image->GetScalarPointer());
    PixelRays rays(ren, w, h);
    double pixelAngle = 2.0 * std::tan(vtkMath::RadiansFromDegrees(20.0)) / h;
    long mismatches = 0, tolerated = 0, covered = 0;
    for (int j = 0; j < h; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const auto ray = rays.Ray(i, j);
        bool inside = false;
        double closestMargin = std::numeric_limits<double>::infinity();
        for (const auto& s : spheres)
        {
          const vtkrt::core::Vec3<double> c(s[0], s[1], s[2]);
          double t;
          if (vtkrt::core::intersectRaySphere(ray, c, s[3], t))
          {
            inside = true;
          }
          // Distance from the center to the ray's line, minus the radius,
          // in pixels at the sphere's distance.
          const vtkrt::core::Vec3<double> d = glm::normalize(ray.dir);
          const vtkrt::core::Vec3<double> f = c - ray.org;
          const double along = glm::dot(f, d);
          const double distance = glm::length(f - along * d);
          const double pixelSize = parallel ? 2.0 * 2.2 / h : pixelAngle * glm::length(c - ray.org);
          closestMargin = std::min(closestMargin, std::abs(distance - s[3]) / pixelSize);
        }
        const bool lit = px[3 * (j * w + i)] > 127;
        covered += lit ? 1 : 0;
        if (lit != inside)
        {
          // Only rays within 1/100 pixel of a silhouette may disagree.
          if (closestMargin < 0.01)
          {
            ++tolerated;
          }
          else
          {
            ++mismatches;
          }
        }
      }
    }
    std::ostringstream s;
    s << (parallel ? "parallel" : "perspective") << " sphere silhouettes: " << covered
      << " covered pixels, " << mismatches << " mismatches with the analytic mask (want 0), "
      << tolerated << " within 0.01 px of a silhouette";
    Check(covered > 1000 && mismatches == 0, s.str());
  }
  NoGLError(win, "sphere silhouettes");
  NoVTKOutput("sphere silhouettes");
}

void TestIdPick()
{
  const int w = 300, h = 300;
  auto win = MakeWindow(w, h);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  auto bunnyData = ReadPolyData("bunny.vtp");
  auto sphereData = ReadPolyData("demo-spheres.vtp");
  auto bunny = MeshActor(bunnyData);
  auto glyphs = GlyphActor(sphereData);
  ren->AddActor(bunny);
  ren->AddActor(glyphs);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(30);
  ren->GetActiveCamera()->Elevation(15);
  ren->GetActiveCamera()->Dolly(1.3);
  ren->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  pass->IdModeOn();
  ren->SetPass(pass);
  win->Render();
  auto image = Grab(win, true);
  const auto* px = static_cast<const unsigned char*>(image->GetScalarPointer());
  Check(image->GetNumberOfScalarComponents() == 4, "id mode: RGBA readback");
  Check(pass->GetNumberOfTracedProps() == 2 && pass->GetTracedProp(0) == bunny &&
      pass->GetTracedProp(1) == glyphs,
    "id mode: traced props in renderer order");

  // CPU side: the same triangles and spheres in double, the core's closest
  // hit along each pixel's ray.
  std::vector<vtkrt::core::Vec3<double>> vertices(bunnyData->GetNumberOfPoints());
  for (vtkIdType i = 0; i < bunnyData->GetNumberOfPoints(); ++i)
  {
    bunnyData->GetPoint(i, &vertices[i].x);
  }
  std::vector<std::uint32_t> indices;
  std::vector<vtkIdType> cellOfTriangle;
  vtkIdType npts;
  const vtkIdType* pts;
  vtkCellArray* polys = bunnyData->GetPolys();
  polys->InitTraversal();
  for (vtkIdType cell = 0; polys->GetNextCell(npts, pts); ++cell)
  {
    for (vtkIdType k = 1; k + 1 < npts; ++k)
    {
      indices.insert(indices.end(), { std::uint32_t(pts[0]), std::uint32_t(pts[k]), std::uint32_t(pts[k + 1]) });
      cellOfTriangle.push_back(cell + bunnyData->GetNumberOfVerts() + bunnyData->GetNumberOfLines());
    }
  }
  vtkrt::core::TriangleMesh<double> mesh(vertices, indices);
  vtkrt::core::BVH meshBVH = vtkrt::core::buildTriangleBVH(mesh);
  std::vector<vtkrt::core::Vec3<double>> centers(sphereData->GetNumberOfPoints());
  std::vector<double> radii(centers.size());
  vtkDataArray* radiusArray = sphereData->GetPointData()->GetArray("radius");
  for (vtkIdType i = 0; i < sphereData->GetNumberOfPoints(); ++i)
  {
    sphereData->GetPoint(i, &centers[i].x);
    radii[i] = std::abs(radiusArray->GetTuple1(i)) * 2.0 * 0.5; // scale factor * source radius
  }
  vtkrt::core::SphereSet<double> set(centers, radii);
  vtkrt::core::BVH sphereBVH = vtkrt::core::buildSphereBVH(set);

  PixelRays rays(ren, w, h);
  std::vector<long> gpu(static_cast<std::size_t>(w) * h), cpu(gpu.size());
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t p = static_cast<std::size_t>(j) * w + i;
      int prop;
      vtkIdType id;
      gpu[p] = vtkRayTracePass::DecodeId(px + 4 * p, prop, id) ? prop * 100000000L + id : -1;
      auto ray = rays.Ray(i, j);
      vtkrt::core::Hit<double> hit;
      vtkrt::core::TriangleIntersector<double> tri(mesh);
      long best = -1;
      if (vtkrt::core::closestHit(meshBVH, ray, tri, hit))
      {
        best = cellOfTriangle[hit.prim];
        ray.tmax = hit.t;
      }
      vtkrt::core::Hit<double> sphereHit;
      vtkrt::core::SphereIntersector<double> sph(set);
      if (vtkrt::core::closestHit(sphereBVH, ray, sph, sphereHit))
      {
        best = 100000000L + sphereHit.prim;
      }
      cpu[p] = best;
    }
  }
  long hits = 0, mismatches = 0, offEdge = 0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t p = static_cast<std::size_t>(j) * w + i;
      hits += gpu[p] >= 0 ? 1 : 0;
      if (gpu[p] == cpu[p])
      {
        continue;
      }
      ++mismatches;
      // Within a pixel of an edge: some neighbour shows another id.
      bool edge = false;
      for (int dj = -1; dj <= 1 && !edge; ++dj)
      {
        for (int di = -1; di <= 1 && !edge; ++di)
        {
          const int ni = i + di, nj = j + dj;
          if (ni < 0 || nj < 0 || ni >= w || nj >= h)
          {
            continue;
          }
          const std::size_t q = static_cast<std::size_t>(nj) * w + ni;
          edge = gpu[q] != gpu[p] || cpu[q] != cpu[p];
        }
      }
      offEdge += edge ? 0 : 1;
    }
  }
  // The same check through VTK's own picking: vtkCellPicker with a
  // vtkBVHCellLocator over the mesh (the glyphs are not pickable, so only
  // pixels the GPU gives to the mesh or to nothing are compared), on every
  // fifth pixel of every fifth row.
  glyphs->PickableOff();
  vtkNew<vtkBVHCellLocator> locator;
  locator->SetDataSet(bunnyData);
  locator->BuildLocator();
  vtkNew<vtkCellPicker> picker;
  picker->AddLocator(locator);
  picker->SetTolerance(0.0);
  long picked = 0, pickMismatches = 0, pickOffEdge = 0;
  for (int j = 2; j < h; j += 5)
  {
    for (int i = 2; i < w; i += 5)
    {
      const std::size_t p = static_cast<std::size_t>(j) * w + i;
      if (gpu[p] >= 100000000L)
      {
        continue; // a sphere in front
      }
      ++picked;
      const bool hit = picker->Pick(i + 0.5, j + 0.5, 0.0, ren) != 0;
      const long id = hit && picker->GetActor() == bunny ? static_cast<long>(picker->GetCellId()) : -1;
      if (id != gpu[p])
      {
        ++pickMismatches;
        bool edge = false;
        for (int dj = -1; dj <= 1; ++dj)
        {
          for (int di = -1; di <= 1; ++di)
          {
            const std::size_t q = static_cast<std::size_t>(j + dj) * w + (i + di);
            edge = edge || gpu[q] != gpu[p];
          }
        }
        pickOffEdge += edge ? 0 : 1;
      }
    }
  }
  std::ostringstream pk;
  pk << "id mode vs vtkCellPicker + vtkBVHCellLocator: " << picked << " pixels, "
     << pickMismatches << " disagree, " << pickOffEdge << " away from an edge (want 0)";
  Check(picked > 1000 && pickOffEdge == 0 && pickMismatches <= picked / 100, pk.str());

  std::ostringstream s;
  s << "id mode vs CPU pick: " << hits << " pixels hit, " << mismatches
    << " disagree (bound: 0.5% of pixels), " << offEdge << " of them away from an edge (want 0)";
  Check(hits > w * h / 10 && offEdge == 0 && mismatches <= w * h / 200, s.str());
  NoGLError(win, "id pick");
  NoVTKOutput("id pick");
}

// Many actors (more than 8): the pass walks a top-level BVH over them. The
// image matches raster; the top level is built once, not for camera moves,
// again when an actor moves; the shared mesh is built once.
void TestManyActors()
{
  auto win = MakeWindow(300, 300);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.2, 0.2, 0.2);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 6; ++j)
    {
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(mapper);
      actor->SetPosition(1.1 * i, 1.1 * j, 0.4 * ((i + j) % 3));
      actor->SetScale(1.0 + 0.1 * i, 1.0, 1.0 + 0.1 * j);
      actor->GetProperty()->SetColor(0.3 + 0.1 * i, 0.9 - 0.1 * j, 0.5);
      ren->AddActor(actor);
      actors.push_back(actor);
    }
  }
  ren->ResetCamera();
  ren->GetActiveCamera()->Elevation(35);
  ren->GetActiveCamera()->Azimuth(20);
  ren->ResetCameraClippingRange();
  auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
  const double error = Difference(traced, raster);
  const long differing = CountDifferingPixels(traced, raster, 24);
  std::ostringstream s;
  s << "36 actors: ray traced vs raster error " << error << " <= 40, " << differing
    << " pixels differ (<= 2%)";
  Check(error <= 40.0 && differing >= 0 && differing <= 300 * 300 / 50, s.str());
  Check(std::string(pass->GetLastFeatureKey()).find("X1") != std::string::npos,
    "36 actors: the shader walks a top-level BVH");
  Check(pass->GetLastBVHBuilds() == 1 && pass->GetLastTopLevelBuilds() == 1,
    "36 actors: one mesh BVH and one top-level BVH built");
  ren->GetActiveCamera()->Azimuth(30);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastTopLevelBuilds() == 0 &&
      pass->GetLastGeometryBytesUploaded() == 0,
    "36 actors, camera move: nothing built or uploaded but the instance records");
  actors[7]->AddPosition(0.0, 0.0, 0.5);
  win->Render();
  Check(pass->GetLastBVHBuilds() == 0 && pass->GetLastTopLevelBuilds() == 1,
    "36 actors, one actor moved: the top level only is rebuilt");
  NoGLError(win, "many actors");
  NoVTKOutput("many actors");
}

// Which props the pass traces and which it leaves to the raster delegate.
void TestClassification()
{
  auto win = MakeWindow(100, 100);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  std::vector<std::pair<std::string, vtkSmartPointer<vtkActor>>> traced, raster;
  auto meshActor = [](vtkPolyData* poly) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(poly);
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    return actor;
  };
  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  vtkPolyData* mesh = sphere->GetOutput();
  traced.emplace_back("opaque mesh", meshActor(mesh));
  auto translucent = meshActor(mesh);
  translucent->GetProperty()->SetOpacity(0.5);
  raster.emplace_back("translucent property", translucent);
  auto wire = meshActor(mesh);
  wire->GetProperty()->SetRepresentationToWireframe();
  raster.emplace_back("wireframe", wire);
  auto edges = meshActor(mesh);
  edges->GetProperty()->EdgeVisibilityOn();
  raster.emplace_back("edge visibility", edges);
  auto culled = meshActor(mesh);
  culled->GetProperty()->BackfaceCullingOn();
  raster.emplace_back("backface culling", culled);
  auto points = meshActor(mesh);
  points->GetProperty()->SetRepresentationToPoints();
  raster.emplace_back("points without RenderPointsAsSpheres", points);
  auto spheres = meshActor(mesh);
  spheres->GetProperty()->SetRepresentationToPoints();
  spheres->GetProperty()->RenderPointsAsSpheresOn();
  traced.emplace_back("points with RenderPointsAsSpheres", spheres);
  // Scalars with alpha make the actor translucent in VTK.
  auto alphaMesh = vtkSmartPointer<vtkPolyData>::New();
  alphaMesh->DeepCopy(mesh);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetNumberOfComponents(4);
  for (vtkIdType i = 0; i < alphaMesh->GetNumberOfPoints(); ++i)
  {
    const unsigned char c[4] = { 255, 0, 0, 100 };
    rgba->InsertNextTypedTuple(c);
  }
  alphaMesh->GetPointData()->SetScalars(rgba);
  auto alpha = meshActor(alphaMesh);
  vtkPolyDataMapper::SafeDownCast(alpha->GetMapper())->SetColorModeToDirectScalars();
  raster.emplace_back("scalars with alpha", alpha);
  // Lines cannot be traced: the whole actor falls back.
  vtkNew<vtkConeSource> cone;
  cone->Update();
  auto withLines = vtkSmartPointer<vtkPolyData>::New();
  withLines->DeepCopy(cone->GetOutput());
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  withLines->SetLines(lines);
  raster.emplace_back("polydata with lines", meshActor(withLines));
  vtkNew<vtkGlyph3DMapper> coneGlyphs;
  coneGlyphs->SetInputData(mesh);
  coneGlyphs->SetSourceConnection(cone->GetOutputPort());
  auto coneActor = vtkSmartPointer<vtkActor>::New();
  coneActor->SetMapper(coneGlyphs);
  raster.emplace_back("glyphs of a cone", coneActor);
  vtkNew<vtkGlyph3DMapper> sphereGlyphs;
  sphereGlyphs->SetInputData(mesh);
  sphereGlyphs->SetSourceConnection(sphere->GetOutputPort());
  auto sphereActor = vtkSmartPointer<vtkActor>::New();
  sphereActor->SetMapper(sphereGlyphs);
  traced.emplace_back("glyphs of a sphere", sphereActor);

  // A composite with a translucent block falls back whole; one with only
  // opaque blocks is traced.
  for (int translucentBlock = 0; translucentBlock < 2; ++translucentBlock)
  {
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(2);
    blocks->SetBlock(0, mesh);
    blocks->SetBlock(1, cone->GetOutput());
    vtkNew<vtkCompositePolyDataMapper2> composite;
    composite->SetInputDataObject(blocks);
    vtkNew<vtkCompositeDataDisplayAttributes> attributes;
    if (translucentBlock)
    {
      attributes->SetBlockOpacity(blocks->GetBlock(1), 0.5);
    }
    composite->SetCompositeDataDisplayAttributes(attributes);
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(composite);
    (translucentBlock ? raster : traced)
      .emplace_back(translucentBlock ? "composite with a translucent block" : "composite", actor);
  }

  for (auto* list : { &traced, &raster })
  {
    for (auto& e : *list)
    {
      ren->AddActor(e.second);
    }
  }
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  win->Render();
  auto isTraced = [&](vtkActor* a) {
    for (int i = 0; i < pass->GetNumberOfTracedProps(); ++i)
    {
      if (pass->GetTracedProp(i) == a)
      {
        return true;
      }
    }
    return false;
  };
  for (auto& e : traced)
  {
    Check(isTraced(e.second), "traced: " + e.first);
  }
  for (auto& e : raster)
  {
    Check(!isTraced(e.second), "left to raster: " + e.first);
  }
  // (An actor with opaque and translucent parts counts in both raster passes.)
  Check(pass->GetNumberOfRenderedProps() >= static_cast<int>(traced.size() + raster.size()),
    "every prop is rendered by the pass or its delegate");
  NoGLError(win, "classification");
  NoVTKOutput("classification");
}

// Removing the pass gives raster back; the pass survives its window being
// destroyed and renders the same renderer in a new window.
void TestLifecycle()
{
  vtkNew<vtkRenderer> ren;
  ren->AddActor(MeshActor(ReadPolyData("bunny.vtp")));
  ren->SetBackground(0.1, 0.2, 0.3);
  ren->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  vtkSmartPointer<vtkImageData> raster, traced;
  {
    auto win = MakeWindow(160, 160);
    win->AddRenderer(ren);
    win->Render();
    raster = Grab(win);
    ren->SetPass(pass);
    win->Render();
    traced = Grab(win);
    ren->SetPass(nullptr);
    win->Render();
    Check(Difference(Grab(win), raster) == 0.0, "pass removed: the raster image is back");
    ren->SetPass(pass);
    win->Render();
    win->RemoveRenderer(ren);
    win->Finalize();
  }
  auto win2 = MakeWindow(160, 160);
  win2->AddRenderer(ren);
  win2->Render();
  Check(pass->GetLastGeometryBytesUploaded() > 0 && pass->GetLastShaderCompiles() == 1,
    "new window: geometry uploaded and shader compiled again");
  Check(Difference(Grab(win2), traced) == 0.0, "new window: the same traced image");
  NoGLError(win2, "lifecycle");
  NoVTKOutput("lifecycle");
}

void TestApp()
{
  if (AppPath.empty())
  {
    Check(false, "app: path of vtkrt-render given on the command line");
    return;
  }
  const std::string tmp = VTKRT_TEMP_DIR;
  // A file the app reads: a sphere and a cone in one PLY.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(20);
  vtkNew<vtkPLYWriter> writer;
  writer->SetInputConnection(sphere->GetOutputPort());
  const std::string ply = tmp + "/pass_app_sphere.ply";
  writer->SetFileName(ply.c_str());
  writer->Write();
  const std::pair<std::string, std::string> inputs[] = { { "demo", "--demo" }, { "file", "'" + ply + "'" } };
  for (const auto& input : inputs)
  {
    vtkSmartPointer<vtkImageData> images[2];
    const char* modes[2] = { "raster", "raytrace" };
    for (int m = 0; m < 2; ++m)
    {
      const std::string out = tmp + "/pass_app_" + input.first + "_" + modes[m] + ".png";
      const std::string cmd = "'" + AppPath + "' " + input.second + " --mode " + modes[m] +
        " --size 200x160 --frames 2 --output '" + out + "' > '" + out + ".log' 2>&1";
      const int rc = std::system(cmd.c_str());
      Check(rc == 0, "app " + input.first + " --mode " + modes[m] + ": exit status 0");
      vtkNew<vtkPNGReader> reader;
      reader->SetFileName(out.c_str());
      reader->Update();
      images[m] = vtkSmartPointer<vtkImageData>::New();
      images[m]->DeepCopy(reader->GetOutput());
    }
    const double error = Difference(images[1], images[0]);
    const long differing = CountDifferingPixels(images[1], images[0], 24);
    std::ostringstream s;
    s << "app " << input.first << ": raytrace vs raster error " << error << " <= 40, " << differing
      << " pixels differ (<= 3%)";
    Check(error <= 40.0 && differing >= 0 && differing <= 200 * 160 * 3 / 100, s.str());
  }
  NoVTKOutput("app");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Counters", TestCounters },
    { "FarFromOrigin", TestFarFromOrigin },
    { "Degenerate", TestDegenerate },
    { "TooLarge", TestTooLarge },
    { "SphereSilhouettes", TestSphereSilhouettes },
    { "IdPick", TestIdPick },
    { "ManyActors", TestManyActors },
    { "Classification", TestClassification },
    { "Lifecycle", TestLifecycle },
    { "App", TestApp },
  };
  if (argc > 2)
  {
    AppPath = argv[2];
  }
  return RunCase(argc, argv, cases, " [vtkrt-render]");
}
