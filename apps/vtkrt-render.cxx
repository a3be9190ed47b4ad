// vtkrt-render: renders a mesh file or the demo scene headless (EGL) to a PNG,
// rasterized by VTK or ray traced by vtkRayTracePass, and reports timings.
// Run with --help for the options.
#include "vtkEGLHeadlessRenderWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellPicker.h"
#include "vtkDataSet.h"
#include "vtkGenericDataObjectReader.h"
#include "vtkGeometryFilter.h"
#include "vtkLogger.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkOutputWindow.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtksys/SystemTools.hxx"

#include "vtkrt/core/Sphere.h"
#include "vtkrtDemoGlyphs.h"

#ifdef VTKRT_HAVE_RAYTRACE_PASS
#include "vtkRayTracePass.h"
#endif
#ifdef VTKRT_HAVE_BVH_LOCATOR
#include "vtkBVHCellLocator.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// Exit codes.
constexpr int ExitOk = 0;
constexpr int ExitRuntimeError = 1; // unreadable input, no GL context, cannot write
constexpr int ExitUsage = 2;        // wrong arguments
constexpr int ExitUnavailable = 3;  // a mode this build does not have

const char* const Usage =
  R"(usage: vtkrt-render [options] (--demo | MESH_FILE)

Renders a mesh (.vtp .vtk .ply .obj .stl) or the built-in demo scene (a mesh
plus sphere glyphs) headless through EGL and writes a PNG.

  --demo               render the demo scene (bunny + sphere glyphs)
  --size WxH           image size in pixels (default 800x600)
  --azimuth DEG        orbit the camera about the view up (default 30)
  --elevation DEG      orbit the camera up/down (default 20)
  --output FILE        PNG to write (default vtkrt-render.png)
  --mode raster|raytrace
                       VTK's rasterizer (default) or the vtkrt ray tracer
  --samples N          samples per pixel (raster: MSAA samples; default 0)
  --frames N           orbit steps timed for the steady frame time (default 8;
                       0 skips them)
  --pick X Y           pick the pixel (X, Y) of the image (origin top left;
                       the ray through its centre) with vtkCellPicker; prints
                       the cell id and world point (or the glyph sphere hit)
  --help               this text

Exit status: 0 success, 1 runtime error (unreadable file, no EGL/GL context,
cannot write the image), 2 wrong arguments, 3 mode not available in this build.
)";

struct Options
{
  bool Demo = false;
  std::string MeshFile;
  int Width = 800;
  int Height = 600;
  double Azimuth = 30.0;
  double Elevation = 20.0;
  std::string Output = "vtkrt-render.png";
  std::string Mode = "raster";
  int Samples = 0;
  int Frames = 8;
  bool Pick = false;
  int PickX = 0;
  int PickY = 0;
};

// Thrown for wrong arguments: one message, exit status 2.
struct UsageError
{
  std::string Message;
};

bool ParseInt(const std::string& text, int& value)
{
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < -(1L << 30) || v > (1L << 30))
  {
    return false;
  }
  value = static_cast<int>(v);
  return true;
}

bool ParseDouble(const std::string& text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && std::isfinite(value);
}

