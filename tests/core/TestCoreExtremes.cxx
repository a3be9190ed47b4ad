// Robustness at extremes:
//  - one scene translated by 1e4, 1e6, 1e8 and scaled by 1e-6, 1e6 gives
//    the same hits (tolerances stated per case below), in double, and in
//    float through the GPU copy relative to the local origin, whose boxes
//    contain every float vertex and child box (outward rounding);
//  - grazing rays in the plane of a face; rays parallel to a flat mesh;
//  - tangent rays and a 1e-6 sphere seen from 1e6 through the BVH (double
//    and float);
//  - zero-area, NaN, inf and out-of-range triangles: skipped, counted, no
//    crash; empty input; NaN / zero / infinite rays.
#include "CoreTestUtils.h"

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{

double minBary(const Hit<double>& h)
{
  return std::min({ h.u, h.v, 1 - h.u - h.v });
}

struct Transform
{
  const char* name;
  double scale;
  double shift;
  double distTol;   // |t' - t| * |dir| allowed (distance along the ray)
  double edgeGuard; // barycentric margin below which the triangle may differ
};

void testTransformedScenes()
{
  Rng rng(17);
  MeshData base = makeIcosphere(3, 0.5, Vec3<double>(0.5));
  for (auto& v : base.vertices)
  {
    v += 0.02 * rng.inBox(Vec3<double>(-1), Vec3<double>(1));
  }
  const MeshData soup = makeTriangleSoup(rng, 500, 0.05);
  for (std::size_t i = 0; i < soup.vertices.size(); ++i)
  {
    base.indices.push_back(std::uint32_t(base.vertices.size()));
    base.vertices.push_back(soup.vertices[soup.indices[i]]);
  }
  std::vector<std::pair<Vec3<double>, Vec3<double>>> rays; // origin, target
  for (int i = 0; i < 4000; ++i)
  {
    rays.emplace_back(rng.inBox(Vec3<double>(-1), Vec3<double>(2)), rng.inBox(Vec3<double>(0), Vec3<double>(1)));
  }
  const BVH bvh0 = buildTriangleBVH(base.view());
  TriangleIntersector<double> isect0(base.view());
  std::vector<Hit<double>> hits0(rays.size());
  int baseHits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    closestHit(bvh0, Ray<double>(rays[i].first, rays[i].second - rays[i].first), isect0, hits0[i]);
    baseHits += hits0[i].found();
  }
  VTKRT_CHECK(baseHits > 2000);

  // Tolerances: a coordinate c + D carries an absolute rounding error of
  // about eps * D (eps = 2.2e-16), so the hit moves along the ray by a few
  // eps * D: we allow 100 eps * D (2.2e-10 at 1e4, 2.2e-8 at 1e6, 2.2e-6 at
  // 1e8). Barycentrics move by eps * D / (triangle size ~0.05): hits closer
  // than the edge guard to an edge may land on the neighbour. Pure
  // scalings add a few ulps: 100 eps * scene size (3 * scale).
  const double eps = std::numeric_limits<double>::epsilon();
  const Transform transforms[] = {
    { "shift 1e4", 1.0, 1e4, 100 * eps * 1e4, 1e-10 },
    { "shift 1e6", 1.0, 1e6, 100 * eps * 1e6, 1e-8 },
    { "shift 1e8", 1.0, 1e8, 100 * eps * 1e8, 1e-6 },
    { "scale 1e-6", 1e-6, 0.0, 100 * eps * 3e-6, 1e-12 },
    { "scale 1e6", 1e6, 0.0, 100 * eps * 3e6, 1e-12 },
  };
  for (const Transform& tr : transforms)
  {
    MeshData m = base;
    const Vec3<double> shift(tr.shift, -0.5 * tr.shift, 0.25 * tr.shift);
    for (auto& v : m.vertices)
    {
      v = tr.scale * v + shift;
    }
    const BVH bvh = buildTriangleBVH(m.view());
    TriangleIntersector<double> isect(m.view());
    // The float GPU path, relative to the local origin.
    const Vec3<double> origin = localOrigin(m.vertices.data(), m.vertices.size());
    const std::vector<float> packed = packNodesForGpu(bvh, origin);
    const std::vector<Vec3<float>> fverts = relativeFloatPoints(m.vertices.data(), m.vertices.size(), origin);
    const TriangleMesh<float> fmesh(fverts, m.indices);
    // Conservative float copy: every float vertex lies inside the float box
    // of its leaf and every float child box inside its parent's.
    int outside = 0;
    for (std::size_t n = 0; n < bvh.nodes.size(); ++n)
    {
      const float* box = &packed[8 * n];
      auto inside = [&](const Vec3<float>& p) {
        return p.x >= box[0] && p.y >= box[1] && p.z >= box[2] && p.x <= box[4] && p.y <= box[5] && p.z <= box[6];
      };
      const BVHNode& node = bvh.nodes[n];
      // Outward against the double box (min - origin is exact here in the
      // shifted scenes: Sterbenz; elsewhere within an ulp of double).
      for (int k = 0; k < 3; ++k)
      {
        outside += !(double(box[k]) <= node.min[k] - origin[k]);
        outside += !(double(box[4 + k]) >= node.max[k] - origin[k]);
      }
      if (node.isLeaf())
      {
        for (std::uint32_t k = 0; k < node.count; ++k)
        {
          const std::uint32_t t = bvh.primIndex[node.index + k];
          for (int c = 0; c < 3; ++c)
          {
            outside += !inside(fverts[m.indices[3 * t + c]]);
          }
        }
      }
      else
      {
        for (std::uint32_t c = node.index; c < node.index + 2; ++c)
        {
          outside += !inside(Vec3<float>(packed[8 * c], packed[8 * c + 1], packed[8 * c + 2]));
          outside += !inside(Vec3<float>(packed[8 * c + 4], packed[8 * c + 5], packed[8 * c + 6]));
        }
      }
    }
    VTKRT_CHECK_MSG(outside == 0, "%s: %d float points outside their float box", tr.name, outside);
    int mismatches = 0, floatMismatches = 0, compared = 0, floatCompared = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
    {
      const Vec3<double> o = tr.scale * rays[i].first + shift;
      const Vec3<double> target = tr.scale * rays[i].second + shift;
      Hit<double> h;
      const Ray<double> ray(o, target - o);
      const bool found = closestHit(bvh, ray, isect, h);
      const Hit<double>& h0 = hits0[i];
      if (h0.found() && minBary(h0) < tr.edgeGuard)
      {
        continue; // within rounding of an edge: either neighbour is right
      }
      ++compared;
      if (found && minBary(h) < tr.edgeGuard)
      {
        continue; // a base miss that grazes an edge
      }
      if (found != h0.found() || (found && (h.prim != h0.prim || std::abs(h.t - h0.t) * glm::length(ray.dir) > tr.distTol)))
      {
        ++mismatches;
        std::fprintf(stderr, "%s ray %zu: %d/%d prim %u/%u t %.17g/%.17g bary %g/%g\n", tr.name, i, found, h0.found(), h.prim, h0.prim, h.t, h0.t, found ? minBary(h) : -1.0, h0.found() ? minBary(h0) : -1.0);
      }
      // Float, camera-relative: the same rays in local coordinates.
      if (h0.found() && minBary(h0) > 1e-3)
      {
        ++floatCompared;
        const Vec3<float> fo(o - origin);
        const Vec3<float> ft(target - origin);
        TriangleIntersector<float> fisect(fmesh);
        Hit<float> fh;
        const bool ffound = closestHit(GpuNodeSource(packed), bvh.primIndex.data(), Ray<float>(fo, ft - fo), fisect, fh);
        if (!ffound || fh.prim != h0.prim || std::abs(fh.t - h0.t) > 1e-4 * h0.t)
        {
          ++floatMismatches;
        }
      }
    }
    VTKRT_CHECK_MSG(mismatches == 0, "%s: %d of %d rays differ", tr.name, mismatches, compared);
    VTKRT_CHECK_MSG(floatMismatches == 0, "%s: float %d of %d differ", tr.name, floatMismatches, floatCompared);
    VTKRT_CHECK(compared > 3500 && floatCompared > 1500);
  }
}

