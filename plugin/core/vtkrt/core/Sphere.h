// Numerically stable ray/sphere test.
#ifndef vtkrt_core_Sphere_h
#define vtkrt_core_Sphere_h

#include "vtkrt/core/Ray.h"

namespace vtkrt::core
{

/// Both roots of a ray/sphere test, t0 <= t1 (equal when tangent).
template <class T>
struct SphereRoots
{
  T t0;
  T t1;
};

/// Ray/sphere roots after Haines, Guenther & Akenine-Moeller, "Precision
/// Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7):
/// the discriminant is a * (r^2 - |f - (b'/a) d|^2) instead of b'^2 - a c,
/// so a small sphere far away does not cancel to nothing, and the roots come
/// from q = -(b' + sign(b') sqrt(D)): t0 = c / q, t1 = q / a (no subtraction
/// of nearly equal numbers). dir need not be unit length. Returns false when
/// the line misses the sphere (ignores [tmin, tmax]; see intersectRaySphere).
template <class T>
inline bool raySphereRoots(
  const Vec3<T>& org, const Vec3<T>& dir, const Vec3<T>& center, T radius, SphereRoots<T>& roots)
{
  const Vec3<T> f = org - center;
  const T a = glm::dot(dir, dir);
  const T bPrime = glm::dot(f, dir); // b / 2 of the textbook quadratic
  const T c = glm::dot(f, f) - radius * radius;
  const Vec3<T> l = f - (bPrime / a) * dir; // f minus its projection on dir
  const T disc = a * (radius * radius - glm::dot(l, l));
  if (!(disc >= T(0)) || !(a > T(0)))
  {
    return false;
  }
  const T s = std::sqrt(disc); // sqrt(b'^2 - a c)
  const T q = -(bPrime + std::copysign(s, bPrime));
  if (q == T(0))
  {
    // b' == 0 and disc == 0: tangent at the origin itself, double root t = 0.
    roots.t0 = roots.t1 = T(0);
    return true;
  }
  T t0 = c / q;
  T t1 = q / a;
  if (t1 < t0)
  {
    const T tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  roots.t0 = t0;
  roots.t1 = t1;
  return true;
}

/// Nearest root within [tmin, tmax]: t0 if it lies there, else t1 (origin
/// inside the sphere). Tangent rays (disc == 0) hit with t0 == t1.
template <class T>
inline bool intersectRaySphere(const Ray<T>& ray, const Vec3<T>& center, T radius, T& t)
{
  SphereRoots<T> roots;
  if (!raySphereRoots(ray.org, ray.dir, center, radius, roots))
  {
    return false;
  }
  if (roots.t0 >= ray.tmin && roots.t0 <= ray.tmax)
  {
    t = roots.t0;
    return true;
  }
  if (roots.t1 >= ray.tmin && roots.t1 <= ray.tmax)
  {
    t = roots.t1;
    return true;
  }
  return false;
}

/// Outward unit normal at a surface point p.
template <class T>
inline Vec3<T> sphereNormal(const Vec3<T>& p, const Vec3<T>& center)
{
  return glm::normalize(p - center);
}

/// True when the sphere has a finite center and a finite positive radius.
template <class T>
inline bool isValidSphere(const Vec3<T>& center, T radius)
{
  return isFinite(center) && std::isfinite(radius) && radius > T(0);
}

} // namespace vtkrt::core

#endif
