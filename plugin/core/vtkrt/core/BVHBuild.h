// BVH builders over a generic list of primitive bounds (centroid = box
// center), so one builder serves triangles, spheres and instances.
//
// Determinism: the tree depends only on the input, never on the thread count.
// Subtrees with at least kTaskPrimitives primitives are laid out after the
// parent's smaller children; when two such siblings run on two threads, each
// is built into its own node array and spliced, which appends exactly the
// nodes, in the order, that building both on the calling thread appends.
#ifndef vtkrt_core_BVHBuild_h
#define vtkrt_core_BVHBuild_h

#include "vtkrt/core/BVH.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <new>
#include <system_error>
#include <thread>
#include <utility>

namespace vtkrt::core
{

namespace detail
{

struct BuildRef
{
  AABB<double> box;
  std::uint32_t id;
  Vec3<double> centroid() const { return box.center(); }
};

constexpr std::size_t kMinChunk = 32768;

/// Runs fn(begin, end) over [0, n) split into contiguous chunks, on up to
/// `threads` threads (the calling one included); small ranges stay on the
/// calling thread. fn must be safe to run concurrently on disjoint ranges.
/// `work`: the elements the n chunks cover (n itself when 0), which decides
/// whether threads pay off.
template <class Fn>
void parallelChunks(std::size_t n, unsigned threads, Fn&& fn, std::size_t work = 0)
{
  work = work ? work : n;
  std::size_t t = std::max<std::size_t>(1,
    std::min<std::size_t>({ threads ? threads : std::thread::hardware_concurrency(), work / kMinChunk, n }));
  if (t <= 1)
  {
    fn(std::size_t(0), n);
    return;
  }
  std::vector<std::thread> workers;
  workers.reserve(t - 1);
  std::size_t inlineFrom = t;
  for (std::size_t i = 1; i < t; ++i)
  {
    try
    {
      workers.emplace_back([&fn, i, t, n]() { fn(i * n / t, (i + 1) * n / t); });
    }
    catch (const std::system_error&)
    {
      inlineFrom = i; // no thread from the system: the rest runs here
      break;
    }
  }
  fn(std::size_t(0), n / t);
  for (std::size_t i = inlineFrom; i < t; ++i)
  {
    fn(i * n / t, (i + 1) * n / t);
  }
  for (std::thread& w : workers)
  {
    w.join();
  }
}

/// parallelChunks through the options' parallelFor when they have one.
template <class Fn>
void parallelChunks(std::size_t n, const BuildOptions& options, Fn&& fn, std::size_t work = 0)
{
  if (options.parallelFor && (work ? work : n) >= 2 * kMinChunk && n > 1)
  {
    options.parallelFor(n, [&fn](std::size_t b, std::size_t e) { fn(b, e); });
    return;
  }
  parallelChunks(n, options.parallelFor ? 1u : options.numThreads, fn, work);
}

/// Spreads the low 21 bits of x to every third bit (Morton codes).
inline std::uint64_t expandBits21(std::uint64_t x)
{
  x &= 0x1fffffull;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

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

class Builder
{
public:
  static constexpr std::uint32_t kTaskPrimitives = 16384;
  static constexpr std::uint32_t kPooledDepth = 4;
  static constexpr std::uint32_t kMaxBins = 64;

  Builder(std::vector<BuildRef>& refs, const BuildOptions& options)
    : Refs(refs)
    , Options(options)
  {
    if (Options.maxLeafSize < 1)
    {
      Options.maxLeafSize = 1;
    }
    Options.numBins = std::max<std::uint32_t>(2, std::min<std::uint32_t>(Options.numBins, kMaxBins));
    unsigned threads = Options.numThreads ? Options.numThreads : std::thread::hardware_concurrency();
    FreeThreads = static_cast<int>(std::max(1u, threads)) - 1;
  }

  /// Room for the nodes over `count` primitives: LBVH leaves hold about
  /// half of the leaf size (it splits at Morton bits, not counts), the SAH
  /// builders' nearly all of it. Too little costs a reallocation of the
  /// whole array; the build shrinks it to size at the end.
  std::size_t nodeEstimate(std::size_t count) const
  {
    const std::uint32_t leaf = Options.quality == BuildQuality::Fast
      ? std::max<std::uint32_t>(1, Options.maxLeafSize / 2)
      : Options.maxLeafSize;
    return 2 * count / leaf + 1;
  }

  /// The id of the primitive at leaf position pos (after build()).
  std::uint32_t idAt(std::uint32_t pos) const { return refAt(pos).id; }

  std::vector<BVHNode> build()
  {
    std::vector<BVHNode> nodes;
    if (Refs.empty())
    {
      return nodes;
    }
    if (Options.quality == BuildQuality::Fast)
    {
      sortByMortonCode();
    }
    else if (Options.quality == BuildQuality::High)
    {
      presort();
    }
    nodes.reserve(nodeEstimate(Refs.size()));
    nodes.resize(1);
    buildNode(nodes, 0, 0, static_cast<std::uint32_t>(Refs.size()), 0);
    if (Options.quality == BuildQuality::High)
    {
      finishPresorted();
    }
    std::vector<std::uint64_t>().swap(Codes);
    nodes.shrink_to_fit(); // splices grow it geometrically
    return nodes;
  }

private:
  std::vector<BuildRef>& Refs;
  BuildOptions Options;
  std::atomic<int> FreeThreads{ 0 };
  std::vector<std::uint64_t> Codes; ///< Fast only: Morton codes by position, ascending
  std::vector<std::uint32_t> Perm;  ///< Fast only: Refs index at each position
  std::vector<std::uint32_t> Order[3]; ///< High only: Refs indices sorted per axis, by node range
  std::vector<std::uint8_t> Side;      ///< High only: 1 = goes left in the current split
  std::vector<std::uint32_t> Scratch;  ///< High only: partition buffer (disjoint ranges per task)

  /// Positions ahead whose reference is fetched early where the order goes
  /// through a permutation (Fast): the LBVH reads the references in Morton
  /// order, a random walk over an array of 56 bytes a primitive (at 4M
  /// primitives, a cache and TLB miss per read without it).
  static constexpr std::uint32_t kPrefetchAhead = 16;

  void prefetchRef(std::uint32_t pos) const
  {
#if defined(__GNUC__) || defined(__clang__)
    if (!Perm.empty() && pos < Perm.size())
    {
      __builtin_prefetch(&Refs[Perm[pos]]);
    }
#else
    (void)pos;
#endif
  }

  /// The primitive at position pos of the current order.
  const BuildRef& refAt(std::uint32_t pos) const
  {
    return !Perm.empty() ? Refs[Perm[pos]] : (Order[0].empty() ? Refs[pos] : Refs[Order[0][pos]]);
  }

  /// LBVH preparation (Lauterbach et al. 2009): 63-bit Morton codes of the
  /// centroids in their bounds; Perm lists the refs by (code, id). The refs
  /// themselves never move (a permutation of large refs costs random writes
  /// over the whole array): positions go through Perm.
  void sortByMortonCode()
  {
    const std::size_t n = Refs.size();
    // Centroid bounds in fixed chunks (min/max: exact in any order).
    constexpr std::size_t kChunks = 64;
    std::vector<AABB<double>> chunkBounds(kChunks);
    parallelChunks(kChunks, Options, [&](std::size_t cb0, std::size_t ce0) {
      for (std::size_t c = cb0; c < ce0; ++c)
      {
        AABB<double> box;
        for (std::size_t i = c * n / kChunks, e = (c + 1) * n / kChunks; i < e; ++i)
        {
          box.extend(Refs[i].centroid());
        }
        chunkBounds[c] = box;
      }
    }, n);
    AABB<double> cb;
    for (const AABB<double>& box : chunkBounds)
    {
      cb.extend(box);
    }
    const Vec3<double> ext = cb.diagonal();
    const double cells = double((1u << 21) - 1);
    Vec3<double> scale(0.0);
    for (int k = 0; k < 3; ++k)
    {
      scale[k] = ext[k] > 0.0 ? cells / ext[k] : 0.0;
    }
    Codes.resize(n);
    Perm.resize(n);
    std::atomic<bool> idsAscending{ true };
    parallelChunks(n, Options, [&](std::size_t b, std::size_t e) {
      bool ascending = true;
      for (std::size_t i = b; i < e; ++i)
      {
        const Vec3<double> q = (Refs[i].centroid() - cb.min) * scale;
        std::uint64_t code = 0;
        for (int k = 0; k < 3; ++k)
        {
          const double c = std::min(std::max(q[k], 0.0), cells);
          code |= expandBits21(static_cast<std::uint64_t>(c)) << (2 - k);
        }
        Codes[i] = code;
        Perm[i] = static_cast<std::uint32_t>(i);
        ascending = ascending && (i == 0 || Refs[i - 1].id < Refs[i].id);
      }
      if (!ascending)
      {
        idsAscending = false;
      }
    });
    if (idsAscending)
    {
      // Stable radix sort on the code: ties keep index order = id order.
      radixSortByCode();
    }
    else
    {
      std::sort(Perm.begin(), Perm.end(), [this](std::uint32_t a, std::uint32_t b) {
        return Codes[a] < Codes[b] || (Codes[a] == Codes[b] && Refs[a].id < Refs[b].id);
      });
      std::vector<std::uint64_t> sorted(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        sorted[i] = Codes[Perm[i]];
      }
      Codes.swap(sorted);
    }
  }

  /// Stable sort of (Codes, Perm) by Codes. An LSD radix sort on the top
  /// kPrefixBits (10 per axis: one pass per axis' worth of bits, where a
  /// full 63-bit sort took eight passes), then each run of equal prefixes
  /// longer than one is sorted on the whole code (comparison sort: such runs
  /// are short unless primitives crowd one cell of a 1024^3 grid). Same
  /// order as a full stable sort. Histograms in parallel.
  void radixSortByCode()
  {
    const std::size_t n = Codes.size();
    constexpr int kBits = 8;
    constexpr std::uint32_t kRadix = 1u << kBits;
    constexpr int kPasses = 4;
    constexpr int kShift = 63 - kBits * kPasses; // the prefix is bits [31, 63)
    constexpr std::size_t kChunks = 16;
    std::vector<std::uint32_t> chunkHist(kChunks * kPasses * kRadix, 0);
    parallelChunks(kChunks, Options, [&](std::size_t cb, std::size_t ce) {
      for (std::size_t c = cb; c < ce; ++c)
      {
        std::uint32_t* h = chunkHist.data() + c * kPasses * kRadix;
        for (std::size_t i = c * n / kChunks, e = (c + 1) * n / kChunks; i < e; ++i)
        {
          const std::uint64_t code = Codes[i] >> kShift;
          for (int p = 0; p < kPasses; ++p)
          {
            h[p * kRadix + ((code >> (kBits * p)) & (kRadix - 1))]++;
          }
        }
      }
    }, n);
    std::vector<std::uint32_t> hist(kPasses * kRadix, 0);
    for (std::size_t c = 0; c < kChunks; ++c)
    {
      for (std::size_t k = 0; k < hist.size(); ++k)
      {
        hist[k] += chunkHist[c * kPasses * kRadix + k];
      }
    }
    std::vector<std::uint64_t> codes2(n);
    std::vector<std::uint32_t> perm2(n);
    for (int p = 0; p < kPasses; ++p)
    {
      const int shift = kShift + kBits * p;
      std::uint32_t* h = hist.data() + p * kRadix;
      if (h[(Codes[0] >> shift) & (kRadix - 1)] == n)
      {
        continue;
      }
      std::uint32_t sum = 0;
      for (std::uint32_t b = 0; b < kRadix; ++b)
      {
        const std::uint32_t c = h[b];
        h[b] = sum;
        sum += c;
      }
      for (std::size_t i = 0; i < n; ++i)
      {
        const std::uint32_t dst = h[(Codes[i] >> shift) & (kRadix - 1)]++;
        codes2[dst] = Codes[i];
        perm2[dst] = Perm[i];
      }
      Codes.swap(codes2);
      Perm.swap(perm2);
    }
    // Runs of one prefix: order by the whole code, ties by position (the
    // radix passes kept the input order, which is id order).
    std::vector<std::pair<std::uint64_t, std::uint32_t>> run;
    for (std::size_t b = 0; b < n;)
    {
      std::size_t e = b + 1;
      while (e < n && (Codes[e] >> kShift) == (Codes[b] >> kShift))
      {
        ++e;
      }
      if (e - b > 1)
      {
        run.clear();
        bool sorted = true;
        for (std::size_t i = b; i < e; ++i)
        {
          run.emplace_back(Codes[i], Perm[i]);
          sorted = sorted && (i == b || Codes[i - 1] <= Codes[i]);
        }
        if (!sorted)
        {
          std::stable_sort(run.begin(), run.end(),
            [](const std::pair<std::uint64_t, std::uint32_t>& x,
              const std::pair<std::uint64_t, std::uint32_t>& y) { return x.first < y.first; });
          for (std::size_t i = b; i < e; ++i)
          {
            Codes[i] = run[i - b].first;
            Perm[i] = run[i - b].second;
          }
        }
      }
      b = e;
    }
  }

  /// LBVH split: the first primitive whose code has the highest bit in
  /// which the range's codes differ; the middle when all codes are equal.
  /// Never reorders (sub-ranges stay sorted).
  std::uint32_t mortonSplit(std::uint32_t begin, std::uint32_t end) const
  {
    const std::uint64_t diff = Codes[begin] ^ Codes[end - 1];
    if (diff == 0)
    {
      return begin + (end - begin) / 2;
    }
    int bit = 63;
    while (!(diff >> bit & 1u))
    {
      --bit;
    }
    const auto it = std::partition_point(Codes.begin() + begin, Codes.begin() + end,
      [bit](std::uint64_t c) { return !(c >> bit & 1u); });
    return static_cast<std::uint32_t>(it - Codes.begin());
  }

  AABB<double> rangeBounds(std::uint32_t begin, std::uint32_t end, AABB<double>& centroids) const
  {
    AABB<double> box;
    for (std::uint32_t i = begin; i < end; ++i)
    {
      prefetchRef(i + kPrefetchAhead);
      const BuildRef& r = refAt(i);
      box.extend(r.box);
      centroids.extend(r.centroid());
    }
    return box;
  }

  /// Total order on (centroid[axis], id): makes median splits and sorts
  /// independent of the input order's ties.
  struct AxisLess
  {
    int axis;
    bool operator()(const BuildRef& a, const BuildRef& b) const
    {
      const double ca = a.box.min[axis] + a.box.max[axis];
      const double cb = b.box.min[axis] + b.box.max[axis];
      return ca < cb || (ca == cb && a.id < b.id);
    }
  };

  std::uint32_t medianSplit(std::uint32_t begin, std::uint32_t end, const AABB<double>& centroids)
  {
    const std::uint32_t mid = begin + (end - begin) / 2;
    const Vec3<double> ext = centroids.diagonal();
    if (!Order[0].empty())
    {
      const bool spread = ext.x > 0.0 || ext.y > 0.0 || ext.z > 0.0;
      partitionPresorted(begin, end, spread ? centroids.largestAxis() : 0, mid - begin);
      return mid;
    }
    if (ext.x > 0.0 || ext.y > 0.0 || ext.z > 0.0)
    {
      const int axis = centroids.largestAxis();
      std::nth_element(Refs.begin() + begin, Refs.begin() + mid, Refs.begin() + end, AxisLess{ axis });
    }
    return mid;
  }

  /// Binned SAH (Wald 2007). Returns the split position, or `end` when a leaf
  /// is cheaper (only considered when the range fits in a leaf).
  std::uint32_t binnedSplit(std::uint32_t begin, std::uint32_t end, const AABB<double>& box,
    const AABB<double>& centroids)
  {
    const std::uint32_t count = end - begin;
    // Small ranges get fewer bins: the sweeps below cost O(bins) per node.
    const std::uint32_t nb = std::min(Options.numBins, std::max<std::uint32_t>(2, count));
    struct Bin
    {
      AABB<double> box;
      std::uint32_t count;
    };
    double bestCost = std::numeric_limits<double>::infinity();
    int bestAxis = -1;
    std::uint32_t bestBin = 0;
    // Fixed-size scratch on the stack, raw storage initialized for the nb
    // bins in use only: no allocation, no 3 x kMaxBins constructor calls.
    alignas(Bin) unsigned char binStorage[3 * kMaxBins * sizeof(Bin)];
    Bin(*bins)[kMaxBins] = reinterpret_cast<Bin(*)[kMaxBins]>(binStorage);
    double rightArea[kMaxBins];
    std::uint32_t rightCount[kMaxBins];
    double scale[3];
    bool active[3];
    for (int axis = 0; axis < 3; ++axis)
    {
      const double extent = centroids.max[axis] - centroids.min[axis];
      active[axis] = extent > 0.0;
      scale[axis] = active[axis] ? nb / extent : 0.0;
      for (std::uint32_t b = 0; b < nb; ++b)
      {
        new (&bins[axis][b]) Bin{ AABB<double>(), 0u };
      }
    }
    // One pass over the primitives bins all three axes.
    for (std::uint32_t i = begin; i < end; ++i)
    {
      const BuildRef& r = Refs[i];
      const Vec3<double> c = r.centroid();
      for (int axis = 0; axis < 3; ++axis)
      {
        if (active[axis])
        {
          Bin& bin = bins[axis][binOf(c[axis], centroids.min[axis], scale[axis], nb)];
          bin.box.extend(r.box);
          bin.count++;
        }
      }
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      if (!active[axis])
      {
        continue;
      }
      const Bin* axisBins = bins[axis];
      AABB<double> acc;
      std::uint32_t n = 0;
      for (std::uint32_t b = nb - 1; b > 0; --b)
      {
        acc.extend(axisBins[b].box);
        n += axisBins[b].count;
        rightArea[b] = acc.halfArea();
        rightCount[b] = n;
      }
      acc = AABB<double>();
      n = 0;
      for (std::uint32_t b = 1; b < nb; ++b)
      {
        acc.extend(axisBins[b - 1].box);
        n += axisBins[b - 1].count;
        if (n == 0 || rightCount[b] == 0)
        {
          continue;
        }
        const double cost = acc.halfArea() * n + rightArea[b] * rightCount[b];
        if (cost < bestCost)
        {
          bestCost = cost;
          bestAxis = axis;
          bestBin = b;
        }
      }
    }
    if (bestAxis < 0)
    {
      return count <= Options.maxLeafSize ? end : medianSplit(begin, end, centroids);
    }
    if (leafIsCheaper(count, bestCost, box))
    {
      return end;
    }
    const double lo = centroids.min[bestAxis];
    const double axisScale = scale[bestAxis];
    auto it = std::partition(Refs.begin() + begin, Refs.begin() + end, [&](const BuildRef& r) {
      return binOf(r.centroid()[bestAxis], lo, axisScale, nb) < bestBin;
    });
    const std::uint32_t mid = static_cast<std::uint32_t>(it - Refs.begin());
    if (mid == begin || mid == end)
    {
      return medianSplit(begin, end, centroids);
    }
    return mid;
  }

  /// SAH: whether a leaf over `count` primitives in `box` costs no more
  /// than the best split found (bestCost: the children's half areas times
  /// their counts). Only a range that fits in a leaf may stay one.
  bool leafIsCheaper(std::uint32_t count, double bestCost, const AABB<double>& box) const
  {
    if (count > Options.maxLeafSize)
    {
      return false;
    }
    const double parentArea = box.halfArea();
    const double splitCost = Options.traversalCost +
      Options.intersectionCost * (parentArea > 0.0 ? bestCost / parentArea : double(count));
    return splitCost >= Options.intersectionCost * count;
  }

  static std::uint32_t binOf(double c, double lo, double scale, std::uint32_t nb)
  {
    const double f = (c - lo) * scale;
    const std::uint32_t b = f > 0.0 ? static_cast<std::uint32_t>(f) : 0u;
    return std::min(b, nb - 1);
  }

  /// Full-sweep SAH: every primitive boundary in centroid order on each
  /// axis, over the presorted orders (no sorting per node: O(n log n) in all).
  std::uint32_t sweepSplit(std::uint32_t begin, std::uint32_t end, const AABB<double>& box,
    const AABB<double>& centroids)
  {
    const std::uint32_t count = end - begin;
    std::vector<double> rightArea(count);
    double bestCost = std::numeric_limits<double>::infinity();
    int bestAxis = -1;
    std::uint32_t bestSplit = 0;
    for (int axis = 0; axis < 3; ++axis)
    {
      if (!(centroids.max[axis] > centroids.min[axis]))
      {
        continue;
      }
      const std::uint32_t* order = Order[axis].data() + begin;
      AABB<double> acc;
      for (std::uint32_t i = count - 1; i > 0; --i)
      {
        acc.extend(Refs[order[i]].box);
        rightArea[i] = acc.halfArea();
      }
      acc = AABB<double>();
      for (std::uint32_t i = 1; i < count; ++i)
      {
        acc.extend(Refs[order[i - 1]].box);
        const double cost = acc.halfArea() * i + rightArea[i] * (count - i);
        if (cost < bestCost)
        {
          bestCost = cost;
          bestAxis = axis;
          bestSplit = i;
        }
      }
    }
    if (bestAxis < 0)
    {
      return count <= Options.maxLeafSize ? end : medianSplit(begin, end, centroids);
    }
    if (leafIsCheaper(count, bestCost, box))
    {
      return end;
    }
    partitionPresorted(begin, end, bestAxis, bestSplit);
    return begin + bestSplit;
  }

  /// High only: the first k entries of Order[axis][begin, end) go left; the
  /// other two orders are partitioned the same way, stably, so each stays
  /// sorted within both halves.
  void partitionPresorted(std::uint32_t begin, std::uint32_t end, int axis, std::uint32_t k)
  {
    for (std::uint32_t i = begin; i < end; ++i)
    {
      Side[Order[axis][i]] = i < begin + k ? 1 : 0;
    }
    for (int a = 0; a < 3; ++a)
    {
      if (a == axis)
      {
        continue;
      }
      std::uint32_t* order = Order[a].data();
      std::uint32_t left = begin, right = begin;
      for (std::uint32_t i = begin; i < end; ++i)
      {
        const std::uint32_t r = order[i];
        if (Side[r])
        {
          order[left++] = r;
        }
        else
        {
          Scratch[right++] = r;
        }
      }
      std::copy(Scratch.begin() + begin, Scratch.begin() + right, order + left);
    }
  }

  /// High only: sort the three orders once; Refs stay put until finish.
  void presort()
  {
    const std::uint32_t n = static_cast<std::uint32_t>(Refs.size());
    for (int axis = 0; axis < 3; ++axis)
    {
      Order[axis].resize(n);
      for (std::uint32_t i = 0; i < n; ++i)
      {
        Order[axis][i] = i;
      }
      const AxisLess less{ axis };
      std::sort(Order[axis].begin(), Order[axis].end(),
        [&](std::uint32_t x, std::uint32_t y) { return less(Refs[x], Refs[y]); });
    }
    Side.assign(n, 0);
    Scratch.resize(n);
  }

  /// High only: Refs in leaf order (any of the three orders, they agree on
  /// every leaf range).
  void finishPresorted()
  {
    std::vector<BuildRef> sorted(Refs.size());
    for (std::size_t i = 0; i < Refs.size(); ++i)
    {
      sorted[i] = Refs[Order[0][i]];
    }
    Refs.swap(sorted);
    for (auto& o : Order)
    {
      std::vector<std::uint32_t>().swap(o);
    }
    std::vector<std::uint8_t>().swap(Side);
    std::vector<std::uint32_t>().swap(Scratch);
  }

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
      // Fast keeps Morton order: its middle is a spatial median already.
      return Options.quality == BuildQuality::Fast ? begin + count / 2 : medianSplit(begin, end, centroids);
    }
    switch (Options.quality)
    {
      case BuildQuality::Fast:
        return count <= Options.maxLeafSize ? end : mortonSplit(begin, end);
      case BuildQuality::High:
        return sweepSplit(begin, end, box, centroids);
      case BuildQuality::Medium:
      default:
        return binnedSplit(begin, end, box, centroids);
    }
  }

