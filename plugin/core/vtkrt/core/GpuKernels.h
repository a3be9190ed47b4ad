// The C++ twins of the shader's kernels (shaders/vtkrtRayTraceKernels.glsl,
// vtkrtRayTraceTriangles.glsl, vtkrtRayTraceSpheres.glsl, vtkrtRayTraceTubes.glsl): each has the GLSL
// function's name, arguments and float operations in its order, so the CPU
// can compute what the GPU computes (TestCoreGpuTwins checks them against the
// double kernels). Where the shader runs a core kernel (slab, ray/plane clip,
// watertight triangle, stable sphere) the twin is that kernel in float; the
// box test of the traversals exists only here and in the shader.
// Change a twin and its GLSL function together. Compile without -ffast-math
// and, where FMA instructions are enabled, with -ffp-contract=off: the
// shader's float products and sums are rounded one by one.
#ifndef vtkrt_core_GpuKernels_h
#define vtkrt_core_GpuKernels_h

#include "vtkrt/core/Capsule.h"
#include "vtkrt/core/GpuLayout.h"
#include "vtkrt/core/Plane.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Sphere.h"
#include "vtkrt/core/Triangle.h"

namespace vtkrt::core::gpu
{

/// The 8-bit color channels of a word, lowest byte red (the buffers' RGBA8
/// colors and texels), each byte / 255 as GLSL's unpackUnorm4x8.
inline vec4 unpackRGBA8(std::uint32_t v)
{
  return vec4(static_cast<float>(v & 0xFFu), static_cast<float>((v >> 8) & 0xFFu),
           static_cast<float>((v >> 16) & 0xFFu), static_cast<float>((v >> 24) & 0xFFu)) /
    255.0f;
}

/// The far-distance scale of the conservative slab test (Ize 2013).
constexpr float kFarScale = 1.0f + 2.0f * gammaBound<float>(3);

inline float safeInverse(float d)
{
  return RayBoxPrecomputed<float>::safeInverse(d);
}

inline vec3 safeInverse(const vec3& d)
{
  return vec3(safeInverse(d.x), safeInverse(d.y), safeInverse(d.z));
}

inline bool clipSlab(float lo, float hi, float org, float invDir, float& tmin, float& tmax)
{
  return core::detail::clipSlab(lo, hi, org, invDir, tmin, tmax);
}

/// The shader writes tnear on every path (a GLSL out parameter).
inline bool intersectRayAABB(const vec3& org, const vec3& invDir, const vec3& bmin, const vec3& bmax,
  float tmin, float tmax, float& tnear)
{
  tnear = tmin;
  return core::intersectRayAABB(org, invDir, bmin, bmax, tmin, tmax, tnear);
}

/// The parallelBias of intersectRayBoxConservative for a ray's invDir:
/// 3e38 on the axes the ray is parallel to (invDir 0), 0 elsewhere.
inline vec3 parallelAxisBias(const vec3& invDir)
{
  return vec3(glm::equal(invDir, vec3(0.0f))) * 3.0e38f;
}

/// The slab test of intersectRayAABB without its per-axis branches (the
/// shader's SIMD groups would run both sides of each): the same arithmetic
/// and result on every axis the ray is not parallel to. On a parallel axis
/// (invDir 0, parallelBias 3e38) the origin decides, as in clipSlab: inside
/// the closed slab the axis bounds nothing; outside it, tnear becomes
/// parallelBias, past every tfar of the ray's other axes. Testing
/// the origin matters: a parallel projection along an axis makes every
/// camera ray parallel to two axes, and a walk that accepted every box on
/// them would visit most of the tree. Needs tmin >= 0. glm's min and max
/// are GLSL's (y < x ? y : x, x < y ? y : x).
inline bool intersectRayBoxConservative(const vec3& org, const vec3& invDir, const vec3& parallelBias,
  const vec3& bmin, const vec3& bmax, float tmin, float tmax, float& tnear)
{
  const vec3 d0 = bmin - org;
  const vec3 d1 = bmax - org;
  const vec3 t0 = d0 * invDir;
  const vec3 t1 = d1 * invDir;
  const vec3 outside = glm::max(glm::max(d0, -d1), vec3(0.0f));
  const vec3 tn = glm::min(t0, t1) + glm::sign(outside) * parallelBias;
  const vec3 tf = glm::max(t0, t1) * kFarScale + parallelBias;
  tnear = glm::max(glm::max(tn.x, tn.y), glm::max(tn.z, tmin));
  const float tfar = glm::min(glm::min(tf.x, tf.y), glm::min(tf.z, tmax));
  return tnear <= tfar;
}

/// A point through the rows of an affine map (an instance's camera-to-local
/// rows, an ellipsoid's world-to-unit rows): each row's dot product, then
/// its translation.
inline vec3 rowsPoint(const vec4& r0, const vec4& r1, const vec4& r2, const vec3& p)
{
  return vec3(glm::dot(vec3(r0), p) + r0.w, glm::dot(vec3(r1), p) + r1.w, glm::dot(vec3(r2), p) + r2.w);
}

/// A direction through the same rows: no translation.
inline vec3 rowsDir(const vec4& r0, const vec4& r1, const vec4& r2, const vec3& d)
{
  return vec3(glm::dot(vec3(r0), d), glm::dot(vec3(r1), d), glm::dot(vec3(r2), d));
}

/// The normalized device depth of a camera ray's point at t, from the
/// frame's rayDepth: (x + t y) / (z + t w), clip z over clip w along the ray
/// (affine rays only; the pass's CameraFrame::RayDepth).
inline float affineRayDepth(const vec4& rayDepth, float t)
{
  return (rayDepth.x + t * rayDepth.y) / (rayDepth.z + t * rayDepth.w);
}

/// affineRayDepth inverted: the t at which the camera ray's normalized
/// device depth is ndcDepth.
inline float affineRayT(const vec4& rayDepth, float ndcDepth)
{
  return (rayDepth.x - ndcDepth * rayDepth.z) / (ndcDepth * rayDepth.w - rayDepth.y);
}

/// The t at which the camera ray (org, dir) through ndc reaches normalized
/// device depth ndcDepth, for a camera with any projective clipToCamera
/// matrix: the unprojected point's position along the ray.
inline float projectiveRayT(const glm::mat4& clipToCamera, const vec2& ndc, float ndcDepth, const vec3& org, const vec3& dir)
{
  const vec4 p = clipToCamera * vec4(ndc, ndcDepth, 1.0f);
  return glm::dot(vec3(p) / p.w - org, dir) / glm::dot(dir, dir);
}

inline bool clipRayByPlane(const vec3& org, const vec3& dir, const vec4& plane, float& tmin, float& tmax)
{
  return core::clipRayByPlane(org, dir, plane, tmin, tmax);
}

/// The watertight test's per-ray data: the shader's struct holds the same
/// axes and shear.
using RayTrianglePrecomputed = core::RayTrianglePrecomputed<float>;

inline RayTrianglePrecomputed precomputeRayTriangle(const vec3& org, const vec3& dir)
{
  return RayTrianglePrecomputed(Ray<float>(org, dir));
}

/// hit = (t, u, v), zero on a miss. The shader recomputes a zero edge
/// function in double only where it has fp64 (VTKRT_HAS_FP64): the twin
/// always does, as core's float test does.
inline bool intersectRayTriangle(const RayTrianglePrecomputed& r, const vec3& v0, const vec3& v1,
  const vec3& v2, float tmin, float tmax, vec3& hit)
{
  hit = vec3(0.0f);
  TriangleHit<float> h;
  if (!core::intersectRayTriangle(r, v0, v1, v2, tmin, tmax, h))
  {
    return false;
  }
  hit = vec3(h.t, h.u, h.v);
  return true;
}

/// roots = (t0, t1), t0 <= t1; zero when the line misses.
inline bool raySphereRoots(const vec3& org, const vec3& dir, const vec3& center, float radius, vec2& roots)
{
  roots = vec2(0.0f);
  SphereRoots<float> r;
  if (!core::raySphereRoots(org, dir, center, radius, r))
  {
    return false;
  }
  roots = vec2(r.t0, r.t1);
  return true;
}

inline bool intersectRaySphere(const vec3& org, const vec3& dir, const vec3& center, float radius,
  float tmin, float tmax, float& t)
{
  t = 0.0f;
  return core::intersectRaySphere(Ray<float>(org, dir, tmin, tmax), center, radius, t);
}

/// A tube piece (core::intersectRayTube in float): the hull of the spheres
/// (a, ra) and (b, rb).
inline bool intersectRayTube(const vec3& org, const vec3& dir, const vec3& a, const vec3& b, float ra,
  float rb, float tmin, float tmax, float& t)
{
  t = 0.0f;
  return core::intersectRayTube(Ray<float>(org, dir, tmin, tmax), a, b, ra, rb, t);
}

inline float tubeParameter(const vec3& p, const vec3& a, const vec3& b, float ra, float rb)
{
  return core::tubeParameter(p, a, b, ra, rb);
}

} // namespace vtkrt::core::gpu

#endif
