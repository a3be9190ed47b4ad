/**
 * Image regression for vtkrt's tests.
 *
 * vtkrtCompareWithBaseline compares an image with data/baselines/<name>.png
 * through vtkImageDifference (averaging on, per-pixel Threshold 16, no
 * shift), passing when its thresholded error is <= `threshold`. In VTK 9.1
 * that error is summed over the image: each pixel adds its colour
 * difference scaled to [0, 1], so it reads as "about this many wholly wrong
 * pixels" (vtkTesting's default is 10).
 * - Failure (difference or size mismatch): writes the image to
 *   <build>/Testing/Temporary/<name>.png and the difference image to
 *   <name>.diff.png there, and prints both paths.
 * - Missing baseline: fails with a clear message, unless the environment has
 *   VTKRT_UPDATE_BASELINES=1, in which case the image becomes the baseline
 *   (written into the source tree) and the comparison passes.
 * Images are compared as RGB (alpha dropped).
 *
 * Tests linking vtkrtTesting get the compile definitions VTKRT_DATA_DIR
 * (the source tree's data/) and VTKRT_TEMP_DIR (<build>/Testing/Temporary).
 */
#ifndef vtkrtImageRegression_h
#define vtkrtImageRegression_h

#include <string>

class vtkImageData;
class vtkRenderWindow;

/// Default for `threshold`, as vtkTesting::RegressionTest's in VTK 9.1.
constexpr double vtkrtDefaultImageThreshold = 10.0;

/**
 * Reads the window's current image (front buffer, no re-render) and compares
 * it. Returns 1 on pass, 0 on failure (after printing why).
 */
int vtkrtCompareWithBaseline(vtkRenderWindow* window, const std::string& baselineName,
  double threshold = vtkrtDefaultImageThreshold);

/**
 * Compares an image (unsigned char, 1-4 components). Returns 1 on pass, 0 on
 * failure.
 */
int vtkrtCompareWithBaseline(vtkImageData* image, const std::string& baselineName,
  double threshold = vtkrtDefaultImageThreshold);

/**
 * As above with explicit directories: baselines are <baselineDir>/<name>.png
 * and failure images go to <outputDir>. The functions above use
 * VTKRT_DATA_DIR "/baselines" and VTKRT_TEMP_DIR.
 */
int vtkrtCompareWithBaselineIn(vtkImageData* image, const std::string& baselineDir,
  const std::string& outputDir, const std::string& baselineName, double threshold);

/**
 * The thresholded error of the last comparison made in this process
 * (-1 when none or when the images could not be compared).
 */
double vtkrtLastImageError();

#endif
