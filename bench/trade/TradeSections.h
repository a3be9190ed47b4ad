// vtkrtBenchTrade's sections, one file each: every section renders or
// queries the mesh under one knob's settings, prints a line per setting
// and appends rows (see TradeMain.cxx for the order they run in).
#ifndef vtkrtTradeSections_h
#define vtkrtTradeSections_h

#include "TradeErrors.h"
#include "TradeRows.h"
#include "TradeStage.h"

#include "vtkPolyData.h"

#include <string>
#include <vector>

namespace vtkrtTrade
{
/// The one reference every traced setting is also measured against (the
/// exact_* columns): the EXACT preset's image after opt.ReferenceFrames
/// still frames, its depth, and the points under a grid of its pixels
/// from that depth (what vtkWorldPointPicker picks). RunPresets makes it.
struct Reference
{
  std::unique_ptr<Stage> Exact;
  Pixels PickAt;
  Picks Picked;
};

/// The exact_* columns of `row`: `st`'s depth and depth picks and `image`
/// (st's own image when null) against the reference.
void MeasureAgainst(const Reference& ref, const Stage& st, TradeRow& row, vtkImageData* image = nullptr);

/// A section appending rows to trade.csv; false when it could not run.
using TradeSection = bool (*)(
  vtkPolyData*, const Scene&, const Options&, const Reference&, std::vector<TradeRow>&);

/// The quality presets of vtkRayTracePass, INTERACTIVE, BALANCED and EXACT,
/// each in its own window, their first frames, then opt.ReferenceFrames - 1
/// still frames taken in turn (so that other load on the machine weighs on
/// all three alike): first frame, steady frame, and the error of one frame
/// (what a moving view shows) and of the accumulated frames (a still view)
/// against EXACT's accumulated image, which becomes `reference`.
/// TradePresets.cxx.
bool RunPresets(vtkPolyData* mesh, const Scene& scene, const Options& opt, Reference& reference,
  std::vector<TradeRow>& rows);

/// vtkBVHCellLocator BuildQuality (FAST / SAH / HIGH) x NumberOfCellsPerNode:
/// build time, thread-CPU time per IntersectWithLine ray, pick error
/// against HIGH / leaf 1 (the locator is exact in double, so any difference
/// is a bug, not a trade). TradeBuilder.cxx.
bool RunBuilder(vtkPolyData* mesh, const Scene& scene, const Options& opt, const Reference& exact,
  std::vector<TradeRow>& rows);

/// vtkRayTracePass BuildQuality on the full mesh: first frame (which pays the
/// BVH build), steady frame, image and depth error against HIGH.
/// TradeBuilder.cxx.
bool RunPassBuilder(vtkPolyData* mesh, const Scene& scene, const Options& opt, const Reference& exact,
  std::vector<TradeRow>& rows);

/// The pass's SamplesPerPixel, MaximumTraversalSteps, Shadows,
/// AmbientOcclusionSamples (each against its best setting) and LeafSize:
/// first frame, steady frame, image and depth error. TradeKnobs.cxx.
bool RunPassKnobs(vtkPolyData* mesh, const Scene& scene, const Options& opt, const Reference& exact,
  std::vector<TradeRow>& rows);

/// Shadows against the number of scene lights (1..8): frame time with
/// shadows off and on, and what shadows change. TradeShadows.cxx.
bool RunShadowLights(vtkPolyData* mesh, const Scene& scene, const Options& opt, const Reference& exact,
  std::vector<TradeRow>& rows);

/// Progressive accumulation, 1 sample a frame (plain and with one AO ray):
/// image error after 1, 2, 4, .. frames against the most accumulated one,
/// time per frame. TradeAccumulation.cxx.
bool RunAccumulation(vtkPolyData* mesh, const Scene& scene, const Options& opt, const Reference& exact,
  std::vector<TradeRow>& rows);

/// Level of detail: vtkOpenMeshDecimation TargetReduction, drawn traced
/// (vtkRayTracePass) and raster (vtkPolyDataMapper): decimation time,
/// locator build, first frame, steady frame, picking time; image error
/// (RMSE, vtkImageDifference), depth error, pick error and symmetric sampled
/// surface distance against the full-resolution mesh. Also the renderer
/// knob: raster against traced at full resolution. TradeLOD.cxx.
bool RunLOD(vtkPolyData* mesh, const Scene& scene, const Options& opt, const Reference& exact,
  std::vector<TradeRow>& rows);

/// The scene and camera translated by 1e2 .. 1e8, each method against its
/// own untranslated result: traced (camera-relative and WORLD precision
/// mode) and raster images, the point under a pixel from each one's depth
/// buffer (what vtkWorldPointPicker does), vtkCellPicker with
/// vtkBVHCellLocator and without a locator, and the pass's id-mode picks.
/// TradePrecision.cxx.
bool RunPrecision(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<PrecisionRow>& rows);

/// The PNG plots of both tables in `dir`; their paths are appended to
/// `written`. False when a plot could not be drawn. TradePlots.cxx.
bool WritePlots(const std::string& dir, const std::vector<TradeRow>& trade,
  const std::vector<PrecisionRow>& precision, double diagonal, std::vector<std::string>& written);
}

#endif
