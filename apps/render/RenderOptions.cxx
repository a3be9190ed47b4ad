#include "RenderOptions.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace vtkrtRender
{
namespace
{
const char* const Description =
  R"(Renders meshes (.vtp .vtu .vti .vts .vtr .vtm .vtk .ply .obj .stl .gltf .glb .g),
several in one scene, or the built-in demo scene (a mesh plus sphere glyphs):
ray traced by vtkRayTracePass (or rasterized by VTK with --mode raster)
headless through EGL into an image (.png .jpg .tif .bmp), or, with a display
and no --output, in a window to look around in (keys below).)";

const char* const Footer = R"(
Window keys: left drag rotates, right drag or wheel zooms, middle drag pans;
h shadows on/off, q ambient occlusion on/off, b scalar bar on/off, p picks the
cell under the cursor (printed on stdout), r resets the view, Escape or e quits.

Exit status: 0 success, 1 runtime error (unreadable file, no EGL/GL context,
cannot write the image), 2 wrong arguments (or an array the files do not
have), 3 mode not available in this build.
)";

// The command line as words, before the values are checked.
struct Words
{
  std::string Size, Resolution, Output, Mode, Samples, Frames, Azimuth, Elevation;
  std::vector<std::string> Picks;
  std::string Scalars, Comp, Range, Colormap;
  std::string Up, Position, FocalPoint, ViewUp, ViewAngle, Zoom;
  std::string Ao, Progressive, Precision, Preset;
  std::string Color, Opacity, PointSize, Background;
};

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

// "a,b,c" into exactly `n` finite numbers.
bool ParseNumbers(const std::string& text, size_t n, double* values)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ','))
  {
    parts.push_back(part);
  }
  if (parts.size() != n || (!text.empty() && text.back() == ','))
  {
    return false;
  }
  for (size_t i = 0; i < n; ++i)
  {
    if (!ParseDouble(parts[i], values[i]))
    {
      return false;
    }
  }
  return true;
}

int IntIn(const std::string& name, const std::string& text, int lo, int hi)
{
  int v = 0;
  if (!ParseInt(text, v) || v < lo || v > hi)
  {
    throw UsageError{ name + " expects an integer in [" + std::to_string(lo) + ", " +
      std::to_string(hi) + "] (got '" + text + "')" };
  }
  return v;
}

double NumberIn(const std::string& name, const std::string& text, double lo, double hi)
{
  double v = 0.0;
  if (!ParseDouble(text, v) || v < lo || v > hi)
  {
    std::ostringstream range;
    range << "[" << lo << ", " << hi << "]";
    throw UsageError{ name + " expects a number in " + range.str() + " (got '" + text + "')" };
  }
  return v;
}

Vector3 VectorOf(const std::string& name, const std::string& text)
{
  Vector3 v{};
  if (!ParseNumbers(text, 3, v.data()))
  {
    throw UsageError{ name + " expects three numbers X,Y,Z (got '" + text + "')" };
  }
  return v;
}

Vector3 ColorOf(const std::string& name, const std::string& text)
{
  Vector3 c = VectorOf(name, text);
  if (*std::min_element(c.begin(), c.end()) < 0.0 || *std::max_element(c.begin(), c.end()) > 1.0)
  {
    throw UsageError{ name + " expects R,G,B in [0, 1] (got '" + text + "')" };
  }
  return c;
}

void SizeOf(const std::string& name, const std::string& text, char separator, Options& opt)
{
  const size_t x = separator == 'x' ? text.find_first_of("xX") : text.find(',');
  if (x == std::string::npos || !ParseInt(text.substr(0, x), opt.Width) ||
    !ParseInt(text.substr(x + 1), opt.Height) || opt.Width < 1 || opt.Height < 1 ||
    opt.Width > 16384 || opt.Height > 16384)
  {
    const std::string form = separator == 'x' ? "WxH" : "W,H";
    throw UsageError{ name + " expects " + form + " with 1 <= W, H <= 16384, e.g. " +
      (separator == 'x' ? "1024x768" : "1024,768") + " (got '" + text + "')" };
  }
}

