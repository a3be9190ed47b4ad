// Four-wide float pre-tests for a double-precision ray: four boxes, or four
// triangles, at once (SSE when the compiler targets it, plain loops
// otherwise). They are CONSERVATIVE: they never reject a box that the
// double slab test (Ray.h) accepts, nor a triangle that the double
// watertight test (Triangle.h) accepts, so a traversal can cull in float
// and decide every surviving candidate exactly in double.
//
// Why they are conservative (u = 2^-24, float unit roundoff):
// - Boxes are rounded outward to float (BVH.h); a wide node's are then
//   rounded outward again to its grid, whose decoded planes are exact floats
//   (QuantizedBoxPack8), so they too are float boxes holding the exact ones.
//   The ray origin o is
//   rounded to a float o_f; the residual |o - o_f| (plus an optional
//   tolerance) is added to each box side by using for the lower planes the
//   float roundUp(o_f + m) and for the upper planes roundDown(o_f - m) as
//   origin, so the grown box holds the exact ray. The slab distances then
//   carry only relative errors (subtraction, rounded 1/d, product: gamma(3)),
//   covered as in Ize 2013 by scaling the far distances (and tmax) by
//   1 + 4 gamma(3); a tiny absolute term covers gradual underflow.
// - Triangles: vertices rounded to nearest float, Q = R + |o|inf with R a
//   bound on |vertex|inf. Each sheared coordinate (Woop et al.'s Ax, Ay, ...)
//   is then within E = 16 u Q of the exact one the double test approximates
//   (the derivation gives 10 u Q), and each edge function (U, V, W) within
//   2 E S + 6 E^2 + 3 u S^2 of it, where S bounds |X| + |Y| of the computed
//   sheared vertices. The double test's own error is below 2^-29 of that.
//   A lane is rejected only when one edge function is below -m and another
//   above +m, with m = 4 E S + 8 E^2 + 8 u S^2 (twice the bound): the double
//   test then sees mixed signs too. The t range is left to the double test.
// Preconditions, checked by ConservativeRay4::init (false: use double only):
// finite float origin and inverse direction, Q <= 1e17 (no float overflow in
// the products), and on x86 no flush-to-zero / denormals-are-zero mode.
#ifndef vtkrt_core_ConservativeFloat_h
#define vtkrt_core_ConservativeFloat_h

#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__) || defined(_M_X64)
#define VTKRT_CORE_SSE 1
#include <emmintrin.h>
#include <xmmintrin.h>
#else
#define VTKRT_CORE_SSE 0
#endif

// Eight-wide AVX2 kernels, compiled for AVX2 function by function (target
// attribute) and chosen at run time (useAvx2()), so the library still runs
// on any x86-64. They do the same float operations in the same order as
// the SSE ones (no FMA: target("avx2") does not enable it), so their bits
// are the same and so is the proof at the top of this file.
#if VTKRT_CORE_SSE && (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#define VTKRT_CORE_AVX2 1
#define VTKRT_TARGET_AVX2 __attribute__((target("avx2")))
#include <cstdlib>
#include <immintrin.h>
#else
#define VTKRT_CORE_AVX2 0
#define VTKRT_TARGET_AVX2
#endif

namespace vtkrt::core
{

/// Four triangles, structure of arrays: v[3 * vertex + axis][lane], in the
/// local frame of the double vertices (rounded to nearest float).
struct alignas(16) TrianglePack4
{
  float v[9][4];

  void set(int lane, const Vec3<double>& v0, const Vec3<double>& v1, const Vec3<double>& v2)
  {
    const Vec3<double>* vs[3] = { &v0, &v1, &v2 };
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        v[3 * k + a][lane] = static_cast<float>((*vs[k])[a]);
      }
    }
  }
  void clear(int lane)
  {
    for (auto& row : v)
    {
      row[lane] = 0.0f;
    }
  }
};

