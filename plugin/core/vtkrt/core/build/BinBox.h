// The boxes the binned SAH builder weighs its splits with: float boxes in a
// range's own frame (its box's corner at the origin, its largest extent 1),
// four lanes so that a reference's box extends a bin in two SSE
// instructions. Only the split's cost is decided on them: bin indices,
// partition and node boxes stay in double, so every node box is exact.
#ifndef vtkrt_core_build_BinBox_h
#define vtkrt_core_build_BinBox_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/simd/Dispatch.h"

#include <algorithm>
#include <limits>

namespace vtkrt::core::detail
{

/// A float box (lanes 0-2; lane 3 is never read).
struct alignas(16) BinBox
{
  float lo[4];
  float hi[4];

  static BinBox empty()
  {
    constexpr float inf = std::numeric_limits<float>::infinity();
    return BinBox{ { inf, inf, inf, inf }, { -inf, -inf, -inf, -inf } };
  }

  VTKRT_ALWAYS_INLINE void extend(const BinBox& b)
  {
#if VTKRT_CORE_SSE
    _mm_store_ps(lo, _mm_min_ps(_mm_load_ps(lo), _mm_load_ps(b.lo)));
    _mm_store_ps(hi, _mm_max_ps(_mm_load_ps(hi), _mm_load_ps(b.hi)));
#else
    for (int k = 0; k < 4; ++k)
    {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
#endif
  }

  /// Half the area; 0 when empty.
  float halfArea() const
  {
    const float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx >= 0.0f && dy >= 0.0f && dz >= 0.0f ? dx * dy + dy * dz + dz * dx : 0.0f;
  }
};

/// A range's frame: box corner at the origin, largest extent scaled to 1
/// (any coordinate range and scale fits float).
struct BinFrame
{
  Vec3<double> origin;
  double scale;

  explicit BinFrame(const AABB<double>& box)
    : origin(box.min)
  {
    const Vec3<double> d = box.diagonal();
    const double extent = std::max(d.x, std::max(d.y, d.z));
    // A box wider than the largest double (extent inf) gets scale 0: every
    // bin box is then a point, every split costs nothing, and the first one
    // is taken; the tree stays valid.
    scale = extent > 0.0 ? 1.0 / extent : 1.0;
  }

  /// `box` in this frame, rounded to nearest.
  VTKRT_ALWAYS_INLINE BinBox toBin(const AABB<double>& box) const
  {
    BinBox b;
#if VTKRT_CORE_SSE
    const __m128d o01 = _mm_set_pd(origin.y, origin.x);
    const __m128d o2 = _mm_set_sd(origin.z);
    const __m128d s = _mm_set1_pd(scale);
    const __m128d lo01 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&box.min.x), o01), s);
    const __m128d lo2 = _mm_mul_pd(_mm_sub_pd(_mm_load_sd(&box.min.z), o2), s);
    const __m128d hi01 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&box.max.x), o01), s);
    const __m128d hi2 = _mm_mul_pd(_mm_sub_pd(_mm_load_sd(&box.max.z), o2), s);
    _mm_store_ps(b.lo, _mm_movelh_ps(_mm_cvtpd_ps(lo01), _mm_cvtpd_ps(lo2)));
    _mm_store_ps(b.hi, _mm_movelh_ps(_mm_cvtpd_ps(hi01), _mm_cvtpd_ps(hi2)));
#else
    for (int k = 0; k < 3; ++k)
    {
      b.lo[k] = static_cast<float>((box.min[k] - origin[k]) * scale);
      b.hi[k] = static_cast<float>((box.max[k] - origin[k]) * scale);
    }
    b.lo[3] = b.hi[3] = 0.0f;
#endif
    return b;
  }

};

} // namespace vtkrt::core::detail

#endif
