// vtkrt-render's command line: the options, their parser and the help text.
// The one unit that knows the argument syntax.
#ifndef vtkrtRenderOptions_h
#define vtkrtRenderOptions_h

#include <ostream>
#include <string>

namespace vtkrtRender
{
struct Options
{
  bool Demo = false;
  std::string MeshFile;
  int Width = 800;
  int Height = 600;
  double Azimuth = 30.0;
  double Elevation = 20.0;
  std::string Output = "vtkrt-render.png";
  std::string Mode = "raster";
  int Samples = 0;
  int Frames = 8;
  bool Pick = false;
  int PickX = 0;
  int PickY = 0;
};

// Thrown for wrong arguments: one message, exit status 2.
struct UsageError
{
  std::string Message;
};

// The options of argv; `help` is set (and the rest left default) when
// --help or -h is given. Throws UsageError.
Options ParseArguments(int argc, char* argv[], bool& help);

// The --help text, with what this build has.
void PrintHelp(std::ostream& os);
} // namespace vtkrtRender

#endif
