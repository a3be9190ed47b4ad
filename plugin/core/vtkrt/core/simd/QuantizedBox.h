// A wide node's eight child boxes in one cache line: a byte a plane on a
// per-axis grid of exact floats (QuantizedBoxPack8), so that the box tests
// see float boxes holding the exact ones, as the proof in
// ConservativeFloat.h needs.
#ifndef vtkrt_core_simd_QuantizedBox_h
#define vtkrt_core_simd_QuantizedBox_h

#include "vtkrt/core/simd/Packs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace vtkrt::core
{

namespace detail
{
/// kPow2.v[e + 128] = 2^e for the grid exponents -126..127 (0 below): a
/// box test reads a node's three grid steps with one load each, not
/// through the float's bits.
struct Pow2Table
{
  float v[256];
};
constexpr Pow2Table makePow2Table()
{
  Pow2Table t{};
  float up = 1.0f, down = 1.0f;
  for (int e = 0; e <= 126; ++e)
  {
    t.v[128 + e] = up;
    t.v[128 - e] = down;
    up *= 2.0f;
    down *= 0.5f;
  }
  t.v[255] = up; // 2^127
  return t;
}
// Internal linkage: read RIP-relative, not through a shared library's GOT.
alignas(64) static constexpr Pow2Table kPow2 = makePow2Table();
} // namespace detail

/// Eight boxes on a per-axis grid, a byte a plane: half the bytes of a
/// BoxPack8, so that a wide node is two cache lines instead of four (a
/// pick's walk waits on one node load a level). Lane i on axis a spans
/// [origin[a] + lo * step, origin[a] + hi * step] with step = 2^exp[a] and
/// lo = q[a][i], hi = q[3 + a][i]. The grid is chosen so that every decoded
/// plane is an exact float (origin is a multiple of step below 2^24 steps
/// from 0, and q <= 255), which holds the float box it was made from
/// (planes rounded outward to the grid). So the box tests see float boxes
/// that contain the exact ones, as with BoxPack8, and the same proof holds.
struct alignas(64) QuantizedBoxPack8
{
  float origin[3];
  std::int8_t exp[3];
  std::uint8_t valid;   ///< bit i: lane i holds a box; the others are never hit
  std::uint8_t q[6][8]; ///< lo rows x, y, z, then hi rows: grid steps above origin

  /// The grid step of axis a (a normal float: exp >= -126).
  float step(int a) const { return detail::kPow2.v[exp[a] + 128]; }

  /// Lane i's decoded box (exact floats), for lanes in `valid`.
  void lane(int i, float lo[3], float hi[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = origin[a] + static_cast<float>(q[a][i]) * step(a);
      hi[a] = origin[a] + static_cast<float>(q[3 + a][i]) * step(a);
    }
  }

  /// Every lane decoded (unused lanes too: not boxes).
  BoxPack<8> decoded() const
  {
    BoxPack<8> b;
    for (int i = 0; i < 8; ++i)
    {
      float lo[3], hi[3];
      lane(i, lo, hi);
      for (int a = 0; a < 3; ++a)
      {
        b.lo[a][i] = lo[a];
        b.hi[a][i] = hi[a];
      }
    }
    return b;
  }

  /// The lanes of b whose boxes are not empty (lo <= hi on every axis), on
  /// the finest grid that spans them in 255 steps and keeps every plane an
  /// exact float. Boxes beyond 1e17 (which the float walk never meets:
  /// ConservativeRay4::init refuses such extents) get a grid that may not
  /// hold them.
  static QuantizedBoxPack8 quantize(const BoxPack<8>& b)
  {
    QuantizedBoxPack8 out;
    out.valid = 0;
    for (int i = 0; i < 8; ++i)
    {
      bool used = true;
      for (int a = 0; a < 3; ++a)
      {
        used = used && b.lo[a][i] <= b.hi[a][i];
      }
      out.valid |= used ? static_cast<std::uint8_t>(1u << i) : 0;
    }
    for (int a = 0; a < 3; ++a)
    {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int i = 0; i < 8; ++i)
      {
        if (out.valid >> i & 1)
        {
          lo = std::min(lo, static_cast<double>(b.lo[a][i]));
          hi = std::max(hi, static_cast<double>(b.hi[a][i]));
        }
      }
      if (!(lo <= hi) || !(hi - lo < 1e30) || !(std::abs(lo) < 1e30))
      {
        lo = hi = 0.0; // no lane, or beyond the float walk's reach
      }
      // The smallest exponent whose grid spans [lo, hi] in 255 steps with
      // every grid point below 2^24 steps from 0 (so exact in float).
      const double need = std::max((hi - lo) / 255.0, std::max(std::abs(lo), std::abs(hi)) / (0x1p24 - 512.0));
      int e = -126;
      if (need > 0.0)
      {
        int ne;
        std::frexp(need, &ne); // need < 2^ne
        e = std::max(e, ne);
      }
      double stepD = std::ldexp(1.0, e), k = std::floor(lo / stepD);
      while (e < 127 && !(std::ceil(hi / stepD) - k <= 255.0 && std::abs(k) + 256.0 < 0x1p24))
      {
        ++e;
        stepD = std::ldexp(1.0, e);
        k = std::floor(lo / stepD);
      }
      out.exp[a] = static_cast<std::int8_t>(e);
      out.origin[a] = static_cast<float>(k * stepD); // exact: |k| < 2^24
      for (int i = 0; i < 8; ++i)
      {
        if (out.valid >> i & 1)
        {
          const double qlo = std::floor(static_cast<double>(b.lo[a][i]) / stepD) - k;
          const double qhi = std::ceil(static_cast<double>(b.hi[a][i]) / stepD) - k;
          out.q[a][i] = static_cast<std::uint8_t>(std::min(255.0, std::max(0.0, qlo)));
          out.q[3 + a][i] = static_cast<std::uint8_t>(std::min(255.0, std::max(0.0, qhi)));
        }
        else
        {
          out.q[a][i] = 255;
          out.q[3 + a][i] = 0;
        }
      }
    }
    return out;
  }
};
static_assert(sizeof(QuantizedBoxPack8) == 64, "one cache line");

} // namespace vtkrt::core

#endif
