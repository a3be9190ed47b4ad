// Section "presets": vtkRayTracePass's quality presets against the EXACT
// preset's converged image, which is also the reference of every other
// traced setting (MeasureAgainst).
#include "TradeErrors.h"
#include "TradeSections.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>

namespace vtkrtTrade
{
void MeasureAgainst(const Reference& ref, const Stage& st, TradeRow& row, vtkImageData* image)
{
  if (!ref.Exact)
  {
    return;
  }
  vtkImageData* candidate = image ? image : st.Image.GetPointer();
  row.ExactRMSE = ImageRMSE(ref.Exact->Image, candidate);
  row.ExactDiff = ImageDifference(ref.Exact->Image, candidate);
  const DepthError de = CompareDepth(*ref.Exact, st);
  row.ExactDepth = de.Mean;
  row.ExactCoverage = de.Coverage;
  const PickError pe = ComparePicks(ref.Picked, PickFromDepth(st, ref.PickAt));
  row.ExactPickMean = pe.Mean;
  row.ExactPickMiss = pe.Miss;
}

namespace
{
/// One preset's window and what it measured.
struct PresetRun
{
  int Preset;
  const char* Name;
  std::unique_ptr<Stage> St; // its Image: the first frame's
  vtkSmartPointer<vtkImageData> Still; // after all the still frames
  std::vector<double> Times;           // each still frame
  std::vector<double> CpuTimes;        // each still frame's process CPU
};

/// The first frames, one preset after the other, then the still frames in
/// turn; false when a window could not be made or an accumulation restarted.
bool RenderPresets(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  std::vector<PresetRun>& runs, vtkSmartPointer<vtkImageData>& exactHalfway)
{
  Options firstOnly = opt;
  firstOnly.Frames = 0;
  for (PresetRun& run : runs)
  {
    PassSettings settings;
    settings.Preset = run.Preset;
    run.St = RenderStage(mesh, scene, Point{ { 0, 0, 0 } }, true, firstOnly, settings);
    if (!run.St)
    {
      return NoContext();
    }
  }
  const int frames = std::max(2, opt.ReferenceFrames);
  for (int k = 2; k <= frames; ++k)
  {
    for (PresetRun& run : runs)
    {
      const auto t0 = Clock::now();
      const double cpu0 = vtkrtBench::ProcessSeconds();
      run.St->Window->Render();
      run.St->Window->WaitForCompletion();
      run.Times.push_back(Seconds(t0, Clock::now()));
      run.CpuTimes.push_back(vtkrtBench::ProcessSeconds() - cpu0);
      if (k == frames / 2 && run.Preset == vtkRayTracePass::EXACT)
      {
        exactHalfway = run.St->GrabImage();
      }
    }
  }
  for (PresetRun& run : runs)
  {
    if (run.St->Pass->GetAccumulatedFrames() != frames)
    {
      std::cerr << "vtkrtBenchTrade: preset " << run.Name << " accumulated "
                << run.St->Pass->GetAccumulatedFrames() << " frames, " << frames << " expected\n";
      return false;
    }
    run.Still = run.St->GrabImage();
  }
  return true;
}

/// The rows of one preset: one frame (a moving view) and all the still
/// frames, each against the reference.
void PresetRows(const PresetRun& run, const Reference& ref, int frames, double triangles,
  std::vector<TradeRow>& rows)
{
  const double steady = Median(run.Times);
  const double fastest = *std::min_element(run.Times.begin(), run.Times.end());
  for (int still = 0; still < 2; ++still)
  {
    TradeRow row;
    row.Knob = "preset";
    row.Setting = std::string(run.Name) + (still ? " still" : "");
    row.Method = "vtkRayTracePass";
    row.Value = still ? frames : 1;
    row.Triangles = triangles;
    row.FirstFrameS = run.St->FirstSeconds;
    row.SteadyFrameS = steady;
    row.SteadyMinS = fastest;
    row.ImageS = row.Value * fastest;
    row.SteadyCpuS = Median(run.CpuTimes);
    MeasureAgainst(ref, *run.St, row, still ? run.Still.GetPointer() : run.St->Image.GetPointer());
    row.ImageRMSE = row.ExactRMSE;
    row.ImageDiff = row.ExactDiff;
    row.DepthErr = row.ExactDepth;
    row.Coverage = row.ExactCoverage;
    row.PickMean = row.ExactPickMean;
    row.PickMiss = row.ExactPickMiss;
    rows.push_back(row);
    std::printf("  %-17s %2d frame%s  first %6.0f ms  frame %6.1f ms (min %6.1f, %4.1f fps; "
                "cpu %6.1f ms)  vs EXACT: rmse %6.2f  diff %7.1f  depth %.3g  pick %.3g  pick miss %.3g\n",
      row.Setting.c_str(), static_cast<int>(row.Value), still ? "s" : " ", 1e3 * row.FirstFrameS,
      1e3 * steady, 1e3 * fastest, 1.0 / steady, 1e3 * row.SteadyCpuS, row.ExactRMSE, row.ExactDiff, row.ExactDepth,
      row.ExactPickMean, row.ExactPickMiss);
  }
}
}

bool RunPresets(vtkPolyData* mesh, const Scene& scene, const Options& opt, Reference& reference,
  std::vector<TradeRow>& rows)
{
  std::vector<PresetRun> runs;
  runs.push_back({ vtkRayTracePass::INTERACTIVE, "INTERACTIVE", nullptr, nullptr, {} });
  runs.push_back({ vtkRayTracePass::BALANCED, "BALANCED", nullptr, nullptr, {} });
  runs.push_back({ vtkRayTracePass::EXACT, "EXACT", nullptr, nullptr, {} });
  vtkSmartPointer<vtkImageData> halfway;
  if (!RenderPresets(mesh, scene, opt, runs, halfway))
  {
    return false;
  }
  const int frames = std::max(2, opt.ReferenceFrames);
  PresetRun& exact = runs.back();
  // The reference: EXACT's accumulated image, with the depth of its frames.
  reference.Exact = std::make_unique<Stage>();
  Stage& ref = *reference.Exact;
  ref.Image = exact.Still;
  ref.Width = exact.St->Width;
  ref.Height = exact.St->Height;
  ref.Depth = exact.St->Depth;
  ref.Offset = exact.St->Offset;
  ref.DisplayToWorld->DeepCopy(exact.St->DisplayToWorld);
  reference.PickAt = PickPixels(ref, opt.PickGrid);
  reference.Picked = PickFromDepth(ref, reference.PickAt);
  std::printf("  reference: EXACT after %d still frames (rmse %.2f against %d frames)\n", frames,
    ImageRMSE(halfway, exact.Still), frames / 2);
  for (const PresetRun& run : runs)
  {
    PresetRows(run, reference, frames, mesh->GetNumberOfCells(), rows);
  }
  return true;
}
}
