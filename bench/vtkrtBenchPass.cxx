// vtkrtBenchPass: frame times of vtkRayTracePass against VTK's raster peers,
// measured in one run, in one EGL window, MultiSamples 0, malloc tuned for
// large buffers (the same for every side).
//   quad:      a full-screen quad (two triangles), pass vs vtkPolyDataMapper,
//              plain and with a 256x256 interpolated, repeated texture
//   triangles: pass vs vtkPolyDataMapper, 100k and 1M (4M with --large);
//              with --edges also with edge visibility and as a wireframe;
//              built with Embree 3, also vs the same camera rays cast by
//              Embree on every core (packets of 8, a facing-ratio shade)
//   spheres:   pass (analytic) vs vtkGlyph3DMapper (triangulated 16x16
//              spheres), RenderPointsAsSpheres and vtkOpenGLSphereMapper
//              impostors, 10k and 100k (1M with --large)
//   tubes:     with --tubes N,..: N segments of random polylines drawn as
//              tubes (RenderLinesAsTubes, LineWidth 4), pass vs vtkPolyDataMapper
// at 512x512 and 1024x1024, camera orbiting; the first frame (build, upload,
// compile) is reported separately. Ratios are peer time / pass time (> 1:
// the pass is faster); the cpu columns are process CPU time per steady frame
// (every llvmpipe thread counted), steadier than wall time on a shared machine.
//   dynamic (--dynamic N,..): a mesh of N triangles beside a small ball that
//              moves every frame, camera still, pass vs vtkPolyDataMapper
//   actors (--actors N,..): N actors sharing one vtkCubeSource (12
//              triangles), each placed and colored at random, pass (a
//              top-level tree over N instances) vs vtkPolyDataMapper
//   translucent (--translucent N,..): an opaque mesh of N triangles inside a
//              translucent shell of N triangles, pass vs vtkPolyDataMapper
//              with depth peeling (100 peels, occlusion ratio 0), and the pass
//              with the shell opaque (what compositing the layers costs)
// usage: vtkrtBenchPass [--large] [--frames N] [--sizes 512,1024] [--edges]
//          [--meshes quad,N,..] [--spheres N,..] [--peers glyphs,points,impostors]
//          [--translucent N,..] [--tubes N,..] [--dynamic N,..] [--actors N,..]
// (--meshes / --spheres replace the default counts, 0 skips that kind,
// "quad" in --meshes keeps the quad; the pass's first frame is also printed
// by phase: extraction, triangulation, BVH build, packing, upload, compile,
// and the wait for trees built in the background after it, untimed, before
// the steady frames; --peers picks the sphere peers, "none" times the pass alone)
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"
#ifdef VTKRT_HAVE_EMBREE
#include "vtkrtBenchEmbreeRays.h"
#endif
#include "vtkrtBenchScenes.h"
#include "vtkrtBenchTiming.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkImageData.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkOpenGLSphereMapper.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTexture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using vtkrtBench::Clock;
using vtkrtBench::MeshOf;
using vtkrtBench::WarmUp;

double Ms(Clock::time_point a, Clock::time_point b)
{
  return 1e3 * vtkrtBench::Seconds(a, b);
}

struct Timing
{
  double First = 0;
  double Steady = 0;
  double SteadyCpu = 0; ///< process CPU time per steady frame (all threads)
  /// The pass's first frame by phase, ms (GetLast...Seconds): extraction,
  /// triangulation, BVH build, packing, upload, shader compile.
  double Phases[6] = { 0, 0, 0, 0, 0, 0 };
  /// After the first frame, until the trees built in the background
  /// (vtkRayTracePass::BackgroundBuildThreshold) are ready, ms.
  double BackgroundWait = 0;
};

/// How a scene is framed, then moved each steady frame.
struct Camera
{
  std::function<void(vtkRenderer*)> Frame;
  std::function<void(vtkRenderer*, int frames)> Step;
};

/// The default: the whole scene in view from 20 degrees up, orbiting.
Camera Orbit()
{
  return { [](vtkRenderer* ren) {
            ren->ResetCamera();
            ren->GetActiveCamera()->Elevation(20);
          },
    [](vtkRenderer* ren, int frames) { ren->GetActiveCamera()->Azimuth(360.0 / frames); } };
}

