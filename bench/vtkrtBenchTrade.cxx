// vtkrtBenchTrade: the speed/accuracy trade of vtkrt's knobs, measured in
// one run on one mesh.
//
// Knobs measured (each against a reference setting):
// - builder: vtkBVHCellLocator BuildQuality (FAST / SAH / HIGH) x
//   NumberOfCellsPerNode (leaf size): build time, thread-CPU time per
//   IntersectWithLine ray, pick error against HIGH / leaf 1 (the locator is
//   exact in double, so any difference is a bug, not a trade);
// - pass builder: vtkRayTracePass BuildQuality (FAST / SAH / HIGH): first
//   frame (which pays the BVH build), steady frame, image and depth error
//   against HIGH;
// - lod: vtkOpenMeshDecimation TargetReduction, drawn traced
//   (vtkRayTracePass) and raster (vtkPolyDataMapper): decimation time,
//   locator build, first frame, steady frame, picking time; image error
//   (RMSE, vtkImageDifference), depth error, pick error and symmetric
//   sampled surface distance against the full-resolution mesh;
// - renderer: raster against traced at full resolution;
// - precision: the scene and camera translated by 1e2 .. 1e8, each method
//   against its own untranslated result: traced and raster images, the
//   point under a pixel from each one's depth buffer (what
//   vtkWorldPointPicker does), vtkCellPicker with vtkBVHCellLocator, and
//   vtkCellPicker without a locator.
// - pass knobs: SamplesPerPixel, MaximumTraversalSteps, Shadows,
//   AmbientOcclusionSamples, each against its best setting (first frame,
//   steady frame, image and depth error).
// - pass LeafSize (triangles per BVH leaf): first and steady frame;
// - shadows against the number of scene lights (1..8): frame time, on/off;
// - progressive accumulation, 1 sample a frame (plain and with one AO ray):
//   image error after 1, 2, 4, .. frames against the most accumulated one,
//   time per frame;
// - precision mode: the precision section also renders the pass in WORLD
//   mode (plain float world coordinates).
//
// Output: DIR/trade.csv, DIR/precision.csv and PNG plots in DIR (default
// ./results). A timing never decides anything here beyond being reported.
//
// Usage: vtkrtBenchTrade [--quick] [--out DIR] [--size PIXELS]
//                        [--mesh FILE.ply|.obj|.stl|.vtp|generated]
// The default mesh is bunny.ply from $VTKRT_DATA_DIR or the project's data/
// (vtkrtDataFile.h); --quick defaults to the generated one.
#include "vtkrtPlot.h"

#include "vtkBVHCellLocator.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkOpenMeshDecimation.h"
#include "vtkRayTracePass.h"
#include "vtkrtDataFile.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellPicker.h"
#include "vtkGenericCell.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
using Point = std::array<double, 3>;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// CPU time of the calling thread: single-threaded query loops timed this
/// way are far less disturbed by other processes than by the wall clock.
double ThreadSeconds()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return kNaN;
  }
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Options
{
  bool Quick = false;
  std::string Out = "results";
  std::string Mesh; // empty: bunny.ply (vtkrtDataFile) when found, else generated
  int Size = 384;
  int Frames = 7;        // steady frames timed (median and minimum reported)
  int Repeats = 3;       // builder: best of this many builds and ray sweeps
  int PickGrid = 24;     // LOD picks: PickGrid^2 pixels over the object
  int PrecisionGrid = 8; // precision picks (vtkCellPicker without a locator is slow)
  int GeomSamples = 20000;
  int BuilderRays = 20000;
  std::vector<double> Ratios{ 0.0, 0.5, 0.75, 0.9, 0.95, 0.98, 0.99 };
  std::vector<double> Translations{ 0.0, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8 };
  std::vector<int> Leaves{ 1, 2, 4, 8, 16 };
};

//------------------------------------------------------------------------------
// Meshes

/// Triangles only, points in double (so that translating by 1e8 loses
/// nothing in the data itself).
vtkSmartPointer<vtkPolyData> DoubleTriangles(vtkPolyData* input)
{
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputData(input);
  tri->PassVertsOff();
  tri->PassLinesOff();
  tri->Update();
  vtkPolyData* t = tri->GetOutput();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(t->GetNumberOfPoints());
  for (vtkIdType i = 0; i < t->GetNumberOfPoints(); ++i)
  {
    pts->SetPoint(i, t->GetPoint(i));
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(pts);
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(t->GetPolys());
  out->SetPolys(polys);
  return out;
}

/// A sphere with bumps on every scale the decimation will remove.
vtkSmartPointer<vtkPolyData> BumpySphere(int res)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  sphere->Update();
  auto pd = DoubleTriangles(sphere->GetOutput());
  vtkPoints* pts = pd->GetPoints();
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pts->GetPoint(i, p);
    const double theta = std::atan2(p[1], p[0]);
    const double phi = std::acos(std::max(-1.0, std::min(1.0, p[2])));
    const double r = 1.0 + 0.08 * std::sin(5 * theta) * std::sin(6 * phi) +
      0.02 * std::sin(23 * theta) * std::sin(19 * phi);
    pts->SetPoint(i, r * p[0], r * p[1], r * p[2]);
  }
  return pd;
}

vtkSmartPointer<vtkPolyData> Translated(vtkPolyData* mesh, const Point& offset)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    pts->SetPoint(i, p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
  }
  out->SetPoints(pts);
  out->SetPolys(mesh->GetPolys());
  return out;
}

/// Where the camera looks from, fixed for the whole run.
struct Scene
{
  Point Center{ { 0, 0, 0 } };
  double Radius = 1.0;
  double Diagonal = 1.0;
  Point Direction{ { 0, 0, 1 } };
  double Distance = 1.0;
};

Scene MakeScene(vtkPolyData* mesh)
{
  Scene s;
  double b[6];
  mesh->GetBounds(b);
  for (int k = 0; k < 3; ++k)
  {
    s.Center[k] = 0.5 * (b[2 * k] + b[2 * k + 1]);
  }
  s.Diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  s.Radius = 0.5 * s.Diagonal;
  const double d[3] = { 0.35, 0.25, 1.0 };
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  s.Direction = { { d[0] / n, d[1] / n, d[2] / n } };
  // Fill most of a 30-degree view with the bounding sphere.
  s.Distance = 0.8 * s.Radius / std::sin(vtkMath::RadiansFromDegrees(15.0));
  return s;
}

void SetupCamera(vtkCamera* camera, const Scene& s, const Point& offset)
{
  double focal[3], position[3];
  for (int k = 0; k < 3; ++k)
  {
    focal[k] = s.Center[k] + offset[k];
    position[k] = focal[k] + s.Distance * s.Direction[k];
  }
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30.0);
  camera->SetClippingRange(
    std::max(0.05 * s.Distance, s.Distance - 1.1 * s.Radius), s.Distance + 1.1 * s.Radius);
}

//------------------------------------------------------------------------------
// Rendering

/// One rendered view of one mesh: window, timings, image and depth.
struct Stage
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkActor> Actor;
  vtkSmartPointer<vtkRayTracePass> Pass;
  Point Offset{ { 0, 0, 0 } };
  double FirstSeconds = kNaN;
  double SteadySeconds = kNaN;    // median of the timed frames
  double SteadyMinSeconds = kNaN; // fastest of them (least disturbed by other load)
  int Width = 0, Height = 0;
  vtkSmartPointer<vtkImageData> Image;
  std::vector<float> Depth;
  vtkNew<vtkMatrix4x4> DisplayToWorld; // NDC -> world, inverse of the composite matrix

  ~Stage()
  {
    if (this->Window)
    {
      this->Window->Finalize();
    }
  }

  /// The window's current image (RGB, no re-render).
  vtkSmartPointer<vtkImageData> GrabImage() const
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(this->Window);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOn();
    grab->ShouldRerenderOff();
    grab->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(grab->GetOutput());
    return image;
  }

  /// World point under pixel (i, j) from the depth buffer, translation
  /// removed; false where the pixel shows background.
  bool Unproject(int i, int j, Point& x) const
  {
    const float z = this->Depth[static_cast<size_t>(j) * this->Width + i];
    if (!(z < 1.0f))
    {
      return false;
    }
    const double ndc[4] = { 2.0 * (i + 0.5) / this->Width - 1.0,
      2.0 * (j + 0.5) / this->Height - 1.0, 2.0 * z - 1.0, 1.0 };
    double w[4];
    this->DisplayToWorld->MultiplyPoint(ndc, w);
    for (int k = 0; k < 3; ++k)
    {
      x[k] = w[k] / w[3] - this->Offset[k];
    }
    return true;
  }
};

