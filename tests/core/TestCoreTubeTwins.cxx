// The tube-piece kernel (core/Capsule.h) and its shader twin
// (gpu::intersectRayTube, the float operations of vtkrtRayTraceTubes.glsl):
// the double kernel against a brute-force answer (sphere tracing the exact
// distance to the union of the spheres swept along the segment, found by a
// ternary search over the convex distance along it), the float twin against
// the double kernel, and the surface parameter (the normal's sphere) at hits.
// Capsules (equal radii), round cones (the radii of a perspective tube),
// zero-length segments and rays from far away.
#include "CoreTestUtils.h"

#include "vtkrt/core/GpuKernels.h"

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{
using gpu::vec3;

struct Piece
{
  Vec3<double> a, b;
  double ra, rb;

  Vec3<double> center(double s) const { return a + s * (b - a); }
  double radius(double s) const { return ra + s * (rb - ra); }
  /// The distance from p to the swept solid (negative inside): a convex
  /// function of s, minimized by a ternary search.
  double distance(const Vec3<double>& p) const
  {
    double lo = 0.0, hi = 1.0;
    const auto f = [&](double s) { return glm::length(p - center(s)) - radius(s); };
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i)
    {
      const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
      (f(m1) < f(m2) ? hi : lo) = f(m1) < f(m2) ? m2 : m1;
    }
    return std::min({ f(0.0), f(1.0), f(0.5 * (lo + hi)) });
  }
};

/// Sphere tracing: the first t in [0, tmax] where the ray enters the solid,
/// or -1; `nearest` is the smallest distance met on the way (a miss's margin).
double bruteForceHit(const Piece& piece, const Vec3<double>& org, const Vec3<double>& dir, double tmax,
  double& nearest)
{
  const double len = glm::length(dir);
  double t = 0.0;
  nearest = 1e300;
  for (int i = 0; i < 100000 && t <= tmax; ++i)
  {
    const double d = piece.distance(org + t * dir);
    nearest = std::min(nearest, d);
    if (d < 1e-12)
    {
      return t;
    }
    t += d / len;
  }
  return -1.0;
}

Piece randomPiece(Rng& rng, int kind)
{
  Piece p;
  p.a = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
  p.b = kind == 2 ? p.a : p.a + rng.uniform(0.05, 1.5) * rng.unitVector();
  p.ra = rng.uniform(0.01, 0.3);
  // 0: a capsule; 1: a round cone; 2: a zero-length segment (a sphere).
  p.rb = kind == 1 ? p.ra * rng.uniform(0.2, 3.0) : p.ra;
  // The float twin's input: the same values in float.
  p.a = Vec3<double>(vec3(p.a));
  p.b = Vec3<double>(vec3(p.b));
  p.ra = double(float(p.ra));
  p.rb = double(float(p.rb));
  return p;
}