  /// Builds the subtree of [begin, end) into nodes[slot] and nodes appended
  /// to `nodes`.
  void buildNode(std::vector<BVHNode>& nodes, std::size_t slot, std::uint32_t begin, std::uint32_t end,
    std::uint32_t depth)
  {
    // The LBVH split needs no bounds: its boxes are merged bottom-up
    // (O(n) in total instead of a pass over the range at every level).
    const bool bottomUp = Options.quality == BuildQuality::Fast;
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

    const std::uint32_t ranges[2][2] = { { begin, mid }, { mid, end } };
    bool isTask[2];
    for (int c = 0; c < 2; ++c)
    {
      isTask[c] = ranges[c][1] - ranges[c][0] >= kTaskPrimitives;
      if (!isTask[c])
      {
        buildNode(nodes, first + c, ranges[c][0], ranges[c][1], depth + 1);
      }
    }
    // Two task children: the first may run on another thread, into its own
    // array; the second then goes to its own array too, so that both are
    // spliced in order. Every other task child is built straight into
    // `nodes`: its nodes are appended in exactly the order a splice would
    // put them (same layout, no copy of the subtree).
    bool spawned = false;
    bool pooled = false;
    std::vector<BVHNode> sub[2];
    std::thread worker;
    // Through the pool only near the root: each pooled level copies its
    // subtrees once more in the splices, and a few levels make enough tasks.
    if (isTask[0] && isTask[1] && Options.parallelFor && depth < kPooledDepth)
    {
      pooled = true;
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
    else if (isTask[0] && isTask[1])
    {
      if (FreeThreads.fetch_sub(1) > 0)
      {
        try
        {
          worker = std::thread([this, &sub, &ranges, depth]() {
            sub[0].resize(1);
            buildNode(sub[0], 0, ranges[0][0], ranges[0][1], depth + 1);
          });
          spawned = true;
        }
        catch (const std::system_error&)
        {
          // No thread available from the system: build inline (same output).
        }
      }
      if (!spawned)
      {
        FreeThreads.fetch_add(1);
      }
    }
    if (spawned)
    {
      sub[1].resize(1);
      buildNode(sub[1], 0, ranges[1][0], ranges[1][1], depth + 1);
      worker.join();
      FreeThreads.fetch_add(1);
      splice(nodes, first, sub[0]);
      splice(nodes, first + 1, sub[1]);
    }
    else if (!pooled)
    {
      for (int c = 0; c < 2; ++c)
      {
        if (isTask[c])
        {
          buildNode(nodes, first + c, ranges[c][0], ranges[c][1], depth + 1);
        }
      }
    }
    if (bottomUp)
    {
      box = nodes[first].bounds();
      box.extend(nodes[first + 1].bounds());
      nodes[slot].setBounds(box);
    }
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

} // namespace detail

/// Depth, leaf count and SAH cost of a finished tree (parents precede
/// children in the layout, so one forward pass suffices).
inline void computeTreeStats(BVH& bvh, const BuildOptions& options = BuildOptions())
{
  BuildStats& s = bvh.stats;
  s.nodeCount = bvh.nodes.size();
  s.leafCount = 0;
  s.maxDepth = 0;
  s.maxLeafPrimitives = 0;
  s.sahCost = 0.0;
  if (bvh.nodes.empty())
  {
    return;
  }
  std::vector<std::uint32_t> depth(bvh.nodes.size(), 0);
  const double rootArea = bvh.nodes[0].bounds().halfArea();
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
  {
    const BVHNode& n = bvh.nodes[i];
    const double rel = rootArea > 0.0 ? n.bounds().halfArea() / rootArea : 1.0;
    s.maxDepth = std::max(s.maxDepth, depth[i]);
    if (n.isLeaf())
    {
      s.leafCount++;
      s.maxLeafPrimitives = std::max(s.maxLeafPrimitives, n.count);
      s.sahCost += rel * options.intersectionCost * n.count;
    }
    else
    {
      depth[n.index] = depth[n.index + 1] = depth[i] + 1;
      s.sahCost += rel * options.traversalCost;
    }
  }
}

namespace detail
{
/// The build from filled references (valid boxes only, ascending ids).
inline BVH buildFromRefs(std::vector<BuildRef>& refs, std::size_t count, const BuildOptions& options,
  std::chrono::steady_clock::time_point start)
{
  BVH bvh;
  bvh.stats.inputPrimitives = count;
  bvh.stats.builtPrimitives = refs.size();
  bvh.stats.skippedPrimitives = count - refs.size();
  {
    Builder builder(refs, options);
    bvh.nodes = builder.build();
    bvh.primIndex.resize(refs.size());
    parallelChunks(refs.size(), options, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i)
      {
        bvh.primIndex[i] = builder.idAt(static_cast<std::uint32_t>(i));
      }
    });
  }
  computeTreeStats(bvh, options);
  bvh.stats.buildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}
} // namespace detail

/// Builds a BVH over primitives given by a callable: boundsOf(i) for i in
/// [0, count) returns primitive i's box. Primitives with empty, NaN or
/// infinite bounds are skipped and counted in stats.skippedPrimitives. (No
/// intermediate array of boxes: the builder's references are filled
/// directly.)
template <class BoundsFn>
BVH buildBVH(std::size_t count, BoundsFn&& boundsOf, const BuildOptions& options = BuildOptions())
{
  const auto start = std::chrono::steady_clock::now();
  std::vector<detail::BuildRef> refs;
  refs.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const AABB<double> b = boundsOf(i);
    if (b.isEmpty() || !b.isFinite())
    {
      continue;
    }
    refs.push_back({ b, static_cast<std::uint32_t>(i) });
  }
  return detail::buildFromRefs(refs, count, options, start);
}

