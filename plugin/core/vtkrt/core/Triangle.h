// Ray/triangle (watertight) and point/triangle (closest point) kernels.
#ifndef vtkrt_core_Triangle_h
#define vtkrt_core_Triangle_h

#include "vtkrt/core/Ray.h"

#include <type_traits>

namespace vtkrt::core
{

/// Per-ray data of the watertight test: the axis permutation and shear that
/// map the ray direction onto +z (Woop, Benthin & Wald 2013, "Watertight
/// Ray/Triangle Intersection", JCGT 2(1)).
template <class T>
struct RayTrianglePrecomputed
{
  Vec3<T> org;
  int kx, ky, kz;
  T sx, sy, sz;

  explicit RayTrianglePrecomputed(const Ray<T>& ray)
    : org(ray.org)
  {
    kz = maxAbsDimension(ray.dir);
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    // Keep the winding independent of the direction sign.
    if (ray.dir[kz] < T(0))
    {
      const int tmp = kx;
      kx = ky;
      ky = tmp;
    }
    sx = ray.dir[kx] / ray.dir[kz];
    sy = ray.dir[ky] / ray.dir[kz];
    sz = T(1) / ray.dir[kz];
  }
};

/// Result of a ray/triangle test. Barycentrics follow VTK's triangle pcoords:
/// hit point = (1 - u - v) * v0 + u * v1 + v * v2.
template <class T>
struct TriangleHit
{
  T t = T(0);
  T u = T(0);
  T v = T(0);
};

/// Watertight ray/triangle test: rays through a shared edge or vertex of a
/// closed mesh hit at least one of the triangles there. Both windings hit (no
/// culling). Accepts t in [tmin, tmax]. Degenerate (zero-area) triangles never
/// hit. In float, an edge function that evaluates to exactly 0 is recomputed
/// in double, as the paper prescribes.
template <class T>
inline bool intersectRayTriangle(const RayTrianglePrecomputed<T>& r, const Vec3<T>& v0,
  const Vec3<T>& v1, const Vec3<T>& v2, T tmin, T tmax, TriangleHit<T>& hit)
{
  const Vec3<T> Av = v0 - r.org;
  const Vec3<T> Bv = v1 - r.org;
  const Vec3<T> Cv = v2 - r.org;
  // Component access by index through the contiguous storage (what
  // glm::value_ptr does): glm's operator[] is a switch.
  const T* A = &Av.x;
  const T* B = &Bv.x;
  const T* C = &Cv.x;

  const T Ax = A[r.kx] - r.sx * A[r.kz];
  const T Ay = A[r.ky] - r.sy * A[r.kz];
  const T Bx = B[r.kx] - r.sx * B[r.kz];
  const T By = B[r.ky] - r.sy * B[r.kz];
  const T Cx = C[r.kx] - r.sx * C[r.kz];
  const T Cy = C[r.ky] - r.sy * C[r.kz];

  T U = Cx * By - Cy * Bx;
  T V = Ax * Cy - Ay * Cx;
  T W = Bx * Ay - By * Ax;

  if constexpr (std::is_same_v<T, float>)
  {
    if (U == 0.0f || V == 0.0f || W == 0.0f)
    {
      const double CxBy = double(Cx) * double(By);
      const double CyBx = double(Cy) * double(Bx);
      U = float(CxBy - CyBx);
      const double AxCy = double(Ax) * double(Cy);
      const double AyCx = double(Ay) * double(Cx);
      V = float(AxCy - AyCx);
      const double BxAy = double(Bx) * double(Ay);
      const double ByAx = double(By) * double(Ax);
      W = float(BxAy - ByAx);
    }
  }

  if ((U < T(0) || V < T(0) || W < T(0)) && (U > T(0) || V > T(0) || W > T(0)))
  {
    return false;
  }
  const T det = U + V + W;
  if (det == T(0) || std::isnan(det))
  {
    return false;
  }

  const T Az = r.sz * A[r.kz];
  const T Bz = r.sz * B[r.kz];
  const T Cz = r.sz * C[r.kz];
  const T Tsc = U * Az + V * Bz + W * Cz;

  const T rcpDet = T(1) / det;
  const T t = Tsc * rcpDet;
  if (!(t >= tmin && t <= tmax))
  {
    return false;
  }
  hit.t = t;
  hit.u = V * rcpDet;
  hit.v = W * rcpDet;
  return true;
}

template <class T>
inline bool intersectRayTriangle(
  const Ray<T>& ray, const Vec3<T>& v0, const Vec3<T>& v1, const Vec3<T>& v2, TriangleHit<T>& hit)
{
  return intersectRayTriangle(RayTrianglePrecomputed<T>(ray), v0, v1, v2, ray.tmin, ray.tmax, hit);
}

/// Geometric (unnormalized) normal, right-handed from the vertex order.
template <class T>
inline Vec3<T> triangleNormal(const Vec3<T>& v0, const Vec3<T>& v1, const Vec3<T>& v2)
{
  return glm::cross(v1 - v0, v2 - v0);
}

/// True when the triangle has finite vertices and non-zero area.
template <class T>
inline bool isValidTriangle(const Vec3<T>& v0, const Vec3<T>& v1, const Vec3<T>& v2)
{
  if (!isFinite(v0) || !isFinite(v1) || !isFinite(v2))
  {
    return false;
  }
  const Vec3<T> n = triangleNormal(v0, v1, v2);
  return n.x != T(0) || n.y != T(0) || n.z != T(0);
}

/// Closest point on triangle (a, b, c) to p, by Voronoi regions (Ericson,
/// "Real-Time Collision Detection", 5.1.5). Also returns the barycentrics
/// (u weights b, v weights c, as in TriangleHit).
template <class T>
inline Vec3<T> closestPointOnTriangle(
  const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, T& u, T& v)
{
  const Vec3<T> ab = b - a;
  const Vec3<T> ac = c - a;
  const Vec3<T> ap = p - a;
  const T d1 = glm::dot(ab, ap);
  const T d2 = glm::dot(ac, ap);
  if (d1 <= T(0) && d2 <= T(0))
  {
    u = v = T(0);
    return a;
  }
  const Vec3<T> bp = p - b;
  const T d3 = glm::dot(ab, bp);
  const T d4 = glm::dot(ac, bp);
  if (d3 >= T(0) && d4 <= d3)
  {
    u = T(1);
    v = T(0);
    return b;
  }
  const T vc = d1 * d4 - d3 * d2;
  if (vc <= T(0) && d1 >= T(0) && d3 <= T(0))
  {
    const T w = d1 / (d1 - d3);
    u = w;
    v = T(0);
    return a + w * ab;
  }
  const Vec3<T> cp = p - c;
  const T d5 = glm::dot(ab, cp);
  const T d6 = glm::dot(ac, cp);
  if (d6 >= T(0) && d5 <= d6)
  {
    u = T(0);
    v = T(1);
    return c;
  }
  const T vb = d5 * d2 - d1 * d6;
  if (vb <= T(0) && d2 >= T(0) && d6 <= T(0))
  {
    const T w = d2 / (d2 - d6);
    u = T(0);
    v = w;
    return a + w * ac;
  }
  const T va = d3 * d6 - d5 * d4;
  if (va <= T(0) && (d4 - d3) >= T(0) && (d5 - d6) >= T(0))
  {
    const T w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    u = T(1) - w;
    v = w;
    return b + w * (c - b);
  }
  const T denom = T(1) / (va + vb + vc);
  u = vb * denom;
  v = vc * denom;
  return a + ab * u + ac * v;
}

template <class T>
inline Vec3<T> closestPointOnTriangle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c)
{
  T u, v;
  return closestPointOnTriangle(p, a, b, c, u, v);
}

} // namespace vtkrt::core

#endif
