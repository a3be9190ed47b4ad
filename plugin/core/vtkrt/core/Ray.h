// Rays (segments org + t*dir, t in [tmin, tmax]; dir need not be unit length,
// so a segment p1->p2 is org = p1, dir = p2 - p1, t in [0, 1]) and the robust
// ray/AABB slab test.
#ifndef vtkrt_core_Ray_h
#define vtkrt_core_Ray_h

#include "vtkrt/core/AABB.h"

#include <limits>

namespace vtkrt::core
{

template <class T>
struct Ray
{
  Vec3<T> org = Vec3<T>(T(0));
  Vec3<T> dir = Vec3<T>(T(0), T(0), T(1));
  T tmin = T(0);
  T tmax = std::numeric_limits<T>::infinity();

  Ray() = default;
  Ray(const Vec3<T>& o, const Vec3<T>& d, T t0 = T(0), T t1 = std::numeric_limits<T>::infinity())
    : org(o)
    , dir(d)
    , tmin(t0)
    , tmax(t1)
  {
  }

  Vec3<T> at(T t) const { return org + t * dir; }

  /// A ray that can hit something: finite origin and direction, non-zero
  /// direction, tmin <= tmax (tmax may be +inf), no NaN. Queries return "no
  /// hit" for invalid rays instead of walking the whole tree.
  bool isValid() const
  {
    return core::isFinite(org) && core::isFinite(dir) && (dir.x != T(0) || dir.y != T(0) || dir.z != T(0)) &&
      !std::isnan(tmin) && !std::isnan(tmax) && tmin <= tmax;
  }
};

/// Per-ray data reused by every box test: the inverse direction. A
/// component that is zero, or whose inverse overflows (|d| subnormal), is
/// "parallel" and stored as invDir = 0 (a real inverse is never 0), so the
/// slab test never forms 0 * inf = NaN. (Relying on NaN comparisons would
/// not carry over to GLSL, where NaN behaviour is undefined.)
template <class T>
struct RayBoxPrecomputed
{
  Vec3<T> org;
  Vec3<T> invDir;

  static T safeInverse(T d)
  {
    const T inv = T(1) / d;
    return std::abs(inv) <= std::numeric_limits<T>::max() ? inv : T(0);
  }

  explicit RayBoxPrecomputed(const Ray<T>& ray)
    : org(ray.org)
    , invDir(safeInverse(ray.dir.x), safeInverse(ray.dir.y), safeInverse(ray.dir.z))
  {
  }
};

namespace detail
{
/// One slab of intersectRayAABB. Returns false when the slab alone rules
/// the box out.
template <class T>
inline bool clipSlab(T lo, T hi, T org, T invDir, T& tmin, T& tmax)
{
  if (invDir == T(0))
  {
    // Parallel to the slab: inside it (closed) for every t, or never.
    return org >= lo && org <= hi;
  }
  constexpr T farScale = T(1) + T(2) * gammaBound<T>(3);
  T t0 = (lo - org) * invDir;
  T t1 = (hi - org) * invDir;
  if (t1 < t0)
  {
    const T tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  t1 *= farScale;
  tmin = t0 > tmin ? t0 : tmin;
  tmax = t1 < tmax ? t1 : tmax;
  return true;
}
} // namespace detail

/// Slab test, conservative under rounding (Ize 2013, "Robust BVH Ray
/// Traversal": each far distance is scaled by 1 + 2*gamma(3)). For a valid
/// ray (finite origin) and a finite box no NaN arises: parallel axes are
/// decided by the origin alone (closed interval, so a ray lying in a face
/// plane of a flat box hits it). On hit, tnear gets the entry distance
/// clamped to [tmin, tmax]. invDir as RayBoxPrecomputed makes it. The GLSL
/// intersectRayAABB is this function (its twin: core/GpuKernels.h).
template <class T>
inline bool intersectRayAABB(const Vec3<T>& org, const Vec3<T>& invDir, const Vec3<T>& bmin,
  const Vec3<T>& bmax, T tmin, T tmax, T& tnear)
{
  if (!detail::clipSlab(bmin.x, bmax.x, org.x, invDir.x, tmin, tmax) ||
    !detail::clipSlab(bmin.y, bmax.y, org.y, invDir.y, tmin, tmax) ||
    !detail::clipSlab(bmin.z, bmax.z, org.z, invDir.z, tmin, tmax))
  {
    return false;
  }
  tnear = tmin;
  return tmin <= tmax;
}

template <class T>
inline bool intersectRayAABB(
  const RayBoxPrecomputed<T>& r, const Vec3<T>& bmin, const Vec3<T>& bmax, T tmin, T tmax, T& tnear)
{
  return intersectRayAABB(r.org, r.invDir, bmin, bmax, tmin, tmax, tnear);
}

template <class T>
inline bool intersectRayAABB(const Ray<T>& ray, const AABB<T>& box, T& tnear)
{
  return intersectRayAABB(RayBoxPrecomputed<T>(ray), box.min, box.max, ray.tmin, ray.tmax, tnear);
}

} // namespace vtkrt::core

#endif
