// Ray/plane test with the parallel case handled explicitly.
#ifndef vtkrt_core_Plane_h
#define vtkrt_core_Plane_h

#include "vtkrt/core/Ray.h"

namespace vtkrt::core
{

/// Plane through `point` with normal `normal` (any length, non-zero).
template <class T>
struct Plane
{
  Vec3<T> point;
  Vec3<T> normal;

  /// Signed distance times |normal|: > 0 on the side the normal points to.
  T evaluate(const Vec3<T>& p) const { return glm::dot(normal, p - point); }
};

enum class PlaneHit
{
  Miss,     ///< the crossing lies outside [tmin, tmax]
  Hit,      ///< t set
  Parallel, ///< direction parallel to the plane: no single crossing (the
            ///< ray lies in the plane or never meets it; see evaluate())
};

/// Crossing of the ray with the plane. A direction exactly parallel to the
/// plane (n . d == 0) returns Parallel instead of dividing by zero; nearly
/// parallel directions give a huge t that the [tmin, tmax] check rejects.
template <class T>
inline PlaneHit intersectRayPlane(const Ray<T>& ray, const Plane<T>& plane, T& t)
{
  const T denom = glm::dot(plane.normal, ray.dir);
  if (denom == T(0))
  {
    return PlaneHit::Parallel;
  }
  const T tt = glm::dot(plane.normal, plane.point - ray.org) / denom;
  if (!(tt >= ray.tmin && tt <= ray.tmax))
  {
    return PlaneHit::Miss;
  }
  t = tt;
  return PlaneHit::Hit;
}

} // namespace vtkrt::core

#endif
