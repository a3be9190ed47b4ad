// BuildQuality::Medium: binned SAH (Wald 2007). Each range's centroids are
// binned on all three axes; the split is the bin boundary of least SAH
// cost, the references partitioned in place. The splits are decided on
// float references (FloatRef.h: half the bytes of double ones, SSE
// passes); every node box is exact, the union of its primitives' double
// boxes (leafBounds(id)), merged up from the leaves.
#ifndef vtkrt_core_build_BinnedSAHBuilder_h
#define vtkrt_core_build_BinnedSAHBuilder_h

#include "vtkrt/core/build/BinBox.h"
#include "vtkrt/core/build/FloatRef.h"
#include "vtkrt/core/build/SAH.h"
#include "vtkrt/core/build/TopDownBuilder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <new>

namespace vtkrt::core::detail
{

/// A range's bounds in the build's frame: its box, and the box of its
/// references' lo + hi (twice their centroids).
struct FloatRangeBounds
{
  BinBox box = BinBox::empty();
  BinBox centroids = BinBox::empty();
};

/// Orders references by lo + hi on one axis, then id (median splits).
struct FloatAxisLess
{
  int axis;
  bool operator()(const FloatRef& a, const FloatRef& b) const
  {
    const float ca = a.centroid2(axis), cb = b.centroid2(axis);
    return ca < cb || (ca == cb && a.id < b.id);
  }
};

template <class LeafBoundsFn, class Format = DoubleNodes>
class BinnedSAHBuilder : public TopDownBuilder<BinnedSAHBuilder<LeafBoundsFn, Format>, FloatRef, Format>
{
  using Base = TopDownBuilder<BinnedSAHBuilder<LeafBoundsFn, Format>, FloatRef, Format>;

public:
  static constexpr std::uint32_t kMaxBins = 64;

  /// leafBounds(id): primitive id's exact box; called from several threads.
  BinnedSAHBuilder(FloatRefs& refs, const BuildOptions& options, const LeafBoundsFn& leafBounds,
    const Format& format = Format())
    : Base(refs, options, format)
    , LeafBounds(leafBounds)
  {
    this->Options.numBins = std::max<std::uint32_t>(2, std::min<std::uint32_t>(this->Options.numBins, kMaxBins));
  }

private:
  friend Base;
  using Base::Options;
  using Base::Refs;

  static constexpr bool kBottomUpBounds = true;
  static constexpr bool kSplitNeedsBounds = true;

  const LeafBoundsFn& LeafBounds;

  struct Bin
  {
    BinBox box;
    std::uint32_t count;
  };

  /// How a range's references map to bins: bin = (lo + hi - min) * scale,
  /// clamped to [0, nb - 1], on the three axes at once.
  struct alignas(16) BinMap
  {
    float min[4];
    float scale[4];
    float last; ///< nb - 1
  };

  /// One node's bins on the three axes. Fixed-size scratch on the stack,
  /// raw storage initialized for the nb bins in use only: no allocation, no
  /// 3 x kMaxBins constructor calls.
  struct Bins
  {
    alignas(Bin) unsigned char storage[3 * kMaxBins * sizeof(Bin)];
    std::uint32_t nb;
    BinMap map;
    bool active[3]; ///< the centroids spread on this axis
    Bin* axis(int a) { return reinterpret_cast<Bin*>(storage) + a * kMaxBins; }
    const Bin* axis(int a) const { return reinterpret_cast<const Bin*>(storage) + a * kMaxBins; }
  };

  /// The best split found so far: before bin `bin` on `axis`.
  struct Candidate
  {
    double cost = std::numeric_limits<double>::infinity();
    int axis = -1;
    std::uint32_t bin = 0;
  };

  const FloatRef& refAt(std::uint32_t pos) const { return Refs[pos]; }
  void prepare() {}
  void finish() {}

  static BinBox boxOf(const FloatRef& r)
  {
    BinBox b;
    std::copy(r.lo, r.lo + 3, b.lo);
    std::copy(r.hi, r.hi + 3, b.hi);
    b.lo[3] = b.hi[3] = 0.0f;
    return b;
  }