// The option table: every option with its help line, bound to `words` (or
// straight to `opt` for flags).
void DeclareOptions(CLI::App& app, Words& w, Options& opt)
{
  app.add_flag("--demo", opt.Demo, "render the demo scene (bunny + sphere glyphs)");
  app.add_option("files", opt.MeshFiles, "mesh files, rendered together")->type_name("FILE");
  app.add_option("--resolution", w.Resolution, "image size in pixels (default 800,600)")
    ->type_name("W,H");
  app.add_option("--size", w.Size, "the same as WxH")->type_name("WxH");
  app
    .add_option("-o,--output", w.Output,
      "image to write, by extension .png .jpg .tif .bmp (default: a window when there is a "
      "display, else vtkrt-render.png)")
    ->type_name("FILE");
  app.add_option("--mode", w.Mode, "raytrace (default; vtkRayTracePass) or raster (VTK's)")
    ->type_name("raytrace|raster");
  app
    .add_option("--samples", w.Samples,
      "raytrace: rays per pixel (default 1); raster: MSAA samples (default 0)")
    ->type_name("N");
  app.add_flag("--shadows", opt.Trace.Shadows, "raytrace: hard shadows");
  app.add_option("--ao", w.Ao, "raytrace: ambient occlusion rays per sample (0 off)")
    ->type_name("N");
  app
    .add_option("--progressive", w.Progressive,
      "raytrace: frames accumulated before writing (progressive accumulation)")
    ->type_name("N");
  app
    .add_option("--preset", w.Preset,
      "raytrace: quality preset; the knobs given beside it override it")
    ->type_name("interactive|balanced|exact");
  app
    .add_option("--precision", w.Precision,
      "raytrace: GPU coordinates relative to the eye (default) or plain world floats")
    ->type_name("camera|world");
  app
    .add_option(
      "--frames", w.Frames, "orbit steps timed for the steady frame time (default 8; 0 skips them)")
    ->type_name("N");
  app
    .add_option("--pick", w.Picks,
      "pick the pixel (X, Y) of the image (origin top left) and print the cell id and "
      "world point (or the glyph sphere); repeatable")
    ->type_name("X Y")
    ->expected(2)
    ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_flag("-v,--verbose", opt.Verbose, "progress on stderr even when it is no terminal");
}

void DeclareScalarOptions(CLI::App& app, Words& w, Options& opt)
{
  app.add_flag("--scalars{@active@}", w.Scalars,
    "colour by a point array, NAME or the active scalars (--scalars=NAME)");
  app.add_flag("--cells", opt.Scalars.Cells, "--scalars takes cell arrays");
  app.add_option("--comp", w.Comp, "component to colour by (default -1: magnitude)")
    ->type_name("N");
  app.add_option("--range", w.Range, "scalar range (default: the union of the files' ranges)")->type_name("MIN,MAX");
  std::string names;
  for (const std::string& n : ColormapNames())
  {
    names += (names.empty() ? "" : "|") + n;
  }
  app.add_option("--colormap", w.Colormap, "colormap (default viridis)")->type_name(names);
  app.add_flag("--bar", opt.Scalars.Bar, "show a scalar bar");
}

void DeclareCameraOptions(CLI::App& app, Words& w)
{
  app.add_option("--up", w.Up, "up axis (default +Y)")->type_name("+X|-X|+Y|-Y|+Z|-Z");
  app.add_option("--azimuth", w.Azimuth, "orbit about the view up (default 30)")->type_name("DEG");
  app.add_option("--elevation", w.Elevation, "orbit up/down (default 20)")->type_name("DEG");
  app.add_option("--camera-position", w.Position, "camera position")->type_name("X,Y,Z");
  app.add_option("--camera-focal-point", w.FocalPoint, "camera focal point")->type_name("X,Y,Z");
  app.add_option("--camera-view-up", w.ViewUp, "camera view up")->type_name("X,Y,Z");
  app.add_option("--camera-view-angle", w.ViewAngle, "vertical view angle (default 30)")
    ->type_name("DEG");
  app.add_option("--camera-zoom-factor,--zoom", w.Zoom, "zoom in (> 1) or out (< 1) last")
    ->type_name("F");
}

