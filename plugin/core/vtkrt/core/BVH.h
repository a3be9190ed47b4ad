// The flattened BVH: the one layout that the CPU (double) and the GPU (float)
// both walk.
//
// Layout (USED VERBATIM BY THE GLSL TRAVERSAL, do not change lightly):
//   nodes[] : each node is two vec4, 32 bytes on the GPU (float), 64 on the
//             CPU (double):
//               lo = (min.x, min.y, min.z, uintBitsToFloat(index))
//               hi = (max.x, max.y, max.z, uintBitsToFloat(count))
//             count == 0 : interior node; its two children are siblings at
//                          nodes[index] and nodes[index + 1]. Children always
//                          come after their parent (index > own position).
//             count  > 0 : leaf; its primitives are
//                          primIndex[index .. index + count), each an ORIGINAL
//                          primitive id (triangle id, sphere id, instance id).
//             The root is nodes[0] (it may itself be a leaf). An empty BVH (no
//             valid primitive) has no nodes at all: callers skip tracing.
//   primIndex[] : uint32 original primitive ids, grouped by leaf.
// Depth: the root has depth 0 and no node is deeper than kMaxDepth, so an
// ordered traversal that pushes the far child and descends into the near one
// holds at most kMaxDepth entries (one per level of the current path):
// kMaxStackSize (64) > kMaxDepth (48) can never overflow.
// GPU copy: packGpuNodes() writes one gpu::Node (GpuLayout.h: two RGBA32UI
// texels, float boxes as bits) per node, boxes rounded OUTWARD and expressed
// relative to a local origin.
#ifndef vtkrt_core_BVH_h
#define vtkrt_core_BVH_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/GpuLayout.h"
#include "vtkrt/core/HugePageArray.h"

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <cstring>
#include <functional>
#include <vector>

namespace vtkrt::core
{

/// No node is deeper than this (root depth 0); builders enforce it.
constexpr std::uint32_t kMaxDepth = 48;
/// Traversal stack size, CPU and GLSL: >= kMaxDepth, so it never overflows.
constexpr std::uint32_t kMaxStackSize = 64;
static_assert(kMaxStackSize >= kMaxDepth, "the traversal stack must hold one entry per level");

/// CPU node in double. Same fields, same meaning as the GPU's two vec4.
/// Trivial: an array of them is sized without writing it (BVHNode() is
/// all zeros).
struct BVHNode
{
  Vec3<double> min;
  std::uint32_t index; ///< first child (interior) or first primIndex slot (leaf)
  Vec3<double> max;
  std::uint32_t count; ///< 0: interior; > 0: number of primitives in the leaf

  bool isLeaf() const { return count > 0; }
  AABB<double> bounds() const { return AABB<double>(min, max); }
  void setBounds(const AABB<double>& b)
  {
    min = b.min;
    max = b.max;
  }
  bool operator==(const BVHNode& o) const
  {
    return min == o.min && max == o.max && index == o.index && count == o.count;
  }
};

static_assert(std::is_trivially_default_constructible<BVHNode>::value, "BVHNode arrays are sized without a write");

/// A tree's nodes: read at random by every traversal, so on huge pages when
/// large (HugePageArray.h); written in full by the builders, so no zero fill.
using BVHNodes = HugePageArray<BVHNode>;

/// Which builder: quality of the tree against build time.
enum class BuildQuality
{
  Fast,   ///< LBVH: Morton-ordered primitives split at the highest differing bit (dynamic data)
  Medium, ///< binned SAH (default)
  High,   ///< full-sweep SAH (every primitive boundary on every axis)
};

struct BuildOptions
{
  BuildQuality quality = BuildQuality::Medium;
  std::uint32_t maxLeafSize = 4; ///< max primitives per leaf (>= 1)
  unsigned numThreads = 0;       ///< 0: std::thread::hardware_concurrency()
  /// When set, the builder's parallel work runs through it instead of its
  /// own std::threads (numThreads is then ignored): parallelFor(n, body)
  /// must call body(begin, end) over disjoint ranges covering [0, n), in
  /// any split, on any threads, and return when all are done. An adapter
  /// passes its toolkit's pool (e.g. vtkSMPTools::For), whose idle workers
  /// would otherwise spin against the builder's threads.
  std::function<void(std::size_t, const std::function<void(std::size_t, std::size_t)>&)> parallelFor;
  std::uint32_t numBins = 32;    ///< binned SAH bins per axis (2..64)
  double traversalCost = 1.0;    ///< SAH cost of visiting an interior node
  double intersectionCost = 1.0; ///< SAH cost of one primitive test
};

/// What a build did. Skipped primitives (empty, NaN or infinite bounds) are
/// in no leaf; adapters split them into degenerate and non-finite.
struct BuildStats
{
  std::size_t inputPrimitives = 0;
  std::size_t builtPrimitives = 0;
  std::size_t skippedPrimitives = 0;
  std::size_t degeneratePrimitives = 0; ///< zero-area triangles, zero radius spheres
  std::size_t nonFinitePrimitives = 0;  ///< NaN or infinite coordinates
  std::size_t nodeCount = 0;
  std::size_t leafCount = 0;
  std::uint32_t maxDepth = 0;
  std::uint32_t maxLeafPrimitives = 0;
  double sahCost = 0.0; ///< sum over nodes of area/rootArea * cost
  double buildSeconds = 0.0;
};

struct BVH
{
  BVHNodes nodes;
  std::vector<std::uint32_t> primIndex;
  BuildStats stats;