Options ParseArguments(int argc, char* argv[], bool& help)
{
  Options opt;
  help = false;
  auto next = [&](int& i, const std::string& name) -> std::string {
    if (i + 1 >= argc)
    {
      throw UsageError{ name + " needs a value" };
    }
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h")
    {
      help = true;
      return opt;
    }
    else if (arg == "--demo")
    {
      opt.Demo = true;
    }
    else if (arg == "--size")
    {
      const std::string v = next(i, arg);
      const size_t x = v.find_first_of("xX");
      if (x == std::string::npos || !ParseInt(v.substr(0, x), opt.Width) ||
        !ParseInt(v.substr(x + 1), opt.Height) || opt.Width < 1 || opt.Height < 1 ||
        opt.Width > 16384 || opt.Height > 16384)
      {
        throw UsageError{ "--size expects WxH with 1 <= W, H <= 16384, e.g. 1024x768 (got '" + v +
          "')" };
      }
    }
    else if (arg == "--azimuth" || arg == "--elevation")
    {
      const std::string v = next(i, arg);
      if (!ParseDouble(v, arg == "--azimuth" ? opt.Azimuth : opt.Elevation))
      {
        throw UsageError{ arg + " expects a number of degrees (got '" + v + "')" };
      }
    }
    else if (arg == "--output" || arg == "-o")
    {
      opt.Output = next(i, arg);
      if (opt.Output.empty())
      {
        throw UsageError{ "--output expects a file name" };
      }
    }
    else if (arg == "--mode")
    {
      opt.Mode = next(i, arg);
      if (opt.Mode != "raster" && opt.Mode != "raytrace")
      {
        throw UsageError{ "--mode expects raster or raytrace (got '" + opt.Mode + "')" };
      }
    }
    else if (arg == "--samples")
    {
      const std::string v = next(i, arg);
      if (!ParseInt(v, opt.Samples) || opt.Samples < 0 || opt.Samples > 64)
      {
        throw UsageError{ "--samples expects an integer in [0, 64] (got '" + v + "')" };
      }
    }
    else if (arg == "--frames")
    {
      const std::string v = next(i, arg);
      if (!ParseInt(v, opt.Frames) || opt.Frames < 0 || opt.Frames > 10000)
      {
        throw UsageError{ "--frames expects an integer in [0, 10000] (got '" + v + "')" };
      }
    }
    else if (arg == "--pick")
    {
      const std::string x = next(i, arg);
      const std::string y = next(i, arg);
      if (!ParseInt(x, opt.PickX) || !ParseInt(y, opt.PickY))
      {
        throw UsageError{ "--pick expects two integer pixel coordinates X Y (got '" + x + "' '" +
          y + "')" };
      }
      opt.Pick = true;
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      throw UsageError{ "unknown option '" + arg + "'" };
    }
    else if (opt.MeshFile.empty())
    {
      opt.MeshFile = arg;
    }
    else
    {
      throw UsageError{ "only one mesh file can be given ('" + opt.MeshFile + "', then '" + arg +
        "')" };
    }
  }
  if (opt.Demo == !opt.MeshFile.empty())
  {
    throw UsageError{ opt.Demo ? "give either --demo or a mesh file, not both"
                               : "nothing to render: give a mesh file or --demo" };
  }
  if (opt.Pick &&
    (opt.PickX < 0 || opt.PickY < 0 || opt.PickX >= opt.Width || opt.PickY >= opt.Height))
  {
    throw UsageError{ "--pick " + std::to_string(opt.PickX) + " " + std::to_string(opt.PickY) +
      " is outside the " + std::to_string(opt.Width) + "x" + std::to_string(opt.Height) +
      " image" };
  }
  return opt;
}

// Records VTK's error/warning text while a file is read, so that a bad file
// gives one message of ours instead of a reader's stack of errors.
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);
  std::vector<std::string> Captured;

  // While capturing, VTK's text is kept here and vtkLogger's own copy on
  // stderr is muted; our one message replaces both.
  void StartCapture()
  {
    this->Captured.clear();
    this->Capturing = true;
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  void StopCapture()
  {
    if (this->Capturing)
    {
      this->Capturing = false;
      // VTK 9.1 cannot query the level; INFO is loguru's default.
      vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_INFO);
    }
  }
  void DisplayErrorText(const char* text) override { this->Handle(text); }
  void DisplayWarningText(const char* text) override { this->Handle(text); }
  void DisplayGenericWarningText(const char* text) override { this->Handle(text); }

private:
  bool Capturing = false;

  void Handle(const char* text)
  {
    if (this->Capturing)
    {
      this->Captured.emplace_back(text ? text : "");
    }
    else
    {
      this->Superclass::DisplayErrorText(text);
    }
  }
};
vtkStandardNewMacro(CapturingOutputWindow);

