// vtkrtBenchFirstFrame: the first frame a VTK application draws, for
// vtkRayTracePass and for vtkPolyDataMapper, each in a process of its own.
// vtkrtBenchPass times both sides' first frames in one window, where raster
// reuses the program an earlier scene compiled and the pass (whose program
// follows the scene's features) often does not; an application that opens
// one mesh has neither. Here every first frame runs in a fresh process (this
// program again, with --child) after the window's warm-up, with the driver's
// shader disk cache (MESA_SHADER_CACHE_DIR, __GL_SHADER_DISK_CACHE_PATH)
// pointed at a new, empty folder: "cold", what a first run after installing
// pays; then the same again with that folder kept: "warm", what every later
// run of the same scene pays. Medians of --repeats runs, sides interleaved.
// usage: vtkrtBenchFirstFrame [--sizes 1024,..] [--meshes quad,N,..] [--repeats R]
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"
#include "vtkrtBenchScenes.h"
#include "vtkrtBenchTiming.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
/// What one child process measured, ms: the whole first frame, and the
/// pass's phases (extraction, triangulation, build, packing, upload, compile).
struct FirstFrame
{
  double Total = 0;
  double Phases[6] = { 0, 0, 0, 0, 0, 0 };
};

/// The scene `name` ("quad" or a triangle count) in `ren`, framed as
/// vtkrtBenchPass frames it.
bool AddScene(vtkRenderer* ren, const std::string& name)
{
  vtkNew<vtkPolyDataMapper> mapper;
  if (name == "quad")
  {
    vtkNew<vtkPlaneSource> plane;
    plane->Update();
    mapper->SetInputData(plane->GetOutput());
  }
  else if (std::atol(name.c_str()) > 0)
  {
    mapper->SetInputData(vtkrtBench::MeshOf(std::atol(name.c_str())));
  }
  else
  {
    return false;
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  ren->AddActor(actor);
  ren->ResetCamera();
  if (name == "quad")
  {
    ren->GetActiveCamera()->Zoom(3.0); // the quad covers the view
  }
  else
  {
    ren->GetActiveCamera()->Elevation(20);
  }
  ren->ResetCameraClippingRange();
  return true;
}

/// The child: one side's first frame of one scene, printed on one line.
int RunChild(const std::string& side, const std::string& scene, int size)
{
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  vtkNew<vtkEGLHeadlessRenderWindow> win;
  win->SetMultiSamples(0);
  win->SetSize(size, size);
  vtkrtBench::WarmUp(win);
  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.2, 0.2, 0.25);
  if (!AddScene(ren, scene))
  {
    std::cerr << "unknown scene " << scene << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkRayTracePass> pass;
  if (side == "pass")
  {
    ren->SetPass(pass);
  }
  win->AddRenderer(ren);
  const auto t0 = vtkrtBench::Clock::now();
  win->Render();
  win->WaitForCompletion();
  const double total = 1e3 * vtkrtBench::Seconds(t0, vtkrtBench::Clock::now());
  std::cout << "first " << total << ' ' << 1e3 * pass->GetLastExtractionSeconds() << ' '
            << 1e3 * pass->GetLastTriangulationSeconds() << ' ' << 1e3 * pass->GetLastBuildSeconds()
            << ' ' << 1e3 * pass->GetLastPackingSeconds() << ' '
            << 1e3 * pass->GetLastUploadSeconds() << ' '
            << 1e3 * pass->GetLastShaderCompileSeconds() << "\n";
  return EXIT_SUCCESS;
}

/// `text` as one word for /bin/sh.
std::string Quoted(const std::string& text)
{
  std::string out = "'";
  for (char c : text)
  {
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return out + "'";
}

/// Runs this program as a child measuring one first frame with the shader
/// disk cache in `cacheDir` (turned on, whatever the environment says);
/// false if it printed no measurement.
bool RunInChild(const std::string& self, const std::string& side, const std::string& scene,
  int size, const std::string& cacheDir, FirstFrame& out)
{
  const std::string command = "MESA_SHADER_CACHE_DIR=" + Quoted(cacheDir) +
    " MESA_SHADER_CACHE_DISABLE=false MESA_GLSL_CACHE_DISABLE=false" +
    " __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_PATH=" + Quoted(cacheDir) + " " +
    Quoted(self) + " --child " + Quoted(side) + " " + Quoted(scene) + " " +
    std::to_string(size);
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
  {
    return false;
  }
  bool found = false;
  char line[512];
  while (std::fgets(line, sizeof(line), pipe))
  {
    std::istringstream in(line);
    std::string word;
    if (in >> word && word == "first" && in >> out.Total)
    {
      for (double& p : out.Phases)
      {
        in >> p;
      }
      found = true;
    }
  }
  return pclose(pipe) == 0 && found;
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Options
{
  std::vector<int> Sizes = { 1024 };
  std::vector<std::string> Scenes = { "quad", "100000", "1000000" };
  int Repeats = 3;
};

/// The items of a comma-separated list.
std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ','))
  {
    if (!item.empty())
    {
      out.push_back(item);
    }
  }
  return out;
}

