// The C++ twins of the shader's BVH walks: the while-while walk of
// traverseTriangles and traverseSpheres (bvhInteriorStep, bvhPopAfterLeaf)
// and the top-level walk of traceTopLevel, reading the packed arrays the
// pass uploads (packNodesForGpu and the primitive texels) the way the
// shader reads its texture buffers: through texelFetch on a TexelBuffer.
// Names, arguments and operations are the shader's (see GpuKernels.h);
// uniforms and feature #defines the walks read are a ShaderInputs.
#ifndef vtkrt_core_GpuTraversal_h
#define vtkrt_core_GpuTraversal_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/GpuKernels.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <vector>

namespace vtkrt::core::gpu
{

/// A texture buffer of four 32-bit components per texel (the pass's
/// RGBA32UI buffers), over an array the caller keeps alive. The one place
/// the twins read packed data.
class TexelBuffer
{
public:
  TexelBuffer() = default;
  explicit TexelBuffer(const std::vector<float>& components)
    : Bytes(reinterpret_cast<const unsigned char*>(components.data()))
    , Texels(components.size() / 4)
  {
  }
  explicit TexelBuffer(const std::vector<std::uint32_t>& components)
    : Bytes(reinterpret_cast<const unsigned char*>(components.data()))
    , Texels(components.size() / 4)
  {
  }