/// Renders `mesh` in a fresh window (so the first frame pays for everything:
/// BVH build, upload, shader compile); passQuality >= 0 sets the pass's
/// BuildQuality.
/// Pass knobs of one traced stage (defaults: the pass's own).
struct PassSettings
{
  int Quality = -1; // BuildQuality; -1 keeps the default
  int SamplesPerPixel = 1;
  int MaximumTraversalSteps = 0;
  bool Shadows = false;
  int AmbientOcclusionSamples = 0;
  bool Progressive = false;
  int LeafSize = 4;
  int PrecisionMode = vtkRayTracePass::CAMERA_RELATIVE;
  int Lights = 0; // > 0: this many scene lights instead of the headlight
};

/// `count` scene lights of total intensity 1 around the camera's side of the
/// object: directional and positional (spot) lights alternately, above.
void AddSceneLights(vtkRenderer* ren, const Scene& s, const Point& offset, int count)
{
  for (int i = 0; i < count; ++i)
  {
    const double phi = 2.0 * vtkMath::Pi() * (i + 0.25) / count;
    const double dir[3] = { 0.8 * std::cos(phi) + 0.3 * s.Direction[0], 1.0,
      0.8 * std::sin(phi) + 0.6 * s.Direction[2] };
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    double focal[3], position[3];
    for (int k = 0; k < 3; ++k)
    {
      focal[k] = s.Center[k] + offset[k];
      position[k] = focal[k] + 2.0 * s.Radius * dir[k];
    }
    light->SetFocalPoint(focal);
    light->SetPosition(position);
    light->SetIntensity(1.0 / count);
    if (i % 2 == 1)
    {
      light->SetPositional(true);
      light->SetConeAngle(60.0);
    }
    ren->AddLight(light);
  }
}

std::unique_ptr<Stage> RenderStage(vtkPolyData* mesh, const Scene& scene, const Point& offset,
  bool traced, const Options& opt, const PassSettings& knobs = PassSettings())
{
  auto st = std::make_unique<Stage>();
  st->Offset = offset;
  st->Window = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  st->Window->SetSize(opt.Size, opt.Size);
  st->Window->SetMultiSamples(0);
  st->Renderer = vtkSmartPointer<vtkRenderer>::New();
  st->Renderer->SetBackground(0.12, 0.12, 0.15);
  st->Window->AddRenderer(st->Renderer);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->ScalarVisibilityOff();
  st->Actor = vtkSmartPointer<vtkActor>::New();
  st->Actor->SetMapper(mapper);
  st->Actor->GetProperty()->SetColor(0.92, 0.82, 0.66);
  st->Actor->GetProperty()->SetSpecular(0.3);
  st->Actor->GetProperty()->SetSpecularPower(30.0);
  st->Renderer->AddActor(st->Actor);
  SetupCamera(st->Renderer->GetActiveCamera(), scene, offset);
  if (traced)
  {
    st->Pass = vtkSmartPointer<vtkRayTracePass>::New();
    if (knobs.Quality >= 0)
    {
      st->Pass->SetBuildQuality(knobs.Quality);
    }
    st->Pass->SetSamplesPerPixel(knobs.SamplesPerPixel);
    st->Pass->SetMaximumTraversalSteps(knobs.MaximumTraversalSteps);
    st->Pass->SetShadows(knobs.Shadows);
    st->Pass->SetAmbientOcclusionSamples(knobs.AmbientOcclusionSamples);
    st->Pass->SetProgressiveAccumulation(knobs.Progressive);
    st->Pass->SetLeafSize(knobs.LeafSize);
    st->Pass->SetPrecisionMode(knobs.PrecisionMode);
    st->Renderer->SetPass(st->Pass);
  }
  if (knobs.Lights > 0)
  {
    AddSceneLights(st->Renderer, scene, offset, knobs.Lights);
  }

  st->Window->Initialize();
  if (!st->Window->IsContextReady())
  {
    return nullptr;
  }
  auto t0 = Clock::now();
  st->Window->Render();
  st->Window->WaitForCompletion();
  st->FirstSeconds = Seconds(t0, Clock::now());
  std::vector<double> times;
  for (int f = 0; f < opt.Frames; ++f)
  {
    t0 = Clock::now();
    st->Window->Render();
    st->Window->WaitForCompletion();
    times.push_back(Seconds(t0, Clock::now()));
  }
  if (!times.empty())
  {
    st->SteadySeconds = Median(times);
    st->SteadyMinSeconds = *std::min_element(times.begin(), times.end());
  }
  st->Image = st->GrabImage();

  const int* size = st->Window->GetSize();
  st->Width = size[0];
  st->Height = size[1];
  st->Depth.resize(static_cast<size_t>(st->Width) * st->Height);
  st->Window->GetZbufferData(0, 0, st->Width - 1, st->Height - 1, st->Depth.data());

  vtkCamera* camera = st->Renderer->GetActiveCamera();
  st->DisplayToWorld->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(st->Renderer->GetTiledAspectRatio(), -1, 1));
  st->DisplayToWorld->Invert();
  return st;
}

//------------------------------------------------------------------------------
// Errors

double ImageRMSE(vtkImageData* a, vtkImageData* b)
{
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  const vtkIdType n = a->GetNumberOfPoints() * a->GetNumberOfScalarComponents();
  if (n != b->GetNumberOfPoints() * b->GetNumberOfScalarComponents())
  {
    return kNaN;
  }
  double sum = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double d = double(pa[i]) - double(pb[i]);
    sum += d * d;
  }
  return std::sqrt(sum / std::max<vtkIdType>(1, n));
}

/// vtkImageDifference's thresholded error (the image-test harness settings).
double ImageDifference(vtkImageData* a, vtkImageData* b)
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

struct DepthError
{
  double Mean = 0.0;     // world distance between the points under a pixel
  double Coverage = 0.0; // pixels hit by one side only / pixels hit by either
};

DepthError CompareDepth(const Stage& ref, const Stage& cand)
{
  DepthError e;
  long both = 0, either = 0, one = 0;
  double sum = 0.0;
  for (int j = 0; j < ref.Height; ++j)
  {
    for (int i = 0; i < ref.Width; ++i)
    {
      Point a, b;
      const bool ha = ref.Unproject(i, j, a);
      const bool hb = cand.Unproject(i, j, b);
      either += (ha || hb) ? 1 : 0;
      one += (ha != hb) ? 1 : 0;
      if (ha && hb)
      {
        ++both;
        sum += std::sqrt(vtkMath::Distance2BetweenPoints(a.data(), b.data()));
      }
    }
  }
  e.Mean = both ? sum / both : kNaN;
  e.Coverage = either ? double(one) / either : 0.0;
  return e;
}

/// Display positions on a grid over the object's footprint in `ref`.
std::vector<std::array<double, 2>> PickPixels(const Stage& ref, int grid)
{
  int lo[2] = { ref.Width, ref.Height }, hi[2] = { -1, -1 };
  for (int j = 0; j < ref.Height; ++j)
  {
    for (int i = 0; i < ref.Width; ++i)
    {
      if (ref.Depth[static_cast<size_t>(j) * ref.Width + i] < 1.0f)
      {
        lo[0] = std::min(lo[0], i);
        lo[1] = std::min(lo[1], j);
        hi[0] = std::max(hi[0], i);
        hi[1] = std::max(hi[1], j);
      }
    }
  }
  std::vector<std::array<double, 2>> pixels;
  if (hi[0] < 0)
  {
    return pixels;
  }
  for (int b = 0; b < grid; ++b)
  {
    for (int a = 0; a < grid; ++a)
    {
      const int i = lo[0] + static_cast<int>((a + 0.5) / grid * (hi[0] - lo[0] + 1));
      const int j = lo[1] + static_cast<int>((b + 0.5) / grid * (hi[1] - lo[1] + 1));
      pixels.push_back({ { i + 0.5, j + 0.5 } });
    }
  }
  return pixels;
}

struct Picks
{
  std::vector<char> Hit;
  std::vector<Point> X;
  std::vector<vtkIdType> CellId;
  double SecondsPerPick = kNaN;
};

/// vtkCellPicker at each display position (with `locator` when given).
Picks PickWithPicker(const Stage& st, const std::vector<std::array<double, 2>>& pixels,
  vtkAbstractCellLocator* locator)
{
  vtkNew<vtkCellPicker> picker;
  if (locator)
  {
    picker->AddLocator(locator);
  }
  Picks p;
  p.Hit.resize(pixels.size());
  p.X.resize(pixels.size());
  p.CellId.assign(pixels.size(), -1);
  const auto t0 = Clock::now();
  for (size_t k = 0; k < pixels.size(); ++k)
  {
    p.Hit[k] = picker->Pick(pixels[k][0], pixels[k][1], 0.0, st.Renderer) != 0;
    if (p.Hit[k])
    {
      double x[3];
      picker->GetPickPosition(x);
      p.CellId[k] = picker->GetCellId();
      for (int c = 0; c < 3; ++c)
      {
        p.X[k][c] = x[c] - st.Offset[c];
      }
    }
  }
  p.SecondsPerPick = pixels.empty() ? kNaN : Seconds(t0, Clock::now()) / pixels.size();
  return p;
}