/// Four (BoxPack4) or eight (BoxPack8) boxes, structure of arrays:
/// lo[axis][lane], hi[axis][lane], float, rounded outward. An unused lane
/// holds lo = +inf, hi = -inf (never hit).
template <int N>
struct alignas(4 * N) BoxPack
{
  float lo[3][N];
  float hi[3][N];

  void clear(int lane)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a][lane] = std::numeric_limits<float>::infinity();
      hi[a][lane] = -std::numeric_limits<float>::infinity();
    }
  }
};
using BoxPack4 = BoxPack<4>;
using BoxPack8 = BoxPack<8>; ///< the children of a wide node

/// Whether the AVX2 kernels run: the CPU has AVX2 and the environment
/// variable VTKRT_NO_AVX2 is unset (set: the SSE kernels, e.g. to compare).
inline bool useAvx2()
{
#if VTKRT_CORE_AVX2
  static const bool use = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && !std::getenv("VTKRT_NO_AVX2");
  }();
  return use;
#else
  return false;
#endif
}

namespace detail
{
/// Finite f moved `steps` (0 or 1) floats toward +inf, through its bits
/// (no libm call, no branch): +1 on the bits of a float >= +0, -1 on those
/// of a negative one. -0 counts as +0, so that 0 steps to denorm_min.
inline float stepUp(float f, std::int32_t steps)
{
  f += 0.0f; // -0 -> +0 (round to nearest)
  std::int32_t u;
  std::memcpy(&u, &f, sizeof u);
  u += steps * ((u >> 31) | 1);
  std::memcpy(&f, &u, sizeof f);
  return f;
}
/// Next float toward +inf / -inf of a finite float.
inline float nextUp(float f)
{
  return stepUp(f, 1);
}
inline float nextDown(float f)
{
  return -nextUp(-f);
}
/// Smallest float >= x / largest float <= x, for |x| < FLT_MAX. Without a
/// branch on the rounding's direction: a ray's setup rounds eight of them,
/// each as likely to go one way as the other.
inline float ceilFloat(double x)
{
  const float f = static_cast<float>(x);
  return stepUp(f, static_cast<double>(f) < x ? 1 : 0);
}
inline float floorFloat(double x)
{
  return -ceilFloat(-x);
}
} // namespace detail

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
  /// where the CPU has AVX2 (useAvx2()).
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

#if VTKRT_CORE_AVX2
namespace detail
{
/// Four 64-bit lane masks as four 32-bit ones (the low half of each).
VTKRT_TARGET_AVX2 inline __m128i narrowMask(__m256d mask)
{
  return _mm256_castsi256_si128(
    _mm256_permutevar8x32_epi32(_mm256_castpd_si256(mask), _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7)));
}

/// ceilFloat of four doubles: the nearest float, one step up where it lies
/// below (through the float's bits, as stepUp).
VTKRT_TARGET_AVX2 inline __m128 ceilFloat4(__m256d x)
{
  const __m128 f = _mm_add_ps(_mm256_cvtpd_ps(x), _mm_setzero_ps()); // -0 -> +0
  const __m128i step = narrowMask(_mm256_cmp_pd(_mm256_cvtps_pd(f), x, _CMP_LT_OQ));
  const __m128i u = _mm_castps_si128(f);
  const __m128i dir = _mm_or_si128(_mm_srai_epi32(u, 31), _mm_set1_epi32(1));
  return _mm_castsi128_ps(_mm_add_epi32(u, _mm_and_si128(step, dir)));
}
} // namespace detail

