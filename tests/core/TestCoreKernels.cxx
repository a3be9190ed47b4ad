// Intersection kernels against analytic answers: ray/triangle (hits,
// misses, barycentrics, float == double), ray/sphere (both roots, tangent,
// tiny far sphere, origin inside), ray/plane (parallel), ray/AABB (zero
// direction components, conservative far bound), closest point on triangle
// (against dense sampling).
#include "CoreTestUtils.h"

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{

template <class T>
void testTriangle()
{
  using V = Vec3<T>;
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  TriangleHit<T> h;
  // Straight down onto (0.25, 0.5): t = 2, u = 0.25, v = 0.5.
  VTKRT_CHECK(intersectRayTriangle(Ray<T>(V(0.25, 0.5, 2), V(0, 0, -1)), a, b, c, h));
  VTKRT_CHECK_NEAR(h.t, 2, 1e-6);
  VTKRT_CHECK_NEAR(h.u, 0.25, 1e-6);
  VTKRT_CHECK_NEAR(h.v, 0.5, 1e-6);
  // From below (other winding) hits too; a non-unit direction scales t.
  VTKRT_CHECK(intersectRayTriangle(Ray<T>(V(0.25, 0.5, -3), V(0, 0, 2)), a, b, c, h));
  VTKRT_CHECK_NEAR(h.t, 1.5, 1e-6);
  // Outside the triangle, behind the origin, beyond tmax: misses.
  VTKRT_CHECK(!intersectRayTriangle(Ray<T>(V(0.75, 0.5, 2), V(0, 0, -1)), a, b, c, h));
  VTKRT_CHECK(!intersectRayTriangle(Ray<T>(V(0.25, 0.5, 2), V(0, 0, 1)), a, b, c, h));
  VTKRT_CHECK(!intersectRayTriangle(Ray<T>(V(0.25, 0.5, 2), V(0, 0, -1), T(0), T(1.5)), a, b, c, h));
  // Exactly on an edge and on a vertex: hit (closed intervals).
  VTKRT_CHECK(intersectRayTriangle(Ray<T>(V(0.5, 0.5, 1), V(0, 0, -1)), a, b, c, h));
  VTKRT_CHECK(intersectRayTriangle(Ray<T>(V(0, 0, 1), V(0, 0, -1)), a, b, c, h));
  VTKRT_CHECK_NEAR(h.u, 0, 0);
  VTKRT_CHECK_NEAR(h.v, 0, 0);
  // Degenerate triangle never hits; parallel ray in the plane misses.
  VTKRT_CHECK(!intersectRayTriangle(Ray<T>(V(0.5, 0, 1), V(0, 0, -1)), a, b, V(2, 0, 0), h));
  VTKRT_CHECK(!intersectRayTriangle(Ray<T>(V(-1, 0.25, 0), V(1, 0, 0)), a, b, c, h));
  // Segment semantics: p1 -> p2 with t in [0, 1].
  VTKRT_CHECK(intersectRayTriangle(Ray<T>(V(0.1, 0.1, 1), V(0, 0, -2), T(0), T(1)), a, b, c, h));
  VTKRT_CHECK_NEAR(h.t, 0.5, 1e-6);
}

void testTriangleRandomAgainstPlane()
{
  // Random rays through random triangles: the hit point lies on the plane and
  // reproduces from the barycentrics; float agrees with double on clear cases.
  Rng rng(7);
  int checked = 0;
  for (int i = 0; i < 20000; ++i)
  {
    const Vec3<double> a = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const Vec3<double> b = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const Vec3<double> c = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const double u = rng.uniform(-0.2, 1.0), v = rng.uniform(-0.2, 1.0);
    const Vec3<double> target = (1 - u - v) * a + u * b + v * c;
    const Vec3<double> org = rng.inBox(Vec3<double>(-3), Vec3<double>(3));
    const Ray<double> ray(org, target - org);
    TriangleHit<double> h;
    const bool inside = u >= 0 && v >= 0 && u + v <= 1;
    const double margin = std::min({ u, v, 1 - u - v });
    const Vec3<double> n = glm::normalize(triangleNormal(a, b, c));
    if (std::abs(glm::dot(n, glm::normalize(ray.dir))) < 1e-3)
    {
      continue; // nearly edge-on: the expected answer is ill-conditioned
    }
    const bool hit = intersectRayTriangle(ray, a, b, c, h);
    if (std::abs(margin) > 1e-9)
    {
      VTKRT_CHECK(hit == inside);
    }
    if (hit && inside)
    {
      ++checked;
      VTKRT_CHECK_NEAR(h.t, 1.0, 1e-9);
      VTKRT_CHECK_NEAR(h.u, u, 1e-8);
      VTKRT_CHECK_NEAR(h.v, v, 1e-8);
      const Vec3<double> p = (1 - h.u - h.v) * a + h.u * b + h.v * c;
      VTKRT_CHECK(glm::length(p - ray.at(h.t)) < 1e-9);
      if (margin > 1e-3)
      {
        TriangleHit<float> hf{};
        VTKRT_CHECK(intersectRayTriangle(Ray<float>(Vec3<float>(org), Vec3<float>(target - org)),
          Vec3<float>(a), Vec3<float>(b), Vec3<float>(c), hf));
        VTKRT_CHECK_NEAR(hf.t, 1.0, 1e-3);
      }
    }
  }
  VTKRT_CHECK(checked > 3000);
}

template <class T>
void testSphere()
{
  using V = Vec3<T>;
  T t;
  SphereRoots<T> roots;
  // Both roots of a unit sphere seen from x = -5.
  VTKRT_CHECK(raySphereRoots(V(-5, 0, 0), V(1, 0, 0), V(0, 0, 0), T(1), roots));
  VTKRT_CHECK_NEAR(roots.t0, 4, 1e-6);
  VTKRT_CHECK_NEAR(roots.t1, 6, 1e-6);
  // Same with a non-unit direction and from the other side.
  VTKRT_CHECK(raySphereRoots(V(5, 0, 0), V(-2, 0, 0), V(0, 0, 0), T(1), roots));
  VTKRT_CHECK_NEAR(roots.t0, 2, 1e-6);
  VTKRT_CHECK_NEAR(roots.t1, 3, 1e-6);
  // Origin inside: the nearest root in range is the exit.
  VTKRT_CHECK(intersectRaySphere(Ray<T>(V(0, 0, 0), V(0, 0, 1)), V(0, 0, 0), T(2), t));
  VTKRT_CHECK_NEAR(t, 2, 1e-6);
  // Tangent: touches y = 1 exactly (double root), and a hair outside misses.
  VTKRT_CHECK(raySphereRoots(V(-5, 1, 0), V(1, 0, 0), V(0, 0, 0), T(1), roots));
  VTKRT_CHECK_NEAR(roots.t0, 5, 1e-3);
  VTKRT_CHECK_NEAR(roots.t1, 5, 1e-3);
  VTKRT_CHECK(!raySphereRoots(V(-5, T(1.0001), 0), V(1, 0, 0), V(0, 0, 0), T(1), roots));
  // Behind the ray: no hit in [0, inf).
  VTKRT_CHECK(!intersectRaySphere(Ray<T>(V(5, 0, 0), V(1, 0, 0)), V(0, 0, 0), T(1), t));
  // Normal.
  const V n = sphereNormal(V(0, 0, 3), V(0, 0, 1));
  VTKRT_CHECK_NEAR(n.z, 1, 1e-6);

  // A sphere of radius 1e-6 seen from 1e6 away. The textbook discriminant
  // b'^2 - a c cancels to 0 here (c = 1e12 - 1e-12 rounds to 1e12) and would
  // report a (tangent) hit for every offset; the stable form resolves
  // offsets of a fraction of the radius.
  const T r = T(1e-6);
  const V org(T(1e6), 0, 0);
  VTKRT_CHECK(intersectRaySphere(Ray<T>(org, V(-1, 0, 0)), V(0, 0, 0), r, t));
  VTKRT_CHECK_NEAR(t, 1e6 - 1e-6, 1e6 * 1e-7);
  VTKRT_CHECK(intersectRaySphere(Ray<T>(org, V(-1, T(0.5e-12), 0)), V(0, 0, 0), r, t)); // passes 0.5 r off
  VTKRT_CHECK(!intersectRaySphere(Ray<T>(org, V(-1, T(1.5e-12), 0)), V(0, 0, 0), r, t)); // 1.5 r off
  VTKRT_CHECK(!intersectRaySphere(Ray<T>(org, V(-1, 0, T(-2e-12))), V(0, 0, 0), r, t));
}

void testSmallFarSphereDouble()
{
  // Random directions in double: a ray aimed at offset o from the center of
  // a 1e-6 sphere 1e6 away hits exactly when |o| < r (margin 1 %).
  Rng rng(11);
  const double r = 1e-6;
  int hits = 0, misses = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const Vec3<double> center = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const Vec3<double> org = center + 1e6 * rng.unitVector();
    Vec3<double> off = rng.unitVector();
    const Vec3<double> viewDir = glm::normalize(center - org);
    off = glm::normalize(off - glm::dot(off, viewDir) * viewDir) * (r * rng.uniform(0, 2));
    const double offLen = glm::length(off);
    if (std::abs(offLen - r) < 0.01 * r)
    {
      continue;
    }
    double t;
    const bool hit = intersectRaySphere(Ray<double>(org, center + off - org), center, r, t);
    VTKRT_CHECK(hit == (offLen < r));
    (hit ? hits : misses)++;
    if (hit)
    {
      VTKRT_CHECK_NEAR(t, 1.0 - std::sqrt(r * r - offLen * offLen) / 1e6, 1e-12);
    }
  }
  VTKRT_CHECK(hits > 500 && misses > 500);
}

