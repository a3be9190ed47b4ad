#include "vtkrtPlot.h"

#include "vtkEGLHeadlessRenderWindow.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlotPoints.h"
#include "vtkRenderer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace vtkrtPlot
{
namespace
{
// Distinguishable colors (Okabe-Ito, readable by most color-blind readers).
const unsigned char kPalette[][3] = { { 0, 114, 178 }, { 213, 94, 0 }, { 0, 158, 115 },
  { 204, 121, 167 }, { 230, 159, 0 }, { 86, 180, 233 }, { 0, 0, 0 }, { 240, 228, 66 } };
const int kMarkers[] = { vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE, vtkPlotPoints::DIAMOND,
  vtkPlotPoints::CROSS, vtkPlotPoints::PLUS };

void StyleAxis(vtkAxis* axis, const std::string& title)
{
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(15);
  axis->GetTitleProperties()->BoldOff();
  axis->GetLabelProperties()->SetFontSize(13);
}

// A tick value on a log axis (1, 2 or 5 times a power of ten): plain
// decimals in a readable range, "2e-4" style outside it.
std::string DecadeLabel(double value)
{
  char buf[32];
  if (value >= 1e-3 && value < 1e5)
  {
    std::snprintf(buf, sizeof(buf), "%g", value);
    return buf;
  }
  const int exponent = static_cast<int>(std::floor(std::log10(value) + 1e-9));
  const long mantissa = std::lround(value / std::pow(10.0, exponent));
  std::snprintf(buf, sizeof(buf), "%lde%d", mantissa, exponent);
  return buf;
}

// VTK 9.1's own log axes do not match what its plots draw, so a log axis is
// drawn here as a linear axis over log10 of the data (lo..hi), padded a
// little, with ticks at decades (and at 2 and 5 times them when the range
// spans few decades) labelled with the values themselves.
void MakeLogAxis(vtkAxis* axis, double lo, double hi)
{
  const double pad = std::max(0.05, 0.04 * (hi - lo));
  const double a = lo - pad;
  const double b = hi + pad;
  const double span = b - a;
  const int step = span > 12 ? 2 : 1;
  vtkNew<vtkDoubleArray> positions;
  vtkNew<vtkStringArray> labels;
  for (int d = static_cast<int>(std::floor(a)); d <= static_cast<int>(std::ceil(b)); d += step)
  {
    for (double m : { 1.0, 2.0, 5.0 })
    {
      const double at = d + std::log10(m);
      if ((m == 1.0 || span <= 3.0) && at >= a && at <= b)
      {
        positions->InsertNextValue(at);
        labels->InsertNextValue(DecadeLabel(m * std::pow(10.0, d)));
      }
    }
  }
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetRange(a, b);
  axis->SetCustomTickPositions(positions, labels);
}

const int kWidth = 880;
const int kHeight = 480;

/// Adds `s` as the `index`-th plot of `xy` (log10 of the values on a log
/// axis) and grows `range` ([axis][lo, hi]) to its points.
void AddCurve(vtkChartXY* xy, const Series& s, int index, const Axis& xAxis, const Axis& yAxis,
  double range[2][2])
{
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> xs;
  xs->SetName("x");
  vtkNew<vtkDoubleArray> ys;
  ys->SetName(s.Name.c_str());
  const size_t n = std::min(s.X.size(), s.Y.size());
  for (size_t i = 0; i < n; ++i)
  {
    double x = s.X[i];
    double y = s.Y[i];
    if (!std::isfinite(x) || !std::isfinite(y))
    {
      continue;
    }
    if (xAxis.Log)
    {
      x = std::log10(std::max(x, xAxis.LogFloor));
    }
    if (yAxis.Log)
    {
      y = std::log10(std::max(y, yAxis.LogFloor));
    }
    range[0][0] = std::min(range[0][0], x);
    range[0][1] = std::max(range[0][1], x);
    range[1][0] = std::min(range[1][0], y);
    range[1][1] = std::max(range[1][1], y);
    xs->InsertNextValue(x);
    ys->InsertNextValue(y);
  }
  table->AddColumn(xs);
  table->AddColumn(ys);

  // A line needs two points (VTK reports an error otherwise): markers only.
  vtkPlot* plot = xy->AddPlot(xs->GetNumberOfTuples() >= 2 ? vtkChart::LINE : vtkChart::POINTS);
  plot->SetInputData(table, 0, 1);
  plot->SetLabel(s.Name);
  const unsigned char* pal = kPalette[index % 8];
  if (s.Color[0] >= 0)
  {
    plot->SetColor(static_cast<unsigned char>(s.Color[0]), static_cast<unsigned char>(s.Color[1]),
      static_cast<unsigned char>(s.Color[2]), 255);
  }
  else
  {
    plot->SetColor(pal[0], pal[1], pal[2], 255);
  }
  plot->SetWidth(2.5);
  if (s.Dashed)
  {
    plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
  }
  if (auto* points = vtkPlotPoints::SafeDownCast(plot))
  {
    points->SetMarkerStyle(kMarkers[index % 5]);
    points->SetMarkerSize(8.0);
  }
}

/// Fixes `axis` to the data's range lo..hi (log10 of it on a log axis).
void SetRange(vtkAxis* axis, const Axis& spec, double lo, double hi)
{
  if (lo > hi)
  {
    return; // no data
  }
  if (spec.Log)
  {
    MakeLogAxis(axis, lo, hi);
    return;
  }
  // Markers on the plot's edge are cut: pad the data range.
  if (spec.FromZero)
  {
    lo = std::min(0.0, lo);
    hi = std::max(0.0, hi);
  }
  const double span = hi > lo ? hi - lo : std::max(1e-12, 0.1 * std::abs(hi));
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetRange(lo == 0.0 && spec.FromZero ? 0.0 : lo - 0.06 * span, hi + 0.06 * span);
}

void PlaceLegend(vtkChartLegend* legend, LegendCorner corner)
{
  const bool bottom = corner == LegendCorner::BottomLeft || corner == LegendCorner::BottomCenter ||
    corner == LegendCorner::BottomRight;
  const bool left = corner == LegendCorner::TopLeft || corner == LegendCorner::BottomLeft;
  const bool center = corner == LegendCorner::TopCenter || corner == LegendCorner::BottomCenter;
  legend->SetVerticalAlignment(bottom ? vtkChartLegend::BOTTOM : vtkChartLegend::TOP);
  legend->SetHorizontalAlignment(
    left ? vtkChartLegend::LEFT : (center ? vtkChartLegend::CENTER : vtkChartLegend::RIGHT));
  legend->SetInline(corner != LegendCorner::OutsideRight);
}

/// The window's image as a PNG file at `path`.
bool SavePNG(vtkRenderWindow* window, const std::string& path)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();

  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetCompressionLevel(9);
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    std::cerr << "vtkrtPlot: could not write " << path << "\n";
    return false;
  }
  return true;
}
}

