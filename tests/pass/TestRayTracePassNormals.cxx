// Normals as VTK 9.1's vtkOpenGLPolyDataMapper shades with them: interpolated
// point normals, cell normals (one per VTK cell, also over every triangle of
// a non-planar polygon or a strip), no normals (each triangle's geometric
// normal turned to the viewer), and flat interpolation (cell normals when
// there are some, else the geometric ones). Each case compares the traced
// image with VTK's raster of the same scene: non-planar quads, strips,
// inside and outside of an open tube, an actor scale and a mirroring one
// (whose turned winding makes raster flip its normals: it shades dark),
// under the headlight, then with off-axis scene lights added; the specular
// term, compiled only where a surface has one.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSuperquadricSource.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
constexpr int kSize = 300;
constexpr double kMaximumRMSE = 2.0;

/// An open tube (three quarters of a turn) of quads whose corners
/// alternate in and out radially: every quad is non-planar, so its fan
/// triangles' normals differ from the polygon's. No normals.
vtkSmartPointer<vtkPolyData> BumpyTube()
{
  constexpr int around = 18;
  constexpr int along = 6;
  vtkNew<vtkPoints> points;
  for (int j = 0; j <= along; ++j)
  {
    for (int i = 0; i <= around; ++i)
    {
      const double angle = vtkMath::Pi() * (1.5 * i / around - 0.25);
      const double radius = 1.0 + ((i + j) % 2 ? 0.07 : -0.07);
      points->InsertNextPoint(
        radius * std::cos(angle), radius * std::sin(angle), 2.0 * j / along - 1.0);
    }
  }
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j < along; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const vtkIdType first = j * (around + 1) + i;
      const vtkIdType quad[4] = { first, first + 1, first + around + 2, first + around + 1 };
      quads->InsertNextCell(4, quad);
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(quads);
  return poly;
}

/// `poly` with the normals vtkPolyDataNormals computes (no splitting, so
/// the points stay those of `poly`).
vtkSmartPointer<vtkPolyData> WithComputedNormals(
  vtkPolyData* poly, bool pointNormals, bool cellNormals)
{
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(poly);
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->SetComputePointNormals(pointNormals);
  normals->SetComputeCellNormals(cellNormals);
  normals->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(normals->GetOutput());
  return out;
}

/// A boxy superquadric of triangle strips, with the source's point normals
/// and, as cell normals, each strip's mean point normal (far from most of
/// its triangles' geometric normals), as asked for.
vtkSmartPointer<vtkPolyData> Superquadric(bool pointNormals, bool cellNormals)
{
  vtkNew<vtkSuperquadricSource> source;
  source->SetThetaResolution(12);
  source->SetPhiResolution(8);
  source->SetThetaRoundness(0.4);
  source->SetPhiRoundness(0.6);
  source->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(source->GetOutput());
  vtkDataArray* pointNormalArray = poly->GetPointData()->GetNormals();
  if (cellNormals)
  {
    vtkNew<vtkFloatArray> strips;
    strips->SetName("StripNormals");
    strips->SetNumberOfComponents(3);
    vtkIdType npts;
    const vtkIdType* pts;
    for (poly->GetStrips()->InitTraversal(); poly->GetStrips()->GetNextCell(npts, pts);)
    {
      double mean[3] = { 0.0, 0.0, 0.0 };
      for (vtkIdType k = 0; k < npts; ++k)
      {
        const double* n = pointNormalArray->GetTuple3(pts[k]);
        vtkMath::Add(mean, n, mean);
      }
      vtkMath::Normalize(mean);
      strips->InsertNextTuple(mean);
    }
    poly->GetCellData()->SetNormals(strips);
  }
  poly->GetPointData()->SetTCoords(nullptr);
  if (!pointNormals)
  {
    poly->GetPointData()->SetNormals(nullptr);
  }
  return poly;
}

/// The tube and the superquadric with the normals asked for.
struct Meshes
{
  vtkSmartPointer<vtkPolyData> Tube;
  vtkSmartPointer<vtkPolyData> Superquadric;
};

Meshes MakeMeshes(bool pointNormals, bool cellNormals)
{
  Meshes m;
  m.Tube = pointNormals || cellNormals ? WithComputedNormals(BumpyTube(), pointNormals, cellNormals)
                                       : BumpyTube();
  m.Superquadric = Superquadric(pointNormals, cellNormals);
  for (vtkPolyData* poly : { m.Tube.Get(), m.Superquadric.Get() })
  {
    const bool hasPoint = poly->GetPointData()->GetNormals() != nullptr;
    const bool hasCell = poly->GetCellData()->GetNormals() != nullptr;
    Check(hasPoint == pointNormals && hasCell == cellNormals,
      std::string("the mesh has ") + (pointNormals ? "point normals" : "no point normals") +
        " and " + (cellNormals ? "cell normals" : "no cell normals"));
  }
  return m;
}

