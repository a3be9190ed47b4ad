// Tests of vtkRayTracePass's speed/accuracy knobs (sub-pixel sampling and
// progressive accumulation, ...): each case asserts what the knob changes in
// the image, that its shader code is present only when the knob is used, and
// compares against a baseline under data/baselines/.
// TestRayTracePassKnobs <Case>.
#include "vtkrtImageRegression.h"
#include "vtkrtPassTestUtils.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace vtkrtPassTest;

namespace
{
int Failures = 0;
vtkrtTestOutputWindow* Output = nullptr;

void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  if (!ok)
  {
    ++Failures;
  }
}

void NoVTKOutput(const std::string& label)
{
  Check(Output->GetNumberOfErrors() == 0 && Output->GetNumberOfWarnings() == 0,
    label + ": no VTK error or warning");
  Output->Clear();
}

/// Pixels whose red channel is strictly between lo and hi.
long CountIntermediatePixels(vtkImageData* image, int lo, int hi)
{
  int d[3];
  image->GetDimensions(d);
  const int comps = image->GetNumberOfScalarComponents();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  long count = 0;
  for (long i = 0; i < static_cast<long>(d[0]) * d[1]; ++i)
  {
    count += (p[i * comps] > lo && p[i * comps] < hi) ? 1 : 0;
  }
  return count;
}

bool HasDefine(vtkRayTracePass* pass, const std::string& define)
{
  return std::string(pass->GetLastFragmentShaderSource()).find("#define " + define) !=
    std::string::npos;
}

/// Sub-pixel sampling and progressive accumulation, on an unlit white sphere
/// over black (every pixel of a one-ray image is 0 or 255).
void TestSampling()
{
  const int size = 160;
  auto win = MakeWindow(size, size);
  vtkNew<vtkRenderer> ren;
  win->AddRenderer(ren);
  ren->SetBackground(0.0, 0.0, 0.0);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  ren->AddActor(actor);
  ren->ResetCamera();

  // One centered ray per pixel, straight to the framebuffer.
  vtkNew<vtkRayTracePass> direct;
  ren->SetPass(direct);
  win->Render();
  auto single = Grab(win);
  const float centerDepth = win->GetZbufferDataAtPoint(size / 2, size / 2);
  Check(direct->GetAccumulatedFrames() == 0, "direct: no accumulation");
  Check(!HasDefine(direct, "VTKRT_SAMPLES_PER_PIXEL"), "direct: no sampling code in the shader");
  const long hard = CountIntermediatePixels(single, 16, 240);
  Check(hard == 0, "direct: a one-ray silhouette is hard (" + std::to_string(hard) +
      " intermediate pixels)");

  // Progressive, 1 sample per frame: frame 1 is the pixel center again.
  vtkNew<vtkRayTracePass> progressive;
  progressive->ProgressiveAccumulationOn();
  ren->SetPass(progressive);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "progressive: first frame accumulates 1");
  Check(HasDefine(progressive, "VTKRT_SAMPLES_PER_PIXEL 1"), "progressive: sampling code compiled");
  auto first = Grab(win);
  const long firstDiff = CountDifferingPixels(first, single, 1);
  Check(firstDiff == 0,
    "progressive frame 1 equals the one-ray image (" + std::to_string(firstDiff) + " differ)");
  const int n = 8;
  for (int k = 1; k < n; ++k)
  {
    win->Render();
  }
  Check(progressive->GetAccumulatedFrames() == n,
    "progressive: " + std::to_string(progressive->GetAccumulatedFrames()) + " frames accumulated, " +
      std::to_string(n) + " expected");
  Check(progressive->GetLastShaderCompiles() == 0 && progressive->GetLastBVHBuilds() == 0,
    "progressive: unchanged frames compile and build nothing");
  auto accumulated = Grab(win);

  // One frame of n samples: the same sample sequence, so the same image
  // (up to float summation order: 1/255 per channel).
  vtkNew<vtkRayTracePass> sampled;
  sampled->SetSamplesPerPixel(n);
  ren->SetPass(sampled);
  win->Render();
  Check(sampled->GetAccumulatedFrames() == 1, "sampled: one frame, no progressive accumulation");
  auto multi = Grab(win);
  const float sampledDepth = win->GetZbufferDataAtPoint(size / 2, size / 2);
  Check(centerDepth < 1.0f && std::abs(sampledDepth - centerDepth) < 1e-3f,
    "sampled: the hit's depth is written (" + std::to_string(sampledDepth) + " vs one ray " +
      std::to_string(centerDepth) + ")");
  const long sameDiff = CountDifferingPixels(accumulated, multi, 1);
  Check(sameDiff == 0,
    std::to_string(n) + " frames of 1 sample equal 1 frame of " + std::to_string(n) +
      " samples within 1/255 (" + std::to_string(sameDiff) + " differ)");
  const long soft = CountIntermediatePixels(multi, 16, 240);
  // The silhouette circle (radius ~ 1/3 of the image) crosses ~2*pi*r pixels.
  const long perimeter = static_cast<long>(2.0 * 3.14159 * size / 3.5);
  Check(soft > perimeter / 2,
    "sampled: silhouette pixels take intermediate values (" + std::to_string(soft) + " > " +
      std::to_string(perimeter / 2) + ")");
  win->Render();
  Check(sampled->GetAccumulatedFrames() == 1, "sampled without progressive: every frame restarts");
  Check(vtkrtCompareWithBaseline(multi, "pass_Sampling") == 1, "sampled: matches its baseline");

  // Any change restarts the accumulation.
  ren->SetPass(progressive);
  win->Render();
  win->Render();
  Check(progressive->GetAccumulatedFrames() >= 2, "progressive: accumulating again");
  ren->GetActiveCamera()->Azimuth(5.0);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "camera moved: accumulation restarts");
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 2, "unchanged after the move: 2 frames");
  actor->GetProperty()->SetColor(1.0, 0.5, 0.5);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "property changed: accumulation restarts");
  win->Render();
  sphere->SetThetaResolution(40);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "data changed: accumulation restarts");
  win->Render();
  win->SetSize(size + 20, size);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "window resized: accumulation restarts");
  win->Render();
  progressive->SetSamplesPerPixel(2);
  win->Render();
  Check(progressive->GetAccumulatedFrames() == 1, "samples per pixel changed: restarts");
  NoVTKOutput("Sampling");
  ren->SetPass(nullptr);
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Sampling", TestSampling },
  };
  const std::string which = argc > 1 ? argv[1] : "";
  auto it = cases.find(which);
  if (it == cases.end())
  {
    std::cerr << "usage: " << argv[0] << " <case>; cases:";
    for (const auto& c : cases)
    {
      std::cerr << " " << c.first;
    }
    std::cerr << "\n";
    return EXIT_FAILURE;
  }
  it->second();
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
