// What vtkrt-render hands back: the clock of its timings, the PNG of the
// window, and the report on stdout.
#ifndef vtkrtRenderReport_h
#define vtkrtRenderReport_h

#include <chrono>
#include <string>
#include <vector>

class vtkEGLHeadlessRenderWindow;
class vtkRenderer;

namespace vtkrtRender
{
class CapturingOutputWindow;
struct Options;
struct Scene;

using Clock = std::chrono::steady_clock;

inline double Milliseconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Milliseconds of the three phases the report shows.
struct Timings
{
  double SceneBuild = 0.0;  // read + set up
  double FirstFrame = 0.0;  // context, upload, build
  double SteadyFrame = 0.0; // mean of the orbit steps; 0 without them
  // Ray traced: the pass's first frame by phase (extraction, triangulation,
  // BVH build, packing, upload, shader compile); empty in raster mode.
  std::vector<double> PassPhases;
  int AccumulatedFrames = 0; // the pass's, after --progressive
  double Accumulation = 0.0; // milliseconds of the --progressive frames
};

// Keeps the pass's phases of the frame just drawn (none without a pass).
void KeepPassPhases(vtkRenderer* renderer, Timings& timings);

// Writes the window's front buffer to `path`, as PNG, JPEG, TIFF or BMP by
// its extension; VTK's writer errors are caught through `output`. Throws
// Failure.
void WriteImage(
  vtkEGLHeadlessRenderWindow* window, const std::string& path, CapturingOutputWindow* output);

// The report on stdout: mode, scene, device, timings, the picks (one line
// each) and the file written.
void PrintReport(const Options& opt, const Scene& scene, vtkEGLHeadlessRenderWindow* window,
  const Timings& timings, const std::vector<std::string>& picks);
} // namespace vtkrtRender

#endif
