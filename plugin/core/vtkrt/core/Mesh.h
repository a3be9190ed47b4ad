// Primitive sets the BVH is built over (indexed triangle meshes, spheres),
// their bounds, and the intersector / closest-point callables the
// traversals take. Views only: the caller owns the arrays.
#ifndef vtkrt_core_Mesh_h
#define vtkrt_core_Mesh_h

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/Sphere.h"
#include "vtkrt/core/Triangle.h"

namespace vtkrt::core
{

/// Indexed triangle mesh: triangle i is vertices[indices[3i..3i+2]].
/// Vec3<double> is layout-compatible with double[3].
template <class T>
struct TriangleMesh
{
  const Vec3<T>* vertices = nullptr;
  std::size_t vertexCount = 0;
  const std::uint32_t* indices = nullptr;
  std::size_t triangleCount = 0;

  TriangleMesh() = default;
  TriangleMesh(const std::vector<Vec3<T>>& v, const std::vector<std::uint32_t>& i)
    : vertices(v.data())
    , vertexCount(v.size())
    , indices(i.data())
    , triangleCount(i.size() / 3)
  {
  }

  /// False when an index is out of range.
  bool triangle(std::size_t tri, Vec3<T>& a, Vec3<T>& b, Vec3<T>& c) const
  {
    const std::uint32_t* t = indices + 3 * tri;
    if (t[0] >= vertexCount || t[1] >= vertexCount || t[2] >= vertexCount)
    {
      return false;
    }
    a = vertices[t[0]];
    b = vertices[t[1]];
    c = vertices[t[2]];
    return true;
  }
};

/// Spheres: centers[i], radii[i] (or one shared radius when radii is null).
template <class T>
struct SphereSet
{
  const Vec3<T>* centers = nullptr;
  const T* radii = nullptr;
  T radius = T(0);
  std::size_t count = 0;