  bool empty() const { return nodes.empty(); }
  AABB<double> bounds() const { return nodes.empty() ? AABB<double>() : nodes[0].bounds(); }
  std::size_t memoryBytes() const
  {
    return nodes.size() * sizeof(BVHNode) + primIndex.capacity() * sizeof(std::uint32_t);
  }
};

/// A tree built straight into GPU nodes (boxes relative to `origin`,
/// rounded outward: the same nodes as packGpuNodes(bvh.nodes, origin)).
struct GpuBVH
{
  HugePageArray<gpu::Node> nodes;
  std::vector<std::uint32_t> primIndex;
  AABB<double> bounds; ///< the exact box of every built primitive
  BuildStats stats;    ///< sahCost from the float boxes

  bool empty() const { return nodes.empty(); }
  /// What the nodes' boxes are relative to: originOf(bounds).
  Vec3<double> origin() const { return originOf(bounds); }
  /// The nodes' origin for a tree of these bounds: its center, 0 when empty.
  static Vec3<double> originOf(const AABB<double>& bounds)
  {
    return bounds.isEmpty() ? Vec3<double>(0.0) : bounds.center();
  }
};

/// Bits of a uint32 as a float (GLSL's uintBitsToFloat).
inline float uintBitsToFloat(std::uint32_t u)
{
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}
inline std::uint32_t floatBitsToUint(float f)
{
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

namespace detail
{
/// x - origin rounded outward to float. The double subtraction is correctly
/// rounded, so it is off by at most half an ulp of the result: widening by a
/// relative epsilon before the directed float rounding keeps the box
/// conservative. Exact (no widening) when origin is 0.
inline float relativeLower(double x, double origin)
{
  if (origin == 0.0)
  {
    return roundDownToFloat(x);
  }
  const double d = x - origin;
  return roundDownToFloat(d - std::abs(d) * std::numeric_limits<double>::epsilon());
}
inline float relativeUpper(double x, double origin)
{
  if (origin == 0.0)
  {
    return roundUpToFloat(x);
  }
  const double d = x - origin;
  return roundUpToFloat(d + std::abs(d) * std::numeric_limits<double>::epsilon());
}
} // namespace detail

/// A gpu::Node's box: `box` relative to `origin`, rounded outward (as
/// packGpuNode). Monotone in each coordinate, so the box of a union is the
/// union of the packed boxes.
inline void packGpuBox(gpu::Node& o, const AABB<double>& box, const Vec3<double>& origin)
{
  // + 0.0f makes a zero +0: a union's -0 and +0 ends then pack alike.
  for (int k = 0; k < 3; ++k)
  {
    o.lo[k] = detail::relativeLower(box.min[k], origin[k]) + 0.0f;
    o.hi[k] = detail::relativeUpper(box.max[k], origin[k]) + 0.0f;
  }
}

/// Float GPU copy of one node (gpu::Node, see GpuLayout.h), its box
/// relative to `origin` (use the same origin for the vertices, see
/// LocalFrame.h) and rounded outward so float traversal never misses what
/// double traversal would hit. Triangle vertices rounded to nearest float
/// always lie inside these boxes; a sphere whose float center and radius
/// both round outward can poke out by about one float ulp (a sub-ulp
/// silhouette difference, no missing geometry).
inline gpu::Node packGpuNode(const BVHNode& n, const Vec3<double>& origin = Vec3<double>(0.0))
{
  gpu::Node o;
  packGpuBox(o, n.bounds(), origin);
  o.index = n.index;
  o.count = n.count;
  return o;
}

/// packGpuNode of every node.
template <class Nodes>
std::vector<gpu::Node> packGpuNodes(const Nodes& nodes, const Vec3<double>& origin = Vec3<double>(0.0))
{
  std::vector<gpu::Node> out(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    out[i] = packGpuNode(nodes[i], origin);
  }
  return out;
}

/// The same nodes as 8 floats each (lo.xyz, bits(index), hi.xyz,
/// bits(count)): the view the float CPU traversal and the tests read.
template <class Nodes>
std::vector<float> packNodesForGpu(const Nodes& nodes, const Vec3<double>& origin = Vec3<double>(0.0))
{
  const std::vector<gpu::Node> packed = packGpuNodes(nodes, origin);
  std::vector<float> out(packed.size() * 8);
  static_assert(sizeof(gpu::Node) == 8 * sizeof(float), "a node is 8 floats");
  if (!packed.empty())
  {
    std::memcpy(out.data(), packed.data(), packed.size() * sizeof(gpu::Node));
  }
  return out;
}

inline std::vector<float> packNodesForGpu(const BVH& bvh, const Vec3<double>& origin = Vec3<double>(0.0))
{
  return packNodesForGpu(bvh.nodes, origin);
}

} // namespace vtkrt::core

#endif
