// The top-down recursion every builder shares: split a range of references
// in two, build both halves. A builder derives from TopDownBuilder<Itself>
// (no virtual calls in the recursion) and says where to split (see "What a
// builder provides" below).
//
// Parallelism in two phases. The top phase splits the ranges larger than
// the task size one level at a time, the ranges of a level at once, each
// pass over a large range (bounds, bins) in parallel chunks too; every
// range it leaves at or under the task size becomes a task. The tasks' subtrees are then built at once, each
// into its own part of the tree's array (room for the most nodes it can
// make), then moved down after the top nodes in task order: no array a
// task, no second array to join them in (fresh memory pages are dear on
// some machines), the pages past the tree given back.
//
// Determinism: the tree depends only on the input, never on the thread
// count: the task size depends on the primitive count only, and the
// parallel passes merge bounds and counts (exact in any order).
#ifndef vtkrt_core_build_TopDownBuilder_h
#define vtkrt_core_build_TopDownBuilder_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/build/BuildRef.h"
#include "vtkrt/core/build/NodeFormats.h"
#include "vtkrt/core/build/Parallel.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
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

/// What a builder provides (private, with its TopDownBuilder a friend):
///   static constexpr bool kBottomUpBounds: node boxes merged from the
///     children (a leaf's from leafBox) instead of the split's bounds;
///   static constexpr bool kSplitNeedsBounds: splitBounds(begin, end) is
///     passed to the split (else default bounds);
///   void prepare(), void finish(): before and after the recursion;
///   const Ref& refAt(pos) const: the primitive at position pos;
///   void prefetchAfter(pos) const: optional, fetch refAt(pos + a few) early;
///   splitBounds(begin, end), leafBox(begin, end): optional, by default
///     from a pass over the double references (RangeBounds, its box);
///   medianSplit(begin, end, bounds): the split at the depth cap;
///   split(begin, end, bounds): the builder's own split, or `end` for a
///     leaf.
///
/// Format (NodeFormats.h) says what the nodes are and how their boxes are
/// written and merged.
template <class Builder, class Ref = BuildRef, class Format = DoubleNodes>
class TopDownBuilder
{
public:
  using Node = typename Format::Node;
  using Nodes = HugePageArray<Node>;

  /// The smallest task size: smaller subtrees are not worth a task.
  static constexpr std::size_t kTaskPrimitives = 16384;
  /// The top phase stops at ranges of 1/kTopTasks of the primitives, enough
  /// tasks to balance any thread count this runs on.
  static constexpr std::size_t kTopTasks = 64;

  TopDownBuilder(HugePageArray<Ref>& refs, const BuildOptions& options, const Format& format = Format())
    : Refs(refs)
    , Options(options)
    , NodeFormat(format)
  {
    if (Options.maxLeafSize < 1)
    {
      Options.maxLeafSize = 1;
    }
  }

  /// The id of the primitive at leaf position pos (after build()).
  std::uint32_t idAt(std::uint32_t pos) const { return self().refAt(pos).id; }

  Nodes build()
  {
    if (Refs.empty())
    {
      return Nodes();
    }
    self().prepare();
    const std::size_t n = Refs.size();
    TaskSize = std::max(kTaskPrimitives, n / kTopTasks);
    std::vector<Task> tasks;
    Nodes top(1);
    TopPhase = true;
    buildTop(top, tasks);
    TopPhase = false;
    Nodes nodes = placeTasks(top, tasks);
    runTasks(tasks);
    joinTasks(nodes, top.size(), tasks);
    self().finish();
    return nodes;
  }

protected:
  HugePageArray<Ref>& Refs;
  BuildOptions Options;
  Format NodeFormat;

  void prefetchAfter(std::uint32_t) const {}

