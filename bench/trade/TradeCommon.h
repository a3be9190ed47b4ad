// vtkrtBenchTrade's common ground: the run's options, the clocks, a point
// type and the NaN that marks a value not measured.
#ifndef vtkrtTradeCommon_h
#define vtkrtTradeCommon_h

#include "vtkrtBenchTiming.h"

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace vtkrtTrade
{
using vtkrtBench::Clock;
using vtkrtBench::Seconds;
using vtkrtBench::ThreadSeconds;
using Point = std::array<double, 3>;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Options
{
  bool Quick = false;
  std::string Out = "results";
  std::string Mesh; // empty: bunny.ply (vtkrtDataFile) when found, else generated
  int Size = 384;
  int Triangles = 0;     // > 0: the generated mesh with about this many triangles
  std::vector<std::string> Sections; // empty: all; else these (names in TradeMain.cxx)
  int ReferenceFrames = 32; // frames the EXACT reference accumulates (presets: the still frames)
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

/// The middle value (the upper one of an even count); NaN when empty.
double Median(std::vector<double> v);

/// Says on stderr that no EGL context could be made; returns false, a
/// section's failure.
bool NoContext();
}

#endif
