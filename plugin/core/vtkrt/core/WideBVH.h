// The direct builder of the eight-wide BVH (WideNode.h) for CPU ray
// queries.
//
// LazyWideBVH writes this tree directly, without a binary tree to collapse,
// and builds most of it only when a query first reaches it (a first pick
// waits for the build; one ray meets a few percent of a big mesh):
// 1. build(): each primitive's box center goes to a bucket, a cell of a
//    2^L x 2^L x 2^L grid over the given bounds (a Morton prefix of 3L
//    bits); the primitives are scattered into bucket order (stable) and
//    each bucket's box is gathered on the way. The levels above the buckets
//    split bucket ranges at the highest differing bucket-index bit (the
//    LBVH rule on the prefix); a bucket is a slot marked kWideSubtree.
// 2. subtree(k), at the first query that reaches bucket k (or all of them,
//    in parallel, from buildAll()): the bucket sorts its primitives by a
//    30-bit Morton code relative to its own centroid bounds (an outlier far
//    away costs no resolution inside), then builds its subtree: LBVH splits
//    at the highest differing code bit, the largest child split again until
//    a node has eight children. The adapter puts each leaf's primitives in
//    their final slots (placeLeaf) and returns the leaf's float box.
// The tree depends only on the input (ties in a code keep primitive id
// order), never on the thread count or on which queries came first.
#ifndef vtkrt_core_WideBVH_h
#define vtkrt_core_WideBVH_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHBuild.h" // expandBits21, parallelChunks
#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/WideNode.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>
#include <cstdint>
#include <limits>
#include <vector>

namespace vtkrt::core
{

namespace detail
{

/// What a subtree is to its parent's slot.
struct WideChildRef
{
  std::uint32_t child = 0; ///< node index (count 0) or first slot
  std::uint32_t count = 0;
  std::uint32_t depth = 0; ///< wide levels below it (0 for a leaf)
  float lo[3] = { std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
    std::numeric_limits<float>::infinity() };
  float hi[3] = { -std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::infinity() };

  void merge(const WideChildRef& o)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], o.lo[a]);
      hi[a] = std::max(hi[a], o.hi[a]);
    }
  }
};

/// Morton code of p with `bits` bits per axis (<= 10) on the grid `scale`
/// cells over [lo, ...]; outside points clamp to the border cells.
inline std::uint32_t mortonCode(const Vec3<double>& p, const Vec3<double>& lo, const Vec3<double>& scale, int bits)
{
  const double top = double((1u << bits) - 1);
  std::uint32_t code = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double q = std::min(std::max((p[a] - lo[a]) * scale[a], 0.0), top); // NaN -> 0
    code |= static_cast<std::uint32_t>(expandBits21(static_cast<std::uint64_t>(q))) << (2 - a);
  }
  return code;
}

inline Vec3<double> mortonScale(const AABB<double>& box, int bits)
{
  const Vec3<double> ext = box.diagonal();
  Vec3<double> scale(0.0);
  for (int a = 0; a < 3; ++a)
  {
    // Just below 2^bits cells so that the max lands in the last cell.
    scale[a] = ext[a] > 0.0 ? double(1u << bits) * (1.0 - 1e-9) / ext[a] : 0.0;
  }
  return scale;
}

/// The index of the highest set bit of x != 0.
inline int highestBit(std::uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
  return 31 - __builtin_clz(x);
#else
  int b = 31;
  while (!(x >> b & 1u))
  {
    --b;
  }
  return b;
#endif
}

} // namespace detail