  /// The exact box of a leaf's primitives.
  AABB<double> leafBox(std::uint32_t begin, std::uint32_t end) const
  {
    AABB<double> box;
    for (std::uint32_t i = begin; i < end; ++i)
    {
      extendBox(box, LeafBounds(Refs[i].id));
    }
    return box;
  }

  /// [begin, end)'s box and centroid box in the frame (in parallel chunks
  /// for a large range of the top phase). A range too small for the float
  /// steps at its coordinates first gets a frame of its own, so that its
  /// splits are not decided on a coarse grid (siblings' costs are never
  /// compared, so ranges may differ in frame).
  FloatRangeBounds splitBounds(std::uint32_t begin, std::uint32_t end)
  {
    FloatRangeBounds bounds = boundsInFrame(begin, end);
    if (isCoarseInFrame(bounds.box))
    {
      reframe(begin, end);
      bounds = boundsInFrame(begin, end);
    }
    return bounds;
  }

  FloatRangeBounds boundsInFrame(std::uint32_t begin, std::uint32_t end) const
  {
    FloatRangeBounds bounds;
    std::mutex merge;
    this->forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e) {
      FloatRangeBounds chunk;
      for (std::uint32_t i = b; i < e; ++i)
      {
        extendRange(chunk, Refs[i]);
      }
      std::lock_guard<std::mutex> lock(merge);
      bounds.box.extend(chunk.box);
      bounds.centroids.extend(chunk.centroids);
    });
    return bounds;
  }

  /// Whether a box spans fewer than 2^12 float steps of its coordinates.
  static bool isCoarseInFrame(const BinBox& box)
  {
    float extent = 0.0f, magnitude = 0.0f;
    for (int k = 0; k < 3; ++k)
    {
      extent = std::max(extent, box.hi[k] - box.lo[k]);
      magnitude = std::max(magnitude, std::max(std::abs(box.lo[k]), std::abs(box.hi[k])));
    }
    return extent < magnitude * 0x1p-12f;
  }

  /// Rewrites [begin, end)'s references in the frame of their exact box
  /// (which spans [0, 1] there: a range is reframed at most once per factor
  /// 2^12 by which it is smaller than its frame).
  void reframe(std::uint32_t begin, std::uint32_t end)
  {
    AABB<double> exact;
    std::mutex merge;
    this->forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e) {
      const AABB<double> chunk = leafBox(b, e);
      std::lock_guard<std::mutex> lock(merge);
      exact.extend(chunk);
    });
    const RefFrame frame(exact);
    this->forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t i = b; i < e; ++i)
      {
        Refs[i] = frame.toRef(LeafBounds(Refs[i].id), Refs[i].id);
      }
    });
  }

  VTKRT_ALWAYS_INLINE static void extendRange(FloatRangeBounds& bounds, const FloatRef& r)
  {
#if VTKRT_CORE_SSE
    const __m128 lo = _mm_load_ps(r.lo);
    const __m128 hi = _mm_load_ps(r.hi);
    _mm_store_ps(bounds.box.lo, _mm_min_ps(_mm_load_ps(bounds.box.lo), lo));
    _mm_store_ps(bounds.box.hi, _mm_max_ps(_mm_load_ps(bounds.box.hi), hi));
    const __m128 c = centroid2(lo, hi);
    _mm_store_ps(bounds.centroids.lo, _mm_min_ps(_mm_load_ps(bounds.centroids.lo), c));
    _mm_store_ps(bounds.centroids.hi, _mm_max_ps(_mm_load_ps(bounds.centroids.hi), c));
#else
    bounds.box.extend(boxOf(r));
    BinBox c;
    for (int k = 0; k < 3; ++k)
    {
      c.lo[k] = c.hi[k] = r.centroid2(k);
    }
    c.lo[3] = c.hi[3] = 0.0f;
    bounds.centroids.extend(c);
#endif
  }