MeshData makeUnitCube()
{
  MeshData m;
  for (int i = 0; i < 8; ++i)
  {
    m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  }
  m.indices = { 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6,
    1, 3, 5, 3, 7, 5 };
  return m;
}

void testGrazing()
{
  const MeshData cube = makeUnitCube();
  const BVH bvh = buildTriangleBVH(cube.view());
  TriangleIntersector<double> isect(cube.view());
  Hit<double> h;
  // In the plane of the top face (z = 1), entering through the top edge of
  // the x = 0 face: that edge belongs to the side face, which is hit at t = 1
  // exactly (the flat top-face boxes see 0 * inf in the slab test).
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(-1, 0.5, 1), Vec3<double>(1, 0, 0)), isect, h));
  VTKRT_CHECK(h.t == 1.0);
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(-1, 0.3, 1), Vec3<double>(1, 0.1, 0)), isect, h));
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(-1, 0.5, 1 - 1e-12), Vec3<double>(1, 0, 0)), isect, h));
  VTKRT_CHECK_NEAR(h.t, 1.0, 1e-15);
  VTKRT_CHECK(!closestHit(bvh, Ray<double>(Vec3<double>(-1, 0.5, 1 + 1e-12), Vec3<double>(1, 0, 0)), isect, h));
  // Along the top edge itself, and along a face diagonal inside the face.
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(-1, 1, 1), Vec3<double>(1, 0, 0)), isect, h));
  VTKRT_CHECK(h.t == 1.0);
  // In the face plane but beside the cube: miss.
  VTKRT_CHECK(!closestHit(bvh, Ray<double>(Vec3<double>(-1, 1.5, 1), Vec3<double>(1, 0, 0)), isect, h));
  // The same in float.
  const std::vector<Vec3<float>> fv = relativeFloatPoints(cube.vertices.data(), cube.vertices.size(), Vec3<double>(0.0));
  const std::vector<float> packed = packNodesForGpu(bvh);
  TriangleIntersector<float> fisect(TriangleMesh<float>(fv, cube.indices));
  Hit<float> fh;
  VTKRT_CHECK(closestHit(GpuNodeSource(packed), bvh.primIndex.data(), Ray<float>(Vec3<float>(-1, 0.5f, 1), Vec3<float>(1, 0, 0)), fisect, fh));
  VTKRT_CHECK(fh.t == 1.0f);

  // Rays parallel to a flat grid (z = 0): above it miss; in its plane they
  // graze (no hit on the flat triangles, no crash, no NaN).
  MeshData grid;
  const int n = 20;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      grid.vertices.emplace_back(double(i) / n, double(j) / n, 0.0);
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const std::uint32_t a = j * (n + 1) + i;
      grid.indices.insert(grid.indices.end(), { a, a + 1, a + n + 2, a, a + n + 2, a + n + 1 });
    }
  }
  const BVH gbvh = buildTriangleBVH(grid.view());
  TriangleIntersector<double> gisect(grid.view());
  Rng rng(4);
  for (int i = 0; i < 200; ++i)
  {
    const double a = rng.uniform(0, 6.283);
    const Vec3<double> d(std::cos(a), std::sin(a), 0.0);
    VTKRT_CHECK(!closestHit(gbvh, Ray<double>(Vec3<double>(0.5, 0.5, 0.5), d), gisect, h));
    VTKRT_CHECK(!closestHit(gbvh, Ray<double>(Vec3<double>(0.5, 0.5, 0.0), d), gisect, h));
    VTKRT_CHECK(allHits(gbvh, Ray<double>(Vec3<double>(-1, 0.5, 0.0), d), gisect).empty());
  }
  // ... and a ray through it from above always hits.
  VTKRT_CHECK(closestHit(gbvh, Ray<double>(Vec3<double>(0.3, 0.55, 1), Vec3<double>(0, 0, -1)), gisect, h));
}

