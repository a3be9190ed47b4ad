// Section "pass knobs": the pass's shading, sampling and BVH leaf knobs.
#include "TradeErrors.h"
#include "TradeSections.h"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace vtkrtTrade
{
namespace
{
struct Knob
{
  std::string Name;
  std::vector<int> Values; // reference first
  void (*Apply)(PassSettings&, int);
};

std::vector<Knob> PassKnobs(const Options& opt)
{
  return {
    { "pass samples per pixel", opt.Quick ? std::vector<int>{ 4, 1 } : std::vector<int>{ 16, 1, 2, 4, 8 },
      [](PassSettings& k, int v) { k.SamplesPerPixel = v; } },
    { "pass max traversal steps",
      opt.Quick ? std::vector<int>{ 0, 16 } : std::vector<int>{ 0, 16, 32, 64, 128 },
      [](PassSettings& k, int v) { k.MaximumTraversalSteps = v; } },
    { "pass shadows", { 1, 0 }, [](PassSettings& k, int v) { k.Shadows = v != 0; } },
    { "pass AO samples", opt.Quick ? std::vector<int>{ 4, 0 } : std::vector<int>{ 16, 0, 1, 4 },
      [](PassSettings& k, int v) { k.AmbientOcclusionSamples = v; } },
    // Reference: the default (images do not depend on the leaf size).
    { "pass leaf size",
      opt.Quick ? std::vector<int>{ 8, 1, 16 } : std::vector<int>{ 8, 1, 2, 4, 16, 32 },
      [](PassSettings& k, int v) { k.LeafSize = v; } },
  };
}

/// The setting's name in the CSV: the value, "unlimited" for 0 steps.
std::string SettingName(const Knob& knob, int v, bool reference)
{
  std::string setting = (v == 0 && knob.Name.find("steps") != std::string::npos)
    ? std::string("unlimited")
    : std::to_string(v);
  if (reference)
  {
    setting += " (reference)";
  }
  return setting;
}
}

/// Each knob against its own highest-quality setting (listed first).
bool RunPassKnobs(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  const Reference& exact, std::vector<TradeRow>& rows)
{
  Options fewer = opt;
  fewer.Frames = std::min(opt.Frames, 3); // many-sample frames are slow on llvmpipe
  const Point zero{ { 0, 0, 0 } };
  for (const Knob& knob : PassKnobs(opt))
  {
    std::unique_ptr<Stage> reference;
    for (int v : knob.Values)
    {
      PassSettings settings;
      knob.Apply(settings, v);
      std::unique_ptr<Stage> st = RenderStage(mesh, scene, zero, true, fewer, settings);
      if (!st)
      {
        return NoContext();
      }
      const Stage& ref = reference ? *reference : *st;
      const DepthError de = CompareDepth(ref, *st);
      TradeRow row = StageRow(knob.Name, SettingName(knob, v, !reference), "vtkRayTracePass", v,
        mesh->GetNumberOfCells(), *st, ref);
      row.DepthErr = de.Mean;
      row.Coverage = de.Coverage;
      MeasureAgainst(exact, *st, row);
      rows.push_back(row);
      std::printf("  %-25s %-18s first %6.0f ms  frame %7.1f ms (min %7.1f)  rmse %6.2f  "
                  "diff %7.1f  coverage %.3g  vs EXACT rmse %6.2f\n",
        knob.Name.c_str(), row.Setting.c_str(), 1e3 * st->FirstSeconds, 1e3 * st->SteadySeconds,
        1e3 * st->SteadyMinSeconds, row.ImageRMSE, row.ImageDiff, de.Coverage, row.ExactRMSE);
      if (!reference)
      {
        reference = std::move(st);
      }
    }
  }
  return true;
}
}