vtkSmartPointer<vtkActor> AddActor(vtkRenderer* ren, vtkPolyData* poly, int interpolation)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.75, 0.5);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(15);
  actor->GetProperty()->SetInterpolation(interpolation);
  ren->AddActor(actor);
  return actor;
}

/// Writes raster, traced and their difference (x4, RGB) to the test's
/// temporary directory.
void WriteComparison(const std::string& name, vtkImageData* raster, vtkImageData* traced)
{
  const std::string base = std::string(VTKRT_TEMP_DIR) + "/pass_Normals" + name;
  WritePNG(raster, base + ".raster.png");
  WritePNG(traced, base + ".traced.png");
  vtkNew<vtkImageData> diff;
  diff->SetDimensions(raster->GetDimensions());
  diff->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  const int cr = raster->GetNumberOfScalarComponents();
  const int ct = traced->GetNumberOfScalarComponents();
  const auto* pr = static_cast<const unsigned char*>(raster->GetScalarPointer());
  const auto* pt = static_cast<const unsigned char*>(traced->GetScalarPointer());
  auto* pd = static_cast<unsigned char*>(diff->GetScalarPointer());
  for (vtkIdType i = 0; i < diff->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int d = std::abs(int(pr[i * cr + c]) - int(pt[i * ct + c]));
      pd[3 * i + c] = static_cast<unsigned char>(std::min(255, 4 * d));
    }
  }
  WritePNG(diff, base + ".diff.png");
  std::cout << "  wrote " << base << ".{raster,traced,diff}.png\n";
}

/// Renders the tube (at the origin) and the superquadric twice (scaled,
/// and mirrored) in raster and traced, under the headlight and then with
/// two off-axis scene lights added, and compares each pair.
void CompareWithRaster(const std::string& name, const Meshes& meshes, int interpolation)
{
  const bool cellNormals = meshes.Tube->GetCellData()->GetNormals() &&
    (interpolation == VTK_FLAT || !meshes.Tube->GetPointData()->GetNormals());
  auto win = MakeWindow(kSize, kSize);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.1, 0.1, 0.15);
  AddActor(ren, meshes.Tube, interpolation);
  auto scaled = AddActor(ren, meshes.Superquadric, interpolation);
  scaled->SetPosition(1.9, 0.6, 0.3);
  scaled->SetScale(0.8, 1.1, 0.6);
  scaled->RotateX(35);
  auto mirrored = AddActor(ren, meshes.Superquadric, interpolation);
  mirrored->SetPosition(-1.7, -0.9, -0.2);
  mirrored->SetScale(-0.7, 0.7, 0.9);
  mirrored->RotateY(-25);
  vtkCamera* camera = ren->GetActiveCamera();
  camera->SetFocalPoint(0.1, 0.0, 0.0);
  camera->SetPosition(2.0, -3.3, 1.9);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(55);
  ren->ResetCameraClippingRange();

  for (const bool sceneLights : { false, true })
  {
    const std::string label = name + (sceneLights ? "SceneLights" : "Headlight");
    if (sceneLights)
    {
      vtkNew<vtkLight> side;
      side->SetLightTypeToSceneLight();
      side->SetPosition(-3.0, -1.0, 1.0);
      side->SetFocalPoint(0.0, 0.0, 0.0);
      side->SetIntensity(0.8);
      ren->AddLight(side);
      vtkNew<vtkLight> above;
      above->SetLightTypeToSceneLight();
      above->SetPosition(1.0, 2.0, 4.0);
      above->SetFocalPoint(0.0, 0.0, 0.0);
      above->SetIntensity(0.6);
      ren->AddLight(above);
    }
    ren->SetPass(nullptr);
    auto [raster, traced, pass] = RenderRasterThenTraced(win, ren);
    const double rmse = RootMeanSquareError(traced, raster);
    const long foreground = CountForegroundPixels(raster, ren->GetBackground());
    const long differing = CountDifferingPixels(traced, raster, 24);
    std::ostringstream what;
    what << label << ": " << pass->GetLastTracedInstances() << " instances traced (3), RGB RMSE "
         << rmse << " <= " << kMaximumRMSE << " against raster, " << differing
         << " pixels differ by > 24 (<= 0.1% of the " << foreground
         << " foreground pixels, >= 25% of the image)";
    const bool ok = pass->GetLastTracedInstances() == 3 &&
      rmse <= kMaximumRMSE && differing >= 0 && differing <= foreground / 1000 &&
      foreground >= kSize * kSize / 4;
    Check(ok, what.str());
    if (!ok)
    {
      WriteComparison(label, raster, traced);
    }
    // The cell normal branch is compiled only for scenes that use it.
    const std::string key = pass->GetLastFeatureKey();
    Check(key.find(cellNormals ? "F1" : "F0") != std::string::npos,
      label + ": the shader has the cell normal code " + (cellNormals ? "(F1)" : "not (F0)") +
        ", key " + key);
  }
  NoVTKOutput(name);
}