bool ParseArgs(int argc, char* argv[], Options& opt)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sizes" && i + 1 < argc)
    {
      opt.Sizes.clear();
      for (const std::string& s : SplitList(argv[++i]))
      {
        opt.Sizes.push_back(std::max(16, std::atoi(s.c_str())));
      }
    }
    else if (a == "--meshes" && i + 1 < argc)
    {
      opt.Scenes = SplitList(argv[++i]);
    }
    else if (a == "--repeats" && i + 1 < argc)
    {
      opt.Repeats = std::max(1, std::atoi(argv[++i]));
    }
    else
    {
      std::cerr << "usage: vtkrtBenchFirstFrame [--sizes 1024,..] [--meshes quad,N,..] "
                   "[--repeats R]\n";
      return false;
    }
  }
  return true;
}

/// A new, empty folder for a shader disk cache, removed with its contents.
struct CacheFolder
{
  std::string Path;
  CacheFolder()
  {
    std::string name = (std::filesystem::temp_directory_path() / "vtkrtBenchFirstFrame-XXXXXX").string();
    if (mkdtemp(name.data()))
    {
      this->Path = name;
    }
  }
  ~CacheFolder()
  {
    std::error_code ignored;
    if (!this->Path.empty())
    {
      std::filesystem::remove_all(this->Path, ignored);
    }
  }
  bool Empty() const
  {
    std::error_code ignored;
    return std::filesystem::is_empty(this->Path, ignored);
  }
};

/// Prints a scene's row: medians of the repeats. Each repeat gives each
/// side a new cache folder and runs four children, raster cold, pass cold,
/// raster warm, pass warm: every child of the run follows one of the other
/// side, as the memory a process finds free (how much of it the machine
/// has touched before) changes a large build's time.
bool MeasureScene(const std::string& self, const std::string& scene, int size, int repeats)
{
  std::vector<double> times[2][2]; // [pass?][warm?]
  std::vector<double> build;
  std::vector<double> compile;
  for (int r = 0; r < repeats; ++r)
  {
    const CacheFolder folders[2];
    if (folders[0].Path.empty() || folders[1].Path.empty())
    {
      std::cerr << "vtkrtBenchFirstFrame: cannot make a cache folder\n";
      return false;
    }
    for (int step = 0; step < 4; ++step)
    {
      const int side = step % 2; // 1: the pass
      const int warm = step / 2;
      FirstFrame frame;
      if (!RunInChild(self, side ? "pass" : "raster", scene, size, folders[side].Path, frame))
      {
        std::cerr << "vtkrtBenchFirstFrame: a child measuring " << scene << " failed\n";
        return false;
      }
      if (!warm && folders[side].Empty())
      {
        std::cout << "warning: the driver wrote no shader cache for " << scene
                  << ": its warm first frames are cold ones\n";
      }
      times[side][warm].push_back(frame.Total);
      if (side && !warm)
      {
        build.push_back(frame.Phases[1] + frame.Phases[2]);
        compile.push_back(frame.Phases[5]);
      }
    }
  }
  const double rc = Median(times[0][0]), rw = Median(times[0][1]);
  const double pc = Median(times[1][0]), pw = Median(times[1][1]);
  std::cout << std::left << std::setw(10) << scene << std::setw(6) << size << std::right
            << std::fixed << std::setprecision(1) << std::setw(11) << rc << std::setw(11) << pc
            << std::setw(7) << std::setprecision(2) << pc / rc << std::setprecision(1)
            << std::setw(13) << rw << std::setw(11) << pw << std::setw(7) << std::setprecision(2)
            << pw / rw << std::setprecision(1) << std::setw(13) << Median(build) << std::setw(10)
            << Median(compile) << std::endl;
  return true;
}
}

int main(int argc, char* argv[])
{
  if (argc == 5 && std::string(argv[1]) == "--child")
  {
    return RunChild(argv[2], argv[3], std::atoi(argv[4]));
  }
  Options opt;
  if (!ParseArgs(argc, argv, opt))
  {
    return EXIT_FAILURE;
  }
  std::error_code error;
  const std::string self = std::filesystem::read_symlink("/proc/self/exe", error).string();
  if (error)
  {
    std::cerr << "vtkrtBenchFirstFrame: cannot find its own executable\n";
    return EXIT_FAILURE;
  }
  std::cout << "vtkrtBenchFirstFrame: first frames in fresh processes, ms, medians of "
            << opt.Repeats << "; ratio = pass / raster; cold: empty shader disk cache, warm: "
            << "the cache the cold run filled; pass build = triangulation + BVH build, "
            << "compile = its link (cold)\n\n"
            << std::left << std::setw(10) << "scene" << std::setw(6) << "size" << std::right
            << std::setw(11) << "raster cold" << std::setw(11) << "pass cold" << std::setw(7)
            << "ratio" << std::setw(13) << "raster warm" << std::setw(11) << "pass warm"
            << std::setw(7) << "ratio" << std::setw(13) << "pass build" << std::setw(10)
            << "compile" << "\n";
  bool ok = true;
  for (int size : opt.Sizes)
  {
    for (const std::string& scene : opt.Scenes)
    {
      ok = MeasureScene(self, scene, size, opt.Repeats) && ok;
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
