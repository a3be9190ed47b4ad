// The top-down recursion every builder shares: split a range of references
// in two, build both halves, in parallel near the root. A builder derives
// from TopDownBuilder<Itself> (no virtual calls in the recursion) and says
// where to split (see "What a builder provides" below).
//
// Determinism: the tree depends only on the input, never on the thread count.
// Subtrees with at least kTaskPrimitives primitives are laid out after the
// parent's smaller children; when two such siblings run on two threads, each
// is built into its own node array and spliced, which appends exactly the
// nodes, in the order, that building both on the calling thread appends.
#ifndef vtkrt_core_build_TopDownBuilder_h
#define vtkrt_core_build_TopDownBuilder_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/build/BuildRef.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <system_error>
#include <thread>
#include <vector>

namespace vtkrt::core::detail
{

/// Ceil(log2(x)) for x >= 1.
inline std::uint32_t ceilLog2(std::uint64_t x)
{
  std::uint32_t r = 0;
  while ((std::uint64_t(1) << r) < x)
  {
    ++r;
  }
  return r;
}

/// What a builder provides (private, with TopDownBuilder<Builder> a friend):
///   static constexpr bool kBottomUpBounds: boxes merged from the children
///     instead of a pass over each range before its split;
///   std::uint32_t expectedLeafSize() const: for sizing the node array;
///   void prepare(), void finish(): before and after the recursion;
///   const BuildRef& refAt(pos) const: the primitive at position pos;
///   void prefetchAfter(pos) const: optional, fetch refAt(pos + a few) early;
///   medianSplit(begin, end, centroids): the split at the depth cap;
///   split(begin, end, box, centroids): the builder's own split, or `end`
///     for a leaf (box and centroids are empty when kBottomUpBounds).
template <class Builder>
class TopDownBuilder
{
public:
  static constexpr std::uint32_t kTaskPrimitives = 16384;
  static constexpr std::uint32_t kPooledDepth = 4;

  TopDownBuilder(std::vector<BuildRef>& refs, const BuildOptions& options)
    : Refs(refs)
    , Options(options)
  {
    if (Options.maxLeafSize < 1)
    {
      Options.maxLeafSize = 1;
    }
    unsigned threads = Options.numThreads ? Options.numThreads : std::thread::hardware_concurrency();
    FreeThreads = static_cast<int>(std::max(1u, threads)) - 1;
  }

  /// The id of the primitive at leaf position pos (after build()).
  std::uint32_t idAt(std::uint32_t pos) const { return self().refAt(pos).id; }

  std::vector<BVHNode> build()
  {
    std::vector<BVHNode> nodes;
    if (Refs.empty())
    {
      return nodes;
    }
    self().prepare();
    nodes.reserve(nodeEstimate(Refs.size()));
    nodes.resize(1);
    buildNode(nodes, 0, 0, static_cast<std::uint32_t>(Refs.size()), 0);
    self().finish();
    nodes.shrink_to_fit(); // splices grow it geometrically
    return nodes;
  }

protected:
  std::vector<BuildRef>& Refs;
  BuildOptions Options;

  void prefetchAfter(std::uint32_t) const {}

  AABB<double> rangeBounds(std::uint32_t begin, std::uint32_t end, AABB<double>& centroids) const
  {
    AABB<double> box;
    for (std::uint32_t i = begin; i < end; ++i)
    {
      self().prefetchAfter(i);
      const BuildRef& r = self().refAt(i);
      box.extend(r.box);
      centroids.extend(r.centroid());
    }
    return box;
  }

private:
  using Ranges = std::uint32_t[2][2]; ///< the two children's [begin, end)

  std::atomic<int> FreeThreads{ 0 };

  Builder& self() { return static_cast<Builder&>(*this); }
  const Builder& self() const { return static_cast<const Builder&>(*this); }

  /// Room for the nodes over `count` primitives. Too little costs a
  /// reallocation of the whole array; the build shrinks it to size at the end.
  std::size_t nodeEstimate(std::size_t count) const { return 2 * count / self().expectedLeafSize() + 1; }

  /// Where to split [begin, end), or `end` for a leaf.
  std::uint32_t chooseSplit(std::uint32_t begin, std::uint32_t end, std::uint32_t depth,
    const AABB<double>& box, const AABB<double>& centroids)
  {
    const std::uint32_t count = end - begin;
    if (count <= 1 || depth >= kMaxDepth)
    {
      return end;
    }
    // Depth cap: once the remaining levels only just suffice for halving the
    // range down to leaf size, split at the object median (never deeper
    // than kMaxDepth, leaves never larger than maxLeafSize for any input up
    // to maxLeafSize * 2^kMaxDepth primitives).
    const std::uint64_t leavesNeeded = (std::uint64_t(count) + Options.maxLeafSize - 1) / Options.maxLeafSize;
    if (kMaxDepth - depth <= ceilLog2(leavesNeeded) + 1)
    {
      if (count <= Options.maxLeafSize)
      {
        return end;
      }
      return self().medianSplit(begin, end, centroids);
    }
    return self().split(begin, end, box, centroids);
  }