VTKRT_TARGET_AVX2 inline bool ConservativeRay4::initAvx2(
  const Ray<double>& ray, const RayTrianglePrecomputed<double>& tri, double grow, double extent)
{
  double Q;
  if (!usable(ray, grow, extent, Q))
  {
    return false;
  }
  // Lane 3 is padding: direction 1, origin 0.
  const __m256d d = _mm256_setr_pd(ray.dir.x, ray.dir.y, ray.dir.z, 1.0);
  const __m256d o = _mm256_setr_pd(ray.org.x, ray.org.y, ray.org.z, 0.0);
  const __m256d absMask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  const __m128 absMaskF = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m256d eps = _mm256_set1_pd(std::numeric_limits<double>::epsilon());
  const __m128 invF = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), d));
  const __m128 absInv = _mm_and_ps(invF, absMaskF);
  const int usable = _mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(absInv, _mm_set1_ps(std::numeric_limits<float>::max())),
                       _mm_cmpge_ps(absInv, _mm_set1_ps(0x1p-100f)))) &
    ~_mm256_movemask_pd(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_EQ_OQ));
  if ((usable & 7) != 7)
  {
    return false;
  }
  const __m128 of = _mm256_cvtpd_ps(o);
  const __m256d ofD = _mm256_cvtps_pd(of);
  const __m256d mExact = _mm256_add_pd(_mm256_and_pd(_mm256_sub_pd(o, ofD), absMask), _mm256_set1_pd(grow));
  const __m256d m = _mm256_add_pd(mExact, _mm256_mul_pd(mExact, eps));
  const __m256d up = _mm256_add_pd(ofD, m), down = _mm256_sub_pd(ofD, m);
  const __m128 oLo = detail::ceilFloat4(_mm256_add_pd(up, _mm256_mul_pd(_mm256_and_pd(up, absMask), eps)));
  // floorFloat(x) = -ceilFloat(-x)
  const __m256d negDown = _mm256_sub_pd(_mm256_mul_pd(_mm256_and_pd(down, absMask), eps), down);
  const __m128 signF = _mm_set1_ps(-0.0f);
  const __m128 oHi = _mm_xor_ps(detail::ceilFloat4(negDown), signF);
  const __m128 neg = _mm_castsi128_ps(detail::narrowMask(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_LT_OQ)));
  alignas(16) float lanes[4][4];
  _mm_store_ps(lanes[0], invF);
  _mm_store_ps(lanes[1], of);
  _mm_store_ps(lanes[2], _mm_blendv_ps(oLo, oHi, neg));
  _mm_store_ps(lanes[3], _mm_blendv_ps(oHi, oLo, neg));
  std::memcpy(inv, lanes[0], sizeof inv);
  std::memcpy(org, lanes[1], sizeof org);
  std::memcpy(oNear, lanes[2], sizeof oNear);
  std::memcpy(oFar, lanes[3], sizeof oFar);
  setSignRows(_mm_movemask_ps(neg) & 7);
  setScalars(ray, tri, Q);
  return true;
}
#endif

#if VTKRT_CORE_SSE
namespace detail
{
inline __m128 abs4(__m128 x)
{
  return _mm_andnot_ps(_mm_set1_ps(-0.0f), x);
}
} // namespace detail

/// The box constants of a ConservativeRay4, broadcast once per ray: a walk
/// over many nodes then reloads and broadcasts nothing per node.
struct ConservativeBoxRay4
{
  __m128 oNear[3], oFar[3], inv[3], tmin;
  int nearRow[3], farRow[3];
  int qNear[3], qFar[3]; ///< byte offsets of the near / far plane rows in a QuantizedBoxPack8's q

  explicit ConservativeBoxRay4(const ConservativeRay4& r)
  {
    for (int a = 0; a < 3; ++a)
    {
      oNear[a] = _mm_set1_ps(r.oNear[a]);
      oFar[a] = _mm_set1_ps(r.oFar[a]);
      inv[a] = _mm_set1_ps(r.inv[a]);
      nearRow[a] = r.rows.nearRow[a];
      farRow[a] = r.rows.farRow[a];
      qNear[a] = r.rows.qNear[a];
      qFar[a] = r.rows.qFar[a];
    }
    tmin = _mm_set1_ps(r.tmin);
  }
};

