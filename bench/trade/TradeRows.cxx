#include "TradeRows.h"

#include "TradeErrors.h"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace vtkrtTrade
{
namespace
{
/// A CSV cell: empty for NaN.
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
}

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
  row.ImageS = st.SteadyMinSeconds;
  row.ImageRMSE = ImageRMSE(ref.Image, st.Image);
  row.ImageDiff = ImageDifference(ref.Image, st.Image);
  return row;
}

bool WriteTradeCSV(const std::string& path, const std::vector<TradeRow>& rows, double diagonal)
{
  std::ofstream f(path);
  f << "knob,setting,method,value,triangles,prep_s,build_s,first_frame_s,steady_frame_s,steady_frame_min_s,pick_us,"
       "image_rmse,image_diff,depth_err,coverage_err,pick_err_mean,pick_err_max,pick_miss,"
       "geom_mean,geom_max,nodes,sah_cost,memory_mb,diagonal,image_s,exact_rmse,exact_diff,"
       "exact_depth_err,exact_coverage_err,exact_pick_mean,exact_pick_miss,steady_cpu_s\n";
  for (const TradeRow& r : rows)
  {
    f << r.Knob << ',' << r.Setting << ',' << r.Method << ',' << Cell(r.Value) << ','
      << Cell(r.Triangles) << ',' << Cell(r.PrepS) << ',' << Cell(r.BuildS) << ','
      << Cell(r.FirstFrameS) << ',' << Cell(r.SteadyFrameS) << ',' << Cell(r.SteadyMinS) << ',' << Cell(r.PickUs) << ','
      << Cell(r.ImageRMSE) << ',' << Cell(r.ImageDiff) << ',' << Cell(r.DepthErr) << ','
      << Cell(r.Coverage) << ',' << Cell(r.PickMean) << ',' << Cell(r.PickMax) << ','
      << Cell(r.PickMiss) << ',' << Cell(r.GeomMean) << ',' << Cell(r.GeomMax) << ','
      << Cell(r.Nodes) << ',' << Cell(r.SAHCost) << ',' << Cell(r.MemoryMB) << ','
      << Cell(diagonal) << ',' << Cell(r.ImageS) << ',' << Cell(r.ExactRMSE) << ','
      << Cell(r.ExactDiff) << ',' << Cell(r.ExactDepth) << ',' << Cell(r.ExactCoverage) << ','
      << Cell(r.ExactPickMean) << ',' << Cell(r.ExactPickMiss) << ',' << Cell(r.SteadyCpuS) << '\n';
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
}