void DeclareLookOptions(CLI::App& app, Words& w, Options& opt)
{
  app.add_option("--color", w.Color, "surface colour (default 0.8,0.82,0.88)")->type_name("R,G,B");
  app.add_option("--opacity", w.Opacity, "surface opacity (traced; with --edges: rasterized)")->type_name("A");
  app.add_flag("--edges", opt.Look.Edges, "show cell edges (traced; with --opacity below 1: rasterized)");
  app.add_option("--point-size", w.PointSize, "size of points in pixels (point clouds)")
    ->type_name("PX");
  app.add_option("--bg-color", w.Background, "background colour")->type_name("R,G,B");
  app
    .add_option("--interaction-test-play", opt.InteractionPlay,
      "window: play a vtkInteractorEventRecorder log, then quit (for tests)")
    ->type_name("FILE");
}

void CheckImageWords(const CLI::App& app, const Words& w, Options& opt)
{
  if (app.count("--size") && app.count("--resolution"))
  {
    throw UsageError{ "--size and --resolution both give the image size: give one" };
  }
  if (app.count("--size"))
  {
    SizeOf("--size", w.Size, 'x', opt);
  }
  if (app.count("--resolution"))
  {
    SizeOf("--resolution", w.Resolution, ',', opt);
  }
  if (app.count("--output"))
  {
    opt.Output = w.Output;
    opt.OutputGiven = true;
    const size_t dot = opt.Output.rfind('.');
    std::string ext = dot == std::string::npos ? "" : opt.Output.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".tif" && ext != ".tiff" &&
      ext != ".bmp")
    {
      throw UsageError{ "--output '" + opt.Output +
        "': unknown image type (expected .png .jpg .jpeg .tif .tiff .bmp)" };
    }
  }
  if (w.Picks.size() % 2 != 0)
  {
    throw UsageError{ "--pick needs a value (two: X Y)" };
  }
  for (size_t i = 0; i < w.Picks.size(); i += 2)
  {
    Pixel p;
    if (!ParseInt(w.Picks[i], p.X) || !ParseInt(w.Picks[i + 1], p.Y))
    {
      throw UsageError{ "--pick expects two integer pixel coordinates X Y (got '" + w.Picks[i] +
        "' '" + w.Picks[i + 1] + "')" };
    }
    opt.Picks.push_back(p);
  }
}

void CheckRenderWords(const CLI::App& app, const Words& w, Options& opt)
{
  if (app.count("--mode"))
  {
    opt.Mode = w.Mode;
    if (opt.Mode != "raster" && opt.Mode != "raytrace")
    {
      throw UsageError{ "--mode expects raster or raytrace (got '" + opt.Mode + "')" };
    }
  }
  if (app.count("--samples"))
  {
    // Raster's 0 is no MSAA; a traced pixel needs a ray.
    opt.Samples = IntIn("--samples", w.Samples, opt.Mode == "raster" ? 0 : 1, 256);
  }
  if (app.count("--frames"))
  {
    opt.Frames = IntIn("--frames", w.Frames, 0, 10000);
  }
  if (app.count("--ao"))
  {
    opt.Trace.AmbientOcclusion = IntIn("--ao", w.Ao, 0, 64);
  }
  if (app.count("--progressive"))
  {
    opt.Trace.Progressive = IntIn("--progressive", w.Progressive, 0, 100000);
  }
  if (app.count("--preset"))
  {
    opt.Trace.Preset = w.Preset;
    if (w.Preset != "interactive" && w.Preset != "balanced" && w.Preset != "exact")
    {
      throw UsageError{ "--preset expects interactive, balanced or exact (got '" + w.Preset +
        "')" };
    }
  }
  if (!opt.Trace.Preset.empty() && opt.Trace.Preset != "interactive" && !app.count("--progressive"))
  {
    opt.Trace.Progressive = 16; // an image of a converging preset is its still view, converged
  }
  if (app.count("--precision"))
  {
    opt.Trace.Precision = w.Precision;
    if (w.Precision != "camera" && w.Precision != "world")
    {
      throw UsageError{ "--precision expects camera or world (got '" + w.Precision + "')" };
    }
  }
  std::string ignored;
  for (const char* traceOnly : { "--shadows", "--ao", "--progressive", "--preset", "--precision" })
  {
    if (opt.Mode == "raster" && app.count(traceOnly))
    {
      ignored += std::string(ignored.empty() ? "" : ", ") + traceOnly;
    }
  }
  if (!ignored.empty())
  {
    std::cerr << "vtkrt-render: note: " << ignored << " apply to raytrace mode; ignored with --mode raster\n";
  }
}