void testSpheres()
{
  // Tangent rays through the BVH: touching hits, a hair off misses.
  std::vector<Vec3<double>> centers{ Vec3<double>(0, 0, 0), Vec3<double>(10, 0, 0) };
  std::vector<double> radii{ 1.0, 2.0 };
  const SphereSet<double> spheres(centers, radii);
  const BVH bvh = buildSphereBVH(spheres);
  SphereIntersector<double> isect(spheres);
  Hit<double> h;
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(-5, 1, 0), Vec3<double>(1, 0, 0)), isect, h));
  VTKRT_CHECK(h.prim == 0 && h.t == 5.0);
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(-5, 1 + 1e-9, 0), Vec3<double>(1, 0, 0)), isect, h));
  VTKRT_CHECK(h.prim == 1);
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(10, -7, 2), Vec3<double>(0, 1, 0)), isect, h));
  VTKRT_CHECK(h.prim == 1 && h.t == 7.0);
  VTKRT_CHECK(!closestHit(bvh, Ray<double>(Vec3<double>(10, -7, 2.000001), Vec3<double>(0, 1, 0)), isect, h));

  // A sphere of radius 1e-6 seen from 1e6 away, through the BVH, double:
  // random directions, aimed 0.5 r off center hit, 1.5 r off miss.
  Rng rng(8);
  for (int i = 0; i < 500; ++i)
  {
    std::vector<Vec3<double>> c{ rng.inBox(Vec3<double>(-10), Vec3<double>(10)) };
    std::vector<double> r{ 1e-6 };
    const SphereSet<double> tiny(c, r);
    const BVH tb = buildSphereBVH(tiny);
    SphereIntersector<double> ti(tiny);
    const Vec3<double> o = c[0] + 1e6 * rng.unitVector();
    const Vec3<double> view = glm::normalize(c[0] - o);
    Vec3<double> side = rng.unitVector();
    side = glm::normalize(side - glm::dot(side, view) * view);
    VTKRT_CHECK(closestHit(tb, Ray<double>(o, c[0] + 0.5e-6 * side - o), ti, h));
    VTKRT_CHECK_NEAR(h.t, 1.0 - std::sqrt(0.75) * 1e-12, 1e-13);
    VTKRT_CHECK(!closestHit(tb, Ray<double>(o, c[0] + 1.5e-6 * side - o), ti, h));
  }
  // Float (GPU copy relative to the sphere's center): float cannot place a
  // ray 1e6 long to better than ~0.06 sideways in general, so this checks
  // axis-aligned views, where the stable discriminant still resolves 1e-6.
  {
    std::vector<Vec3<double>> c{ Vec3<double>(3e6, -2e6, 5e5) };
    std::vector<double> r{ 1e-6 };
    const SphereSet<double> tiny(c, r);
    const BVH tb = buildSphereBVH(tiny);
    const std::vector<float> packed = packNodesForGpu(tb, c[0]);
    std::vector<Vec3<float>> fc{ Vec3<float>(0.0f) };
    std::vector<float> fr{ 1e-6f };
    SphereIntersector<float> fi(SphereSet<float>(fc, fr));
    Hit<float> fh;
    for (int axis = 0; axis < 3; ++axis)
    {
      for (float sign : { -1.0f, 1.0f })
      {
        Vec3<float> o(0.0f), d(0.0f), side(0.0f);
        o[axis] = sign * 1e6f;
        d[axis] = -sign;
        side[(axis + 1) % 3] = 1.0f;
        VTKRT_CHECK(closestHit(GpuNodeSource(packed), tb.primIndex.data(), Ray<float>(o, d), fi, fh));
        VTKRT_CHECK_NEAR(fh.t, 1e6, 0.07);
        VTKRT_CHECK(closestHit(GpuNodeSource(packed), tb.primIndex.data(), Ray<float>(o, d + 0.5e-12f * side), fi, fh));
        VTKRT_CHECK(!closestHit(GpuNodeSource(packed), tb.primIndex.data(), Ray<float>(o, d + 1.5e-12f * side), fi, fh));
      }
    }
  }
}