namespace detail
{
/// The slab test of four boxes whose near and far planes on axis a are
/// planes(a, nearPlane, farPlane).
template <class PlanesFn>
inline int slabLanes4(const ConservativeBoxRay4& r, PlanesFn&& planes, float tmaxScaled, float tnear[4])
{
  __m128 tn = r.tmin;
  __m128 tf = _mm_set1_ps(std::numeric_limits<float>::infinity());
  for (int a = 0; a < 3; ++a)
  {
    __m128 nearPlane, farPlane;
    planes(a, nearPlane, farPlane);
    tn = _mm_max_ps(tn, _mm_mul_ps(_mm_sub_ps(nearPlane, r.oNear[a]), r.inv[a]));
    tf = _mm_min_ps(tf, _mm_mul_ps(_mm_sub_ps(farPlane, r.oFar[a]), r.inv[a]));
  }
  tf = _mm_add_ps(_mm_mul_ps(tf, _mm_set1_ps(ConservativeRay4::kFarScale)),
    _mm_set1_ps(ConservativeRay4::kTiny));
  tf = _mm_min_ps(tf, _mm_set1_ps(tmaxScaled));
  _mm_storeu_ps(tnear, tn);
  return _mm_movemask_ps(_mm_cmple_ps(tn, tf));
}

/// Four boxes of a BoxPack<N> (N = 4 * Scale) from lane `first` on.
template <int Scale>
inline int intersectBoxLanes4(const ConservativeBoxRay4& r, const BoxPack<4 * Scale>& b, int first, float tmaxScaled, float tnear[4])
{
  static_assert(sizeof(BoxPack<4 * Scale>) == 24 * Scale * sizeof(float), "lo rows, then hi rows");
  const float* base = &b.lo[0][0] + first;
  return slabLanes4(
    r,
    [&](int a, __m128& nearPlane, __m128& farPlane) {
      nearPlane = _mm_load_ps(base + Scale * r.nearRow[a]);
      farPlane = _mm_load_ps(base + Scale * r.farRow[a]);
    },
    tmaxScaled, tnear);
}
} // namespace detail

/// Bit i set: box i may be hit with entry distance <= tmaxScaled
/// (ConservativeRay4::scaledTmax); tnear[i] gets a lower bound of its entry
/// distance (valid for set bits).
inline int intersectBoxes4(const ConservativeBoxRay4& r, const BoxPack4& b, float tmaxScaled, float tnear[4])
{
  return detail::intersectBoxLanes4<1>(r, b, 0, tmaxScaled, tnear);
}

/// Eight boxes (bits 0-7), four per SSE step.
inline int intersectBoxes8(const ConservativeBoxRay4& r, const BoxPack8& b, float tmaxScaled, float tnear[8])
{
  return detail::intersectBoxLanes4<2>(r, b, 0, tmaxScaled, tnear) |
    detail::intersectBoxLanes4<2>(r, b, 4, tmaxScaled, tnear + 4) << 4;
}

namespace detail
{
/// Lanes first .. first + 3 of the q row at byte offset `row`, decoded
/// (exact: see QuantizedBoxPack8).
inline __m128 decodeRow4(const QuantizedBoxPack8& b, int row, int first, __m128 origin, __m128 step)
{
  std::int32_t bytes;
  std::memcpy(&bytes, &b.q[0][0] + row + first, sizeof bytes);
  const __m128i zero = _mm_setzero_si128();
  const __m128i q = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(bytes), zero), zero);
  return _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(q), step), origin);
}

/// The slab test on four decoded lanes of a QuantizedBoxPack8.
inline int intersectQuantizedLanes4(const ConservativeBoxRay4& r, const QuantizedBoxPack8& b, int first, float tmaxScaled, float tnear[4])
{
  return slabLanes4(
    r,
    [&](int a, __m128& nearPlane, __m128& farPlane) {
      const __m128 origin = _mm_set1_ps(b.origin[a]), step = _mm_set1_ps(b.step(a));
      nearPlane = decodeRow4(b, r.qNear[a], first, origin, step);
      farPlane = decodeRow4(b, r.qFar[a], first, origin, step);
    },
    tmaxScaled, tnear);
}
} // namespace detail

