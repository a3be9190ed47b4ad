// Section "progressive accumulation".
#include "TradeErrors.h"
#include "TradeSections.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>

namespace vtkrtTrade
{
namespace
{
/// What one accumulating window gave: the image after k frames for k = 1,
/// 2, 4, .., the wall time until each, and the time of each frame after
/// the first.
struct Accumulated
{
  std::vector<std::pair<int, vtkSmartPointer<vtkImageData>>> Images;
  std::vector<double> Totals;
  std::vector<double> Times;
};

/// Renders `st` (its first frame done) up to `maxFrames` accumulated frames;
/// false, with a message, when the pass restarted its accumulation.
bool Accumulate(Stage& st, int maxFrames, Accumulated& acc)
{
  double total = st.FirstSeconds;
  acc.Images.emplace_back(1, st.Image);
  acc.Totals.push_back(total);
  for (int k = 2; k <= maxFrames; ++k)
  {
    const auto t0 = Clock::now();
    st.Window->Render();
    st.Window->WaitForCompletion();
    acc.Times.push_back(Seconds(t0, Clock::now()));
    total += acc.Times.back();
    if ((k & (k - 1)) == 0)
    {
      if (st.Pass->GetAccumulatedFrames() != k)
      {
        std::cerr << "vtkrtBenchTrade: progressive accumulation restarted (" <<
          st.Pass->GetAccumulatedFrames() << " frames, " << k << " expected)\n";
        return false;
      }
      acc.Images.emplace_back(k, st.GrabImage());
      acc.Totals.push_back(total);
    }
  }
  return true;
}

/// One row per image, against the last (most accumulated) one and against
/// the run's reference (with `st`'s depth, that of its first frame).
void AccumulationRows(const Accumulated& acc, bool ao, double triangles, const Stage& st,
  const Reference& exact, std::vector<TradeRow>& rows)
{
  const double perFrame = Median(acc.Times);
  const double perFrameMin =
    acc.Times.empty() ? kNaN : *std::min_element(acc.Times.begin(), acc.Times.end());
  vtkImageData* reference = acc.Images.back().second;
  for (size_t i = 0; i < acc.Images.size(); ++i)
  {
    TradeRow row;
    row.Knob = ao ? "pass accumulation (AO 1)" : "pass accumulation";
    row.Setting = std::to_string(acc.Images[i].first) + " frames" +
      (i + 1 == acc.Images.size() ? " (reference)" : "");
    row.Method = "vtkRayTracePass";
    row.Value = acc.Images[i].first;
    row.Triangles = triangles;
    row.FirstFrameS = acc.Totals[i]; // wall time until this image
    row.SteadyFrameS = perFrame;
    row.SteadyMinS = perFrameMin;
    row.ImageRMSE = ImageRMSE(reference, acc.Images[i].second);
    row.ImageDiff = ImageDifference(reference, acc.Images[i].second);
    row.ImageS = acc.Images[i].first * perFrameMin;
    MeasureAgainst(exact, st, row, acc.Images[i].second);
    rows.push_back(row);
    std::printf("  %-26s %3d frames: %7.0f ms in all (%.1f ms a frame)  rmse %6.2f  diff %7.1f  "
                "vs EXACT rmse %6.2f\n",
      row.Knob.c_str(), acc.Images[i].first, 1e3 * acc.Totals[i], 1e3 * perFrame, row.ImageRMSE,
      row.ImageDiff, row.ExactRMSE);
  }
}
}

/// One window, 1 sample per frame, the image after k accumulated frames
/// against the last (most accumulated) one; plain shading (anti-aliasing
/// only) and with one ambient occlusion ray per frame.
bool RunAccumulation(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  const Reference& exact, std::vector<TradeRow>& rows)
{
  const int maxFrames = opt.Quick ? 8 : 64;
  const Point zero{ { 0, 0, 0 } };
  for (int ao = 0; ao < 2; ++ao)
  {
    PassSettings settings;
    settings.Progressive = true;
    settings.AmbientOcclusionSamples = ao;
    Options none = opt;
    none.Frames = 0;
    std::unique_ptr<Stage> st = RenderStage(mesh, scene, zero, true, none, settings);
    if (!st)
    {
      return NoContext();
    }
    Accumulated acc;
    if (!Accumulate(*st, maxFrames, acc))
    {
      return false;
    }
    AccumulationRows(acc, ao != 0, mesh->GetNumberOfCells(), *st, exact, rows);
  }
  return true;
}
}