template <class T>
void testPlane()
{
  using V = Vec3<T>;
  const Plane<T> plane{ V(0, 0, 1), V(0, 0, 2) };
  T t = T(-1);
  VTKRT_CHECK(intersectRayPlane(Ray<T>(V(3, 4, 5), V(0, 0, -1)), plane, t) == PlaneHit::Hit);
  VTKRT_CHECK_NEAR(t, 4, 1e-6);
  t = T(-1);
  VTKRT_CHECK(intersectRayPlane(Ray<T>(V(3, 4, 5), V(1, 1, 0)), plane, t) == PlaneHit::Parallel);
  VTKRT_CHECK(intersectRayPlane(Ray<T>(V(3, 4, 1), V(1, 0, 0)), plane, t) == PlaneHit::Parallel);
  VTKRT_CHECK(t == T(-1)); // untouched
  VTKRT_CHECK(intersectRayPlane(Ray<T>(V(3, 4, 5), V(0, 0, 1)), plane, t) == PlaneHit::Miss);
  // Nearly parallel: a huge t outside the segment.
  VTKRT_CHECK(intersectRayPlane(Ray<T>(V(0, 0, 5), V(1, 0, T(-1e-30)), T(0), T(1e6)), plane, t) ==
    PlaneHit::Miss);
}

