// Every BVH query against brute force in double, for each builder and
// several leaf sizes, on random triangle soups, a noisy closed sphere and
// random spheres: closest hit (hit/miss, primitive id where the nearest hit
// is unique, t within 1e-12 relative), any hit, all hits, closest point
// (distance, with and without a radius), box overlap. Rays include
// axis-aligned ones and origins lying exactly on node box planes. Also the packed float
// GPU copy walked on the CPU: it must find every hit the double tree finds
// away from edges (conservative boxes). Concurrent queries on one tree
// give the sequential answers.
#include "CoreTestUtils.h"

#include <set>
#include <thread>

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{

int disagreements = 0;

std::vector<Ray<double>> makeRays(Rng& rng, const MeshData& mesh, std::size_t count)
{
  std::vector<Ray<double>> rays;
  for (std::size_t i = 0; i < count; ++i)
  {
    Vec3<double> org = rng.inBox(Vec3<double>(-1), Vec3<double>(2));
    Vec3<double> dir(0.0);
    if (i % 2 == 0 && mesh.triangleCount() > 0)
    {
      // Aim at a random point of a random triangle (hits likely).
      Vec3<double> a(0.0), b(0.0), c(0.0);
      mesh.view().triangle(rng.index(mesh.triangleCount()), a, b, c);
      const double u = rng.uniform(), v = rng.uniform() * (1 - u);
      dir = (1 - u - v) * a + u * b + v * c - org;
    }
    else
    {
      dir = rng.unitVector() * rng.uniform(0.1, 3.0);
    }
    if (i % 5 == 1)
    {
      // Axis-aligned (zero direction components, as picks along an axis).
      dir = Vec3<double>(0.0);
      dir[i / 5 % 3] = (i / 15) % 2 ? 1.0 : -1.0;
    }
    if (i % 7 == 3 && mesh.triangleCount() > 0)
    {
      // Origin coordinates copied from a vertex: exactly on node box planes.
      const Vec3<double>& v = mesh.vertices[mesh.indices[3 * rng.index(mesh.triangleCount())]];
      org.x = v.x;
      if (i % 2)
      {
        org.y = v.y;
      }
      if (dir.x != 0.0 && dir.y != 0.0 && dir.z != 0.0 && i % 3 == 0)
      {
        dir.x = 0.0; // and parallel to that plane
      }
    }
    // Mix segments and half-infinite rays.
    const double tmax = i % 3 == 0 ? rng.uniform(0.2, 2.0) : std::numeric_limits<double>::infinity();
    rays.emplace_back(org, dir, 0.0, tmax);
  }
  return rays;
}

template <class Isect>
void checkRayQueries(const char* what, const BVH& bvh, std::size_t primCount, const std::vector<Ray<double>>& rays,
  Isect isect)
{
  int hits = 0, unique = 0;
  for (const Ray<double>& ray : rays)
  {
    double second;
    const Hit<double> expected = bruteForceClosest(primCount, ray, isect, &second);
    Hit<double> got;
    const bool found = closestHit(bvh, ray, isect, got);
    if (found != expected.found())
    {
      ++disagreements;
      std::fprintf(stderr, "%s: closest hit/miss disagrees\n", what);
      continue;
    }
    // any hit agrees on hit/miss, and what it returns is a real hit
    Hit<double> any;
    if (anyHit(bvh, ray, isect, any) != found)
    {
      ++disagreements;
      std::fprintf(stderr, "%s: any hit/miss disagrees\n", what);
    }
    // all hits: same set as brute force, sorted by t
    std::vector<Hit<double>> all = allHits(bvh, ray, isect);
    std::vector<std::uint32_t> bruteAll;
    for (std::uint32_t p = 0; p < primCount; ++p)
    {
      Hit<double> h;
      if (isect(p, ray, h))
      {
        bruteAll.push_back(p);
      }
    }
    std::set<std::uint32_t> gotAll;
    for (std::size_t k = 0; k < all.size(); ++k)
    {
      gotAll.insert(all[k].prim);
      VTKRT_CHECK(k == 0 || all[k - 1].t <= all[k].t);
    }
    if (gotAll != std::set<std::uint32_t>(bruteAll.begin(), bruteAll.end()) || all.size() != bruteAll.size())
    {
      ++disagreements;
      std::fprintf(stderr, "%s: all hits disagree (%zu vs %zu)\n", what, all.size(), bruteAll.size());
    }
    if (!found)
    {
      continue;
    }
    ++hits;
    VTKRT_CHECK(any.found() && any.t >= ray.tmin && any.t <= ray.tmax);
    VTKRT_CHECK(!all.empty() && all.front().t == expected.t);
    if (std::abs(got.t - expected.t) > 1e-12 * std::abs(expected.t))
    {
      ++disagreements;
      std::fprintf(stderr, "%s: t %.17g vs %.17g\n", what, got.t, expected.t);
    }
    if (second > expected.t * (1 + 1e-9))
    {
      ++unique;
      if (got.prim != expected.prim)
      {
        ++disagreements;
        std::fprintf(stderr, "%s: prim %u vs %u\n", what, got.prim, expected.prim);
      }
    }
  }
  // Real coverage, not a vacuous pass.
  VTKRT_CHECK_MSG(hits > int(rays.size()) / 5, "%s: only %d hits", what, hits);
  VTKRT_CHECK_MSG(unique > hits * 9 / 10, "%s: only %d unique of %d", what, unique, hits);
}

template <class PointFn>
void checkPointQueries(const char* what, const BVH& bvh, std::size_t primCount, Rng& rng, PointFn fn)
{
  int found = 0;
  for (int i = 0; i < 300; ++i)
  {
    const Vec3<double> p = rng.inBox(Vec3<double>(-0.5), Vec3<double>(1.5));
    PointHit<double> expected;
    for (std::uint32_t k = 0; k < primCount; ++k)
    {
      PointHit<double> c;
      if (fn(k, p, c) && c.dist2 < expected.dist2)
      {
        expected = c;
        expected.prim = k;
      }
    }
    PointHit<double> got;
    VTKRT_CHECK(closestPoint(bvh, p, std::numeric_limits<double>::infinity(), fn, got) == expected.found());
    if (expected.found())
    {
      if (got.dist2 != expected.dist2)
      {
        ++disagreements;
        std::fprintf(stderr, "%s: closest point dist2 %.17g vs %.17g\n", what, got.dist2, expected.dist2);
      }
      // With a radius: found iff the closest lies within it.
      const double d = std::sqrt(expected.dist2);
      PointHit<double> within;
      VTKRT_CHECK(closestPoint(bvh, p, d * 1.0001, fn, within));
      VTKRT_CHECK(within.dist2 == expected.dist2);
      VTKRT_CHECK(!closestPoint(bvh, p, d * 0.9999, fn, within));
      ++found;
    }
  }
  VTKRT_CHECK(found > 0);
}

void checkBoxQueries(const BVH& bvh, const MeshData& mesh, Rng& rng)
{
  const TriangleMesh<double> view = mesh.view();
  for (int i = 0; i < 200; ++i)
  {
    const Vec3<double> lo = rng.inBox(Vec3<double>(-0.2), Vec3<double>(1.0));
    const AABB<double> box(lo, lo + rng.inBox(Vec3<double>(0.0), Vec3<double>(0.3)));
    std::vector<std::uint32_t> got = trianglesOverlappingBox(bvh, view, box);
    std::sort(got.begin(), got.end());
    std::vector<std::uint32_t> expected;
    for (std::uint32_t k = 0; k < mesh.triangleCount(); ++k)
    {
      Vec3<double> a(0.0), b(0.0), c(0.0);
      view.triangle(k, a, b, c);
      AABB<double> tb;
      tb.extend(a);
      tb.extend(b);
      tb.extend(c);
      if (tb.overlaps(box) && isValidTriangle(a, b, c))
      {
        expected.push_back(k);
      }
    }
    if (got != expected)
    {
      ++disagreements;
      std::fprintf(stderr, "box query: %zu vs %zu\n", got.size(), expected.size());
    }
  }
}

/// The float copy (relative to the local origin) must find a hit wherever
/// double finds one well inside a triangle (2 % barycentric margin), at the
/// same triangle when that hit is unique.
void checkGpuCopy(const BVH& bvh, const MeshData& mesh, const std::vector<Ray<double>>& rays)
{
  const Vec3<double> origin = localOrigin(mesh.vertices.data(), mesh.vertices.size());
  const std::vector<float> packed = packNodesForGpu(bvh, origin);
  const std::vector<Vec3<float>> fverts = relativeFloatPoints(mesh.vertices.data(), mesh.vertices.size(), origin);
  const TriangleMesh<float> fmesh(fverts, mesh.indices);
  const GpuNodeSource gpu(packed);
  TriangleIntersector<double> isect(mesh.view());
  int compared = 0;
  for (const Ray<double>& ray : rays)
  {
    Hit<double> h;
    if (!closestHit(bvh, ray, isect, h) || std::min({ h.u, h.v, 1 - h.u - h.v }) < 0.02)
    {
      continue;
    }
    double second;
    bruteForceClosest(mesh.triangleCount(), ray, isect, &second);
    const Ray<float> fray(Vec3<float>(ray.org - origin), Vec3<float>(ray.dir), 0.0f,
      std::isinf(ray.tmax) ? std::numeric_limits<float>::infinity() : float(ray.tmax * 1.001));
    TriangleIntersector<float> fisect(fmesh);
    Hit<float> fh;
    const bool found = closestHit(gpu, bvh.primIndex.data(), fray, fisect, fh);
    VTKRT_CHECK(found);
    if (found && second > h.t * 1.01)
    {
      ++compared;
      VTKRT_CHECK(fh.prim == h.prim);
      VTKRT_CHECK_NEAR(fh.t, h.t, 1e-4 * (1 + h.t));
    }
  }
  VTKRT_CHECK(compared > 100);
}

void checkTree(const BVH& bvh, std::size_t validPrims, std::uint32_t maxLeaf)
{
  // Structural invariants: every valid primitive in exactly one leaf, child
  // boxes inside parents, children after parents, leaves within size.
  VTKRT_CHECK(bvh.primIndex.size() == validPrims);
  std::vector<int> seen(bvh.stats.inputPrimitives, 0);
  for (std::uint32_t p : bvh.primIndex)
  {
    VTKRT_CHECK(p < seen.size());
    if (p < seen.size())
    {
      seen[p]++;
    }
  }
  for (int s : seen)
  {
    VTKRT_CHECK(s <= 1);
  }
  std::size_t leafPrims = 0;
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
  {
    const BVHNode& n = bvh.nodes[i];
    if (n.isLeaf())
    {
      leafPrims += n.count;
      VTKRT_CHECK(n.count <= maxLeaf);
      VTKRT_CHECK(n.index + n.count <= bvh.primIndex.size());
    }
    else
    {
      VTKRT_CHECK(n.index > i && n.index + 1 < bvh.nodes.size());
      for (int c = 0; c < 2; ++c)
      {
        VTKRT_CHECK(n.bounds().contains(bvh.nodes[n.index + c].bounds()));
      }
    }
  }
  VTKRT_CHECK(leafPrims == validPrims);
  VTKRT_CHECK(bvh.stats.maxDepth <= kMaxDepth);
}

MeshData makeNoisySphere(Rng& rng)
{
  MeshData m = makeIcosphere(4, 0.5, Vec3<double>(0.5));
  for (auto& v : m.vertices)
  {
    v += 0.01 * rng.inBox(Vec3<double>(-1), Vec3<double>(1));
  }
  return m;
}

} // namespace

