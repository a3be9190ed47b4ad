// vtkGlyph3DMapper over a composite input (what ParaView's 3D Glyphs feed it):
// a vtkMultiBlockDataSet of point clouds (one leaf in a nested block, one
// null block, one empty polydata, one leaf hidden through the mapper's block
// attributes, one with a block color) glyphed with a vtkSphereSource scaled
// by a "radius" point array. Asserts that
//   - the actor is traced: one instance per visible non-empty leaf, as many
//     analytic spheres as visible points;
//   - unlit white silhouettes match the analytic mask of the visible
//     spheres (0 mismatches beyond 1/100 px) and VTK's raster silhouettes
//     (differences only on the rims of the tessellated raster spheres);
//     the hidden leaf's spheres are drawn by neither;
//   - shaded (scalar colors on one leaf, a block color on another), the
//     traced image is close to VTK's raster;
//   - id mode reports (prop 0, the point id within its leaf);
//   - a camera move builds and uploads nothing; showing the hidden leaf
//     builds only it, hiding it again builds nothing and drops its entry
//     (showing it once more builds it again);
//   - the same leaves in a vtkPartitionedDataSetCollection trace the same
//     image.
// TestRayTracePassCompositeGlyphs <Case>.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Sphere.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

using namespace vtkrtPassTest;

namespace
{
const double kBlack[3] = { 0, 0, 0 };
constexpr int kWidth = 300;
constexpr int kHeight = 220;

using Sphere = std::array<double, 4>; // x, y, z, radius

/// A point cloud with a "radius" array (and a "value" array as active
/// scalars when `scalars`).
vtkSmartPointer<vtkPolyData> Cloud(const std::vector<Sphere>& spheres, bool scalars)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  vtkNew<vtkDoubleArray> value;
  value->SetName("value");
  for (std::size_t i = 0; i < spheres.size(); ++i)
  {
    points->InsertNextPoint(spheres[i][0], spheres[i][1], spheres[i][2]);
    radius->InsertNextValue(spheres[i][3]);
    value->InsertNextValue(static_cast<double>(i) / static_cast<double>(spheres.size() - 1));
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->GetPointData()->AddArray(radius);
  if (scalars)
  {
    poly->GetPointData()->SetScalars(value);
  }
  return poly;
}

/// Three rows of spheres that never overlap on screen: A (top, scalar
/// colors), B (middle, hidden by block visibility), C (bottom, in a nested
/// block, with a block color).
struct Scene
{
  std::vector<Sphere> A = { { -2.0, 1.0, 0.0, 0.30 }, { -1.2, 1.0, -0.5, 0.25 },
    { -0.4, 1.0, 0.4, 0.35 }, { 0.4, 1.0, -1.0, 0.30 }, { 1.2, 1.0, 0.2, 0.20 },
    { 2.0, 1.0, -0.3, 0.32 } };
  std::vector<Sphere> B = { { -1.8, 0.0, 0.0, 0.30 }, { -0.9, 0.0, 0.3, 0.30 },
    { 0.0, 0.0, -0.4, 0.30 }, { 0.9, 0.0, 0.1, 0.30 }, { 1.8, 0.0, 0.0, 0.30 } };
  std::vector<Sphere> C = { { -1.5, -1.0, 0.2, 0.40 }, { -0.5, -1.0, -0.6, 0.25 },
    { 0.5, -1.0, 0.5, 0.33 }, { 1.5, -1.0, 0.0, 0.28 } };
  vtkSmartPointer<vtkPolyData> LeafA = Cloud(A, true);
  vtkSmartPointer<vtkPolyData> LeafB = Cloud(B, false);
  vtkSmartPointer<vtkPolyData> LeafC = Cloud(C, false);
  vtkNew<vtkPolyData> Empty;
  vtkNew<vtkMultiBlockDataSet> Blocks;
  vtkNew<vtkSphereSource> Source;
  vtkNew<vtkGlyph3DMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window = MakeWindow(kWidth, kHeight);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRayTracePass> Pass;

