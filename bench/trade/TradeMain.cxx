// vtkrtBenchTrade: the speed/accuracy trade of vtkrt's knobs, measured in
// one run on one mesh. Each knob is a section (TradeSections.h says what
// each measures, one file each): the locator's and the pass's BVH builder,
// the pass's shading and sampling knobs, shadows per light count,
// progressive accumulation, level of detail (decimation, traced and
// raster, and the renderer knob), precision far from the origin.
//
// Output: DIR/trade.csv, DIR/precision.csv and PNG plots in DIR (default
// ./results). A timing never decides anything here beyond being reported.
//
// Usage: vtkrtBenchTrade [--quick] [--out DIR] [--size PIXELS]
//                        [--mesh FILE.ply|.obj|.stl|.vtp|generated]
// The default mesh is bunny.ply from $VTKRT_DATA_DIR or the project's data/
// (vtkrtDataFile.h); --quick defaults to the generated one.
#include "TradeMesh.h"
#include "TradeSections.h"

#include "vtkrtDataFile.h"

#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
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
    return BumpySphere(opt.Quick ? 70 : 320);
  }
  name = vtksys::SystemTools::GetFilenameName(opt.Mesh);
  return ReadMesh(opt.Mesh);
}

/// Every section in turn, printing its title first; false when one failed.
bool RunSections(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  std::vector<TradeRow>& trade, std::vector<PrecisionRow>& precision)
{
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
      return false;
    }
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