// The last line of VTK's "ERROR: In file, line N\nclass (ptr): message" text.
std::string MessageOf(const std::string& vtkText)
{
  std::string text = vtkText;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  const size_t nl = text.rfind('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  const size_t paren = line.find("): ");
  return paren == std::string::npos ? line : line.substr(paren + 3);
}

struct Failure
{
  std::string Message;
  int Code;
};

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, CapturingOutputWindow* output)
{
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    throw Failure{ "cannot read mesh '" + path + "': no such file", ExitRuntimeError };
  }
  if (!std::ifstream(path).good())
  {
    throw Failure{ "cannot read mesh '" + path + "': cannot open it", ExitRuntimeError };
  }
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  output->StartCapture();
  vtkSmartPointer<vtkDataObject> data;
  if (ext == ".vtp")
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    data = reader->GetOutputDataObject(0);
  }
  else if (ext == ".vtk")
  {
    vtkNew<vtkGenericDataObjectReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    data = reader->GetOutputDataObject(0);
  }
  else if (ext == ".ply")
  {
    vtkNew<vtkPLYReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    data = reader->GetOutputDataObject(0);
  }
  else if (ext == ".obj")
  {
    vtkNew<vtkOBJReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    data = reader->GetOutputDataObject(0);
  }
  else if (ext == ".stl")
  {
    vtkNew<vtkSTLReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    data = reader->GetOutputDataObject(0);
  }
  else
  {
    output->StopCapture();
    throw Failure{ "cannot read mesh '" + path + "': unknown extension '" + ext +
        "' (expected .vtp .vtk .ply .obj .stl)",
      ExitRuntimeError };
  }

  vtkSmartPointer<vtkPolyData> mesh = vtkPolyData::SafeDownCast(data);
  if (!mesh && vtkDataSet::SafeDownCast(data))
  {
    // A legacy .vtk grid: render its outer surface.
    vtkNew<vtkGeometryFilter> surface;
    surface->SetInputData(data);
    surface->Update();
    mesh = surface->GetOutput();
  }
  output->StopCapture();
  if (!output->Captured.empty())
  {
    throw Failure{ "cannot read mesh '" + path + "': " + MessageOf(output->Captured.front()),
      ExitRuntimeError };
  }
  if (!mesh || mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    throw Failure{ "cannot read mesh '" + path + "': it has no polygons to render",
      ExitRuntimeError };
  }
  return mesh;
}

vtkIdType CountTriangles(vtkPolyData* mesh)
{
  // A polygon or strip of n points is n - 2 triangles.
  vtkIdType triangles = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    for (vtkIdType i = 0; i < cells->GetNumberOfCells(); ++i)
    {
      const vtkIdType n = cells->GetCellSize(i);
      triangles += n >= 3 ? n - 2 : 0;
    }
  }
  return triangles;
}

std::string DemoDataDirectory()
{
  // An explicit override, the source tree this was built from, then an
  // installed layout next to the executable.
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("VTKRT_DATA_DIR"))
  {
    candidates.emplace_back(env);
  }
#ifdef VTKRT_SOURCE_DATA_DIR
  candidates.emplace_back(VTKRT_SOURCE_DATA_DIR);
#endif
  const std::string exeDir =
    vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::GetRealPath("/proc/self/exe"));
  candidates.emplace_back(exeDir + "/../share/vtkrt");
  for (const std::string& dir : candidates)
  {
    if (vtksys::SystemTools::FileExists(dir + "/bunny.vtp", true) &&
      vtksys::SystemTools::FileExists(dir + "/demo-spheres.vtp", true))
    {
      return dir;
    }
  }
  throw Failure{ "the demo scene's data (bunny.vtp, demo-spheres.vtp) was not found; set "
                 "VTKRT_DATA_DIR to the folder holding them",
    ExitRuntimeError };
}

struct Scene
{
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkPolyData> Mesh;       // the triangle mesh (picking locator input)
  vtkSmartPointer<vtkActor> MeshActor;
  vtkSmartPointer<vtkPolyData> SphereCentres; // glyph centres with a "radius" array
  vtkIdType Triangles = 0;
  vtkIdType Spheres = 0;
  std::string Description;
};

