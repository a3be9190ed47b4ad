// Section "precision": the scene and camera translated far from the origin.
#include "TradeErrors.h"
#include "TradeMesh.h"
#include "TradeSections.h"

#include "vtkBVHCellLocator.h"
#include "vtkNew.h"
#include "vtkWindowToImageFilter.h"

#include <cmath>
#include <cstdio>
#include <memory>

namespace vtkrtTrade
{
namespace
{
enum
{
  Traced,
  Raster,
  World,
  Locator,
  NoLocator,
  Methods,
  Stages = 3 // Traced, Raster, World render images
};
const char* const kMethodNames[Methods] = { "traced depth (vtkRayTracePass)",
  "raster depth (vtkPolyDataMapper)", "traced depth WORLD precision mode (vtkRayTracePass)",
  "vtkCellPicker + vtkBVHCellLocator", "vtkCellPicker (no locator)" };

/// Renders the traced stage once more in id mode and returns the fraction of
/// `pixels` (hit by either side) whose GPU cell id differs from `exact`'s.
double IdMismatch(Stage& st, const Pixels& pixels, const Picks& exact)
{
  st.Pass->SetIdMode(true);
  st.Window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(st.Window);
  grab->SetInputBufferTypeToRGBA();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  st.Pass->SetIdMode(false);
  vtkImageData* image = grab->GetOutput();
  const auto* rgba = static_cast<const unsigned char*>(image->GetScalarPointer());
  long either = 0, differ = 0;
  for (size_t k = 0; k < pixels.size(); ++k)
  {
    const size_t i = static_cast<size_t>(pixels[k][0]);
    const size_t j = static_cast<size_t>(pixels[k][1]);
    int prop;
    vtkIdType id;
    const bool hit = vtkRayTracePass::DecodeId(rgba + 4 * (j * st.Width + i), prop, id);
    if (hit || exact.Hit[k])
    {
      ++either;
      differ += (hit != static_cast<bool>(exact.Hit[k]) || id != exact.CellId[k]) ? 1 : 0;
    }
  }
  return either ? double(differ) / either : 0.0;
}

/// The untranslated results every translation is compared with.
struct PrecisionReference
{
  std::unique_ptr<Stage> Rendered[Stages];
  Picks Picked[Methods];
  Pixels PickAt; // the untranslated footprint
};

/// One row per method at `translation`, against the untranslated results
/// (`ref`, or this translation's own when it is the first).
void MethodRows(double translation, std::unique_ptr<Stage> (&stage)[Stages], const Picks (&picks)[Methods],
  const PrecisionReference& ref, std::vector<PrecisionRow>& rows)
{
  for (int m = 0; m < Methods; ++m)
  {
    PrecisionRow row;
    row.Method = kMethodNames[m];
    row.Translation = translation;
    if (m < Stages)
    {
      const Stage& refStage = ref.Rendered[m] ? *ref.Rendered[m] : *stage[m];
      row.ImageRMSE = ImageRMSE(refStage.Image, stage[m]->Image);
      row.ImageDiff = ImageDifference(refStage.Image, stage[m]->Image);
      const DepthError de = CompareDepth(refStage, *stage[m]);
      row.DepthErr = de.Mean;
      row.Coverage = de.Coverage;
    }
    else
    {
      row.PickUs = 1e6 * picks[m].SecondsPerPick;
    }
    const PickError pe = ComparePicks(ref.Picked[m], picks[m]);
    row.PickMean = pe.Mean;
    row.PickMax = pe.Max;
    row.PickMiss = pe.Miss;
    row.PickExact = ComparePicks(ref.Picked[Locator], picks[m]).Mean;
    rows.push_back(row);
    std::printf("  translate %-8.0e %-52s rmse %7.2f  depth %.3g  pick %.3g (max %.3g, miss %.3g, "
                "vs exact %.3g)\n",
      translation, kMethodNames[m], row.ImageRMSE, row.DepthErr, pe.Mean, pe.Max, pe.Miss,
      row.PickExact);
  }
}

/// The pass's own picking: id mode, one ray per pixel on the GPU, against
/// the locator's cells.
void IdRows(double translation, std::unique_ptr<Stage> (&stage)[Stages], const Pixels& pixels,
  const Picks& exact, std::vector<PrecisionRow>& rows)
{
  for (int m : { Traced, World })
  {
    PrecisionRow idRow;
    idRow.Method = m == Traced ? "traced id (vtkRayTracePass IdMode)"
                               : "traced id WORLD precision mode (IdMode)";
    idRow.Translation = translation;
    idRow.IdMismatch = IdMismatch(*stage[m], pixels, exact);
    rows.push_back(idRow);
    std::printf("  translate %-8.0e %-52s cell ids differing from the locator's: %.3g\n",
      translation, idRow.Method.c_str(), idRow.IdMismatch);
  }
}
}

/// The pass also renders in WORLD mode (plain float world coordinates).
bool RunPrecision(vtkPolyData* mesh, const Scene& scene, const Options& opt, std::vector<PrecisionRow>& rows)
{
  PassSettings world;
  world.PrecisionMode = vtkRayTracePass::WORLD;
  PrecisionReference ref;
  for (double translation : opt.Translations)
  {
    const double c = translation / std::sqrt(3.0);
    const Point offset{ { c, c, c } };
    vtkSmartPointer<vtkPolyData> moved = Translated(mesh, offset);
    std::unique_ptr<Stage> stage[Stages] = { RenderStage(moved, scene, offset, true, opt),
      RenderStage(moved, scene, offset, false, opt),
      RenderStage(moved, scene, offset, true, opt, world) };
    if (!stage[0] || !stage[1] || !stage[2])
    {
      return NoContext();
    }
    const bool first = translation == opt.Translations.front();
    if (first)
    {
      ref.PickAt = PickPixels(*stage[0], opt.PrecisionGrid);
    }
    vtkNew<vtkBVHCellLocator> locator;
    locator->SetDataSet(moved);
    locator->BuildLocator();
    const Picks picks[Methods] = { PickFromDepth(*stage[0], ref.PickAt),
      PickFromDepth(*stage[1], ref.PickAt), PickFromDepth(*stage[2], ref.PickAt),
      PickWithPicker(*stage[0], ref.PickAt, locator), PickWithPicker(*stage[0], ref.PickAt, nullptr) };
    if (first)
    {
      for (int m = 0; m < Methods; ++m)
      {
        ref.Picked[m] = picks[m];
      }
    }
    MethodRows(translation, stage, picks, ref, rows);
    IdRows(translation, stage, ref.PickAt, picks[Locator], rows);
    if (first)
    {
      for (int m = 0; m < Stages; ++m)
      {
        ref.Rendered[m] = std::move(stage[m]);
      }
    }
  }
  return true;
}
}