  SphereSet() = default;
  SphereSet(const std::vector<Vec3<T>>& c, const std::vector<T>& r)
    : centers(c.data())
    , radii(r.data())
    , count(std::min(c.size(), r.size()))
  {
  }
  T radiusOf(std::size_t i) const { return radii ? radii[i] : radius; }
};

/// Why a primitive has no box.
enum class PrimitiveStatus
{
  Valid,
  Degenerate, ///< zero area / zero radius
  NonFinite,  ///< NaN or infinite coordinates, or an index out of range
};

/// Bounds of triangle i; an empty box (skipped by the builders) for
/// degenerate, non-finite or out-of-range triangles.
inline AABB<double> triangleBox(const TriangleMesh<double>& mesh, std::size_t i, PrimitiveStatus* status = nullptr)
{
  Vec3<double> a(0.0), b(0.0), c(0.0);
  AABB<double> box;
  PrimitiveStatus st = PrimitiveStatus::Valid;
  if (!mesh.triangle(i, a, b, c) || !isFinite(a) || !isFinite(b) || !isFinite(c))
  {
    st = PrimitiveStatus::NonFinite;
  }
  else if (!isValidTriangle(a, b, c))
  {
    st = PrimitiveStatus::Degenerate;
  }
  else
  {
    box.extend(a);
    box.extend(b);
    box.extend(c);
  }
  if (status)
  {
    *status = st;
  }
  return box;
}

/// Bounds of every triangle (see triangleBox). Counts go to
/// stats.degeneratePrimitives / nonFinitePrimitives when given.
inline std::vector<AABB<double>> triangleBounds(const TriangleMesh<double>& mesh, BuildStats* stats = nullptr)
{
  std::vector<AABB<double>> bounds(mesh.triangleCount);
  std::size_t degenerate = 0, nonFinite = 0;
  for (std::size_t i = 0; i < mesh.triangleCount; ++i)
  {
    PrimitiveStatus st;
    bounds[i] = triangleBox(mesh, i, &st);
    degenerate += st == PrimitiveStatus::Degenerate;
    nonFinite += st == PrimitiveStatus::NonFinite;
  }
  if (stats)
  {
    stats->degeneratePrimitives = degenerate;
    stats->nonFinitePrimitives = nonFinite;
  }
  return bounds;
}

inline std::vector<AABB<double>> sphereBounds(const SphereSet<double>& spheres, BuildStats* stats = nullptr)
{
  std::vector<AABB<double>> bounds(spheres.count);
  std::size_t degenerate = 0, nonFinite = 0;
  for (std::size_t i = 0; i < spheres.count; ++i)
  {
    const Vec3<double>& c = spheres.centers[i];
    const double r = spheres.radiusOf(i);
    if (!isFinite(c) || !std::isfinite(r))
    {
      ++nonFinite;
      continue;
    }
    if (!(r > 0.0))
    {
      ++degenerate;
      continue;
    }
    bounds[i] = AABB<double>(c - Vec3<double>(r), c + Vec3<double>(r));
  }
  if (stats)
  {
    stats->degeneratePrimitives = degenerate;
    stats->nonFinitePrimitives = nonFinite;
  }
  return bounds;
}

inline BVH buildTriangleBVH(const TriangleMesh<double>& mesh, const BuildOptions& options = BuildOptions())
{
  std::size_t degenerate = 0, nonFinite = 0;
  BVH bvh = buildBVH(
    mesh.triangleCount,
    [&](std::size_t i) {
      PrimitiveStatus st;
      const AABB<double> box = triangleBox(mesh, i, &st);
      degenerate += st == PrimitiveStatus::Degenerate;
      nonFinite += st == PrimitiveStatus::NonFinite;
      return box;
    },
    options);
  bvh.stats.degeneratePrimitives = degenerate;
  bvh.stats.nonFinitePrimitives = nonFinite;
  return bvh;
}

inline BVH buildSphereBVH(const SphereSet<double>& spheres, const BuildOptions& options = BuildOptions())
{
  BuildStats counts;
  const auto start = std::chrono::steady_clock::now();
  BVH bvh = buildBVH(sphereBounds(spheres, &counts), options);
  bvh.stats.degeneratePrimitives = counts.degeneratePrimitives;
  bvh.stats.nonFinitePrimitives = counts.nonFinitePrimitives;
  bvh.stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

/// Watertight ray/triangle callable for the traversals. Caches the per-ray
/// shear, so make one per query (or per thread); it is cheap.
template <class T>
class TriangleIntersector
{
public:
  explicit TriangleIntersector(const TriangleMesh<T>& mesh)
    : Mesh(mesh)
  {
  }

  bool operator()(std::uint32_t prim, const Ray<T>& ray, Hit<T>& hit)
  {
    if (!Cached || ray.org != CachedOrg || ray.dir != CachedDir)
    {
      Pre = RayTrianglePrecomputed<T>(ray);
      CachedOrg = ray.org;
      CachedDir = ray.dir;
      Cached = true;
    }
    Vec3<T> a(T(0)), b(T(0)), c(T(0));
    if (!Mesh.triangle(prim, a, b, c))
    {
      return false;
    }
    TriangleHit<T> th;
    if (!intersectRayTriangle(Pre, a, b, c, ray.tmin, ray.tmax, th))
    {
      return false;
    }
    hit.t = th.t;
    hit.u = th.u;
    hit.v = th.v;
    return true;
  }

private:
  TriangleMesh<T> Mesh;
  RayTrianglePrecomputed<T> Pre{ Ray<T>() };
  Vec3<T> CachedOrg{ T(0) }, CachedDir{ T(0) };
  bool Cached = false;
};

/// Stable ray/sphere callable (nearest root in range; hit.u = hit.v = 0).
template <class T>
class SphereIntersector
{
public:
  explicit SphereIntersector(const SphereSet<T>& spheres)
    : Spheres(spheres)
  {
  }
  bool operator()(std::uint32_t prim, const Ray<T>& ray, Hit<T>& hit) const
  {
    T t;
    if (!intersectRaySphere(ray, Spheres.centers[prim], Spheres.radiusOf(prim), t))
    {
      return false;
    }
    hit.t = t;
    hit.u = hit.v = T(0);
    return true;
  }

private:
  SphereSet<T> Spheres;
};

/// Closest point on a triangle (Ericson), for closestPoint().
template <class T>
class TriangleClosestPoint
{
public:
  explicit TriangleClosestPoint(const TriangleMesh<T>& mesh)
    : Mesh(mesh)
  {
  }
  bool operator()(std::uint32_t prim, const Vec3<T>& p, PointHit<T>& cand) const
  {
    Vec3<T> a(T(0)), b(T(0)), c(T(0));
    if (!Mesh.triangle(prim, a, b, c))
    {
      return false;
    }
    cand.point = closestPointOnTriangle(p, a, b, c);
    const Vec3<T> d = cand.point - p;
    cand.dist2 = glm::dot(d, d);
    return true;
  }

private:
  TriangleMesh<T> Mesh;
};

/// Closest point on a sphere's surface.
template <class T>
class SphereClosestPoint
{
public:
  explicit SphereClosestPoint(const SphereSet<T>& spheres)
    : Spheres(spheres)
  {
  }
  bool operator()(std::uint32_t prim, const Vec3<T>& p, PointHit<T>& cand) const
  {
    const Vec3<T>& c = Spheres.centers[prim];
    const T r = Spheres.radiusOf(prim);
    const Vec3<T> d = p - c;
    const T len = glm::length(d);
    // At the center every surface point is closest: pick +x.
    const Vec3<T> dir = len > T(0) ? d / len : Vec3<T>(T(1), T(0), T(0));
    cand.point = c + r * dir;
    const T dist = std::abs(len - r);
    cand.dist2 = dist * dist;
    return true;
  }

private:
  SphereSet<T> Spheres;
};

/// Triangles whose bounds overlap `box` (closed), in traversal order.
inline std::vector<std::uint32_t> trianglesOverlappingBox(
  const BVH& bvh, const TriangleMesh<double>& mesh, const AABB<double>& box)
{
  std::vector<std::uint32_t> out;
  queryBox(bvh, box, [&](std::uint32_t prim) {
    Vec3<double> a(0.0), b(0.0), c(0.0);
    if (!mesh.triangle(prim, a, b, c))
    {
      return;
    }
    AABB<double> tb;
    tb.extend(a);
    tb.extend(b);
    tb.extend(c);
    if (tb.overlaps(box))
    {
      out.push_back(prim);
    }
  });
  return out;
}

/// Refit a triangle BVH to the mesh's current vertex positions.
inline void refitTriangles(BVH& bvh, const TriangleMesh<double>& mesh)
{
  refit(bvh, [&mesh](std::uint32_t prim) {
    AABB<double> b;
    Vec3<double> v0(0.0), v1(0.0), v2(0.0);
    if (mesh.triangle(prim, v0, v1, v2))
    {
      b.extend(v0);
      b.extend(v1);
      b.extend(v2);
    }
    return b;
  });
}

} // namespace vtkrt::core

#endif
