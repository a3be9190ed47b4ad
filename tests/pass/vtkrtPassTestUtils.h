// Helpers shared by the pass tests: headless windows, image capture,
// raster-vs-ray-traced comparison, common scene actors and GL error checks.
#ifndef vtkrtPassTestUtils_h
#define vtkrtPassTestUtils_h

#include "vtkrtCheck.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkrt/core/Ray.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtk_glew.h"

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace vtkrtPassTest
{
/// Failed checks of this test program, and the output window that counts
/// VTK errors and warnings (each test's main installs it).
using vtkrtTest::Check;
using vtkrtTest::Failures;
inline vtkrtTestOutputWindow* Output = nullptr;

/// Runs the case named by argv[1] and reports the failures; an unknown or
/// missing name prints the usage with the known cases.
inline int RunCase(int argc, char* argv[],
  const std::map<std::string, std::function<void()>>& cases, const std::string& extraArgs = "")
{
  auto it = cases.find(argc > 1 ? argv[1] : "");
  if (it == cases.end())
  {
    std::cerr << "usage: " << argv[0] << " <case>" << extraArgs << "; cases:";
    for (const auto& c : cases)
    {
      std::cerr << " " << c.first;
    }
    std::cerr << "\n";
    return EXIT_FAILURE;
  }
  it->second();
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}

inline void NoVTKOutput(const std::string& label)
{
  Check(Output->GetNumberOfErrors() == 0 && Output->GetNumberOfWarnings() == 0,
    label + ": no VTK error or warning");
  Output->Clear();
}

/// The world ray of pixel (i, j) of a w x h view (pixel centers, origin
/// bottom left) from VTK's composite projection, in double: org on the near
/// plane, org + dir on the far plane.
struct PixelRays
{
  vtkNew<vtkMatrix4x4> ClipToWorld;
  int Width, Height;
  PixelRays(vtkRenderer* ren, int w, int h)
    : Width(w)
    , Height(h)
  {
    vtkMatrix4x4* m = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
      static_cast<double>(w) / h, -1, 1);
    vtkMatrix4x4::Invert(m, this->ClipToWorld);
  }
  vtkrt::core::Ray<double> Ray(int i, int j) const
  {
    const double x = 2.0 * (i + 0.5) / this->Width - 1.0;
    const double y = 2.0 * (j + 0.5) / this->Height - 1.0;
    double n[4] = { x, y, -1.0, 1.0 };
    double f[4] = { x, y, 1.0, 1.0 };
    this->ClipToWorld->MultiplyPoint(n, n);
    this->ClipToWorld->MultiplyPoint(f, f);
    vtkrt::core::Vec3<double> o(n[0] / n[3], n[1] / n[3], n[2] / n[3]);
    vtkrt::core::Vec3<double> e(f[0] / f[3], f[1] / f[3], f[2] / f[3]);
    return vtkrt::core::Ray<double>(o, e - o, 0.0, 1.0);
  }
};

/// A polydata of data/ (read and shallow-copied: no reader kept alive).
inline vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& name)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((std::string(VTKRT_DATA_DIR) + "/" + name).c_str());
  reader->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(reader->GetOutput());
  return out;
}

inline vtkSmartPointer<vtkEGLHeadlessRenderWindow> MakeWindow(int w, int h)
{
  auto win = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  win->SetSize(w, h);
  win->SetMultiSamples(0);
  return win;
}

/// The window's current image (no re-render), RGB or RGBA.
inline vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* win, bool rgba = false)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  if (rgba)
  {
    grab->SetInputBufferTypeToRGBA();
  }
  else
  {
    grab->SetInputBufferTypeToRGB();
  }
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

/// vtkImageDifference's thresholded error between two images (the same
/// settings as the baseline harness: averaging, threshold 16).
inline double Difference(vtkImageData* a, vtkImageData* b)
{
  vtkNew<vtkImageDifference> diff;
  diff->SetInputData(a);
  diff->SetImageData(b);
  diff->SetThreshold(16);
  diff->AllowShiftOff();
  diff->AveragingOn();
  diff->Update();
  return diff->GetThresholdedError();
}

/// Pixels whose color differs by more than `tolerance` in some channel.
inline long CountDifferingPixels(vtkImageData* a, vtkImageData* b, int tolerance)
{
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    return -1;
  }
  const int ca = a->GetNumberOfScalarComponents();
  const int cb = b->GetNumberOfScalarComponents();
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  long count = 0;
  for (long i = 0; i < static_cast<long>(da[0]) * da[1]; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(int(pa[i * ca + c]) - int(pb[i * cb + c])) > tolerance)
      {
        ++count;
        break;
      }
    }
  }
  return count;
}

