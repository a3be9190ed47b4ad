#include "vtkRayTracePass.h"

#include "vtkRayTraceScene.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLightsPass.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpaquePass.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOverlayPass.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderState.h"
#include "vtkSequencePass.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTranslucentPass.h"
#include "vtkVolumetricPass.h"
#include "vtk_glew.h"

#include "vtkrtRayTraceKernels.h"
#include "vtkrtRayTraceMain.h"
#include "vtkrtRayTraceResolve.h"
#include "vtkrtRayTraceSpheres.h"
#include "vtkrtRayTraceTriangles.h"

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHBuild.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using vtkrt::pass::FrameCounters;
using vtkrt::pass::Features;
using vtkrt::pass::Instance;

namespace
{
constexpr int kInstanceTexels = 11;
// Scenes with more instances than this walk a top-level BVH over them
// instead of testing every instance's box.
constexpr std::size_t kTopLevelMinInstances = 8;
enum InstanceFlags : std::uint32_t
{
  kSpheres = 1u,
  kLit = 2u,
  kVertexNormals = 4u,
  kPointColors = 8u,
  kCellColors = 16u,
  kMirrored = 32u,
  kEllipsoids = 64u,
  kColorTexture = 128u,
};

float bits(std::uint32_t u)
{
  return vtkrt::core::uintBitsToFloat(u);
}

/// One texture buffer of 4 x 32-bit texels (the GLSL's usamplerBuffer).
struct TextureBuffer
{
  vtkNew<vtkOpenGLBufferObject> Buffer;
  vtkNew<vtkTextureObject> Texture;
  std::size_t Texels = 0;

  /// Uploads (4 floats per texel; an empty array gets one zero texel so the
  /// sampler is always complete). Returns the bytes uploaded.
  std::size_t Upload(vtkOpenGLRenderWindow* win, const std::vector<float>& data)
  {
    static const float zero[4] = { 0, 0, 0, 0 };
    const float* ptr = data.empty() ? zero : data.data();
    const std::size_t n = data.empty() ? 4 : data.size();
    this->Buffer->Upload(ptr, n, vtkOpenGLBufferObject::TextureBuffer);
    this->Texture->SetContext(win);
    // RGBA32UI (read by a usamplerBuffer): integer fields come back bit
    // exact, floats are reinterpreted in the shader.
    this->Texture->SetInternalFormat(GL_RGBA32UI);
    this->Texture->CreateTextureBuffer(
      static_cast<unsigned int>(n / 4), 4, VTK_UNSIGNED_INT, this->Buffer);
    this->Texels = n / 4;
    return n * sizeof(float);
  }

  void Release(vtkWindow* w)
  {
    this->Texture->ReleaseGraphicsResources(w);
    this->Buffer->ReleaseGraphicsResources();
    this->Texels = 0;
  }
};

/// Row-major double 4x4 -> column-major float (what GLSL's mat4 expects).
void toGLSL(const vtkMatrix4x4* m, float out[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
    }
  }
}
} // namespace

struct vtkRayTracePass::Internals
{
  vtkrt::pass::Scene Scene;
  vtkNew<vtkLightsPass> Lights;
  std::vector<vtkProp*> Traced;
  std::vector<vtkProp*> Others;
  FrameCounters Counters;
  std::map<std::string, std::unique_ptr<vtkOpenGLQuadHelper>> Programs;
  std::string LastKey;
  std::string LastSource; ///< LastKey's shader source (outlives the cached programs)
  vtkOpenGLRenderWindow* Window = nullptr;
  bool GeometryOnGpu = false;
  bool ColorsOnGpu = false;
  bool GeometryValid = true;
  bool ColorsValid = true;
  std::size_t CheckedLimit = 0; ///< the texel limit the buffers were checked against
  std::vector<float> LastRecords; ///< the instance records on the GPU

  TextureBuffer Nodes, Triangles, TriangleVertices, Spheres, SphereIds, Normals, Colors, Instances;

  // Top-level BVH over the instances' world boxes, for scenes with many
  // instances; rebuilt when an instance's world box changes (never for a
  // camera move).
  TextureBuffer TopNodes;
  std::vector<double> TopSignature;
  std::vector<std::uint32_t> TopOrder;
  vtkrt::core::Vec3<double> TopAnchor{ 0.0 };

  // Sub-pixel sampling: float accumulation buffer (sum of hit colors, hit
  // count), its depth, the resolve program, and what the accumulated frames
  // were traced from (any change restarts the accumulation).
  vtkNew<vtkOpenGLFramebufferObject> AccumulationFBO;
  vtkNew<vtkTextureObject> AccumulationColor;
  vtkNew<vtkTextureObject> AccumulationDepth;
  std::unique_ptr<vtkOpenGLQuadHelper> Resolve;
  int AccumulationSize[2] = { 0, 0 };
  std::vector<float> AccumulationSignature;
  int AccumulatedFrames = 0;

