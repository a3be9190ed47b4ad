// Tests the image-regression harness itself: identical and slightly noisy
// images pass, a perturbed image fails and leaves the actual and diff images,
// a size change fails, a missing baseline fails (or is recorded on request).
#include "vtkrtCheck.h"
#include "vtkrtImageRegression.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
using vtkrtTest::Failures;

using vtkrtTest::Check;

// A deterministic RGB test card: gradients plus a disc.
vtkSmartPointer<vtkImageData> MakeCard(int w, int h)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const double dx = x - 0.5 * w, dy = y - 0.5 * h;
      const bool disc = std::sqrt(dx * dx + dy * dy) < 0.3 * h;
      unsigned char* c = p + 3 * (y * w + x);
      c[0] = static_cast<unsigned char>(disc ? 230 : (255 * x) / (w - 1));
      c[1] = static_cast<unsigned char>(disc ? 40 : (255 * y) / (h - 1));
      c[2] = static_cast<unsigned char>(disc ? 40 : 128);
    }
  }
  return image;
}

vtkSmartPointer<vtkImageData> Copy(vtkImageData* image)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(image);
  return copy;
}
} // namespace

int main()
{
  vtkrtTestOutputWindow* output = vtkrtTestOutputWindow::Install();
  const std::string name = "common_TestCard";
  const std::string tmp = VTKRT_TEMP_DIR;
  vtkSmartPointer<vtkImageData> card = MakeCard(96, 64);

  // 1. The same image passes with zero error. (VTKRT_UPDATE_BASELINES=1 may
  // record the checked-in baseline here; later cases run without it.)
  Check(vtkrtCompareWithBaseline(card, name) == 1, "identical image passes");
  unsetenv("VTKRT_UPDATE_BASELINES");
  Check(vtkrtLastImageError() == 0.0, "identical image has zero error");

  // 2. Small noise (below the per-pixel threshold) passes.
  {
    vtkSmartPointer<vtkImageData> noisy = Copy(card);
    auto* p = static_cast<unsigned char*>(noisy->GetScalarPointer());
    for (int i = 0; i < 96 * 64 * 3; i += 7)
    {
      p[i] = static_cast<unsigned char>(p[i] > 3 ? p[i] - 3 : p[i] + 3);
    }
    Check(vtkrtCompareWithBaseline(noisy, name) == 1, "slightly noisy image passes");
  }

  // 3. A perturbed image fails and leaves the actual and diff images.
  {
    const std::string actualPath = tmp + "/" + name + ".png";
    const std::string diffPath = tmp + "/" + name + ".diff.png";
    vtksys::SystemTools::RemoveFile(actualPath);
    vtksys::SystemTools::RemoveFile(diffPath);
    vtkSmartPointer<vtkImageData> perturbed = Copy(card);
    auto* p = static_cast<unsigned char*>(perturbed->GetScalarPointer());
    for (int y = 10; y < 40; ++y)
    {
      for (int x = 10; x < 50; ++x)
      {
        for (int c = 0; c < 3; ++c)
        {
          p[3 * (y * 96 + x) + c] = static_cast<unsigned char>(255 - p[3 * (y * 96 + x) + c]);
        }
      }
    }
    Check(vtkrtCompareWithBaseline(perturbed, name) == 0, "perturbed image fails");
    Check(vtkrtLastImageError() > vtkrtDefaultImageThreshold, "perturbed image error is large");
    Check(vtksys::SystemTools::FileExists(actualPath, true), "actual image written: " + actualPath);
    Check(vtksys::SystemTools::FileExists(diffPath, true), "diff image written: " + diffPath);
  }

  // 4. A different size fails.
  Check(vtkrtCompareWithBaseline(MakeCard(64, 64), name) == 0, "image of another size fails");

  // 5. A missing baseline fails unless VTKRT_UPDATE_BASELINES=1 ...
  const std::string scratch = tmp + "/TestImageRegression-baselines";
  vtksys::SystemTools::RemoveADirectory(scratch);
  Check(vtkrtCompareWithBaselineIn(card, scratch, tmp, "missing", vtkrtDefaultImageThreshold) == 0,
    "missing baseline fails");
  Check(!vtksys::SystemTools::FileExists(scratch + "/missing.png", true),
    "missing baseline is not created without VTKRT_UPDATE_BASELINES");
  // ... which records it, after which it is compared like any other.
  setenv("VTKRT_UPDATE_BASELINES", "1", 1);
  Check(vtkrtCompareWithBaselineIn(card, scratch, tmp, "missing", vtkrtDefaultImageThreshold) == 1,
    "missing baseline recorded with VTKRT_UPDATE_BASELINES=1");
  unsetenv("VTKRT_UPDATE_BASELINES");
  Check(vtksys::SystemTools::FileExists(scratch + "/missing.png", true), "recorded baseline exists");
  Check(vtkrtCompareWithBaselineIn(card, scratch, tmp, "missing", vtkrtDefaultImageThreshold) == 1,
    "recorded baseline then passes");
  vtksys::SystemTools::RemoveADirectory(scratch);

  Check(output->GetNumberOfErrors() == 0 && output->GetNumberOfWarnings() == 0,
    "no VTK error or warning");
  std::cout << (Failures ? "FAILED: " : "passed: ") << Failures << " failure(s)\n";
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
