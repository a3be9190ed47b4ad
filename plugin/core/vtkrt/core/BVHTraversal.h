// BVH queries: closest hit, any hit, all hits, closest point, box overlap.
// All are const and thread-safe (state lives on the caller's stack), walk
// an explicit stack of kMaxStackSize entries, and visit the nearer child
// first. The primitive test is a callable, so the same traversal serves
// triangles, spheres, instances and a caller's exact cell test.
//
// Ray intersector:  bool(std::uint32_t prim, const Ray<T>& ray, Hit<T>& hit)
//   Test primitive `prim` (an original id) on [ray.tmin, ray.tmax]. On a hit,
//   write hit.t (and u, v if meaningful) and return true; otherwise leave
//   `hit` alone and return false. The traversal then sets hit.prim and
//   shrinks ray.tmax to hit.t, so for closestHit every `true` is a new
//   closest hit (a caller may store extra per-hit data when returning true).
// Point query:      bool(std::uint32_t prim, const Vec3<T>& p, PointHit<T>& cand)
//   Write the closest point of `prim` to p into cand.point and its squared
//   distance into cand.dist2; return false to ignore the primitive.
//
// The traversals are templated on a node source, so the float GPU copy
// (GpuNodeSource) can be walked on the CPU exactly as the shader walks it.
#ifndef vtkrt_core_BVHTraversal_h
#define vtkrt_core_BVHTraversal_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/Ray.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace vtkrt::core
{

template <class T>
struct Hit
{
  T t = std::numeric_limits<T>::infinity();
  T u = T(0); ///< barycentric weight of v1 (triangles)
  T v = T(0); ///< barycentric weight of v2 (triangles)
  std::uint32_t prim = kInvalidIndex;
  std::uint32_t instance = kInvalidIndex; ///< two-level queries only
  bool found() const { return prim != kInvalidIndex; }
};

template <class T>
struct PointHit
{
  Vec3<T> point = Vec3<T>(T(0));
  T dist2 = std::numeric_limits<T>::infinity();
  std::uint32_t prim = kInvalidIndex;
  bool found() const { return prim != kInvalidIndex; }
};

/// The CPU double nodes.
struct NodeSource
{
  using Scalar = double;
  const BVHNode* nodes = nullptr;
  std::size_t size = 0;

  explicit NodeSource(const BVH& bvh)
    : nodes(bvh.nodes.data())
    , size(bvh.nodes.size())
  {
  }
  const Vec3<double>& lo(std::uint32_t i) const { return nodes[i].min; }
  const Vec3<double>& hi(std::uint32_t i) const { return nodes[i].max; }
  std::uint32_t index(std::uint32_t i) const { return nodes[i].index; }
  std::uint32_t count(std::uint32_t i) const { return nodes[i].count; }
};

/// The packed float copy from packNodesForGpu (8 floats per node), read the
/// way the GLSL traversal reads it.
struct GpuNodeSource
{
  using Scalar = float;
  const float* data = nullptr;
  std::size_t size = 0;

  GpuNodeSource(const std::vector<float>& packed)
    : data(packed.data())
    , size(packed.size() / 8)
  {
  }
  Vec3<float> lo(std::uint32_t i) const { return Vec3<float>(data[8 * i], data[8 * i + 1], data[8 * i + 2]); }
  Vec3<float> hi(std::uint32_t i) const
  {
    return Vec3<float>(data[8 * i + 4], data[8 * i + 5], data[8 * i + 6]);
  }
  std::uint32_t index(std::uint32_t i) const { return floatBitsToUint(data[8 * i + 3]); }
  std::uint32_t count(std::uint32_t i) const { return floatBitsToUint(data[8 * i + 7]); }
};

namespace detail
{
template <class T>
struct StackEntry
{
  std::uint32_t node;
  T dist; ///< entry t (rays) or squared distance (points)
};

/// The nearer-child-first walk shared by ray and point queries: its stack,
/// the step into an interior node's children and the pop.
template <class T>
struct OrderedWalk
{
  StackEntry<T> stack[kMaxStackSize];
  std::uint32_t sp = 0;

  /// Children index and index + 1, hit (h0, h1) at distances d0, d1: the
  /// nearer hit one becomes `cur`, the other waits on the stack. False when
  /// neither is hit.
  bool descend(std::uint32_t index, bool h0, T d0, bool h1, T d1, std::uint32_t& cur)
  {
    if (h0 && h1)
    {
      const bool firstNear = d0 <= d1;
      stack[sp++] = { firstNear ? index + 1 : index, firstNear ? d1 : d0 };
      cur = firstNear ? index : index + 1;
      return true;
    }
    if (h0 || h1)
    {
      cur = h0 ? index : index + 1;
      return true;
    }
    return false;
  }

  /// The next waiting node still within `bound` (entries beyond it are
  /// dropped); false when none is left.
  bool pop(T bound, std::uint32_t& cur)
  {
    while (sp > 0)
    {
      const StackEntry<T> e = stack[--sp];
      if (e.dist <= bound)
      {
        cur = e.node;
        return true;
      }
    }
    return false;
  }
};

/// Shared by closestHit/anyHit/allHits. mode: 0 closest, 1 any, 2 all.
template <int Mode, class Nodes, class T, class Isect, class Sink>
bool traverseRay(const Nodes& nodes, const std::uint32_t* primIndex, Ray<T> ray, Isect& isect, Hit<T>& hit,
  Sink&& sink)
{
  if (nodes.size == 0 || !ray.isValid())
  {
    return false;
  }
  const RayBoxPrecomputed<T> pre(ray);
  OrderedWalk<T> walk;
  T tnear = T(0);
  if (!intersectRayAABB(pre, nodes.lo(0), nodes.hi(0), ray.tmin, ray.tmax, tnear))
  {
    return false;
  }
  bool found = false;
  std::uint32_t cur = 0;
  for (;;)
  {
    const std::uint32_t count = nodes.count(cur);
    const std::uint32_t index = nodes.index(cur);
    if (count > 0)
    {
      for (std::uint32_t k = 0; k < count; ++k)
      {
        const std::uint32_t prim = primIndex[index + k];
        Hit<T> candidate = hit;
        if (isect(prim, ray, candidate))
        {
          candidate.prim = prim;
          found = true;
          if constexpr (Mode == 2)
          {
            sink(candidate);
          }
          else
          {
            hit = candidate;
            if constexpr (Mode == 1)
            {
              return true;
            }
            ray.tmax = hit.t;
          }
        }
      }
    }
    else
    {
      T t0 = T(0), t1 = T(0);
      const bool h0 = intersectRayAABB(pre, nodes.lo(index), nodes.hi(index), ray.tmin, ray.tmax, t0);
      const bool h1 = intersectRayAABB(pre, nodes.lo(index + 1), nodes.hi(index + 1), ray.tmin, ray.tmax, t1);
      if (walk.descend(index, h0, t0, h1, t1, cur))
      {
        continue;
      }
    }
    // The next node still in front of the closest hit.
    if (!walk.pop(ray.tmax, cur))
    {
      return found;
    }
  }
}

struct NoSink
{
  template <class H>
  void operator()(const H&) const
  {
  }
};
} // namespace detail

/// Closest hit on [ray.tmin, ray.tmax]. Returns whether anything was hit;
/// `hit` holds it (hit.prim = original primitive id).
template <class Nodes, class T, class Isect>
bool closestHit(const Nodes& nodes, const std::uint32_t* primIndex, const Ray<T>& ray, Isect&& isect, Hit<T>& hit)
{
  hit = Hit<T>();
  return detail::traverseRay<0>(nodes, primIndex, ray, isect, hit, detail::NoSink());
}

template <class T, class Isect>
bool closestHit(const BVH& bvh, const Ray<T>& ray, Isect&& isect, Hit<T>& hit)
{
  static_assert(std::is_same_v<T, double>, "the CPU BVH is double; walk packNodesForGpu() for float");
  return closestHit(NodeSource(bvh), bvh.primIndex.data(), ray, isect, hit);
}

/// Any hit on [ray.tmin, ray.tmax] (shadow rays): stops at the first.
template <class Nodes, class T, class Isect>
bool anyHit(const Nodes& nodes, const std::uint32_t* primIndex, const Ray<T>& ray, Isect&& isect, Hit<T>& hit)
{
  hit = Hit<T>();
  return detail::traverseRay<1>(nodes, primIndex, ray, isect, hit, detail::NoSink());
}

template <class T, class Isect>
bool anyHit(const BVH& bvh, const Ray<T>& ray, Isect&& isect, Hit<T>& hit)
{
  return anyHit(NodeSource(bvh), bvh.primIndex.data(), ray, isect, hit);
}

template <class T, class Isect>
bool anyHit(const BVH& bvh, const Ray<T>& ray, Isect&& isect)
{
  Hit<T> hit;
  return anyHit(bvh, ray, isect, hit);
}

/// Every hit on [ray.tmin, ray.tmax], sorted by (t, prim). For a primitive
/// the intersector reports one hit (the nearest in range).
template <class Nodes, class T, class Isect>
std::vector<Hit<T>> allHits(const Nodes& nodes, const std::uint32_t* primIndex, const Ray<T>& ray, Isect&& isect)
{
  std::vector<Hit<T>> hits;
  Hit<T> scratch;
  detail::traverseRay<2>(nodes, primIndex, ray, isect, scratch, [&hits](const Hit<T>& h) { hits.push_back(h); });
  std::sort(hits.begin(), hits.end(),
    [](const Hit<T>& a, const Hit<T>& b) { return a.t < b.t || (a.t == b.t && a.prim < b.prim); });
  return hits;
}

template <class T, class Isect>
std::vector<Hit<T>> allHits(const BVH& bvh, const Ray<T>& ray, Isect&& isect)
{
  return allHits(NodeSource(bvh), bvh.primIndex.data(), ray, isect);
}

/// Closest point to p among primitives within maxDistance (inclusive; +inf
/// for no limit). Returns whether one was found.
template <class T, class PointFn>
bool closestPoint(const BVH& bvh, const Vec3<T>& p, T maxDistance, PointFn&& fn, PointHit<T>& best)
{
  best = PointHit<T>();
  if (bvh.empty() || !isFinite(p) || std::isnan(maxDistance) || maxDistance < T(0))
  {
    return false;
  }
  best.dist2 = maxDistance * maxDistance;
  const NodeSource nodes(bvh);
  detail::OrderedWalk<T> walk;
  const auto boxDist2 = [&](std::uint32_t i) { return AABB<T>(nodes.lo(i), nodes.hi(i)).distance2(p); };
  if (boxDist2(0) > best.dist2)
  {
    return false;
  }
  std::uint32_t cur = 0;
  for (;;)
  {
    const std::uint32_t count = nodes.count(cur);
    const std::uint32_t index = nodes.index(cur);
    if (count > 0)
    {
      for (std::uint32_t k = 0; k < count; ++k)
      {
        const std::uint32_t prim = bvh.primIndex[index + k];
        PointHit<T> cand;
        if (fn(prim, p, cand) &&
          (cand.dist2 < best.dist2 || (!best.found() && cand.dist2 <= best.dist2)))
        {
          best = cand;
          best.prim = prim;
        }
      }
    }
    else
    {
      const T d0 = boxDist2(index);
      const T d1 = boxDist2(index + 1);
      if (walk.descend(index, d0 <= best.dist2, d0, d1 <= best.dist2, d1, cur))
      {
        continue;
      }
    }
    if (!walk.pop(best.dist2, cur))
    {
      return best.found();
    }
  }
}

namespace detail
{
/// The box walk of queryBox and queryBoxSlots: onLeaf(index, count) for
/// every leaf that overlaps(node) admits, its ancestors admitted too.
template <class Node, class Overlaps, class OnLeaf>
void walkOverlapping(const Node* nodes, std::size_t size, Overlaps&& overlaps, OnLeaf&& onLeaf)
{
  if (size == 0 || !overlaps(nodes[0]))
  {
    return;
  }
  std::uint32_t stack[kMaxStackSize];
  std::uint32_t sp = 0;
  stack[sp++] = 0;
  while (sp > 0)
  {
    const Node& n = nodes[stack[--sp]];
    if (n.count > 0)
    {
      onLeaf(n.index, n.count);
      continue;
    }
    // Push right first so the left child is visited first.
    for (std::uint32_t c : { n.index + 1, n.index })
    {
      if (overlaps(nodes[c]))
      {
        stack[sp++] = c;
      }
    }
  }
}
} // namespace detail

/// Calls fn(prim) for every primitive in a leaf whose box overlaps `box`
/// (closed intervals). The leaf box is a superset of its primitives'
/// bounds: fn does the exact test (see meshes' overlap helpers).
template <class Fn>
void queryBox(const BVH& bvh, const AABB<double>& box, Fn&& fn)
{
  if (bvh.empty() || box.isEmpty())
  {
    return;
  }
  detail::walkOverlapping(
    bvh.nodes.data(), bvh.nodes.size(), [&box](const BVHNode& n) { return n.bounds().overlaps(box); },
    [&](std::uint32_t index, std::uint32_t count) {
      for (std::uint32_t k = 0; k < count; ++k)
      {
        fn(bvh.primIndex[index + k]);
      }
    });
}

/// Calls fn(slot) for every leaf slot (a primIndex position) of float
/// nodes (packGpuNodes with origin 0: boxes rounded outward) whose box may
/// overlap `box`, itself rounded outward: conservative, fn does the exact
/// test. Half the bytes a step of queryBox's double nodes.
template <class Fn>
void queryBoxSlots(const std::vector<gpu::Node>& nodes, const AABB<double>& box, Fn&& fn)
{
  if (nodes.empty() || box.isEmpty())
  {
    return;
  }
  float lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
  {
    lo[k] = detail::floorFloat(box.min[k]);
    hi[k] = detail::ceilFloat(box.max[k]);
  }
  detail::walkOverlapping(
    nodes.data(), nodes.size(),
    [&lo, &hi](const gpu::Node& n) {
      return n.lo[0] <= hi[0] && lo[0] <= n.hi[0] && n.lo[1] <= hi[1] && lo[1] <= n.hi[1] &&
        n.lo[2] <= hi[2] && lo[2] <= n.hi[2];
    },
    [&](std::uint32_t index, std::uint32_t count) {
      for (std::uint32_t slot = index; slot < index + count; ++slot)
      {
        fn(slot);
      }
    });
}

} // namespace vtkrt::core

#endif