  void ReleaseGL(vtkWindow* w)
  {
    if (this->Resolve)
    {
      this->Resolve->ReleaseGraphicsResources(w);
      this->Resolve.reset();
    }
    this->AccumulationFBO->ReleaseGraphicsResources(w);
    this->AccumulationColor->ReleaseGraphicsResources(w);
    this->AccumulationDepth->ReleaseGraphicsResources(w);
    this->AccumulationSize[0] = this->AccumulationSize[1] = 0;
    this->AccumulationSignature.clear();
    this->AccumulatedFrames = 0;
    for (auto& p : this->Programs)
    {
      p.second->ReleaseGraphicsResources(w);
    }
    this->Programs.clear();
    for (TextureBuffer* b : { &this->Nodes, &this->Triangles, &this->TriangleVertices, &this->Spheres,
           &this->SphereIds, &this->Normals, &this->Colors, &this->Instances, &this->TopNodes })
    {
      b->Release(w);
    }
    this->GeometryOnGpu = false;
    this->ColorsOnGpu = false;
    this->TopSignature.clear();
  }
};

vtkStandardNewMacro(vtkRayTracePass);

vtkRayTracePass::vtkRayTracePass()
  : Internal(new Internals)
{
  // Default delegate: everything a vtkRenderStepsPass does after the camera
  // pass (which would clear the traced image).
  vtkNew<vtkRenderPassCollection> passes;
  vtkNew<vtkLightsPass> lights;
  vtkNew<vtkOpaquePass> opaque;
  vtkNew<vtkTranslucentPass> translucent;
  vtkNew<vtkVolumetricPass> volumes;
  vtkNew<vtkOverlayPass> overlay;
  passes->AddItem(lights);
  passes->AddItem(opaque);
  passes->AddItem(translucent);
  passes->AddItem(volumes);
  passes->AddItem(overlay);
  vtkNew<vtkSequencePass> sequence;
  sequence->SetPasses(passes);
  this->SetDelegatePass(sequence);
}

vtkRayTracePass::~vtkRayTracePass()
{
  this->SetDelegatePass(nullptr);
}

void vtkRayTracePass::SetDelegatePass(vtkRenderPass* pass)
{
  if (pass == this->DelegatePass)
  {
    return;
  }
  if (this->DelegatePass)
  {
    this->DelegatePass->UnRegister(this);
  }
  this->DelegatePass = pass;
  if (pass)
  {
    pass->Register(this);
  }
  this->Modified();
}

vtkRenderPass* vtkRayTracePass::GetDelegatePass()
{
  return this->DelegatePass;
}

void vtkRayTracePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "IdMode: " << this->IdMode << "\n";
  os << indent << "BuildQuality: " << this->BuildQuality << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "ProgressiveAccumulation: " << this->ProgressiveAccumulation << "\n";
  os << indent << "Shadows: " << this->Shadows << "\n";
  os << indent << "AmbientOcclusionSamples: " << this->AmbientOcclusionSamples << "\n";
  os << indent << "AmbientOcclusionRadius: " << this->AmbientOcclusionRadius << "\n";
  os << indent << "MaximumTraversalSteps: " << this->MaximumTraversalSteps << "\n";
  os << indent << "LeafSize: " << this->LeafSize << "\n";
  os << indent << "PrecisionMode: " << this->GetPrecisionModeAsString() << "\n";
  os << indent << "AccumulatedFrames: " << this->Internal->AccumulatedFrames << "\n";
  os << indent << "MaximumTextureBufferTexels: " << this->MaximumTextureBufferTexels << "\n";
  os << indent << "DelegatePass: " << this->DelegatePass << "\n";
  os << indent << "LastFeatureKey: " << this->Internal->LastKey << "\n";
  const FrameCounters& c = this->Internal->Counters;
  os << indent << "Last frame: BVH builds " << c.BVHBuilds << ", geometry bytes "
     << c.GeometryBytesUploaded << ", frame bytes " << c.FrameBytesUploaded << ", shader compiles "
     << c.ShaderCompiles << ", traced primitives " << c.TracedPrimitives << "\n";
}

bool vtkRayTracePass::DecodeId(const unsigned char rgba[4], int& propIndex, vtkIdType& id)
{
  if (rgba[3] == 0)
  {
    propIndex = -1;
    id = -1;
    return false;
  }
  propIndex = static_cast<int>(rgba[3]) - 1;
  id = static_cast<vtkIdType>(rgba[0]) | (static_cast<vtkIdType>(rgba[1]) << 8) |
    (static_cast<vtkIdType>(rgba[2]) << 16);
  return true;
}

int vtkRayTracePass::GetNumberOfTracedProps() const
{
  return static_cast<int>(this->Internal->Traced.size());
}

vtkProp* vtkRayTracePass::GetTracedProp(int index) const
{
  const auto& t = this->Internal->Traced;
  return index >= 0 && index < static_cast<int>(t.size()) ? t[index] : nullptr;
}

const char* vtkRayTracePass::GetPrecisionModeAsString() const
{
  return this->PrecisionMode == WORLD ? "World" : "CameraRelative";
}

int vtkRayTracePass::GetAccumulatedFrames() const
{
  return this->Internal->AccumulatedFrames;
}