/// Process CPU time in ms (vtkrtBench::ProcessSeconds).
double CpuMs()
{
  return 1e3 * vtkrtBench::ProcessSeconds();
}

/// `count` random sphere centers in a unit cube with radii and scalars, as
/// vertices (RenderPointsAsSpheres draws vertices).
vtkSmartPointer<vtkPolyData> SpheresOf(long count)
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(count);
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  radius->SetNumberOfTuples(count);
  vtkNew<vtkCellArray> verts;
  const double r = 0.5 / std::cbrt(static_cast<double>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    double p[3];
    for (double& c : p)
    {
      c = random->GetNextRangeValue(-0.5, 0.5);
    }
    points->SetPoint(i, p);
    radius->SetValue(i, static_cast<float>(r * random->GetNextRangeValue(0.5, 1.0)));
    verts->InsertNextCell(1, &i);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetVerts(verts);
  poly->GetPointData()->AddArray(radius);
  return poly;
}

/// Random walks in a unit cube, 100 segments each, `segments` in all, with
/// a point scalar along each.
vtkSmartPointer<vtkPolyData> PolylinesOf(long segments)
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(11);
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> scalar;
  vtkNew<vtkCellArray> lines;
  const long perLine = 100;
  const double step = 0.5 / std::sqrt(static_cast<double>(segments));
  for (long line = 0; line * perLine < segments; ++line)
  {
    double p[3];
    for (double& c : p)
    {
      c = random->GetNextRangeValue(-0.5, 0.5);
    }
    lines->InsertNextCell(perLine + 1);
    for (long k = 0; k <= perLine; ++k)
    {
      lines->InsertCellPoint(points->InsertNextPoint(p));
      scalar->InsertNextValue(static_cast<float>(k) / perLine);
      for (double& c : p)
      {
        c = std::max(-0.5, std::min(0.5, c + step * random->GetNextRangeValue(-1.0, 1.0)));
      }
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetLines(lines);
  poly->GetPointData()->SetScalars(scalar);
  return poly;
}

/// Renders `frames` orbit steps after a first frame; fresh renderer each time.
Timing Measure(vtkRenderWindow* win, const std::function<void(vtkRenderer*)>& setup, bool trace,
  int frames, const Camera& camera = Orbit())
{
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.2, 0.2, 0.25);
  setup(ren);
  camera.Frame(ren);
  ren->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  if (trace)
  {
    ren->SetPass(pass);
  }
  win->AddRenderer(ren);
  Timing t;
  auto t0 = Clock::now();
  win->Render();
  win->WaitForCompletion();
  t.First = Ms(t0, Clock::now());
  const double phases[6] = { pass->GetLastExtractionSeconds(), pass->GetLastTriangulationSeconds(),
    pass->GetLastBuildSeconds(), pass->GetLastPackingSeconds(), pass->GetLastUploadSeconds(),
    pass->GetLastShaderCompileSeconds() };
  for (int k = 0; k < 6; ++k)
  {
    t.Phases[k] = 1e3 * phases[k];
  }
  if (trace && pass->GetNumberOfBackgroundBuilds() > 0)
  {
    // Steady frames on the trees the pass keeps: a frame takes the ones
    // built in the background, untimed, as the raster side draws nothing
    // in the background either.
    t0 = Clock::now();
    pass->WaitForBackgroundBuilds();
    t.BackgroundWait = Ms(t0, Clock::now());
    win->Render();
    win->WaitForCompletion();
  }
  t0 = Clock::now();
  const double cpu0 = CpuMs();
  for (int i = 0; i < frames; ++i)
  {
    camera.Step(ren, frames);
    ren->ResetCameraClippingRange();
    win->Render();
  }
  win->WaitForCompletion();
  t.Steady = Ms(t0, Clock::now()) / frames;
  t.SteadyCpu = (CpuMs() - cpu0) / frames;
  win->RemoveRenderer(ren);
  ren->ReleaseGraphicsResources(win);
  return t;
}