  Scene()
  {
    vtkNew<vtkMultiBlockDataSet> nested;
    nested->SetNumberOfBlocks(1);
    nested->SetBlock(0, this->LeafC);
    this->Blocks->SetNumberOfBlocks(5);
    this->Blocks->SetBlock(0, this->LeafA);
    this->Blocks->SetBlock(1, nullptr);
    this->Blocks->SetBlock(2, this->LeafB);
    this->Blocks->SetBlock(3, this->Empty);
    this->Blocks->SetBlock(4, nested);
    this->Source->SetRadius(1.0);
    this->Source->SetThetaResolution(48);
    this->Source->SetPhiResolution(48);
    this->Mapper->SetInputDataObject(this->Blocks);
    this->Mapper->SetSourceConnection(this->Source->GetOutputPort());
    this->Mapper->SetScaleArray("radius");
    this->Mapper->SetScaleModeToScaleByMagnitude();
    this->Mapper->SetScalarRange(0.0, 1.0);
    vtkNew<vtkCompositeDataDisplayAttributes> attributes;
    attributes->SetBlockVisibility(this->LeafB, false);
    attributes->SetBlockColor(this->LeafC, std::array<double, 3>{ { 0.2, 0.8, 0.3 } }.data());
    this->Mapper->SetBlockAttributes(attributes);
    this->Actor->SetMapper(this->Mapper);
    this->Actor->GetProperty()->SetColor(0.9, 0.6, 0.4);
    this->Actor->GetProperty()->SetSpecular(0.3);
    this->Actor->GetProperty()->SetSpecularPower(30);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AddActor(this->Actor);
    this->Window->AddRenderer(this->Renderer);
    vtkCamera* cam = this->Renderer->GetActiveCamera();
    cam->SetPosition(0.3, 0.4, 8.0);
    cam->SetFocalPoint(0, 0, 0);
    cam->SetViewUp(0, 1, 0);
    cam->SetViewAngle(35);
    cam->SetClippingRange(3, 14);
  }

  vtkCompositeDataDisplayAttributes* Attributes() { return this->Mapper->GetBlockAttributes(); }

  void Unlit(bool unlit)
  {
    vtkProperty* p = this->Actor->GetProperty();
    p->SetLighting(!unlit);
    if (unlit)
    {
      p->SetColor(1, 1, 1);
    }
    else
    {
      p->SetColor(0.9, 0.6, 0.4);
    }
    this->Mapper->SetScalarVisibility(!unlit);
    if (unlit)
    {
      this->Attributes()->RemoveBlockColor(this->LeafC);
    }
    else
    {
      this->Attributes()->SetBlockColor(
        this->LeafC, std::array<double, 3>{ { 0.2, 0.8, 0.3 } }.data());
    }
  }

  vtkSmartPointer<vtkImageData> Render(bool traced, bool rgba = false)
  {
    this->Renderer->SetPass(traced ? this->Pass.GetPointer() : nullptr);
    this->Window->Render();
    return Grab(this->Window, rgba);
  }
};

/// Per pixel of the current view: whether its ray hits one of `spheres`,
/// and its distance (in pixels) from the nearest silhouette.
struct AnalyticMask
{
  std::vector<char> Inside;
  std::vector<double> Margin;
  std::vector<int> Nearest; ///< index of the nearest sphere hit, -1: none

  AnalyticMask(vtkRenderer* ren, const std::vector<Sphere>& spheres)
  {
    PixelRays rays(ren, kWidth, kHeight);
    const double pixelAngle =
      2.0 * std::tan(vtkMath::RadiansFromDegrees(ren->GetActiveCamera()->GetViewAngle() / 2.0)) /
      kHeight;
    for (int j = 0; j < kHeight; ++j)
    {
      for (int i = 0; i < kWidth; ++i)
      {
        const auto ray = rays.Ray(i, j);
        bool inside = false;
        int nearest = -1;
        double tNearest = std::numeric_limits<double>::infinity();
        double margin = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < spheres.size(); ++k)
        {
          const Sphere& s = spheres[k];
          const vtkrt::core::Vec3<double> c(s[0], s[1], s[2]);
          double t;
          if (vtkrt::core::intersectRaySphere(ray, c, s[3], t))
          {
            inside = true;
            if (t < tNearest)
            {
              tNearest = t;
              nearest = static_cast<int>(k);
            }
          }
          const vtkrt::core::Vec3<double> d = glm::normalize(ray.dir);
          const vtkrt::core::Vec3<double> f = c - ray.org;
          const double distance = glm::length(f - glm::dot(f, d) * d);
          margin = std::min(margin, std::abs(distance - s[3]) / (pixelAngle * glm::length(f)));
        }
        this->Inside.push_back(inside ? 1 : 0);
        this->Margin.push_back(margin);
        this->Nearest.push_back(nearest);
      }
    }
  }
};

bool Lit(vtkImageData* image, std::size_t k)
{
  return static_cast<const unsigned char*>(image->GetScalarPointer())[3 * k] > 127;
}