/// Pixels that are not the background color (exactly).
inline long CountForegroundPixels(vtkImageData* image, const double background[3])
{
  int d[3];
  image->GetDimensions(d);
  const int comps = image->GetNumberOfScalarComponents();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  long count = 0;
  for (long i = 0; i < static_cast<long>(d[0]) * d[1]; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(int(p[i * comps + c]) - int(background[c] * 255.0 + 0.5)) > 1)
      {
        ++count;
        break;
      }
    }
  }
  return count;
}

/// Pixels within 8/255 of the color `rgb` in every channel.
inline long CountColor(vtkImageData* image, const unsigned char rgb[3])
{
  int d[3];
  image->GetDimensions(d);
  const int comps = image->GetNumberOfScalarComponents();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  long count = 0;
  for (long i = 0; i < static_cast<long>(d[0]) * d[1]; ++i)
  {
    count += std::abs(p[i * comps] - rgb[0]) <= 8 && std::abs(p[i * comps + 1] - rgb[1]) <= 8 &&
      std::abs(p[i * comps + 2] - rgb[2]) <= 8;
  }
  return count;
}

/// Root mean square of the RGB differences (0-255 scale); infinite when the
/// sizes differ (so no bound accepts it).
inline double RootMeanSquareError(vtkImageData* a, vtkImageData* b)
{
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    return std::numeric_limits<double>::infinity();
  }
  const int ca = a->GetNumberOfScalarComponents();
  const int cb = b->GetNumberOfScalarComponents();
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  const long pixels = static_cast<long>(da[0]) * da[1];
  double sum = 0.0;
  for (long i = 0; i < pixels; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = double(pa[i * ca + c]) - double(pb[i * cb + c]);
      sum += d * d;
    }
  }
  return std::sqrt(sum / (3.0 * pixels));
}

inline void WritePNG(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}
/// Adds unlit white spheres ({x, y, z, radius} each) to `ren` as one
/// vtkGlyph3DMapper actor scaling a unit sphere by a "radius" point array,
/// the form the pass turns into analytic spheres.
template <std::size_t N>
inline void AddUnlitWhiteSphereGlyphs(vtkRenderer* ren, const double (&spheres)[N][4])
{
  vtkNew<vtkPolyData> centers;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  for (const auto& s : spheres)
  {
    points->InsertNextPoint(s[0], s[1], s[2]);
    radius->InsertNextValue(s[3]);
  }
  centers->SetPoints(points);
  centers->GetPointData()->AddArray(radius);
  vtkNew<vtkSphereSource> source;
  source->SetRadius(1.0);
  vtkNew<vtkGlyph3DMapper> mapper;
  mapper->SetInputData(centers);
  mapper->SetSourceConnection(source->GetOutputPort());
  mapper->SetScaleArray("radius");
  mapper->SetScaleModeToScaleByMagnitude();
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(1, 1, 1);
  ren->AddActor(actor);
}
/// A tessellated sphere's polydata (res x res), radius 0.5 about (cx, 0, 0).
inline vtkSmartPointer<vtkPolyData> Sphere(double cx, int res)
{
  vtkNew<vtkSphereSource> source;
  source->SetCenter(cx, 0.0, 0.0);
  source->SetRadius(0.5);
  source->SetThetaResolution(res);
  source->SetPhiResolution(res);
  source->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->DeepCopy(source->GetOutput());
  return poly;
}

/// A tessellated sphere actor (res x res), default material.
inline vtkSmartPointer<vtkActor> SphereActor(
  double x, double y, double z, double r, int res = 32)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(x, y, z);
  sphere->SetRadius(r);
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// The floor of the shadow scenes: the square [-half, half]^2 in y = 0,
/// ambient 0.1 so shadowed floor stays visible.
inline vtkSmartPointer<vtkActor> FloorActor(double half)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-half, 0.0, -half);
  plane->SetPoint1(half, 0.0, -half);
  plane->SetPoint2(-half, 0.0, half);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetAmbient(0.1);
  return actor;
}
/// One mesh of a sphere (res x res, radius 0.5 at (0, 0.8, 0)) and the floor
/// [-2, 2]^2 in y = 0 (floorRes x floorRes quads).
inline vtkSmartPointer<vtkPolyData> SphereOverFloor(int res, int floorRes)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.0, 0.8, 0.0);
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-2.0, 0.0, -2.0);
  floor->SetPoint1(2.0, 0.0, -2.0);
  floor->SetPoint2(-2.0, 0.0, 2.0);
  floor->SetResolution(floorRes, floorRes);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(sphere->GetOutputPort());
  both->AddInputConnection(floor->GetOutputPort());
  both->Update();
  return both->GetOutput();
}

