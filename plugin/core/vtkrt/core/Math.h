// Scalar and vector helpers shared by every core header: the Vec3 alias,
// floating-point error bounds and outward rounding.
#ifndef vtkrt_core_Math_h
#define vtkrt_core_Math_h

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

namespace vtkrt::core
{

template <class T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

/// Sentinel for "no primitive / no instance".
constexpr std::uint32_t kInvalidIndex = 0xffffffffu;

/// Higham's gamma(n) = n*u / (1 - n*u), u = unit roundoff: bounds the relative
/// error of n chained floating-point operations (used by the slab test).
template <class T>
constexpr T gammaBound(int n)
{
  constexpr T u = std::numeric_limits<T>::epsilon() * T(0.5);
  return (T(n) * u) / (T(1) - T(n) * u);
}

template <class T>
inline bool isFinite(const Vec3<T>& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Largest float <= x (x rounded toward -inf); for conservative float boxes.
inline float roundDownToFloat(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x)
  {
    f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  }
  return f;
}

/// Smallest float >= x (x rounded toward +inf).
inline float roundUpToFloat(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x)
  {
    f = std::nextafter(f, std::numeric_limits<float>::infinity());
  }
  return f;
}

/// Index (0, 1, 2) of the component with the largest magnitude.
template <class T>
inline int maxAbsDimension(const Vec3<T>& v)
{
  const T ax = std::abs(v.x), ay = std::abs(v.y), az = std::abs(v.z);
  return ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
}

} // namespace vtkrt::core

#endif
