// Ray/tube-piece test: one segment of a line drawn as a round tube is the
// convex hull of two spheres, (a, ra) and (b, rb) — a capsule when the radii
// are equal, a "round cone" when they differ (a tube of constant screen
// width under perspective grows with depth). Consecutive segments share
// their joint sphere, so a polyline is one closed, gapless solid.
#ifndef vtkrt_core_Capsule_h
#define vtkrt_core_Capsule_h

#include "vtkrt/core/Sphere.h"

#include <algorithm>
#include <cmath>

namespace vtkrt::core
{

/// Nearest hit t in [ray.tmin, ray.tmax] of the ray with the hull of the
/// spheres (a, ra) and (b, rb) (ra, rb >= 0). The end spheres are tested by
/// the stable sphere test; the body, the cone tangent to both, by a
/// quadratic written so that nothing large cancels: the ray's origin is
/// first moved along the ray to its point nearest the segment's middle, and
/// the discriminant is |w0 pd - w1 po|^2 - |po x pd|^2 (the Lagrange
/// identity of B^2 - A C), po and pd the origin's and direction's parts
/// across the axis, w0 + w1 t the cone's radius along the ray. A body root
/// counts only between the tangency circles. A zero-length segment is its
/// larger sphere.
template <class T>
inline bool intersectRayTube(const Ray<T>& ray, const Vec3<T>& a, const Vec3<T>& b, T ra, T rb, T& t)
{
  bool found = false;
  T best = ray.tmax;
  T hit = T(0);
  if (intersectRaySphere(Ray<T>(ray.org, ray.dir, ray.tmin, best), a, ra, hit))
  {
    best = hit;
    found = true;
  }
  if (intersectRaySphere(Ray<T>(ray.org, ray.dir, ray.tmin, best), b, rb, hit))
  {
    best = hit;
    found = true;
  }
  const Vec3<T> ba = b - a;
  const T m0 = glm::dot(ba, ba);
  const T rr = ra - rb;
  const T d2 = m0 - rr * rr; // > 0: neither sphere holds the other
  const T dd = glm::dot(ray.dir, ray.dir);
  if (d2 > T(0) && dd > T(0))
  {
    const T len = std::sqrt(m0);
    const Vec3<T> u = ba / len;
    const Vec3<T> mid = a + T(0.5) * ba;
    const T shift = glm::dot(mid - ray.org, ray.dir) / dd;
    const Vec3<T> oa = (ray.org + shift * ray.dir) - a;
    const T zo = glm::dot(oa, u);
    const T zd = glm::dot(ray.dir, u);
    const Vec3<T> po = oa - zo * u;
    const Vec3<T> pd = ray.dir - zd * u;
    // The cone's radius across the axis at axial distance z: c (ra - rr z / len).
    const T c = len / std::sqrt(d2);
    const T slope = c * rr / len;
    const T w0 = c * ra - slope * zo;
    const T w1 = -slope * zd;
    const T qa = glm::dot(pd, pd) - w1 * w1;
    const T qb = glm::dot(po, pd) - w0 * w1;
    const T qc = glm::dot(po, po) - w0 * w0;
    const Vec3<T> e = w0 * pd - w1 * po;
    const Vec3<T> x = glm::cross(po, pd);
    const T disc = glm::dot(e, e) - glm::dot(x, x);
    if (disc >= T(0) && qa != T(0))
    {
      const T s = std::sqrt(disc);
      const T q = -(qb + std::copysign(s, qb));
      // The tangency circles lie at these axial distances from a.
      const T zlo = ra * rr / len;
      const T zhi = (d2 + ra * rr) / len;
      const T roots[2] = { qc / q, q / qa };
      for (const T r : roots)
      {
        const T z = zo + r * zd;
        const T tr = shift + r;
        if (z > zlo && z < zhi && tr >= ray.tmin && tr <= best)
        {
          best = tr;
          found = true;
        }
      }
    }
  }
  if (found)
  {
    t = best;
  }
  return found;
}

/// Where a surface point p of the tube piece lies along it: the parameter
/// s in [0, 1] of the sphere center a + s (b - a) whose sphere touches the
/// surface at p (0 or 1 on the end caps). The outward normal at p is
/// p - (a + s (b - a)); point colors interpolate by s.
template <class T>
inline T tubeParameter(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, T ra, T rb)
{
  const Vec3<T> ba = b - a;
  const T rr = ra - rb;
  const T d2 = glm::dot(ba, ba) - rr * rr;
  if (!(d2 > T(0)))
  {
    return ra >= rb ? T(0) : T(1);
  }
  const T s = (glm::dot(p - a, ba) - ra * rr) / d2;
  return std::min(T(1), std::max(T(0), s));
}

} // namespace vtkrt::core

#endif
