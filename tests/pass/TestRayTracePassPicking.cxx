// What vtkRayTracePass gives each pixel and each prop:
//   SphereSilhouettes analytic spheres against an analytic per-pixel mask
//   IdPick            id mode vs a CPU pick (core closest hit, double) along
//                     every pixel's ray, and vs vtkCellPicker
//   Classification    which props are traced and which are left to the
//                     raster delegate
// TestRayTracePassPicking <Case>.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkBVHCellLocator.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellPicker.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkConeSource.h"
#include "vtkDataArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkImageData.h"
#include "vtkLineSource.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTexture.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include "vtkrt/core/Core.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
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
  traced.emplace_back("translucent property", translucent);
  auto wire = meshActor(mesh);
  wire->GetProperty()->SetRepresentationToWireframe();
  traced.emplace_back("wireframe", wire);
  auto edges = meshActor(mesh);
  edges->GetProperty()->EdgeVisibilityOn();
  traced.emplace_back("edge visibility", edges);
  auto culledWire = meshActor(mesh);
  culledWire->GetProperty()->SetRepresentationToWireframe();
  culledWire->GetProperty()->BackfaceCullingOn();
  raster.emplace_back("culled wireframe (raster's lines are never culled)", culledWire);
  auto culled = meshActor(mesh);
  culled->GetProperty()->BackfaceCullingOn();
  traced.emplace_back("backface culling", culled);
  auto backProperty = meshActor(mesh);
  vtkNew<vtkProperty> back;
  backProperty->SetBackfaceProperty(back);
  traced.emplace_back("backface property", backProperty);
  auto translucentBack = meshActor(mesh);
  vtkNew<vtkProperty> translucentBackProperty;
  translucentBackProperty->SetOpacity(0.5);
  translucentBack->SetBackfaceProperty(translucentBackProperty);
  raster.emplace_back("translucent backface property", translucentBack);
  // An RGB texture on a mesh with texture coordinates; one moved by a
  // texture transform stays with raster.
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  std::fill_n(static_cast<unsigned char*>(image->GetScalarPointer()), 12, 200);
  vtkNew<vtkPlaneSource> plane;
  plane->Update();
  vtkNew<vtkTexture> texture;
  texture->SetInputData(image);
  auto textured = meshActor(plane->GetOutput());
  textured->SetTexture(texture);
  traced.emplace_back("texture", textured);
  vtkNew<vtkTexture> moved;
  moved->SetInputData(image);
  vtkNew<vtkTransform> shift;
  shift->Translate(0.5, 0.0, 0.0);
  moved->SetTransform(shift);
  auto transformed = meshActor(plane->GetOutput());
  transformed->SetTexture(moved);
  raster.emplace_back("texture transform", transformed);
  auto points = meshActor(mesh);
  points->GetProperty()->SetRepresentationToPoints();
  raster.emplace_back("points without RenderPointsAsSpheres", points);
  auto spheres = meshActor(mesh);
  spheres->GetProperty()->SetRepresentationToPoints();
  spheres->GetProperty()->RenderPointsAsSpheresOn();
  traced.emplace_back("points with RenderPointsAsSpheres", spheres);
  // Scalars with alpha make the actor translucent in VTK (traced too).
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
  traced.emplace_back("scalars with alpha", alpha);
  // Plain lines are raster's: a stand-in draws them beside the traced
  // surface; with nothing else the whole actor is raster's.
  vtkNew<vtkConeSource> cone;
  cone->Update();
  auto withLines = vtkSmartPointer<vtkPolyData>::New();
  withLines->DeepCopy(cone->GetOutput());
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  withLines->SetLines(lines);
  traced.emplace_back("polydata with plain lines (a raster stand-in draws them)", meshActor(withLines));
  auto linesOnlyData = vtkSmartPointer<vtkPolyData>::New();
  linesOnlyData->SetPoints(withLines->GetPoints());
  linesOnlyData->SetLines(lines);
  raster.emplace_back("polydata of plain lines alone", meshActor(linesOnlyData));
  // Properties that only matter for cells the data has (vedo sets
  // RenderPointsAsSpheres and edges on every actor): a translucent surface
  // with RenderPointsAsSpheres and no vertices, and a tube polyline with
  // edge visibility, are traced; translucent tubes and translucent points as
  // spheres (raster draws one layer of them), and polygon edges drawn as
  // tubes (raster's shaded fake tubes) stay with raster.
  auto translucentSpheresFlag = meshActor(mesh);
  translucentSpheresFlag->GetProperty()->SetOpacity(0.5);
  translucentSpheresFlag->GetProperty()->RenderPointsAsSpheresOn();
  traced.emplace_back("translucent surface with RenderPointsAsSpheres", translucentSpheresFlag);
  auto translucentPointSpheres = meshActor(mesh);
  translucentPointSpheres->GetProperty()->SetOpacity(0.5);
  translucentPointSpheres->GetProperty()->SetRepresentationToPoints();
  translucentPointSpheres->GetProperty()->RenderPointsAsSpheresOn();
  raster.emplace_back("translucent points as spheres", translucentPointSpheres);
  vtkNew<vtkLineSource> segment;
  segment->SetResolution(4);
  segment->Update();
  auto tubeActor = [&](double opacity, bool edgesOn) {
    auto actor = meshActor(segment->GetOutput());
    actor->GetProperty()->RenderLinesAsTubesOn();
    actor->GetProperty()->SetLineWidth(4.0f);
    actor->GetProperty()->SetOpacity(opacity);
    actor->GetProperty()->SetEdgeVisibility(edgesOn);
    return actor;
  };
  traced.emplace_back("tubes with edge visibility", tubeActor(1.0, true));
  raster.emplace_back("translucent tubes", tubeActor(0.5, false));
  auto tubeEdges = meshActor(mesh);
  tubeEdges->GetProperty()->EdgeVisibilityOn();
  tubeEdges->GetProperty()->RenderLinesAsTubesOn();
  tubeEdges->GetProperty()->SetLineWidth(4.0f);
  raster.emplace_back("polygon edges drawn as tubes", tubeEdges);
  auto tubeWires = meshActor(mesh);
  tubeWires->GetProperty()->SetRepresentationToWireframe();
  tubeWires->GetProperty()->RenderLinesAsTubesOn();
  tubeWires->GetProperty()->SetLineWidth(4.0f);
  raster.emplace_back("wireframe drawn as tubes", tubeWires);
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

  // Composites are traced, with opaque or translucent blocks.
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
    traced.emplace_back(translucentBlock ? "composite with a translucent block" : "composite", actor);
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
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "SphereSilhouettes", TestSphereSilhouettes },
    { "IdPick", TestIdPick },
    { "Classification", TestClassification },
  };
  return RunCase(argc, argv, cases);
}