void Row(
  const std::string& scene, int size, const std::string& peer, const Timing& p, const Timing& r)
{
  std::cout << std::left << std::setw(20) << scene << std::setw(6) << size << std::setw(28) << peer
            << std::right << std::fixed << std::setprecision(1) << std::setw(10) << r.Steady
            << std::setw(10) << p.Steady << std::setw(8) << std::setprecision(2)
            << r.Steady / p.Steady << std::setprecision(1) << std::setw(11) << r.First
            << std::setw(11) << p.First << std::setw(10) << r.SteadyCpu << std::setw(10)
            << p.SteadyCpu << std::setprecision(2) << std::setw(8) << r.SteadyCpu / p.SteadyCpu
            << std::endl; // rows appear as they are measured (long runs)
}
/// An actor of `mapper` in `ren`, returned for its property.
vtkActor* AddActor(vtkRenderer* ren, vtkMapper* mapper)
{
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  return actor;
}

struct Options
{
  bool Large = false;
  int Frames = 6;
  std::vector<int> Sizes = { 512, 1024 };
  std::vector<long> Meshes = { 100000, 1000000 };
  std::vector<long> SphereCounts = { 10000, 100000 };
  std::string Peers = "glyphs,points,impostors";
  std::vector<long> TubeSegments; ///< none unless --tubes
  bool Quad = true; ///< the full-screen quad (off with --meshes not naming it)
  std::vector<long> Translucent; ///< triangle counts of the translucent scene (none by default)
  std::vector<long> Dynamic;     ///< triangle counts of the moving-ball scene (none by default)
  std::vector<long> Actors;      ///< actor counts of the many-cubes scene (none by default)
  bool Edges = false; ///< meshes also with edge visibility and as wireframes
};

/// The positive numbers of a comma-separated list.
std::vector<long> ParseList(const char* text)
{
  std::vector<long> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ','))
  {
    if (std::atol(item.c_str()) > 0)
    {
      out.push_back(std::atol(item.c_str()));
    }
  }
  return out;
}

bool ParseArgs(int argc, char* argv[], Options& opt)
{
  std::vector<long> meshesArg, spheresArg;
  bool meshesGiven = false, spheresGiven = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--large")
    {
      opt.Large = true;
    }
    else if (a == "--edges")
    {
      opt.Edges = true;
    }
    else if (a == "--frames" && i + 1 < argc)
    {
      opt.Frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (a == "--meshes" && i + 1 < argc)
    {
      const std::string list = argv[++i];
      meshesArg = ParseList(list.c_str());
      meshesGiven = true;
      opt.Quad = list.find("quad") != std::string::npos;
    }
    else if (a == "--spheres" && i + 1 < argc)
    {
      spheresArg = ParseList(argv[++i]);
      spheresGiven = true;
    }
    else if (a == "--translucent" && i + 1 < argc)
    {
      opt.Translucent = ParseList(argv[++i]);
    }
    else if (a == "--dynamic" && i + 1 < argc)
    {
      opt.Dynamic = ParseList(argv[++i]);
    }
    else if (a == "--actors" && i + 1 < argc)
    {
      opt.Actors = ParseList(argv[++i]);
    }
    else if (a == "--tubes" && i + 1 < argc)
    {
      opt.TubeSegments = ParseList(argv[++i]);
    }
    else if (a == "--peers" && i + 1 < argc)
    {
      opt.Peers = argv[++i];
    }
    else if (a == "--sizes" && i + 1 < argc)
    {
      opt.Sizes.clear();
      std::stringstream list(argv[++i]);
      std::string item;
      while (std::getline(list, item, ','))
      {
        opt.Sizes.push_back(std::atoi(item.c_str()));
      }
    }
    else
    {
      std::cerr << "usage: " << argv[0]
                << " [--large] [--frames N] [--sizes 512,1024] [--edges] [--meshes quad,N,..] "
                   "[--spheres N,..]"
                   " [--peers glyphs,points,impostors] [--translucent N,..] [--tubes N,..] [--dynamic N,..]"
                   " [--actors N,..]\n";
      return false;
    }
  }
  if (opt.Large)
  {
    opt.Meshes.push_back(4000000);
    opt.SphereCounts.push_back(1000000);
  }
  if (meshesGiven)
  {
    opt.Meshes = meshesArg;
  }
  if (spheresGiven)
  {
    opt.SphereCounts = spheresArg;
  }
  return true;
}