template <class T>
void testAABB()
{
  using V = Vec3<T>;
  const AABB<T> box(V(0, 0, 0), V(1, 1, 1));
  T tn;
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 0.5, 0.5), V(1, 0, 0)), box, tn));
  VTKRT_CHECK_NEAR(tn, 1, 1e-6);
  // Zero direction components: origin inside the slab, outside, exactly on
  // the slab planes (0 * inf = NaN must not make a hit a miss), -0.
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 0.5, 0.5), V(1, 0, 0)), box, tn));
  VTKRT_CHECK(!intersectRayAABB(Ray<T>(V(-1, 1.5, 0.5), V(1, 0, 0)), box, tn));
  VTKRT_CHECK(!intersectRayAABB(Ray<T>(V(-1, -0.5, 0.5), V(1, 0, 0)), box, tn));
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 0, 0), V(1, 0, 0)), box, tn));
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 1, 1), V(1, 0, 0)), box, tn));
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 1, 1), V(1, T(-0.0), T(-0.0))), box, tn));
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(0.5, 0.5, 0.5), V(0, 0, -1)), box, tn)); // inside
  VTKRT_CHECK(tn == T(0));
  VTKRT_CHECK(!intersectRayAABB(Ray<T>(V(-1, 0.5, 0.5), V(-1, 0, 0)), box, tn)); // behind
  VTKRT_CHECK(!intersectRayAABB(Ray<T>(V(-1, 0.5, 0.5), V(1, 0, 0), T(0), T(0.5)), box, tn));
  // A flat box (zero thickness) hit head-on and along its plane.
  const AABB<T> flat(V(0, 0, 1), V(1, 1, 1));
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(0.5, 0.5, 3), V(0, 0, -1)), flat, tn));
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 0.5, 1), V(1, 0, 0)), flat, tn));
  // Conservative: a segment ending exactly on the box face still hits.
  VTKRT_CHECK(intersectRayAABB(Ray<T>(V(-1, 0.3, 0.7), V(1, 0, 0), T(0), T(1)), box, tn));
  // Random rays through random points of random boxes always hit.
  Rng rng(3);
  for (int i = 0; i < 20000; ++i)
  {
    const Vec3<double> lo = rng.inBox(Vec3<double>(-10), Vec3<double>(10));
    const Vec3<double> hi = lo + rng.inBox(Vec3<double>(0), Vec3<double>(1e-3));
    const Vec3<double> p = rng.inBox(lo, hi);
    const Vec3<double> o = rng.inBox(Vec3<double>(-100), Vec3<double>(100));
    const Ray<T> ray(V(o), V(p) - V(o));
    VTKRT_CHECK(intersectRayAABB(ray, AABB<T>(V(lo), V(hi)), tn));
  }
}

