// The shader's C++ kernel twins (core/GpuKernels.h, core/GpuEdgeKernels.h)
// against the double core: the generated layout constants; the branch-free
// box test never rejects a box the double slab test hits and equals the
// float slab test off the parallel axes (and a box test without the far
// scale is caught); the plane clip agrees with the double clip and
// crossing; the primitive kernels' hits; the edge kernels measure pixels as
// double does (GpuEdgeTwinChecks.h). The walks: TestCoreGpuTwins.
#include "CoreTestUtils.h"
#include "GpuEdgeTwinChecks.h"
#include "GpuTwinTestUtils.h"

#include "vtkrt/core/GpuTraversal.h"

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{
bool parallelToAnAxis(const vec3& d)
{
  return d.x == 0.0f || d.y == 0.0f || d.z == 0.0f;
}

void testConstants()
{
  VTKRT_CHECK(gpu::kFarScale == 1.0f + 2.0f * (3.0f * 5.9604645e-8f) / (1.0f - 3.0f * 5.9604645e-8f));
  VTKRT_CHECK(gpu::kFarScale > 1.0f);
  VTKRT_CHECK(gpu::safeInverse(2.0f) == 0.5f);
  VTKRT_CHECK(gpu::safeInverse(0.0f) == 0.0f && gpu::safeInverse(-0.0f) == 0.0f);
  VTKRT_CHECK(gpu::safeInverse(1e-40f) == 0.0f); // subnormal: inverse overflows
  const vec3 bias = gpu::parallelAxisBias(gpu::safeInverse(vec3(0.0f, 2.0f, -0.0f)));
  VTKRT_CHECK(bias == vec3(3.0e38f, 0.0f, 3.0e38f));
  // Entries 0..depth, a power of two, never above kMaxStackSize.
  VTKRT_CHECK(gpu::stackSizeForDepth(0) == 8 && gpu::stackSizeForDepth(7) == 8);
  VTKRT_CHECK(gpu::stackSizeForDepth(8) == 16 && gpu::stackSizeForDepth(31) == 32);
  VTKRT_CHECK(gpu::stackSizeForDepth(kMaxDepth) == kMaxStackSize);
  VTKRT_CHECK(gpu::stackSizeForDepth(kMaxDepth) > kMaxDepth);
}

/// The shader's box test without the far scale: what the conservative
/// check must catch.
bool boxTestWithoutFarScale(const vec3& org, const vec3& invDir, const vec3& bias, const vec3& bmin,
  const vec3& bmax, float tmin, float tmax, float& tnear)
{
  const vec3 t0 = (bmin - org) * invDir;
  const vec3 t1 = (bmax - org) * invDir;
  const vec3 tn = glm::min(t0, t1);
  const vec3 tf = glm::max(t0, t1) + bias;
  tnear = glm::max(glm::max(tn.x, tn.y), glm::max(tn.z, tmin));
  return tnear <= glm::min(glm::min(tf.x, tf.y), glm::min(tf.z, tmax));
}

void testBoxTest()
{
  Rng rng(11);
  int doubleHits = 0, missedByTwin = 0, missedByMutant = 0, grazing = 0, parallel = 0, parallelMissed = 0;
  for (int i = 0; i < 200000; ++i)
  {
    const vec3 a = toFloat(rng.inBox(Vec3<double>(-2), Vec3<double>(2)));
    const vec3 b = toFloat(rng.inBox(Vec3<double>(-2), Vec3<double>(2)));
    const vec3 lo = glm::min(a, b);
    vec3 hi = glm::max(a, b);
    if (i % 7 == 0)
    {
      const int flat = int(rng.index(3));
      hi[flat] = lo[flat];
    }
    // Aim at a corner, an edge or a face (grazing: 3, 2 or 1 coordinates on
    // the box's planes), or anywhere near.
    Vec3<double> target = rng.inBox(Vec3<double>(lo), Vec3<double>(hi));
    const int onPlanes = 3 - i % 4;
    const int skip = int(rng.index(3));
    for (int k = 0; k < onPlanes; ++k)
    {
      const int axis = (skip + k) % 3;
      target[axis] = rng.uniform() < 0.5 ? lo[axis] : hi[axis];
    }
    if (onPlanes == 0)
    {
      target += rng.unitVector() * 0.5;
    }
    grazing += onPlanes > 0;
    const Vec3<double> from = target + 3.0 * rng.unitVector();
    const vec3 org = toFloat(from);
    const vec3 dir = randomDirection(rng, target - from);
    if (dir == vec3(0.0f))
    {
      continue;
    }
    const float tmax = i % 5 == 0 ? 1.0f : 1e30f;
    const vec3 invDir = gpu::safeInverse(dir);
    const vec3 bias = gpu::parallelAxisBias(invDir);
    float tTwin, tMutant, tCore;
    const bool twin = gpu::intersectRayBoxConservative(org, invDir, bias, lo, hi, 0.0f, tmax, tTwin);
    const bool mutant = boxTestWithoutFarScale(org, invDir, bias, lo, hi, 0.0f, tmax, tMutant);
    const bool core = gpu::intersectRayAABB(org, invDir, lo, hi, 0.0f, tmax, tCore);
    double tDouble;
    const bool exact = intersectRayAABB(Ray<double>(Vec3<double>(org), Vec3<double>(dir), 0.0, double(tmax)),
      AABB<double>(Vec3<double>(lo), Vec3<double>(hi)), tDouble);
    doubleHits += exact;
    missedByTwin += exact && !twin;
    missedByMutant += exact && !mutant;
    if (parallelToAnAxis(dir))
    {
      // The origin decides a parallel axis, as the core's.
      ++parallel;
      parallelMissed += !core;
      VTKRT_CHECK(twin == core);
      VTKRT_CHECK(!twin || tTwin == tCore);
    }
    else
    {
      VTKRT_CHECK(twin == core);
      VTKRT_CHECK(!twin || tTwin == tCore);
    }
  }
  VTKRT_CHECK_MSG(missedByTwin == 0, "%d of %d boxes hit in double rejected", missedByTwin, doubleHits);
  VTKRT_CHECK_MSG(missedByMutant > 0, "grazing rays never needed the far scale");
  VTKRT_CHECK(doubleHits > 50000 && grazing > 100000 && parallel > 20000 && parallelMissed > 5000);
}

void testPlaneClip()
{
  Rng rng(13);
  int crossings = 0, parallels = 0;
  for (int i = 0; i < 50000; ++i)
  {
    vec3 n = toFloat(rng.unitVector() * rng.uniform(0.5, 2.0));
    const Vec3<double> point = rng.inBox(Vec3<double>(-3), Vec3<double>(3));
    const vec3 org = toFloat(rng.inBox(Vec3<double>(-4), Vec3<double>(4)));
    vec3 dir = toFloat(rng.unitVector() * rng.uniform(0.1, 10.0));
    if (i % 10 == 0)
    {
      dir = glm::cross(n, dir); // nearly parallel to the plane
    }
    else if (i % 10 == 1)
    {
      const int axis = maxAbsDimension(n); // an axis-aligned plane, dir exactly parallel
      dir[axis] = 0.0f;
      n = vec3(0.0f);
      n[axis] = 1.5f;
    }
    const Vec3<double> nd(n);
    const vec4 plane(n, float(-glm::dot(nd, point)));
    const float t0 = i % 3 == 0 ? 0.0f : float(rng.uniform(-1, 1));
    const float t1 = i % 4 == 0 ? 1e30f : t0 + float(rng.uniform(0, 5));
    float tmin = t0, tmax = t1;
    const bool kept = gpu::clipRayByPlane(org, dir, plane, tmin, tmax);
    // The same clip in double on the same (exact) input.
    double dmin = t0, dmax = t1;
    const bool dkept =
      clipRayByPlane(Vec3<double>(org), Vec3<double>(dir), PlaneEquation<double>(plane), dmin, dmax);
    const double denom = glm::dot(Vec3<double>(n), Vec3<double>(dir));
    if (glm::dot(n, dir) == 0.0f)
    {
      ++parallels;
      const double side = glm::dot(Vec3<double>(n), Vec3<double>(org)) + double(plane.w);
      if (std::abs(side) > 1e-5)
      {
        VTKRT_CHECK(kept == (side >= 0));
        VTKRT_CHECK(tmin == t0 && tmax == t1);
      }
      continue;
    }
    // The crossing of the point-normal plane (the crossing query).
    double tc = 0.0;
    const Ray<double> ray(Vec3<double>(org), Vec3<double>(dir), -1e300, 1e300);
    if (intersectRayPlane(ray, Plane<double>{ point, nd }, tc) != PlaneHit::Hit || std::abs(denom) < 1e-3)
    {
      continue;
    }
    ++crossings;
    const double tol = 1e-4 * (1.0 + std::abs(tc)) + 1e-5 / std::abs(denom);
    const double moved = denom > 0 ? double(tmin) : double(tmax);
    if (moved != double(denom > 0 ? t0 : t1))
    {
      VTKRT_CHECK_NEAR(moved, tc, tol);
    }
    VTKRT_CHECK_NEAR(denom > 0 ? dmin : dmax, denom > 0 ? tmin : tmax, tol);
    if (std::abs(tc - t0) > tol && std::abs(tc - t1) > tol)
    {
      VTKRT_CHECK(kept == dkept);
      VTKRT_CHECK(kept == (denom > 0 ? tc <= t1 : tc >= t0));
    }
  }
  VTKRT_CHECK(crossings > 30000 && parallels > 1000);
}

void testPrimitiveKernels()
{
  // An affine map's rows: rowsPoint is M p + b, rowsDir is M d (no b), each
  // within float rounding of the double product.
  {
    Rng rows(29);
    for (int i = 0; i < 1000; ++i)
    {
      vec4 r[3];
      for (vec4& row : r)
      {
        row = vec4(toFloat(rows.inBox(Vec3<double>(-2), Vec3<double>(2))), float(rows.uniform(-5.0, 5.0)));
      }
      const vec3 p = toFloat(rows.inBox(Vec3<double>(-3), Vec3<double>(3)));
      const vec3 mp = gpu::rowsPoint(r[0], r[1], r[2], p);
      const vec3 md = gpu::rowsDir(r[0], r[1], r[2], p);
      for (int k = 0; k < 3; ++k)
      {
        const double dot = double(r[k].x) * p.x + double(r[k].y) * p.y + double(r[k].z) * p.z;
        VTKRT_CHECK_NEAR(md[k], dot, 1e-5 * (1.0 + std::abs(dot)) + 1e-5);
        VTKRT_CHECK_NEAR(mp[k], dot + r[k].w, 1e-5 * (1.0 + std::abs(dot + r[k].w)) + 1e-5);
      }
    }
  }

  // Sphere roots in float against double; the tangent ray; a ray along an
  // axis through the center plane (b' = -0).
  Rng rng(17);
  for (int i = 0; i < 20000; ++i)
  {
    const vec3 center = toFloat(rng.inBox(Vec3<double>(-1), Vec3<double>(1)));
    const float radius = float(rng.uniform(0.05, 1.0));
    const vec3 org = toFloat(rng.inBox(Vec3<double>(-4), Vec3<double>(4)));
    const vec3 dir = toFloat(Vec3<double>(center) + 0.9 * radius * rng.unitVector() - Vec3<double>(org));
    vec2 roots;
    SphereRoots<double> d{ 0.0, 0.0 };
    VTKRT_CHECK(gpu::raySphereRoots(org, dir, center, radius, roots));
    VTKRT_CHECK(raySphereRoots(Vec3<double>(org), Vec3<double>(dir), Vec3<double>(center), double(radius), d));
    VTKRT_CHECK(roots.x <= roots.y);
    VTKRT_CHECK_NEAR(roots.x, d.t0, 1e-4 * (1 + std::abs(d.t0)));
    VTKRT_CHECK_NEAR(roots.y, d.t1, 1e-4 * (1 + std::abs(d.t1)));
  }
  vec2 roots;
  VTKRT_CHECK(gpu::raySphereRoots(vec3(-1.0f, 0.0f, -3.0f), vec3(0, 0, 1), vec3(0.0f), 1.0f, roots));
  VTKRT_CHECK(roots.x == roots.y && std::abs(roots.x - 3.0f) < 1e-3f);
  VTKRT_CHECK(gpu::raySphereRoots(vec3(-0.5f, -0.5f, 0.0f), vec3(0, 0, -1), vec3(0.0f), 1.0f, roots));
  VTKRT_CHECK(std::abs(roots.x + std::sqrt(0.5f)) < 1e-6f && std::abs(roots.y - std::sqrt(0.5f)) < 1e-6f);
  float t;
  VTKRT_CHECK(gpu::intersectRaySphere(vec3(0.0f), vec3(1, 0, 0), vec3(0.0f), 2.0f, 0.0f, 10.0f, t) && t == 2.0f);
  VTKRT_CHECK(!gpu::intersectRaySphere(vec3(0.0f), vec3(1, 0, 0), vec3(5, 0, 0), 1.0f, 0.0f, 3.0f, t) && t == 0.0f);
  // The triangle test: hit (t, u, v), a miss zeroes it.
  const gpu::RayTrianglePrecomputed pre = gpu::precomputeRayTriangle(vec3(0.25f, 0.5f, 2.0f), vec3(0, 0, -1));
  vec3 hit;
  VTKRT_CHECK(gpu::intersectRayTriangle(pre, vec3(0.0f), vec3(1, 0, 0), vec3(0, 1, 0), 0.0f, 10.0f, hit));
  VTKRT_CHECK(hit == vec3(2.0f, 0.25f, 0.5f));
  VTKRT_CHECK(!gpu::intersectRayTriangle(pre, vec3(0.0f), vec3(1, 0, 0), vec3(0, 1, 0), 0.0f, 1.0f, hit));
  VTKRT_CHECK(hit == vec3(0.0f));
}

// unpackRGBA8: red in the lowest byte, each byte b as b / 255 (GLSL's
// unpackUnorm4x8), so 0 and 255 are exactly 0 and 1 and every byte comes back.
void testColorUnpack()
{
  for (std::uint32_t b = 0; b < 256; ++b)
  {
    const std::uint32_t word = b | ((255u - b) << 8) | (((b * 7u) & 0xFFu) << 16) | (((b * 13u + 5u) & 0xFFu) << 24);
    const vec4 c = gpu::unpackRGBA8(word);
    const std::uint32_t bytes[4] = { b, 255u - b, (b * 7u) & 0xFFu, (b * 13u + 5u) & 0xFFu };
    for (int k = 0; k < 4; ++k)
    {
      VTKRT_CHECK(c[k] == static_cast<float>(bytes[k]) / 255.0f);
      VTKRT_CHECK(static_cast<std::uint32_t>(std::lround(c[k] * 255.0f)) == bytes[k]);
    }
  }
  VTKRT_CHECK(gpu::unpackRGBA8(0xFF0000FFu) == vec4(1.0f, 0.0f, 0.0f, 1.0f));
}
} // namespace

int main()
{
  testConstants();
  testBoxTest();
  testPlaneClip();
  testPrimitiveKernels();
  testEdgeKernels();
  testColorUnpack();
  return testResult("TestCoreGpuKernelTwins");
}
