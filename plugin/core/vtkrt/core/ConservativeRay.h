// The per-ray float constants of the conservative pre-tests
// (ConservativeFloat.h explains why they are conservative): the grown float
// origins and inverse direction of the box test, the shear and error bound
// of the triangle test.
// Preconditions, checked by ConservativeRay4::init (false: use double only):
// finite float origin and inverse direction, Q <= 1e17 (no float overflow in
// the products), and on x86 no flush-to-zero / denormals-are-zero mode.
#ifndef vtkrt_core_ConservativeRay_h
#define vtkrt_core_ConservativeRay_h

#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/simd/Dispatch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtkrt::core
{

/// Per-ray float constants of both pre-tests.
struct ConservativeRay4
{
  // Boxes: per axis, the float origin for the near and the far plane, the
  // near plane's row (0: lo, 1: hi) and the float inverse direction.
  float oNear[3], oFar[3], inv[3];
  /// Which plane is near on each axis, and where the kernels find it: set
  /// together from the direction's signs (SignRows).
  struct SignRows
  {
    int nearHi[3];             ///< 1: the hi plane is near (direction < 0)
    int nearRow[3], farRow[3]; ///< float offsets of the near / far plane rows in a BoxPack4
    int qNear[3], qFar[3];     ///< byte offsets of the near / far plane rows in a QuantizedBoxPack8's q
  };
  SignRows rows;
  float tmin;
  // Triangles: the float origin, the shear of the double test, the
  // coordinate error bound E.
  float org[3];
  int kx, ky, kz;
  float sx, sy;
  float E;

  static constexpr float kUnit = 0x1p-24f;
  static constexpr float kTiny = 1e-36f; // above any sum of a few underflowed terms
  /// 1 + 4 gamma(3) in float, rounded up.
  static constexpr float kFarScale = 1.0f + 4.0f * (3.0f * 0x1p-24f) / (1.0f - 3.0f * 0x1p-24f) + 0x1p-23f;

  /// Fills the constants for `ray` (double), boxes grown by `grow` >= 0,
  /// triangles whose vertices are within `extent` (inf norm) of 0. False when
  /// a precondition fails: use the double tests for this ray.
  bool init(const Ray<double>& ray, const RayTrianglePrecomputed<double>& tri, double grow, double extent)
  {
    double Q;
    if (!usable(ray, grow, extent, Q))
    {
      return false;
    }
    int signs = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double d = ray.dir[a];
      const double invD = 1.0 / d;
      const float invF = static_cast<float>(invD);
      if (d == 0.0 || !std::isfinite(invF) || !(std::abs(invF) >= 0x1p-100f))
      {
        return false;
      }
      inv[a] = invF;
      const float of = static_cast<float>(ray.org[a]);
      org[a] = of;
      // Residual of the rounding plus the growth, rounded up; the origin for
      // the lower planes moves up by it, for the upper planes down.
      const double mExact = std::abs(ray.org[a] - static_cast<double>(of)) + grow;
      const double m = mExact + mExact * std::numeric_limits<double>::epsilon();
      const double up = static_cast<double>(of) + m, down = static_cast<double>(of) - m;
      const float oLo = detail::ceilFloat(up + std::abs(up) * std::numeric_limits<double>::epsilon());
      const float oHi = detail::floorFloat(down - std::abs(down) * std::numeric_limits<double>::epsilon());
      signs |= d < 0.0 ? 1 << a : 0;
      oNear[a] = d < 0.0 ? oHi : oLo;
      oFar[a] = d < 0.0 ? oLo : oHi;
    }
    setSignRows(signs);
    setScalars(ray, tri, Q);
    return true;
  }

  /// init's preconditions (the file's header); Q = extent + |origin|inf.
  static bool usable(const Ray<double>& ray, double grow, double extent, double& Q)
  {
#if VTKRT_CORE_SSE
    if (_mm_getcsr() & 0x8040u) // FTZ or DAZ: underflow is not gradual
    {
      return false;
    }
#endif
    const double oMax = std::max(std::abs(ray.org.x), std::max(std::abs(ray.org.y), std::abs(ray.org.z)));
    Q = extent + oMax;
    return Q <= 1e17 && grow >= 0.0 && grow <= 1e17 && ray.tmin >= 0.0 && ray.tmin <= 1e30;
  }

  /// The constants that are no per-axis work: tmin, the shear, E.
  void setScalars(const Ray<double>& ray, const RayTrianglePrecomputed<double>& tri, double Q)
  {
    tmin = detail::floorFloat(ray.tmin);
    kx = tri.kx;
    ky = tri.ky;
    kz = tri.kz;
    sx = static_cast<float>(tri.sx);
    sy = static_cast<float>(tri.sy);
    E = detail::ceilFloat(16.0 * 0x1p-24 * Q * (1.0 + 1e-6));
  }

#if VTKRT_CORE_AVX2
  /// init() with the three axes in one AVX step each: the same operations
  /// in the same order as init()'s loop, lane by lane (no FMA), so the same
  /// fields, bit for bit (TestCoreConservativeFloat compares them). Only
  /// where the CPU has AVX2 (useAvx2()). Defined in simd/Avx2.h.
  VTKRT_TARGET_AVX2 bool initAvx2(
    const Ray<double>& ray, const RayTrianglePrecomputed<double>& tri, double grow, double extent);
#endif

  /// The rows of the direction's sign bits (bit a: dir[a] < 0): one copy
  /// from a table made at compile time (kSignRows).
  void setSignRows(int signs);

  /// The float bound to compare box entry distances with, for a double tmax.
  static float scaledTmax(double tmax)
  {
    if (!(tmax < 1e38))
    {
      return std::numeric_limits<float>::infinity();
    }
    // float(tmax) is within half an ulp (relative 2^-24, or an absolute
    // 2^-150 below FLT_MIN): the extra 2^-22 and kTiny cover it.
    return static_cast<float>(tmax) * (kFarScale * (1.0f + 0x1p-22f)) + kTiny;
  }
};

namespace detail
{
struct SignRowsTable
{
  ConservativeRay4::SignRows rows[8];
};
constexpr SignRowsTable makeSignRows()
{
  SignRowsTable t{};
  for (int b = 0; b < 8; ++b)
  {
    for (int a = 0; a < 3; ++a)
    {
      const int hi = b >> a & 1;
      t.rows[b].nearHi[a] = hi;
      t.rows[b].nearRow[a] = 12 * hi + 4 * a;
      t.rows[b].farRow[a] = 12 * (1 - hi) + 4 * a;
      t.rows[b].qNear[a] = 8 * (3 * hi + a);
      t.rows[b].qFar[a] = 8 * (3 * (1 - hi) + a);
    }
  }
  return t;
}
/// ConservativeRay4::SignRows of each sign pattern (internal linkage: no
/// guard, no GOT).
static constexpr SignRowsTable kSignRows = makeSignRows();
} // namespace detail

inline void ConservativeRay4::setSignRows(int signs)
{
  rows = detail::kSignRows.rows[signs];
}
} // namespace vtkrt::core

#endif