int vtkRayTracePass::GetLastBVHBuilds() const
{
  return this->Internal->Counters.BVHBuilds;
}
vtkTypeInt64 vtkRayTracePass::GetLastGeometryBytesUploaded() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.GeometryBytesUploaded);
}
vtkTypeInt64 vtkRayTracePass::GetLastFrameBytesUploaded() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.FrameBytesUploaded);
}
int vtkRayTracePass::GetLastShaderCompiles() const
{
  return this->Internal->Counters.ShaderCompiles;
}
vtkTypeInt64 vtkRayTracePass::GetLastTracedPrimitives() const
{
  return static_cast<vtkTypeInt64>(this->Internal->Counters.TracedPrimitives);
}
int vtkRayTracePass::GetLastTopLevelBuilds() const
{
  return this->Internal->Counters.TopLevelBuilds;
}
int vtkRayTracePass::GetLastTracedInstances() const
{
  return this->Internal->Counters.TracedInstances;
}
const char* vtkRayTracePass::GetLastFeatureKey() const
{
  return this->Internal->LastKey.c_str();
}
const char* vtkRayTracePass::GetLastFragmentShaderSource() const
{
  return this->Internal->LastSource.c_str();
}

void vtkRayTracePass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseGL(w);
  // The window may be going away: the next Render starts afresh.
  this->Internal->Window = nullptr;
  if (this->DelegatePass)
  {
    this->DelegatePass->ReleaseGraphicsResources(w);
  }
}

namespace
{
/// The fragment shader for a feature set: only the chunks it needs.
std::string assembleShader(const Features& f)
{
  std::ostringstream s;
  s << (f.Fp64 ? "#version 400 core\n#define VTKRT_HAS_FP64\n" : "#version 330 core\n");
  s << "// vtkrt feature key " << f.Key() << "\n";
  if (f.Triangles)
  {
    s << "#define VTKRT_HAS_TRIANGLES\n";
  }
  if (f.Spheres)
  {
    s << "#define VTKRT_HAS_SPHERES\n";
  }
  if (f.VertexNormals)
  {
    s << "#define VTKRT_HAS_VERTEX_NORMALS\n";
  }
  if (f.Colors)
  {
    s << "#define VTKRT_HAS_COLORS\n";
  }
  if (f.ColorTexture)
  {
    s << "#define VTKRT_HAS_COLOR_TEXTURE\n";
  }
  if (f.Triangles && (f.VertexNormals || f.Colors))
  {
    s << "#define VTKRT_HAS_TRIANGLE_VERTICES\n";
  }
  if (f.IdMode)
  {
    s << "#define VTKRT_ID_MODE\n";
  }
  if (f.TopLevel)
  {
    s << "#define VTKRT_HAS_TOP_LEVEL\n";
  }
  if (f.SamplesPerPixel > 0)
  {
    s << "#define VTKRT_SAMPLES_PER_PIXEL " << f.SamplesPerPixel << "\n";
  }
  if (f.Shadows)
  {
    s << "#define VTKRT_SHADOWS\n";
  }
  if (f.WorldCoordinates)
  {
    s << "#define VTKRT_WORLD_COORDINATES\n";
  }
  if (f.ScreenSpheres)
  {
    s << "#define VTKRT_SCREEN_SPHERES\n";
  }
  if (f.Ellipsoids)
  {
    s << "#define VTKRT_HAS_ELLIPSOIDS\n";
  }
  s << "#define VTKRT_AMBIENT_OCCLUSION_SAMPLES " << f.AmbientOcclusionSamples << "\n";
  s << "#define VTKRT_MAXIMUM_TRAVERSAL_STEPS " << f.MaximumTraversalSteps << "\n";
  s << "#define VTKRT_NUMBER_OF_CLIP_PLANES " << f.ClipPlanes << "\n";
  s << "#define VTKRT_NUMBER_OF_LIGHTS " << f.Lights << "\n";
  s << "#define VTKRT_LIGHT_COMPLEXITY " << f.LightComplexity << "\n";
  s << "#define VTKRT_STACK_SIZE " << vtkrt::core::kMaxStackSize << "\n";
  s << "#define VTKRT_INSTANCE_TEXELS " << kInstanceTexels << "\n";
  s << vtkrtRayTraceKernels << "\n";
  if (f.Triangles)
  {
    s << vtkrtRayTraceTriangles << "\n";
  }
  if (f.Spheres)
  {
    s << vtkrtRayTraceSpheres << "\n";
  }
  s << vtkrtRayTraceMain;
  return s.str();
}
} // namespace