/// The eight boxes of a wide node (bits 0-7; unused lanes never), decoded
/// and tested four per SSE step: the bits and entry distances of the same
/// test on the decoded BoxPack8.
inline int intersectBoxes8(const ConservativeBoxRay4& r, const QuantizedBoxPack8& b, float tmaxScaled, float tnear[8])
{
  return (detail::intersectQuantizedLanes4(r, b, 0, tmaxScaled, tnear) |
           detail::intersectQuantizedLanes4(r, b, 4, tmaxScaled, tnear + 4) << 4) &
    b.valid;
}

inline int intersectBoxes4(const ConservativeRay4& r, const BoxPack4& b, float tmaxScaled, float tnear[4])
{
  return intersectBoxes4(ConservativeBoxRay4(r), b, tmaxScaled, tnear);
}

namespace detail
{
/// triangleCandidates4 on the rows of a TrianglePack4 held in registers:
/// v[3 * vertex + axis] = that coordinate of the four lanes.
inline int triangleCandidatesRows4(const ConservativeRay4& r, const __m128 v[9])
{
  const __m128 ox = _mm_set1_ps(r.org[r.kx]), oy = _mm_set1_ps(r.org[r.ky]), oz = _mm_set1_ps(r.org[r.kz]);
  const __m128 sx = _mm_set1_ps(r.sx), sy = _mm_set1_ps(r.sy);
  __m128 X[3], Y[3], S = _mm_setzero_ps();
  for (int k = 0; k < 3; ++k)
  {
    const __m128 z = _mm_sub_ps(v[3 * k + r.kz], oz);
    X[k] = _mm_sub_ps(_mm_sub_ps(v[3 * k + r.kx], ox), _mm_mul_ps(sx, z));
    Y[k] = _mm_sub_ps(_mm_sub_ps(v[3 * k + r.ky], oy), _mm_mul_ps(sy, z));
    S = _mm_max_ps(S, _mm_add_ps(detail::abs4(X[k]), detail::abs4(Y[k])));
  }
  // (A, B, C) = vertices 0, 1, 2.
  const __m128 U = _mm_sub_ps(_mm_mul_ps(X[2], Y[1]), _mm_mul_ps(Y[2], X[1]));
  const __m128 V = _mm_sub_ps(_mm_mul_ps(X[0], Y[2]), _mm_mul_ps(Y[0], X[2]));
  const __m128 W = _mm_sub_ps(_mm_mul_ps(X[1], Y[0]), _mm_mul_ps(Y[1], X[0]));
  const __m128 E = _mm_set1_ps(r.E);
  const __m128 m = _mm_add_ps(
    _mm_mul_ps(S, _mm_add_ps(_mm_mul_ps(_mm_set1_ps(4.0f), E), _mm_mul_ps(_mm_set1_ps(8.0f * ConservativeRay4::kUnit), S))),
    _mm_add_ps(_mm_mul_ps(_mm_set1_ps(8.0f), _mm_mul_ps(E, E)), _mm_set1_ps(ConservativeRay4::kTiny)));
  const __m128 negM = _mm_sub_ps(_mm_setzero_ps(), m);
  const __m128 neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(U, negM), _mm_cmplt_ps(V, negM)), _mm_cmplt_ps(W, negM));
  const __m128 pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(U, m), _mm_cmpgt_ps(V, m)), _mm_cmpgt_ps(W, m));
  return ~_mm_movemask_ps(_mm_and_ps(neg, pos)) & 0xf;
}

} // namespace detail

/// Bit i set: the double watertight test may hit triangle i (see the top of
/// this file); clear bits are certain misses.
inline int triangleCandidates4(const ConservativeRay4& r, const TrianglePack4& p)
{
  __m128 v[9];
  for (int k = 0; k < 9; ++k)
  {
    v[k] = _mm_load_ps(p.v[k]);
  }
  return detail::triangleCandidatesRows4(r, v);
}

