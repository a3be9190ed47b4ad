// BuildQuality::High: full-sweep SAH. Every primitive boundary in centroid
// order on each axis is a candidate split, over three orders sorted once
// up front and partitioned stably at every split (no sorting per node:
// O(n log n) in all).
#ifndef vtkrt_core_build_SweepSAHBuilder_h
#define vtkrt_core_build_SweepSAHBuilder_h

#include "vtkrt/core/build/SAH.h"
#include "vtkrt/core/build/TopDownBuilder.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace vtkrt::core::detail
{

/// Format: the nodes it writes (NodeFormats.h).
template <class Format = DoubleNodes>
class SweepSAHBuilder : public TopDownBuilder<SweepSAHBuilder<Format>, BuildRef, Format>
{
  using Base = TopDownBuilder<SweepSAHBuilder<Format>, BuildRef, Format>;

public:
  using Base::Base;

private:
  friend Base;
  using Base::Options;
  using Base::Refs;

  static constexpr bool kBottomUpBounds = false;
  static constexpr bool kSplitNeedsBounds = true;

  /// The best split found so far: the first `split` entries of Order[axis].
  struct Candidate
  {
    double cost = std::numeric_limits<double>::infinity();
    int axis = -1;
    std::uint32_t split = 0;
  };

  std::vector<std::uint32_t> Order[3]; ///< Refs indices sorted per axis, by node range
  std::vector<std::uint8_t> Side;      ///< 1 = goes left in the current split
  std::vector<std::uint32_t> Scratch;  ///< partition buffer (disjoint ranges per task)


  /// Through Order[0] during the build; Refs themselves once finish() has
  /// put them in leaf order.
  const BuildRef& refAt(std::uint32_t pos) const { return Order[0].empty() ? Refs[pos] : Refs[Order[0][pos]]; }

  /// Sorts the three orders once; Refs stay put until finish.
  void prepare()
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

  /// Refs in leaf order (any of the three orders, they agree on every leaf
  /// range).
  void finish()
  {
    BuildRefs sorted(Refs.size());
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

  std::uint32_t medianSplit(std::uint32_t begin, std::uint32_t end, const RangeBounds& bounds)
  {
    const AABB<double>& centroids = bounds.centroids;
    const std::uint32_t mid = begin + (end - begin) / 2;
    const Vec3<double> ext = centroids.diagonal();
    const bool spread = ext.x > 0.0 || ext.y > 0.0 || ext.z > 0.0;
    partitionPresorted(begin, end, spread ? centroids.largestAxis() : 0, mid - begin);
    return mid;
  }

  /// The split position, or `end` when a leaf is cheaper (only considered
  /// when the range fits in a leaf).
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const RangeBounds& bounds)
  {
    const AABB<double>& box = bounds.box;
    const AABB<double>& centroids = bounds.centroids;
    const std::uint32_t count = end - begin;
    std::vector<double> rightArea(count);
    Candidate best;
    for (int axis = 0; axis < 3; ++axis)
    {
      if (centroids.max[axis] > centroids.min[axis])
      {
        sweepAxis(begin, count, axis, rightArea.data(), best);
      }
    }
    if (best.axis < 0)
    {
      return count <= Options.maxLeafSize ? end : medianSplit(begin, end, bounds);
    }
    if (leafIsCheaper(Options, count, best.cost, box.halfArea()))
    {
      return end;
    }
    partitionPresorted(begin, end, best.axis, best.split);
    return begin + best.split;
  }

  /// The SAH cost of every boundary in Order[axis][begin, begin + count)
  /// (right sides accumulated first, into rightArea); keeps the cheapest in
  /// `best` (a local copy during the sweep, in registers).
  void sweepAxis(std::uint32_t begin, std::uint32_t count, int axis, double* rightArea, Candidate& best) const
  {
    const std::uint32_t* order = Order[axis].data() + begin;
    Candidate local = best;
    AABB<double> acc;
    for (std::uint32_t i = count - 1; i > 0; --i)
    {
      extendBox(acc, Refs[order[i]].box);
      rightArea[i] = acc.halfArea();
    }
    acc = AABB<double>();
    for (std::uint32_t i = 1; i < count; ++i)
    {
      extendBox(acc, Refs[order[i - 1]].box);
      const double cost = acc.halfArea() * i + rightArea[i] * (count - i);
      if (cost < local.cost)
      {
        local.cost = cost;
        local.axis = axis;
        local.split = i;
      }
    }
    best = local;
  }

  /// The first k entries of Order[axis][begin, end) go left; the other two
  /// orders are partitioned the same way, stably, so each stays sorted
  /// within both halves.
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
};

} // namespace vtkrt::core::detail

#endif