/// The same tree as buildBVH(count, boundsOf, options), with boundsOf called
/// from several threads at once (options.numThreads) on disjoint indices: it
/// must be safe to call concurrently (no shared state written).
template <class BoundsFn>
BVH buildBVHConcurrentBounds(std::size_t count, BoundsFn&& boundsOf, const BuildOptions& options = BuildOptions())
{
  const auto start = std::chrono::steady_clock::now();
  std::vector<detail::BuildRef> refs(count);
  std::atomic<bool> allValid{ true };
  detail::parallelChunks(count, options, [&](std::size_t b, std::size_t e) {
    bool valid = true;
    for (std::size_t i = b; i < e; ++i)
    {
      const AABB<double> box = boundsOf(i);
      const bool ok = !box.isEmpty() && box.isFinite();
      refs[i] = { ok ? box : AABB<double>(), static_cast<std::uint32_t>(i) };
      valid = valid && ok;
    }
    if (!valid)
    {
      allValid = false;
    }
  });
  if (!allValid)
  {
    // Drop the skipped ones, keeping the order (what buildBVH's loop does).
    refs.erase(std::remove_if(refs.begin(), refs.end(), [](const detail::BuildRef& r) { return r.box.isEmpty(); }),
      refs.end());
  }
  return detail::buildFromRefs(refs, count, options, start);
}

/// Builds a BVH over primitives given by their bounds (primitive id = index
/// in `bounds`).
inline BVH buildBVH(const std::vector<AABB<double>>& bounds, const BuildOptions& options = BuildOptions())
{
  return buildBVH(bounds.size(), [&bounds](std::size_t i) { return bounds[i]; }, options);
}

/// Refit after the primitives moved (same topology, same validity): leaf
/// boxes from primitiveBounds(id), then interior boxes bottom-up (children
/// always follow their parent in the layout). Quality degrades as the motion
/// grows; rebuild when it matters.
template <class BoundsFn>
void refit(BVH& bvh, BoundsFn&& primitiveBounds)
{
  for (std::size_t i = bvh.nodes.size(); i-- > 0;)
  {
    BVHNode& n = bvh.nodes[i];
    AABB<double> box;
    if (n.isLeaf())
    {
      for (std::uint32_t k = 0; k < n.count; ++k)
      {
        box.extend(primitiveBounds(bvh.primIndex[n.index + k]));
      }
    }
    else
    {
      box = bvh.nodes[n.index].bounds();
      box.extend(bvh.nodes[n.index + 1].bounds());
    }
    n.setBounds(box);
  }
}

} // namespace vtkrt::core

#endif
