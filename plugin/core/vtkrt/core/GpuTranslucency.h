// The C++ twins of the shader's translucency (shaders/vtkrtRayTraceTranslucent.glsl):
// the layer step past a hit, front-to-back compositing, and the layer walk
// that traceTranslucentLayers runs over the closest-hit traversal for the
// camera ray and for each layer's shadow and occlusion rays (the shader
// interleaves those walks in one loop; each is this walk), here over one
// bottom-level triangle BVH (traverseTriangles). Names and float operations
// are the shader's (see GpuKernels.h).
#ifndef vtkrt_core_GpuTranslucency_h
#define vtkrt_core_GpuTranslucency_h

#include "vtkrt/core/GpuTraversal.h"

#include <cstdint>

namespace vtkrt::core::gpu
{

/// Accumulated alpha from which what lies behind adds under 1/1024: the ray stops.
constexpr float kOpaqueAlpha = 1.0f - 1.0f / 1024.0f;
/// The next layer starts this many float ulps of t past a hit, so the
/// triangles about a shared edge or vertex (hit at t a few ulps apart by the
/// watertight test) count as one layer.
constexpr std::uint32_t kLayerGapUlps = 64u;
/// Transmittance below which a secondary ray counts as blocked.
constexpr float kBlockedTransmittance = 1.0f / 1024.0f;

/// The smallest t of the layer after a hit at t (t >= 0). GLSL's max(x, y)
/// is (x < y ? y : x).
inline float nextLayerTMin(float t)
{
  const float next = uintBitsToFloat(floatBitsToUint(t) + kLayerGapUlps);
  return next < 1.0e-30f ? 1.0e-30f : next;
}

/// Front-to-back compositing ("under"): the layer (color, alpha) behind what
/// is accumulated (premultiplied RGB, alpha) shows through what is left.
inline void compositeLayer(vec4& accumulated, const vec3& color, float alpha)
{
  const float weight = (1.0f - accumulated.a) * alpha;
  accumulated.r += weight * color.r;
  accumulated.g += weight * color.g;
  accumulated.b += weight * color.b;
  accumulated.a += weight;
}

/// A visibility ray crosses a layer of `opacity` (the shader's crossLayer,
/// which reads it with surfaceOpacity): what it lets through multiplies
/// the transmittance; false, and a transmittance of 0, once the ray counts
/// as blocked (a NaN blocks too).
inline bool crossLayer(float& transmittance, float opacity)
{
  transmittance *= 1.0f - opacity;
  if (!(transmittance >= kBlockedTransmittance))
  {
    transmittance = 0.0f;
    return false;
  }
  return true;
}

/// The layer loop of traceTranslucentLayers (camera and visibility rays) over the
/// triangle BVH at `root`: each closest hit within [tMin, tmax], from tMin
/// 0, then past the hit by nextLayerTMin, until none is left or
/// `layer(t, tri, uv)` returns false (the ray is done).
template <class Layer>
inline void walkLayers(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmax,
  Layer&& layer)
{
  float tMin = 0.0f;
  for (;;)
  {
    float t = tmax;
    int tri;
    vec2 uv;
    if (!traverseTriangles(u, root, org, dir, tMin, t, tri, uv, false) || !layer(t, tri, uv))
    {
      return;
    }
    tMin = nextLayerTMin(t);
  }
}

} // namespace vtkrt::core::gpu

#endif