void AddMesh(Scene& scene, vtkPolyData* mesh, const double color[3])
{
  vtkSmartPointer<vtkPolyData> shaded = mesh;
  if (!mesh->GetPointData()->GetNormals())
  {
    // Shading normals for files without them: smooth, but split at sharp
    // edges (30 degrees) so boxes stay boxes. Cells keep their ids.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(mesh);
    normals->SplittingOn();
    normals->SetFeatureAngle(30.0);
    normals->ComputeCellNormalsOff();
    normals->Update();
    shaded = normals->GetOutput();
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(shaded);
  mapper->ScalarVisibilityOff();
  scene.MeshActor = vtkSmartPointer<vtkActor>::New();
  scene.MeshActor->SetMapper(mapper);
  scene.MeshActor->GetProperty()->SetColor(color[0], color[1], color[2]);
  scene.MeshActor->GetProperty()->SetSpecular(0.3);
  scene.MeshActor->GetProperty()->SetSpecularPower(30);
  scene.Renderer->AddActor(scene.MeshActor);
  scene.Mesh = shaded;
  scene.Triangles += CountTriangles(mesh);
}

void BuildDemo(Scene& scene, CapturingOutputWindow* output)
{
  const std::string dir = DemoDataDirectory();
  vtkSmartPointer<vtkPolyData> bunny = ReadMesh(dir + "/bunny.vtp", output);
  const double bunnyColor[3] = { 0.86, 0.82, 0.74 };
  AddMesh(scene, bunny, bunnyColor);

  // Sphere glyphs of the "radius" array, coloured by "scalar" (vtkrtDemoGlyphs.h).
  vtkNew<vtkXMLPolyDataReader> centresReader;
  centresReader->SetFileName((dir + "/demo-spheres.vtp").c_str());
  centresReader->Update();
  vtkPolyData* centres = centresReader->GetOutput();
  if (!centres || centres->GetNumberOfPoints() == 0 ||
    !centres->GetPointData()->GetArray("radius") || !centres->GetPointData()->GetArray("scalar"))
  {
    throw Failure{ "demo-spheres.vtp in '" + dir + "' lacks points or its radius/scalar arrays",
      ExitRuntimeError };
  }
  vtkSmartPointer<vtkActor> glyphActor = vtkrtDemo::NewGlyphActor(centres);
  scene.Renderer->AddActor(glyphActor);
  scene.Spheres = centres->GetNumberOfPoints();
  scene.SphereCentres = centres;
  scene.Description = "demo (" + dir + "/bunny.vtp + demo-spheres.vtp)";
}

// Puts the vtkrt ray tracer in charge of the renderer. Returns false when
// this build has no vtkRayTracePass.
bool UseRayTracing(vtkRenderer* renderer, const Options& opt)
{
#ifdef VTKRT_HAVE_RAYTRACE_PASS
  vtkNew<vtkRayTracePass> pass;
  renderer->SetPass(pass);
  (void)opt;
  return true;
#else
  (void)renderer;
  (void)opt;
  return false;
#endif
}

// Adds a BVH locator over the mesh to the picker when the build has one.
// Returns a description of what picks.
std::string PrepareLocator(vtkCellPicker* picker, vtkPolyData* mesh)
{
#ifdef VTKRT_HAVE_BVH_LOCATOR
  if (mesh)
  {
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(mesh);
    locator->BuildLocator();
    picker->AddLocator(locator);
    return "vtkCellPicker + vtkBVHCellLocator";
  }
#else
  (void)picker;
  (void)mesh;
#endif
  return "vtkCellPicker";
}

// The ray through a display pixel from the near to the far clipping plane.
struct PickRay
{
  vtkrt::core::Ray<double> Ray;
};

PickRay MakePickRay(vtkRenderer* renderer, double x, double y)
{
  double ends[2][3];
  for (int i = 0; i < 2; ++i)
  {
    renderer->SetDisplayPoint(x, y, i);
    renderer->DisplayToWorld();
    const double* w = renderer->GetWorldPoint();
    for (int k = 0; k < 3; ++k)
    {
      ends[i][k] = w[k] / w[3];
    }
  }
  const vtkrt::core::Vec3<double> a(ends[0][0], ends[0][1], ends[0][2]);
  const vtkrt::core::Vec3<double> b(ends[1][0], ends[1][1], ends[1][2]);
  return PickRay{ vtkrt::core::Ray<double>(a, b - a, 0.0, 1.0) };
}

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

double Milliseconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

int Run(const Options& opt)
{
  using Clock = std::chrono::steady_clock;
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  vtkNew<CapturingOutputWindow> output;
  vtkOutputWindow::SetInstance(output);

  if (opt.Mode == "raytrace")
  {
    vtkNew<vtkRenderer> probe;
    if (!UseRayTracing(probe, opt))
    {
      throw Failure{ "raytrace mode is not available in this build (vtkRayTracePass was not "
                     "built); use --mode raster",
        ExitUnavailable };
    }
  }

  // Fail before any work when the image cannot go where asked.
  const std::string outputDir = vtksys::SystemTools::GetFilenamePath(opt.Output);
  if (!outputDir.empty() && !vtksys::SystemTools::FileIsDirectory(outputDir))
  {
    throw Failure{ "cannot write '" + opt.Output + "': no directory '" + outputDir + "'",
      ExitRuntimeError };
  }

  const auto t0 = Clock::now();
  Scene scene;
  if (opt.Demo)
  {
    BuildDemo(scene, output);
  }
  else
  {
    const double color[3] = { 0.80, 0.82, 0.88 };
    AddMesh(scene, ReadMesh(opt.MeshFile, output), color);
    scene.Description = opt.MeshFile;
  }
  scene.Renderer->SetBackground(0.32, 0.34, 0.43);
  if (opt.Mode == "raytrace")
  {
    UseRayTracing(scene.Renderer, opt);
  }

  vtkNew<vtkEGLHeadlessRenderWindow> window;
  window->SetSize(opt.Width, opt.Height);
  // Explicit: VTK's default is 8 (llvmpipe clamps to 4) and MSAA costs a lot.
  window->SetMultiSamples(opt.Mode == "raster" ? opt.Samples : 0);
  window->AddRenderer(scene.Renderer);

  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  scene.Renderer->ResetCamera();
  camera->Azimuth(opt.Azimuth);
  camera->Elevation(opt.Elevation);
  camera->OrthogonalizeViewUp();
  FrameScene(scene.Renderer, FramingPoints(scene), static_cast<double>(opt.Width) / opt.Height);
  const auto t1 = Clock::now();

  // The first frame creates the context: a failure there becomes our one
  // message; anything else VTK says is passed on.
  output->StartCapture();
  window->Render();
  output->StopCapture();
  const auto t2 = Clock::now();
  if (!window->IsContextReady())
  {
    throw Failure{ output->Captured.empty() ? std::string("no usable EGL/OpenGL context")
                                            : MessageOf(output->Captured.front()),
      ExitRuntimeError };
  }
  for (const std::string& text : output->Captured)
  {
    std::cerr << text;
  }

  // Steady frames: orbit one full turn in opt.Frames steps, then return to
  // the requested view exactly.
  double steady = 0.0;
  if (opt.Frames > 0)
  {
    vtkNew<vtkCamera> saved;
    saved->DeepCopy(camera);
    const auto s0 = Clock::now();
    for (int i = 0; i < opt.Frames; ++i)
    {
      camera->Azimuth(360.0 / opt.Frames);
      scene.Renderer->ResetCameraClippingRange();
      window->Render();
    }
    steady = Milliseconds(s0, Clock::now()) / opt.Frames;
    camera->DeepCopy(saved);
    window->Render();
  }

  std::ostringstream pickReport;
  if (opt.Pick)
  {
    pickReport << std::setprecision(9);
    // Image rows run top down, VTK's display coordinates bottom up; the ray
    // goes through the pixel's centre, as the image's own rays do.
    const double x = opt.PickX + 0.5, y = opt.Height - 1 - opt.PickY + 0.5;
    vtkNew<vtkCellPicker> picker;
    picker->SetTolerance(0.0);
    const auto p0 = Clock::now();
    const std::string how = PrepareLocator(picker, scene.Mesh);
    const auto p1 = Clock::now();
    const bool meshHit = picker->Pick(x, y, 0.0, scene.Renderer) && picker->GetCellId() >= 0;
    const auto p2 = Clock::now();

    // Glyph spheres have no cells for vtkCellPicker: intersect the same pick
    // ray (near to far plane, t in [0, 1]) with them as analytic spheres,
    // with the core's kernel, as the ray tracer sees them.
    const PickRay ray = MakePickRay(scene.Renderer, x, y);
    double meshT = std::numeric_limits<double>::infinity();
    if (meshHit)
    {
      const double* p = picker->GetPickPosition();
      const vtkrt::core::Vec3<double> d = ray.Ray.dir;
      meshT = glm::dot(vtkrt::core::Vec3<double>(p[0], p[1], p[2]) - ray.Ray.org, d) / glm::dot(d, d);
    }
    vtkIdType sphereId = -1;
    double sphereT = meshT;
    if (scene.SphereCentres)
    {
      vtkDataArray* radius = scene.SphereCentres->GetPointData()->GetArray("radius");
      for (vtkIdType i = 0; i < scene.SphereCentres->GetNumberOfPoints(); ++i)
      {
        double c[3];
        scene.SphereCentres->GetPoint(i, c);
        double t;
        if (vtkrt::core::intersectRaySphere(ray.Ray, vtkrt::core::Vec3<double>(c[0], c[1], c[2]),
              radius->GetTuple1(i), t) &&
          t < sphereT)
        {
          sphereT = t;
          sphereId = i;
        }
      }
    }
    pickReport << "pick (" << opt.PickX << ", " << opt.PickY << "): ";
    if (sphereId >= 0)
    {
      const vtkrt::core::Vec3<double> p = ray.Ray.at(sphereT);
      pickReport << "sphere " << sphereId << " at world (" << p.x << ", " << p.y << ", " << p.z
                 << ") [analytic glyph sphere]";
    }
    else if (meshHit)
    {
      const double* p = picker->GetPickPosition();
      pickReport << "cell " << picker->GetCellId() << " at world (" << p[0] << ", " << p[1]
                 << ", " << p[2] << ")"
                 << (picker->GetActor() == scene.MeshActor ? " on the mesh" : "") << " [" << how
                 << "]";
    }
    else
    {
      pickReport << "nothing [" << how << "]";
    }
    pickReport << std::fixed << std::setprecision(2) << " (locator build "
               << Milliseconds(p0, p1) << " ms, mesh pick " << Milliseconds(p1, p2) << " ms)";
  }

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  output->StartCapture();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(opt.Output.c_str());
  writer->Write();
  output->StopCapture();
  if (!output->Captured.empty() || !vtksys::SystemTools::FileExists(opt.Output, true))
  {
    throw Failure{ "cannot write '" + opt.Output + "'" +
        (output->Captured.empty() ? std::string() : ": " + MessageOf(output->Captured.front())),
      ExitRuntimeError };
  }

  std::cout << std::fixed << std::setprecision(1);
  std::cout << "vtkrt-render: " << opt.Mode << " " << opt.Width << "x" << opt.Height
            << ", MultiSamples " << window->GetMultiSamples() << "\n"
            << "  scene:        " << scene.Description << "\n"
            << "  triangles:    " << scene.Triangles << "\n"
            << "  spheres:      " << scene.Spheres << "\n"
            << "  device:       " << window->GetGLRenderer() << " (" << window->GetGLVersion()
            << "; " << window->GetDeviceDescription() << ")\n"
            << "  scene build:  " << Milliseconds(t0, t1) << " ms (read + set up)\n"
            << "  first frame:  " << Milliseconds(t1, t2) << " ms (context, upload, build)\n";
  if (opt.Frames > 0)
  {
    std::cout << "  steady frame: " << steady << " ms (mean of " << opt.Frames << " orbit steps)\n";
  }
  if (opt.Mode == "raytrace" && opt.Samples > 0)
  {
    std::cout << "  note:         --samples applies to raster mode (MSAA); ignored\n";
  }
  if (opt.Pick)
  {
    std::cout << "  " << pickReport.str() << "\n";
  }
  std::cout << "  wrote " << opt.Output << "\n";
  return ExitOk;
}
} // namespace

int main(int argc, char* argv[])
{
  try
  {
    bool help = false;
    const Options opt = ParseArguments(argc, argv, help);
    if (help)
    {
      std::cout << Usage << "\nThis build: raytrace mode "
#ifdef VTKRT_HAVE_RAYTRACE_PASS
                << "available"
#else
                << "not available"
#endif
                << "; picking with vtkBVHCellLocator "
#ifdef VTKRT_HAVE_BVH_LOCATOR
                << "available"
#else
                << "not available"
#endif
                << ".\n";
      return ExitOk;
    }
    return Run(opt);
  }
  catch (const UsageError& e)
  {
    std::cerr << "vtkrt-render: " << e.Message << "\n(run vtkrt-render --help for the options)\n";
    return ExitUsage;
  }
  catch (const Failure& e)
  {
    std::cerr << "vtkrt-render: " << e.Message << "\n";
    return e.Code;
  }
}