/// The point under each display position from the stage's depth buffer.
Picks PickFromDepth(const Stage& st, const std::vector<std::array<double, 2>>& pixels)
{
  Picks p;
  p.Hit.resize(pixels.size());
  p.X.resize(pixels.size());
  for (size_t k = 0; k < pixels.size(); ++k)
  {
    p.Hit[k] = st.Unproject(static_cast<int>(pixels[k][0]), static_cast<int>(pixels[k][1]), p.X[k]);
  }
  return p;
}

struct PickError
{
  double Mean = kNaN, Max = kNaN;
  double Miss = 0.0; // picks hit by one side only / picks hit by either
};

PickError ComparePicks(const Picks& ref, const Picks& cand)
{
  PickError e;
  long both = 0, either = 0, one = 0;
  double sum = 0.0, mx = 0.0;
  for (size_t k = 0; k < ref.Hit.size() && k < cand.Hit.size(); ++k)
  {
    either += (ref.Hit[k] || cand.Hit[k]) ? 1 : 0;
    one += (ref.Hit[k] != cand.Hit[k]) ? 1 : 0;
    if (ref.Hit[k] && cand.Hit[k])
    {
      ++both;
      const double d = std::sqrt(vtkMath::Distance2BetweenPoints(ref.X[k].data(), cand.X[k].data()));
      sum += d;
      mx = std::max(mx, d);
    }
  }
  if (both)
  {
    e.Mean = sum / both;
    e.Max = mx;
  }
  e.Miss = either ? double(one) / either : 0.0;
  return e;
}

/// Area-uniform random points on the surface (fixed seed).
std::vector<Point> SampleSurface(vtkPolyData* mesh, int count, unsigned seed)
{
  std::vector<std::array<vtkIdType, 3>> tris;
  std::vector<double> cumulative;
  double total = 0.0;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType npts;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    double a[3], b[3], c[3], u[3], v[3], n[3];
    mesh->GetPoint(ids[0], a);
    mesh->GetPoint(ids[1], b);
    mesh->GetPoint(ids[2], c);
    vtkMath::Subtract(b, a, u);
    vtkMath::Subtract(c, a, v);
    vtkMath::Cross(u, v, n);
    total += 0.5 * vtkMath::Norm(n);
    tris.push_back({ { ids[0], ids[1], ids[2] } });
    cumulative.push_back(total);
  }
  std::vector<Point> samples;
  if (tris.empty() || total <= 0.0)
  {
    return samples;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  samples.reserve(count);
  for (int s = 0; s < count; ++s)
  {
    const double r = uni(rng) * total;
    const size_t t = std::min(tris.size() - 1,
      static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()));
    double a[3], b[3], c[3];
    mesh->GetPoint(tris[t][0], a);
    mesh->GetPoint(tris[t][1], b);
    mesh->GetPoint(tris[t][2], c);
    double r1 = std::sqrt(uni(rng)), r2 = uni(rng);
    const double wa = 1.0 - r1, wb = r1 * (1.0 - r2), wc = r1 * r2;
    samples.push_back({ { wa * a[0] + wb * b[0] + wc * c[0], wa * a[1] + wb * b[1] + wc * c[1],
      wa * a[2] + wb * b[2] + wc * c[2] } });
  }
  return samples;
}

/// Distance from each sample to the locator's surface (parallel).
std::vector<double> DistancesTo(vtkBVHCellLocator* locator, const std::vector<Point>& samples)
{
  std::vector<double> d(samples.size(), kNaN);
  vtkSMPThreadLocalObject<vtkGenericCell> cells;
  vtkSMPTools::For(0, static_cast<vtkIdType>(samples.size()), [&](vtkIdType begin, vtkIdType end) {
    vtkGenericCell* cell = cells.Local();
    for (vtkIdType k = begin; k < end; ++k)
    {
      double closest[3], dist2;
      vtkIdType cellId;
      int subId;
      locator->FindClosestPoint(samples[k].data(), closest, cell, cellId, subId, dist2);
      d[k] = cellId >= 0 ? std::sqrt(dist2) : kNaN;
    }
  });
  return d;
}

struct GeomError
{
  double Mean = kNaN, Max = kNaN;
};

/// Symmetric sampled surface distance: samples of A to B and of B to A.
GeomError SurfaceDistance(vtkBVHCellLocator* a, const std::vector<Point>& samplesA,
  vtkBVHCellLocator* b, const std::vector<Point>& samplesB)
{
  std::vector<double> d = DistancesTo(b, samplesA);
  std::vector<double> back = DistancesTo(a, samplesB);
  d.insert(d.end(), back.begin(), back.end());
  GeomError e;
  double sum = 0.0, mx = 0.0;
  long n = 0;
  for (double v : d)
  {
    if (std::isfinite(v))
    {
      sum += v;
      mx = std::max(mx, v);
      ++n;
    }
  }
  if (n)
  {
    e.Mean = sum / n;
    e.Max = mx;
  }
  return e;
}

//------------------------------------------------------------------------------
// Results

/// One row of trade.csv; NaN cells are written empty.
struct TradeRow
{
  std::string Knob, Setting, Method;
  double Value = kNaN; // the knob's numeric value (ratio, leaf size, ...)
  double Triangles = kNaN;
  double PrepS = kNaN, BuildS = kNaN, FirstFrameS = kNaN, SteadyFrameS = kNaN, PickUs = kNaN;
  double SteadyMinS = kNaN;
  double ImageRMSE = kNaN, ImageDiff = kNaN, DepthErr = kNaN, Coverage = kNaN;
  double PickMean = kNaN, PickMax = kNaN, PickMiss = kNaN;
  double GeomMean = kNaN, GeomMax = kNaN;
  double Nodes = kNaN, SAHCost = kNaN, MemoryMB = kNaN;
};

struct PrecisionRow
{
  std::string Method;
  double Translation = 0.0;
  double ImageRMSE = kNaN, ImageDiff = kNaN, DepthErr = kNaN, Coverage = kNaN;
  double PickMean = kNaN, PickMax = kNaN, PickMiss = kNaN, PickUs = kNaN;
  double PickExact = kNaN; // mean distance to the exact, untranslated pick
  double IdMismatch = kNaN; // GPU id picks differing from the locator's cell
};

/// A row for one rendered stage: its frame times and its image error
/// against `ref` (the caller adds depth, pick and geometry errors).
TradeRow StageRow(const std::string& knob, const std::string& setting, const std::string& method,
  double value, double triangles, const Stage& st, const Stage& ref)
{
  TradeRow row;
  row.Knob = knob;
  row.Setting = setting;
  row.Method = method;
  row.Value = value;
  row.Triangles = triangles;
  row.FirstFrameS = st.FirstSeconds;
  row.SteadyFrameS = st.SteadySeconds;
  row.SteadyMinS = st.SteadyMinSeconds;
  row.ImageRMSE = ImageRMSE(ref.Image, st.Image);
  row.ImageDiff = ImageDifference(ref.Image, st.Image);
  return row;
}

