// vtkrt-render's command line: the options, their parser (CLI11) and the
// help text generated from it. The one unit that knows the argument syntax.
#ifndef vtkrtRenderOptions_h
#define vtkrtRenderOptions_h

#include <array>
#include <ostream>
#include <string>
#include <vector>

namespace vtkrtRender
{
using Vector3 = std::array<double, 3>;

// Colouring by a data array (--scalars and what refines it).
struct ScalarOptions
{
  bool Enabled = false;
  std::string Array;  // empty: the active scalars (else the first array)
  bool Cells = false; // cell data instead of point data
  int Component = -1; // -1: magnitude
  bool RangeGiven = false;
  double Range[2] = { 0.0, 1.0 };
  std::string Colormap = "viridis";
  bool Bar = false;
};

// The camera beyond the orbit: up axis, explicit placement, zoom.
struct CameraOptions
{
  std::string Up = "+Y";
  bool OrbitGiven = false; // --azimuth or --elevation on the command line
  bool PositionGiven = false, FocalPointGiven = false, ViewUpGiven = false;
  Vector3 Position{}, FocalPoint{}, ViewUp{};
  double ViewAngle = 30.0;
  double Zoom = 1.0;
};

// What the ray tracer does beyond one ray a pixel. What is not given leaves
// the pass's own setting (its default, or a quality preset's).
struct TraceOptions
{
  bool Shadows = false;      // on when given
  int AmbientOcclusion = -1; // rays per sample; -1 not given
  int Progressive = 0;       // frames accumulated before writing; 0 not given
  std::string Precision;     // "camera" or "world"; empty not given
  std::string Preset;        // "interactive", "balanced" or "exact"; empty not given
};

// Surface appearance and background.
struct LookOptions
{
  bool ColorGiven = false;
  Vector3 Color{ 0.80, 0.82, 0.88 };
  double Opacity = 1.0;
  bool Edges = false;
  double PointSize = 3.0;
  Vector3 Background{ 0.32, 0.34, 0.43 };
};

struct Pixel
{
  int X = 0;
  int Y = 0;
};

struct Options
{
  bool Demo = false;
  std::vector<std::string> MeshFiles;
  int Width = 800;
  int Height = 600;
  double Azimuth = 30.0;
  double Elevation = 20.0;
  std::string Output = "vtkrt-render.png";
  bool OutputGiven = false;
  std::string Mode; // "raster" or "raytrace"; empty: raytrace when built
  int Samples = -1; // -1: the mode's default (raster 0 MSAA, raytrace 1 ray)
  int Frames = 8;
  std::vector<Pixel> Picks;
  bool Verbose = false;
  std::string InteractionPlay; // event log for the window (tests)
  ScalarOptions Scalars;
  CameraOptions Camera;
  TraceOptions Trace;
  LookOptions Look;
};

// Thrown for wrong arguments or input that does not match them (an unknown
// array name): one message, exit status 2.
struct UsageError
{
  std::string Message;
};

// The options of argv; `help` is set (and the rest left default) when
// --help or -h is given. Throws UsageError.
Options ParseArguments(int argc, char* argv[], bool& help);

// The --help text, generated from the option table, with what this build has.
void PrintHelp(std::ostream& os);

// The colormaps --colormap knows, in help order.
const std::vector<std::string>& ColormapNames();
} // namespace vtkrtRender

#endif