  /// Texel i as bits; a texel beyond the buffer reads as zero, as under
  /// GL's robust buffer access (the shader never reads one).
  uvec4 fetch(int i) const
  {
    assert(i >= 0 && static_cast<std::size_t>(i) < Texels);
    uvec4 texel(0u);
    if (i >= 0 && static_cast<std::size_t>(i) < Texels)
    {
      std::memcpy(&texel, Bytes + 16 * static_cast<std::size_t>(i), sizeof texel);
    }
    return texel;
  }
  std::size_t size() const { return Texels; }

private:
  const unsigned char* Bytes = nullptr;
  std::size_t Texels = 0;
};

inline uvec4 texelFetch(const TexelBuffer& buffer, int i)
{
  return buffer.fetch(i);
}

inline vec3 uintBitsToFloat(const glm::uvec3& bits)
{
  return vec3(core::uintBitsToFloat(bits.x), core::uintBitsToFloat(bits.y), core::uintBitsToFloat(bits.z));
}

inline vec4 uintBitsToFloat(const uvec4& bits)
{
  return vec4(uintBitsToFloat(glm::uvec3(bits)), core::uintBitsToFloat(bits.w));
}

/// A node texel's box corner (lo: min, hi: max).
inline vec3 boxCorner(const uvec4& texel)
{
  return uintBitsToFloat(glm::uvec3(texel));
}

/// Value i of a buffer of four 32-bit values per texel (ids, RGBA8 colors).
inline std::uint32_t fetchPacked(const TexelBuffer& buffer, int i)
{
  const uvec4 texel = texelFetch(buffer, i >> 2);
  const int c = i & 3;
  return c == 0 ? texel.x : (c == 1 ? texel.y : (c == 2 ? texel.z : texel.w));
}

/// What the walks read besides their arguments: the texture buffers (named
/// as the shader's uniforms) and the #defines that change a walk.
struct ShaderInputs
{
  TexelBuffer uNodes;     ///< every bottom-level BVH, 2 texels a node (packNodesForGpu)
  TexelBuffer uTriangles; ///< 3 texels a triangle in leaf order: (v0, cell id), (v1, 0), (v2, 0)
  TexelBuffer uSpheres;   ///< a texel a sphere (center, radius), 3 an ellipsoid (its map's rows)
  TexelBuffer uTopNodes;  ///< the top-level BVH over the instance records
  vec3 uCameraToAnchor = vec3(0.0f);
  int maximumTraversalSteps = 0; ///< VTKRT_MAXIMUM_TRAVERSAL_STEPS (0: no cap)
  bool screenSpheres = false;    ///< VTKRT_SCREEN_SPHERES
  bool hasEllipsoids = false;    ///< VTKRT_HAS_ELLIPSOIDS
};

/// The shader's bvhStackIndex, bvhStackCount and bvhStackNear.
struct BvhStack
{
  std::uint32_t index[kMaxStackSize] = {};
  std::uint32_t count[kMaxStackSize] = {};
  float tnear[kMaxStackSize] = {};
};

/// One interior step (see the shader): the farther child is written above
/// the stack top and kept only when both children are hit; the top entry
/// is read every step and used only at a dead end. False when the walk is
/// over.
inline bool bvhInteriorStep(BvhStack& stack, const uvec4& lo0, const uvec4& hi0, bool h0, float t0,
  const uvec4& lo1, const uvec4& hi1, bool h1, float t1, float tmax, int& sp, std::uint32_t& index,
  std::uint32_t& count, bool& culled)
{
  assert(sp >= 0 && sp + 1 < static_cast<int>(kMaxStackSize));
  const bool nearIs1 = h1 && (!h0 || t1 < t0);
  stack.index[sp] = nearIs1 ? lo0.w : lo1.w;
  stack.count[sp] = nearIs1 ? hi0.w : hi1.w;
  stack.tnear[sp] = nearIs1 ? t0 : t1;
  const bool anyHit = h0 || h1;
  if (!anyHit && sp == 0)
  {
    return false;
  }
  sp += h0 && h1 ? 1 : 0;
  const int top = anyHit ? sp : std::max(sp - 1, 0);
  culled = !anyHit && stack.tnear[top] > tmax;
  const std::uint32_t popIndex = stack.index[top];
  const std::uint32_t popCount = stack.count[top];
  sp = top;
  index = anyHit ? (nearIs1 ? lo1.w : lo0.w) : (culled ? 0u : popIndex);
  count = anyHit ? (nearIs1 ? hi1.w : hi0.w) : (culled ? 0u : popCount);
  return true;
}

/// After a leaf: the next node from the stack (culled when tmax prunes it).
/// False when the stack is empty.
inline bool bvhPopAfterLeaf(
  BvhStack& stack, float tmax, int& sp, std::uint32_t& index, std::uint32_t& count, bool& culled)
{
  if (sp == 0)
  {
    return false;
  }
  --sp;
  culled = stack.tnear[sp] > tmax;
  index = culled ? 0u : stack.index[sp];
  count = culled ? 0u : stack.count[sp];
  return true;
}

/// The interior part of the walk (see the shader): descends from the node at
/// hand to a leaf, boxes grown by growBy; false when the walk is over.
inline bool bvhDescend(BvhStack& stack, const ShaderInputs& u, const vec3& org, const vec3& invDir,
  const vec3& parallelBias, const vec3& growBy, float tmin, float tmax, int& sp, int& steps,
  std::uint32_t& index, std::uint32_t& count, bool& culled)
{
  while (count == 0u)
  {
    if (u.maximumTraversalSteps > 0 && ++steps > u.maximumTraversalSteps)
    {
      return false;
    }
    const int child = 2 * static_cast<int>(index);
    const uvec4 lo0 = texelFetch(u.uNodes, child);
    const uvec4 hi0 = texelFetch(u.uNodes, child + 1);
    const uvec4 lo1 = texelFetch(u.uNodes, child + 2);
    const uvec4 hi1 = texelFetch(u.uNodes, child + 3);
    float t0, t1;
    const bool h0 = intersectRayBoxConservative(org, invDir, parallelBias, boxCorner(lo0) - growBy,
                      boxCorner(hi0) + growBy, tmin, tmax, t0) && !culled;
    const bool h1 = intersectRayBoxConservative(org, invDir, parallelBias, boxCorner(lo1) - growBy,
                      boxCorner(hi1) + growBy, tmin, tmax, t1) && !culled;
    if (!bvhInteriorStep(stack, lo0, hi0, h0, t0, lo1, hi1, h1, t1, tmax, sp, index, count, culled))
    {
      return false;
    }
  }
  return true;
}

namespace detail
{
/// The walk that traverseTriangles and traverseSpheres share (the shader
/// spells it out in both): leaf(first, count) tests a leaf's primitives
/// and returns true to end the walk; it shrinks tmax (the caller's, so the
/// walk prunes by it) on a hit. Grow: boxes grow by `grow` (spheres).
template <bool Grow, class Leaf>
inline void whileWhileWalk(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, float grow, Leaf&& leaf)
{
  const vec3 invDir = safeInverse(dir);
  const vec3 parallelBias = parallelAxisBias(invDir);
  const vec3 growBy = vec3(grow);
  const auto lower = [&](const uvec4& texel) { return Grow ? boxCorner(texel) - growBy : boxCorner(texel); };
  const auto upper = [&](const uvec4& texel) { return Grow ? boxCorner(texel) + growBy : boxCorner(texel); };
  float tnear;
  const uvec4 rootLo = texelFetch(u.uNodes, 2 * root);
  const uvec4 rootHi = texelFetch(u.uNodes, 2 * root + 1);
  if (!intersectRayAABB(org, invDir, lower(rootLo), upper(rootHi), tmin, tmax, tnear))
  {
    return;
  }
  BvhStack stack;
  int sp = 0;
  int steps = 0;
  std::uint32_t index = rootLo.w;
  std::uint32_t count = rootHi.w;
  bool culled = false;
  for (;;)
  {
    if (!bvhDescend(stack, u, org, invDir, parallelBias, Grow ? growBy : vec3(0.0f), tmin, tmax, sp,
      steps, index, count, culled))
    {
      break;
    }
    if (u.maximumTraversalSteps > 0 && ++steps > u.maximumTraversalSteps)
    {
      break;
    }
    if (leaf(static_cast<int>(index), static_cast<int>(count)))
    {
      return;
    }
    if (!bvhPopAfterLeaf(stack, tmax, sp, index, count, culled))
    {
      break;
    }
  }
}
} // namespace detail

/// Closest hit (any hit with stopAtFirstHit) in the triangle BVH whose root
/// node is `root`: tmax becomes the hit's t, tri its leaf-order index into
/// uTriangles, uv its barycentrics.
inline bool traverseTriangles(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, int& tri, vec2& uv, bool stopAtFirstHit)
{
  tri = -1;
  uv = vec2(0.0f);
  const RayTrianglePrecomputed pre = precomputeRayTriangle(org, dir);
  detail::whileWhileWalk<false>(u, root, org, dir, tmin, tmax, 0.0f, [&](int first, int count) {
    const int end = first + count;
    for (int i = first; i < end; ++i)
    {
      const vec3 v0 = uintBitsToFloat(glm::uvec3(texelFetch(u.uTriangles, 3 * i)));
      const vec3 v1 = uintBitsToFloat(glm::uvec3(texelFetch(u.uTriangles, 3 * i + 1)));
      const vec3 v2 = uintBitsToFloat(glm::uvec3(texelFetch(u.uTriangles, 3 * i + 2)));
      vec3 h;
      if (intersectRayTriangle(pre, v0, v1, v2, tmin, tmax, h))
      {
        tmax = h.x;
        tri = i;
        uv = vec2(h.y, h.z);
      }
    }
    return stopAtFirstHit && tri >= 0;
  });
  return tri >= 0;
}

/// Closest hit (any hit with stopAtFirstHit) in the sphere BVH whose root
/// node is `root`: tmax becomes the hit's t, sphere its texel in uSpheres.
/// Screen-sized spheres get this frame's radius from radiusPlane and grow
/// every box by `grow`; an ellipsoid set (`ellipsoids`) maps the ray onto
/// each one's unit sphere.
inline bool traverseSpheres(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, int& sphere, bool stopAtFirstHit, const vec4& radiusPlane, float grow, bool ellipsoids)
{
  sphere = -1;
  detail::whileWhileWalk<true>(u, root, org, dir, tmin, tmax, grow, [&](int first, int count) {
    int end = first + count;
    if (u.hasEllipsoids)
    {
      if (ellipsoids)
      {
        const int last = first + 3 * count;
        for (int i = first; i < last; i += 3)
        {
          const vec4 r0 = uintBitsToFloat(texelFetch(u.uSpheres, i));
          const vec4 r1 = uintBitsToFloat(texelFetch(u.uSpheres, i + 1));
          const vec4 r2 = uintBitsToFloat(texelFetch(u.uSpheres, i + 2));
          const vec3 unitOrg(glm::dot(vec3(r0), org) + r0.w, glm::dot(vec3(r1), org) + r1.w,
            glm::dot(vec3(r2), org) + r2.w);
          const vec3 unitDir(glm::dot(vec3(r0), dir), glm::dot(vec3(r1), dir), glm::dot(vec3(r2), dir));
          float t;
          if (intersectRaySphere(unitOrg, unitDir, vec3(0.0f), 1.0f, tmin, tmax, t))
          {
            tmax = t;
            sphere = i;
          }
        }
      }
      end = ellipsoids ? first : first + count;
    }
    for (int i = first; i < end; ++i)
    {
      vec4 s = uintBitsToFloat(texelFetch(u.uSpheres, i));
      if (u.screenSpheres)
      {
        s.w += glm::max(0.0f, glm::dot(vec3(radiusPlane), vec3(s)) + radiusPlane.w);
      }
      float t;
      if (intersectRaySphere(org, dir, vec3(s), s.w, tmin, tmax, t))
      {
        tmax = t;
        sphere = i;
      }
    }
    return stopAtFirstHit && sphere >= 0;
  });
  return sphere >= 0;
}

/// The top-level walk over the instance records: core's nearer-first walk
/// (detail::OrderedWalk) over uTopNodes, whose boxes are relative to an
/// anchor (uCameraToAnchor moves the ray origin there); a leaf's records
/// [index, index + count) go to traceInstance, the shader's function of
/// that name: traceInstance(instance, org, dir, invDir, tBest, hitInstance,
/// hitPrimitive, hitUV, stopAtFirstHit) updates the best hit.
template <class TraceInstance>
inline void traceTopLevel(const ShaderInputs& u, const vec3& org, const vec3& dir, const vec3& invDir,
  float& tBest, int& hitInstance, int& hitPrimitive, vec2& hitUV, bool stopAtFirstHit,
  TraceInstance&& traceInstance)
{
  const vec3 anchorOrg = org + u.uCameraToAnchor;
  float tnear;
  if (!intersectRayAABB(anchorOrg, invDir, boxCorner(texelFetch(u.uTopNodes, 0)),
        boxCorner(texelFetch(u.uTopNodes, 1)), 0.0f, tBest, tnear))
  {
    return;
  }
  core::detail::OrderedWalk<float> walk;
  std::uint32_t cur = 0;
  for (;;)
  {
    const int index = static_cast<int>(texelFetch(u.uTopNodes, 2 * static_cast<int>(cur)).w);
    const int count = static_cast<int>(texelFetch(u.uTopNodes, 2 * static_cast<int>(cur) + 1).w);
    if (count > 0)
    {
      for (int i = index; i < index + count; ++i)
      {
        traceInstance(i, org, dir, invDir, tBest, hitInstance, hitPrimitive, hitUV, stopAtFirstHit);
        if (stopAtFirstHit && hitInstance >= 0)
        {
          return;
        }
      }
    }
    else
    {
      float t0, t1;
      const bool h0 = intersectRayAABB(anchorOrg, invDir, boxCorner(texelFetch(u.uTopNodes, 2 * index)),
        boxCorner(texelFetch(u.uTopNodes, 2 * index + 1)), 0.0f, tBest, t0);
      const bool h1 = intersectRayAABB(anchorOrg, invDir, boxCorner(texelFetch(u.uTopNodes, 2 * index + 2)),
        boxCorner(texelFetch(u.uTopNodes, 2 * index + 3)), 0.0f, tBest, t1);
      if (walk.descend(static_cast<std::uint32_t>(index), h0, t0, h1, t1, cur))
      {
        continue;
      }
    }
    if (!walk.pop(tBest, cur))
    {
      return;
    }
  }
}

} // namespace vtkrt::core::gpu

#endif