void PrintHeader(vtkEGLHeadlessRenderWindow* win, int frames)
{
  std::cout << "vtkrtBenchPass: " << win->GetGLRenderer() << ", " << frames
            << " orbit frames after a first frame; times in ms; ratio = peer / "
               "pass\n\n";
  std::cout << std::left << std::setw(20) << "scene" << std::setw(6) << "size" << std::setw(28)
            << "peer" << std::right << std::setw(10) << "peer" << std::setw(10) << "pass"
            << std::setw(8) << "ratio" << std::setw(11) << "peer 1st" << std::setw(11) << "pass 1st"
            << std::setw(10) << "peer cpu" << std::setw(10) << "pass cpu" << std::setw(8)
            << "cpu rat"
            << "\n";
}

/// The pass's first frame by phase against raster's whole first frame.
void PhaseRow(std::ostream& out, const std::string& scene, int size, const Timing& p, const Timing& r)
{
  std::ostringstream os;
  os << std::left << std::setw(20) << scene << std::setw(6) << size << std::right
            << std::fixed << std::setprecision(1);
  double known = 0;
  for (double ms : p.Phases)
  {
    os << std::setw(9) << ms;
    known += ms;
  }
  os << std::setw(9) << p.First - known << std::setw(10) << p.First << std::setw(11) << r.First
     << std::setw(12) << p.BackgroundWait << "\n";
  out << os.str();
}

/// A 256x256 RGB texture, interpolated and repeated (4 x 4 over the quad).
vtkSmartPointer<vtkTexture> QuadTexture()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(256, 256, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* texels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int i = 0; i < 256 * 256; ++i)
  {
    texels[3 * i] = static_cast<unsigned char>(i % 256);
    texels[3 * i + 1] = static_cast<unsigned char>(i / 256);
    texels[3 * i + 2] = static_cast<unsigned char>(((i % 256) / 16 + (i / 4096)) % 2 ? 220 : 40);
  }
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOn();
  texture->RepeatOn();
  return texture;
}

/// A quad filling the view (two triangles): the per-pixel cost alone, then
/// with a texture (the cost of sampling it).
void RunQuad(vtkRenderWindow* win, int size, const Options& opt, std::ostream& phases)
{
  vtkNew<vtkPlaneSource> plane;
  plane->Update();
  vtkNew<vtkPolyData> tiled;
  tiled->DeepCopy(plane->GetOutput());
  vtkDataArray* tcoords = tiled->GetPointData()->GetTCoords();
  for (vtkIdType i = 0; i < tcoords->GetNumberOfTuples(); ++i)
  {
    tcoords->SetComponent(i, 0, 4.0 * tcoords->GetComponent(i, 0));
    tcoords->SetComponent(i, 1, 4.0 * tcoords->GetComponent(i, 1));
  }
  vtkSmartPointer<vtkTexture> texture = QuadTexture();
  bool textured = false;
  auto setup = [&](vtkRenderer* ren) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(textured ? tiled.Get() : plane->GetOutput());
    vtkActor* actor = AddActor(ren, mapper);
    actor->SetTexture(textured ? texture.Get() : nullptr);
  };
  // Facing the camera, zoomed until the quad covers the view at any roll.
  const Camera fill = { [](vtkRenderer* ren) {
                         ren->ResetCamera();
                         ren->GetActiveCamera()->Zoom(3.0);
                       },
    [](vtkRenderer* ren, int frames) { ren->GetActiveCamera()->Roll(360.0 / frames); } };
  for (bool withTexture : { false, true })
  {
    textured = withTexture;
    const std::string scene = withTexture ? "textured quad" : "full-screen quad";
    const Timing pass = Measure(win, setup, true, opt.Frames, fill);
    const Timing raster = Measure(win, setup, false, opt.Frames, fill);
    Row(scene, size, "vtkPolyDataMapper", pass, raster);
    PhaseRow(phases, scene, size, pass, raster);
  }
}

