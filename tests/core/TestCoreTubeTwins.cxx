// The tube-piece kernel (core/Capsule.h) and its shader twin
// (gpu::intersectRayTube, the float operations of vtkrtRayTraceTubes.glsl):
// the double kernel against a brute-force answer (sphere tracing the exact
// distance to the union of the spheres swept along the segment, found by a
// ternary search over the convex distance along it), the float twin against
// the double kernel, and the surface parameter (the normal's sphere) at hits.
// Capsules (equal radii), round cones (the radii of a perspective tube),
// zero-length segments and rays from far away. Then the shader's walk
// (gpu::traverseTubes) over random polylines packed as the pass packs them,
// its BVH over the bare segments grown by the frame's largest radius,
// against every segment tested in turn: the growth never loses a hit.
#include "CoreTestUtils.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/GpuTraversal.h"

#include <array>
#include <cstring>

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

/// Random polylines, their BVH over bare segment boxes and the segments in
/// the sphere buffer (two texels each), walked with a perspective-like
/// radius plane and the grow bound the pass computes (the plane's largest
/// value over the corners of the segments' box).
void checkTubeWalk(int lines, int rayCount, std::uint64_t seed)
{
  Rng rng(seed);
  std::vector<std::array<Vec3<double>, 2>> segments;
  for (int l = 0; l < lines; ++l)
  {
    Vec3<double> p = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    for (int k = 0; k < 20; ++k)
    {
      const Vec3<double> q = p + 0.08 * rng.unitVector();
      segments.push_back({ { p, q } });
      p = q;
    }
  }
  std::vector<AABB<double>> boxes;
  for (const auto& s : segments)
  {
    AABB<double> box;
    box.extend(s[0]);
    box.extend(s[1]);
    boxes.push_back(box);
  }
  const BVH bvh = buildBVH(boxes);
  const Vec3<double> origin = bvh.bounds().center();
  std::vector<gpu::Node> gpuNodes = packGpuNodes(bvh.nodes, origin);
  for (gpu::Node& node : gpuNodes)
  {
    // Leaves index texels, as the pass's.
    node.index *= node.count > 0 ? gpu::kSegmentTexels : 1u;
  }
  std::vector<float> nodes(gpuNodes.size() * 8);
  std::memcpy(nodes.data(), gpuNodes.data(), nodes.size() * sizeof(float));
  std::vector<gpu::Segment> records;
  for (std::uint32_t s : bvh.primIndex)
  {
    records.push_back({ vec3(segments[s][0] - origin), s, vec3(segments[s][1] - origin), s });
  }
  std::vector<float> texels(records.size() * 8);
  std::memcpy(texels.data(), records.data(), texels.size() * sizeof(float));
  gpu::ShaderInputs u;
  u.uNodes = gpu::TexelBuffer(nodes);
  u.uSpheres = gpu::TexelBuffer(texels);
  // Radius growing with depth along -z from an eye at z = 4 (local units).
  const gpu::vec4 radiusPlane(0.0f, 0.0f, -0.004f, 0.016f);
  const AABB<double> local(bvh.bounds().min - origin, bvh.bounds().max - origin);
  float grow = 0.0f;
  for (int corner = 0; corner < 8; ++corner)
  {
    const vec3 c(float((corner & 1) ? local.max.x : local.min.x), float((corner & 2) ? local.max.y : local.min.y),
      float((corner & 4) ? local.max.z : local.min.z));
    grow = std::max(grow, gpu::tubeRadius(radiusPlane, c));
  }
  int hits = 0;
  for (int r = 0; r < rayCount; ++r)
  {
    const vec3 org = vec3(rng.inBox(Vec3<double>(-1.2), Vec3<double>(1.2))) + vec3(0.0f, 0.0f, 4.0f);
    const vec3 dir = vec3(rng.inBox(Vec3<double>(-1.2), Vec3<double>(1.2))) - org;
    float tmax = 1.0f;
    int segment;
    const bool found = gpu::traverseTubes(u, 0, org, dir, 0.0f, tmax, segment, false, radiusPlane, grow);
    float best = 1.0f;
    bool any = false;
    for (const gpu::Segment& s : records)
    {
      float t;
      if (gpu::intersectRayTube(org, dir, s.a, s.b, gpu::tubeRadius(radiusPlane, s.a),
            gpu::tubeRadius(radiusPlane, s.b), 0.0f, best, t))
      {
        best = t;
        any = true;
      }
    }
    VTKRT_CHECK(found == any);
    if (found && any)
    {
      ++hits;
      VTKRT_CHECK(tmax == best);
    }
  }
  VTKRT_CHECK_MSG(hits > rayCount / 4, "%d hits of %d rays", hits, rayCount);
}

} // namespace

int main()
{
  checkEdgeCases();
  checkPieces(0, 3000, 3.0, 31);
  checkPieces(1, 3000, 3.0, 32);
  checkPieces(2, 1000, 3.0, 33);
  checkPieces(1, 2000, 300.0, 34);
  checkTubeWalk(200, 3000, 35);
  return testResult("TestCoreTubeTwins");
}