/// triangleCandidates4 over a leaf's triangles stored one after another:
/// triangle i (i < n, 1 <= n <= 4) is the nine floats tri[9i .. 9i + 8]
/// (vertex 0, 1, 2; x, y, z; each rounded to nearest from the double
/// vertex), and one readable float follows the last triangle. The same
/// float coordinates as a TrianglePack4 of them, so the same bits; lanes
/// from n on are undefined (mask them). One unaligned load a vertex, and
/// no load waits for another (a leaf read through point ids would wait for
/// the ids before it could fetch the points).
inline int triangleCandidates4(const ConservativeRay4& r, const float* tri, int n)
{
  // Lanes from n on repeat the last triangle (no branch per lane).
  const float* t1 = tri + 9 * std::min(1, n - 1);
  const float* t2 = tri + 9 * std::min(2, n - 1);
  const float* t3 = tri + 9 * std::min(3, n - 1);
  __m128 v[9];
  for (int k = 0; k < 3; ++k)
  {
    __m128 a = _mm_loadu_ps(tri + 3 * k);
    __m128 b = _mm_loadu_ps(t1 + 3 * k);
    __m128 c = _mm_loadu_ps(t2 + 3 * k);
    __m128 d = _mm_loadu_ps(t3 + 3 * k);
    _MM_TRANSPOSE4_PS(a, b, c, d); // a, b, c: the x, y, z rows of vertex k
    v[3 * k] = a;
    v[3 * k + 1] = b;
    v[3 * k + 2] = c;
  }
  return detail::triangleCandidatesRows4(r, v);
}
#else
template <int N>
inline int intersectBoxesScalar(const ConservativeRay4& r, const BoxPack<N>& b, float tmaxScaled, float tnear[N])
{
  const float(*rows[2])[N] = { b.lo, b.hi };
  int mask = 0;
  for (int i = 0; i < N; ++i)
  {
    float tn = r.tmin, tf = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a)
    {
      tn = std::max(tn, (rows[r.rows.nearHi[a]][a][i] - r.oNear[a]) * r.inv[a]);
      tf = std::min(tf, (rows[1 - r.rows.nearHi[a]][a][i] - r.oFar[a]) * r.inv[a]);
    }
    tf = std::min(tf * ConservativeRay4::kFarScale + ConservativeRay4::kTiny, tmaxScaled);
    tnear[i] = tn;
    mask |= (tn <= tf) ? (1 << i) : 0;
  }
  return mask;
}

inline int intersectBoxes4(const ConservativeRay4& r, const BoxPack4& b, float tmaxScaled, float tnear[4])
{
  return intersectBoxesScalar(r, b, tmaxScaled, tnear);
}

/// Without SSE: the ray itself.
struct ConservativeBoxRay4
{
  ConservativeRay4 ray;
  explicit ConservativeBoxRay4(const ConservativeRay4& r)
    : ray(r)
  {
  }
};

inline int intersectBoxes4(const ConservativeBoxRay4& r, const BoxPack4& b, float tmaxScaled, float tnear[4])
{
  return intersectBoxes4(r.ray, b, tmaxScaled, tnear);
}

inline int intersectBoxes8(const ConservativeBoxRay4& r, const BoxPack8& b, float tmaxScaled, float tnear[8])
{
  return intersectBoxesScalar(r.ray, b, tmaxScaled, tnear);
}

inline int intersectBoxes8(const ConservativeBoxRay4& r, const QuantizedBoxPack8& b, float tmaxScaled, float tnear[8])
{
  return intersectBoxesScalar(r.ray, b.decoded(), tmaxScaled, tnear) & b.valid;
}

inline int triangleCandidates4(const ConservativeRay4& r, const TrianglePack4& p)
{
  int mask = 0;
  for (int i = 0; i < 4; ++i)
  {
    float X[3], Y[3], S = 0.0f;
    for (int k = 0; k < 3; ++k)
    {
      const float z = p.v[3 * k + r.kz][i] - r.org[r.kz];
      X[k] = (p.v[3 * k + r.kx][i] - r.org[r.kx]) - r.sx * z;
      Y[k] = (p.v[3 * k + r.ky][i] - r.org[r.ky]) - r.sy * z;
      S = std::max(S, std::abs(X[k]) + std::abs(Y[k]));
    }
    const float U = X[2] * Y[1] - Y[2] * X[1];
    const float V = X[0] * Y[2] - Y[0] * X[2];
    const float W = X[1] * Y[0] - Y[1] * X[0];
    const float m = S * (4.0f * r.E + 8.0f * ConservativeRay4::kUnit * S) + (8.0f * r.E * r.E + ConservativeRay4::kTiny);
    const bool neg = U < -m || V < -m || W < -m;
    const bool pos = U > m || V > m || W > m;
    mask |= (neg && pos) ? 0 : (1 << i);
  }
  return mask;
}