#ifdef VTKRT_HAVE_EMBREE
/// The same camera rays as the pass's orbit frames, cast by Embree 3 on
/// every core (vtkrtBenchEmbreeRays): a native CPU tracer's time for the
/// pixels; its "first frame" is its scene build.
Timing EmbreeFrames(vtkPolyData* mesh, int size, int frames)
{
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  AddActor(ren, mapper);
  const Camera orbit = Orbit();
  orbit.Frame(ren);
  const vtkrtBench::EmbreeTiming e =
    vtkrtBench::EmbreePrimaryRays(mesh, ren, size, size, frames, orbit.Step);
  Timing t;
  t.First = e.Build;
  t.Steady = e.Steady;
  t.SteadyCpu = e.SteadyCpu;
  return t;
}
#endif

/// Triangles: the pass against vtkPolyDataMapper; with --edges also with
/// edge visibility (1 pixel) and as a wireframe.
void RunMeshes(vtkRenderWindow* win, int size, const Options& opt, std::ostream& phases)
{
  const char* looks[] = { "k triangles", "k edges", "k wireframe" };
  for (long n : opt.Meshes)
  {
    auto mesh = MeshOf(n);
    for (int look = 0; look < (opt.Edges ? 3 : 1); ++look)
    {
      auto setup = [&](vtkRenderer* ren)
      {
        vtkNew<vtkPolyDataMapper> mapper;
        mapper->SetInputData(mesh);
        vtkActor* actor = AddActor(ren, mapper);
        actor->GetProperty()->SetEdgeVisibility(look == 1);
        actor->GetProperty()->SetEdgeColor(0.1, 0.1, 0.1);
        if (look == 2)
        {
          actor->GetProperty()->SetRepresentationToWireframe();
        }
      };
      const Timing pass = Measure(win, setup, true, opt.Frames);
      const Timing raster = Measure(win, setup, false, opt.Frames);
      const std::string scene = std::to_string(mesh->GetNumberOfCells() / 1000) + looks[look];
      Row(scene, size, "vtkPolyDataMapper", pass, raster);
      PhaseRow(phases, scene, size, pass, raster);
#ifdef VTKRT_HAVE_EMBREE
      if (look == 0)
      {
        Row(scene, size, "Embree 3 on the CPU", pass, EmbreeFrames(mesh, size, opt.Frames));
      }
#endif
    }
  }
}

/// A mesh of n triangles beside a small ball (a 16x16 sphere source) that
/// moves every frame, camera still: what a changing prop costs each frame
/// (the pass rebuilds the ball's BVH and writes its records only; raster
/// uploads the ball's buffers).
void RunDynamic(vtkRenderWindow* win, int size, const Options& opt)
{
  for (long n : opt.Dynamic)
  {
    auto mesh = MeshOf(n);
    vtkNew<vtkSphereSource> ball;
    ball->SetRadius(0.05);
    ball->SetThetaResolution(16);
    ball->SetPhiResolution(16);
    auto setup = [&](vtkRenderer* ren) {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(mesh);
      AddActor(ren, mapper);
      vtkNew<vtkPolyDataMapper> ballMapper;
      ballMapper->SetInputConnection(ball->GetOutputPort());
      AddActor(ren, ballMapper)->GetProperty()->SetColor(0.2, 0.4, 1.0);
    };
    int step = 0;
    const Camera moveBall{ [&](vtkRenderer* ren) {
                            ball->SetCenter(0.0, 0.0, 0.6);
                            ren->ResetCamera();
                          },
      [&](vtkRenderer*, int frames) {
        const double a = 6.283185307179586 * (++step) / frames;
        ball->SetCenter(0.6 * std::sin(a), 0.0, 0.6 * std::cos(a));
      } };
    const Timing pass = Measure(win, setup, true, opt.Frames, moveBall);
    const Timing raster = Measure(win, setup, false, opt.Frames, moveBall);
    Row(std::to_string(mesh->GetNumberOfCells() / 1000) + "k + moving ball", size, "vtkPolyDataMapper", pass,
      raster);
  }
}