std::string Cell(double v)
{
  if (!std::isfinite(v))
  {
    return "";
  }
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

bool WriteTradeCSV(const std::string& path, const std::vector<TradeRow>& rows, double diagonal)
{
  std::ofstream f(path);
  f << "knob,setting,method,value,triangles,prep_s,build_s,first_frame_s,steady_frame_s,steady_frame_min_s,pick_us,"
       "image_rmse,image_diff,depth_err,coverage_err,pick_err_mean,pick_err_max,pick_miss,"
       "geom_mean,geom_max,nodes,sah_cost,memory_mb,diagonal\n";
  for (const TradeRow& r : rows)
  {
    f << r.Knob << ',' << r.Setting << ',' << r.Method << ',' << Cell(r.Value) << ','
      << Cell(r.Triangles) << ',' << Cell(r.PrepS) << ',' << Cell(r.BuildS) << ','
      << Cell(r.FirstFrameS) << ',' << Cell(r.SteadyFrameS) << ',' << Cell(r.SteadyMinS) << ',' << Cell(r.PickUs) << ','
      << Cell(r.ImageRMSE) << ',' << Cell(r.ImageDiff) << ',' << Cell(r.DepthErr) << ','
      << Cell(r.Coverage) << ',' << Cell(r.PickMean) << ',' << Cell(r.PickMax) << ','
      << Cell(r.PickMiss) << ',' << Cell(r.GeomMean) << ',' << Cell(r.GeomMax) << ','
      << Cell(r.Nodes) << ',' << Cell(r.SAHCost) << ',' << Cell(r.MemoryMB) << ','
      << Cell(diagonal) << '\n';
  }
  return static_cast<bool>(f);
}

bool WritePrecisionCSV(const std::string& path, const std::vector<PrecisionRow>& rows, double diagonal)
{
  std::ofstream f(path);
  f << "method,translation,image_rmse,image_diff,depth_err,coverage_err,pick_err_mean,"
       "pick_err_max,pick_miss,pick_us,pick_err_vs_exact,id_mismatch,diagonal\n";
  for (const PrecisionRow& r : rows)
  {
    f << r.Method << ',' << Cell(r.Translation) << ',' << Cell(r.ImageRMSE) << ','
      << Cell(r.ImageDiff) << ',' << Cell(r.DepthErr) << ',' << Cell(r.Coverage) << ','
      << Cell(r.PickMean) << ',' << Cell(r.PickMax) << ',' << Cell(r.PickMiss) << ','
      << Cell(r.PickUs) << ',' << Cell(r.PickExact) << ',' << Cell(r.IdMismatch) << ','
      << Cell(diagonal) << '\n';
  }
  return static_cast<bool>(f);
}

//------------------------------------------------------------------------------
// Sections

/// Builder quality x leaf size on vtkBVHCellLocator (always succeeds: the
/// bool matches the other sections').
bool RunBuilder(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<TradeRow>& rows)
{
  // Segments from a sphere around the object through random points of it.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<std::array<Point, 2>> segments;
  double b[6];
  mesh->GetBounds(b);
  for (int r = 0; r < opt.BuilderRays; ++r)
  {
    Point dir{ { uni(rng), uni(rng), uni(rng) } };
    const double n = std::max(1e-9, vtkMath::Norm(dir.data()));
    Point p1, target, p2;
    for (int k = 0; k < 3; ++k)
    {
      p1[k] = scene.Center[k] + 2.0 * scene.Radius * dir[k] / n;
      target[k] = b[2 * k] + 0.5 * (uni(rng) + 1.0) * (b[2 * k + 1] - b[2 * k]);
      p2[k] = p1[k] + 3.0 * (target[k] - p1[k]);
    }
    segments.push_back({ { p1, p2 } });
  }

  const char* names[] = { "FAST", "SAH", "HIGH" };
  Picks reference;
  struct Setting
  {
    int Quality, Leaf;
  };
  std::vector<Setting> settings{ { vtkBVHCellLocator::HIGH, 1 } }; // reference first
  for (int q = vtkBVHCellLocator::FAST; q <= vtkBVHCellLocator::HIGH; ++q)
  {
    for (int leaf : opt.Leaves)
    {
      settings.push_back({ q, leaf });
    }
  }
  vtkNew<vtkGenericCell> cell;
  for (size_t s = 0; s < settings.size(); ++s)
  {
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(mesh);
    locator->SetBuildQuality(settings[s].Quality);
    locator->SetNumberOfCellsPerNode(settings[s].Leaf);
    double build = HUGE_VAL;
    for (int rep = 0; rep < opt.Repeats; ++rep)
    {
      const auto t0 = Clock::now();
      locator->ForceBuildLocator();
      build = std::min(build, Seconds(t0, Clock::now()));
    }

    Picks picks;
    picks.Hit.resize(segments.size());
    picks.X.resize(segments.size());
    double sweep = HUGE_VAL;
    for (int rep = 0; rep < opt.Repeats; ++rep)
    {
      const double t0 = ThreadSeconds();
      for (size_t r = 0; r < segments.size(); ++r)
      {
        double t, x[3], pc[3];
        int subId;
        vtkIdType cellId;
        picks.Hit[r] = locator->IntersectWithLine(
          segments[r][0].data(), segments[r][1].data(), 0.0, t, x, pc, subId, cellId, cell) != 0;
        picks.X[r] = { { x[0], x[1], x[2] } };
      }
      sweep = std::min(sweep, ThreadSeconds() - t0);
    }
    picks.SecondsPerPick = sweep / std::max<size_t>(1, segments.size());
    if (s == 0)
    {
      reference = picks;
      continue;
    }
    const PickError e = ComparePicks(reference, picks);
    TradeRow row;
    row.Knob = "builder";
    row.Setting = std::string(names[settings[s].Quality]) + "/leaf" + std::to_string(settings[s].Leaf);
    row.Method = "vtkBVHCellLocator";
    row.Value = settings[s].Leaf;
    row.Triangles = mesh->GetNumberOfCells();
    row.BuildS = build;
    row.PickUs = 1e6 * picks.SecondsPerPick;
    row.PickMean = e.Mean;
    row.PickMax = e.Max;
    row.PickMiss = e.Miss;
    row.Nodes = locator->GetNumberOfNodes();
    row.SAHCost = locator->GetSAHCost();
    row.MemoryMB = locator->GetMemorySize() / 1048576.0;
    rows.push_back(row);
    std::printf("  builder %-12s build %7.1f ms  pick %6.2f us/ray  SAH %7.2f  nodes %8lld  "
                "pick err max %.3g  miss %.3g\n",
      row.Setting.c_str(), 1e3 * build, row.PickUs, row.SAHCost, static_cast<long long>(row.Nodes),
      e.Max, e.Miss);
  }
  return true;
}

/// vtkRayTracePass BuildQuality on the full mesh, against HIGH.
bool RunPassBuilder(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<TradeRow>& rows)
{
  const Point zero{ { 0, 0, 0 } };
  const char* names[] = { "FAST", "SAH", "HIGH" };
  std::unique_ptr<Stage> reference;
  for (int q : { 2, 0, 1 }) // reference (HIGH) first
  {
    PassSettings knobs;
    knobs.Quality = q;
    std::unique_ptr<Stage> st = RenderStage(mesh, scene, zero, true, opt, knobs);
    if (!st)
    {
      std::cerr << "vtkrtBenchTrade: no EGL context\n";
      return false;
    }
    const Stage& ref = reference ? *reference : *st;
    const DepthError de = CompareDepth(ref, *st);
    TradeRow row =
      StageRow("pass builder", names[q], "vtkRayTracePass", q, mesh->GetNumberOfCells(), *st, ref);
    row.DepthErr = de.Mean;
    row.Coverage = de.Coverage;
    rows.push_back(row);
    std::printf("  pass BuildQuality %-4s first %6.0f ms  frame %6.1f ms (min %6.1f)  rmse %.3g  "
                "depth %.3g\n",
      names[q], 1e3 * st->FirstSeconds, 1e3 * st->SteadySeconds, 1e3 * st->SteadyMinSeconds,
      row.ImageRMSE, de.Mean);
    if (!reference)
    {
      reference = std::move(st);
    }
  }
  return true;
}

/// The pass's shading and sampling knobs on the full mesh, each against its
/// own highest-quality setting (listed first).
bool RunPassKnobs(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<TradeRow>& rows)
{
  struct Knob
  {
    std::string Name;
    std::vector<int> Values; // reference first
    void (*Apply)(PassSettings&, int);
  };
  const std::vector<Knob> knobs = {
    { "pass samples per pixel", opt.Quick ? std::vector<int>{ 4, 1 } : std::vector<int>{ 16, 1, 2, 4, 8 },
      [](PassSettings& k, int v) { k.SamplesPerPixel = v; } },
    { "pass max traversal steps",
      opt.Quick ? std::vector<int>{ 0, 16 } : std::vector<int>{ 0, 16, 32, 64, 128 },
      [](PassSettings& k, int v) { k.MaximumTraversalSteps = v; } },
    { "pass shadows", { 1, 0 }, [](PassSettings& k, int v) { k.Shadows = v != 0; } },
    { "pass AO samples", opt.Quick ? std::vector<int>{ 4, 0 } : std::vector<int>{ 16, 0, 1, 4 },
      [](PassSettings& k, int v) { k.AmbientOcclusionSamples = v; } },
    // Reference: the default (images do not depend on the leaf size).
    { "pass leaf size",
      opt.Quick ? std::vector<int>{ 4, 1, 16 } : std::vector<int>{ 4, 1, 2, 8, 16, 32 },
      [](PassSettings& k, int v) { k.LeafSize = v; } },
  };
  Options fewer = opt;
  fewer.Frames = std::min(opt.Frames, 3); // many-sample frames are slow on llvmpipe
  const Point zero{ { 0, 0, 0 } };
  for (const Knob& knob : knobs)
  {
    std::unique_ptr<Stage> reference;
    for (int v : knob.Values)
    {
      PassSettings settings;
      knob.Apply(settings, v);
      std::unique_ptr<Stage> st = RenderStage(mesh, scene, zero, true, fewer, settings);
      if (!st)
      {
        std::cerr << "vtkrtBenchTrade: no EGL context\n";
        return false;
      }
      const Stage& ref = reference ? *reference : *st;
      const DepthError de = CompareDepth(ref, *st);
      std::string setting = (v == 0 && knob.Name.find("steps") != std::string::npos)
        ? std::string("unlimited")
        : std::to_string(v);
      if (!reference)
      {
        setting += " (reference)";
      }
      TradeRow row =
        StageRow(knob.Name, setting, "vtkRayTracePass", v, mesh->GetNumberOfCells(), *st, ref);
      row.DepthErr = de.Mean;
      row.Coverage = de.Coverage;
      rows.push_back(row);
      std::printf("  %-25s %-18s first %6.0f ms  frame %7.1f ms (min %7.1f)  rmse %6.2f  "
                  "diff %7.1f  coverage %.3g\n",
        knob.Name.c_str(), row.Setting.c_str(), 1e3 * st->FirstSeconds, 1e3 * st->SteadySeconds,
        1e3 * st->SteadyMinSeconds, row.ImageRMSE, row.ImageDiff, de.Coverage);
      if (!reference)
      {
        reference = std::move(st);
      }
    }
  }
  return true;
}

/// Shadows against the number of scene lights (directional and spot lights
/// alternately): frame time with shadows off and on, and what shadows change.
bool RunShadowLights(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<TradeRow>& rows)
{
  // The per-light cost is a difference of two frame times, which a changing
  // load on the machine disturbs most: the two windows' frames are timed
  // alternately (same load for both), fastest of opt.Frames each.
  Options first = opt;
  first.Frames = 0;
  const Point zero{ { 0, 0, 0 } };
  const std::vector<int> counts = opt.Quick ? std::vector<int>{ 1, 4 } : std::vector<int>{ 1, 2, 4, 8 };
  for (int n : counts)
  {
    std::unique_ptr<Stage> stages[2];
    for (int on = 0; on < 2; ++on)
    {
      PassSettings settings;
      settings.Lights = n;
      settings.Shadows = on != 0;
      stages[on] = RenderStage(mesh, scene, zero, true, first, settings);
      if (!stages[on])
      {
        std::cerr << "vtkrtBenchTrade: no EGL context\n";
        return false;
      }
    }
    std::vector<double> times[2];
    for (int f = 0; f < std::max(1, opt.Frames); ++f)
    {
      for (int on = 0; on < 2; ++on)
      {
        const auto t0 = Clock::now();
        stages[on]->Window->Render();
        stages[on]->Window->WaitForCompletion();
        times[on].push_back(Seconds(t0, Clock::now()));
      }
    }
    for (int on = 0; on < 2; ++on)
    {
      stages[on]->SteadySeconds = Median(times[on]);
      stages[on]->SteadyMinSeconds = *std::min_element(times[on].begin(), times[on].end());
    }
    for (int on = 0; on < 2; ++on)
    {
      const Stage& st = *stages[on];
      rows.push_back(StageRow("pass shadow lights",
        std::to_string(n) + (n == 1 ? " light shadows " : " lights shadows ") +
          (on ? "on (reference)" : "off"),
        on ? "shadows on" : "shadows off", n, mesh->GetNumberOfCells(), st, *stages[1]));
    }
    std::printf("  %d scene light(s): frame %7.1f ms without shadows, %7.1f ms with (min %6.1f / "
                "%6.1f): %+.1f ms per light; shadows change RMSE %.2f\n",
      n, 1e3 * stages[0]->SteadySeconds, 1e3 * stages[1]->SteadySeconds,
      1e3 * stages[0]->SteadyMinSeconds, 1e3 * stages[1]->SteadyMinSeconds,
      1e3 * (stages[1]->SteadyMinSeconds - stages[0]->SteadyMinSeconds) / n,
      rows[rows.size() - 2].ImageRMSE);
  }
  return true;
}

/// Progressive accumulation: one window, 1 sample per frame, the image after
/// k accumulated frames against the last (most accumulated) one; plain
/// shading (anti-aliasing only) and with one ambient occlusion ray per frame.
bool RunAccumulation(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<TradeRow>& rows)
{
  const int maxFrames = opt.Quick ? 8 : 64;
  const Point zero{ { 0, 0, 0 } };
  for (int ao = 0; ao < 2; ++ao)
  {
    PassSettings settings;
    settings.Progressive = true;
    settings.AmbientOcclusionSamples = ao;
    Options none = opt;
    none.Frames = 0;
    std::unique_ptr<Stage> st = RenderStage(mesh, scene, zero, true, none, settings);
    if (!st)
    {
      std::cerr << "vtkrtBenchTrade: no EGL context\n";
      return false;
    }
    std::vector<std::pair<int, vtkSmartPointer<vtkImageData>>> images;
    std::vector<double> times;
    double total = st->FirstSeconds;
    std::vector<double> totals;
    images.emplace_back(1, st->Image);
    totals.push_back(total);
    for (int k = 2; k <= maxFrames; ++k)
    {
      const auto t0 = Clock::now();
      st->Window->Render();
      st->Window->WaitForCompletion();
      times.push_back(Seconds(t0, Clock::now()));
      total += times.back();
      if ((k & (k - 1)) == 0)
      {
        if (st->Pass->GetAccumulatedFrames() != k)
        {
          std::cerr << "vtkrtBenchTrade: progressive accumulation restarted (" <<
            st->Pass->GetAccumulatedFrames() << " frames, " << k << " expected)\n";
          return false;
        }
        images.emplace_back(k, st->GrabImage());
        totals.push_back(total);
      }
    }
    const double perFrame = Median(times);
    const double perFrameMin = times.empty() ? kNaN : *std::min_element(times.begin(), times.end());
    vtkImageData* reference = images.back().second;
    for (size_t i = 0; i < images.size(); ++i)
    {
      TradeRow row;
      row.Knob = ao ? "pass accumulation (AO 1)" : "pass accumulation";
      row.Setting = std::to_string(images[i].first) + " frames" +
        (i + 1 == images.size() ? " (reference)" : "");
      row.Method = "vtkRayTracePass";
      row.Value = images[i].first;
      row.Triangles = mesh->GetNumberOfCells();
      row.FirstFrameS = totals[i]; // wall time until this image
      row.SteadyFrameS = perFrame;
      row.SteadyMinS = perFrameMin;
      row.ImageRMSE = ImageRMSE(reference, images[i].second);
      row.ImageDiff = ImageDifference(reference, images[i].second);
      rows.push_back(row);
      std::printf("  %-26s %3d frames: %7.0f ms in all (%.1f ms a frame)  rmse %6.2f  diff %7.1f\n",
        row.Knob.c_str(), images[i].first, 1e3 * totals[i], 1e3 * perFrame, row.ImageRMSE,
        row.ImageDiff);
    }
  }
  return true;
}

/// Level of detail: decimation ratio, traced and raster.
bool RunLOD(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<TradeRow>& rows)
{
  const Point zero{ { 0, 0, 0 } };
  std::unique_ptr<Stage> refTraced, refRaster;
  Picks refPicks;
  std::vector<std::array<double, 2>> pixels;
  vtkSmartPointer<vtkBVHCellLocator> refLocator;
  const std::vector<Point> refSamples = SampleSurface(mesh, opt.GeomSamples, 11);

  for (double ratio : opt.Ratios)
  {
    vtkSmartPointer<vtkPolyData> lod = mesh;
    double prep = 0.0;
    if (ratio > 0.0)
    {
      vtkNew<vtkOpenMeshDecimation> decimate;
      decimate->SetInputData(mesh);
      decimate->SetTargetModeToReduction();
      decimate->SetTargetReduction(ratio);
      const auto t0 = Clock::now();
      decimate->Update();
      prep = Seconds(t0, Clock::now());
      lod = DoubleTriangles(decimate->GetOutput());
      if (lod->GetNumberOfCells() == 0)
      {
        std::printf("  lod %.2f: decimation gave no triangles, skipped\n", ratio);
        continue;
      }
    }

    auto locator = vtkSmartPointer<vtkBVHCellLocator>::New();
    locator->SetDataSet(lod);
    auto t0 = Clock::now();
    locator->BuildLocator();
    const double build = Seconds(t0, Clock::now());

    std::unique_ptr<Stage> traced = RenderStage(lod, scene, zero, true, opt);
    std::unique_ptr<Stage> raster = RenderStage(lod, scene, zero, false, opt);
    if (!traced || !raster)
    {
      std::cerr << "vtkrtBenchTrade: no EGL context\n";
      return false;
    }
    if (ratio == opt.Ratios.front())
    {
      pixels = PickPixels(*traced, opt.PickGrid);
    }
    const Picks picks = PickWithPicker(*traced, pixels, locator);
    const std::vector<Point> samples = SampleSurface(lod, opt.GeomSamples, 13);

    if (ratio == opt.Ratios.front())
    {
      refPicks = picks;
      refLocator = locator;
    }
    const PickError pe = ComparePicks(refPicks, picks);
    const GeomError ge = SurfaceDistance(refLocator, refSamples, locator, samples);

    for (int m = 0; m < 2; ++m)
    {
      Stage& st = m == 0 ? *traced : *raster;
      Stage& ref = m == 0 ? (refTraced ? *refTraced : *traced) : (refRaster ? *refRaster : *raster);
      const DepthError de = CompareDepth(ref, st);
      char setting[32];
      std::snprintf(setting, sizeof(setting), "reduction %.2f", ratio);
      TradeRow row = StageRow(
        "lod", setting, m == 0 ? "traced" : "raster", ratio, lod->GetNumberOfCells(), st, ref);
      row.PrepS = prep;
      row.BuildS = build;
      row.PickUs = 1e6 * picks.SecondsPerPick;
      row.DepthErr = de.Mean;
      row.Coverage = de.Coverage;
      row.PickMean = pe.Mean;
      row.PickMax = pe.Max;
      row.PickMiss = pe.Miss;
      row.GeomMean = ge.Mean;
      row.GeomMax = ge.Max;
      rows.push_back(row);
      std::printf("  lod %.2f %-6s %8lld tris  decimate %6.0f ms  first %6.0f ms  frame %6.1f ms  "
                  "rmse %6.2f  diff %7.1f  depth %.3g  pick %.3g  geom %.3g/%.3g\n",
        ratio, row.Method.c_str(), static_cast<long long>(row.Triangles), 1e3 * prep,
        1e3 * st.FirstSeconds, 1e3 * st.SteadySeconds, row.ImageRMSE, row.ImageDiff, de.Mean,
        pe.Mean, ge.Mean, ge.Max);
    }

    if (ratio == opt.Ratios.front())
    {
      // Renderer knob: raster against traced at full resolution.
      const DepthError de = CompareDepth(*traced, *raster);
      for (int m = 0; m < 2; ++m)
      {
        Stage& st = m == 0 ? *traced : *raster;
        TradeRow row = StageRow("renderer", m == 0 ? "traced (reference)" : "raster",
          m == 0 ? "vtkRayTracePass" : "vtkPolyDataMapper", kNaN, lod->GetNumberOfCells(), st,
          *traced);
        row.DepthErr = m == 0 ? 0.0 : de.Mean;
        row.Coverage = m == 0 ? 0.0 : de.Coverage;
        rows.push_back(row);
      }
      refTraced = std::move(traced);
      refRaster = std::move(raster);
    }
  }
  return true;
}

/// Renders the traced stage once more in id mode and returns the fraction of
/// `pixels` (hit by either side) whose GPU cell id differs from `exact`'s.
double IdMismatch(Stage& st, const std::vector<std::array<double, 2>>& pixels, const Picks& exact)
{
  st.Pass->SetIdMode(true);
  st.Window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(st.Window);
  grab->SetInputBufferTypeToRGBA();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  st.Pass->SetIdMode(false);
  vtkImageData* image = grab->GetOutput();
  const auto* rgba = static_cast<const unsigned char*>(image->GetScalarPointer());
  long either = 0, differ = 0;
  for (size_t k = 0; k < pixels.size(); ++k)
  {
    const size_t i = static_cast<size_t>(pixels[k][0]);
    const size_t j = static_cast<size_t>(pixels[k][1]);
    int prop;
    vtkIdType id;
    const bool hit = vtkRayTracePass::DecodeId(rgba + 4 * (j * st.Width + i), prop, id);
    if (hit || exact.Hit[k])
    {
      ++either;
      differ += (hit != static_cast<bool>(exact.Hit[k]) || id != exact.CellId[k]) ? 1 : 0;
    }
  }
  return either ? double(differ) / either : 0.0;
}

/// The scene and camera translated far from the origin.
bool RunPrecision(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<PrecisionRow>& rows)
{
  enum
  {
    Traced,
    Raster,
    World,
    Locator,
    NoLocator,
    Methods,
    Stages = 3 // Traced, Raster, World render images
  };
  const char* names[Methods] = { "traced depth (vtkRayTracePass)",
    "raster depth (vtkPolyDataMapper)", "traced depth WORLD precision mode (vtkRayTracePass)",
    "vtkCellPicker + vtkBVHCellLocator", "vtkCellPicker (no locator)" };
  PassSettings world;
  world.PrecisionMode = vtkRayTracePass::WORLD;
  std::unique_ptr<Stage> refStage[Stages];
  Picks refPicks[Methods];
  std::vector<std::array<double, 2>> pixels;

  for (double translation : opt.Translations)
  {
    const double c = translation / std::sqrt(3.0);
    const Point offset{ { c, c, c } };
    vtkSmartPointer<vtkPolyData> moved = Translated(mesh, offset);
    std::unique_ptr<Stage> stage[Stages] = { RenderStage(moved, scene, offset, true, opt),
      RenderStage(moved, scene, offset, false, opt),
      RenderStage(moved, scene, offset, true, opt, world) };
    if (!stage[0] || !stage[1] || !stage[2])
    {
      std::cerr << "vtkrtBenchTrade: no EGL context\n";
      return false;
    }
    const bool first = translation == opt.Translations.front();
    if (first)
    {
      pixels = PickPixels(*stage[0], opt.PrecisionGrid);
    }
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(moved);
    locator->BuildLocator();
    Picks picks[Methods] = { PickFromDepth(*stage[0], pixels), PickFromDepth(*stage[1], pixels),
      PickFromDepth(*stage[2], pixels), PickWithPicker(*stage[0], pixels, locator),
      PickWithPicker(*stage[0], pixels, nullptr) };
    if (first)
    {
      for (int m = 0; m < Methods; ++m)
      {
        refPicks[m] = picks[m];
      }
    }
    for (int m = 0; m < Methods; ++m)
    {
      PrecisionRow row;
      row.Method = names[m];
      row.Translation = translation;
      if (m < Stages)
      {
        const Stage& ref = refStage[m] ? *refStage[m] : *stage[m];
        row.ImageRMSE = ImageRMSE(ref.Image, stage[m]->Image);
        row.ImageDiff = ImageDifference(ref.Image, stage[m]->Image);
        const DepthError de = CompareDepth(ref, *stage[m]);
        row.DepthErr = de.Mean;
        row.Coverage = de.Coverage;
      }
      else
      {
        row.PickUs = 1e6 * picks[m].SecondsPerPick;
      }
      const PickError pe = ComparePicks(refPicks[m], picks[m]);
      row.PickMean = pe.Mean;
      row.PickMax = pe.Max;
      row.PickMiss = pe.Miss;
      row.PickExact = ComparePicks(refPicks[Locator], picks[m]).Mean;
      rows.push_back(row);
      std::printf("  translate %-8.0e %-52s rmse %7.2f  depth %.3g  pick %.3g (max %.3g, miss %.3g, "
                  "vs exact %.3g)\n",
        translation, names[m], row.ImageRMSE, row.DepthErr, pe.Mean, pe.Max, pe.Miss, row.PickExact);
    }
    // The pass's own picking: id mode, one ray per pixel on the GPU.
    for (int m : { Traced, World })
    {
      PrecisionRow idRow;
      idRow.Method = m == Traced ? "traced id (vtkRayTracePass IdMode)"
                                 : "traced id WORLD precision mode (IdMode)";
      idRow.Translation = translation;
      idRow.IdMismatch = IdMismatch(*stage[m], pixels, picks[Locator]);
      rows.push_back(idRow);
      std::printf("  translate %-8.0e %-52s cell ids differing from the locator's: %.3g\n",
        translation, idRow.Method.c_str(), idRow.IdMismatch);
    }

    if (first)
    {
      for (int m = 0; m < Stages; ++m)
      {
        refStage[m] = std::move(stage[m]);
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
// Plots

vtkrtPlot::Series Curve(const std::string& name, const std::vector<TradeRow>& rows,
  const std::string& knob, const std::string& method, double TradeRow::*x, double TradeRow::*y,
  double xScale = 1.0, double yScale = 1.0)
{
  vtkrtPlot::Series s;
  s.Name = name;
  for (const TradeRow& r : rows)
  {
    if (r.Knob == knob && (method.empty() || r.Method == method))
    {
      s.X.push_back(r.*x * xScale);
      s.Y.push_back(r.*y * yScale);
    }
  }
  return s;
}

bool WritePlots(const std::string& dir, const std::vector<TradeRow>& trade,
  const std::vector<PrecisionRow>& precision, double diagonal, std::vector<std::string>& written)
{
  bool ok = true;
  auto write = [&](const vtkrtPlot::Chart& chart, const std::string& name) {
    const std::string path = dir + "/" + name;
    if (vtkrtPlot::WritePNG(chart, path))
    {
      written.push_back(path);
    }
    else
    {
      ok = false;
    }
  };
  const double rel = 1.0 / diagonal;

  {
    vtkrtPlot::Chart c;
    c.Title = "Level of detail: frame time vs image error (reductions 0..0.99)";
    c.XLabel = "frame time (ms): first frame, and steady (fastest of the timed frames)";
    c.YLabel = "image RMSE vs full mesh (0-255; 0 drawn at 0.01)";
    c.LogX = true;
    c.LogY = true;
    c.LogFloor = 0.01;
    for (int m = 0; m < 2; ++m)
    {
      const std::string method = m == 0 ? "traced" : "raster";
      const std::string name = m == 0 ? "traced" : "raster";
      vtkrtPlot::Series steady = Curve(name + ", steady frame", trade, "lod", method,
        &TradeRow::SteadyMinS, &TradeRow::ImageRMSE, 1e3);
      vtkrtPlot::Series first = Curve(name + ", first frame", trade, "lod", method,
        &TradeRow::FirstFrameS, &TradeRow::ImageRMSE, 1e3);
      const int color[2][3] = { { 0, 114, 178 }, { 213, 94, 0 } };
      std::copy(color[m], color[m] + 3, steady.Color);
      std::copy(color[m], color[m] + 3, first.Color);
      first.Dashed = true;
      c.Curves.push_back(steady);
      c.Curves.push_back(first);
    }
    write(c, "trade_lod_frame.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "Level of detail: errors vs triangle count";
    c.XLabel = "triangles";
    c.YLabel = "error vs full mesh / diagonal";
    c.LogX = true;
    c.LogY = true;
    c.LogFloor = 1e-7;
    // The reference (reduction 0) has no error by definition: left out.
    std::vector<TradeRow> decimated;
    std::copy_if(trade.begin(), trade.end(), std::back_inserter(decimated),
      [](const TradeRow& r) { return r.Knob == "lod" && r.Value > 0.0; });
    c.Curves.push_back(Curve("surface distance, max", decimated, "lod", "traced",
      &TradeRow::Triangles, &TradeRow::GeomMax, 1.0, rel));
    c.Curves.push_back(Curve("surface distance, mean", decimated, "lod", "traced",
      &TradeRow::Triangles, &TradeRow::GeomMean, 1.0, rel));
    c.Curves.push_back(Curve("pick point (vtkBVHCellLocator), mean", decimated, "lod", "traced",
      &TradeRow::Triangles, &TradeRow::PickMean, 1.0, rel));
    c.Curves.push_back(Curve("depth (traced), mean", decimated, "lod", "traced",
      &TradeRow::Triangles, &TradeRow::DepthErr, 1.0, rel));
    write(c, "trade_lod_error.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "BVH builder: build time vs pick time (leaf size 1..16 along each curve)";
    c.XLabel = "build time (ms)";
    c.YLabel = "time per pick ray (us of thread CPU)";
    c.YFromZero = true;
    c.LogX = true;
    for (const char* q : { "FAST", "SAH", "HIGH" })
    {
      vtkrtPlot::Series s;
      s.Name = q;
      for (const TradeRow& r : trade)
      {
        if (r.Knob == "builder" && r.Setting.rfind(q, 0) == 0)
        {
          s.X.push_back(1e3 * r.BuildS);
          s.Y.push_back(r.PickUs);
        }
      }
      c.Curves.push_back(s);
    }
    write(c, "trade_builder.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "vtkRayTracePass BuildQuality: first frame vs steady frame";
    c.XLabel = "first frame (ms): BVH build, upload, shader compile, trace";
    c.YLabel = "steady frame (ms, fastest of the timed frames)";
    c.XFromZero = true;
    c.YFromZero = true;
    for (const char* q : { "FAST", "SAH", "HIGH" })
    {
      vtkrtPlot::Series s;
      s.Name = q;
      for (const TradeRow& r : trade)
      {
        if (r.Knob == "pass builder" && r.Setting == q)
        {
          s.X.push_back(1e3 * r.FirstFrameS);
          s.Y.push_back(1e3 * r.SteadyMinS);
        }
      }
      c.Curves.push_back(s);
    }
    write(c, "trade_pass_builder.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "vtkRayTracePass knobs: steady frame time vs image error";
    c.XLabel = "steady frame (ms, fastest of the timed frames)";
    c.YLabel = "image RMSE vs the knob's best setting (0-255; 0 drawn at 0.01)";
    c.LogX = true;
    c.LogY = true;
    c.LogFloor = 0.01;
    const char* knobs[][2] = { { "pass samples per pixel", "samples per pixel 1..16" },
      { "pass max traversal steps", "max traversal steps 16..unlimited" },
      { "pass shadows", "shadows off/on" }, { "pass AO samples", "AO samples 0..16" } };
    for (const auto& k : knobs)
    {
      vtkrtPlot::Series s = Curve(k[1], trade, k[0], "", &TradeRow::SteadyMinS, &TradeRow::ImageRMSE, 1e3);
      // Reference first in the CSV; draw the curve in knob order.
      std::vector<size_t> order(s.X.size());
      for (size_t i = 0; i < order.size(); ++i)
      {
        order[i] = i;
      }
      vtkrtPlot::Series sorted = s;
      std::vector<double> values;
      for (const TradeRow& r : trade)
      {
        if (r.Knob == k[0])
        {
          values.push_back(r.Value == 0 && std::string(k[0]).find("steps") != std::string::npos ? 1e9 : r.Value);
        }
      }
      std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
      for (size_t i = 0; i < order.size(); ++i)
      {
        sorted.X[i] = s.X[order[i]];
        sorted.Y[i] = s.Y[order[i]];
      }
      c.Curves.push_back(sorted);
    }
    write(c, "trade_pass_knobs.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "Progressive accumulation (1 sample per frame): error vs frames";
    c.XLabel = "accumulated frames";
    c.YLabel = "image RMSE vs the most accumulated image (0-255)";
    c.LogX = true;
    c.LogY = true;
    c.LogFloor = 0.01;
    c.Legend = vtkrtPlot::LegendCorner::TopRight;
    for (const char* knob : { "pass accumulation", "pass accumulation (AO 1)" })
    {
      std::vector<TradeRow> shown;
      double perFrame = kNaN;
      for (const TradeRow& r : trade)
      {
        if (r.Knob == knob && r.Setting.find("reference") == std::string::npos)
        {
          shown.push_back(r);
          perFrame = r.SteadyMinS;
        }
      }
      char name[128];
      std::snprintf(name, sizeof(name), "%s, %.0f ms a frame",
        std::string(knob).find("AO") != std::string::npos ? "with 1 AO ray per frame"
                                                          : "anti-aliasing only",
        1e3 * perFrame);
      c.Curves.push_back(Curve(name, shown, knob, "", &TradeRow::Value, &TradeRow::ImageRMSE));
    }
    write(c, "trade_accumulation.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "vtkRayTracePass LeafSize (triangles per BVH leaf): frame times";
    c.XLabel = "leaf size (images identical for every size)";
    c.YLabel = "time (ms)";
    c.LogX = true;
    c.YFromZero = true;
    std::vector<TradeRow> leaves;
    std::copy_if(trade.begin(), trade.end(), std::back_inserter(leaves),
      [](const TradeRow& r) { return r.Knob == "pass leaf size"; });
    std::sort(leaves.begin(), leaves.end(),
      [](const TradeRow& a, const TradeRow& b) { return a.Value < b.Value; });
    c.Curves.push_back(Curve("steady frame (fastest)", leaves, "pass leaf size", "",
      &TradeRow::Value, &TradeRow::SteadyMinS, 1.0, 1e3));
    c.Curves.push_back(Curve("first frame (build, upload, compile, trace)", leaves,
      "pass leaf size", "", &TradeRow::Value, &TradeRow::FirstFrameS, 1.0, 1e3));
    write(c, "trade_pass_leaf.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "Shadows vs number of scene lights (directional and spot, alternately)";
    c.XLabel = "scene lights";
    c.YLabel = "steady frame (ms, fastest of the timed frames)";
    c.XFromZero = true;
    c.YFromZero = true;
    c.Legend = vtkrtPlot::LegendCorner::TopLeft;
    c.Curves.push_back(Curve("shadows off", trade, "pass shadow lights", "shadows off",
      &TradeRow::Value, &TradeRow::SteadyMinS, 1.0, 1e3));
    c.Curves.push_back(Curve("shadows on", trade, "pass shadow lights", "shadows on",
      &TradeRow::Value, &TradeRow::SteadyMinS, 1.0, 1e3));
    write(c, "trade_shadow_lights.png");
  }
  {
    vtkrtPlot::Chart c;
    c.Title = "Precision: pick error of a translated scene";
    c.XLabel = "translation of scene and camera (world units)";
    c.YLabel = "mean pick error vs untranslated / diagonal";
    c.LogX = true;
    c.LogY = true;
    c.LogFloor = 1e-18;
    std::vector<std::string> methods;
    for (const PrecisionRow& r : precision)
    {
      if (std::isfinite(r.PickMean) &&
        std::find(methods.begin(), methods.end(), r.Method) == methods.end())
      {
        methods.push_back(r.Method);
      }
    }
    for (const std::string& m : methods)
    {
      vtkrtPlot::Series s;
      s.Name = m;
      for (const PrecisionRow& r : precision)
      {
        if (r.Method == m && r.Translation > 0.0)
        {
          s.X.push_back(r.Translation);
          s.Y.push_back(r.PickMean * rel);
        }
      }
      c.Curves.push_back(s);
    }
    write(c, "precision_pick.png");

    vtkrtPlot::Chart im;
    im.Title = "Precision: image error of a translated scene";
    im.XLabel = "translation of scene and camera (world units)";
    im.YLabel = "image RMSE vs untranslated (0-255; 0 drawn at 0.01)";
    im.LogX = true;
    im.LogY = true;
    im.LogFloor = 0.01;
    const char* imageMethods[][2] = {
      { "traced depth (vtkRayTracePass)", "traced, camera-relative (default)" },
      { "raster depth (vtkPolyDataMapper)", "raster (vtkPolyDataMapper)" },
      { "traced depth WORLD precision mode (vtkRayTracePass)", "traced, WORLD (float world coordinates)" }
    };
    for (const auto& method : imageMethods)
    {
      vtkrtPlot::Series s;
      s.Name = method[1];
      for (const PrecisionRow& r : precision)
      {
        if (r.Method == method[0] && r.Translation > 0.0)
        {
          s.X.push_back(r.Translation);
          s.Y.push_back(r.ImageRMSE);
        }
      }
      im.Curves.push_back(s);
    }
    write(im, "precision_image.png");
  }
  return ok;
}

bool ParseArgs(int argc, char* argv[], Options& opt)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--quick")
    {
      opt.Quick = true;
    }
    else if (a == "--out" && i + 1 < argc)
    {
      opt.Out = argv[++i];
    }
    else if (a == "--mesh" && i + 1 < argc)
    {
      opt.Mesh = argv[++i];
    }
    else if (a == "--size" && i + 1 < argc)
    {
      opt.Size = std::max(32, std::atoi(argv[++i]));
    }
    else
    {
      std::cerr << "usage: vtkrtBenchTrade [--quick] [--out DIR] [--size PIXELS] "
                   "[--mesh FILE.ply|.obj|.stl|.vtp|generated]\n";
      return false;
    }
  }
  if (opt.Quick)
  {
    opt.Size = std::min(opt.Size, 128);
    opt.Frames = 2;
    opt.Repeats = 1;
    opt.PickGrid = 8;
    opt.PrecisionGrid = 6;
    opt.GeomSamples = 2000;
    opt.BuilderRays = 2000;
    opt.Ratios = { 0.0, 0.5, 0.9 };
    opt.Translations = { 0.0, 1e4, 1e8 };
    opt.Leaves = { 1, 4, 16 };
    if (opt.Mesh.empty())
    {
      opt.Mesh = "generated";
    }
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  Options opt;
  if (!ParseArgs(argc, argv, opt))
  {
    return 2;
  }
  const auto start = Clock::now();

  vtkSmartPointer<vtkPolyData> mesh;
  std::string meshName;
  if (opt.Mesh.empty())
  {
    const std::string bunny = vtkrtDataFile::Find("bunny.ply");
    opt.Mesh = bunny.empty() ? "generated" : bunny;
  }
  if (opt.Mesh == "generated")
  {
    mesh = BumpySphere(opt.Quick ? 70 : 320);
    meshName = "generated bumpy sphere";
  }
  else
  {
    if (!vtksys::SystemTools::FileExists(opt.Mesh))
    {
      std::cerr << "vtkrtBenchTrade: no mesh " << opt.Mesh << "\n";
      return 2;
    }
    const std::string ext =
      vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(opt.Mesh));
    vtkSmartPointer<vtkAlgorithm> reader;
    if (ext == ".ply")
    {
      auto r = vtkSmartPointer<vtkPLYReader>::New();
      r->SetFileName(opt.Mesh.c_str());
      reader = r;
    }
    else if (ext == ".obj")
    {
      auto r = vtkSmartPointer<vtkOBJReader>::New();
      r->SetFileName(opt.Mesh.c_str());
      reader = r;
    }
    else if (ext == ".stl")
    {
      auto r = vtkSmartPointer<vtkSTLReader>::New();
      r->SetFileName(opt.Mesh.c_str());
      reader = r;
    }
    else if (ext == ".vtp")
    {
      auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
      r->SetFileName(opt.Mesh.c_str());
      reader = r;
    }
    else
    {
      std::cerr << "vtkrtBenchTrade: " << opt.Mesh << ": not .ply, .obj, .stl or .vtp\n";
      return 2;
    }
    reader->Update();
    auto* read = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
    if (!read)
    {
      std::cerr << "vtkrtBenchTrade: could not read " << opt.Mesh << "\n";
      return 2;
    }
    mesh = DoubleTriangles(read);
    meshName = vtksys::SystemTools::GetFilenameName(opt.Mesh);
  }
  if (mesh->GetNumberOfCells() == 0)
  {
    std::cerr << "vtkrtBenchTrade: empty mesh\n";
    return 2;
  }
  vtksys::SystemTools::MakeDirectory(opt.Out);
  const Scene scene = MakeScene(mesh);
  std::printf("vtkrtBenchTrade: %s, %lld triangles, %dx%d px, %d smp threads, out %s%s\n",
    meshName.c_str(), static_cast<long long>(mesh->GetNumberOfCells()), opt.Size, opt.Size,
    vtkSMPTools::GetEstimatedNumberOfThreads(), opt.Out.c_str(), opt.Quick ? " (quick)" : "");

  // The first window and pass of the process pay one-time costs (EGL
  // display, driver start-up): pay them before anything is timed.
  {
    Options warm = opt;
    warm.Frames = 1;
    RenderStage(mesh, scene, Point{ { 0, 0, 0 } }, true, warm);
    RenderStage(mesh, scene, Point{ { 0, 0, 0 } }, false, warm);
  }

  std::vector<TradeRow> trade;
  std::vector<PrecisionRow> precision;
  using TradeSection = bool (*)(vtkPolyData*, const Scene&, const Options&, std::vector<TradeRow>&);
  const std::pair<const char*, TradeSection> sections[] = {
    { "builder (vtkBVHCellLocator, reference HIGH/leaf1)", RunBuilder },
    { "pass builder (vtkRayTracePass BuildQuality, reference HIGH)", RunPassBuilder },
    { "pass knobs (vtkRayTracePass, each against its best setting)", RunPassKnobs },
    { "shadows per scene light count (vtkRayTracePass)", RunShadowLights },
    { "progressive accumulation (vtkRayTracePass, 1 sample a frame)", RunAccumulation },
    { "level of detail (vtkOpenMeshDecimation, reference full mesh)", RunLOD },
  };
  for (const auto& section : sections)
  {
    std::printf("%s:\n", section.first);
    if (!section.second(mesh, scene, opt, trade))
    {
      return 1;
    }
  }
  std::printf("precision (scene translated, reference untranslated):\n");
  if (!RunPrecision(mesh, scene, opt, precision))
  {
    return 1;
  }

  bool ok = WriteTradeCSV(opt.Out + "/trade.csv", trade, scene.Diagonal);
  ok = WritePrecisionCSV(opt.Out + "/precision.csv", precision, scene.Diagonal) && ok;
  std::vector<std::string> plots;
  ok = WritePlots(opt.Out, trade, precision, scene.Diagonal, plots) && ok;
  std::printf("wrote %s/trade.csv, %s/precision.csv and %zu plots in %.1f s\n", opt.Out.c_str(),
    opt.Out.c_str(), plots.size(), Seconds(start, Clock::now()));
  return ok ? 0 : 1;
}
