// vtkrtBenchTrade's plots: one function a chart, each drawn by vtkrtPlot.
#include "TradeSections.h"

#include "vtkrtPlot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vtkrtTrade
{
namespace
{
using vtkrtPlot::LegendCorner;
using vtkrtPlot::Linear;
using vtkrtPlot::LinearFromZero;
using vtkrtPlot::Log;
using vtkrtPlot::Series;
using vtkrtPlot::SeriesOf;
using Curves = std::vector<Series>;

/// The folder the charts go to: the paths written, and whether all were.
struct PlotFolder
{
  std::string Dir;
  std::vector<std::string>& Written;
  bool Ok = true;

  void Write(const std::string& name, const std::string& title, const vtkrtPlot::Axis& x,
    const vtkrtPlot::Axis& y, const Curves& curves, LegendCorner legend = LegendCorner::OutsideRight)
  {
    // A section left out of the run (--sections) leaves its charts empty.
    if (std::all_of(curves.begin(), curves.end(), [](const Series& s) { return s.X.empty(); }))
    {
      return;
    }
    const std::string path = this->Dir + "/" + name;
    if (vtkrtPlot::WritePNG(path, title, x, y, curves, legend))
    {
      this->Written.push_back(path);
    }
    else
    {
      this->Ok = false;
    }
  }
};

/// The rows of `knob` (and of `method` unless empty), `x` against `y`, each
/// field scaled.
Series Curve(const std::string& name, const std::vector<TradeRow>& rows, const std::string& knob,
  const std::string& method, double TradeRow::*x, double TradeRow::*y, double xScale = 1.0,
  double yScale = 1.0)
{
  return SeriesOf(
    name, rows,
    [&](const TradeRow& r) { return r.Knob == knob && (method.empty() || r.Method == method); },
    [&](const TradeRow& r) { return r.*x * xScale; }, [&](const TradeRow& r) { return r.*y * yScale; });
}

/// The rows of `knob` ordered by `key(row)`.
template <class Key>
std::vector<TradeRow> SortedRows(const std::vector<TradeRow>& trade, const std::string& knob, Key key)
{
  std::vector<TradeRow> rows;
  std::copy_if(trade.begin(), trade.end(), std::back_inserter(rows),
    [&](const TradeRow& r) { return r.Knob == knob; });
  std::stable_sort(rows.begin(), rows.end(),
    [&](const TradeRow& a, const TradeRow& b) { return key(a) < key(b); });
  return rows;
}

void PlotLODFrame(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  const int color[2][3] = { { 0, 114, 178 }, { 213, 94, 0 } };
  Curves curves;
  for (int m = 0; m < 2; ++m)
  {
    const std::string method = m == 0 ? "traced" : "raster";
    Series steady = Curve(method + ", steady frame", trade, "lod", method, &TradeRow::SteadyMinS,
      &TradeRow::ImageRMSE, 1e3);
    Series first = Curve(method + ", first frame", trade, "lod", method, &TradeRow::FirstFrameS,
      &TradeRow::ImageRMSE, 1e3);
    std::copy(color[m], color[m] + 3, steady.Color);
    std::copy(color[m], color[m] + 3, first.Color);
    first.Dashed = true;
    curves.push_back(steady);
    curves.push_back(first);
  }
  out.Write("trade_lod_frame.png", "Level of detail: frame time vs image error (reductions 0..0.99)",
    Log("frame time (ms): first frame, and steady (fastest of the timed frames)"),
    Log("image RMSE vs full mesh (0-255; 0 drawn at 0.01)", 0.01), curves);
}

void PlotLODError(PlotFolder& out, const std::vector<TradeRow>& trade, double diagonal)
{
  // The reference (reduction 0) has no error by definition: left out.
  auto decimated = [](const TradeRow& r) { return r.Knob == "lod" && r.Method == "traced" && r.Value > 0.0; };
  auto triangles = [](const TradeRow& r) { return r.Triangles; };
  const double rel = 1.0 / diagonal;
  auto relative = [rel](double TradeRow::*field) {
    return [rel, field](const TradeRow& r) { return r.*field * rel; };
  };
  out.Write("trade_lod_error.png", "Level of detail: errors vs triangle count", Log("triangles"),
    Log("error vs full mesh / diagonal", 1e-7),
    { SeriesOf("surface distance, max", trade, decimated, triangles, relative(&TradeRow::GeomMax)),
      SeriesOf("surface distance, mean", trade, decimated, triangles, relative(&TradeRow::GeomMean)),
      SeriesOf("pick point (vtkBVHCellLocator), mean", trade, decimated, triangles,
        relative(&TradeRow::PickMean)),
      SeriesOf("depth (traced), mean", trade, decimated, triangles, relative(&TradeRow::DepthErr)) });
}

void PlotBuilder(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  Curves curves;
  for (const std::string q : { "FAST", "SAH", "HIGH" })
  {
    curves.push_back(SeriesOf(
      q, trade, [&](const TradeRow& r) { return r.Knob == "builder" && r.Setting.rfind(q, 0) == 0; },
      [](const TradeRow& r) { return 1e3 * r.BuildS; }, [](const TradeRow& r) { return r.PickUs; }));
  }
  out.Write("trade_builder.png",
    "BVH builder: build time vs pick time (leaf size 1..16 along each curve)", Log("build time (ms)"),
    LinearFromZero("time per pick ray (us of thread CPU)"), curves);
}

void PlotPassBuilder(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  Curves curves;
  for (const std::string q : { "FAST", "SAH", "HIGH" })
  {
    curves.push_back(SeriesOf(
      q, trade, [&](const TradeRow& r) { return r.Knob == "pass builder" && r.Setting == q; },
      [](const TradeRow& r) { return 1e3 * r.FirstFrameS; },
      [](const TradeRow& r) { return 1e3 * r.SteadyMinS; }));
  }
  out.Write("trade_pass_builder.png", "vtkRayTracePass BuildQuality: first frame vs steady frame",
    LinearFromZero("first frame (ms): BVH build, upload, shader compile, trace"),
    LinearFromZero("steady frame (ms, fastest of the timed frames)"), curves);
}

void PlotPassKnobs(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  const char* knobs[][2] = { { "pass samples per pixel", "samples per pixel 1..16" },
    { "pass max traversal steps", "max traversal steps 16..unlimited" },
    { "pass shadows", "shadows off/on" }, { "pass AO samples", "AO samples 0..16" } };
  Curves curves;
  for (const auto& k : knobs)
  {
    // Reference first in the CSV; the curve in knob order (0 steps: unlimited).
    const bool steps = std::string(k[0]).find("steps") != std::string::npos;
    const std::vector<TradeRow> rows = SortedRows(trade, k[0],
      [steps](const TradeRow& r) { return r.Value == 0 && steps ? 1e9 : r.Value; });
    curves.push_back(Curve(k[1], rows, k[0], "", &TradeRow::SteadyMinS, &TradeRow::ImageRMSE, 1e3));
  }
  out.Write("trade_pass_knobs.png", "vtkRayTracePass knobs: steady frame time vs image error",
    Log("steady frame (ms, fastest of the timed frames)"),
    Log("image RMSE vs the knob's best setting (0-255; 0 drawn at 0.01)", 0.01), curves);
}

void PlotAccumulation(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  Curves curves;
  for (const std::string knob : { "pass accumulation", "pass accumulation (AO 1)" })
  {
    auto shown = [&](const TradeRow& r) {
      return r.Knob == knob && r.Setting.find("reference") == std::string::npos;
    };
    double perFrame = kNaN;
    for (const TradeRow& r : trade)
    {
      perFrame = shown(r) ? r.SteadyMinS : perFrame;
    }
    char name[128];
    std::snprintf(name, sizeof(name), "%s, %.0f ms a frame",
      knob.find("AO") != std::string::npos ? "with 1 AO ray per frame" : "anti-aliasing only",
      1e3 * perFrame);
    curves.push_back(SeriesOf(name, trade, shown, [](const TradeRow& r) { return r.Value; },
      [](const TradeRow& r) { return r.ImageRMSE; }));
  }
  out.Write("trade_accumulation.png", "Progressive accumulation (1 sample per frame): error vs frames",
    Log("accumulated frames"), Log("image RMSE vs the most accumulated image (0-255)", 0.01), curves,
    LegendCorner::TopRight);
}

void PlotPassLeaf(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  const std::vector<TradeRow> leaves =
    SortedRows(trade, "pass leaf size", [](const TradeRow& r) { return r.Value; });
  out.Write("trade_pass_leaf.png", "vtkRayTracePass LeafSize (triangles per BVH leaf): frame times",
    Log("leaf size (images identical for every size)"), LinearFromZero("time (ms)"),
    { Curve("steady frame (fastest)", leaves, "pass leaf size", "", &TradeRow::Value,
        &TradeRow::SteadyMinS, 1.0, 1e3),
      Curve("first frame (build, upload, compile, trace)", leaves, "pass leaf size", "",
        &TradeRow::Value, &TradeRow::FirstFrameS, 1.0, 1e3) });
}

void PlotShadowLights(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  out.Write("trade_shadow_lights.png",
    "Shadows vs number of scene lights (directional and spot, alternately)",
    LinearFromZero("scene lights"), LinearFromZero("steady frame (ms, fastest of the timed frames)"),
    { Curve("shadows off", trade, "pass shadow lights", "shadows off", &TradeRow::Value,
        &TradeRow::SteadyMinS, 1.0, 1e3),
      Curve("shadows on", trade, "pass shadow lights", "shadows on", &TradeRow::Value,
        &TradeRow::SteadyMinS, 1.0, 1e3) },
    LegendCorner::TopLeft);
}

/// The settings no other setting beats in both time and error, by time.
Series ParetoFront(const std::vector<TradeRow>& trade)
{
  std::vector<const TradeRow*> points;
  for (const TradeRow& r : trade)
  {
    if (std::isfinite(r.ImageS) && std::isfinite(r.ExactRMSE))
    {
      points.push_back(&r);
    }
  }
  std::sort(points.begin(), points.end(), [](const TradeRow* a, const TradeRow* b) {
    return a->ImageS < b->ImageS || (a->ImageS == b->ImageS && a->ExactRMSE < b->ExactRMSE);
  });
  Series front;
  front.Name = "Pareto front";
  front.Dashed = true;
  front.Color[0] = front.Color[1] = front.Color[2] = 130; // grey: no curve of the palette
  double best = std::numeric_limits<double>::infinity();
  for (const TradeRow* r : points)
  {
    if (r->ExactRMSE < best)
    {
      best = r->ExactRMSE;
      front.X.push_back(1e3 * r->ImageS);
      front.Y.push_back(r->ExactRMSE);
    }
  }
  return front;
}

/// Every traced or raster setting measured against the EXACT reference:
/// time to its image against its image error, each knob a curve, the Pareto
/// front, and each preset from one frame (moving view) to its still frames.
void PlotPresets(PlotFolder& out, const std::vector<TradeRow>& trade)
{
  const char* knobs[][2] = { { "pass samples per pixel", "samples per pixel" },
    { "pass max traversal steps", "max traversal steps" }, { "pass shadows", "shadows off/on" },
    { "pass AO samples", "AO samples" }, { "pass leaf size", "leaf size" },
    { "pass builder", "BuildQuality" }, { "pass accumulation", "progressive, frames" },
    { "pass accumulation (AO 1)", "progressive + 1 AO ray, frames" } };
  Curves curves;
  for (const auto& k : knobs)
  {
    const std::vector<TradeRow> rows =
      SortedRows(trade, k[0], [](const TradeRow& r) { return r.ImageS; });
    curves.push_back(Curve(k[1], rows, k[0], "", &TradeRow::ImageS, &TradeRow::ExactRMSE, 1e3));
  }
  for (const std::string method : { "traced", "raster" })
  {
    curves.push_back(Curve("LOD reductions, " + method, trade, "lod", method, &TradeRow::ImageS,
      &TradeRow::ExactRMSE, 1e3));
  }
  curves.push_back(ParetoFront(trade));
  // Colors outside the palette of the knob curves.
  const int colors[3][3] = { { 0, 170, 0 }, { 140, 70, 0 }, { 204, 0, 0 } };
  const char* presets[] = { "INTERACTIVE", "BALANCED", "EXACT" };
  for (int p = 0; p < 3; ++p)
  {
    const std::string name = presets[p];
    Series s = SeriesOf("preset " + name + ": 1 frame, then still", trade,
      [&](const TradeRow& r) { return r.Knob == "preset" && r.Setting.rfind(name, 0) == 0; },
      [](const TradeRow& r) { return 1e3 * r.ImageS; },
      [](const TradeRow& r) { return r.ExactRMSE; });
    std::copy(colors[p], colors[p] + 3, s.Color);
    curves.push_back(s);
  }
  // Sections left out of the run (--sections) leave their curves empty.
  curves.erase(std::remove_if(curves.begin(), curves.end(), [](const Series& c) { return c.X.empty(); }),
    curves.end());
  out.Write("trade_presets.png",
    "Every setting against the EXACT preset's converged image: time vs error",
    Log("time to the image, scene loaded (ms): one steady frame, or k accumulated frames"),
    Log("image RMSE vs EXACT converged (0-255; 0 drawn at 0.01)", 0.01), curves);
}

/// `method`'s translated rows, translation against `y`.
template <class Y>
Series TranslationCurve(const std::string& name, const std::vector<PrecisionRow>& precision,
  const std::string& method, Y y)
{
  return SeriesOf(
    name, precision, [&](const PrecisionRow& r) { return r.Method == method && r.Translation > 0.0; },
    [](const PrecisionRow& r) { return r.Translation; }, y);
}

void PlotPrecisionPick(PlotFolder& out, const std::vector<PrecisionRow>& precision, double diagonal)
{
  std::vector<std::string> methods;
  for (const PrecisionRow& r : precision)
  {
    if (std::isfinite(r.PickMean) && std::find(methods.begin(), methods.end(), r.Method) == methods.end())
    {
      methods.push_back(r.Method);
    }
  }
  const double rel = 1.0 / diagonal;
  Curves curves;
  for (const std::string& m : methods)
  {
    curves.push_back(TranslationCurve(m, precision, m, [rel](const PrecisionRow& r) { return r.PickMean * rel; }));
  }
  out.Write("precision_pick.png", "Precision: pick error of a translated scene",
    Log("translation of scene and camera (world units)"),
    Log("mean pick error vs untranslated / diagonal", 1e-18), curves);
}

void PlotPrecisionImage(PlotFolder& out, const std::vector<PrecisionRow>& precision)
{
  const char* methods[][2] = {
    { "traced depth (vtkRayTracePass)", "traced, camera-relative (default)" },
    { "raster depth (vtkPolyDataMapper)", "raster (vtkPolyDataMapper)" },
    { "traced depth WORLD precision mode (vtkRayTracePass)", "traced, WORLD (float world coordinates)" }
  };
  Curves curves;
  for (const auto& method : methods)
  {
    curves.push_back(
      TranslationCurve(method[1], precision, method[0], [](const PrecisionRow& r) { return r.ImageRMSE; }));
  }
  out.Write("precision_image.png", "Precision: image error of a translated scene",
    Log("translation of scene and camera (world units)"),
    Log("image RMSE vs untranslated (0-255; 0 drawn at 0.01)", 0.01), curves);
}
}

bool WritePlots(const std::string& dir, const std::vector<TradeRow>& trade,
  const std::vector<PrecisionRow>& precision, double diagonal, std::vector<std::string>& written)
{
  PlotFolder out{ dir, written };
  PlotPresets(out, trade);
  PlotLODFrame(out, trade);
  PlotLODError(out, trade, diagonal);
  PlotBuilder(out, trade);
  PlotPassBuilder(out, trade);
  PlotPassKnobs(out, trade);
  PlotAccumulation(out, trade);
  PlotPassLeaf(out, trade);
  PlotShadowLights(out, trade);
  PlotPrecisionPick(out, precision, diagonal);
  PlotPrecisionImage(out, precision);
  return out.Ok;
}
}
