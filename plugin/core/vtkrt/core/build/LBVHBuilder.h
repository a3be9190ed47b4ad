// BuildQuality::Fast: the LBVH (Lauterbach et al. 2009). The primitives in
// the order of their centroids' Morton codes, each range split at the
// highest bit in which its codes differ; boxes merged bottom-up.
#ifndef vtkrt_core_build_LBVHBuilder_h
#define vtkrt_core_build_LBVHBuilder_h

#include "vtkrt/core/build/Morton.h"
#include "vtkrt/core/build/Parallel.h"
#include "vtkrt/core/build/TopDownBuilder.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

namespace vtkrt::core::detail
{

/// Format: the nodes it writes (NodeFormats.h).
template <class Format = DoubleNodes>
class LBVHBuilder : public TopDownBuilder<LBVHBuilder<Format>, BuildRef, Format>
{
  using Base = TopDownBuilder<LBVHBuilder<Format>, BuildRef, Format>;

public:
  using Base::Base;

private:
  friend Base;
  using Base::Options;
  using Base::Refs;

  /// The split needs no bounds: merging them bottom-up is O(n) in total
  /// instead of a pass over the range at every level.
  static constexpr bool kBottomUpBounds = true;
  static constexpr bool kSplitNeedsBounds = false;

  /// Positions ahead whose reference is fetched early: the build reads the
  /// references in Morton order through Perm, a random walk over the array
  /// that misses the cache and the TLB on large inputs without it.
  static constexpr std::uint32_t kPrefetchAhead = 16;

  /// The radix sort on the codes' top bits (see radixSortByCode).
  static constexpr int kRadixBits = 8;
  static constexpr std::uint32_t kRadix = 1u << kRadixBits;
  static constexpr int kRadixPasses = 4;
  static constexpr int kPrefixShift = 63 - kRadixBits * kRadixPasses; ///< the prefix is bits [31, 63)
  static constexpr std::size_t kHistogramChunks = 16;

  // Written in full right after they are sized: no zero fill.
  HugePageArray<std::uint64_t> Codes; ///< Morton codes by position, ascending
  HugePageArray<std::uint32_t> Perm;  ///< Refs index at each position

  /// The refs themselves never move (a permutation of large refs costs
  /// random writes over the whole array): positions go through Perm.
  const BuildRef& refAt(std::uint32_t pos) const { return Refs[Perm[pos]]; }

  void prefetchAfter(std::uint32_t pos) const
  {
#if defined(__GNUC__) || defined(__clang__)
    pos += kPrefetchAhead;
    if (!Perm.empty() && pos < Perm.size())
    {
      __builtin_prefetch(&Refs[Perm[pos]]);
    }
#else
    (void)pos;
#endif
  }

  void prepare() { sortByMortonCode(); }
  void finish() { HugePageArray<std::uint64_t>().swap(Codes); }

  /// Morton order keeps the middle a spatial median already.
  std::uint32_t medianSplit(std::uint32_t begin, std::uint32_t end, const RangeBounds&) const
  {
    return begin + (end - begin) / 2;
  }

  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const RangeBounds&) const
  {
    return end - begin <= Options.maxLeafSize ? end : mortonSplit(begin, end);
  }

  /// The first primitive whose code has the highest bit in which the
  /// range's codes differ; the middle when all codes are equal. Never
  /// reorders (sub-ranges stay sorted).
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

  /// 63-bit Morton codes of the centroids in their bounds; Perm lists the
  /// refs by (code, id), Codes ends up in that order.
  void sortByMortonCode()
  {
    const std::size_t n = Refs.size();
    Codes.resize(n);
    Perm.resize(n);
    if (computeCodes(centroidBounds()))
    {
      // Stable radix sort on the code: ties keep index order = id order.
      radixSortByCode();
      return;
    }
    std::sort(Perm.begin(), Perm.end(), [this](std::uint32_t a, std::uint32_t b) {
      return Codes[a] < Codes[b] || (Codes[a] == Codes[b] && Refs[a].id < Refs[b].id);
    });
    HugePageArray<std::uint64_t> sorted(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      sorted[i] = Codes[Perm[i]];
    }
    Codes.swap(sorted);
  }

  /// The bounds of all centroids, in fixed chunks (min/max: exact in any order).
  AABB<double> centroidBounds() const
  {
    const std::size_t n = Refs.size();
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
    return cb;
  }

  /// Codes[i] of Refs[i] in the grid over `cb`, Perm the identity. Returns
  /// whether the ids ascend with the index.
  bool computeCodes(const AABB<double>& cb)
  {
    const std::size_t n = Refs.size();
    const Vec3<double> ext = cb.diagonal();
    const double cells = double((1u << 21) - 1);
    Vec3<double> scale(0.0);
    for (int k = 0; k < 3; ++k)
    {
      scale[k] = ext[k] > 0.0 ? cells / ext[k] : 0.0;
    }
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
    return idsAscending;
  }

  /// Stable sort of (Codes, Perm) by Codes: an LSD radix sort on the top
  /// bits of the code (one pass per 8 bits), then each run of equal
  /// prefixes longer than one sorted on the whole code (comparison sort:
  /// such runs are short unless primitives crowd one cell of the prefix
  /// grid). Same order as a full stable sort in fewer passes.
  void radixSortByCode()
  {
    std::vector<std::uint32_t> hist = prefixHistograms();
    radixPasses(hist);
    sortPrefixRuns();
  }

  /// Each pass' histogram of its digit, kRadix counts a pass, counted in
  /// parallel chunks.
  std::vector<std::uint32_t> prefixHistograms() const
  {
    const std::size_t n = Codes.size();
    constexpr std::size_t kHistSize = kRadixPasses * kRadix;
    std::vector<std::uint32_t> chunkHist(kHistogramChunks * kHistSize, 0);
    parallelChunks(kHistogramChunks, Options, [&](std::size_t cb, std::size_t ce) {
      for (std::size_t c = cb; c < ce; ++c)
      {
        std::uint32_t* h = chunkHist.data() + c * kHistSize;
        for (std::size_t i = c * n / kHistogramChunks, e = (c + 1) * n / kHistogramChunks; i < e; ++i)
        {
          const std::uint64_t code = Codes[i] >> kPrefixShift;
          for (int p = 0; p < kRadixPasses; ++p)
          {
            h[p * kRadix + ((code >> (kRadixBits * p)) & (kRadix - 1))]++;
          }
        }
      }
    }, n);
    std::vector<std::uint32_t> hist(kHistSize, 0);
    for (std::size_t c = 0; c < kHistogramChunks; ++c)
    {
      for (std::size_t k = 0; k < hist.size(); ++k)
      {
        hist[k] += chunkHist[c * kHistSize + k];
      }
    }
    return hist;
  }

  /// The LSD passes over the prefix, skipping those whose digit is the same
  /// everywhere.
  void radixPasses(std::vector<std::uint32_t>& hist)
  {
    const std::size_t n = Codes.size();
    HugePageArray<std::uint64_t> codes2(n);
    HugePageArray<std::uint32_t> perm2(n);
    for (int p = 0; p < kRadixPasses; ++p)
    {
      const int shift = kPrefixShift + kRadixBits * p;
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
  }

  /// Runs of one prefix: order by the whole code, ties by position (the
  /// radix passes kept the input order, which is id order).
  void sortPrefixRuns()
  {
    const std::size_t n = Codes.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> run;
    for (std::size_t b = 0; b < n;)
    {
      std::size_t e = b + 1;
      while (e < n && (Codes[e] >> kPrefixShift) == (Codes[b] >> kPrefixShift))
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
};

} // namespace vtkrt::core::detail

#endif