inline int triangleCandidates4(const ConservativeRay4& r, const float* tri, int n)
{
  TrianglePack4 pack;
  for (int i = 0; i < 4; ++i)
  {
    const float* t = tri + 9 * (i < n ? i : 0);
    for (int k = 0; k < 9; ++k)
    {
      pack.v[k][i] = t[k];
    }
  }
  return triangleCandidates4(r, pack);
}
#endif

#if VTKRT_CORE_AVX2
/// The box constants of a ConservativeRay4 for the eight-wide AVX2 box test.
struct ConservativeBoxRay8
{
  __m256 oNear[3], oFar[3], inv[3], tmin;
  int qNear[3], qFar[3]; ///< byte offsets of the rows in a QuantizedBoxPack8's q

  VTKRT_TARGET_AVX2 explicit ConservativeBoxRay8(const ConservativeRay4& r)
  {
    for (int a = 0; a < 3; ++a)
    {
      oNear[a] = _mm256_set1_ps(r.oNear[a]);
      oFar[a] = _mm256_set1_ps(r.oFar[a]);
      inv[a] = _mm256_set1_ps(r.inv[a]);
      qNear[a] = r.rows.qNear[a];
      qFar[a] = r.rows.qFar[a];
    }
    tmin = _mm256_set1_ps(r.tmin);
  }
};

/// intersectBoxes8 on a QuantizedBoxPack8 in one AVX2 step: the same
/// decode and operations as the SSE form, the same bits.
VTKRT_TARGET_AVX2 inline int intersectBoxes8(const ConservativeBoxRay8& r, const QuantizedBoxPack8& b, float tmaxScaled, float tnear[8])
{
  const std::uint8_t* q = &b.q[0][0];
  __m256 tn = r.tmin;
  __m256 tf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  for (int a = 0; a < 3; ++a)
  {
    const __m256 origin = _mm256_set1_ps(b.origin[a]), step = _mm256_set1_ps(b.step(a));
    const __m256 nearPlane = _mm256_add_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(
      _mm_loadl_epi64(reinterpret_cast<const __m128i*>(q + r.qNear[a])))), step), origin);
    const __m256 farPlane = _mm256_add_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(
      _mm_loadl_epi64(reinterpret_cast<const __m128i*>(q + r.qFar[a])))), step), origin);
    tn = _mm256_max_ps(tn, _mm256_mul_ps(_mm256_sub_ps(nearPlane, r.oNear[a]), r.inv[a]));
    tf = _mm256_min_ps(tf, _mm256_mul_ps(_mm256_sub_ps(farPlane, r.oFar[a]), r.inv[a]));
  }
  tf = _mm256_add_ps(_mm256_mul_ps(tf, _mm256_set1_ps(ConservativeRay4::kFarScale)),
    _mm256_set1_ps(ConservativeRay4::kTiny));
  tf = _mm256_min_ps(tf, _mm256_set1_ps(tmaxScaled));
  _mm256_storeu_ps(tnear, tn);
  return _mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OS)) & b.valid;
}

