// Directed rounding of doubles to floats and single float steps, through
// the float's bits: no libm call, no change of the rounding mode, and no
// branch on the rounding's direction. The conservative float pre-tests
// (ConservativeFloat.h) and the wide tree's boxes (WideNode.h) round outward
// with them.
#ifndef vtkrt_core_FloatRounding_h
#define vtkrt_core_FloatRounding_h

#include <cstdint>
#include <cstring>

namespace vtkrt::core::detail
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

} // namespace vtkrt::core::detail

#endif
