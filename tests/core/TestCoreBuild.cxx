// Builders: structure invariants for each quality and leaf size; identical
// node arrays for identical input whatever the thread count, with a
// caller's parallelFor pool, and with concurrent bounds (empty and NaN
// primitives skipped alike); the LBVH splitting a cluster that shares one
// Morton prefix cell spatially; SAH quality
// order (sweep <= binned <= median, within 5 %); the depth cap on
// adversarial input (100k triangles with one centroid, exponentially spaced
// primitives) with queries still matching brute force; refit after moving
// vertices (tight boxes, same answers as a rebuild).
#include "CoreTestUtils.h"

#include <cstring>
#include <functional>
#include <thread>

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{

/// Every valid primitive in exactly one leaf, children after parents, child
/// boxes inside parent boxes, leaf boxes = union of their primitives' boxes.
void checkStructure(const char* what, const BVH& bvh, const std::vector<AABB<double>>& primBounds,
  std::uint32_t maxLeaf)
{
  std::vector<int> seen(primBounds.size(), 0);
  int bad = 0;
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
  {
    const BVHNode& n = bvh.nodes[i];
    if (n.isLeaf())
    {
      bad += n.count > maxLeaf || n.index + n.count > bvh.primIndex.size();
      AABB<double> u;
      for (std::uint32_t k = 0; k < n.count && n.index + k < bvh.primIndex.size(); ++k)
      {
        const std::uint32_t p = bvh.primIndex[n.index + k];
        seen[p]++;
        u.extend(primBounds[p]);
      }
      bad += !(u == n.bounds());
    }
    else
    {
      bad += !(n.index > i && n.index + 1 < bvh.nodes.size());
      if (n.index + 1 < bvh.nodes.size())
      {
        AABB<double> u = bvh.nodes[n.index].bounds();
        u.extend(bvh.nodes[n.index + 1].bounds());
        bad += !(u == n.bounds());
      }
    }
  }
  for (std::size_t p = 0; p < primBounds.size(); ++p)
  {
    const bool valid = !primBounds[p].isEmpty() && primBounds[p].isFinite();
    bad += seen[p] != (valid ? 1 : 0);
  }
  VTKRT_CHECK_MSG(bad == 0, "%s: %d structural errors", what, bad);
  VTKRT_CHECK_MSG(bvh.stats.maxDepth <= kMaxDepth, "%s: depth %u", what, bvh.stats.maxDepth);
  VTKRT_CHECK(bvh.stats.nodeCount == bvh.nodes.size());
}

int queryMismatches(const BVH& bvh, const MeshData& m, Rng& rng, int rays)
{
  TriangleIntersector<double> isect(m.view());
  const AABB<double> box = bvh.bounds();
  int mismatches = 0;
  for (int i = 0; i < rays; ++i)
  {
    const Vec3<double> o = rng.inBox(box.min - box.diagonal(), box.max + box.diagonal());
    const Vec3<double> target = rng.inBox(box.min, box.max);
    const Ray<double> ray(o, target - o);
    double second;
    const Hit<double> expected = bruteForceClosest(m.triangleCount(), ray, isect, &second);
    Hit<double> got;
    closestHit(bvh, ray, isect, got);
    mismatches += got.found() != expected.found() || got.t != expected.t ||
      (second > expected.t && got.prim != expected.prim);
  }
  return mismatches;
}

/// Moves every vertex of `m` by up to `amount` on each axis.
void jitter(MeshData& m, double amount, Rng& rng)
{
  for (auto& v : m.vertices)
  {
    v += amount * rng.inBox(Vec3<double>(-1), Vec3<double>(1));
  }
}

void testDeterminismAndQuality()
{
  Rng rng(1);
  // ~100k triangles: a noisy sphere plus a soup, enough for parallel tasks.
  MeshData m = makeIcosphere(6, 0.5, Vec3<double>(0.5)); // 81920 triangles
  jitter(m, 0.003, rng);
  const MeshData soup = makeTriangleSoup(rng, 20000, 0.02);
  for (std::size_t i = 0; i < soup.indices.size(); ++i)
  {
    m.indices.push_back(std::uint32_t(m.vertices.size()));
    m.vertices.push_back(soup.vertices[soup.indices[i]]);
  }
  const std::vector<AABB<double>> bounds = triangleBounds(m.view());
  double sah[3] = { 0, 0, 0 };
  const char* names[] = { "fast", "binned", "sweep" };
  for (int q = 0; q < 3; ++q)
  {
    BuildOptions opt;
    opt.quality = BuildQuality(q);
    opt.numThreads = 1;
    const BVH ref = buildTriangleBVH(m.view(), opt);
    checkStructure(names[q], ref, bounds, opt.maxLeafSize);
    sah[q] = ref.stats.sahCost;
    for (unsigned threads : { 2u, 8u })
    {
      opt.numThreads = threads;
      const BVH other = buildTriangleBVH(m.view(), opt);
      VTKRT_CHECK_MSG(other.nodes == ref.nodes && other.primIndex == ref.primIndex,
        "%s: %u threads give a different tree", names[q], threads);
    }
    {
      // A caller's pool (here: uneven ranges on std::threads, as a pool may
      // split them) gives the same tree too.
      BuildOptions pooled = opt;
      pooled.parallelFor = [](std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
        const std::size_t cuts[] = { 0, n / 7, n / 2, n - n / 5, n };
        std::vector<std::thread> threads;
        for (int i = 0; i < 4; ++i)
        {
          if (cuts[i] < cuts[i + 1])
          {
            threads.emplace_back([&body, &cuts, i]() { body(cuts[i], cuts[i + 1]); });
          }
        }
        for (std::thread& t : threads)
        {
          t.join();
        }
      };
      const BVH other = buildTriangleBVH(m.view(), pooled);
      VTKRT_CHECK_MSG(other.nodes == ref.nodes && other.primIndex == ref.primIndex,
        "%s: a parallelFor pool gives a different tree", names[q]);
    }
    {
      // Concurrent bounds (Fast: the reference-free LBVH) build the same
      // tree as the serial callable, skipped primitives included.
      std::vector<AABB<double>> holes = bounds;
      for (std::size_t i = 7; i < holes.size(); i += 997)
      {
        holes[i] = i % 2 ? AABB<double>() : AABB<double>(Vec3<double>(std::nan("")), Vec3<double>(1.0));
      }
      BuildOptions serial = opt;
      serial.numThreads = 1;
      const BVH a = buildBVH(holes, serial);
      opt.numThreads = 2;
      const BVH b = buildBVHConcurrentBounds(holes.size(), [&holes](std::size_t i) { return holes[i]; }, opt);
      VTKRT_CHECK_MSG(a.nodes == b.nodes && a.primIndex == b.primIndex &&
          a.stats.skippedPrimitives == b.stats.skippedPrimitives && b.stats.skippedPrimitives > 0,
        "%s: concurrent bounds give a different tree", names[q]);
      checkStructure(names[q], b, holes, opt.maxLeafSize);
    }
    VTKRT_CHECK(queryMismatches(ref, m, rng, 300) == 0);
    std::printf("%s: %zu nodes, depth %u, SAH %.2f, %.3f s\n", names[q], ref.nodes.size(), ref.stats.maxDepth,
      ref.stats.sahCost, ref.stats.buildSeconds);
  }
  VTKRT_CHECK(sah[2] <= sah[1] * 1.05);
  VTKRT_CHECK(sah[1] <= sah[0] * 1.05);

  // Leaf sizes 1..16 respected by every builder (smaller mesh).
  const MeshData small = makeTriangleSoup(rng, 3000, 0.05);
  const std::vector<AABB<double>> sb = triangleBounds(small.view());
  for (int q = 0; q < 3; ++q)
  {
    for (std::uint32_t leaf : { 1u, 2u, 7u, 16u })
    {
      BuildOptions opt;
      opt.quality = BuildQuality(q);
      opt.maxLeafSize = leaf;
      const BVH b = buildTriangleBVH(small.view(), opt);
      checkStructure(names[q], b, sb, leaf);
    }
  }
}

/// The LBVH orders primitives by 63-bit Morton codes (sorted on a prefix
/// first): a cluster that shares one prefix cell is still split spatially,
/// not in input order.
void testFastCrowdedCluster()
{
  Rng rng(5);
  std::vector<AABB<double>> boxes;
  boxes.emplace_back(Vec3<double>(1.0), Vec3<double>(1.0 + 1e-6)); // sets the grid: 1 / 2^10.7 per cell
  const double size = 1e-5; // well inside one prefix cell
  for (int i = 0; i < 4000; ++i)
  {
    const Vec3<double> c = rng.inBox(Vec3<double>(0.0), Vec3<double>(size));
    boxes.emplace_back(c, c + Vec3<double>(1e-9));
  }
  BuildOptions opt;
  opt.quality = BuildQuality::Fast;
  opt.maxLeafSize = 4;
  const BVH bvh = buildBVH(boxes, opt);
  checkStructure("fast cluster", bvh, boxes, opt.maxLeafSize);
  const BVH linear = buildBVHConcurrentBounds(boxes.size(), [&boxes](std::size_t i) { return boxes[i]; }, opt);
  VTKRT_CHECK(linear.nodes == bvh.nodes && linear.primIndex == bvh.primIndex);
  double sumDiag = 0.0;
  std::size_t leaves = 0;
  for (const BVHNode& n : bvh.nodes)
  {
    if (n.isLeaf() && n.bounds().diagonal().x < 0.5)
    {
      sumDiag += glm::length(n.bounds().diagonal());
      ++leaves;
    }
  }
  // Input-order leaves would span the cluster (diagonal ~ 1.4 size);
  // spatial ones about size / (4000 / 4)^(1/3) ~ size / 10.
  const double meanDiag = sumDiag / double(std::max<std::size_t>(leaves, 1));
  std::printf("fast cluster: %zu leaves, mean leaf diagonal %.3g of the cluster\n", leaves, meanDiag / size);
  VTKRT_CHECK(leaves >= 1000);
  VTKRT_CHECK(meanDiag < 0.4 * size);
}

void testDepthCap()
{
  Rng rng(2);
  // 100k triangles sharing one centroid (rotated copies): no split plane
  // separates them.
  {
    MeshData m;
    for (int i = 0; i < 100000; ++i)
    {
      const Vec3<double> a = rng.unitVector(), b = rng.unitVector();
      const Vec3<double> c = -(a + b);
      for (const Vec3<double>& v : { a, b, c })
      {
        m.indices.push_back(std::uint32_t(m.vertices.size()));
        m.vertices.push_back(v);
      }
    }
    for (int q = 0; q < 3; ++q)
    {
      BuildOptions opt;
      opt.quality = BuildQuality(q);
      const BVH b = buildTriangleBVH(m.view(), opt);
      checkStructure("same-centroid", b, triangleBounds(m.view()), opt.maxLeafSize);
      if (q == 1)
      {
        VTKRT_CHECK(queryMismatches(b, m, rng, 20) == 0);
      }
    }
  }
  // Exponentially spaced primitives: SAH alone peels one primitive per
  // level (a chain as deep as there are primitives); the cap must bound it.
  // (Coordinates stay below 1e100: beyond ~1e154 the kernel's products
  // overflow double.)
  for (const auto& [base, count] : { std::pair<double, int>(1.5, 500), std::pair<double, int>(1.05, 2000) })
  {
    MeshData m;
    for (int i = 0; i < count; ++i)
    {
      const double x = std::pow(base, i);
      const double s = 0.02 * x; // disjoint from the neighbours
      for (const Vec3<double>& v : { Vec3<double>(x, 0, 0), Vec3<double>(x + s, 0, 0), Vec3<double>(x, s, s) })
      {
        m.indices.push_back(std::uint32_t(m.vertices.size()));
        m.vertices.push_back(v);
      }
    }
    for (int q = 0; q < 3; ++q)
    {
      for (std::uint32_t leaf : { 1u, 4u })
      {
        BuildOptions opt;
        opt.quality = BuildQuality(q);
        opt.maxLeafSize = leaf;
        const BVH b = buildTriangleBVH(m.view(), opt);
        checkStructure("exponential", b, triangleBounds(m.view()), leaf);
        if (q == 1)
        {
          std::printf("exponential %.2f leaf %u: depth %u\n", base, leaf, b.stats.maxDepth);
        }
      }
    }
    BuildOptions opt;
    opt.maxLeafSize = 1;
    const BVH b = buildTriangleBVH(m.view(), opt);
    VTKRT_CHECK(b.stats.maxDepth > 30); // far deeper than balanced: the cap, not SAH, stopped it
    // Queries on the capped tree: a ray through each triangle finds it.
    TriangleIntersector<double> isect(m.view());
    for (int i = 0; i < count; i += 7)
    {
      Vec3<double> a(0.0), bb(0.0), c(0.0);
      m.view().triangle(i, a, bb, c);
      const Vec3<double> p = a + 0.2 * (bb - a) + 0.2 * (c - a);
      Hit<double> h;
      const Ray<double> ray(p - Vec3<double>(0, 0, a.x), Vec3<double>(0, 0, a.x));
      const bool found = closestHit(b, ray, isect, h);
      VTKRT_CHECK_MSG(found && h.prim == std::uint32_t(i), "base %g i %d found %d prim %u", base, i, found, h.prim);
    }
  }
}

void testRefit()
{
  Rng rng(3);
  MeshData m = makeIcosphere(4, 0.5, Vec3<double>(0.5));
  const BVH original = buildTriangleBVH(m.view());
  for (int step = 0; step < 3; ++step)
  {
    // Deform: twist + noise, moving vertices by up to ~20 % of the size.
    for (auto& v : m.vertices)
    {
      const double a = 0.3 * (v.z - 0.5);
      const Vec3<double> c = v - Vec3<double>(0.5);
      v = Vec3<double>(0.5) +
        Vec3<double>(c.x * std::cos(a) - c.y * std::sin(a), c.x * std::sin(a) + c.y * std::cos(a), c.z * 1.1) +
        0.01 * rng.inBox(Vec3<double>(-1), Vec3<double>(1));
    }
    BVH refitted = original;
    refitTriangles(refitted, m.view());
    checkStructure("refit", refitted, triangleBounds(m.view()), BuildOptions().maxLeafSize);
    VTKRT_CHECK(refitted.primIndex == original.primIndex);
    const BVH rebuilt = buildTriangleBVH(m.view());
    // Same answers as a rebuild and as brute force.
    TriangleIntersector<double> isect(m.view());
    int differ = 0;
    for (int i = 0; i < 2000; ++i)
    {
      const Vec3<double> o = rng.inBox(Vec3<double>(-1), Vec3<double>(2));
      const Ray<double> ray(o, rng.inBox(Vec3<double>(0.2), Vec3<double>(0.8)) - o);
      Hit<double> a, b;
      closestHit(refitted, ray, isect, a);
      closestHit(rebuilt, ray, isect, b);
      differ += a.found() != b.found() || a.t != b.t;
    }
    VTKRT_CHECK(differ == 0);
    VTKRT_CHECK(queryMismatches(refitted, m, rng, 300) == 0);
  }
}

/// The SAH cost of the subtree under `root`, relative to root's box.
double subtreeSAH(const BVH& bvh, std::uint32_t root, const BuildOptions& opt)
{
  const double rootArea = bvh.nodes[root].bounds().halfArea();
  double cost = 0.0;
  std::vector<std::uint32_t> stack{ root };
  while (!stack.empty())
  {
    const BVHNode& n = bvh.nodes[stack.back()];
    stack.pop_back();
    const double rel = n.bounds().halfArea() / rootArea;
    cost += rel * (n.isLeaf() ? opt.intersectionCost * n.count : opt.traversalCost);
    if (!n.isLeaf())
    {
      stack.push_back(n.index);
      stack.push_back(n.index + 1);
    }
  }
  return cost;
}

/// The binned SAH decides its splits on float references in the frame of
/// the primitives' union: a mesh scaled by a power of two (down to 1e-90,
/// up to 1e90) builds the same tree as at unit scale, one 1e8 away from
/// the origin or far from an outlier a tree as good, and one whose boxes
/// span the whole double range a valid tree; every node box is the exact
/// double one.
void testFloatReferenceFrames()
{
  Rng rng(4);
  MeshData unit = makeIcosphere(5, 0.5, Vec3<double>(0.5)); // 20480 triangles
  jitter(unit, 0.002, rng);
  BuildOptions opt;
  opt.numThreads = 2;
  const BVH ref = buildTriangleBVH(unit.view(), opt);
  checkStructure("unit", ref, triangleBounds(unit.view()), opt.maxLeafSize);
  auto transformed = [&unit](double scale, Vec3<double> offset) {
    MeshData m = unit;
    for (auto& v : m.vertices)
    {
      v = v * scale + offset;
    }
    return m;
  };
  for (const int exponent : { -300, -60, 60, 300 })
  {
    const MeshData m = transformed(std::ldexp(1.0, exponent), Vec3<double>(0.0));
    const BVH b = buildTriangleBVH(m.view(), opt);
    checkStructure("scaled", b, triangleBounds(m.view()), opt.maxLeafSize);
    VTKRT_CHECK_MSG(b.primIndex == ref.primIndex && b.nodes.size() == ref.nodes.size(),
      "scale 2^%d builds another tree", exponent);
  }
  {
    const MeshData m = transformed(1.0, Vec3<double>(1e8, -1e8, 1e8));
    const BVH b = buildTriangleBVH(m.view(), opt);
    checkStructure("offset 1e8", b, triangleBounds(m.view()), opt.maxLeafSize);
    VTKRT_CHECK_MSG(b.stats.sahCost <= ref.stats.sahCost * 1.01, "offset 1e8: SAH %g against %g at the origin",
      b.stats.sahCost, ref.stats.sahCost);
  }
  for (const double distance : { 1e5, 1e7, 1e12 })
  {
    // The mesh far from one tiny box at the origin, on the frame's min
    // side: the mesh spans a few float steps of the frame, and its subtree
    // is as good as the mesh's own tree all the same.
    const MeshData m = transformed(1.0, Vec3<double>(distance, 0.0, 0.0));
    std::vector<AABB<double>> boxes = triangleBounds(m.view());
    boxes.emplace_back(Vec3<double>(0.0), Vec3<double>(1e-3));
    const BVH b = buildBVH(boxes, opt);
    checkStructure("far cluster", b, boxes, opt.maxLeafSize);
    const std::uint32_t first = b.nodes[0].index;
    const std::uint32_t cluster = b.nodes[first].bounds().min.x > 1.0 ? first : first + 1;
    const double sah = subtreeSAH(b, cluster, opt);
    VTKRT_CHECK_MSG(sah <= ref.stats.sahCost * 1.01, "cluster at %g: SAH %g against %g alone", distance, sah,
      ref.stats.sahCost);
  }
  {
    // The unit mesh's boxes, twice, at -1e308 and +1e308 (the union's
    // extent overflows double): valid, and the copies split at the root.
    const std::vector<AABB<double>> unitBoxes = triangleBounds(unit.view());
    std::vector<AABB<double>> boxes;
    for (const double offset : { -1e308, 1e308 })
    {
      for (const AABB<double>& u : unitBoxes)
      {
        boxes.emplace_back(u.min * 1e300 + Vec3<double>(offset), u.max * 1e300 + Vec3<double>(offset));
      }
    }
    const BVH b = buildBVH(boxes, opt);
    checkStructure("whole double range", b, boxes, opt.maxLeafSize);
    const BVHNode& left = b.nodes[b.nodes[0].index];
    VTKRT_CHECK(b.stats.builtPrimitives == boxes.size() && (left.bounds().max.x < 0.0 || left.bounds().min.x > 0.0));
  }
}

/// A tree built straight into GPU nodes is packGpuNodes of the double tree
/// (the same splits; a parent's packed box is the union of its children's),
/// for every quality, with skipped primitives and far from the origin.
void testGpuNodes()
{
  Rng rng(5);
  MeshData m = makeIcosphere(5, 0.5, Vec3<double>(1e8, -3e7, 2.5));
  jitter(m, 0.002, rng);
  std::vector<AABB<double>> boxes = triangleBounds(m.view());
  for (std::size_t i = 3; i < boxes.size(); i += 501)
  {
    boxes[i] = AABB<double>();
  }
  const char* names[] = { "fast", "binned", "sweep" };
  for (int q = 0; q < 3; ++q)
  {
    BuildOptions opt;
    opt.quality = BuildQuality(q);
    opt.numThreads = 2;
    auto boxOf = [&boxes](std::size_t i) { return boxes[i]; };
    const BVH bvh = buildBVHConcurrentBounds(boxes.size(), boxOf, opt);
    const GpuBVH gpu = buildGpuBVHConcurrentBounds(boxes.size(), boxOf, opt);
    const std::vector<gpu::Node> packed = packGpuNodes(bvh.nodes, bvh.bounds().center());
    VTKRT_CHECK_MSG(gpu.bounds == bvh.bounds() && gpu.origin() == bvh.bounds().center() &&
        gpu.primIndex == bvh.primIndex && gpu.nodes.size() == packed.size() &&
        std::memcmp(gpu.nodes.data(), packed.data(), packed.size() * sizeof(gpu::Node)) == 0,
      "%s: GPU nodes differ from the packed double tree", names[q]);
    VTKRT_CHECK(gpu.stats.maxDepth == bvh.stats.maxDepth && gpu.stats.leafCount == bvh.stats.leafCount &&
      gpu.stats.skippedPrimitives == bvh.stats.skippedPrimitives && gpu.stats.skippedPrimitives > 0);
  }
  {
    // Signed zeros: around an origin of exactly 0, leaves whose lower x is
    // -0 and 1e-60 (both packed to a zero) under one parent.
    const std::vector<AABB<double>> zeros = { AABB<double>(Vec3<double>(-1.0), Vec3<double>(-0.5, 1.0, 1.0)),
      AABB<double>(Vec3<double>(0.5, -1.0, -1.0), Vec3<double>(1.0)),
      AABB<double>(Vec3<double>(1e-60, -1.0, -1.0), Vec3<double>(0.2, 1.0, 1.0)),
      AABB<double>(Vec3<double>(-0.0, -1.0, -1.0), Vec3<double>(0.3, 1.0, 1.0)) };
    BuildOptions single;
    single.maxLeafSize = 1;
    const BVH bvh = buildBVH(zeros, single);
    const GpuBVH gpu = buildGpuBVH(zeros, single);
    const std::vector<gpu::Node> packed = packGpuNodes(bvh.nodes, gpu.origin());
    VTKRT_CHECK(gpu.origin() == Vec3<double>(0.0) && gpu.nodes.size() == packed.size() &&
      std::memcmp(gpu.nodes.data(), packed.data(), packed.size() * sizeof(gpu::Node)) == 0);
  }
  const GpuBVH none = buildGpuBVHConcurrentBounds(0, [](std::size_t) { return AABB<double>(); });
  VTKRT_CHECK(none.empty() && none.primIndex.empty());
}

} // namespace

int main()
{
  testDeterminismAndQuality();
  testFastCrowdedCluster();
  testDepthCap();
  testRefit();
  testFloatReferenceFrames();
  testGpuNodes();
  return testResult("TestCoreBuild");
}