/// triangleCandidates4 over eight triangles (1 <= n <= 8) in one AVX2 step:
/// the same operations in each lane, so the same bits as two calls of it.
VTKRT_TARGET_AVX2 inline int triangleCandidates8(const ConservativeRay4& r, const float* tri, int n)
{
  const float* t[8];
  for (int i = 0; i < 8; ++i)
  {
    t[i] = tri + 9 * std::min(i, n - 1); // lanes from n on repeat the last triangle
  }
  __m256 v[9];
  for (int k = 0; k < 3; ++k)
  {
    __m256 m[4];
    for (int j = 0; j < 4; ++j)
    {
      // Lane j in the low half, lane j + 4 in the high half.
      m[j] = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(t[j] + 3 * k)), _mm_loadu_ps(t[j + 4] + 3 * k), 1);
    }
    // _MM_TRANSPOSE4_PS in each half: the x, y, z rows of vertex k.
    const __m256 lo01 = _mm256_unpacklo_ps(m[0], m[1]), lo23 = _mm256_unpacklo_ps(m[2], m[3]);
    const __m256 hi01 = _mm256_unpackhi_ps(m[0], m[1]), hi23 = _mm256_unpackhi_ps(m[2], m[3]);
    v[3 * k] = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(1, 0, 1, 0));
    v[3 * k + 1] = _mm256_shuffle_ps(lo01, lo23, _MM_SHUFFLE(3, 2, 3, 2));
    v[3 * k + 2] = _mm256_shuffle_ps(hi01, hi23, _MM_SHUFFLE(1, 0, 1, 0));
  }
  // detail::triangleCandidatesRows4, eight lanes. A copy, not a shared
  // template: the SSE body must build without AVX2 and this one only with
  // it (a default-target body cannot inline the AVX2 intrinsics), and
  // TestCoreConservativeFloat checks the two agree bit for bit.
  const __m256 ox = _mm256_set1_ps(r.org[r.kx]), oy = _mm256_set1_ps(r.org[r.ky]), oz = _mm256_set1_ps(r.org[r.kz]);
  const __m256 sx = _mm256_set1_ps(r.sx), sy = _mm256_set1_ps(r.sy);
  const __m256 signBit = _mm256_set1_ps(-0.0f);
  __m256 X[3], Y[3], S = _mm256_setzero_ps();
  for (int k = 0; k < 3; ++k)
  {
    const __m256 z = _mm256_sub_ps(v[3 * k + r.kz], oz);
    X[k] = _mm256_sub_ps(_mm256_sub_ps(v[3 * k + r.kx], ox), _mm256_mul_ps(sx, z));
    Y[k] = _mm256_sub_ps(_mm256_sub_ps(v[3 * k + r.ky], oy), _mm256_mul_ps(sy, z));
    S = _mm256_max_ps(S, _mm256_add_ps(_mm256_andnot_ps(signBit, X[k]), _mm256_andnot_ps(signBit, Y[k])));
  }
  const __m256 U = _mm256_sub_ps(_mm256_mul_ps(X[2], Y[1]), _mm256_mul_ps(Y[2], X[1]));
  const __m256 V = _mm256_sub_ps(_mm256_mul_ps(X[0], Y[2]), _mm256_mul_ps(Y[0], X[2]));
  const __m256 W = _mm256_sub_ps(_mm256_mul_ps(X[1], Y[0]), _mm256_mul_ps(Y[1], X[0]));
  const __m256 E = _mm256_set1_ps(r.E);
  const __m256 m = _mm256_add_ps(
    _mm256_mul_ps(S, _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(4.0f), E), _mm256_mul_ps(_mm256_set1_ps(8.0f * ConservativeRay4::kUnit), S))),
    _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(8.0f), _mm256_mul_ps(E, E)), _mm256_set1_ps(ConservativeRay4::kTiny)));
  const __m256 negM = _mm256_sub_ps(_mm256_setzero_ps(), m);
  const __m256 neg = _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, negM, _CMP_LT_OS), _mm256_cmp_ps(V, negM, _CMP_LT_OS)),
    _mm256_cmp_ps(W, negM, _CMP_LT_OS));
  const __m256 pos = _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, m, _CMP_GT_OS), _mm256_cmp_ps(V, m, _CMP_GT_OS)),
    _mm256_cmp_ps(W, m, _CMP_GT_OS));
  return ~_mm256_movemask_ps(_mm256_and_ps(neg, pos)) & 0xff;
}
#endif

} // namespace vtkrt::core

#endif