  /// fn(b, e) over [begin, end): in parallel chunks (any split) for a large
  /// range of the top phase, else once on this thread. fn must merge its
  /// results commutatively and exactly (bounds, counts) and be safe to run
  /// concurrently.
  template <class Fn>
  void forChunks(std::uint32_t begin, std::uint32_t end, Fn&& fn) const
  {
    if (!TopPhase || end - begin < 4 * kMinChunk)
    {
      fn(begin, end);
      return;
    }
    parallelChunks(end - begin, Options,
      [&](std::size_t b, std::size_t e) { fn(begin + static_cast<std::uint32_t>(b), begin + static_cast<std::uint32_t>(e)); });
  }

  /// The box of [begin, end), with the box of its centroids in `centroids`.
  AABB<double> rangeBounds(std::uint32_t begin, std::uint32_t end, AABB<double>& centroids) const
  {
    AABB<double> box;
    std::mutex merge;
    forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e) {
      AABB<double> chunkBox, chunkCentroids;
      for (std::uint32_t i = b; i < e; ++i)
      {
        self().prefetchAfter(i);
        const BuildRef& r = self().refAt(i);
        extendBox(chunkBox, r.box);
        extendBox(chunkCentroids, r.centroid());
      }
      std::lock_guard<std::mutex> lock(merge);
      box.extend(chunkBox);
      centroids.extend(chunkCentroids);
    });
    return box;
  }

  RangeBounds splitBounds(std::uint32_t begin, std::uint32_t end) const
  {
    RangeBounds bounds;
    bounds.box = rangeBounds(begin, end, bounds.centroids);
    return bounds;
  }

  AABB<double> leafBox(std::uint32_t begin, std::uint32_t end) const
  {
    AABB<double> centroids;
    return rangeBounds(begin, end, centroids);
  }