  /// Builds the subtree of [begin, end) into nodes[slot] and nodes appended
  /// to `nodes`.
  void buildNode(std::vector<BVHNode>& nodes, std::size_t slot, std::uint32_t begin, std::uint32_t end,
    std::uint32_t depth)
  {
    constexpr bool bottomUp = Builder::kBottomUpBounds;
    AABB<double> centroids;
    AABB<double> box;
    if (!bottomUp)
    {
      box = rangeBounds(begin, end, centroids);
    }
    const std::uint32_t mid = chooseSplit(begin, end, depth, box, centroids);
    if (mid == end || mid == begin)
    {
      if (bottomUp)
      {
        box = rangeBounds(begin, end, centroids);
      }
      nodes[slot].setBounds(box);
      nodes[slot].index = begin;
      nodes[slot].count = end - begin;
      return;
    }
    nodes[slot].setBounds(box);
    const std::size_t first = nodes.size();
    nodes.resize(first + 2);
    nodes[slot].index = static_cast<std::uint32_t>(first);
    nodes[slot].count = 0;
    const Ranges ranges = { { begin, mid }, { mid, end } };
    buildChildren(nodes, first, ranges, depth);
    if (bottomUp)
    {
      box = nodes[first].bounds();
      box.extend(nodes[first + 1].bounds());
      nodes[slot].setBounds(box);
    }
  }

  /// Builds the two children of a node at `depth` into nodes[first] and
  /// nodes[first + 1]: the small ones first, on this thread; two task
  /// children each into its own array, in parallel, then spliced in order.
  /// Every other task child is built straight into `nodes`: its nodes are
  /// appended in exactly the order a splice would put them (same layout, no
  /// copy of the subtree).
  void buildChildren(std::vector<BVHNode>& nodes, std::size_t first, const Ranges& ranges, std::uint32_t depth)
  {
    bool isTask[2];
    for (int c = 0; c < 2; ++c)
    {
      isTask[c] = ranges[c][1] - ranges[c][0] >= kTaskPrimitives;
      if (!isTask[c])
      {
        buildNode(nodes, first + c, ranges[c][0], ranges[c][1], depth + 1);
      }
    }
    if (isTask[0] && isTask[1])
    {
      // Through the pool only near the root: each pooled level copies its
      // subtrees once more in the splices, and a few levels make enough tasks.
      if (Options.parallelFor && depth < kPooledDepth)
      {
        buildPooled(nodes, first, ranges, depth);
        return;
      }
      if (buildOnTwoThreads(nodes, first, ranges, depth))
      {
        return;
      }
    }
    for (int c = 0; c < 2; ++c)
    {
      if (isTask[c])
      {
        buildNode(nodes, first + c, ranges[c][0], ranges[c][1], depth + 1);
      }
    }
  }

  /// Both children through the options' parallelFor.
  void buildPooled(std::vector<BVHNode>& nodes, std::size_t first, const Ranges& ranges, std::uint32_t depth)
  {
    std::vector<BVHNode> sub[2];
    // Storage from this thread: a pool worker's malloc arena hands large
    // blocks back to the system, which faults them in again next build.
    for (int c = 0; c < 2; ++c)
    {
      sub[c].reserve(nodeEstimate(ranges[c][1] - ranges[c][0]));
    }
    Options.parallelFor(2, [this, &sub, &ranges, depth](std::size_t b, std::size_t e) {
      for (std::size_t c = b; c < e; ++c)
      {
        sub[c].resize(1);
        buildNode(sub[c], 0, ranges[c][0], ranges[c][1], depth + 1);
      }
    });
    splice(nodes, first, sub[0]);
    splice(nodes, first + 1, sub[1]);
  }

  /// The first child on a thread of its own, the second on this one, when
  /// the thread budget and the system give a thread; false (nothing built)
  /// when not.
  bool buildOnTwoThreads(std::vector<BVHNode>& nodes, std::size_t first, const Ranges& ranges, std::uint32_t depth)
  {
    if (FreeThreads.fetch_sub(1) <= 0)
    {
      FreeThreads.fetch_add(1);
      return false;
    }
    std::vector<BVHNode> sub[2];
    std::thread worker;
    try
    {
      worker = std::thread([this, &sub, &ranges, depth]() {
        sub[0].resize(1);
        buildNode(sub[0], 0, ranges[0][0], ranges[0][1], depth + 1);
      });
    }
    catch (const std::system_error&)
    {
      // No thread available from the system: the caller builds inline (same output).
      FreeThreads.fetch_add(1);
      return false;
    }
    sub[1].resize(1);
    buildNode(sub[1], 0, ranges[1][0], ranges[1][1], depth + 1);
    worker.join();
    FreeThreads.fetch_add(1);
    splice(nodes, first, sub[0]);
    splice(nodes, first + 1, sub[1]);
    return true;
  }

  /// Moves a subtree built with its root at sub[0] into nodes[slot] (root)
  /// and the end of `nodes` (the rest), renumbering child indices.
  static void splice(std::vector<BVHNode>& nodes, std::size_t slot, std::vector<BVHNode>& sub)
  {
    const std::size_t base = nodes.size();
    auto remap = [base](BVHNode n) {
      if (!n.isLeaf())
      {
        n.index = static_cast<std::uint32_t>(base + n.index - 1);
      }
      return n;
    };
    nodes[slot] = remap(sub[0]);
    // Grow geometrically: reserving the exact size at every splice would
    // copy the whole array once per task.
    const std::size_t needed = base + sub.size() - 1;
    if (nodes.capacity() < needed)
    {
      nodes.reserve(std::max(needed, 2 * nodes.capacity()));
    }
    for (std::size_t i = 1; i < sub.size(); ++i)
    {
      nodes.push_back(remap(sub[i]));
    }
    std::vector<BVHNode>().swap(sub);
  }
};

} // namespace vtkrt::core::detail

#endif