/// n actors sharing one cube (12 triangles) scattered in a box, each in a
/// color of its own: the pass's walk through a top-level tree of n
/// instances, raster's n draw calls.
void RunActors(vtkRenderWindow* win, int size, const Options& opt)
{
  for (long n : opt.Actors)
  {
    vtkNew<vtkCubeSource> cube;
    cube->Update();
    auto setup = [&](vtkRenderer* ren) {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(cube->GetOutput());
      vtkNew<vtkMinimalStandardRandomSequence> random;
      random->SetSeed(1);
      const auto next = [&random](double lo, double hi) {
        random->Next();
        return random->GetRangeValue(lo, hi);
      };
      for (long i = 0; i < n; ++i)
      {
        vtkActor* actor = AddActor(ren, mapper);
        actor->SetPosition(next(-20.0, 20.0), next(-20.0, 20.0), next(-20.0, 20.0));
        actor->GetProperty()->SetColor(next(0.2, 1.0), next(0.2, 1.0), next(0.2, 1.0));
      }
    };
    const Timing pass = Measure(win, setup, true, opt.Frames);
    const Timing raster = Measure(win, setup, false, opt.Frames);
    Row(std::to_string(n) + " cube actors", size, "vtkPolyDataMapper", pass, raster);
  }
}

/// An opaque mesh inside a translucent shell (opacity 0.4, both of n
/// triangles): the pass against raster with depth peeling, and against the
/// pass with the shell opaque.
void RunTranslucent(vtkRenderWindow* win, int size, const Options& opt, std::ostream& phases)
{
  for (long n : opt.Translucent)
  {
    auto mesh = MeshOf(n);
    double shellOpacity = 0.4;
    auto setup = [&](vtkRenderer* ren) {
      ren->SetUseDepthPeeling(true);
      ren->SetMaximumNumberOfPeels(100);
      ren->SetOcclusionRatio(0.0);
      vtkNew<vtkPolyDataMapper> inner;
      inner->SetInputData(mesh);
      AddActor(ren, inner)->SetScale(0.6);
      vtkNew<vtkPolyDataMapper> shell;
      shell->SetInputData(mesh);
      vtkActor* actor = AddActor(ren, shell);
      actor->GetProperty()->SetOpacity(shellOpacity);
      actor->GetProperty()->SetColor(0.4, 0.6, 1.0);
    };
    const Timing pass = Measure(win, setup, true, opt.Frames);
    const Timing raster = Measure(win, setup, false, opt.Frames);
    shellOpacity = 1.0;
    const Timing opaque = Measure(win, setup, true, opt.Frames);
    const std::string scene = std::to_string(mesh->GetNumberOfCells() / 1000) + "k in a shell";
    Row(scene, size, "vtkPolyDataMapper, peeling", pass, raster);
    Row(scene, size, "pass, shell opaque", pass, opaque);
    PhaseRow(phases, scene, size, pass, raster);
  }
}