int main()
{
  Rng rng(2024);
  std::vector<MeshData> meshes;
  meshes.push_back(makeTriangleSoup(rng, 3000, 0.05));
  meshes.push_back(makeNoisySphere(rng));
  meshes.push_back(makeTriangleSoup(rng, 1500, 0.3)); // large overlapping triangles
  const char* meshNames[] = { "soup", "sphere", "big-soup" };
  const BuildQuality qualities[] = { BuildQuality::Fast, BuildQuality::Medium, BuildQuality::High };
  const char* qualityNames[] = { "fast", "binned-sah", "sweep-sah" };

  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const MeshData& mesh = meshes[m];
    const std::vector<Ray<double>> rays = makeRays(rng, mesh, 1500);
    for (int q = 0; q < 3; ++q)
    {
      for (std::uint32_t leaf : { 1u, 4u, 8u })
      {
        BuildOptions opt;
        opt.quality = qualities[q];
        opt.maxLeafSize = leaf;
        const BVH bvh = buildTriangleBVH(mesh.view(), opt);
        char what[128];
        std::snprintf(what, sizeof what, "%s/%s/leaf%u", meshNames[m], qualityNames[q], leaf);
        checkTree(bvh, mesh.triangleCount(), leaf);
        checkRayQueries(what, bvh, mesh.triangleCount(), rays, TriangleIntersector<double>(mesh.view()));
        if (leaf == 4)
        {
          checkPointQueries(what, bvh, mesh.triangleCount(), rng, TriangleClosestPoint<double>(mesh.view()));
          checkBoxQueries(bvh, mesh, rng);
          checkGpuCopy(bvh, mesh, rays);
        }
      }
    }
  }

  // Spheres: random centers and radii.
  {
    std::vector<Vec3<double>> centers;
    std::vector<double> radii;
    for (int i = 0; i < 2000; ++i)
    {
      centers.push_back(rng.inBox(Vec3<double>(0), Vec3<double>(1)));
      radii.push_back(rng.uniform(0.002, 0.03));
    }
    const SphereSet<double> spheres(centers, radii);
    MeshData none;
    for (int q = 0; q < 3; ++q)
    {
      BuildOptions opt;
      opt.quality = qualities[q];
      const BVH bvh = buildSphereBVH(spheres, opt);
      checkTree(bvh, centers.size(), opt.maxLeafSize);
      std::vector<Ray<double>> rays;
      for (int i = 0; i < 1500; ++i)
      {
        const Vec3<double> org = rng.inBox(Vec3<double>(-1), Vec3<double>(2));
        const Vec3<double> target =
          i % 2 ? centers[rng.index(centers.size())] : rng.inBox(Vec3<double>(0), Vec3<double>(1));
        rays.emplace_back(org, target - org);
      }
      checkRayQueries(qualityNames[q], bvh, centers.size(), rays, SphereIntersector<double>(spheres));
      checkPointQueries(qualityNames[q], bvh, centers.size(), rng, SphereClosestPoint<double>(spheres));
    }
  }

  // Queries are const and thread-safe: 4 threads (one intersector each)
  // over one tree give the sequential answers.
  {
    const MeshData& mesh = meshes[1];
    const BVH bvh = buildTriangleBVH(mesh.view());
    const std::vector<Ray<double>> rays = makeRays(rng, mesh, 4000);
    std::vector<Hit<double>> sequential(rays.size()), parallel(rays.size());
    TriangleIntersector<double> isect(mesh.view());
    for (std::size_t i = 0; i < rays.size(); ++i)
    {
      closestHit(bvh, rays[i], isect, sequential[i]);
    }
    std::vector<std::thread> pool;
    for (unsigned k = 0; k < 4; ++k)
    {
      pool.emplace_back([&, k]() {
        TriangleIntersector<double> own(mesh.view());
        for (std::size_t i = k; i < rays.size(); i += 4)
        {
          closestHit(bvh, rays[i], own, parallel[i]);
        }
      });
    }
    for (auto& t : pool)
    {
      t.join();
    }
    int differ = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
    {
      differ += sequential[i].prim != parallel[i].prim || sequential[i].t != parallel[i].t;
    }
    VTKRT_CHECK(differ == 0);
  }

  VTKRT_CHECK_MSG(disagreements == 0, "%d disagreements with brute force", disagreements);
  return testResult("TestCoreBVHQueries");
}
