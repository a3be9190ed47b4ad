// The eight-wide AVX2 forms (simd/Dispatch.h: compiled per function, run
// where useAvx2()): the ray's setup (ConservativeRay4::initAvx2), eight
// boxes of a wide node and eight triangles a step, each the same operations
// in the same order as the SSE form, so the same bits.
#ifndef vtkrt_core_simd_Avx2_h
#define vtkrt_core_simd_Avx2_h

#include "vtkrt/core/ConservativeRay.h"
#include "vtkrt/core/simd/Dispatch.h"
#include "vtkrt/core/simd/QuantizedBox.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#if VTKRT_CORE_AVX2
namespace vtkrt::core
{

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
} // namespace vtkrt::core
#endif

#endif