// Cell normals only: each triangle takes its cell's normal (non-planar
// quads, strips), flipped on back faces (the tube's inside).
void TestCellNormals()
{
  CompareWithRaster("Cells", MakeMeshes(false, true), VTK_GOURAUD);
}

// Point normals, interpolated (Gouraud and Phong shade alike in VTK 9.1).
void TestPointNormals()
{
  const Meshes meshes = MakeMeshes(true, false);
  CompareWithRaster("PointsGouraud", meshes, VTK_GOURAUD);
  CompareWithRaster("PointsPhong", meshes, VTK_PHONG);
}

// No normals: the geometric normal facing the viewer.
void TestNoNormals()
{
  CompareWithRaster("None", MakeMeshes(false, false), VTK_GOURAUD);
}

// Flat interpolation ignores point normals: the geometric normal, or the
// cell normals when the data also has them.
void TestFlatInterpolation()
{
  CompareWithRaster("FlatPoints", MakeMeshes(true, false), VTK_FLAT);
  CompareWithRaster("FlatPointsAndCells", MakeMeshes(true, true), VTK_FLAT);
}

// Normals longer than the points or cells (a tuple appended): raster reads
// the first ones by point or cell id, and so does the pass.
void TestLongerArrays()
{
  auto lengthen = [](Meshes m) {
    for (vtkPolyData* poly : { m.Tube.Get(), m.Superquadric.Get() })
    {
      for (vtkDataArray* normals : { poly->GetPointData()->GetNormals(), poly->GetCellData()->GetNormals() })
      {
        if (normals)
        {
          normals->InsertNextTuple3(0.0, 0.0, 1.0);
        }
      }
    }
    return m;
  };
  CompareWithRaster("LongerPointNormals", lengthen(MakeMeshes(true, false)), VTK_GOURAUD);
  CompareWithRaster("LongerCellNormals", lengthen(MakeMeshes(false, true)), VTK_GOURAUD);
}
// The specular term is compiled only for scenes with a specular color
// (VTKRT_SPECULAR): a ball with VTK's default Specular 0 has none, one with
// Specular 0.6 gets its highlight, under the headlight and under two scene
// lights, each as raster draws it.
void TestSpecular()
{
  auto win = MakeWindow(240, 200);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  auto actor = SphereActor(0.0, 0.0, 0.0, 0.5, 64);
  actor->GetProperty()->SetColor(0.3, 0.5, 0.9);
  actor->GetProperty()->SetSpecularPower(30.0);
  ren->AddActor(actor);
  ren->ResetCamera();
  const std::string define = "#define VTKRT_SPECULAR\n";
  const auto check = [&](const std::string& label, bool specular) {
    RasterAndTraced frames = CompareBlurred(win, ren, label, 1, 4.0, "Specular_" + label);
    const bool has = std::string(frames.Pass->GetLastFragmentShaderSource()).find(define) != std::string::npos;
    Check(has == specular, label + (specular ? ": the shader has" : ": the shader has no") + " specular term");
    ren->SetPass(nullptr);
    return frames.Traced;
  };
  auto dull = check("headlight, Specular 0", false);
  actor->GetProperty()->SetSpecular(0.6);
  auto shiny = check("headlight, Specular 0.6", true);
  const long lit = CountDifferingPixels(dull, shiny, 16);
  Check(lit > 100, "the highlight changes " + std::to_string(lit) + " pixels by more than 16 levels");
  vtkNew<vtkLight> key;
  key->SetPosition(2.0, 3.0, 4.0);
  key->SetFocalPoint(0.0, 0.0, 0.0);
  vtkNew<vtkLight> fill;
  fill->SetPosition(-3.0, 1.0, 2.0);
  fill->SetFocalPoint(0.0, 0.0, 0.0);
  fill->SetIntensity(0.5);
  ren->AddLight(key);
  ren->AddLight(fill);
  check("two scene lights, Specular 0.6", true);
  actor->GetProperty()->SetSpecular(0.0);
  check("two scene lights, Specular 0", false);
  NoVTKOutput("Specular");
}

} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  return RunCase(argc, argv,
    { { "Cells", TestCellNormals }, { "Points", TestPointNormals }, { "None", TestNoNormals },
      { "Flat", TestFlatInterpolation }, { "LongerArrays", TestLongerArrays },
      { "Specular", TestSpecular } });
}
