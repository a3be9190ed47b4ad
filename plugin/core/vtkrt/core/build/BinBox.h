// The boxes the binned SAH builder weighs its splits with: float boxes in
// the build's frame (FloatRef.h), four lanes so that a reference's box
// extends a bin in two SSE instructions.
#ifndef vtkrt_core_build_BinBox_h
#define vtkrt_core_build_BinBox_h

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

} // namespace vtkrt::core::detail

#endif
