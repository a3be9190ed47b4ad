// The shader's C++ walk twins (core/GpuTraversal.h) against each other and
// against the double core (the kernels: TestCoreGpuKernelTwins): the stack
// entries' packing; the while-while walks over packed real BVHs (triangles, spheres, screen-sized spheres,
// ellipsoids) find the closest hit of core's float walk exactly and of the
// double walk wherever that hit is clear; the top-level walk finds what the
// shader's flat loop over the instances finds.
#include "CoreTestUtils.h"
#include "GpuTwinTestUtils.h"

#include "vtkrt/core/GpuTraversal.h"

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{
/// Rays at a primitive set in box `bounds`: at sampled surface points
/// (`surface`), some at its edges, some axis-parallel, some from inside.
template <class Surface>
std::vector<Ray<double>> makeRays(Rng& rng, const AABB<double>& bounds, int count, Surface&& surface)
{
  std::vector<Ray<double>> rays;
  const double size = glm::length(bounds.diagonal());
  for (int i = 0; i < count; ++i)
  {
    const Vec3<double> target = surface(i % 3 == 0);
    const bool inside = i % 5 == 4;
    const Vec3<double> from = inside ? rng.inBox(bounds.min, bounds.max) : bounds.center() + size * rng.unitVector();
    const Vec3<double> dir = inside ? rng.unitVector() : 1.25 * (target - from); // target at t = 0.8
    rays.emplace_back(from, Vec3<double>(randomDirection(rng, dir)), 0.0, i % 4 == 0 ? 1.0 : 1e30);
  }
  return rays;
}

/// Brute-force hits of every primitive along a ray: nearest t, and nearest
/// t of any other primitive.
struct Nearest
{
  double t = std::numeric_limits<double>::infinity();
  double second = std::numeric_limits<double>::infinity();
};

/// One ray of a bottom-level check. twinPrim: the original id of the twin's
/// hit (kInvalidIndex: none); twinGrazes: that hit is at its primitive's
/// edge or silhouette (where float and double may differ); clear: the
/// double hit is no tie and away from edges, so the twin must hit it unless
/// it grazes something in front.
struct Comparison
{
  int rays = 0, exactMatches = 0, clearMatches = 0;

  void check(bool twinFound, float twinT, std::uint32_t twinPrim, bool twinGrazes, bool floatFound,
    const Hit<float>& fh, const Hit<double>& dh, bool clear)
  {
    ++rays;
    VTKRT_CHECK(twinFound == floatFound);
    if (twinFound && floatFound)
    {
      VTKRT_CHECK(twinT == fh.t); // the primitive may differ at a tie only
      exactMatches += twinPrim == fh.prim;
    }
    if (clear && !(twinFound && twinGrazes && twinT < dh.t))
    {
      VTKRT_CHECK_MSG(twinFound && twinPrim == dh.prim, "twin %u vs double %u", twinPrim, dh.prim);
      ++clearMatches;
    }
  }
};

void checkTriangleWalk(const MeshData& mesh, int rayCount, std::uint64_t seed)
{
  const BVH bvh = buildTriangleBVH(mesh.view());
  const Vec3<double> origin = bvh.bounds().center();
  const std::vector<float> nodes = packNodesForGpu(bvh, origin);
  const std::vector<Vec3<float>> fverts = relativeFloatPoints(mesh.vertices.data(), mesh.vertices.size(), origin);
  const std::vector<float> triangles = packTriangles(bvh, fverts, mesh.indices);
  gpu::ShaderInputs u;
  u.uNodes = gpu::TexelBuffer(nodes);
  u.uTriangles = gpu::TexelBuffer(triangles);
  const TriangleMesh<float> fmesh(fverts, mesh.indices);
  TriangleIntersector<double> isect(mesh.view());
  Rng rng(seed);
  const std::vector<Ray<double>> rays = makeRays(rng, bvh.bounds(), rayCount, [&](bool edge) {
    const std::uint32_t* t = mesh.indices.data() + 3 * rng.index(mesh.triangleCount());
    double w1 = rng.uniform(), w2 = rng.uniform() * (1 - w1);
    if (edge)
    {
      (rng.index(2) ? w1 : w2) = 0.0;
    }
    return (1 - w1 - w2) * mesh.vertices[t[0]] + w1 * mesh.vertices[t[1]] + w2 * mesh.vertices[t[2]];
  });
  Comparison cmp;
  for (const Ray<double>& ray : rays)
  {
    const vec3 org = toFloat(ray.org - origin);
    const vec3 dir = toFloat(ray.dir);
    const float tmax0 = float(ray.tmax);
    float tmax = tmax0;
    int tri;
    vec2 uv;
    const bool found = gpu::traverseTriangles(u, 0, org, dir, 0.0f, tmax, tri, uv, false);
    const std::uint32_t prim = found ? bvh.primIndex[tri] : kInvalidIndex;
    {
      // Stack entries of two words (index, count) walk alike.
      gpu::ShaderInputs wide = u;
      wide.packedStackEntries = false;
      float wideTmax = tmax0;
      int wideTri;
      vec2 wideUv;
      VTKRT_CHECK(gpu::traverseTriangles(wide, 0, org, dir, 0.0f, wideTmax, wideTri, wideUv, false) == found &&
        wideTmax == tmax && wideTri == tri && wideUv == uv);
    }
    {
      // A shader of one instance starts from the root node it is given,
      // whatever node index it is passed.
      gpu::ShaderInputs single = u;
      single.singleInstance = true;
      single.uRootNode = gpu::fetchNode(u.uNodes, 0);
      float singleTmax = tmax0;
      int singleTri;
      vec2 singleUv;
      VTKRT_CHECK(gpu::traverseTriangles(single, -1, org, dir, 0.0f, singleTmax, singleTri, singleUv, false) ==
          found &&
        singleTmax == tmax && singleTri == tri && singleUv == uv);
    }
    TriangleIntersector<float> fisect(fmesh);
    Hit<float> fh;
    const bool ffound = closestHit(GpuNodeSource(nodes), bvh.primIndex.data(), Ray<float>(org, dir, 0.0f, tmax0), fisect, fh);
    if (found && ffound && prim == fh.prim)
    {
      VTKRT_CHECK(uv == vec2(fh.u, fh.v));
    }
    // The same ray in double (exactly the float one, moved back).
    const Ray<double> dray(Vec3<double>(org) + origin, Vec3<double>(dir), 0.0, double(tmax0));
    Hit<double> dh;
    double second = std::numeric_limits<double>::infinity();
    const bool dfound = closestHit(bvh, dray, isect, dh);
    if (dfound)
    {
      bruteForceClosest(mesh.triangleCount(), dray, isect, &second);
    }
    const bool clear = dfound && std::min({ dh.u, dh.v, 1 - dh.u - dh.v }) > 1e-3 &&
      second > dh.t * (1 + 1e-4) + 1e-6 && dh.t < 0.9999 * dray.tmax;
    const bool grazes = std::min({ uv.x, uv.y, 1 - uv.x - uv.y }) < 1e-3f || tmax > 0.9999f * tmax0;
    cmp.check(found, tmax, prim, grazes, ffound, fh, dh, clear);
    VTKRT_CHECK(!found || dfound || grazes);
    // Any hit: found exactly when the closest is, and a real hit.
    float tany = tmax0;
    int anyTri;
    vec2 anyUv;
    VTKRT_CHECK(gpu::traverseTriangles(u, 0, org, dir, 0.0f, tany, anyTri, anyUv, true) == found);
    if (found && anyTri >= 0)
    {
      vec3 h;
      const std::uint32_t* t = mesh.indices.data() + 3 * bvh.primIndex[anyTri];
      VTKRT_CHECK(gpu::intersectRayTriangle(gpu::precomputeRayTriangle(org, dir), fverts[t[0]], fverts[t[1]],
        fverts[t[2]], 0.0f, tmax0, h) && h.x == tany);
    }
  }
  VTKRT_CHECK(cmp.clearMatches > rayCount / 4 && cmp.exactMatches > rayCount / 4);
  // The shader's stack, sized from the tree's depth, holds every entry the
  // walk touched.
  VTKRT_CHECK_MSG(u.deepestStackEntry >= 0 &&
      u.deepestStackEntry < static_cast<int>(gpu::stackSizeForDepth(bvh.stats.maxDepth)),
    "deepest entry %d, depth %u", u.deepestStackEntry, bvh.stats.maxDepth);
}

/// A stack entry gives back the index and count it was made of, packed (up
/// to kMaxPackedStackIndex and kMaxPackedStackCount) or not.
void testStackEntries()
{
  for (const bool packed : { true, false })
  {
    gpu::BvhStack stack;
    stack.packed = packed;
    for (const std::uint32_t index : { 0u, 1u, 12345u, gpu::kMaxPackedStackIndex })
    {
      for (std::uint32_t count = 0; count <= gpu::kMaxPackedStackCount; ++count)
      {
        const auto e = gpu::stackEntry(stack, index, count);
        VTKRT_CHECK_MSG(gpu::entryIndex(stack, e) == index && gpu::entryCount(stack, e) == count,
          "packed %d, index %u, count %u", int(packed), index, count);
      }
    }
  }
}

/// The step cap counts interior steps and leaves: a root over two leaves
/// needs two.
void testStepCap()
{
  MeshData mesh;
  mesh.vertices = { Vec3<double>(-1, -1, 0), Vec3<double>(1, -1, 0), Vec3<double>(0, 1, 0), Vec3<double>(9, -1, 0),
    Vec3<double>(11, -1, 0), Vec3<double>(10, 1, 0) };
  mesh.indices = { 0, 1, 2, 3, 4, 5 };
  BuildOptions options;
  options.maxLeafSize = 1;
  const BVH bvh = buildTriangleBVH(mesh.view(), options);
  VTKRT_CHECK(bvh.nodes.size() == 3);
  const std::vector<float> nodes = packNodesForGpu(bvh);
  std::vector<Vec3<float>> fverts = relativeFloatPoints(mesh.vertices.data(), mesh.vertices.size(), Vec3<double>(0.0));
  const std::vector<float> triangles = packTriangles(bvh, fverts, mesh.indices);
  gpu::ShaderInputs u;
  u.uNodes = gpu::TexelBuffer(nodes);
  u.uTriangles = gpu::TexelBuffer(triangles);
  for (int cap : { 0, 1, 2 })
  {
    u.maximumTraversalSteps = cap;
    float tmax = 1e30f;
    int tri;
    vec2 uv;
    VTKRT_CHECK(gpu::traverseTriangles(u, 0, vec3(0.1f, 0.2f, 5.0f), vec3(0, 0, -1), 0.0f, tmax, tri, uv, false) == (cap != 1));
  }
}

/// Spheres (sphere set or screen-sized), packed as the pass packs them.
void checkSphereWalk(int count, int rayCount, bool screenSized, std::uint64_t seed)
{
  Rng rng(seed);
  std::vector<Vec3<double>> centers;
  std::vector<double> radii;
  for (int i = 0; i < count; ++i)
  {
    centers.push_back(rng.inBox(Vec3<double>(-1), Vec3<double>(1)) + Vec3<double>(100, -50, 20));
    radii.push_back(screenSized ? 0.0 : rng.uniform(0.01, 0.08));
  }
  // Screen-sized: radius max(0, plane . center + w) this frame, boxes of
  // the centers grown by a bound of it.
  const vec4 radiusPlane = screenSized ? vec4(0.01f, -0.005f, 0.02f, 0.04f) : vec4(0.0f);
  std::vector<AABB<double>> boxes;
  for (int i = 0; i < count; ++i)
  {
    boxes.emplace_back(centers[i] - radii[i], centers[i] + radii[i]);
  }
  const BVH bvh = buildBVH(boxes);
  const Vec3<double> origin = bvh.bounds().center();
  const std::vector<float> nodes = packNodesForGpu(bvh, origin);
  std::vector<float> spheres;
  std::vector<Vec3<float>> fcenters(count);
  std::vector<float> fradii(count);
  for (int i = 0; i < count; ++i)
  {
    fcenters[i] = Vec3<float>(centers[i] - origin);
    fradii[i] = float(radii[i]);
    if (screenSized)
    {
      fradii[i] += glm::max(0.0f, glm::dot(vec3(radiusPlane), fcenters[i]) + radiusPlane.w);
    }
  }
  for (std::uint32_t s : bvh.primIndex)
  {
    spheres.insert(spheres.end(), { fcenters[s].x, fcenters[s].y, fcenters[s].z, float(radii[s]) });
  }
  gpu::ShaderInputs u;
  u.uNodes = gpu::TexelBuffer(nodes);
  u.uSpheres = gpu::TexelBuffer(spheres);
  u.screenSpheres = screenSized;
  const float grow = screenSized ? 0.1f : 0.0f; // > 0.01 + 0.005 + 0.02 + 0.04 over the unit box
  std::vector<Vec3<double>> dcenters(count);
  std::vector<double> dradii(count);
  for (int i = 0; i < count; ++i)
  {
    dcenters[i] = Vec3<double>(fcenters[i]) + origin;
    dradii[i] = double(fradii[i]);
  }
  const SphereSet<float> fset(fcenters, fradii);
  const SphereSet<double> dset(dcenters, dradii);
  const BVH dbvh = buildSphereBVH(dset);
  SphereIntersector<double> isect(dset);
  const std::vector<Ray<double>> rays = makeRays(rng, bvh.bounds(), rayCount, [&](bool edge) {
    const std::uint32_t s = rng.index(count);
    return dcenters[s] + (edge ? 1.0 : rng.uniform(0.0, 0.999)) * dradii[s] * rng.unitVector();
  });
  Comparison cmp;
  for (const Ray<double>& ray : rays)
  {
    const vec3 org = toFloat(ray.org - origin);
    const vec3 dir = toFloat(ray.dir);
    const float tmax0 = float(ray.tmax);
    float tmax = tmax0;
    int sphere;
    const bool found = gpu::traverseSpheres(u, 0, org, dir, 0.0f, tmax, sphere, false, radiusPlane, grow, false);
    const std::uint32_t prim = found ? bvh.primIndex[sphere] : kInvalidIndex;
    Hit<float> fh;
    bool ffound = false;
    if (screenSized)
    {
      // No core walk grows boxes: every sphere, by the twin's kernel.
      for (int s = 0; s < count; ++s)
      {
        float t;
        if (gpu::intersectRaySphere(org, dir, fcenters[s], fradii[s], 0.0f, ffound ? fh.t : tmax0, t))
        {
          fh.t = t;
          fh.prim = std::uint32_t(s);
          ffound = true;
        }
      }
    }
    else
    {
      ffound = closestHit(GpuNodeSource(nodes), bvh.primIndex.data(), Ray<float>(org, dir, 0.0f, tmax0),
        SphereIntersector<float>(fset), fh);
    }
    const Ray<double> dray(Vec3<double>(org) + origin, Vec3<double>(dir), 0.0, double(tmax0));
    // Whether the ray passes sphere s well inside its silhouette.
    const auto inside = [&](std::uint32_t s) {
      const Vec3<double> f = dray.org - dcenters[s];
      const Vec3<double> side = f - glm::dot(f, dray.dir) / glm::dot(dray.dir, dray.dir) * dray.dir;
      return glm::length(side) < 0.999 * dradii[s];
    };
    Hit<double> dh;
    double second = std::numeric_limits<double>::infinity();
    const bool dfound = closestHit(dbvh, dray, isect, dh);
    if (dfound)
    {
      bruteForceClosest(std::size_t(count), dray, isect, &second);
    }
    const bool clear = dfound && inside(dh.prim) && second > dh.t * (1 + 1e-4) + 1e-6 && dh.t < 0.9999 * dray.tmax;
    const bool grazes = found && (!inside(prim) || tmax > 0.9999f * tmax0);
    cmp.check(found, tmax, prim, grazes, ffound, fh, dh, clear);
    VTKRT_CHECK(!found || dfound || grazes);
  }
  VTKRT_CHECK(cmp.clearMatches > rayCount / 4 && cmp.exactMatches > rayCount / 4);
  // The shader's stack, sized from the tree's depth, holds every entry the
  // walk touched.
  VTKRT_CHECK_MSG(u.deepestStackEntry >= 0 &&
      u.deepestStackEntry < static_cast<int>(gpu::stackSizeForDepth(bvh.stats.maxDepth)),
    "deepest entry %d, depth %u", u.deepestStackEntry, bvh.stats.maxDepth);
}

/// Ellipsoids: three texels each, the rows of the affine map onto their unit
/// sphere (relative to the local origin); leaf indices count texels.
void checkEllipsoidWalk(int count, int rayCount, std::uint64_t seed)
{
  Rng rng(seed);
  std::vector<glm::dmat3> maps(count);
  std::vector<Vec3<double>> centers(count);
  std::vector<AABB<double>> boxes(count);
  for (int i = 0; i < count; ++i)
  {
    const Vec3<double> axes(rng.uniform(0.02, 0.1), rng.uniform(0.02, 0.1), rng.uniform(0.02, 0.1));
    centers[i] = rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    maps[i] = glm::dmat3(1.0 / axes.x, 0, 0, 0, 1.0 / axes.y, 0, 0, 0, 1.0 / axes.z);
    boxes[i] = AABB<double>(centers[i] - axes, centers[i] + axes);
  }
  BVH bvh = buildBVH(boxes);
  const Vec3<double> origin = bvh.bounds().center();
  std::vector<float> nodes = packNodesForGpu(bvh, origin);
  for (std::size_t i = 0; i < nodes.size(); i += 8)
  {
    if (floatBitsToUint(nodes[i + 7]) > 0)
    {
      nodes[i + 3] = uintBitsToFloat(3 * floatBitsToUint(nodes[i + 3]));
    }
  }
  std::vector<float> texels;
  for (std::uint32_t e : bvh.primIndex)
  {
    for (int r = 0; r < 3; ++r)
    {
      const Vec3<double> row(maps[e][0][r], maps[e][1][r], maps[e][2][r]);
      texels.insert(texels.end(), { float(row.x), float(row.y), float(row.z), float(-glm::dot(row, centers[e] - origin)) });
    }
  }
  gpu::ShaderInputs u;
  u.uNodes = gpu::TexelBuffer(nodes);
  u.uSpheres = gpu::TexelBuffer(texels);
  u.hasEllipsoids = true;
  const std::vector<Ray<double>> rays = makeRays(rng, bvh.bounds(), rayCount, [&](bool edge) {
    const std::uint32_t e = rng.index(count);
    return centers[e] + (edge ? 1.0 : 0.9) * (boxes[e].max - centers[e]) * rng.unitVector();
  });
  // An ellipsoid's row as the floats written, not through the twin's reader.
  const auto row = [&](int t) {
    return vec4(texels[4 * t], texels[4 * t + 1], texels[4 * t + 2], texels[4 * t + 3]);
  };
  int hits = 0;
  for (const Ray<double>& ray : rays)
  {
    const vec3 org = toFloat(ray.org - origin);
    const vec3 dir = toFloat(ray.dir);
    float tmax = float(ray.tmax);
    int texel;
    const bool found = gpu::traverseSpheres(u, 0, org, dir, 0.0f, tmax, texel, false, vec4(0.0f), 0.0f, true);
    // Every ellipsoid, by the twin's kernels on the same texels.
    float best = float(ray.tmax);
    int bestTexel = -1;
    for (int i = 0; i < 3 * count; i += 3)
    {
      const vec4 r0 = row(i);
      const vec4 r1 = row(i + 1);
      const vec4 r2 = row(i + 2);
      const vec3 unitOrg(glm::dot(vec3(r0), org) + r0.w, glm::dot(vec3(r1), org) + r1.w, glm::dot(vec3(r2), org) + r2.w);
      const vec3 unitDir(glm::dot(vec3(r0), dir), glm::dot(vec3(r1), dir), glm::dot(vec3(r2), dir));
      float t;
      if (gpu::intersectRaySphere(unitOrg, unitDir, vec3(0.0f), 1.0f, 0.0f, best, t))
      {
        best = t;
        bestTexel = i;
      }
    }
    VTKRT_CHECK(found == (bestTexel >= 0));
    VTKRT_CHECK(!found || tmax == best); // the texel may differ at a tie only
    hits += found;
  }
  VTKRT_CHECK(hits > rayCount / 3);
}

/// Instances (meshes and sphere sets placed by translations) packed as the
/// pass packs them: bottom-level nodes rebased into one buffer, records in
/// the top level's leaf order.
struct InstanceScene
{
  struct Record
  {
    vec3 boxMin, boxMax, toLocal; ///< camera-space box; camera-to-local translation
    int root;
    bool spheres;
  };
  std::vector<float> nodes, triangles, spheres, topNodes;
  std::vector<Record> records;
  std::vector<AABB<double>> worldBoxes;
  Vec3<double> anchor{ 0.0 };

  void add(const BVH& bvh, const Vec3<double>& at, const MeshData* mesh, const std::vector<Vec3<double>>& centers,
    const std::vector<double>& radii)
  {
    const Vec3<double> origin = bvh.bounds().center();
    const std::uint32_t nodeBase = std::uint32_t(nodes.size() / 8);
    const std::uint32_t primBase = std::uint32_t(mesh ? triangles.size() / 12 : spheres.size() / 4);
    std::vector<float> packed = packNodesForGpu(bvh, origin);
    for (std::size_t k = 0; k < packed.size(); k += 8)
    {
      const std::uint32_t count = floatBitsToUint(packed[k + 7]);
      packed[k + 3] = uintBitsToFloat(floatBitsToUint(packed[k + 3]) + (count == 0 ? nodeBase : primBase));
    }
    nodes.insert(nodes.end(), packed.begin(), packed.end());
    if (mesh)
    {
      const std::vector<float> t = packTriangles(
        bvh, relativeFloatPoints(mesh->vertices.data(), mesh->vertices.size(), origin), mesh->indices);
      triangles.insert(triangles.end(), t.begin(), t.end());
    }
    else
    {
      for (std::uint32_t s : bvh.primIndex)
      {
        const Vec3<float> c(centers[s] - origin);
        spheres.insert(spheres.end(), { c.x, c.y, c.z, float(radii[s]) });
      }
    }
    const AABB<double> world(bvh.bounds().min + at, bvh.bounds().max + at);
    worldBoxes.push_back(world);
    Record r;
    for (int k = 0; k < 3; ++k)
    {
      r.boxMin[k] = roundDownToFloat(world.min[k] - 1e-6);
      r.boxMax[k] = roundUpToFloat(world.max[k] + 1e-6);
    }
    r.toLocal = toFloat(-(at + origin));
    r.root = int(nodeBase);
    r.spheres = !mesh;
    records.push_back(r);
  }

  /// The top level: anchor-relative, padded for the rounding of the
  /// anchor-relative origin; the records reordered to its leaves.
  void finish()
  {
    const BVH top = buildBVH(worldBoxes);
    anchor = top.bounds().center();
    topNodes = packNodesForGpu(top, anchor);
    for (std::size_t k = 0; k < topNodes.size(); k += 8)
    {
      for (int c = 0; c < 3; ++c)
      {
        topNodes[k + c] -= 1e-5f;
        topNodes[k + 4 + c] += 1e-5f;
      }
    }
    std::vector<Record> ordered;
    for (std::uint32_t k : top.primIndex)
    {
      ordered.push_back(records[k]);
    }
    records.swap(ordered);
  }

  gpu::ShaderInputs inputs() const
  {
    gpu::ShaderInputs u;
    u.uNodes = gpu::TexelBuffer(nodes);
    u.uTriangles = gpu::TexelBuffer(triangles);
    u.uSpheres = gpu::TexelBuffer(spheres);
    u.uTopNodes = gpu::TexelBuffer(topNodes);
    u.uCameraToAnchor = toFloat(-anchor);
    return u;
  }
};

/// The twin's top-level walk against the flat loop over all instances (the
/// shader's path without a top level), closest and any hit.
void testTopLevel()
{
  Rng rng(23);
  const MeshData torus = makeTorus(24, 12);
  const MeshData ball = makeIcosphere(2, 0.6);
  const std::vector<Vec3<double>> dots = { Vec3<double>(0.0), Vec3<double>(0.5, 0, 0), Vec3<double>(0, 0.5, 0.2) };
  const std::vector<double> dotRadii = { 0.3, 0.2, 0.25 };
  const BVH torusBvh = buildTriangleBVH(torus.view()), ballBvh = buildTriangleBVH(ball.view());
  const BVH dotsBvh = buildSphereBVH(SphereSet<double>(dots, dotRadii));
  InstanceScene scene;
  for (int i = 0; i < 14; ++i)
  {
    const Vec3<double> at = rng.inBox(Vec3<double>(-3), Vec3<double>(3));
    if (i % 3 == 2)
    {
      scene.add(dotsBvh, at, nullptr, dots, dotRadii);
    }
    else
    {
      scene.add(i % 2 ? torusBvh : ballBvh, at, i % 2 ? &torus : &ball, dots, dotRadii);
    }
  }
  scene.finish();
  const gpu::ShaderInputs u = scene.inputs();
  // The shader's traceInstance without clip planes, for translations.
  auto traceInstance = [&](int instance, const vec3& org, const vec3& dir, const vec3& invDir, float& tBest,
                         int& hitInstance, int& hitPrimitive, vec2& hitUV, bool stopAtFirstHit) {
    const InstanceScene::Record& r = scene.records[std::size_t(instance)];
    float t1 = tBest, tnear;
    if (!gpu::intersectRayBoxConservative(
          org, invDir, gpu::parallelAxisBias(invDir), r.boxMin, r.boxMax, 0.0f, t1, tnear))
    {
      return;
    }
    int primitive = -1;
    vec2 uv(0.0f);
    const vec3 localOrg = org + r.toLocal;
    const bool hit = r.spheres
      ? gpu::traverseSpheres(u, r.root, localOrg, dir, 0.0f, t1, primitive, stopAtFirstHit, vec4(0.0f), 0.0f, false)
      : gpu::traverseTriangles(u, r.root, localOrg, dir, 0.0f, t1, primitive, uv, stopAtFirstHit);
    if (hit)
    {
      tBest = t1;
      hitInstance = instance;
      hitPrimitive = primitive;
      hitUV = uv;
    }
  };
  int hits = 0, sameInstance = 0;
  for (int i = 0; i < 6000; ++i)
  {
    const Vec3<double> target = rng.inBox(Vec3<double>(-3.5), Vec3<double>(3.5));
    const Vec3<double> from = 12.0 * rng.unitVector();
    const vec3 org = toFloat(from);
    const vec3 dir = randomDirection(rng, target - from);
    const vec3 invDir = gpu::safeInverse(dir);
    for (bool any : { false, true })
    {
      float tWalk = i % 2 ? 1.0f : 1e30f, tFlat = tWalk;
      int instWalk = -1, instFlat = -1, primWalk = -1, primFlat = -1;
      vec2 uvWalk(0.0f), uvFlat(0.0f);
      gpu::traceTopLevel(u, org, dir, invDir, tWalk, instWalk, primWalk, uvWalk, any, traceInstance);
      for (int k = 0; k < int(scene.records.size()) && !(any && instFlat >= 0); ++k)
      {
        traceInstance(k, org, dir, invDir, tFlat, instFlat, primFlat, uvFlat, any);
      }
      VTKRT_CHECK((instWalk >= 0) == (instFlat >= 0));
      if (!any)
      {
        VTKRT_CHECK(tWalk == tFlat); // the instance may differ at a tie only
        hits += instWalk >= 0;
        sameInstance += instWalk >= 0 && instWalk == instFlat && primWalk == primFlat;
      }
    }
  }
  VTKRT_CHECK(hits > 1000 && sameInstance > hits * 9 / 10);
}

} // namespace

int main()
{
  testStackEntries();
  checkTriangleWalk(makeIcosphere(4, 1.0, Vec3<double>(1e3, -2e3, 5e2)), 4000, 1);
  checkTriangleWalk(makeTorus(64, 32), 4000, 2);
  {
    Rng soupRng(5);
    checkTriangleWalk(makeTriangleSoup(soupRng, 3000, 0.05), 4000, 3);
  }
  testStepCap();
  checkSphereWalk(2000, 4000, false, 7);
  checkSphereWalk(2000, 3000, true, 8);
  checkEllipsoidWalk(600, 3000, 9);
  testTopLevel();
  return testResult("TestCoreGpuTwins");
}
