// Two-level BVH against brute force over the flattened scene: every
// instance's triangles transformed to world space in double and tested with
// the same kernel. Closest hit: same hit/miss, same (instance, triangle)
// where the nearest hit is unique and not within 1e-9 of an edge, t within
// 1e-9 relative (the transforms round). Any hit: same hit/miss. Skipped
// instances: singular transform, empty bottom level. Then a third of the
// instances move (setTransform + refitTop) and the same checks run again.
#include "CoreTestUtils.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace vtkrt::core;
using namespace vtkrt::test;

int main()
{
  Rng rng(31);
  std::vector<MeshData> meshes;
  meshes.push_back(makeIcosphere(3, 0.5));
  meshes.push_back(makeTorus(32, 16, 0.6, 0.2));
  meshes.push_back(makeTriangleSoup(rng, 400, 0.1));
  std::vector<BVH> bottoms;
  for (const MeshData& m : meshes)
  {
    bottoms.push_back(buildTriangleBVH(m.view()));
  }
  const BVH emptyBottom;

  std::vector<Instance> instances;
  std::vector<std::uint32_t> meshOf;
  for (int i = 0; i < 60; ++i)
  {
    const std::uint32_t mi = rng.index(meshes.size());
    glm::dmat4 m(1.0);
    m = glm::translate(m, rng.inBox(Vec3<double>(-5), Vec3<double>(5)));
    m = glm::rotate(m, rng.uniform(0, 6.283), rng.unitVector());
    m = glm::scale(m, Vec3<double>(rng.uniform(0.3, 2.0), rng.uniform(0.3, 2.0), rng.uniform(0.3, 2.0)));
    instances.push_back({ &bottoms[mi], m });
    meshOf.push_back(mi);
  }
  // Invalid ones: singular transform, empty bottom level, no bottom level.
  instances.push_back({ &bottoms[0], glm::scale(glm::dmat4(1.0), Vec3<double>(1, 0, 1)) });
  meshOf.push_back(0);
  instances.push_back({ &emptyBottom, glm::dmat4(1.0) });
  meshOf.push_back(0);
  instances.push_back({ nullptr, glm::dmat4(1.0) });
  meshOf.push_back(0);

  TwoLevelBVH scene;
  scene.build(instances);
  VTKRT_CHECK(scene.top().primIndex.size() == 60);
  VTKRT_CHECK(scene.top().stats.skippedPrimitives == 3);

  // Flattened world-space copy of the valid instances.
  struct WorldTri
  {
    Vec3<double> a, b, c;
    std::uint32_t instance, prim;
  };
  std::vector<WorldTri> flat;
  auto flatten = [&]() {
    flat.clear();
    for (std::uint32_t i = 0; i < 60; ++i)
    {
      const MeshData& m = meshes[meshOf[i]];
      for (std::uint32_t t = 0; t < m.triangleCount(); ++t)
      {
        WorldTri w;
        Vec3<double>* v[3] = { &w.a, &w.b, &w.c };
        for (int k = 0; k < 3; ++k)
        {
          *v[k] = Vec3<double>(instances[i].objectToWorld * glm::dvec4(m.vertices[m.indices[3 * t + k]], 1.0));
        }
        w.instance = i;
        w.prim = t;
        flat.push_back(w);
      }
    }
  };
  flatten();

  auto isect = [&](std::uint32_t instance, std::uint32_t prim, const Ray<double>& ray, Hit<double>& hit) {
    const MeshData& m = meshes[meshOf[instance]];
    TriangleHit<double> th;
    if (!intersectRayTriangle(ray,
          m.vertices[m.indices[3 * prim]],
          m.vertices[m.indices[3 * prim + 1]],
          m.vertices[m.indices[3 * prim + 2]],
          th))
    {
      return false;
    }
    hit.t = th.t;
    hit.u = th.u;
    hit.v = th.v;
    return true;
  };

  auto checkRays = [&](const char* phase) {
    int hits = 0, compared = 0, mismatches = 0;
    for (int r = 0; r < 3000; ++r)
    {
      const Vec3<double> o = rng.inBox(Vec3<double>(-9), Vec3<double>(9));
      const Vec3<double> target = rng.inBox(Vec3<double>(-5), Vec3<double>(5));
      const Ray<double> ray(o, target - o, 0.0, r % 4 == 0 ? 0.7 : std::numeric_limits<double>::infinity());
      // brute force
      double best = std::numeric_limits<double>::infinity(), second = best, bestBary = 0;
      std::uint32_t bestInst = kInvalidIndex, bestPrim = kInvalidIndex;
      for (const WorldTri& w : flat)
      {
        TriangleHit<double> th;
        if (intersectRayTriangle(ray, w.a, w.b, w.c, th))
        {
          if (th.t < best)
          {
            second = best;
            best = th.t;
            bestInst = w.instance;
            bestPrim = w.prim;
            bestBary = std::min({ th.u, th.v, 1 - th.u - th.v });
          }
          else
          {
            second = std::min(second, th.t);
          }
        }
      }
      Hit<double> h;
      const bool found = scene.closestHit(ray, isect, h);
      Hit<double> any;
      const bool anyFound = scene.anyHit(ray, isect, any);
      const bool expected = bestInst != kInvalidIndex;
      if (expected && bestBary < 1e-9)
      {
        continue; // on an edge: transform rounding decides between neighbours
      }
      ++compared;
      hits += expected;
      if (found != expected || anyFound != expected)
      {
        ++mismatches;
        continue;
      }
      if (!found)
      {
        continue;
      }
      VTKRT_CHECK(any.instance < 60 && any.t >= 0 && any.t <= ray.tmax);
      if (std::abs(h.t - best) > 1e-9 * best)
      {
        ++mismatches;
      }
      if (second > best * (1 + 1e-9) && (h.instance != bestInst || h.prim != bestPrim))
      {
        ++mismatches;
      }
    }
    std::printf("two-level %s: %d rays compared, %d hits, %d mismatches\n", phase, compared, hits, mismatches);
    VTKRT_CHECK(mismatches == 0);
    VTKRT_CHECK(hits > 500);
  };
  checkRays("built");

  // Move a third of the instances, refit the top level only, check again.
  for (std::uint32_t i = 0; i < 60; i += 3)
  {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), rng.inBox(Vec3<double>(-2), Vec3<double>(2)));
    m = glm::rotate(m, rng.uniform(0, 6.283), rng.unitVector()) * instances[i].objectToWorld;
    VTKRT_CHECK(scene.setTransform(i, m));
    instances[i].objectToWorld = m;
  }
  VTKRT_CHECK(!scene.setTransform(1, glm::dmat4(0.0))); // singular: refused
  scene.refitTop();
  flatten();
  checkRays("moved+refit");
  return testResult("TestCoreTwoLevel");
}
