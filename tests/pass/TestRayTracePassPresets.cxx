// Tests of vtkRayTracePass's quality presets: each preset sets the knobs it
// documents, a knob set after a preset wins (and GetQualityPreset then says
// CUSTOM), and the presets render what their knobs say (accumulation,
// shadows and ambient occlusion in the frame's shader).
// TestRayTracePassPresets <Case>.
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkRenderer.h"

#include <cmath>
#include <functional>
#include <map>
#include <string>

using namespace vtkrtPassTest;

namespace
{
/// What each preset is documented to set (vtkRayTracePass.h).
struct Expected
{
  int Preset;
  std::string Name;
  int BuildQuality, LeafSize, SamplesPerPixel;
  bool Progressive, Shadows;
  int AmbientOcclusionSamples;
};

const Expected Presets[] = {
  { vtkRayTracePass::INTERACTIVE, "Interactive", 0, 8, 1, true, false, 0 },
  { vtkRayTracePass::BALANCED, "Balanced", 1, 8, 1, true, true, 2 },
  { vtkRayTracePass::EXACT, "Exact", 1, 8, 4, true, true, 4 },
};

/// Knobs away from every preset's values, as a user might have left them.
void Scramble(vtkRayTracePass* pass)
{
  pass->SetBuildQuality(2);
  pass->SetLeafSize(16);
  pass->SetSamplesPerPixel(8);
  pass->SetProgressiveAccumulation(false);
  pass->SetShadows(false);
  pass->SetAmbientOcclusionSamples(7);
  pass->SetMaximumTraversalSteps(64);
  pass->SetPrecisionModeToWorld();
  pass->SetAmbientOcclusionRadius(0.25);
}

bool Holds(vtkRayTracePass* pass, const Expected& e)
{
  return pass->GetBuildQuality() == e.BuildQuality && pass->GetLeafSize() == e.LeafSize &&
    pass->GetSamplesPerPixel() == e.SamplesPerPixel &&
    pass->GetProgressiveAccumulation() == e.Progressive && pass->GetShadows() == e.Shadows &&
    pass->GetAmbientOcclusionSamples() == e.AmbientOcclusionSamples &&
    pass->GetMaximumTraversalSteps() == 0 &&
    pass->GetPrecisionMode() == vtkRayTracePass::CAMERA_RELATIVE;
}

/// Each preset, set over scrambled knobs, sets every knob it names and
/// leaves the others; CUSTOM sets nothing; a new pass is CUSTOM.
void TestPresetKnobs()
{
  vtkNew<vtkRayTracePass> fresh;
  Check(fresh->GetQualityPreset() == vtkRayTracePass::CUSTOM &&
      std::string(fresh->GetQualityPresetAsString()) == "Custom",
    "a new pass is CUSTOM (its defaults are no preset)");
  for (const Expected& e : Presets)
  {
    vtkNew<vtkRayTracePass> pass;
    Scramble(pass);
    const vtkMTimeType before = pass->GetMTime();
    pass->SetQualityPreset(e.Preset);
    Check(Holds(pass, e), e.Name + ": every knob as documented");
    Check(pass->GetAmbientOcclusionRadius() == 0.25, e.Name + ": AmbientOcclusionRadius left alone");
    Check(pass->GetQualityPreset() == e.Preset && e.Name == pass->GetQualityPresetAsString(),
      e.Name + ": GetQualityPreset says so (" + pass->GetQualityPresetAsString() + ")");
    Check(pass->GetMTime() > before, e.Name + ": the pass is modified");
    const vtkMTimeType set = pass->GetMTime();
    pass->SetQualityPreset(e.Preset);
    Check(pass->GetMTime() == set, e.Name + " again: nothing changes, no Modified");
    pass->SetQualityPreset(vtkRayTracePass::CUSTOM);
    Check(Holds(pass, e) && pass->GetMTime() == set, e.Name + ", then CUSTOM: knobs unchanged");
  }
  vtkNew<vtkRayTracePass> pass;
  pass->SetQualityPresetToInteractive();
  Check(pass->GetQualityPreset() == vtkRayTracePass::INTERACTIVE, "SetQualityPresetToInteractive");
  pass->SetQualityPresetToBalanced();
  Check(pass->GetQualityPreset() == vtkRayTracePass::BALANCED, "SetQualityPresetToBalanced");
  pass->SetQualityPresetToExact();
  Check(pass->GetQualityPreset() == vtkRayTracePass::EXACT, "SetQualityPresetToExact");
  Check(Output->GetNumberOfErrors() == 0, "no error so far");
  pass->SetQualityPreset(42);
  Check(Output->GetNumberOfErrors() == 1 && Output->HasErrorContaining("No quality preset 42"),
    "an unknown preset is an error");
  Check(Holds(pass, Presets[2]), "an unknown preset changes nothing");
  Output->Clear();
  // Values no clamp can place: an error each, the knob as it was.
  pass->SetAmbientOcclusionRadius(0.25);
  pass->SetMaximumTextureBufferTexels(5000);
  const vtkMTimeType kept = pass->GetMTime();
  pass->SetAmbientOcclusionRadius(std::nan(""));
  pass->SetMaximumTextureBufferTexels(-1);
  Check(Output->GetNumberOfErrors() == 2 && Output->HasErrorContaining("SetAmbientOcclusionRadius(nan)") &&
      Output->HasErrorContaining("SetMaximumTextureBufferTexels(-1)"),
    "a NaN occlusion radius and a negative texel limit are errors");
  Check(pass->GetAmbientOcclusionRadius() == 0.25 && pass->GetMaximumTextureBufferTexels() == 5000 &&
      pass->GetMTime() == kept,
    "a NaN occlusion radius and a negative texel limit change nothing");
  pass->SetAmbientOcclusionRadius(-3.0);
  Check(pass->GetAmbientOcclusionRadius() == 0.0, "a negative occlusion radius clamps to 0");
  Output->Clear();
  NoVTKOutput("PresetKnobs");
}

/// A knob set after a preset wins; the preset reads CUSTOM until the knob
/// is set back, and the next preset call sets every knob again.
void TestKnobOverrides()
{
  vtkNew<vtkRayTracePass> pass;
  pass->SetQualityPresetToExact();
  pass->SetShadows(false);
  Check(!pass->GetShadows(), "Shadows set after EXACT wins");
  Check(pass->GetSamplesPerPixel() == 4 && pass->GetAmbientOcclusionSamples() == 4 &&
      pass->GetBuildQuality() == 1,
    "the other EXACT knobs stay");
  Check(pass->GetQualityPreset() == vtkRayTracePass::CUSTOM, "EXACT without shadows is CUSTOM");
  pass->SetShadows(true);
  Check(pass->GetQualityPreset() == vtkRayTracePass::EXACT, "shadows back on: EXACT again");

  pass->SetQualityPresetToInteractive();
  pass->SetSamplesPerPixel(4);
  pass->SetPrecisionModeToWorld();
  Check(pass->GetSamplesPerPixel() == 4 && pass->GetPrecisionMode() == vtkRayTracePass::WORLD &&
      !pass->GetShadows() && pass->GetBuildQuality() == 0,
    "SamplesPerPixel and PrecisionMode set after INTERACTIVE win, its other knobs stay");
  Check(std::string(pass->GetQualityPresetAsString()) == "Custom", "and the pass reads Custom");
  pass->SetQualityPresetToInteractive();
  Check(Holds(pass, Presets[0]), "INTERACTIVE again sets every knob back");
  NoVTKOutput("KnobOverrides");
}

/// Each preset renders what it says: progressive accumulation counts frames
/// (EXACT's frames average 4 samples each), INTERACTIVE's shader has no
/// shadow or occlusion rays, the others' have both, and the images differ.
void TestPresetFrames()
{
  auto win = MakeWindow(160, 120);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->AddActor(FloorActor(2.0));
  ren->AddActor(SphereActor(0.0, 0.6, 0.0, 0.5));
  ren->GetActiveCamera()->SetPosition(0.0, 3.0, 4.0);
  ren->GetActiveCamera()->SetFocalPoint(0.0, 0.3, 0.0);
  ren->ResetCameraClippingRange();
  vtkNew<vtkRayTracePass> pass;
  ren->SetPass(pass);
  std::map<std::string, vtkSmartPointer<vtkImageData>> images;
  for (const Expected& e : Presets)
  {
    pass->SetQualityPreset(e.Preset);
    win->Render();
    win->Render();
    const std::string shader = pass->GetLastFragmentShaderSource();
    auto defines = [&shader](const std::string& line) {
      return shader.find("#define " + line + "\n") != std::string::npos;
    };
    Check(pass->GetAccumulatedFrames() == 2,
      e.Name + ": two still frames accumulate (" + std::to_string(pass->GetAccumulatedFrames()) + ")");
    Check(defines("VTKRT_SAMPLES_PER_PIXEL " + std::to_string(e.SamplesPerPixel)) &&
        defines("VTKRT_SHADOWS") == e.Shadows &&
        defines("VTKRT_AMBIENT_OCCLUSION_SAMPLES " + std::to_string(e.AmbientOcclusionSamples)),
      e.Name + ": the frame's shader samples, shadows and occludes as the preset says");
    images[e.Name] = Grab(win);
  }
  const double toBalanced = RootMeanSquareError(images["Interactive"], images["Balanced"]);
  const double toExact = RootMeanSquareError(images["Interactive"], images["Exact"]);
  Check(toBalanced > 1.0 && toExact > 1.0,
    "shadows and occlusion change the image (RMSE " + std::to_string(toBalanced) + ", " +
      std::to_string(toExact) + ")");
  NoVTKOutput("PresetFrames");
  ren->SetPass(nullptr);
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Knobs", TestPresetKnobs },
    { "Overrides", TestKnobOverrides },
    { "Frames", TestPresetFrames },
  };
  return RunCase(argc, argv, cases);
}