void testInvalidInput()
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  MeshData m;
  m.vertices = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 2, 0, 0 }, { nan, 0, 0 }, { 0, inf, 0 }, { 1, 1, 0 } };
  m.indices = {
    0, 1, 2, // valid
    0, 1, 3, // collinear: zero area
    1, 1, 2, // repeated vertex: zero area
    0, 1, 4, // NaN
    0, 5, 2, // inf
    0, 1, 99, // out of range
    1, 6, 2, // valid
  };
  const BVH bvh = buildTriangleBVH(m.view());
  VTKRT_CHECK(bvh.stats.inputPrimitives == 7);
  VTKRT_CHECK(bvh.stats.builtPrimitives == 2);
  VTKRT_CHECK(bvh.stats.skippedPrimitives == 5);
  VTKRT_CHECK(bvh.stats.degeneratePrimitives == 2);
  VTKRT_CHECK(bvh.stats.nonFinitePrimitives == 3);
  VTKRT_CHECK(bvh.primIndex.size() == 2);
  TriangleIntersector<double> isect(m.view());
  Hit<double> h;
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(0.2, 0.2, 1), Vec3<double>(0, 0, -1)), isect, h));
  VTKRT_CHECK(h.prim == 0);
  VTKRT_CHECK(closestHit(bvh, Ray<double>(Vec3<double>(0.8, 0.8, 1), Vec3<double>(0, 0, -1)), isect, h));
  VTKRT_CHECK(h.prim == 6);
  VTKRT_CHECK(!closestHit(bvh, Ray<double>(Vec3<double>(1.5, 0.0, 1), Vec3<double>(0, 0, -1)), isect, h));
  PointHit<double> ph;
  VTKRT_CHECK(closestPoint(bvh, Vec3<double>(5, 0, 0), inf, TriangleClosestPoint<double>(m.view()), ph));
  VTKRT_CHECK(ph.prim == 0 || ph.prim == 6);

  // Spheres: NaN center, zero and negative radius skipped.
  std::vector<Vec3<double>> c{ { 0, 0, 0 }, { nan, 0, 0 }, { 1, 1, 1 }, { 2, 2, 2 } };
  std::vector<double> r{ 1.0, 1.0, 0.0, -1.0 };
  const BVH sb = buildSphereBVH(SphereSet<double>(c, r));
  VTKRT_CHECK(sb.primIndex.size() == 1 && sb.stats.skippedPrimitives == 3);
  VTKRT_CHECK(sb.stats.nonFinitePrimitives == 1 && sb.stats.degeneratePrimitives == 2);

  // Empty input and all-invalid input: no nodes, every query misses.
  for (const MeshData& e : { MeshData(), MeshData{ { { nan, nan, nan } }, { 0, 0, 0 } } })
  {
    const BVH eb = buildTriangleBVH(e.view());
    VTKRT_CHECK(eb.empty() && eb.primIndex.empty());
    VTKRT_CHECK(packNodesForGpu(eb).empty());
    TriangleIntersector<double> ei(e.view());
    VTKRT_CHECK(!closestHit(eb, Ray<double>(Vec3<double>(0), Vec3<double>(1, 0, 0)), ei, h));
    VTKRT_CHECK(!anyHit(eb, Ray<double>(Vec3<double>(0), Vec3<double>(1, 0, 0)), ei));
    VTKRT_CHECK(allHits(eb, Ray<double>(Vec3<double>(0), Vec3<double>(1, 0, 0)), ei).empty());
    VTKRT_CHECK(!closestPoint(eb, Vec3<double>(0), inf, TriangleClosestPoint<double>(e.view()), ph));
    int calls = 0;
    queryBox(eb, AABB<double>(Vec3<double>(-1), Vec3<double>(1)), [&](std::uint32_t) { ++calls; });
    VTKRT_CHECK(calls == 0);
  }

  // Invalid rays: NaN anywhere, zero direction, infinite origin, tmin > tmax.
  const Vec3<double> o(0.2, 0.2, 1), d(0, 0, -1);
  const Ray<double> bad[] = { Ray<double>(Vec3<double>(nan, 0.2, 1), d), Ray<double>(o, Vec3<double>(0, nan, -1)),
    Ray<double>(o, Vec3<double>(0.0)), Ray<double>(Vec3<double>(0.2, 0.2, inf), d), Ray<double>(o, d, nan, 2.0),
    Ray<double>(o, d, 0.0, nan), Ray<double>(o, d, 2.0, 1.0) };
  for (const Ray<double>& ray : bad)
  {
    VTKRT_CHECK(!closestHit(bvh, ray, isect, h) && !h.found());
    VTKRT_CHECK(!anyHit(bvh, ray, isect));
    VTKRT_CHECK(allHits(bvh, ray, isect).empty());
  }
  VTKRT_CHECK(!closestPoint(bvh, Vec3<double>(nan, 0, 0), inf, TriangleClosestPoint<double>(m.view()), ph));
  VTKRT_CHECK(!closestPoint(bvh, Vec3<double>(0, 0, 0), nan, TriangleClosestPoint<double>(m.view()), ph));
}

} // namespace

int main()
{
  testTransformedScenes();
  testGrazing();
  testSpheres();
  testInvalidInput();
  return testResult("TestCoreExtremes");
}