void checkPieces(int kind, int count, double distance, std::uint64_t seed)
{
  Rng rng(seed);
  int hits = 0, misses = 0;
  for (int i = 0; i < count; ++i)
  {
    const Piece piece = randomPiece(rng, kind);
    // Aim at a point near the solid: inside it, or beside it.
    const double s = rng.uniform();
    const Vec3<double> target = piece.center(s) + rng.uniform(0.0, 2.5) * piece.radius(s) * rng.unitVector();
    const Vec3<double> org = Vec3<double>(vec3(target + distance * rng.unitVector()));
    const Vec3<double> dir = Vec3<double>(vec3((target - org) * rng.uniform(0.5, 2.0)));
    const double tmax = 4.0;
    double nearest;
    const double brute = bruteForceHit(piece, org, dir, tmax, nearest);
    double t = -1.0;
    const bool hit = intersectRayTube(Ray<double>(org, dir, 0.0, tmax), piece.a, piece.b, piece.ra, piece.rb, t);
    float ft = -1.0f;
    const bool fhit = gpu::intersectRayTube(vec3(org), vec3(dir), vec3(piece.a), vec3(piece.b),
      float(piece.ra), float(piece.rb), 0.0f, float(tmax), ft);
    // Float against double in clear cases only: the ray passes well inside
    // (its target) or well outside.
    const double scale = glm::length(dir) * std::max(1.0, distance);
    if (brute >= 0.0)
    {
      VTKRT_CHECK(hit);
      VTKRT_CHECK_NEAR(t, brute, 1e-7 * scale);
      if (piece.distance(target) < -0.05 * piece.ra)
      {
        ++hits;
        VTKRT_CHECK(fhit);
        VTKRT_CHECK_NEAR(ft, t, 2e-4 * std::max(1.0, distance));
      }
      // The hit lies on the sphere of its parameter: the normal's center.
      const Vec3<double> p = org + t * dir;
      const double u = tubeParameter(p, piece.a, piece.b, piece.ra, piece.rb);
      VTKRT_CHECK(u >= 0.0 && u <= 1.0);
      VTKRT_CHECK_NEAR(glm::length(p - piece.center(u)), piece.radius(u), 1e-6);
    }
    else if (nearest > 0.02 * piece.ra)
    {
      ++misses;
      VTKRT_CHECK(!hit);
      VTKRT_CHECK(!fhit);
    }
  }
  VTKRT_CHECK_MSG(hits > count / 5 && misses > count / 10, "%d hits, %d misses", hits, misses);
}

void checkEdgeCases()
{
  float t;
  // Along the axis into the end cap; across the middle; a parallel miss.
  VTKRT_CHECK(gpu::intersectRayTube(vec3(-3, 0, 0), vec3(1, 0, 0), vec3(0), vec3(1, 0, 0), 0.5f, 0.5f, 0.0f, 10.0f, t));
  VTKRT_CHECK_NEAR(t, 2.5f, 1e-6);
  VTKRT_CHECK(gpu::intersectRayTube(vec3(0.5f, 0, 4), vec3(0, 0, -1), vec3(0), vec3(1, 0, 0), 0.5f, 0.5f, 0.0f, 10.0f, t));
  VTKRT_CHECK_NEAR(t, 3.5f, 1e-6);
  VTKRT_CHECK(!gpu::intersectRayTube(vec3(-3, 0.6f, 0), vec3(1, 0, 0), vec3(0), vec3(1, 0, 0), 0.5f, 0.5f, 0.0f, 10.0f, t));
  VTKRT_CHECK(t == 0.0f);
  // A cone across the middle: radius 0.5 + 0.5 * (1.5 - 0.5) = 1 there,
  // widened by 1 / cos of its half-angle (sine (1.5 - 0.5) / 2) across the axis.
  VTKRT_CHECK(gpu::intersectRayTube(vec3(0, 0, 5), vec3(0, 0, -1), vec3(-1, 0, 0), vec3(1, 0, 0), 0.5f, 1.5f, 0.0f, 10.0f, t));
  VTKRT_CHECK_NEAR(t, 5.0f - 1.0f / std::sqrt(1.0f - 0.5f * 0.5f), 1e-5);
  // Radius 0 (a segment behind the eye): nothing but tangents.
  VTKRT_CHECK(!gpu::intersectRayTube(vec3(0.5f, 0.1f, 4), vec3(0, 0, -1), vec3(0), vec3(1, 0, 0), 0.0f, 0.0f, 0.0f, 10.0f, t));
  // tmin beyond the whole piece.
  VTKRT_CHECK(!gpu::intersectRayTube(vec3(0.5f, 0, 4), vec3(0, 0, -1), vec3(0), vec3(1, 0, 0), 0.5f, 0.5f, 5.0f, 10.0f, t));
}

} // namespace

int main()
{
  checkEdgeCases();
  checkPieces(0, 3000, 3.0, 31);
  checkPieces(1, 3000, 3.0, 32);
  checkPieces(2, 1000, 3.0, 33);
  checkPieces(1, 2000, 300.0, 34);
  return testResult("TestCoreTubeTwins");
}
