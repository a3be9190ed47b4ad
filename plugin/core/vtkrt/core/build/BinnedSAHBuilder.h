// BuildQuality::Medium: binned SAH (Wald 2007). Each range's centroids are
// binned on all three axes; the split is the bin boundary of least SAH
// cost, the references partitioned in place. The bins' boxes are float
// boxes in the range's frame (BinBox.h): the costs are weighed in float,
// everything else (bin indices, partition, node boxes) is double.
#ifndef vtkrt_core_build_BinnedSAHBuilder_h
#define vtkrt_core_build_BinnedSAHBuilder_h

#include "vtkrt/core/build/BinBox.h"
#include "vtkrt/core/build/SAH.h"
#include "vtkrt/core/build/TopDownBuilder.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <mutex>
#include <new>
#include <vector>

namespace vtkrt::core::detail
{

class BinnedSAHBuilder : public TopDownBuilder<BinnedSAHBuilder>
{
public:
  static constexpr std::uint32_t kMaxBins = 64;

  BinnedSAHBuilder(BuildRefs& refs, const BuildOptions& options)
    : TopDownBuilder(refs, options)
  {
    Options.numBins = std::max<std::uint32_t>(2, std::min<std::uint32_t>(Options.numBins, kMaxBins));
  }

private:
  friend class TopDownBuilder<BinnedSAHBuilder>;

  static constexpr bool kBottomUpBounds = false;

  struct Bin
  {
    BinBox box;
    std::uint32_t count;
  };

  /// One node's bins on the three axes. Fixed-size scratch on the stack,
  /// raw storage initialized for the nb bins in use only: no allocation, no
  /// 3 x kMaxBins constructor calls.
  struct Bins
  {
    alignas(Bin) unsigned char storage[3 * kMaxBins * sizeof(Bin)];
    std::uint32_t nb;
    double scale[3];
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

  const BuildRef& refAt(std::uint32_t pos) const { return Refs[pos]; }
  void prepare() {}
  void finish() {}

  std::uint32_t medianSplit(std::uint32_t begin, std::uint32_t end, const AABB<double>& centroids)
  {
    const std::uint32_t mid = begin + (end - begin) / 2;
    const Vec3<double> ext = centroids.diagonal();
    if (ext.x > 0.0 || ext.y > 0.0 || ext.z > 0.0)
    {
      const int axis = centroids.largestAxis();
      std::nth_element(Refs.begin() + begin, Refs.begin() + mid, Refs.begin() + end, AxisLess{ axis });
    }
    return mid;
  }

  /// The split position, or `end` when a leaf is cheaper (only considered
  /// when the range fits in a leaf).
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const AABB<double>& box, const AABB<double>& centroids)
  {
    const std::uint32_t count = end - begin;
    Bins bins;
    // Small ranges get fewer bins: the sweeps cost O(bins) per node.
    bins.nb = std::min(Options.numBins, std::max<std::uint32_t>(2, count));
    const BinFrame frame(box);
    fillBins(bins, begin, end, centroids, frame);
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
      return count <= Options.maxLeafSize ? end : medianSplit(begin, end, centroids);
    }
    // Decided in the frame: the box's area there is at most 3 at any scale.
    if (leafIsCheaper(Options, count, best.cost, double(frame.toBin(box).halfArea())))
    {
      return end;
    }
    const int axis = best.axis;
    const std::uint32_t bin = best.bin;
    const double lo = centroids.min[axis];
    const double axisScale = bins.scale[axis];
    const std::uint32_t nb = bins.nb;
    auto it = std::partition(Refs.begin() + begin, Refs.begin() + end, [&](const BuildRef& r) {
      return binOf(r.centroid()[axis], lo, axisScale, nb) < bin;
    });
    const std::uint32_t mid = static_cast<std::uint32_t>(it - Refs.begin());
    if (mid == begin || mid == end)
    {
      return medianSplit(begin, end, centroids);
    }
    return mid;
  }

  /// Empties bins.nb bins per axis, then bins [begin, end) on all three
  /// axes in one pass over the primitives (in parallel chunks for a large
  /// range of the top phase, each into bins of its own, merged after).
  void fillBins(Bins& bins, std::uint32_t begin, std::uint32_t end, const AABB<double>& centroids,
    const BinFrame& frame) const
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      const double extent = centroids.max[axis] - centroids.min[axis];
      bins.active[axis] = extent > 0.0;
      bins.scale[axis] = bins.active[axis] ? bins.nb / extent : 0.0;
    }
    clearBins(bins);
    std::mutex merge;
    forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e) {
      if (b == begin && e == end)
      {
        binRange(bins, b, e, centroids, frame);
        return;
      }
      Bins chunk;
      chunk.nb = bins.nb;
      std::copy(bins.scale, bins.scale + 3, chunk.scale);
      std::copy(bins.active, bins.active + 3, chunk.active);
      clearBins(chunk);
      binRange(chunk, b, e, centroids, frame);
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

  /// Bins [begin, end) into `bins` (scale and active in locals: the pass
  /// writes bins, and so never reloads them).
  void binRange(Bins& bins, std::uint32_t begin, std::uint32_t end, const AABB<double>& centroids,
    const BinFrame& frame) const
  {
    const std::uint32_t nb = bins.nb;
    const double scale[3] = { bins.scale[0], bins.scale[1], bins.scale[2] };
    const bool active[3] = { bins.active[0], bins.active[1], bins.active[2] };
    for (std::uint32_t i = begin; i < end; ++i)
    {
      const BuildRef& r = Refs[i];
      const Vec3<double> c = r.centroid();
      const BinBox box = frame.toBin(r.box);
      for (int axis = 0; axis < 3; ++axis)
      {
        if (active[axis])
        {
          Bin& bin = bins.axis(axis)[binOf(c[axis], centroids.min[axis], scale[axis], nb)];
          bin.box.extend(box);
          bin.count++;
        }
      }
    }
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

  static std::uint32_t binOf(double c, double lo, double scale, std::uint32_t nb)
  {
    const double f = (c - lo) * scale;
    const std::uint32_t b = f > 0.0 ? static_cast<std::uint32_t>(f) : 0u;
    return std::min(b, nb - 1);
  }
};

} // namespace vtkrt::core::detail

#endif
