// The pass's shader sources against the GLSL specification, not only the
// driver at hand:
//   ReferenceCompiler  every tracing program the pass assembles (each
//                      feature alone over triangles, spheres and both, all
//                      of them together, with and without double precision
//                      and flat frame constants), the resolve and the
//                      selection shaders compile with glslang, the Khronos
//                      reference compiler, at their own #version; a built-in
//                      of a later version is refused (Mesa accepts
//                      unpackUnorm4x8 in GLSL 3.30, NVIDIA does not);
//                      each program links (every function it calls is
//                      defined, its stages' varyings agree in type)
// TestRayTraceShaderSources ReferenceCompiler <glslangValidator>.
#include "vtkrtPassTestUtils.h"

#include "vtkRayTraceShader.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using namespace vtkrtPassTest;
using vtkrt::pass::Features;

namespace
{
std::string Validator;

/// A feature set the pass can ask for, by the feature it adds.
struct Variant
{
  std::string Name;
  std::function<void(Features&)> Set;
};

/// Each feature the shader has code for, as the pass sets it.
std::vector<Variant> FeatureVariants()
{
  return {
    { "plain", [](Features&) {} },
    { "vertex normals", [](Features& f) { f.VertexNormals = true; } },
    { "cell normals", [](Features& f) { f.CellNormals = true; } },
    { "colors", [](Features& f) { f.Colors = true; } },
    { "color texture", [](Features& f) { f.Colors = f.ColorTexture = true; } },
    { "clip planes", [](Features& f) { f.ClipPlanes = 3; } },
    { "positional lights", [](Features& f) { f.Lights = 3; f.LightComplexity = 3; } },
    { "no lights", [](Features& f) { f.Lights = 0; f.LightComplexity = 0; } },
    { "ids", [](Features& f) { f.IdMode = true; } },
    { "selection ids", [](Features& f) { f.SelectIds = true; } },
    { "top level", [](Features& f) { f.TopLevel = true; } },
    { "single instance", [](Features& f) { f.SingleInstance = true; } },
    { "projective rays", [](Features& f) { f.ProjectiveRays = true; } },
    { "depth below", [](Features& f) { f.DepthBelow = true; } },
    { "depth below, projective rays, translucent",
      [](Features& f) { f.DepthBelow = f.ProjectiveRays = f.Translucent = true; } },
    // As the frame sets them: one triangle instance's walks.
    { "tile entries", [](Features& f) { f.TileEntries = f.SingleInstance = f.Triangles = true; } },
    { "leaf trees", [](Features& f) { f.LeafTrees = true; } },
    { "samples", [](Features& f) { f.SamplesPerPixel = 4; } },
    { "shadows", [](Features& f) { f.Shadows = true; } },
    { "ambient occlusion", [](Features& f) { f.AmbientOcclusionSamples = 4; } },
    { "traversal steps", [](Features& f) { f.MaximumTraversalSteps = 64; } },
    { "world coordinates", [](Features& f) { f.WorldCoordinates = true; } },
    { "screen spheres", [](Features& f) { f.Spheres = f.ScreenSpheres = true; } },
    { "ellipsoids", [](Features& f) { f.Spheres = f.Ellipsoids = true; } },
    { "tubes", [](Features& f) { f.Spheres = f.Tubes = true; } },
    { "textures", [](Features& f) { f.Textures = true; } },
    { "texture cut-outs", [](Features& f) { f.Textures = f.TextureCutOuts = true; } },
    { "face culling", [](Features& f) { f.FaceCulling = true; } },
    { "backface properties", [](Features& f) { f.BackfaceProperties = true; } },
    { "specular", [](Features& f) { f.Specular = true; } },
    { "translucent", [](Features& f) { f.Translucent = true; } },
    { "translucent, visibility rays walked in shading",
      [](Features& f) {
        f.Translucent = f.Shadows = true;
        f.AmbientOcclusionSamples = 2;
      } },
    { "translucent, interleaved walks",
      [](Features& f) {
        f.Translucent = f.Shadows = f.InterleavedWalks = true;
        f.AmbientOcclusionSamples = 2;
      } },
    { "surface edges", [](Features& f) { f.SurfaceEdges = true; } },
    { "wireframe", [](Features& f) { f.Wireframe = true; } },
    { "wide stack entries", [](Features& f) { f.PackedStackEntries = false; } },
    { "small stack", [](Features& f) { f.StackSize = 8; } },
  };
}

/// Everything a scene can hold at once (of a pick, a selection or colors).
void EveryFeature(Features& f)
{
  f.Triangles = f.Spheres = f.VertexNormals = f.CellNormals = f.Colors = f.ColorTexture = true;
  f.ClipPlanes = 2;
  f.Lights = 2;
  f.LightComplexity = 3;
  f.TopLevel = f.Shadows = f.Ellipsoids = f.Tubes = f.Textures = f.TextureCutOuts = true;
  f.FaceCulling = f.BackfaceProperties = f.Specular = f.Translucent = true;
  f.SurfaceEdges = f.Wireframe = f.DepthBelow = true;
  f.SamplesPerPixel = 4;
  f.AmbientOcclusionSamples = 4;
  f.MaximumTraversalSteps = 256;
}

/// Writes `source` to `path`; false when it cannot.
bool WriteSource(const std::string& path, const std::string& source)
{
  std::ofstream out(path, std::ios::binary);
  out << source;
  return static_cast<bool>(out);
}

/// Whether the file at `path` holds `text`.
bool FileHolds(const std::string& path, const std::string& text)
{
  std::ifstream in(path);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return content.find(text) != std::string::npos;
}

/// Runs the validator with `arguments` (files alone: each compiled on its
/// own; -l and files: linked as one program), its output in `log`; true
/// when it succeeds.
bool RunValidator(const std::vector<std::string>& arguments, const std::string& log)
{
  std::string command = "\"" + Validator + "\"";
  for (const std::string& argument : arguments)
  {
    command += " \"" + argument + "\"";
  }
  command += " > \"" + log + "\" 2>&1";
  return std::system(command.c_str()) == 0;
}


/// Links each program `stem`.vert + `stem`.frag (its output in
/// `stem`.link.log), a few at a time; the stems that do not link.
std::vector<std::string> LinkEach(const std::vector<std::string>& stems)
{
  std::vector<char> linked(stems.size(), 0);
  std::atomic<std::size_t> next{ 0 };
  auto work = [&]() {
    for (std::size_t i = next++; i < stems.size(); i = next++)
    {
      linked[i] = RunValidator({ "-l", stems[i] + ".vert", stems[i] + ".frag" }, stems[i] + ".link.log");
    }
  };
  const unsigned workers = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
  std::vector<std::thread> threads;
  for (unsigned w = 0; w < workers; ++w)
  {
    threads.emplace_back(work);
  }
  for (std::thread& t : threads)
  {
    t.join();
  }
  std::vector<std::string> unlinked;
  for (std::size_t i = 0; i < stems.size(); ++i)
  {
    if (!linked[i])
    {
      unlinked.push_back(stems[i]);
    }
  }
  return unlinked;
}

/// The lines of `log` that name an error, at most `limit` of them.
std::string ErrorLines(const std::string& log, int limit)
{
  std::ifstream in(log);
  std::string line, out;
  std::string file;
  int shown = 0;
  while (std::getline(in, line) && shown < limit)
  {
    if (line.find('/') == 0 || line.find(".frag") != std::string::npos ||
      line.find(".vert") != std::string::npos)
    {
      file = line;
    }
    if (line.find("ERROR") != std::string::npos)
    {
      out += "     " + file + ": " + line + "\n";
      ++shown;
    }
  }
  return out;
}

void TestReferenceCompiler()
{
  const std::string dir = std::string(VTKRT_TEMP_DIR) + "/ShaderSources";
  std::error_code error;
  std::filesystem::remove_all(dir, error);
  std::filesystem::create_directories(dir, error);

  // The validator must refuse what a strict driver refuses, or this test
  // proves nothing: unpackUnorm4x8 is GLSL 4.00 (or an extension).
  const std::string laterBuiltin = dir + "/later-builtin";
  bool written = WriteSource(laterBuiltin + ".frag",
    "#version 330 core\nout vec4 color;\nvoid main() { color = unpackUnorm4x8(7u); }\n");
  Check(!RunValidator({ laterBuiltin + ".frag" }, laterBuiltin + ".log") &&
      FileHolds(laterBuiltin + ".log", "unpackUnorm4x8"),
    "the reference compiler refuses a GLSL 4.00 built-in in a 3.30 shader");

  // And a program that calls a function no stage defines must not link.
  const std::string undefined = dir + "/undefined-function";
  written &= WriteSource(undefined + ".vert", "#version 330 core\nin vec4 p;\nvoid main() { gl_Position = p; }\n");
  written &= WriteSource(undefined + ".frag",
    "#version 330 core\nout vec4 color;\nfloat f();\nvoid main() { color = vec4(f()); }\n");
  Check(LinkEach({ undefined }).size() == 1 && FileHolds(undefined + ".link.log", "No function definition"),
    "the reference compiler does not link a program that calls a function nobody defines");

  Features triangles;
  triangles.Triangles = true;
  triangles.Lights = 1;
  triangles.LightComplexity = 1;
  Features spheres = triangles;
  spheres.Triangles = false;
  spheres.Spheres = true;
  Features both = triangles;
  both.Spheres = both.TopLevel = true;
  const std::vector<std::pair<std::string, Features>> bases = { { "triangles", triangles },
    { "spheres", spheres }, { "triangles and spheres", both } };

  std::vector<Features> programs;
  for (const auto& base : bases)
  {
    for (const Variant& v : FeatureVariants())
    {
      Features f = base.second;
      v.Set(f);
      programs.push_back(f);
    }
  }
  // The lighting's every path: each complexity with shadows, occlusion and
  // specular on and off; a tile-entry walk's visibility rays.
  for (int complexity = 1; complexity <= 3; ++complexity)
  {
    for (int variant = 0; variant < 8; ++variant)
    {
      Features f = triangles;
      f.Lights = complexity == 1 ? 1 : 3;
      f.LightComplexity = complexity;
      f.Shadows = (variant & 1) != 0;
      f.AmbientOcclusionSamples = (variant & 2) != 0 ? 4 : 0;
      f.Specular = (variant & 4) != 0;
      programs.push_back(f);
    }
  }
  Features tiles = triangles;
  tiles.SingleInstance = tiles.TileEntries = tiles.Shadows = true;
  tiles.AmbientOcclusionSamples = 2;
  programs.push_back(tiles);
  tiles.Translucent = true;
  programs.push_back(tiles);
  tiles.InterleavedWalks = true;
  programs.push_back(tiles);
  for (int select = 0; select < 3; ++select)
  {
    Features f;
    EveryFeature(f);
    f.IdMode = select == 1;
    f.SelectIds = select == 2;
    programs.push_back(f);
    f.WorldCoordinates = true;
    programs.push_back(f);
  }
  Features interleaved;
  EveryFeature(interleaved);
  interleaved.InterleavedWalks = true;
  programs.push_back(interleaved);

  // Each with and without double precision; flat frame constants in none,
  // few and many varying slots.
  std::set<std::string> assembledKeys;
  std::vector<std::string> stems;
  const int slots[] = { 0, 6, 31 };
  for (std::size_t i = 0; i < programs.size(); ++i)
  {
    for (int fp64 = 0; fp64 < 2; ++fp64)
    {
      Features f = programs[i];
      f.Fp64 = fp64 == 1;
      const int flatSlots = slots[(i + fp64) % 3];
      const std::string key = f.Key() + "f" + std::to_string(flatSlots);
      if (!assembledKeys.insert(key).second)
      {
        continue;
      }
      const vtkrt::pass::ShaderSources sources = vtkrt::pass::AssembleShaders(f, flatSlots);
      const std::string stem = dir + "/" + std::to_string(assembledKeys.size());
      written &= WriteSource(stem + ".frag", sources.Fragment);
      written &= WriteSource(stem + ".vert", sources.Vertex);
      stems.push_back(stem);
    }
  }
  written &= WriteSource(dir + "/resolve.frag", vtkrt::pass::ResolveShaderSource());
  written &= WriteSource(dir + "/select.frag", vtkrt::pass::SelectShaderSource());
  Check(written, "every shader written to " + dir);
  std::vector<std::string> files = { dir + "/resolve.frag", dir + "/select.frag" };
  for (const std::string& stem : stems)
  {
    files.push_back(stem + ".frag");
    files.push_back(stem + ".vert");
  }

  const std::string log = dir + "/validator.log";
  const bool valid = RunValidator(files, log);
  Check(valid, std::to_string(assembledKeys.size()) + " tracing programs (fragment and vertex), the resolve and " +
      "the selection shaders compile with the reference compiler (log: " + log + ")");
  if (!valid)
  {
    std::cout << ErrorLines(log, 20);
  }

  // Each program linked, vertex and fragment shader together: every
  // function a stage calls is defined, the varyings agree in type.
  std::vector<std::string> unlinked = LinkEach(stems);
  Check(unlinked.empty(), std::to_string(stems.size() - unlinked.size()) + " of " +
      std::to_string(stems.size()) + " tracing programs link with the reference compiler");
  for (std::size_t i = 0; i < unlinked.size() && i < 3; ++i)
  {
    std::cout << ErrorLines(unlinked[i] + ".link.log", 6);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  Validator = argc > 2 ? argv[2] : "";
  if (argc > 1 && Validator.empty())
  {
    std::cerr << "usage: " << argv[0] << " ReferenceCompiler <glslangValidator>\n";
    return EXIT_FAILURE;
  }
  const std::map<std::string, std::function<void()>> cases = {
    { "ReferenceCompiler", TestReferenceCompiler },
  };
  return RunCase(argc, argv, cases, " <glslangValidator>");
}
