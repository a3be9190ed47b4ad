// Ray/plane: the crossing with a point-normal plane (parallel case handled
// explicitly) and the clip of a ray interval to a plane equation's kept side.
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

/// A plane as its equation n.p + d = 0, stored (n.x, n.y, n.z, d): the form
/// clip planes take (VTK's vtkPlane as the mapper hands it, the shader's
/// uniforms).
template <class T>
using PlaneEquation = glm::vec<4, T, glm::defaultp>;

/// The equation of a point-normal plane: n.p - n.point = 0.
template <class T>
inline PlaneEquation<T> planeEquation(const Plane<T>& plane)
{
  return PlaneEquation<T>(plane.normal, -glm::dot(plane.normal, plane.point));
}

/// Clips [tmin, tmax] to the half-space n.p + d >= 0 (what VTK keeps):
/// entering it raises tmin, leaving it lowers tmax to the crossing
/// t = -(n.org + d) / (n.dir). A ray parallel to the plane is kept or
/// clipped whole, by the side its origin lies on. Returns false when
/// nothing of the interval survives. The GLSL clipRayByPlane is this
/// function (its twin: core/GpuKernels.h).
template <class T>
inline bool clipRayByPlane(
  const Vec3<T>& org, const Vec3<T>& dir, const PlaneEquation<T>& plane, T& tmin, T& tmax)
{
  const Vec3<T> n(plane);
  const T denom = glm::dot(n, dir);
  const T f0 = glm::dot(n, org) + plane.w;
  if (denom == T(0))
  {
    return f0 >= T(0);
  }
  const T t = -f0 / denom;
  if (denom > T(0))
  {
    tmin = glm::max(tmin, t);
  }
  else
  {
    tmax = glm::min(tmax, t);
  }
  return tmin <= tmax;
}

} // namespace vtkrt::core

#endif