void CheckScalarWords(const CLI::App& app, const Words& w, Options& opt)
{
  ScalarOptions& s = opt.Scalars;
  s.Enabled = app.count("--scalars") > 0;
  s.Array = w.Scalars == "@active@" ? std::string() : w.Scalars;
  if (app.count("--comp"))
  {
    s.Component = IntIn("--comp", w.Comp, -1, 15);
  }
  if (app.count("--range"))
  {
    s.RangeGiven = true;
    if (!ParseNumbers(w.Range, 2, s.Range) || !(s.Range[0] < s.Range[1]))
    {
      throw UsageError{ "--range expects MIN,MAX with MIN < MAX (got '" + w.Range + "')" };
    }
  }
  if (app.count("--colormap"))
  {
    const std::vector<std::string>& names = ColormapNames();
    if (std::find(names.begin(), names.end(), w.Colormap) == names.end())
    {
      std::string known;
      for (const std::string& n : names)
      {
        known += " " + n;
      }
      throw UsageError{ "--colormap: no colormap '" + w.Colormap + "' (known:" + known + ")" };
    }
    s.Colormap = w.Colormap;
  }
  const bool refined = app.count("--cells") || app.count("--comp") || app.count("--range") ||
    app.count("--colormap") || app.count("--bar");
  s.Enabled = s.Enabled || refined; // a refinement implies colouring, as in f3d
}

void CheckCameraWords(const CLI::App& app, const Words& w, Options& opt)
{
  CameraOptions& c = opt.Camera;
  if (app.count("--up"))
  {
    static const char* const axes[] = { "+X", "-X", "+Y", "-Y", "+Z", "-Z", "X", "Y", "Z" };
    if (std::find(std::begin(axes), std::end(axes), w.Up) == std::end(axes))
    {
      throw UsageError{ "--up expects one of +X -X +Y -Y +Z -Z (got '" + w.Up + "')" };
    }
    c.Up = w.Up.size() == 1 ? "+" + w.Up : w.Up;
  }
  for (const char* name : { "--azimuth", "--elevation" })
  {
    if (app.count(name))
    {
      const std::string& v = name[2] == 'a' ? w.Azimuth : w.Elevation;
      if (!ParseDouble(v, name[2] == 'a' ? opt.Azimuth : opt.Elevation))
      {
        throw UsageError{ std::string(name) + " expects a number of degrees (got '" + v + "')" };
      }
      c.OrbitGiven = true;
    }
  }
  c.PositionGiven = app.count("--camera-position") > 0;
  c.FocalPointGiven = app.count("--camera-focal-point") > 0;
  c.ViewUpGiven = app.count("--camera-view-up") > 0;
  if (c.PositionGiven)
  {
    c.Position = VectorOf("--camera-position", w.Position);
  }
  if (c.FocalPointGiven)
  {
    c.FocalPoint = VectorOf("--camera-focal-point", w.FocalPoint);
  }
  if (c.ViewUpGiven)
  {
    c.ViewUp = VectorOf("--camera-view-up", w.ViewUp);
  }
  if (app.count("--camera-view-angle"))
  {
    c.ViewAngle = NumberIn("--camera-view-angle", w.ViewAngle, 1.0, 179.0);
  }
  if (app.count("--camera-zoom-factor"))
  {
    c.Zoom = NumberIn("--camera-zoom-factor", w.Zoom, 1e-3, 1e3);
  }
}

void CheckLookWords(const CLI::App& app, const Words& w, Options& opt)
{
  LookOptions& l = opt.Look;
  if (app.count("--color"))
  {
    l.Color = ColorOf("--color", w.Color);
    l.ColorGiven = true;
  }
  if (app.count("--opacity"))
  {
    l.Opacity = NumberIn("--opacity", w.Opacity, 0.0, 1.0);
  }
  if (app.count("--point-size"))
  {
    l.PointSize = NumberIn("--point-size", w.PointSize, 0.1, 1000.0);
  }
  if (app.count("--bg-color"))
  {
    l.Background = ColorOf("--bg-color", w.Background);
  }
}