/// Spheres: the pass against the sphere peers opt.Peers names.
void RunSpheres(vtkRenderWindow* win, int size, const Options& opt)
{
  auto wants = [&](const std::string& peer) { return opt.Peers.find(peer) != std::string::npos; };
  const int frames = opt.Frames;
  for (long n : opt.SphereCounts)
  {
    auto spheres = SpheresOf(n);
    auto glyphs = [&](int resolution)
    {
      return [&, resolution](vtkRenderer* ren)
      {
        vtkNew<vtkSphereSource> source;
        source->SetThetaResolution(resolution);
        source->SetPhiResolution(resolution);
        source->SetRadius(1.0);
        vtkNew<vtkGlyph3DMapper> mapper;
        mapper->SetInputData(spheres);
        mapper->SetSourceConnection(source->GetOutputPort());
        mapper->SetScaleArray("radius");
        mapper->SetScaleModeToScaleByMagnitude();
        AddActor(ren, mapper);
      };
    };
    auto points = [&](vtkRenderer* ren)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(spheres);
      vtkActor* actor = AddActor(ren, mapper);
      actor->GetProperty()->SetRenderPointsAsSpheres(true);
      actor->GetProperty()->SetPointSize(static_cast<float>(size) / 100.0f);
    };
    auto impostors = [&](vtkRenderer* ren)
    {
      vtkNew<vtkOpenGLSphereMapper> mapper;
      mapper->SetInputData(spheres);
      mapper->SetScaleArray("radius");
      AddActor(ren, mapper);
    };
    const std::string scene = std::to_string(n / 1000) + "k spheres";
    const Timing pass = Measure(win, glyphs(16), true, frames);
    if (opt.Peers == "none")
    {
      Row(scene, size, "(pass alone)", pass, pass);
    }
    const struct
    {
      const char* Key;
      const char* Name;
      std::function<void(vtkRenderer*)> Setup;
      int Frames;
    } peers[] = {
      // Triangulated glyphs are slow at 100k+: fewer frames there.
      { "glyphs", "vtkGlyph3DMapper 16x16", glyphs(16), n > 20000 ? 2 : frames },
      { "points", "RenderPointsAsSpheres", points, frames },
      { "impostors", "vtkOpenGLSphereMapper", impostors, frames },
    };
    for (const auto& peer : peers)
    {
      if (wants(peer.Key))
      {
        const Timing timing = Measure(win, peer.Setup, false, peer.Frames);
        Row(scene, size, peer.Name, pass, timing);
      }
    }
  }
}
/// Lines drawn as tubes: the pass against vtkPolyDataMapper's tubes.
void RunTubes(vtkRenderWindow* win, int size, const Options& opt, std::ostream& phases)
{
  for (long n : opt.TubeSegments)
  {
    auto lines = PolylinesOf(n);
    auto setup = [&](vtkRenderer* ren)
    {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(lines);
      mapper->SetScalarRange(0.0, 1.0);
      vtkActor* actor = AddActor(ren, mapper);
      actor->GetProperty()->SetRenderLinesAsTubes(true);
      actor->GetProperty()->SetLineWidth(4.0f);
    };
    const Timing pass = Measure(win, setup, true, opt.Frames);
    const Timing raster = Measure(win, setup, false, opt.Frames);
    const std::string scene = std::to_string(n / 1000) + "k tube segments";
    Row(scene, size, "vtkPolyDataMapper tubes", pass, raster);
    PhaseRow(phases, scene, size, pass, raster);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  Options opt;
  if (!ParseArgs(argc, argv, opt))
  {
    return EXIT_FAILURE;
  }
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  vtkNew<vtkEGLHeadlessRenderWindow> win;
  win->SetMultiSamples(0);
  win->SetAlphaBitPlanes(opt.Translucent.empty() ? 0 : 1); // depth peeling needs them
  win->SetSize(64, 64);
  win->Render();
  PrintHeader(win, opt.Frames);
  for (int size : opt.Sizes)
  {
    win->SetSize(size, size);
    WarmUp(win);
    std::ostringstream phases;
    if (opt.Quad)
    {
      RunQuad(win, size, opt, phases);
    }
    RunMeshes(win, size, opt, phases);
    RunSpheres(win, size, opt);
    RunTranslucent(win, size, opt, phases);
    RunTubes(win, size, opt, phases);
    RunDynamic(win, size, opt);
    RunActors(win, size, opt);
    if (!phases.str().empty())
    {
      std::cout << "\nfirst frame by phase, ms (pass; rest: drawing and what VTK does around it; "
                   "in one window after the scenes before it: an application's first frames "
                   "are vtkrtBenchFirstFrame's):\n"
                << std::left << std::setw(26) << "scene" << std::right << std::setw(9) << "extract"
                << std::setw(9) << "triang" << std::setw(9) << "build" << std::setw(9) << "pack"
                << std::setw(9) << "upload" << std::setw(9) << "compile" << std::setw(9) << "rest"
                << std::setw(10) << "pass 1st" << std::setw(11) << "raster 1st" << std::setw(12)
                << "bg build" << "\n"
                << phases.str() << "\n";
    }
  }
  return EXIT_SUCCESS;
}