/// A copy of `poly` with double points shifted by `offset` (computed in
/// double, so nothing is lost at 1e8).
inline vtkSmartPointer<vtkPolyData> Shifted(vtkPolyData* poly, const double offset[3])
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(poly->GetNumberOfPoints());
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i)
  {
    double p[3];
    poly->GetPoint(i, p);
    points->SetPoint(i, p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(poly);
  out->SetPoints(points);
  return out;
}

/// Checks that the window's context has no pending GL error (and clears
/// any, so that the next check starts clean).
inline void NoGLError(vtkRenderWindow* win, const std::string& label)
{
  win->MakeCurrent();
  GLenum error = glGetError();
  Check(error == GL_NO_ERROR, label + ": no GL error");
  while (error != GL_NO_ERROR)
  {
    error = glGetError();
  }
}

/// A mesh actor with a fixed specular material and no scalar colors.
inline vtkSmartPointer<vtkActor> MeshActor(vtkPolyData* poly)
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

/// Forty yellow vertices along a sine, from x0 in steps of dx at height z,
/// drawn as points of `pointSize` (raster draws them beside traced props).
inline vtkSmartPointer<vtkActor> PointCloudActor(double x0, double dx, double z, double pointSize)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  for (int i = 0; i < 40; ++i)
  {
    verts->InsertNextCell(1);
    verts->InsertCellPoint(points->InsertNextPoint(x0 + dx * i, 0.3 * std::sin(0.3 * i), z));
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  cloud->SetVerts(verts);
  vtkSmartPointer<vtkActor> dots = MeshActor(cloud);
  dots->GetProperty()->SetPointSize(pointSize);
  dots->GetProperty()->SetColor(1.0, 0.9, 0.1);
  return dots;
}

/// The cell ids a vtkHardwareSelector cell selection of the pixels
/// area = (x0, y0, x1, y1) returns, of every prop or of `prop` alone.
inline std::set<vtkIdType> SelectedCells(vtkRenderer* ren, const unsigned int area[4], vtkProp* prop = nullptr)
{
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(ren);
  selector->SetArea(area[0], area[1], area[2], area[3]);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  vtkSmartPointer<vtkSelection> result = vtk::TakeSmartPointer(selector->Select());
  std::set<vtkIdType> ids;
  for (unsigned int n = 0; result && n < result->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = result->GetNode(n);
    if (prop && node->GetProperties()->Get(vtkSelectionNode::PROP()) != prop)
    {
      continue;
    }
    vtkIdTypeArray* list = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    for (vtkIdType k = 0; list && k < list->GetNumberOfTuples(); ++k)
    {
      ids.insert(list->GetValue(k));
    }
  }
  return ids;
}

/// Sphere glyphs of `points` scaled by their "radius" array (x2) and
/// colored by their "scalar" array, as in data/demo-spheres.vtp.
inline vtkSmartPointer<vtkActor> GlyphActor(vtkPolyData* points)
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

/// One frame rendered in raster, then the same frame ray traced by a new
/// pass installed on `ren` (left installed, so the caller can query it).
struct RasterAndTraced
{
  vtkSmartPointer<vtkImageData> Raster;
  vtkSmartPointer<vtkImageData> Traced;
  vtkSmartPointer<vtkRayTracePass> Pass;
};

inline RasterAndTraced RenderRasterThenTraced(vtkRenderWindow* win, vtkRenderer* ren)
{
  RasterAndTraced frames;
  win->Render();
  frames.Raster = Grab(win);
  frames.Pass = vtkSmartPointer<vtkRayTracePass>::New();
  ren->SetPass(frames.Pass);
  win->Render();
  frames.Traced = Grab(win);
  return frames;
}

/// A copy of `image` blurred by a 2D Gaussian of 2 pixels (radius 6): what
/// one-pixel lines and silhouettes are compared after.
inline vtkSmartPointer<vtkImageData> Blurred(vtkImageData* image)
{
  vtkNew<vtkImageGaussianSmooth> blur;
  blur->SetInputData(image);
  blur->SetDimensionality(2);
  blur->SetStandardDeviations(2.0, 2.0);
  blur->SetRadiusFactors(3.0, 3.0);
  blur->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(blur->GetOutput());
  return out;
}

/// Writes the raster image, the traced one and their difference as
/// NAME.raster.png, NAME.png and NAME.diff.png under the test output folder.
inline void WriteFailedImages(const std::string& name, vtkImageData* raster, vtkImageData* traced)
{
  WritePNG(raster, std::string(VTKRT_TEMP_DIR) + "/" + name + ".raster.png");
  WritePNG(traced, std::string(VTKRT_TEMP_DIR) + "/" + name + ".png");
  vtkNew<vtkImageDifference> diff;
  diff->SetInputData(traced);
  diff->SetImageData(raster);
  diff->Update();
  WritePNG(diff->GetOutput(), std::string(VTKRT_TEMP_DIR) + "/" + name + ".diff.png");
}

/// Raster, then traced (the pass removed first): `traced` props traced and
/// the RGB RMSE of the images after `blur` at most `bound`; on failure the
/// raw images and their difference are written as `failName`.*.png.
inline RasterAndTraced CompareBlurred(vtkRenderWindow* win, vtkRenderer* ren, const std::string& label, int traced,
  double bound, const std::string& failName, vtkSmartPointer<vtkImageData> (*blur)(vtkImageData*) = Blurred)
{
  ren->SetPass(nullptr);
  RasterAndTraced frames = RenderRasterThenTraced(win, ren);
  const double rmse = RootMeanSquareError(blur(frames.Raster), blur(frames.Traced));
  std::ostringstream s;
  s << label << ": " << frames.Pass->GetNumberOfTracedProps() << " traced props (want " << traced
    << "), blurred RGB RMSE vs raster " << rmse << " (bound " << bound << "; unblurred "
    << RootMeanSquareError(frames.Raster, frames.Traced) << ")";
  Check(frames.Pass->GetNumberOfTracedProps() == traced && rmse <= bound, s.str());
  if (rmse > bound)
  {
    WriteFailedImages(failName, frames.Raster, frames.Traced);
  }
  NoGLError(win, label);
  return frames;
}

/// A window of `size` x `size` pixels with one renderer, viewed from an
/// orbit, whose raster and traced frames are compared blurred; failed
/// images are written as `name`-N.*.png.
struct ComparedScene
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  std::string Name;
  int Written = 0;
  vtkSmartPointer<vtkImageData> (*Blur)(vtkImageData*) = Blurred; ///< applied before comparing
  ComparedScene(int size, const std::string& name)
    : Window(MakeWindow(size, size))
    , Name(name)
  {
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.1, 0.1, 0.15);
  }
  void View(double azimuth, double elevation, bool parallel = false)
  {
    this->Renderer->GetActiveCamera()->SetParallelProjection(parallel);
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(azimuth);
    this->Renderer->GetActiveCamera()->Elevation(elevation);
    this->Renderer->ResetCameraClippingRange();
  }
  /// Raster, then traced: `traced` props traced, and the RGB RMSE of the
  /// blurred images at most `bound`.
  RasterAndTraced Compare(const std::string& label, int traced, double bound)
  {
    return CompareBlurred(this->Window, this->Renderer, label, traced, bound,
      this->Name + "-" + std::to_string(this->Written++), this->Blur);
  }
};

/// A renderer in `win` set up as VTK's depth peeling draws translucency
/// exactly: many peels, occlusion ratio 0.
inline void SetUpDepthPeeling(vtkRenderWindow* win, vtkRenderer* ren)
{
  win->AddRenderer(ren);
  win->SetAlphaBitPlanes(1);
  ren->SetBackground(0.1, 0.1, 0.15);
  ren->SetUseDepthPeeling(true);
  ren->SetMaximumNumberOfPeels(200);
  ren->SetOcclusionRatio(0.0);
}

/// Mean RGB (0..255) of an RGB image over the pixel indices in `mask`.
inline double MeanOver(vtkImageData* image, const std::vector<long>& mask)
{
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  double sum = 0.0;
  for (long i : mask)
  {
    sum += (p[3 * i] + p[3 * i + 1] + p[3 * i + 2]) / 3.0;
  }
  return mask.empty() ? 0.0 : sum / static_cast<double>(mask.size());
}
} // namespace vtkrtPassTest

#endif