/// Builds an eight-wide tree over n primitives, mostly on demand (see the
/// top of this file). Prims (copied in, so it must hold pointers) provides:
///   AABB<double> bounds(std::uint32_t id) const  -- finite; its center is
///     the primitive's centroid;
///   void placeLeaf(const std::uint32_t* ids, std::uint32_t begin,
///     std::uint32_t end, float lo[3], float hi[3])  -- primitives ids[0],
///     ids[1], ... go to slots begin, ..., end - 1; lo/hi receive a float
///     box, rounded outward, that holds them; called once per slot, from
///     several threads at once for distinct slots;
///   void prefetch(std::uint32_t id, int stage) const  -- a hint: id's data
///     is read soon (stage 0: in about 16 reads, 1: in about 8).
/// subtree() and buildAll() may run from several threads at once.
template <class Prims>
class LazyWideBVH
{
public:
  /// Deeper than this below a bucket's root, ranges split at the middle:
  /// each level then at least halves the largest child, so no path is
  /// longer than 12 bucket levels + 20 + 32 (within kMaxStackSize).
  static constexpr std::uint32_t kMidSplitDepth = 20;

  using Subtree = WideSubtree;

  LazyWideBVH(const Prims& prims, const BuildOptions& options)
    : P(prims)
    , LeafSize(std::max<std::uint32_t>(1, options.maxLeafSize))
    , Options(options)
  {
  }
  LazyWideBVH(const LazyWideBVH&) = delete;
  LazyWideBVH& operator=(const LazyWideBVH&) = delete;

