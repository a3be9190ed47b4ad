#include "vtkRayTraceFrameConstants.h"

#include "vtkrt/core/GpuLayout.h"

#include "vtk_glew.h"

#include <algorithm>
#include <sstream>

namespace vtkrt
{
namespace pass
{

std::vector<FrameConstant> FrameConstantsOf(const Features& f)
{
  std::vector<FrameConstant> out;
  // Read by every pixel: its camera ray and depth, the view, the instance.
  if (f.ProjectiveRays)
  {
    out.push_back({ "mat4", "uClipToCamera", 0, 4 });
    out.push_back({ "mat4", "uCameraToClip", 0, 4 });
  }
  else
  {
    out.push_back({ "vec3", "uRayOrigin", 3, 1 });
    out.push_back({ "vec3", "uRayDirection", 3, 1 });
    out.push_back({ "vec4", "uRayDepth", 0, 1 });
  }
  // The headlight's direction, and the view wires face.
  out.push_back({ "vec3", "uViewBack", 0, 1, f.LightComplexity == 1 || f.WireframeCode() || f.ScreenSpheres });
  if (f.SingleInstance)
  {
    out.push_back({ "uvec4", "uRootNode", static_cast<int>(core::gpu::texelsOf<core::gpu::Node>()), 1 });
    out.push_back({ "uvec4", "uInstance", static_cast<int>(core::gpu::kInstanceHeadTexels), 1 });
  }
  else if (!f.TopLevel)
  {
    out.push_back({ "int", "uNumberOfInstances", 0, 1 });
  }
  if (f.TileEntries)
  {
    out.push_back({ "vec4", "uTileGrid", 0, 1 });
  }
  if (f.SamplesPerPixel > 0)
  {
    out.push_back({ "vec2", "uPixelSize", 0, 1 });
    out.push_back({ "int", "uFirstSample", 0, 1 });
  }
  if (f.WorldCoordinates)
  {
    // Read where lights are not the headlight (the view direction).
    out.push_back({ "vec3", "uEye", 0, 1, f.Lights > 0 && f.LightComplexity >= 2 });
  }
  // Read by lit pixels, per light.
  if (f.Lights > 0)
  {
    // VTKRT_LIGHT_COMPLEXITY 1 (a headlight) reads the color alone, 2
    // directions too, 3 (positional lights) everything.
    const bool directions = f.LightComplexity >= 2;
    const bool positions = f.LightComplexity >= 3;
    out.push_back({ "vec3", "uLightColor", f.Lights, 1, f.LightComplexity >= 1 });
    out.push_back({ "vec3", "uLightDirection", f.Lights, 1, directions });
    out.push_back({ "vec3", "uLightPosition", f.Lights, 1, positions });
    out.push_back({ "vec3", "uLightAttenuation", f.Lights, 1, positions });
    out.push_back({ "vec3", "uLightCone", f.Lights, 1, positions });
  }
  if (f.ClipPlanes > 0)
  {
    out.push_back({ "vec4", "uClipPlanes", f.ClipPlanes, 1 });
  }
  if (f.AmbientOcclusionSamples > 0)
  {
    out.push_back({ "float", "uAmbientOcclusionRadius", 0, 1 });
  }
  // Read where a scene has what they describe (spheres' screen radii, back
  // faces' colors, edges).
  if (f.SingleInstance)
  {
    out.push_back({ "uvec4", "uInstanceTail", static_cast<int>(core::gpu::kInstanceTailTexels), 1 });
  }
  return out;
}

namespace
{
std::string Declarator(const FrameConstant& c, const std::string& name)
{
  return c.Type + " " + name + (c.Count > 0 ? "[" + std::to_string(c.Count) + "]" : std::string());
}

int SlotsOf(const FrameConstant& c)
{
  return std::max(c.Count, 1) * c.SlotsPerElement;
}
} // namespace

FrameConstantShaders DeclareFrameConstants(const std::vector<FrameConstant>& constants, int slots)
{
  std::ostringstream vertex, copies, fragment;
  vertex << "#version 330 core\n// vtkrt frame constants: uniforms passed on as flat varyings.\n"
         << "in vec4 ndCoordIn;\nin vec2 texCoordIn;\nout vec2 texCoord;\n";
  fragment << "// Frame constants (vtkRayTraceFrameConstants.h): flat inputs where they fit.\n";
  FrameConstantShaders out;
  int left = slots;
  for (const FrameConstant& c : constants)
  {
    const int need = SlotsOf(c);
    if (!c.ReadByShader || need > left)
    {
      fragment << "uniform " << Declarator(c, c.Name) << ";\n";
      continue;
    }
    left -= need;
    ++out.FlatConstants;
    const std::string varying = "vtkrtFrame_" + c.Name;
    vertex << "uniform " << Declarator(c, c.Name) << ";\nflat out " << Declarator(c, varying) << ";\n";
    copies << "  " << varying << " = " << c.Name << ";\n";
    fragment << "flat in " << Declarator(c, varying) << ";\n#define " << c.Name << " " << varying << "\n";
  }
  vertex << "void main()\n{\n  gl_Position = ndCoordIn;\n  texCoord = texCoordIn;\n" << copies.str() << "}\n";
  out.Vertex = vertex.str();
  out.FragmentDeclarations = fragment.str();
  return out;
}

int FlatConstantSlots()
{
  GLint fragmentInputs = 0;
  GLint vertexOutputs = 0;
  GLint varyings = 0;
  glGetIntegerv(GL_MAX_FRAGMENT_INPUT_COMPONENTS, &fragmentInputs);
  glGetIntegerv(GL_MAX_VERTEX_OUTPUT_COMPONENTS, &vertexOutputs);
  glGetIntegerv(GL_MAX_VARYING_COMPONENTS, &varyings);
  // One slot for the texture coordinate.
  return std::max(0, std::min({ fragmentInputs, vertexOutputs, varyings }) / 4 - 1);
}

} // namespace pass
} // namespace vtkrt
