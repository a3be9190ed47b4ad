#include "vtkRayTraceShader.h"

#include "vtkRayTraceFrameConstants.h"

#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"

#include "vtkrtRayTraceEdges.h"
#include "vtkrtRayTraceInputs.h"
#include "vtkrtRayTraceKernels.h"
#include "vtkrtRayTraceLighting.h"
#include "vtkrtRayTraceMain.h"
#include "vtkrtRayTraceResolve.h"
#include "vtkrtRayTraceSelect.h"
#include "vtkrtRayTraceShading.h"
#include "vtkrtRayTraceSpheres.h"
#include "vtkrtRayTraceSurfaces.h"
#include "vtkrtRayTraceTranslucent.h"
#include "vtkrtRayTraceTraversal.h"
#include "vtkrtRayTraceTriangles.h"
#include "vtkrtRayTraceTubes.h"

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/GpuLayout.h"

#include <sstream>

namespace vtkrt
{
namespace pass
{

std::string Features::ImageKey() const
{
  Features f = *this;
  f.StackSize = 0;
  f.TileEntries = false;
  f.LeafTrees = false;
  f.PackedStackEntries = false;
  return f.Key();
}

std::string Features::Key() const
{
  std::ostringstream s;
  s << "T" << this->Triangles << "S" << this->Spheres << "N" << this->VertexNormals << "C"
    << this->Colors << "P" << this->ClipPlanes << "L" << this->Lights << "x"
    << this->LightComplexity << "I" << this->IdMode << "D" << this->Fp64 << "X"
    << this->TopLevel << "A" << this->SamplesPerPixel << "H" << this->Shadows << "O"
    << this->AmbientOcclusionSamples << "M" << this->MaximumTraversalSteps << "W"
    << this->WorldCoordinates << "Q" << this->ScreenSpheres << "E" << this->Ellipsoids << "X"
    << this->ColorTexture << "K" << this->SelectIds << "F" << this->CellNormals << "U"
    << this->Textures << "B" << this->FaceCulling << "Y" << this->BackfaceProperties << "Z"
    << this->TextureCutOuts << "S" << this->StackSize << "R" << this->Translucent << "G"
    << this->SurfaceEdges << "V" << this->Wireframe << "J"
    << this->Tubes << "i" << this->SingleInstance << "p"
    << this->ProjectiveRays << "e" << this->TileEntries << "l" << this->LeafTrees << "w"
    << this->PackedStackEntries << "h" << this->Specular << "n" << this->InterleavedWalks << "c" << this->SphereCellIds
    << "f" << this->FloatColors << "b" << this->DepthBelow;
  return s.str();
}

ShaderSources AssembleShaders(const Features& f, int flatSlots)
{
  std::ostringstream s;
  s << (f.Fp64 ? "#version 400 core\n#define VTKRT_HAS_FP64\n" : "#version 330 core\n");
  s << "// vtkrt feature key " << f.Key() << "\n";
  auto define = [&s](bool on, const char* name) {
    if (on)
    {
      s << "#define " << name << "\n";
    }
  };
  define(f.Triangles, "VTKRT_HAS_TRIANGLES");
  define(f.Spheres, "VTKRT_HAS_SPHERES");
  define(f.VertexNormals, "VTKRT_HAS_VERTEX_NORMALS");
  define(f.CellNormals, "VTKRT_HAS_CELL_NORMALS");
  define(f.Colors, "VTKRT_HAS_COLORS");
  define(f.ColorTexture, "VTKRT_HAS_COLOR_TEXTURE");
  define(f.Triangles && (f.VertexNormals || f.Colors || f.Textures), "VTKRT_HAS_TRIANGLE_VERTICES");
  define(f.Triangles && f.Textures, "VTKRT_HAS_TEXTURES");
  define(f.Triangles && f.FaceCulling, "VTKRT_FACE_CULLING");
  define(f.Triangles && f.Textures && f.TextureCutOuts, "VTKRT_TEXTURE_CUTOUTS");
  define(f.Triangles && f.BackfaceProperties, "VTKRT_BACKFACE_PROPERTIES");
  // Edges change colors only: id and selection shaders need the wires alone.
  const bool surfaceEdges = f.SurfaceEdgeCode();
  const bool wireframe = f.WireframeCode();
  define(surfaceEdges, "VTKRT_SURFACE_EDGES");
  define(wireframe, "VTKRT_HAS_WIREFRAME");
  define(f.IdMode, "VTKRT_ID_MODE");
  define(f.SelectIds, "VTKRT_SELECT_IDS");
  define(f.TopLevel, "VTKRT_HAS_TOP_LEVEL");
  define(f.SingleInstance, "VTKRT_SINGLE_INSTANCE");
  define(f.ProjectiveRays, "VTKRT_PROJECTIVE_RAYS");
  define(f.TileEntries, "VTKRT_TILE_ENTRIES");
  define(f.Triangles && f.LeafTrees, "VTKRT_LEAF_TREES");
  define(f.PackedStackEntries, "VTKRT_PACKED_STACK_ENTRIES");
  define(f.Translucent, "VTKRT_TRANSLUCENT");
  define(f.InterleavedWalks, "VTKRT_INTERLEAVED_WALKS");
  if (f.SamplesPerPixel > 0)
  {
    s << "#define VTKRT_SAMPLES_PER_PIXEL " << f.SamplesPerPixel << "\n";
  }
  define(f.Shadows, "VTKRT_SHADOWS");
  define(f.Specular, "VTKRT_SPECULAR");
  define(f.FloatColors, "VTKRT_FLOAT_COLORS");
  define(f.DepthBelow, "VTKRT_DEPTH_BELOW");
  define(f.WorldCoordinates, "VTKRT_WORLD_COORDINATES");
  define(f.ScreenSpheres, "VTKRT_SCREEN_SPHERES");
  define(f.Spheres && f.SphereCellIds, "VTKRT_SPHERE_CELL_IDS");
  define(f.Ellipsoids, "VTKRT_HAS_ELLIPSOIDS");
  define(f.Spheres && f.Tubes, "VTKRT_HAS_TUBES");
  s << "#define VTKRT_AMBIENT_OCCLUSION_SAMPLES " << f.AmbientOcclusionSamples << "\n";
  s << "#define VTKRT_MAXIMUM_TRAVERSAL_STEPS " << f.MaximumTraversalSteps << "\n";
  s << "#define VTKRT_NUMBER_OF_CLIP_PLANES " << f.ClipPlanes << "\n";
  s << "#define VTKRT_NUMBER_OF_LIGHTS " << f.Lights << "\n";
  s << "#define VTKRT_LIGHT_COMPLEXITY " << f.LightComplexity << "\n";
  s << "#define VTKRT_STACK_SIZE " << f.StackSize << "\n";
  const FrameConstantShaders constants = DeclareFrameConstants(FrameConstantsOf(f), flatSlots);
  s << constants.FragmentDeclarations;
  s << core::gpu::glslLayout();
  s << vtkrtRayTraceKernels << "\n";
  if (f.Triangles)
  {
    s << vtkrtRayTraceTriangles << "\n";
  }
  if (f.Spheres)
  {
    s << vtkrtRayTraceSpheres << "\n";
  }
  if (f.Spheres && f.Tubes)
  {
    s << vtkrtRayTraceTubes << "\n";
  }
  if (f.Triangles && (f.Textures || f.FaceCulling))
  {
    s << vtkrtRayTraceSurfaces << "\n";
  }
  if (surfaceEdges || wireframe)
  {
    s << vtkrtRayTraceEdges << "\n";
  }
  s << vtkrtRayTraceInputs << "\n" << vtkrtRayTraceLighting << "\n" << vtkrtRayTraceTraversal << "\n"
    << vtkrtRayTraceShading << "\n" << vtkrtRayTraceMain;
  if (f.Translucent)
  {
    s << "\n" << vtkrtRayTraceTranslucent;
  }
  return { constants.Vertex, s.str() };
}

std::string ResolveShaderSource()
{
  return std::string("#version 330 core\n") + vtkrtRayTraceResolve;
}

std::string SelectShaderSource()
{
  return std::string("#version 330 core\n") + vtkrtRayTraceSelect;
}

bool ReadyQuadProgram(vtkOpenGLRenderWindow* win, std::unique_ptr<vtkOpenGLQuadHelper>& helper,
  const std::string& source, FrameCounters& counters, const std::string& vertexSource)
{
  if (!helper)
  {
    helper.reset(new vtkOpenGLQuadHelper(
      win, vertexSource.empty() ? nullptr : vertexSource.c_str(), source.c_str(), ""));
    ++counters.ShaderCompiles;
  }
  else
  {
    win->GetShaderCache()->ReadyShaderProgram(helper->Program);
  }
  return helper->Program && helper->Program->GetCompiled();
}

ProgramCache::ProgramCache() = default;
ProgramCache::~ProgramCache() = default;

vtkOpenGLQuadHelper* ProgramCache::Ready(
  vtkOpenGLRenderWindow* win, const Features& f, bool flatConstants, FrameCounters& counters)
{
  if (this->ContextSlots < 0)
  {
    this->ContextSlots = FlatConstantSlots();
  }
  const int slots = flatConstants ? this->ContextSlots : 0;
  vtkOpenGLQuadHelper* program = this->ReadyWithSlots(win, f, slots, counters);
  if (!program && slots > 0)
  {
    // A driver that links fewer varyings than its limits say: uniforms
    // from now on.
    this->ContextSlots = 0;
    program = this->ReadyWithSlots(win, f, 0, counters);
  }
  return program;
}

vtkOpenGLQuadHelper* ProgramCache::ReadyWithSlots(
  vtkOpenGLRenderWindow* win, const Features& f, int slots, FrameCounters& counters)
{
  const std::string key = f.Key() + "f" + std::to_string(slots);
  if (key != this->LastKey)
  {
    ShaderSources sources = AssembleShaders(f, slots);
    this->LastSource = std::move(sources.Fragment);
    this->LastVertexSource = std::move(sources.Vertex);
    this->LastKey = key;
  }
  auto& helper = this->Programs[key];
  return ReadyQuadProgram(win, helper, this->LastSource, counters, this->LastVertexSource) ? helper.get()
                                                                                         : nullptr;
}

void ProgramCache::Release(vtkWindow* w)
{
  for (auto& p : this->Programs)
  {
    p.second->ReleaseGraphicsResources(w);
  }
  this->Programs.clear();
  this->ContextSlots = -1; // the next window's context may hold other limits
}

} // namespace pass
} // namespace vtkrt