// What each option allows alone but the whole command line does not.
void CheckCombination(const Options& opt)
{
  if (opt.Demo == !opt.MeshFiles.empty())
  {
    throw UsageError{ opt.Demo ? "give either --demo or a mesh file, not both"
                               : "nothing to render: give a mesh file or --demo" };
  }
  for (const Pixel& p : opt.Picks)
  {
    if (p.X < 0 || p.Y < 0 || p.X >= opt.Width || p.Y >= opt.Height)
    {
      throw UsageError{ "--pick " + std::to_string(p.X) + " " + std::to_string(p.Y) +
        " is outside the " + std::to_string(opt.Width) + "x" + std::to_string(opt.Height) +
        " image" };
    }
  }
  const CameraOptions& c = opt.Camera;
  if (c.PositionGiven && c.FocalPointGiven && c.Position == c.FocalPoint)
  {
    throw UsageError{ "--camera-position and --camera-focal-point are the same point" };
  }
  if (c.ViewUpGiven && c.ViewUp == Vector3{ 0.0, 0.0, 0.0 })
  {
    throw UsageError{ "--camera-view-up must not be 0,0,0" };
  }
}

// CLI11's message for a parse error, in this program's words.
UsageError Translate(const CLI::ParseError& e)
{
  const std::string what = e.what();
  const std::string unexpected = "not expected: ";
  const size_t u = what.find(unexpected);
  if (u != std::string::npos)
  {
    std::string word = what.substr(u + unexpected.size());
    word = word.substr(0, word.find(' '));
    return UsageError{ (!word.empty() && word[0] == '-' ? "unknown option '" : "unexpected '") +
      word + "'" };
  }
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) && what.find(':') != std::string::npos)
  {
    return UsageError{ what.substr(0, what.find(':')) + " needs a value" };
  }
  return UsageError{ what };
}

// CLI11's help layout, with f3d's spelling for the two options CLI11
// writes its own way (an optional value, a pair of values).
class HelpFormatter : public CLI::Formatter
{
public:
  std::string make_usage(const CLI::App*, std::string) const override
  {
    return ""; // PrintHelp writes its own usage line first
  }
  std::string make_option_name(const CLI::Option* option, bool positional) const override
  {
    return option->check_name("--scalars") ? "--scalars[=NAME]"
                                           : CLI::Formatter::make_option_name(option, positional);
  }
  std::string make_option_opts(const CLI::Option* option) const override
  {
    if (option->check_name("--pick"))
    {
      return " X Y";
    }
    return option->check_name("--scalars") ? "" : CLI::Formatter::make_option_opts(option);
  }
};

void Declare(CLI::App& app, Words& w, Options& opt)
{
  app.description(Description);
  app.footer(Footer);
  auto formatter = std::make_shared<HelpFormatter>();
  formatter->column_width(34);
  app.formatter(formatter);
  DeclareOptions(app, w, opt);
  DeclareScalarOptions(app, w, opt);
  DeclareCameraOptions(app, w);
  DeclareLookOptions(app, w, opt);
}
} // namespace

const std::vector<std::string>& ColormapNames()
{
  static const std::vector<std::string> names = { "viridis", "inferno", "coolwarm", "rainbow",
    "grayscale" };
  return names;
}

Options ParseArguments(int argc, char* argv[], bool& help)
{
  Options opt;
  Words w;
  CLI::App app;
  Declare(app, w, opt);
  help = false;
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::CallForHelp&)
  {
    help = true;
    return Options();
  }
  catch (const CLI::ParseError& e)
  {
    throw Translate(e);
  }
  CheckImageWords(app, w, opt);
  CheckRenderWords(app, w, opt);
  CheckScalarWords(app, w, opt);
  CheckCameraWords(app, w, opt);
  CheckLookWords(app, w, opt);
  CheckCombination(opt);
  return opt;
}

void PrintHelp(std::ostream& os)
{
  Options opt;
  Words w;
  CLI::App app("", "vtkrt-render");
  Declare(app, w, opt);
  os << "usage: vtkrt-render [options] (--demo | MESH_FILE...)\n\n" << app.help();
  os << "\nThis build: raytrace mode "
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
