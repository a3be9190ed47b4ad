#include "RenderOptions.h"

#include <cmath>
#include <cstdlib>

namespace vtkrtRender
{
namespace
{
const char* const Usage =
  R"(usage: vtkrt-render [options] (--demo | MESH_FILE)

Renders a mesh (.vtp .vtk .ply .obj .stl) or the built-in demo scene (a mesh
plus sphere glyphs) headless through EGL and writes a PNG.

  --demo               render the demo scene (bunny + sphere glyphs)
  --size WxH           image size in pixels (default 800x600)
  --azimuth DEG        orbit the camera about the view up (default 30)
  --elevation DEG      orbit the camera up/down (default 20)
  --output FILE        PNG to write (default vtkrt-render.png)
  --mode raster|raytrace
                       VTK's rasterizer (default) or the vtkrt ray tracer
  --samples N          samples per pixel (raster: MSAA samples; default 0)
  --frames N           orbit steps timed for the steady frame time (default 8;
                       0 skips them)
  --pick X Y           pick the pixel (X, Y) of the image (origin top left;
                       the ray through its centre) with vtkCellPicker; prints
                       the cell id and world point (or the glyph sphere hit)
  --help               this text

Exit status: 0 success, 1 runtime error (unreadable file, no EGL/GL context,
cannot write the image), 2 wrong arguments, 3 mode not available in this build.
)";

bool ParseInt(const std::string& text, int& value)
{
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < -(1L << 30) || v > (1L << 30))
  {
    return false;
  }
  value = static_cast<int>(v);
  return true;
}

bool ParseDouble(const std::string& text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && std::isfinite(value);
}

// argv with a cursor: an option takes its values from the words after it.
struct Arguments
{
  int Count;
  char** Words;
  int Index;

  std::string Next(const std::string& name)
  {
    if (this->Index + 1 >= this->Count)
    {
      throw UsageError{ name + " needs a value" };
    }
    return this->Words[++this->Index];
  }
};

// --size, --azimuth, --elevation, --output: the image and the view. False
// when `arg` is none of them.
bool ParseImageOption(const std::string& arg, Arguments& args, Options& opt)
{
  if (arg == "--size")
  {
    const std::string v = args.Next(arg);
    const size_t x = v.find_first_of("xX");
    if (x == std::string::npos || !ParseInt(v.substr(0, x), opt.Width) ||
      !ParseInt(v.substr(x + 1), opt.Height) || opt.Width < 1 || opt.Height < 1 ||
      opt.Width > 16384 || opt.Height > 16384)
    {
      throw UsageError{ "--size expects WxH with 1 <= W, H <= 16384, e.g. 1024x768 (got '" + v +
        "')" };
    }
  }
  else if (arg == "--azimuth" || arg == "--elevation")
  {
    const std::string v = args.Next(arg);
    if (!ParseDouble(v, arg == "--azimuth" ? opt.Azimuth : opt.Elevation))
    {
      throw UsageError{ arg + " expects a number of degrees (got '" + v + "')" };
    }
  }
  else if (arg == "--output" || arg == "-o")
  {
    opt.Output = args.Next(arg);
    if (opt.Output.empty())
    {
      throw UsageError{ "--output expects a file name" };
    }
  }
  else
  {
    return false;
  }
  return true;
}

// --mode, --samples, --frames, --pick: how to render and what to measure.
// False when `arg` is none of them.
bool ParseRenderOption(const std::string& arg, Arguments& args, Options& opt)
{
  if (arg == "--mode")
  {
    opt.Mode = args.Next(arg);
    if (opt.Mode != "raster" && opt.Mode != "raytrace")
    {
      throw UsageError{ "--mode expects raster or raytrace (got '" + opt.Mode + "')" };
    }
  }
  else if (arg == "--samples")
  {
    const std::string v = args.Next(arg);
    if (!ParseInt(v, opt.Samples) || opt.Samples < 0 || opt.Samples > 64)
    {
      throw UsageError{ "--samples expects an integer in [0, 64] (got '" + v + "')" };
    }
  }
  else if (arg == "--frames")
  {
    const std::string v = args.Next(arg);
    if (!ParseInt(v, opt.Frames) || opt.Frames < 0 || opt.Frames > 10000)
    {
      throw UsageError{ "--frames expects an integer in [0, 10000] (got '" + v + "')" };
    }
  }
  else if (arg == "--pick")
  {
    const std::string x = args.Next(arg);
    const std::string y = args.Next(arg);
    if (!ParseInt(x, opt.PickX) || !ParseInt(y, opt.PickY))
    {
      throw UsageError{ "--pick expects two integer pixel coordinates X Y (got '" + x + "' '" +
        y + "')" };
    }
    opt.Pick = true;
  }
  else
  {
    return false;
  }
  return true;
}

// A word that is no option: the one mesh file.
void TakeMeshFile(const std::string& arg, Options& opt)
{
  if (!arg.empty() && arg[0] == '-')
  {
    throw UsageError{ "unknown option '" + arg + "'" };
  }
  if (!opt.MeshFile.empty())
  {
    throw UsageError{ "only one mesh file can be given ('" + opt.MeshFile + "', then '" + arg +
      "')" };
  }
  opt.MeshFile = arg;
}

// What each option allows alone but the whole command line does not.
void CheckCombination(const Options& opt)
{
  if (opt.Demo == !opt.MeshFile.empty())
  {
    throw UsageError{ opt.Demo ? "give either --demo or a mesh file, not both"
                               : "nothing to render: give a mesh file or --demo" };
  }
  if (opt.Pick &&
    (opt.PickX < 0 || opt.PickY < 0 || opt.PickX >= opt.Width || opt.PickY >= opt.Height))
  {
    throw UsageError{ "--pick " + std::to_string(opt.PickX) + " " + std::to_string(opt.PickY) +
      " is outside the " + std::to_string(opt.Width) + "x" + std::to_string(opt.Height) +
      " image" };
  }
}
} // namespace

Options ParseArguments(int argc, char* argv[], bool& help)
{
  Options opt;
  help = false;
  Arguments args{ argc, argv, 1 };
  for (; args.Index < argc; ++args.Index)
  {
    const std::string arg = argv[args.Index];
    if (arg == "--help" || arg == "-h")
    {
      help = true;
      return opt;
    }
    else if (arg == "--demo")
    {
      opt.Demo = true;
    }
    else if (!ParseImageOption(arg, args, opt) && !ParseRenderOption(arg, args, opt))
    {
      TakeMeshFile(arg, opt);
    }
  }
  CheckCombination(opt);
  return opt;
}

void PrintHelp(std::ostream& os)
{
  os << Usage << "\nThis build: raytrace mode "
#ifdef VTKRT_HAVE_RAYTRACE_PASS
     << "available"
#else
     << "not available"
#endif
     << "; picking with vtkBVHCellLocator "
#ifdef VTKRT_HAVE_BVH_LOCATOR
     << "available"
#else
     << "not available"
#endif
     << ".\n";
}
} // namespace vtkrtRender