std::vector<Sphere> Concat(const std::vector<Sphere>& a, const std::vector<Sphere>& b)
{
  std::vector<Sphere> out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

void TestMultiBlock()
{
  Scene scene;
  const std::vector<Sphere> visible = Concat(scene.A, scene.C);
  const vtkIdType visiblePoints = static_cast<vtkIdType>(visible.size());

  // Shaded: scalar colors on A, the block color on C.
  auto rasterShaded = scene.Render(false);
  auto tracedShaded = scene.Render(true);
  {
    std::ostringstream s;
    s << "traced props " << scene.Pass->GetNumberOfTracedProps() << " (want 1), instances "
      << scene.Pass->GetLastTracedInstances() << " (want 2: A, C), spheres "
      << scene.Pass->GetLastTracedPrimitives() << " (want " << visiblePoints << ")";
    Check(scene.Pass->GetNumberOfTracedProps() == 1 && scene.Pass->GetLastTracedInstances() == 2 &&
        scene.Pass->GetLastTracedPrimitives() == visiblePoints,
      s.str());
  }
  const double error = Difference(tracedShaded, rasterShaded);
  const long differing = CountDifferingPixels(tracedShaded, rasterShaded, 24);
  const long foreground = CountForegroundPixels(rasterShaded, kBlack);
  {
    std::ostringstream s;
    s << "shaded (scalar colors, block color): traced vs raster error " << error
      << " (want <= 5), " << differing << " pixels differ by > 24 (want <= 2% of the "
      << foreground << " foreground pixels)";
    const bool ok = foreground > 2000 && error <= 5.0 && differing <= foreground / 50;
    Check(ok, s.str());
    if (!ok)
    {
      WritePNG(rasterShaded, std::string(VTKRT_TEMP_DIR) + "/pass_CompositeGlyphs.raster.png");
      WritePNG(tracedShaded, std::string(VTKRT_TEMP_DIR) + "/pass_CompositeGlyphs.traced.png");
    }
  }

  // Unlit white silhouettes against the analytic mask of A and C, and
  // against VTK's raster; B's spheres drawn by neither.
  scene.Unlit(true);
  auto raster = scene.Render(false);
  auto traced = scene.Render(true);
  const AnalyticMask mask(scene.Renderer, visible);
  const AnalyticMask hidden(scene.Renderer, scene.B);
  long covered = 0, mismatches = 0, tolerated = 0, rasterDiffer = 0, rasterRim = 0;
  long hiddenPixels = 0, hiddenTraced = 0, hiddenRaster = 0;
  for (std::size_t k = 0; k < mask.Inside.size(); ++k)
  {
    const bool lit = Lit(traced, k);
    covered += lit ? 1 : 0;
    if (lit != static_cast<bool>(mask.Inside[k]))
    {
      (mask.Margin[k] < 0.01 ? tolerated : mismatches) += 1;
    }
    if (lit != Lit(raster, k))
    {
      // Raster draws 48x48 polygons: they differ from the sphere within
      // about a pixel of its silhouette.
      (mask.Margin[k] < 1.5 ? rasterRim : rasterDiffer) += 1;
    }
    if (hidden.Inside[k] && !mask.Inside[k] && hidden.Margin[k] > 1.0)
    {
      ++hiddenPixels;
      hiddenTraced += lit ? 1 : 0;
      hiddenRaster += Lit(raster, k) ? 1 : 0;
    }
  }
  {
    std::ostringstream s;
    s << "silhouettes: " << covered << " covered px, " << mismatches
      << " mismatches with the analytic mask of the visible leaves (want 0), " << tolerated
      << " within 0.01 px";
    Check(covered > 2000 && mismatches == 0, s.str());
    std::ostringstream r;
    r << "silhouettes vs raster: " << rasterDiffer << " pixels differ away from the rims (want 0), "
      << rasterRim << " on rims (want <= 3% of " << covered << ")";
    Check(rasterDiffer == 0 && rasterRim <= covered * 3 / 100, r.str());
    std::ostringstream h;
    h << "hidden leaf B: " << hiddenPixels << " px inside its spheres only, lit: traced "
      << hiddenTraced << ", raster " << hiddenRaster << " (want 0, 0)";
    Check(hiddenPixels > 500 && hiddenTraced == 0 && hiddenRaster == 0, h.str());
  }

  // Id mode: (prop 0, the point id within its leaf) for the nearest sphere.
  scene.Pass->IdModeOn();
  auto ids = scene.Render(true, true);
  scene.Pass->IdModeOff();
  {
    const auto* px = static_cast<const unsigned char*>(ids->GetScalarPointer());
    long checked = 0, wrong = 0;
    for (std::size_t k = 0; k < mask.Inside.size(); ++k)
    {
      if (mask.Margin[k] < 0.5)
      {
        continue;
      }
      int prop = -1;
      vtkIdType id = -1;
      const bool hit = vtkRayTracePass::DecodeId(px + 4 * k, prop, id);
      const int n = mask.Nearest[k];
      const vtkIdType want = n < 0 ? -1
        : (n < static_cast<int>(scene.A.size()) ? n : n - static_cast<int>(scene.A.size()));
      ++checked;
      wrong += (hit != (n >= 0) || (hit && (prop != 0 || id != want))) ? 1 : 0;
    }
    std::ostringstream s;
    s << "id mode: " << checked << " pixels away from silhouettes, " << wrong
      << " not (prop 0, point id within the leaf) of the analytic nearest (want 0)";
    Check(checked > kWidth * kHeight / 2 && wrong == 0, s.str());
  }

  // Camera move: nothing built or uploaded.
  scene.Renderer->GetActiveCamera()->Azimuth(25);
  scene.Renderer->GetActiveCamera()->SetClippingRange(3, 14);
  scene.Render(true);
  {
    std::ostringstream s;
    s << "camera move: " << scene.Pass->GetLastBVHBuilds() << " BVH builds, "
      << scene.Pass->GetLastGeometryBytesUploaded() << " geometry bytes uploaded (want 0, 0), "
      << scene.Pass->GetLastTracedInstances() << " instances (want 2)";
    Check(scene.Pass->GetLastBVHBuilds() == 0 && scene.Pass->GetLastGeometryBytesUploaded() == 0 &&
        scene.Pass->GetLastTracedInstances() == 2,
      s.str());
  }

  // Block visibility toggles: only B is built; hidden again, its entry is
  // dropped (nothing built), so showing it once more builds it again.
  const int steps[3][3] = { { 1, 1, 3 }, { 0, 0, 2 }, { 1, 1, 3 } }; // visible, builds, instances
  const char* names[3] = { "show B", "hide B", "show B again" };
  for (int k = 0; k < 3; ++k)
  {
    scene.Attributes()->SetBlockVisibility(scene.LeafB, steps[k][0] != 0);
    scene.Render(true);
    const vtkIdType points = visiblePoints + (steps[k][0] ? static_cast<vtkIdType>(scene.B.size()) : 0);
    std::ostringstream s;
    s << names[k] << ": " << scene.Pass->GetLastBVHBuilds() << " BVH builds (want " << steps[k][1]
      << "), " << scene.Pass->GetLastTracedInstances() << " instances (want " << steps[k][2]
      << "), " << scene.Pass->GetLastTracedPrimitives() << " spheres (want " << points << ")";
    Check(scene.Pass->GetLastBVHBuilds() == steps[k][1] &&
        scene.Pass->GetLastTracedInstances() == steps[k][2] &&
        scene.Pass->GetLastTracedPrimitives() == points,
      s.str());
  }
  NoVTKOutput("composite glyphs");
}

void TestPartitioned()
{
  // The same leaves as partitions of a vtkPartitionedDataSetCollection
  // (B hidden by its block visibility): the same image as the multiblock.
  Scene scene;
  scene.Unlit(true);
  auto reference = scene.Render(true);
  vtkNew<vtkPartitionedDataSet> first;
  first->SetNumberOfPartitions(3);
  first->SetPartition(0, scene.LeafA);
  first->SetPartition(1, scene.Empty);
  first->SetPartition(2, scene.LeafB);
  vtkNew<vtkPartitionedDataSet> second;
  second->SetNumberOfPartitions(1);
  second->SetPartition(0, scene.LeafC);
  vtkNew<vtkPartitionedDataSetCollection> collection;
  collection->SetNumberOfPartitionedDataSets(2);
  collection->SetPartitionedDataSet(0, first);
  collection->SetPartitionedDataSet(1, second);
  scene.Mapper->SetInputDataObject(collection);
  auto traced = scene.Render(true);
  const long differing = CountDifferingPixels(traced, reference, 0);
  std::ostringstream s;
  s << "vtkPartitionedDataSetCollection: " << scene.Pass->GetLastTracedInstances()
    << " instances (want 2), " << scene.Pass->GetLastTracedPrimitives() << " spheres (want "
    << scene.A.size() + scene.C.size() << "), " << differing
    << " pixels differ from the multiblock image (want 0)";
  Check(scene.Pass->GetLastTracedInstances() == 2 &&
      scene.Pass->GetLastTracedPrimitives() == static_cast<vtkIdType>(scene.A.size() + scene.C.size()) &&
      CountForegroundPixels(traced, kBlack) > 2000 && differing == 0,
    s.str());
  NoVTKOutput("partitioned glyphs");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(
    argc, argv, { { "MultiBlock", TestMultiBlock }, { "Partitioned", TestPartitioned } });
}
