// The four-wide pre-tests in SSE: four boxes (of a BoxPack4, of a BoxPack8
// or of a wide node's QuantizedBoxPack8) or four triangles a step, for the
// constants of a ConservativeRay4. Without SSE, simd/Scalar.h has the same
// functions as plain loops.
#ifndef vtkrt_core_simd_Sse_h
#define vtkrt_core_simd_Sse_h

#include "vtkrt/core/ConservativeRay.h"
#include "vtkrt/core/simd/Dispatch.h"
#include "vtkrt/core/simd/Packs.h"
#include "vtkrt/core/simd/QuantizedBox.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#if VTKRT_CORE_SSE
namespace vtkrt::core
{

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
} // namespace vtkrt::core
#endif

#endif
