// Section "shadows per scene light count".
#include "TradeSections.h"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace vtkrtTrade
{
namespace
{
/// Frames of the two stages rendered alternately, `frames` each (at least
/// one): median and fastest of each.
void TimeAlternately(std::unique_ptr<Stage> (&stages)[2], int frames)
{
  std::vector<double> times[2];
  for (int f = 0; f < std::max(1, frames); ++f)
  {
    for (int on = 0; on < 2; ++on)
    {
      const auto t0 = Clock::now();
      stages[on]->Window->Render();
      stages[on]->Window->WaitForCompletion();
      times[on].push_back(Seconds(t0, Clock::now()));
    }
  }
  for (int on = 0; on < 2; ++on)
  {
    stages[on]->SteadySeconds = Median(times[on]);
    stages[on]->SteadyMinSeconds = *std::min_element(times[on].begin(), times[on].end());
  }
}
}

/// Directional and spot lights alternately. The per-light cost is a
/// difference of two frame times, which a changing load on the machine
/// disturbs most: the two windows' frames are timed alternately (same load
/// for both), fastest of opt.Frames each.
bool RunShadowLights(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  const Reference& /*exact: other lights than its*/, std::vector<TradeRow>& rows)
{
  Options first = opt;
  first.Frames = 0;
  const Point zero{ { 0, 0, 0 } };
  const std::vector<int> counts = opt.Quick ? std::vector<int>{ 1, 4 } : std::vector<int>{ 1, 2, 4, 8 };
  for (int n : counts)
  {
    std::unique_ptr<Stage> stages[2];
    for (int on = 0; on < 2; ++on)
    {
      PassSettings settings;
      settings.Lights = n;
      settings.Shadows = on != 0;
      stages[on] = RenderStage(mesh, scene, zero, true, first, settings);
      if (!stages[on])
      {
        return NoContext();
      }
    }
    TimeAlternately(stages, opt.Frames);
    for (int on = 0; on < 2; ++on)
    {
      const Stage& st = *stages[on];
      rows.push_back(StageRow("pass shadow lights",
        std::to_string(n) + (n == 1 ? " light shadows " : " lights shadows ") +
          (on ? "on (reference)" : "off"),
        on ? "shadows on" : "shadows off", n, mesh->GetNumberOfCells(), st, *stages[1]));
    }
    std::printf("  %d scene light(s): frame %7.1f ms without shadows, %7.1f ms with (min %6.1f / "
                "%6.1f): %+.1f ms per light; shadows change RMSE %.2f\n",
      n, 1e3 * stages[0]->SteadySeconds, 1e3 * stages[1]->SteadySeconds,
      1e3 * stages[0]->SteadyMinSeconds, 1e3 * stages[1]->SteadyMinSeconds,
      1e3 * (stages[1]->SteadyMinSeconds - stages[0]->SteadyMinSeconds) / n,
      rows[rows.size() - 2].ImageRMSE);
  }
  return true;
}
}