void testClosestPointOnTriangle()
{
  // Against a dense barycentric sampling (the sampled minimum can only be
  // farther than the exact one, and not by more than the sampling step).
  Rng rng(5);
  for (int i = 0; i < 300; ++i)
  {
    const Vec3<double> a = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const Vec3<double> b = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const Vec3<double> c = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    const Vec3<double> p = rng.inBox(Vec3<double>(-2), Vec3<double>(2));
    double u, v;
    const Vec3<double> q = closestPointOnTriangle(p, a, b, c, u, v);
    VTKRT_CHECK(u >= -1e-12 && v >= -1e-12 && u + v <= 1 + 1e-12);
    VTKRT_CHECK(glm::length(q - ((1 - u - v) * a + u * b + v * c)) < 1e-9);
    const double exact = glm::length(q - p);
    double sampled = 1e300;
    const int n = 200;
    for (int s = 0; s <= n; ++s)
    {
      for (int t = 0; s + t <= n; ++t)
      {
        const Vec3<double> x = a + (double(s) / n) * (b - a) + (double(t) / n) * (c - a);
        sampled = std::min(sampled, glm::length(x - p));
      }
    }
    const double step = std::max({ glm::length(b - a), glm::length(c - a), glm::length(c - b) }) / n;
    VTKRT_CHECK(exact <= sampled + 1e-12);
    VTKRT_CHECK(sampled <= exact + step);
  }
  // Each Voronoi region by construction.
  const Vec3<double> a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  VTKRT_CHECK(closestPointOnTriangle(Vec3<double>(-1, -1, 5), a, b, c) == a);
  VTKRT_CHECK(closestPointOnTriangle(Vec3<double>(2, -1, 5), a, b, c) == b);
  VTKRT_CHECK(closestPointOnTriangle(Vec3<double>(-1, 2, 5), a, b, c) == c);
  VTKRT_CHECK(closestPointOnTriangle(Vec3<double>(0.5, -1, 5), a, b, c) == Vec3<double>(0.5, 0, 0));
  VTKRT_CHECK(closestPointOnTriangle(Vec3<double>(-1, 0.5, 5), a, b, c) == Vec3<double>(0, 0.5, 0));
  VTKRT_CHECK(glm::length(closestPointOnTriangle(Vec3<double>(1, 1, 5), a, b, c) - Vec3<double>(0.5, 0.5, 0)) < 1e-15);
  VTKRT_CHECK(closestPointOnTriangle(Vec3<double>(0.25, 0.25, 5), a, b, c) == Vec3<double>(0.25, 0.25, 0));
}

void testGpuPacking()
{
  // Outward rounding: every packed float box contains its double box.
  BVHNode n;
  n.min = Vec3<double>(0.1, -1e8 + 0.3, 1.0 / 3.0);
  n.max = Vec3<double>(0.2, -1e8 + 0.7, 2.0 / 3.0);
  n.index = 12345;
  n.count = 3;
  const std::vector<BVHNode> nodes{ n };
  for (const Vec3<double>& origin : { Vec3<double>(0.0), Vec3<double>(0.15, -1e8 + 0.5, 0.4) })
  {
    const std::vector<float> p = packNodesForGpu(nodes, origin);
    VTKRT_CHECK(p.size() == 8);
    for (int k = 0; k < 3; ++k)
    {
      VTKRT_CHECK(double(p[k]) <= n.min[k] - origin[k]);
      VTKRT_CHECK(double(p[4 + k]) >= n.max[k] - origin[k]);
    }
    VTKRT_CHECK(floatBitsToUint(p[3]) == 12345u);
    VTKRT_CHECK(floatBitsToUint(p[7]) == 3u);
  }
  VTKRT_CHECK(roundDownToFloat(0.1) <= 0.1 && roundUpToFloat(0.1) >= 0.1);
  VTKRT_CHECK(roundDownToFloat(0.5) == 0.5f && roundUpToFloat(0.5) == 0.5f);
}

} // namespace

int main()
{
  testTriangle<float>();
  testTriangle<double>();
  testTriangleRandomAgainstPlane();
  testSphere<float>();
  testSphere<double>();
  testSmallFarSphereDouble();
  testPlane<float>();
  testPlane<double>();
  testAABB<float>();
  testAABB<double>();
  testClosestPointOnTriangle();
  testGpuPacking();
  return testResult("TestCoreKernels");
}