#if VTKRT_CORE_SSE
  /// lo + hi with lane 3 zero (lo's lane 3 is the id's bits, often a
  /// denormal float, which an addition would make slow).
  VTKRT_ALWAYS_INLINE static __m128 centroid2(__m128 lo, __m128 hi)
  {
    const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
    return _mm_add_ps(_mm_and_ps(lo, xyz), hi);
  }
#endif

  /// r's bins on the three axes: the binning and the partition both use
  /// this, so they agree on every reference.
  VTKRT_ALWAYS_INLINE static void binsOf(const FloatRef& r, const BinMap& map, std::int32_t out[4])
  {
#if VTKRT_CORE_SSE
    const __m128 c = centroid2(_mm_load_ps(r.lo), _mm_load_ps(r.hi));
    __m128 f = _mm_mul_ps(_mm_sub_ps(c, _mm_load_ps(map.min)), _mm_load_ps(map.scale));
    f = _mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), _mm_set1_ps(map.last));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_cvttps_epi32(f));
#else
    for (int k = 0; k < 3; ++k)
    {
      // As maxps then minps: NaN (0 times an infinite scale) goes to 0.
      float f = (r.centroid2(k) - map.min[k]) * map.scale[k];
      f = f > 0.0f ? f : 0.0f;
      f = f < map.last ? f : map.last;
      out[k] = static_cast<std::int32_t>(f);
    }
    out[3] = 0;
