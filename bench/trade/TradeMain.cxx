// vtkrtBenchTrade: the speed/accuracy trade of vtkrt's knobs, measured in
// one run on one mesh. Each knob is a section (TradeSections.h says what
// each measures, one file each): the locator's and the pass's BVH builder,
// the pass's shading and sampling knobs, shadows per light count,
// progressive accumulation, level of detail (decimation, traced and
// raster, and the renderer knob), precision far from the origin.
//
// The quality presets run first: EXACT's converged image is the one
// reference every traced setting is also measured against.
//
// Output: DIR/trade.csv, DIR/precision.csv and PNG plots in DIR (default
// ./results). A timing never decides anything here beyond being reported.
//
// Usage: vtkrtBenchTrade [--quick] [--out DIR] [--size PIXELS]
//                        [--mesh FILE.ply|.obj|.stl|.vtp|generated]
//                        [--triangles N] [--frames N] [--sections a,b,..]
// The default mesh is bunny.ply from $VTKRT_DATA_DIR or the project's data/
// (vtkrtDataFile.h); --quick defaults to the generated one; --triangles N
// generates one of about N triangles. --frames: the still frames of the
// presets (and of the reference). --sections: only these of builder,
// passbuilder, knobs, shadows, accumulation, lod, precision (the presets
// always run: "--sections presets" runs them alone).
#include "TradeMesh.h"
#include "TradeSections.h"

#include "vtkrtDataFile.h"

#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <utility>

namespace vtkrtTrade
{
namespace
{
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
    else if (a == "--triangles" && i + 1 < argc)
    {
      opt.Triangles = std::max(100, std::atoi(argv[++i]));
      opt.Mesh = "generated";
    }
    else if (a == "--frames" && i + 1 < argc)
    {
      opt.ReferenceFrames = std::max(2, std::atoi(argv[++i]));
    }
    else if (a == "--sections" && i + 1 < argc)
    {
      std::stringstream list(argv[++i]);
      for (std::string name; std::getline(list, name, ',');)
      {
        opt.Sections.push_back(name);
      }
    }
    else
    {
      std::cerr << "usage: vtkrtBenchTrade [--quick] [--out DIR] [--size PIXELS] "
                   "[--mesh FILE.ply|.obj|.stl|.vtp|generated] [--triangles N] [--frames N] "
                   "[--sections presets,builder,passbuilder,knobs,shadows,accumulation,lod,precision]\n";
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
    opt.ReferenceFrames = std::min(opt.ReferenceFrames, 8);
    if (opt.Mesh.empty())
    {
      opt.Mesh = "generated";
    }
  }
  return true;
}

/// The mesh of the run (opt.Mesh: a file, "generated", or empty for the
/// bunny) and its name; nullptr, with a message, when it cannot be had.
vtkSmartPointer<vtkPolyData> LoadMesh(Options& opt, std::string& name)
{
  if (opt.Mesh.empty())
  {
    const std::string bunny = vtkrtDataFile::Find("bunny.ply");
    opt.Mesh = bunny.empty() ? "generated" : bunny;
  }
  if (opt.Mesh == "generated")
  {
    name = "generated bumpy sphere";
    // A sphere source of resolution r has about 2 r^2 triangles.
    const int res = opt.Triangles > 0 ? static_cast<int>(std::sqrt(0.5 * opt.Triangles) + 0.5)
                                      : (opt.Quick ? 70 : 320);
    return BumpySphere(res);
  }
  name = vtksys::SystemTools::GetFilenameName(opt.Mesh);
  return ReadMesh(opt.Mesh);
}

bool Selected(const Options& opt, const std::string& name)
{
  return opt.Sections.empty() ||
    std::find(opt.Sections.begin(), opt.Sections.end(), name) != opt.Sections.end();
}

/// The presets (which make the reference), then every selected section in
/// turn, printing its title first; false when one failed.
bool RunSections(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  std::vector<TradeRow>& trade, std::vector<PrecisionRow>& precision)
{
  std::printf("quality presets (vtkRayTracePass, reference EXACT after %d still frames):\n",
    std::max(2, opt.ReferenceFrames));
  Reference exact;
  if (!RunPresets(mesh, scene, opt, exact, trade))
  {
    return false;
  }
  struct Section
  {
    const char* Name;
    const char* Title;
    TradeSection Run;
  };
  const Section sections[] = {
    { "builder", "builder (vtkBVHCellLocator, reference HIGH/leaf1)", RunBuilder },
    { "passbuilder", "pass builder (vtkRayTracePass BuildQuality, reference HIGH)", RunPassBuilder },
    { "knobs", "pass knobs (vtkRayTracePass, each against its best setting)", RunPassKnobs },
    { "shadows", "shadows per scene light count (vtkRayTracePass)", RunShadowLights },
    { "accumulation", "progressive accumulation (vtkRayTracePass, 1 sample a frame)", RunAccumulation },
    { "lod", "level of detail (vtkOpenMeshDecimation, reference full mesh)", RunLOD },
  };
  for (const Section& section : sections)
  {
    if (!Selected(opt, section.Name))
    {
      continue;
    }
    std::printf("%s:\n", section.Title);
    if (!section.Run(mesh, scene, opt, exact, trade))
    {
      return false;
    }
  }
  if (!Selected(opt, "precision"))
  {
    return true;
  }
  std::printf("precision (scene translated, reference untranslated):\n");
  return RunPrecision(mesh, scene, opt, precision);
}
}
}

int main(int argc, char* argv[])
{
  using namespace vtkrtTrade;
  vtkEGLHeadlessRenderWindow::TuneMallocForLargeBuffers();
  std::setvbuf(stdout, nullptr, _IOLBF, 0); // each line as it comes, also into a file
  Options opt;
  if (!ParseArgs(argc, argv, opt))
  {
    return 2;
  }
  const auto start = Clock::now();

  std::string meshName;
  vtkSmartPointer<vtkPolyData> mesh = LoadMesh(opt, meshName);
  if (!mesh)
  {
    return 2;
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
  if (!RunSections(mesh, scene, opt, trade, precision))
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
