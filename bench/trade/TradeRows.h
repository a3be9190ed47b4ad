// vtkrtBenchTrade's results: the rows of trade.csv and precision.csv and
// their writers.
#ifndef vtkrtTradeRows_h
#define vtkrtTradeRows_h

#include "TradeStage.h"

#include <string>
#include <vector>

namespace vtkrtTrade
{
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
  // Time to this image with the scene loaded: one steady frame, or k of
  // them for k accumulated frames.
  double ImageS = kNaN;
  double SteadyCpuS = kNaN; // process CPU (every llvmpipe thread) of a steady frame, median
  // Errors against the run's one reference, the EXACT preset's converged
  // image, depth and depth picks (see Reference in TradeSections.h).
  double ExactRMSE = kNaN, ExactDiff = kNaN, ExactDepth = kNaN, ExactCoverage = kNaN;
  double ExactPickMean = kNaN, ExactPickMiss = kNaN;
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
  double value, double triangles, const Stage& st, const Stage& ref);

/// Writes the rows as CSV (NaN cells empty), `diagonal` in every row;
/// false when the file could not be written.
bool WriteTradeCSV(const std::string& path, const std::vector<TradeRow>& rows, double diagonal);
bool WritePrecisionCSV(const std::string& path, const std::vector<PrecisionRow>& rows, double diagonal);
}

#endif