#endif
  }

  std::uint32_t medianSplit(std::uint32_t begin, std::uint32_t end, const FloatRangeBounds& bounds)
  {
    const std::uint32_t mid = begin + (end - begin) / 2;
    const int axis = largestAxis(bounds.centroids);
    if (axis >= 0)
    {
      std::nth_element(Refs.begin() + begin, Refs.begin() + mid, Refs.begin() + end, FloatAxisLess{ axis });
    }
    return mid;
  }

  /// The axis of the largest extent, -1 when the box is a point.
  static int largestAxis(const BinBox& b)
  {
    int axis = -1;
    float extent = 0.0f;
    for (int k = 0; k < 3; ++k)
    {
      if (b.hi[k] - b.lo[k] > extent)
      {
        extent = b.hi[k] - b.lo[k];
        axis = k;
      }
    }
    return axis;
  }

  /// The split position, or `end` when a leaf is cheaper (only considered
  /// when the range fits in a leaf).
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const FloatRangeBounds& bounds)
  {
    const std::uint32_t count = end - begin;
    Bins bins;
    // Small ranges get fewer bins: the sweeps cost O(bins) per node.
    bins.nb = std::min(Options.numBins, std::max<std::uint32_t>(2, count));
    fillBins(bins, begin, end, bounds);
    Candidate best;
    for (int axis = 0; axis < 3; ++axis)
    {
      if (bins.active[axis])
      {
        sweepAxis(bins, axis, best);
      }
    }
    if (best.axis < 0)
    {
      return count <= Options.maxLeafSize ? end : medianSplit(begin, end, bounds);
    }
    if (leafIsCheaper(Options, count, best.cost, double(bounds.box.halfArea())))
    {
      return end;
    }
    const int axis = best.axis;
    const auto bin = static_cast<std::int32_t>(best.bin);
    const BinMap& map = bins.map;
    auto it = std::partition(Refs.begin() + begin, Refs.begin() + end, [&](const FloatRef& r) {
      std::int32_t b[4];
      binsOf(r, map, b);
      return b[axis] < bin;
    });
    const std::uint32_t mid = static_cast<std::uint32_t>(it - Refs.begin());
    if (mid == begin || mid == end)
    {
      return medianSplit(begin, end, bounds);
    }
    return mid;
  }

  /// Empties bins.nb bins per axis, then bins [begin, end) on all three
  /// axes in one pass over the primitives (in parallel chunks for a large
  /// range of the top phase, each into bins of its own, merged after).
  void fillBins(Bins& bins, std::uint32_t begin, std::uint32_t end, const FloatRangeBounds& bounds) const
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      const float extent = bounds.centroids.hi[axis] - bounds.centroids.lo[axis];
      bins.active[axis] = extent > 0.0f;
      bins.map.min[axis] = bounds.centroids.lo[axis];
      bins.map.scale[axis] = bins.active[axis] ? static_cast<float>(bins.nb) / extent : 0.0f;
    }
    bins.map.min[3] = bins.map.scale[3] = 0.0f;
    bins.map.last = static_cast<float>(bins.nb - 1);
    clearBins(bins);
    std::mutex merge;
    this->forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e) {
      if (b == begin && e == end)
      {
        binRange(bins, b, e);
        return;
      }
      Bins chunk;
      chunk.nb = bins.nb;
      chunk.map = bins.map;
      std::copy(bins.active, bins.active + 3, chunk.active);
      clearBins(chunk);
      binRange(chunk, b, e);
      std::lock_guard<std::mutex> lock(merge);
      for (int axis = 0; axis < 3; ++axis)
      {
        for (std::uint32_t k = 0; k < bins.nb; ++k)
        {
          bins.axis(axis)[k].box.extend(chunk.axis(axis)[k].box);
          bins.axis(axis)[k].count += chunk.axis(axis)[k].count;
        }
      }
    });
  }

  static void clearBins(Bins& bins)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      Bin* axisBins = bins.axis(axis);
      for (std::uint32_t b = 0; b < bins.nb; ++b)
      {
        new (&axisBins[b]) Bin{ BinBox::empty(), 0u };
      }
    }
  }

  /// Bins [begin, end) into `bins` (map and active in locals: the pass
  /// writes bins, and so never reloads them).
  void binRange(Bins& bins, std::uint32_t begin, std::uint32_t end) const
  {
    const BinMap map = bins.map;
    const bool active[3] = { bins.active[0], bins.active[1], bins.active[2] };
    for (std::uint32_t i = begin; i < end; ++i)
    {
      const FloatRef& r = Refs[i];
      std::int32_t b[4];
      binsOf(r, map, b);
      for (int axis = 0; axis < 3; ++axis)
      {
        if (active[axis])
        {
          Bin& bin = bins.axis(axis)[b[axis]];
          extendBin(bin.box, r);
          bin.count++;
        }
      }
    }
  }

  /// A bin's box extended by a reference's (lane 3 is never read).
  VTKRT_ALWAYS_INLINE static void extendBin(BinBox& box, const FloatRef& r)
  {
#if VTKRT_CORE_SSE
    _mm_store_ps(box.lo, _mm_min_ps(_mm_load_ps(box.lo), _mm_load_ps(r.lo)));
    _mm_store_ps(box.hi, _mm_max_ps(_mm_load_ps(box.hi), _mm_load_ps(r.hi)));
#else
    box.extend(boxOf(r));
#endif
  }

  /// The SAH cost of every bin boundary on `axis` (right sides accumulated
  /// first, then the left ones); keeps the cheapest in `best` (a local copy
  /// during the sweep, in registers).
  static void sweepAxis(const Bins& bins, int axis, Candidate& best)
  {
    const std::uint32_t nb = bins.nb;
    const Bin* axisBins = bins.axis(axis);
    float rightArea[kMaxBins];
    std::uint32_t rightCount[kMaxBins];
    Candidate local = best;
    BinBox acc = BinBox::empty();
    std::uint32_t n = 0;
    for (std::uint32_t b = nb - 1; b > 0; --b)
    {
      acc.extend(axisBins[b].box);
      n += axisBins[b].count;
      rightArea[b] = acc.halfArea();
      rightCount[b] = n;
    }
    acc = BinBox::empty();
    n = 0;
    for (std::uint32_t b = 1; b < nb; ++b)
    {
      acc.extend(axisBins[b - 1].box);
      n += axisBins[b - 1].count;
      if (n == 0 || rightCount[b] == 0)
      {
        continue;
      }
      const double cost = double(acc.halfArea()) * n + double(rightArea[b]) * rightCount[b];
      if (cost < local.cost)
      {
        local.cost = cost;
        local.axis = axis;
        local.bin = b;
      }
    }
    best = local;
  }
};

} // namespace vtkrt::core::detail

#endif