private:
  /// A task's nodes (root first, child indices into them), in its own
  /// part of the tree's array: room for the most nodes its range can make.
  struct TaskNodes
  {
    Node* first = nullptr;
    std::size_t used = 0;
    Node& operator[](std::size_t i) { return first[i]; }
    const Node& operator[](std::size_t i) const { return first[i]; }
    std::size_t size() const { return used; }
    /// A node setNode then writes in full.
    void emplace_back() { ::new (static_cast<void*>(first + used++)) Node; }
  };

  /// A subtree built apart: its range, where its root goes in the top
  /// nodes, and its nodes.
  struct Task
  {
    std::size_t slot;
    std::uint32_t begin, end, depth;
    TaskNodes nodes;
  };

  std::size_t TaskSize = kTaskPrimitives;
  bool TopPhase = false;

  Builder& self() { return static_cast<Builder&>(*this); }
  const Builder& self() const { return static_cast<const Builder&>(*this); }

  /// Where to split [begin, end), or `end` for a leaf.
  template <class Bounds>
  std::uint32_t chooseSplit(std::uint32_t begin, std::uint32_t end, std::uint32_t depth, const Bounds& bounds)
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
      return self().medianSplit(begin, end, bounds);
    }
    return self().split(begin, end, bounds);
  }

  /// Where [begin, end) splits (`end`: a leaf) and its box (empty for an
  /// interior node when kBottomUpBounds). Safe to run concurrently on
  /// disjoint ranges.
  std::uint32_t splitRange(std::uint32_t begin, std::uint32_t end, std::uint32_t depth, AABB<double>& box)
  {
    decltype(self().splitBounds(begin, end)) bounds{};
    if constexpr (Builder::kSplitNeedsBounds)
    {
      bounds = self().splitBounds(begin, end);
    }
    std::uint32_t mid = chooseSplit(begin, end, depth, bounds);
    mid = mid == begin ? end : mid;
    if constexpr (Builder::kBottomUpBounds)
    {
      box = mid == end ? self().leafBox(begin, end) : AABB<double>();
    }
    else
    {
      box = bounds.box;
    }
    return mid;
  }

  /// nodes[slot] for [begin, end) split at mid with `box`: a leaf when mid
  /// is `end`, else an interior node whose two children are appended (its
  /// box merged from theirs later when kBottomUpBounds).
  template <class NodeArray>
  void setNode(NodeArray& nodes, std::size_t slot, std::uint32_t begin, std::uint32_t mid,
    std::uint32_t end, const AABB<double>& box) const
  {
    if (mid == end || !Builder::kBottomUpBounds)
    {
      NodeFormat.write(nodes[slot], box);
    }
    if (mid == end)
    {
      nodes[slot].index = begin;
      nodes[slot].count = end - begin;
      return;
    }
    const std::size_t first = nodes.size();
    nodes.emplace_back();
    nodes.emplace_back();
    nodes[slot].index = static_cast<std::uint32_t>(first);
    nodes[slot].count = 0;
  }

  /// Splits [begin, end) into nodes[slot] and, when it is an interior node,
  /// appends its two children; returns the split (`end` for a leaf, whose
  /// node is then complete).
  template <class NodeArray>
  std::uint32_t splitNode(NodeArray& nodes, std::size_t slot, std::uint32_t begin,
    std::uint32_t end, std::uint32_t depth)
  {
    AABB<double> box;
    const std::uint32_t mid = splitRange(begin, end, depth, box);
    setNode(nodes, slot, begin, mid, end, box);
    return mid;
  }

  /// Builds the subtree of [begin, end) into nodes[slot] and nodes appended
  /// to `nodes` (depth first), on this thread.
  template <class NodeArray>
  void buildNode(NodeArray& nodes, std::size_t slot, std::uint32_t begin, std::uint32_t end,
    std::uint32_t depth)
  {
    const std::uint32_t mid = splitNode(nodes, slot, begin, end, depth);
    if (mid == end)
    {
      return;
    }
    const std::size_t first = nodes[slot].index;
    buildNode(nodes, first, begin, mid, depth + 1);
    buildNode(nodes, first + 1, mid, end, depth + 1);
    if (Builder::kBottomUpBounds)
    {
      mergeChildBounds(nodes, slot);
    }
  }

  /// A range of the top phase waiting for its split, and where its node goes.
  struct Range
  {
    std::size_t slot;
    std::uint32_t begin, end, depth;
  };

  /// The top phase, one level at a time: the ranges of a level over the
  /// task size are split at once (on the pool, each on one thread, its
  /// passes in parallel chunks when large), their nodes then appended to
  /// `top` in level order; each range at or under the task size becomes a
  /// task whose root goes in top[slot].
  void buildTop(Nodes& top, std::vector<Task>& tasks)
  {
    std::vector<Range> level{ Range{ 0, 0, static_cast<std::uint32_t>(Refs.size()), 0 } };
    while (!level.empty())
    {
      std::vector<Range> large;
      std::size_t work = 0;
      for (const Range& r : level)
      {
        if (r.end - r.begin <= TaskSize)
        {
          tasks.push_back(Task{ r.slot, r.begin, r.end, r.depth, TaskNodes{} });
          continue;
        }
        large.push_back(r);
        work += r.end - r.begin;
      }
      std::vector<std::uint32_t> mids(large.size());
      std::vector<AABB<double>> boxes(large.size());
      parallelChunks(large.size(), Options, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i)
        {
          mids[i] = splitRange(large[i].begin, large[i].end, large[i].depth, boxes[i]);
        }
      }, work);
      std::vector<Range> next;
      for (std::size_t i = 0; i < large.size(); ++i)
      {
        const Range& r = large[i];
        setNode(top, r.slot, r.begin, mids[i], r.end, boxes[i]);
        if (mids[i] != r.end)
        {
          const std::size_t first = top[r.slot].index;
          next.push_back(Range{ first, r.begin, mids[i], r.depth + 1 });
          next.push_back(Range{ first + 1, mids[i], r.end, r.depth + 1 });
        }
      }
      level.swap(next);
    }
  }

  void buildTask(Task& task)
  {
    task.nodes.emplace_back();
    buildNode(task.nodes, 0, task.begin, task.end, task.depth);
  }

  /// Builds every task, in parallel (options.parallelFor, else up to
  /// numThreads threads taking the next task), largest first.
  void runTasks(std::vector<Task>& tasks)
  {
    std::vector<std::size_t> order(tasks.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(), [&tasks](std::size_t a, std::size_t b) {
      return tasks[a].end - tasks[a].begin > tasks[b].end - tasks[b].begin;
    });
    if (Options.parallelFor && tasks.size() > 1)
    {
      Options.parallelFor(tasks.size(), [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i)
        {
          buildTask(tasks[order[i]]);
        }
      });
      return;
    }
    // Own threads, each taking the next task until none is left.
    const unsigned threads = Options.numThreads ? Options.numThreads : std::thread::hardware_concurrency();
    const std::size_t workers = std::min<std::size_t>(tasks.size(), std::max(1u, threads));
    std::atomic<std::size_t> next{ 0 };
    auto work = [&](std::size_t, std::size_t) {
      for (std::size_t i = next++; i < tasks.size(); i = next++)
      {
        buildTask(tasks[order[i]]);
      }
    };
    parallelChunks(workers, threads, work, Refs.size());
  }

  /// The tree's array: the top nodes, then a part for each task, in task
  /// order (the layout does not depend on which thread builds what), with
  /// room for the most nodes its range can make. One array for all: the
  /// tasks write in place (no array a task, no second array to join them
  /// in), and it is large enough for huge pages; its nodes are not
  /// initialized. With 4 KiB pages a part's pages past its nodes are never
  /// touched; with huge pages a part's first write commits a whole huge
  /// page, so most of the array is committed until joinTasks gives back
  /// what lies past the tree.
  Nodes placeTasks(const Nodes& top, std::vector<Task>& tasks) const
  {
    std::size_t capacity = top.size();
    for (const Task& t : tasks)
    {
      capacity += 2 * std::size_t(t.end - t.begin);
    }
    Nodes nodes(capacity);
    std::copy(top.begin(), top.end(), nodes.begin());
    std::size_t offset = top.size();
    for (Task& t : tasks)
    {
      t.nodes = TaskNodes{ nodes.data() + offset, 0 };
      offset += 2 * std::size_t(t.end - t.begin);
    }
    return nodes;
  }

  /// Moves each task's nodes but its root (which replaces its slot) down
  /// after the top nodes and the tasks before it, child indices renumbered;
  /// the array then ends at the tree's last node (giveBackPastSize).
  void joinTasks(Nodes& nodes, std::size_t topCount, std::vector<Task>& tasks) const
  {
    std::size_t next = topCount;
    for (Task& t : tasks)
    {
      // The part's nodes move down (next <= their place), in order.
      const std::size_t base = next;
      auto remap = [base](Node node) {
        if (node.count == 0)
        {
          node.index = static_cast<std::uint32_t>(base + node.index - 1);
        }
        return node;
      };
      nodes[t.slot] = remap(t.nodes[0]);
      for (std::size_t i = 1; i < t.nodes.size(); ++i)
      {
        nodes[next++] = remap(t.nodes[i]);
      }
    }
    nodes.resize(next);
    giveBackPastSize(nodes);
    if (Builder::kBottomUpBounds)
    {
      // The top's boxes from their children, which come after them.
      for (std::size_t i = topCount; i-- > 0;)
      {
        if (nodes[i].count == 0)
        {
          mergeChildBounds(nodes, i);
        }
      }
    }
  }

  template <class NodeArray>
  void mergeChildBounds(NodeArray& nodes, std::size_t slot) const
  {
    const std::size_t first = nodes[slot].index;
    NodeFormat.merge(nodes[slot], nodes[first], nodes[first + 1]);
  }
};

} // namespace vtkrt::core::detail

#endif
