// Section "level of detail" (and the renderer knob at full resolution).
#include "TradeErrors.h"
#include "TradeMesh.h"
#include "TradeSections.h"

#include "vtkBVHCellLocator.h"
#include "vtkNew.h"
#include "vtkOpenMeshDecimation.h"

#include <cstdio>
#include <memory>

namespace vtkrtTrade
{
namespace
{
/// One reduction of the mesh, drawn and picked.
struct LODLevel
{
  vtkSmartPointer<vtkPolyData> Mesh;
  double Prep = 0.0;  // decimation time
  double Build = 0.0; // locator build time
  std::unique_ptr<Stage> Traced, Raster;
  Picks Picked;
  PickError Pick;
  GeomError Geom;
};

/// What every reduction is compared with: the full mesh's.
struct LODReference
{
  std::unique_ptr<Stage> Traced, Raster;
  Picks Picked;
  Pixels PickAt; // the full mesh's footprint
  vtkSmartPointer<vtkBVHCellLocator> Locator;
  std::vector<Point> Samples;
};

/// `mesh` decimated by `ratio`, in double (the mesh itself for 0), and the
/// decimation time; nullptr when the decimation left no triangles.
vtkSmartPointer<vtkPolyData> Decimated(vtkPolyData* mesh, double ratio, double& prep)
{
  prep = 0.0;
  if (!(ratio > 0.0))
  {
    return mesh;
  }
  vtkNew<vtkOpenMeshDecimation> decimate;
  decimate->SetInputData(mesh);
  decimate->SetTargetModeToReduction();
  decimate->SetTargetReduction(ratio);
  const auto t0 = Clock::now();
  decimate->Update();
  prep = Seconds(t0, Clock::now());
  vtkSmartPointer<vtkPolyData> lod = DoubleTriangles(decimate->GetOutput());
  return lod->GetNumberOfCells() == 0 ? nullptr : lod;
}

/// The rows of one reduction, traced and raster, against the full mesh's
/// stages of the same method.
void LevelRows(double ratio, const LODLevel& level, const LODReference& ref, const Reference& exact,
  std::vector<TradeRow>& rows)
{
  for (int m = 0; m < 2; ++m)
  {
    const Stage& st = m == 0 ? *level.Traced : *level.Raster;
    const Stage& refStage =
      m == 0 ? (ref.Traced ? *ref.Traced : st) : (ref.Raster ? *ref.Raster : st);
    const DepthError de = CompareDepth(refStage, st);
    char setting[32];
    std::snprintf(setting, sizeof(setting), "reduction %.2f", ratio);
    TradeRow row = StageRow("lod", setting, m == 0 ? "traced" : "raster", ratio,
      level.Mesh->GetNumberOfCells(), st, refStage);
    row.PrepS = level.Prep;
    row.BuildS = level.Build;
    row.PickUs = 1e6 * level.Picked.SecondsPerPick;
    row.DepthErr = de.Mean;
    row.Coverage = de.Coverage;
    row.PickMean = level.Pick.Mean;
    row.PickMax = level.Pick.Max;
    row.PickMiss = level.Pick.Miss;
    row.GeomMean = level.Geom.Mean;
    row.GeomMax = level.Geom.Max;
    MeasureAgainst(exact, st, row);
    rows.push_back(row);
    std::printf("  lod %.2f %-6s %8lld tris  decimate %6.0f ms  first %6.0f ms  frame %6.1f ms  "
                "rmse %6.2f  diff %7.1f  depth %.3g  pick %.3g  geom %.3g/%.3g\n",
      ratio, row.Method.c_str(), static_cast<long long>(row.Triangles), 1e3 * level.Prep,
      1e3 * st.FirstSeconds, 1e3 * st.SteadySeconds, row.ImageRMSE, row.ImageDiff, de.Mean,
      level.Pick.Mean, level.Geom.Mean, level.Geom.Max);
  }
}

/// Renderer knob: raster against traced at full resolution.
void RendererRows(const LODLevel& full, const Reference& exact, std::vector<TradeRow>& rows)
{
  const DepthError de = CompareDepth(*full.Traced, *full.Raster);
  for (int m = 0; m < 2; ++m)
  {
    const Stage& st = m == 0 ? *full.Traced : *full.Raster;
    TradeRow row = StageRow("renderer", m == 0 ? "traced (reference)" : "raster",
      m == 0 ? "vtkRayTracePass" : "vtkPolyDataMapper", kNaN, full.Mesh->GetNumberOfCells(), st,
      *full.Traced);
    row.DepthErr = m == 0 ? 0.0 : de.Mean;
    row.Coverage = m == 0 ? 0.0 : de.Coverage;
    MeasureAgainst(exact, st, row);
    rows.push_back(row);
  }
}
}

/// The first reduction (0: the full mesh) is the reference of the others.
bool RunLOD(vtkPolyData* mesh, const Scene& scene, const Options& opt,
  const Reference& exact, std::vector<TradeRow>& rows)
{
  const Point zero{ { 0, 0, 0 } };
  LODReference ref;
  ref.Samples = SampleSurface(mesh, opt.GeomSamples, 11);

  for (double ratio : opt.Ratios)
  {
    LODLevel level;
    level.Mesh = Decimated(mesh, ratio, level.Prep);
    if (!level.Mesh)
    {
      std::printf("  lod %.2f: decimation gave no triangles, skipped\n", ratio);
      continue;
    }

    auto locator = vtkSmartPointer<vtkBVHCellLocator>::New();
    locator->SetDataSet(level.Mesh);
    auto t0 = Clock::now();
    locator->BuildLocator();
    level.Build = Seconds(t0, Clock::now());

    level.Traced = RenderStage(level.Mesh, scene, zero, true, opt);
    level.Raster = RenderStage(level.Mesh, scene, zero, false, opt);
    if (!level.Traced || !level.Raster)
    {
      return NoContext();
    }
    const bool first = ratio == opt.Ratios.front();
    if (first)
    {
      ref.PickAt = PickPixels(*level.Traced, opt.PickGrid);
    }
    level.Picked = PickWithPicker(*level.Traced, ref.PickAt, locator);
    const std::vector<Point> samples = SampleSurface(level.Mesh, opt.GeomSamples, 13);
    if (first)
    {
      ref.Picked = level.Picked;
      ref.Locator = locator;
    }
    level.Pick = ComparePicks(ref.Picked, level.Picked);
    level.Geom = SurfaceDistance(ref.Locator, ref.Samples, locator, samples);

    LevelRows(ratio, level, ref, exact, rows);
    if (first)
    {
      RendererRows(level, exact, rows);
      ref.Traced = std::move(level.Traced);
      ref.Raster = std::move(level.Raster);
    }
  }
  return true;
}
}