void vtkRayTracePass::Render(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  Internals& in = *this->Internal;
  in.Counters = FrameCounters();
  vtkOpenGLRenderer* ren = vtkOpenGLRenderer::SafeDownCast(s->GetRenderer());
  vtkOpenGLRenderWindow* win = ren ? vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()) : nullptr;
  if (!win)
  {
    vtkErrorMacro("vtkRayTracePass needs a vtkOpenGLRenderer in a vtkOpenGLRenderWindow.");
    return;
  }
  if (win != in.Window)
  {
    if (in.Window)
    {
      in.ReleaseGL(in.Window);
    }
    in.Window = win;
    in.GeometryOnGpu = false;
    in.ColorsOnGpu = false;
  }
  vtkOpenGLState* ostate = win->GetState();
  vtkOpenGLCamera* cam = vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera());
  if (!cam)
  {
    vtkErrorMacro("vtkRayTracePass needs a vtkOpenGLCamera.");
    return;
  }
  // Viewport, scissor and VTK's own clear (solid or gradient background).
  cam->Render(ren);
  // Lights follow the camera and VTK computes the lighting complexity.
  in.Lights->Render(s);

  in.Scene.SetBuildQuality(this->BuildQuality);
  in.Scene.SetLeafSize(this->LeafSize);
  const int accumulatedBefore = in.AccumulatedFrames;
  in.AccumulatedFrames = 0;
  if (!this->IdMode && (this->Shadows || this->AmbientOcclusionSamples > 0))
  {
    // Secondary rays see props out of view too (VTK's culler left them out of
    // the render state): trace every visible prop, and leave to raster only
    // the render state's own.
    std::vector<vtkProp*> all;
    vtkPropCollection* props = ren->GetViewProps();
    vtkCollectionSimpleIterator pit;
    props->InitTraversal(pit);
    while (vtkProp* prop = props->GetNextProp(pit))
    {
      if (prop->GetVisibility())
      {
        all.push_back(prop);
      }
    }
    std::vector<vtkProp*> others;
    in.Scene.Extract(ren, all.data(), static_cast<int>(all.size()), in.Traced, others, in.Counters);
    vtkProp** stateProps = s->GetPropArray();
    const int stateCount = s->GetPropArrayCount();
    in.Others.clear();
    for (vtkProp* prop : others)
    {
      if (std::find(stateProps, stateProps + stateCount, prop) != stateProps + stateCount)
      {
        in.Others.push_back(prop);
      }
    }
  }
  else
  {
    in.Scene.Extract(
      ren, s->GetPropArray(), s->GetPropArrayCount(), in.Traced, in.Others, in.Counters);
  }

  if (this->IdMode)
  {
    vtkOpenGLState::ScopedglClearColor clearColor(ostate);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }

  // Geometry: repacked and uploaded only when a cached geometry changed.
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  std::size_t limit = static_cast<std::size_t>(maxTexels);
  if (this->MaximumTextureBufferTexels > 0)
  {
    limit = std::min(limit, static_cast<std::size_t>(this->MaximumTextureBufferTexels));
  }
  // A scene refused for its size is tried again when the limit changes.
  const bool limitChanged = limit != in.CheckedLimit;
  in.CheckedLimit = limit;
  if (in.Scene.GeometryChanged() || !in.GeometryOnGpu || (!in.GeometryValid && limitChanged))
  {
    std::vector<float> nodes, tris, triVerts, spheres, sphereIds, normals;
    in.Scene.PackGeometry(nodes, tris, triVerts, spheres, sphereIds, normals);
    in.GeometryValid = true;
    for (const auto* a : { &nodes, &tris, &triVerts, &spheres, &sphereIds, &normals })
    {
      if (a->size() / 4 > limit)
      {
        vtkErrorMacro("The ray-traced scene needs a texture buffer of "
          << a->size() / 4 << " texels, more than the limit of " << limit
          << " (GL_MAX_TEXTURE_BUFFER_SIZE or MaximumTextureBufferTexels): nothing is traced.");
        in.GeometryValid = false;
        break;
      }
    }
    if (in.GeometryValid)
    {
      std::size_t bytes = 0;
      bytes += in.Nodes.Upload(win, nodes);
      bytes += in.Triangles.Upload(win, tris);
      bytes += in.TriangleVertices.Upload(win, triVerts);
      bytes += in.Spheres.Upload(win, spheres);
      bytes += in.SphereIds.Upload(win, sphereIds);
      bytes += in.Normals.Upload(win, normals);
      in.Counters.GeometryBytesUploaded += bytes;
    }
    in.GeometryOnGpu = true;
  }
  if (in.Scene.ColorsChanged() || !in.ColorsOnGpu || (!in.ColorsValid && limitChanged))
  {
    std::vector<float> colors;
    in.Scene.PackColors(colors);
    in.ColorsValid = colors.size() / 4 <= limit;
    if (!in.ColorsValid)
    {
      vtkErrorMacro("The ray-traced scene's colors need " << colors.size() / 4
                                                          << " texels, more than the limit of "
                                                          << limit << ": nothing is traced.");
    }
    else
    {
      in.Counters.GeometryBytesUploaded += in.Colors.Upload(win, colors);
    }
    in.ColorsOnGpu = true;
  }

  const std::vector<Instance>& instances = in.Scene.GetInstances();
  if (!instances.empty() && in.GeometryValid && in.ColorsValid)
  {
    // Camera: VTK's own matrices (the ones raster uses), made relative to
    // the eye in double.
    vtkMatrix4x4* wcvc;
    vtkMatrix3x3* normalMatrix;
    vtkMatrix4x4* vcdc;
    vtkMatrix4x4* wcdc;
    cam->GetKeyMatrices(ren, wcvc, normalMatrix, vcdc, wcdc);
    double eye[3];
    cam->GetPosition(eye);
    // The origin of the shader's coordinates: the eye (camera-relative) or
    // the world origin (WORLD precision mode: plain float world values).
    const double eyeWorld[3] = { eye[0], eye[1], eye[2] };
    if (this->PrecisionMode == WORLD)
    {
      eye[0] = eye[1] = eye[2] = 0.0;
    }
    vtkNew<vtkMatrix4x4> worldToClip; // row-major P * V
    vtkMatrix4x4::Transpose(wcdc, worldToClip);
    vtkNew<vtkMatrix4x4> eyeTranslation;
    for (int k = 0; k < 3; ++k)
    {
      eyeTranslation->SetElement(k, 3, eye[k]);
    }
    vtkNew<vtkMatrix4x4> cameraToClip;
    vtkMatrix4x4::Multiply4x4(worldToClip, eyeTranslation, cameraToClip);
    vtkNew<vtkMatrix4x4> clipToCamera;
    vtkMatrix4x4::Invert(cameraToClip, clipToCamera);
    double dop[3];
    cam->GetDirectionOfProjection(dop);

    // Per-instance records and clip planes (camera-relative, double -> float).
    std::vector<float> records(instances.size() * kInstanceTexels * 4, 0.0f);
    std::vector<float> planes;
    std::vector<vtkrt::core::AABB<double>> worldBoxes(instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i)
    {
      const Instance& inst = instances[i];
      const vtkrt::pass::Geometry& g = *inst.Geom;
      vtkNew<vtkMatrix4x4> localToCamera;
      localToCamera->DeepCopy(inst.Matrix.data());
      for (int r = 0; r < 3; ++r)
      {
        double t = localToCamera->GetElement(r, 3);
        for (int c = 0; c < 3; ++c)
        {
          t += localToCamera->GetElement(r, c) * g.Origin[c];
        }
        localToCamera->SetElement(r, 3, t - eye[r]);
      }
      vtkNew<vtkMatrix4x4> cameraToLocal;
      vtkMatrix4x4::Invert(localToCamera, cameraToLocal);
      // Points drawn as spheres: radii from this frame's camera.
      const double eyeInShader[3] = { eyeWorld[0] - eye[0], eyeWorld[1] - eye[1],
        eyeWorld[2] - eye[2] };
      const vtkrt::pass::ScreenSphereRadii screen =
        vtkrt::pass::ComputeScreenSphereRadii(inst, ren, localToCamera->GetData(), eyeInShader);
      // The world box (independent of the camera) for the top level.
      for (int corner = 0; corner < 8; ++corner)
      {
        double p[4] = { g.LocalBounds[(corner & 1) ? 1 : 0] + g.Origin[0],
          g.LocalBounds[(corner & 2) ? 3 : 2] + g.Origin[1],
          g.LocalBounds[(corner & 4) ? 5 : 4] + g.Origin[2], 1.0 };
        double w[4];
        for (int r = 0; r < 4; ++r)
        {
          w[r] = inst.Matrix[4 * r] * p[0] + inst.Matrix[4 * r + 1] * p[1] +
            inst.Matrix[4 * r + 2] * p[2] + inst.Matrix[4 * r + 3];
        }
        worldBoxes[i].extend(vtkrt::core::Vec3<double>(w[0] / w[3], w[1] / w[3], w[2] / w[3]));
      }
      if (screen.MaxWorld > 0.0)
      {
        // Grown by the radius bound rounded up to a power of two, so the top
        // level is rebuilt only when a zoom crosses one.
        const double grow = std::exp2(std::ceil(std::log2(screen.MaxWorld)));
        worldBoxes[i].min -= vtkrt::core::Vec3<double>(grow);
        worldBoxes[i].max += vtkrt::core::Vec3<double>(grow);
      }
      float* rec = records.data() + i * kInstanceTexels * 4;
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 4; ++c)
        {
          rec[4 * r + c] = static_cast<float>(cameraToLocal->GetElement(r, c));
        }
      }
      // Camera-space box of the instance: its 8 local corners, padded for
      // the float rounding of the transformed ray.
      double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
      double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
      for (int corner = 0; corner < 8; ++corner)
      {
        double p[4] = { g.LocalBounds[(corner & 1) ? 1 : 0], g.LocalBounds[(corner & 2) ? 3 : 2],
          g.LocalBounds[(corner & 4) ? 5 : 4], 1.0 };
        localToCamera->MultiplyPoint(p, p);
        for (int k = 0; k < 3; ++k)
        {
          lo[k] = std::min(lo[k], p[k]);
          hi[k] = std::max(hi[k], p[k]);
        }
      }
      double pad = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        pad = std::max({ pad, std::abs(lo[k]), std::abs(hi[k]) });
      }
      pad = pad * 1e-6 + screen.MaxWorld;
      std::uint32_t flags = g.Spheres ? kSpheres : 0u;
      flags |= g.Ellipsoids ? kEllipsoids : 0u;
      flags |= inst.Lit ? kLit : 0u;
      flags |= inst.UseVertexNormals ? kVertexNormals : 0u;
      if (inst.Color)
      {
        flags |= inst.Color->CellColors ? kCellColors : kPointColors;
        flags |= inst.Color->Texture ? kColorTexture : 0u;
      }
      if (localToCamera->Determinant() < 0.0)
      {
        flags |= kMirrored;
      }
      for (int k = 0; k < 3; ++k)
      {
        rec[12 + k] = vtkrt::core::roundDownToFloat(lo[k] - pad);
        rec[16 + k] = vtkrt::core::roundUpToFloat(hi[k] + pad);
        rec[20 + k] = inst.Ambient[k];
        rec[24 + k] = inst.Diffuse[k];
        rec[28 + k] = inst.Specular[k];
      }
      rec[15] = bits(g.NodeBase);
      rec[19] = bits(flags);
      rec[23] = inst.SpecularPower;
      rec[27] = bits(inst.Color ? inst.Color->Base : 0u);
      rec[31] = bits(g.NormalBase);
      rec[32] = bits(static_cast<std::uint32_t>(planes.size() / 4));
      rec[33] = bits(static_cast<std::uint32_t>(inst.ClipPlanes.size()));
      rec[34] = bits(static_cast<std::uint32_t>(inst.PropIndex));
      rec[35] = 0.0f;
      rec[36] = inst.AmbientIntensity;
      rec[37] = inst.DiffuseIntensity;
      rec[38] = static_cast<float>(screen.MaxLocal);
      for (int k = 0; k < 4; ++k)
      {
        rec[40 + k] = static_cast<float>(screen.Plane[k]);
      }
      for (const auto& pl : inst.ClipPlanes)
      {
        const double d = pl[3] + pl[0] * eye[0] + pl[1] * eye[1] + pl[2] * eye[2];
        planes.insert(planes.end(),
          { static_cast<float>(pl[0]), static_cast<float>(pl[1]), static_cast<float>(pl[2]),
            static_cast<float>(d) });
      }
    }
    const bool topLevel = instances.size() > kTopLevelMinInstances;
    if (topLevel)
    {
      std::vector<double> signature;
      signature.reserve(6 * worldBoxes.size());
      for (const auto& b : worldBoxes)
      {
        signature.insert(signature.end(), { b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z });
      }
      if (signature != in.TopSignature || !in.TopNodes.Texels)
      {
        vtkrt::core::BVH top = vtkrt::core::buildBVH(worldBoxes);
        in.TopAnchor = top.bounds().center();
        std::vector<float> nodes = vtkrt::core::packNodesForGpu(top, in.TopAnchor);
        // Pad for the float rounding of the anchor-relative ray origin.
        float extent = 0.0f;
        for (std::size_t k = 0; k < std::min<std::size_t>(nodes.size(), 8); ++k)
        {
          if (k != 3 && k != 7)
          {
            extent = std::max(extent, std::abs(nodes[k]));
          }
        }
        const float pad = 1e-6f * extent;
        for (std::size_t k = 0; k < nodes.size(); k += 8)
        {
          for (int c = 0; c < 3; ++c)
          {
            nodes[k + c] -= pad;
            nodes[k + 4 + c] += pad;
          }
        }
        in.TopOrder = top.primIndex;
        in.TopSignature = signature;
        in.Counters.GeometryBytesUploaded += in.TopNodes.Upload(win, nodes);
        ++in.Counters.TopLevelBuilds;
      }
      // Records in top-level leaf order (leaves index them directly).
      std::vector<float> ordered(in.TopOrder.size() * kInstanceTexels * 4);
      for (std::size_t k = 0; k < in.TopOrder.size(); ++k)
      {
        std::copy_n(records.begin() + in.TopOrder[k] * kInstanceTexels * 4, kInstanceTexels * 4,
          ordered.begin() + k * kInstanceTexels * 4);
      }
      records.swap(ordered);
    }
    // Unchanged records (a still frame; any camera move in WORLD mode) are
    // not uploaded again.
    if (records != in.LastRecords || !in.Instances.Texels)
    {
      in.Counters.FrameBytesUploaded += in.Instances.Upload(win, records);
      in.LastRecords = records;
    }

    // Lights, as vtkOpenGLRenderer hands them to vtkOpenGLPolyDataMapper.
    std::vector<float> lightColor, lightDirection, lightPosition, lightAttenuation, lightCone;
    vtkLightCollection* lights = ren->GetLights();
    vtkCollectionSimpleIterator it;
    lights->InitTraversal(it);
    while (vtkLight* light = lights->GetNextLight(it))
    {
      if (!light->GetSwitch())
      {
        continue;
      }
      const double intensity = light->GetIntensity();
      double* color = light->GetDiffuseColor();
      double* position = light->GetTransformedPosition();
      double* focal = light->GetTransformedFocalPoint();
      double direction[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
      vtkMath::Normalize(direction);
      double* attenuation = light->GetAttenuationValues();
      for (int k = 0; k < 3; ++k)
      {
        lightColor.push_back(static_cast<float>(color[k] * intensity));
        lightDirection.push_back(static_cast<float>(direction[k]));
        lightPosition.push_back(static_cast<float>(position[k] - eye[k]));
        lightAttenuation.push_back(static_cast<float>(attenuation[k]));
      }
      lightCone.push_back(static_cast<float>(light->GetConeAngle()));
      lightCone.push_back(static_cast<float>(light->GetExponent()));
      lightCone.push_back(light->GetPositional() ? 1.0f : 0.0f);
    }

    Features f;
    f.Triangles = in.Scene.HasTriangles();
    f.Spheres = in.Scene.HasSpheres();
    f.VertexNormals = in.Scene.HasVertexNormals();
    f.Colors = in.Scene.HasColors();
    f.ColorTexture = in.Scene.HasColorTexture();
    f.ClipPlanes = static_cast<int>(planes.size() / 4);
    f.Lights = static_cast<int>(lightCone.size() / 3);
    f.LightComplexity = f.Lights > 0 ? ren->GetLightingComplexity() : 0;
    f.IdMode = this->IdMode;
    f.TopLevel = topLevel;
    // Sub-pixel sampling goes through the accumulation buffer (not in id
    // mode: ids do not average).
    const bool sampled =
      !this->IdMode && (this->SamplesPerPixel > 1 || this->ProgressiveAccumulation);
    f.SamplesPerPixel = sampled ? this->SamplesPerPixel : 0;
    // Secondary rays only where they change the image: shaded, lit frames.
    const bool shaded = !this->IdMode && f.LightComplexity > 0;
    f.Shadows = shaded && this->Shadows;
    f.AmbientOcclusionSamples = shaded ? this->AmbientOcclusionSamples : 0;
    f.MaximumTraversalSteps = this->MaximumTraversalSteps;
    f.WorldCoordinates = this->PrecisionMode == WORLD;
    f.ScreenSpheres = in.Scene.HasScreenSpheres();
    f.Ellipsoids = in.Scene.HasEllipsoids();
    double occlusionRadius = this->AmbientOcclusionRadius;
    if (occlusionRadius <= 0.0)
    {
      vtkrt::core::AABB<double> all;
      for (const auto& b : worldBoxes)
      {
        all.extend(b.min);
        all.extend(b.max);
      }
      const auto diagonal = all.max - all.min;
      occlusionRadius =
        0.1 * std::sqrt(diagonal.x * diagonal.x + diagonal.y * diagonal.y + diagonal.z * diagonal.z);
    }
    GLint major = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    f.Fp64 = major >= 4;
    const std::string key = f.Key();
    if (key != in.LastKey)
    {
      in.LastSource = assembleShader(f);
      in.LastKey = key;
    }

    auto& helper = in.Programs[in.LastKey];
    if (!helper)
    {
      helper.reset(new vtkOpenGLQuadHelper(win, nullptr, in.LastSource.c_str(), ""));
      ++in.Counters.ShaderCompiles;
      if (!helper->Program || !helper->Program->GetCompiled())
      {
        vtkErrorMacro("vtkRayTracePass: the ray tracing shader (features " << in.LastKey
                                                                          << ") failed to compile.");
      }
    }
    else
    {
      win->GetShaderCache()->ReadyShaderProgram(helper->Program);
    }
    vtkShaderProgram* program = helper->Program;
    if (program && program->GetCompiled())
    {
      float m[16];
      toGLSL(cameraToClip, m);
      program->SetUniformMatrix4x4("uCameraToClip", m);
      toGLSL(clipToCamera, m);
      program->SetUniformMatrix4x4("uClipToCamera", m);
      const float viewBack[3] = { static_cast<float>(-dop[0]), static_cast<float>(-dop[1]),
        static_cast<float>(-dop[2]) };
      program->SetUniform3f("uViewBack", viewBack);
      program->SetUniformi("uNumberOfInstances", static_cast<int>(instances.size()));
      if (f.WorldCoordinates)
      {
        const float eyeFloat[3] = { static_cast<float>(eyeWorld[0]),
          static_cast<float>(eyeWorld[1]), static_cast<float>(eyeWorld[2]) };
        program->SetUniform3f("uEye", eyeFloat);
      }
      if (f.AmbientOcclusionSamples > 0)
      {
        program->SetUniformf("uAmbientOcclusionRadius", static_cast<float>(occlusionRadius));
      }
      if (topLevel)
      {
        const float toAnchor[3] = { static_cast<float>(eye[0] - in.TopAnchor.x),
          static_cast<float>(eye[1] - in.TopAnchor.y), static_cast<float>(eye[2] - in.TopAnchor.z) };
        program->SetUniform3f("uCameraToAnchor", toAnchor);
      }
      if (f.ClipPlanes > 0)
      {
        program->SetUniform4fv("uClipPlanes", f.ClipPlanes, planes.data());
      }
      if (f.Lights > 0)
      {
        program->SetUniform3fv("uLightColor", f.Lights, lightColor.data());
        program->SetUniform3fv("uLightDirection", f.Lights, lightDirection.data());
        program->SetUniform3fv("uLightPosition", f.Lights, lightPosition.data());
        program->SetUniform3fv("uLightAttenuation", f.Lights, lightAttenuation.data());
        program->SetUniform3fv("uLightCone", f.Lights, lightCone.data());
      }
      std::vector<vtkTextureObject*> active;
      const std::pair<const char*, TextureBuffer*> samplers[] = { { "uNodes", &in.Nodes },
        { "uTriangles", &in.Triangles }, { "uTriangleVertices", &in.TriangleVertices },
        { "uSpheres", &in.Spheres }, { "uSphereIds", &in.SphereIds }, { "uNormals", &in.Normals },
        { "uColors", &in.Colors }, { "uInstances", &in.Instances }, { "uTopNodes", &in.TopNodes } };
      for (const auto& sampler : samplers)
      {
        if (program->IsUniformUsed(sampler.first))
        {
          sampler.second->Texture->Activate();
          program->SetUniformi(sampler.first, sampler.second->Texture->GetTextureUnit());
          active.push_back(sampler.second->Texture);
        }
      }

      vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
      vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
      vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
      vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
      ostate->vtkglEnable(GL_DEPTH_TEST);
      ostate->vtkglDepthFunc(GL_ALWAYS);
      ostate->vtkglDepthMask(GL_TRUE);
      ostate->vtkglDisable(GL_BLEND);
      if (sampled)
      {
        // What the image is traced from: any change restarts accumulating.
        std::vector<float> signature(m, m + 16);
        toGLSL(cameraToClip, m);
        signature.insert(signature.end(), m, m + 16);
        for (const auto* a : { &records, &planes, &lightColor, &lightDirection, &lightPosition,
               &lightAttenuation, &lightCone })
        {
          signature.push_back(static_cast<float>(a->size()));
          signature.insert(signature.end(), a->begin(), a->end());
        }
        signature.push_back(static_cast<float>(occlusionRadius));
        signature.insert(signature.end(), in.LastKey.begin(), in.LastKey.end());
        int width = 0, height = 0, originX = 0, originY = 0;
        ren->GetTiledSizeAndOrigin(&width, &height, &originX, &originY);
        width = std::max(width, 1);
        height = std::max(height, 1);
        const bool resized = width != in.AccumulationSize[0] || height != in.AccumulationSize[1];
        const bool restart = !this->ProgressiveAccumulation || resized ||
          in.Counters.GeometryBytesUploaded > 0 || in.Counters.ShaderCompiles > 0 ||
          accumulatedBefore == 0 || signature != in.AccumulationSignature;
        if (resized)
        {
          in.AccumulationColor->SetContext(win);
          in.AccumulationColor->Allocate2D(width, height, 4, VTK_FLOAT);
          in.AccumulationDepth->SetContext(win);
          in.AccumulationDepth->AllocateDepth(width, height, vtkTextureObject::Float32);
          in.AccumulationFBO->SetContext(win);
          ostate->PushFramebufferBindings();
          in.AccumulationFBO->Bind();
          in.AccumulationFBO->AddColorAttachment(0, in.AccumulationColor);
          in.AccumulationFBO->AddDepthAttachment(in.AccumulationDepth);
          ostate->PopFramebufferBindings();
          in.AccumulationSize[0] = width;
          in.AccumulationSize[1] = height;
        }
        in.AccumulatedFrames = restart ? 1 : accumulatedBefore + 1;
        in.AccumulationSignature.swap(signature);
        {
          ostate->PushFramebufferBindings();
          in.AccumulationFBO->Bind();
          in.AccumulationFBO->ActivateDrawBuffers(1);
          vtkOpenGLState::ScopedglViewport viewport(ostate);
          vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
          vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
          ostate->vtkglViewport(0, 0, width, height);
          ostate->vtkglDisable(GL_SCISSOR_TEST);
          if (restart)
          {
            vtkOpenGLState::ScopedglClearColor clearColor(ostate);
            ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
            ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
          }
          // The depth is the first frame's; later frames only add colors.
          ostate->vtkglDepthMask(restart ? GL_TRUE : GL_FALSE);
          ostate->vtkglEnable(GL_BLEND);
          ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
          program->SetUniformi(
            "uFirstSample", (in.AccumulatedFrames - 1) * this->SamplesPerPixel);
          const float pixelSize[2] = { 2.0f / width, 2.0f / height };
          program->SetUniform2f("uPixelSize", pixelSize);
          helper->Render();
          ostate->PopFramebufferBindings();
        }
        for (vtkTextureObject* t : active)
        {
          t->Deactivate();
        }
        active.clear();

        // Resolve: the average, blended by coverage over the background.
        if (!in.Resolve)
        {
          const std::string resolveSource = std::string("#version 330 core\n") + vtkrtRayTraceResolve;
          in.Resolve.reset(new vtkOpenGLQuadHelper(win, nullptr, resolveSource.c_str(), ""));
          ++in.Counters.ShaderCompiles;
        }
        else
        {
          win->GetShaderCache()->ReadyShaderProgram(in.Resolve->Program);
        }
        vtkShaderProgram* resolve = in.Resolve->Program;
        if (!resolve || !resolve->GetCompiled())
        {
          vtkErrorMacro("vtkRayTracePass: the accumulation resolve shader failed to compile.");
        }
        else
        {
          vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
          ostate->vtkglDepthMask(GL_TRUE);
          ostate->vtkglEnable(GL_BLEND);
          ostate->vtkglBlendFuncSeparate(
            GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
          in.AccumulationColor->Activate();
          in.AccumulationDepth->Activate();
          resolve->SetUniformi("uAccumulation", in.AccumulationColor->GetTextureUnit());
          resolve->SetUniformi("uAccumulationDepth", in.AccumulationDepth->GetTextureUnit());
          resolve->SetUniformf("uInverseSamples",
            1.0f / static_cast<float>(in.AccumulatedFrames * this->SamplesPerPixel));
          in.Resolve->Render();
          in.AccumulationColor->Deactivate();
          in.AccumulationDepth->Deactivate();
        }
      }
      else
      {
        helper->Render();
      }
      for (vtkTextureObject* t : active)
      {
        t->Deactivate();
      }
    }
  }
  this->NumberOfRenderedProps += static_cast<int>(in.Traced.size());

  if (!this->IdMode && this->DelegatePass && !in.Others.empty())
  {
    vtkRenderState rest(ren);
    rest.SetPropArrayAndCount(in.Others.data(), static_cast<int>(in.Others.size()));
    rest.SetFrameBuffer(s->GetFrameBuffer());
    rest.SetRequiredKeys(s->GetRequiredKeys());
    this->DelegatePass->Render(&rest);
    this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  }
  vtkOpenGLCheckErrorMacro("failed after vtkRayTracePass::Render");
}
