// Sections "builder" (vtkBVHCellLocator) and "pass builder" (vtkRayTracePass).
#include "TradeErrors.h"
#include "TradeSections.h"

#include "vtkBVHCellLocator.h"
#include "vtkGenericCell.h"
#include "vtkMath.h"
#include "vtkNew.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

namespace vtkrtTrade
{
namespace
{
using Segment = std::array<Point, 2>;

/// Segments from a sphere around the object through random points of it.
std::vector<Segment> BuilderSegments(vtkPolyData* mesh, const Scene& scene, int count)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<Segment> segments;
  double b[6];
  mesh->GetBounds(b);
  for (int r = 0; r < count; ++r)
  {
    Point dir{ { uni(rng), uni(rng), uni(rng) } };
    const double n = std::max(1e-9, vtkMath::Norm(dir.data()));
    Point p1, target, p2;
    for (int k = 0; k < 3; ++k)
    {
      p1[k] = scene.Center[k] + 2.0 * scene.Radius * dir[k] / n;
      target[k] = b[2 * k] + 0.5 * (uni(rng) + 1.0) * (b[2 * k + 1] - b[2 * k]);
      p2[k] = p1[k] + 3.0 * (target[k] - p1[k]);
    }
    segments.push_back({ { p1, p2 } });
  }
  return segments;
}

struct BuilderSetting
{
  int Quality, Leaf;
};

/// The reference (HIGH, leaf 1) first, then every quality x leaf size.
std::vector<BuilderSetting> BuilderSettings(const Options& opt)
{
  std::vector<BuilderSetting> settings{ { vtkBVHCellLocator::HIGH, 1 } };
  for (int q = vtkBVHCellLocator::FAST; q <= vtkBVHCellLocator::HIGH; ++q)
  {
    for (int leaf : opt.Leaves)
    {
      settings.push_back({ q, leaf });
    }
  }
  return settings;
}

/// Best of `repeats` ForceBuildLocator times.
double BestBuild(vtkBVHCellLocator* locator, int repeats)
{
  double build = HUGE_VAL;
  for (int rep = 0; rep < repeats; ++rep)
  {
    const auto t0 = Clock::now();
    locator->ForceBuildLocator();
    build = std::min(build, Seconds(t0, Clock::now()));
  }
  return build;
}

/// IntersectWithLine on every segment, `repeats` sweeps; the time per pick
/// is the best sweep's thread CPU time.
Picks SweepPicks(vtkBVHCellLocator* locator, const std::vector<Segment>& segments, int repeats,
  vtkGenericCell* cell)
{
  Picks picks;
  picks.Hit.resize(segments.size());
  picks.X.resize(segments.size());
  double sweep = HUGE_VAL;
  for (int rep = 0; rep < repeats; ++rep)
  {
    const double t0 = ThreadSeconds();
    for (size_t r = 0; r < segments.size(); ++r)
    {
      double t, x[3], pc[3];
      int subId;
      vtkIdType cellId;
      picks.Hit[r] = locator->IntersectWithLine(
        segments[r][0].data(), segments[r][1].data(), 0.0, t, x, pc, subId, cellId, cell) != 0;
      picks.X[r] = { { x[0], x[1], x[2] } };
    }
    sweep = std::min(sweep, ThreadSeconds() - t0);
  }
  picks.SecondsPerPick = sweep / std::max<size_t>(1, segments.size());
  return picks;
}
}

/// Always succeeds: the bool matches the other sections'.
bool RunBuilder(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  const Reference& /*exact: the locator draws no image*/, std::vector<TradeRow>& rows)
{
  const std::vector<Segment> segments = BuilderSegments(mesh, scene, opt.BuilderRays);
  const std::vector<BuilderSetting> settings = BuilderSettings(opt);
  const char* names[] = { "FAST", "SAH", "HIGH" };
  Picks reference;
  vtkNew<vtkGenericCell> cell;
  for (size_t s = 0; s < settings.size(); ++s)
  {
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(mesh);
    locator->SetBuildQuality(settings[s].Quality);
    locator->SetNumberOfCellsPerNode(settings[s].Leaf);
    const double build = BestBuild(locator, opt.Repeats);
    const Picks picks = SweepPicks(locator, segments, opt.Repeats, cell);
    if (s == 0)
    {
      reference = picks;
      continue;
    }
    const PickError e = ComparePicks(reference, picks);
    TradeRow row;
    row.Knob = "builder";
    row.Setting = std::string(names[settings[s].Quality]) + "/leaf" + std::to_string(settings[s].Leaf);
    row.Method = "vtkBVHCellLocator";
    row.Value = settings[s].Leaf;
    row.Triangles = mesh->GetNumberOfCells();
    row.BuildS = build;
    row.PickUs = 1e6 * picks.SecondsPerPick;
    row.PickMean = e.Mean;
    row.PickMax = e.Max;
    row.PickMiss = e.Miss;
    row.Nodes = locator->GetNumberOfNodes();
    row.SAHCost = locator->GetSAHCost();
    row.MemoryMB = locator->GetMemorySize() / 1048576.0;
    rows.push_back(row);
    std::printf("  builder %-12s build %7.1f ms  pick %6.2f us/ray  SAH %7.2f  nodes %8lld  "
                "pick err max %.3g  miss %.3g\n",
      row.Setting.c_str(), 1e3 * build, row.PickUs, row.SAHCost, static_cast<long long>(row.Nodes),
      e.Max, e.Miss);
  }
  return true;
}

bool RunPassBuilder(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  const Reference& exact, std::vector<TradeRow>& rows)
{
  const Point zero{ { 0, 0, 0 } };
  const char* names[] = { "FAST", "SAH", "HIGH" };
  std::unique_ptr<Stage> reference;
  for (int q : { 2, 0, 1 }) // reference (HIGH) first
  {
    PassSettings knobs;
    knobs.Quality = q;
    std::unique_ptr<Stage> st = RenderStage(mesh, scene, zero, true, opt, knobs);
    if (!st)
    {
      return NoContext();
    }
    const Stage& ref = reference ? *reference : *st;
    const DepthError de = CompareDepth(ref, *st);
    TradeRow row =
      StageRow("pass builder", names[q], "vtkRayTracePass", q, mesh->GetNumberOfCells(), *st, ref);
    row.DepthErr = de.Mean;
    row.Coverage = de.Coverage;
    MeasureAgainst(exact, *st, row);
    rows.push_back(row);
    std::printf("  pass BuildQuality %-4s first %6.0f ms  frame %6.1f ms (min %6.1f)  rmse %.3g  "
                "depth %.3g\n",
      names[q], 1e3 * st->FirstSeconds, 1e3 * st->SteadySeconds, 1e3 * st->SteadyMinSeconds,
      row.ImageRMSE, de.Mean);
    if (!reference)
    {
      reference = std::move(st);
    }
  }
  return true;
}
}