bool WritePNG(const std::string& path, const std::string& title, const Axis& x, const Axis& y,
  const std::vector<Series>& curves, LegendCorner legend)
{
  vtkNew<vtkEGLHeadlessRenderWindow> window;
  window->SetSize(kWidth, kHeight);
  window->SetMultiSamples(0);
  window->Initialize();
  if (!window->IsContextReady())
  {
    std::cerr << "vtkrtPlot: no EGL context, cannot draw " << path << "\n";
    return false;
  }

  vtkNew<vtkContextView> view;
  view->SetRenderWindow(window);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);

  vtkNew<vtkChartXY> xy;
  view->GetScene()->AddItem(xy);
  xy->SetTitle(title);
  xy->GetTitleProperties()->SetFontSize(17);
  xy->SetShowLegend(true);
  xy->GetLegend()->SetLabelSize(13);
  StyleAxis(xy->GetAxis(vtkAxis::BOTTOM), x.Label);
  StyleAxis(xy->GetAxis(vtkAxis::LEFT), y.Label);
  double range[2][2] = { { HUGE_VAL, -HUGE_VAL }, { HUGE_VAL, -HUGE_VAL } };
  for (size_t i = 0; i < curves.size(); ++i)
  {
    AddCurve(xy, curves[i], static_cast<int>(i), x, y, range);
  }
  SetRange(xy->GetAxis(vtkAxis::BOTTOM), x, range[0][0], range[0][1]);
  SetRange(xy->GetAxis(vtkAxis::LEFT), y, range[1][0], range[1][1]);
  PlaceLegend(xy->GetLegend(), legend);

  window->Render();
  if (!SavePNG(window, path))
  {
    return false;
  }
  window->Finalize();
  return true;
}
}
