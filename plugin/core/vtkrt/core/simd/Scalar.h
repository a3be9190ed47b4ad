// The four-wide pre-tests as plain loops, where the compiler targets no SSE:
// the functions of simd/Sse.h, the same float operations lane by lane.
#ifndef vtkrt_core_simd_Scalar_h
#define vtkrt_core_simd_Scalar_h

#include "vtkrt/core/ConservativeRay.h"
#include "vtkrt/core/simd/Dispatch.h"
#include "vtkrt/core/simd/Packs.h"
#include "vtkrt/core/simd/QuantizedBox.h"

#include <algorithm>
#include <cmath>
#include <limits>

#if !VTKRT_CORE_SSE
namespace vtkrt::core
{

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
} // namespace vtkrt::core
#endif

#endif