  /// The eager part: buckets and the levels above them. `bounds` should
  /// hold every centroid (others clamp to the border buckets).
  void build(std::size_t n, const AABB<double>& bounds)
  {
    const auto start = std::chrono::steady_clock::now();
    Top.clear();
    if (n == 0)
    {
      return;
    }
    // About 2048 primitives a bucket: it stays in cache while it is built.
    int levels = 0;
    while (levels < 4 && (std::size_t(2048) << (3 * levels + 2)) <= n)
    {
      ++levels;
    }
    const std::uint32_t buckets = 1u << (3 * levels);
    bucketize(static_cast<std::uint32_t>(n), bounds, levels, buckets);
    BucketNodes.assign(buckets, std::vector<WideNode>());
    State.reset(new std::atomic<std::uint8_t>[buckets]);
    for (std::uint32_t k = 0; k < buckets; ++k)
    {
      State[k].store(0, std::memory_order_relaxed);
    }
    Subtrees = 0;
    for (std::uint32_t k = 0; k < buckets; ++k)
    {
      Subtrees += Start[k + 1] > Start[k] ? 1 : 0;
    }
    BuiltBuckets = 0;
    BuiltNodes = 0;
    BuiltLeaves = 0;
    BuiltDepth = 0;
    detail::WideChildRef root = buildTop(0, buckets);
    if (root.count > 0)
    {
      // One bucket: a root node with that one slot.
      WideNodeDraft node;
      node.clear();
      node.setBox(0, root.lo, root.hi);
      node.child[0] = root.child;
      node.count[0] = root.count;
      Top.push_back(node.pack());
    }
    TopDepth = Top.empty() ? 0 : std::max<std::uint32_t>(1, root.depth);
    BuildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  /// The levels above the buckets; the root is nodes()[0]. Empty: no
  /// primitive.
  const std::vector<WideNode>& nodes() const { return Top; }

  /// Subtree k, built first if no query has reached it yet (other threads
  /// asking for it meanwhile wait for that build).
  Subtree subtree(std::uint32_t k)
  {
    ensure(k, nullptr);
    const detail::WideChildRef& r = BucketRoot[k];
    return { r.count > 0 ? nullptr : BucketNodes[k].data(), r.count > 0 ? r.child : 0u, r.count };
  }

  /// Builds every subtree not built yet, in parallel (options.parallelFor).
  void buildAll()
  {
    if (complete())
    {
      return;
    }
    detail::parallelChunks(BucketRoot.size(), Options, [this](std::size_t b, std::size_t e) {
      Scratch s;
      for (std::size_t k = b; k < e; ++k)
      {
        ensure(static_cast<std::uint32_t>(k), &s);
      }
    }, Start.back());
  }

  bool complete() const { return BuiltBuckets.load(std::memory_order_acquire) == Subtrees; }
  /// Buckets (the range of subtree()'s index), those holding primitives
  /// (the subtrees to build) and those built so far.
  std::size_t bucketCount() const { return BucketRoot.size(); }
  std::size_t subtreeCount() const { return Subtrees; }
  std::size_t builtBuckets() const { return BuiltBuckets.load(); }
  /// Nodes, leaves and depth (wide levels below the root) so far.
  std::size_t nodeCount() const { return Top.size() + BuiltNodes.load(); }
  std::size_t leafCount() const { return BuiltLeaves.load(); }
  std::uint32_t depth() const { return TopDepth + BuiltDepth.load(); }
  double buildSeconds() const { return BuildSeconds; }
  std::size_t memoryBytes() const
  {
    std::size_t bytes = Top.capacity() * sizeof(WideNode) + Order.capacity() * 4 + Start.capacity() * 4 +
      BucketRoot.capacity() * sizeof(detail::WideChildRef) + BucketNodes.capacity() * sizeof(std::vector<WideNode>) +
      BucketRoot.size();
    for (std::size_t k = 0; k < BucketNodes.size(); ++k)
    {
      if (State[k].load(std::memory_order_acquire) == 2)
      {
        bytes += BucketNodes[k].capacity() * sizeof(WideNode);
      }
    }
    return bytes;
  }

private:
  Prims P;
  std::uint32_t LeafSize;
  BuildOptions Options;
  std::vector<WideNode> Top;
  std::uint32_t TopDepth = 0;
  double BuildSeconds = 0.0;
  std::vector<std::uint32_t> Order; ///< primitive id at each slot (bucket order, then leaf order)
  std::vector<std::uint32_t> Start; ///< first slot of each bucket, and n
  std::vector<detail::WideChildRef> BucketRoot; ///< box (from build) and, once built, root
  std::vector<std::vector<WideNode>> BucketNodes; ///< each bucket's nodes, local indices
  std::unique_ptr<std::atomic<std::uint8_t>[]> State; ///< 0 not built, 1 building, 2 built
  std::size_t Subtrees = 0; ///< buckets holding primitives
  std::atomic<std::size_t> BuiltBuckets{ 0 }; ///< of those, built
  std::atomic<std::size_t> BuiltNodes{ 0 };
  std::atomic<std::size_t> BuiltLeaves{ 0 };
  std::atomic<std::uint32_t> BuiltDepth{ 0 };

  struct Scratch
  {
    std::vector<Vec3<double>> centroid;
    std::vector<std::uint64_t> keys, tmp;
    std::vector<std::uint32_t> codes;
    std::size_t leaves = 0;
    const std::uint32_t* ids = nullptr; ///< the bucket's sorted ids (slot base + i)
    std::uint32_t base = 0;             ///< the bucket's first slot
  };

  /// Builds bucket k unless built; waits when another thread builds it.
  void ensure(std::uint32_t k, Scratch* scratch)
  {
    if (State[k].load(std::memory_order_acquire) == 2)
    {
      return;
    }
    std::uint8_t expected = 0;
    if (State[k].compare_exchange_strong(expected, 1, std::memory_order_acq_rel))
    {
      Scratch local;
      buildBucket(k, scratch ? *scratch : local);
      State[k].store(2, std::memory_order_release);
      return;
    }
    while (State[k].load(std::memory_order_acquire) != 2)
    {
      std::this_thread::yield();
    }
  }

  /// Order = primitive ids grouped by bucket (ascending ids within one),
  /// Start = where each bucket begins, BucketRoot = each bucket's box.
  /// Histograms and boxes per fixed chunk: the scatter runs in parallel and
  /// gives the same order for any thread count.
  void bucketize(std::uint32_t n, const AABB<double>& bounds, int levels, std::uint32_t buckets)
  {
    const Vec3<double> scale = detail::mortonScale(bounds, levels);
    const std::uint32_t chunks =
      std::min<std::uint32_t>({ 64, std::max<std::uint32_t>(1, n / 16384), std::max<std::uint32_t>(1, 65536 / buckets) });
    std::vector<std::uint16_t> bucketOf(n);
    std::vector<std::uint32_t> hist(std::size_t(chunks) * buckets, 0);
    std::vector<AABB<double>> boxes(std::size_t(chunks) * buckets);
    detail::parallelChunks(chunks, Options, [&](std::size_t cb, std::size_t ce) {
      for (std::size_t c = cb; c < ce; ++c)
      {
        std::uint32_t* h = hist.data() + c * buckets;
        AABB<double>* box = boxes.data() + c * buckets;
        for (std::uint32_t i = std::uint32_t(c * n / chunks), e = std::uint32_t((c + 1) * n / chunks); i < e; ++i)
        {
          const AABB<double> b = P.bounds(i);
          const std::uint16_t k =
            static_cast<std::uint16_t>(detail::mortonCode(b.center(), bounds.min, scale, levels));
          bucketOf[i] = k;
          h[k]++;
          box[k].extend(b);
        }
      }
    }, n);
    // Offsets: bucket-major, chunk-minor (stable: chunk c's ids after c-1's).
    Start.assign(buckets + 1, 0);
    BucketRoot.assign(buckets, detail::WideChildRef());
    std::uint32_t sum = 0;
    for (std::uint32_t k = 0; k < buckets; ++k)
    {
      Start[k] = sum;
      AABB<double> box;
      for (std::uint32_t c = 0; c < chunks; ++c)
      {
        const std::size_t at = std::size_t(c) * buckets + k;
        const std::uint32_t v = hist[at];
        hist[at] = sum;
        sum += v;
        box.extend(boxes[at]);
      }
      if (!box.isEmpty())
      {
        for (int a = 0; a < 3; ++a)
        {
          BucketRoot[k].lo[a] = detail::floorFloat(box.min[a]);
          BucketRoot[k].hi[a] = detail::ceilFloat(box.max[a]);
        }
      }
    }
    Start[buckets] = sum;
    Order.resize(n);
    detail::parallelChunks(chunks, Options, [&](std::size_t cb, std::size_t ce) {
      for (std::size_t c = cb; c < ce; ++c)
      {
        std::uint32_t* h = hist.data() + c * buckets;
        for (std::uint32_t i = std::uint32_t(c * n / chunks), e = std::uint32_t((c + 1) * n / chunks); i < e; ++i)
        {
          Order[h[bucketOf[i]]++] = i;
        }
      }
    }, n);
  }

  /// Stable LSD radix sort of keys (code << 32 | index) on the 30-bit code.
  static void sortKeys(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& tmp, std::size_t m)
  {
    if (m < 128)
    {
      std::sort(keys.begin(), keys.begin() + m); // indices break ties: same order
      return;
    }
    constexpr int kBits = 10;
    constexpr std::uint32_t kRadix = 1u << kBits;
    tmp.resize(m);
    std::uint32_t h[3][kRadix] = {};
    for (std::size_t i = 0; i < m; ++i)
    {
      const std::uint32_t c = static_cast<std::uint32_t>(keys[i] >> 32);
      h[0][c & (kRadix - 1)]++;
      h[1][(c >> kBits) & (kRadix - 1)]++;
      h[2][(c >> (2 * kBits)) & (kRadix - 1)]++;
    }
    for (int p = 0; p < 3; ++p)
    {
      const int shift = 32 + kBits * p;
      if (h[p][(keys[0] >> shift) & (kRadix - 1)] == m)
      {
        continue; // one digit value: nothing moves
      }
      std::uint32_t sum = 0;
      for (std::uint32_t b = 0; b < kRadix; ++b)
      {
        const std::uint32_t c = h[p][b];
        h[p][b] = sum;
        sum += c;
      }
      for (std::size_t i = 0; i < m; ++i)
      {
        tmp[h[p][(keys[i] >> shift) & (kRadix - 1)]++] = keys[i];
      }
      std::swap_ranges(keys.begin(), keys.begin() + m, tmp.begin());
    }
  }

  void buildBucket(std::uint32_t k, Scratch& s)
  {
    const std::uint32_t b = Start[k], m = Start[k + 1] - b;
    if (m == 0)
    {
      return;
    }
    std::uint32_t* ids = Order.data() + b;
    s.codes.resize(m);
    if (m > LeafSize)
    {
      s.centroid.resize(m);
      AABB<double> cb;
      for (std::uint32_t i = 0; i < m; ++i)
      {
        // The bucket's primitives are spread over the input: fetch ahead.
        if (i + 16 < m)
        {
          P.prefetch(ids[i + 16], 0);
        }
        if (i + 8 < m)
        {
          P.prefetch(ids[i + 8], 1);
        }
        s.centroid[i] = P.bounds(ids[i]).center();
        cb.extend(s.centroid[i]);
      }
      const Vec3<double> scale = detail::mortonScale(cb, 10);
      s.keys.resize(m);
      for (std::uint32_t i = 0; i < m; ++i)
      {
        s.keys[i] = std::uint64_t(detail::mortonCode(s.centroid[i], cb.min, scale, 10)) << 32 | i;
      }
      sortKeys(s.keys, s.tmp, m);
      // Sorted ids through the scratch (ids is read while it is rewritten).
      s.tmp.resize(m);
      for (std::uint32_t j = 0; j < m; ++j)
      {
        s.tmp[j] = ids[static_cast<std::uint32_t>(s.keys[j])];
        s.codes[j] = static_cast<std::uint32_t>(s.keys[j] >> 32);
      }
      for (std::uint32_t j = 0; j < m; ++j)
      {
        ids[j] = static_cast<std::uint32_t>(s.tmp[j]);
      }
    }
    s.leaves = 0;
    s.ids = ids;
    s.base = b;
    std::vector<WideNode>& out = BucketNodes[k];
    out.reserve(m / (2 * LeafSize) + 2);
    const detail::WideChildRef root = buildRange({ b, b + m, false }, 0, s, out);
    // The bucket's box from build() holds the same primitives; keep the
    // tighter one from the leaves.
    BucketRoot[k] = root;
    BuiltNodes += out.size();
    BuiltLeaves += s.leaves;
    std::uint32_t d = BuiltDepth.load();
    while (root.depth > d && !BuiltDepth.compare_exchange_weak(d, root.depth))
    {
    }
    BuiltBuckets.fetch_add(1, std::memory_order_release);
  }

  /// Appends a node to `out` (before its subtrees) whose slots 0..n-1 lead
  /// to child(0), ..., child(n - 1), built in that order; its reference.
  template <class ChildFn>
  static detail::WideChildRef appendNode(std::vector<WideNode>& out, int n, ChildFn&& child)
  {
    const std::uint32_t w = static_cast<std::uint32_t>(out.size());
    out.emplace_back();
    WideNodeDraft node;
    node.clear();
    detail::WideChildRef self;
    self.child = w;
    for (int i = 0; i < n; ++i)
    {
      const detail::WideChildRef c = child(i);
      node.setBox(i, c.lo, c.hi);
      node.child[i] = c.child;
      node.count[i] = c.count;
      self.merge(c);
      self.depth = std::max(self.depth, c.depth + 1);
    }
    out[w] = node.pack(); // after the children: `out` may have grown
    return self;
  }

  /// A range of one bucket's slots; `middle`: split it at the middle
  /// (deep ranges, and their descendants).
  struct Range
  {
    std::uint32_t begin, end;
    bool middle;
  };

  /// Splits r into its two halves: at the first slot whose code has the
  /// highest bit in which the range's codes differ (the LBVH split), at the
  /// middle when they are all equal or r is deep.
  static void splitRange(const Range& r, const Scratch& s, Range& lo, Range& hi)
  {
    const std::uint32_t* c = s.codes.data();
    const std::uint32_t first = c[r.begin - s.base], last = c[r.end - 1 - s.base];
    std::uint32_t mid;
    if (r.middle || first == last)
    {
      mid = r.begin + (r.end - r.begin) / 2;
    }
    else
    {
      const int bit = detail::highestBit(first ^ last);
      mid = s.base +
        static_cast<std::uint32_t>(std::partition_point(c + (r.begin - s.base), c + (r.end - s.base),
                                     [bit](std::uint32_t v) { return !(v >> bit & 1u); }) -
          c);
    }
    lo = { r.begin, mid, r.middle };
    hi = { mid, r.end, r.middle };
  }

  /// The subtree of a bucket's range into `out` (local node indices).
  detail::WideChildRef buildRange(Range range, std::uint32_t depth, Scratch& s, std::vector<WideNode>& out)
  {
    if (range.end - range.begin <= LeafSize)
    {
      s.leaves++;
      detail::WideChildRef r;
      r.child = range.begin;
      r.count = range.end - range.begin;
      P.placeLeaf(s.ids + (range.begin - s.base), range.begin, range.end, r.lo, r.hi);
      return r;
    }
    if (depth >= kMidSplitDepth)
    {
      range.middle = true;
    }
    // Children in slot order: split the largest one again until there are
    // eight (a wide node's worth of binary levels).
    Range r[kWideArity];
    r[0] = range;
    int nr = 1;
    while (nr < kWideArity)
    {
      int best = -1;
      std::uint32_t bestCount = LeafSize;
      for (int i = 0; i < nr; ++i)
      {
        if (r[i].end - r[i].begin > bestCount)
        {
          bestCount = r[i].end - r[i].begin;
          best = i;
        }
      }
      if (best < 0)
      {
        break;
      }
      Range lo, hi;
      splitRange(r[best], s, lo, hi);
      std::copy_backward(r + best + 1, r + nr, r + nr + 1);
      r[best] = lo;
      r[best + 1] = hi;
      ++nr;
    }
    return appendNode(out, nr, [&](int i) { return buildRange(r[i], depth + 1, s, out); });
  }

  /// [b, e) without its empty buckets at either end.
  void shrink(std::uint32_t& b, std::uint32_t& e) const
  {
    while (b < e && Start[b + 1] == Start[b])
    {
      ++b;
    }
    while (e > b && Start[e] == Start[e - 1])
    {
      --e;
    }
  }

  /// The levels over bucket range [kb, ke), into Top; a single bucket is a
  /// slot marked kWideSubtree.
  detail::WideChildRef buildTop(std::uint32_t kb, std::uint32_t ke)
  {
    shrink(kb, ke);
    if (ke - kb == 1)
    {
      detail::WideChildRef r = BucketRoot[kb]; // its box
      r.child = kb;
      r.count = kWideSubtree;
      r.depth = 0;
      return r;
    }
    // Children in bucket order, each without empty end buckets: split the
    // one with the most primitives again until there are eight.
    std::uint32_t rb[kWideArity] = { kb }, re[kWideArity] = { ke };
    int nr = 1;
    while (nr < kWideArity)
    {
      int best = -1;
      std::uint32_t bestCount = 0;
      for (int i = 0; i < nr; ++i)
      {
        const std::uint32_t cnt = Start[re[i]] - Start[rb[i]];
        if (re[i] - rb[i] > 1 && cnt > bestCount)
        {
          bestCount = cnt;
          best = i;
        }
      }
      if (best < 0)
      {
        break;
      }
      // At the highest bit in which the first and last bucket differ: both
      // sides keep a non-empty end bucket.
      const std::uint32_t b = rb[best], e = re[best];
      const std::uint32_t mid = (e - 1) & ~((1u << detail::highestBit(b ^ (e - 1))) - 1);
      std::copy_backward(rb + best + 1, rb + nr, rb + nr + 1);
      std::copy_backward(re + best + 1, re + nr, re + nr + 1);
      rb[best] = b;
      re[best] = mid;
      rb[best + 1] = mid;
      re[best + 1] = e;
      shrink(rb[best], re[best]);
      shrink(rb[best + 1], re[best + 1]);
      ++nr;
    }
    return appendNode(Top, nr, [&](int i) { return buildTop(rb[i], re[i]); });
  }
};

} // namespace vtkrt::core

#endif
