// The point and box queries over the eight-wide picking tree (WideNode.h):
// the closest primitive to a point (nearest child first, pruned by the best
// squared distance so far) and every primitive whose box may overlap a box.
// Node boxes are tested in float on the node's quantized grid (every
// decoded plane an exact float holding the exact box), with the point held
// between its two neighbouring floats and each float distance shrunk by a
// proven margin, so a box is never pruned while something in it could be
// closer than the best (the double tests of the primitives decide).
//
// The Scene is WideTraversal.h's (pickingRoot, triangleCount, generalCount,
// slotPrimitives, subtree; extent). The walks refuse (return -1) where
// float cannot be trusted: an extent or a point beyond 1e17, or a
// flush-to-zero FPU mode; the caller then walks the binary tree in double.
#ifndef vtkrt_core_WidePointQueries_h
#define vtkrt_core_WidePointQueries_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h" // PointHit
#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/WideNode.h"
#include "vtkrt/core/WideTraversal.h" // countTrailingZeros
#include "vtkrt/core/simd/Dispatch.h"
#include "vtkrt/core/simd/Sse.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace vtkrt::core
{

namespace detail
{
/// Where the float walks hold: every coordinate they round within this.
constexpr double kWidePointReach = 1e17;

/// Whether float boxes, points and squared distances within reach can be
/// trusted here (no flush-to-zero or denormals-are-zero mode).
inline bool widePointWalkUsable(double extent, double reach)
{
#if VTKRT_CORE_SSE
  if (_mm_getcsr() & 0x8040u)
  {
    return false;
  }
#endif
  return extent <= kWidePointReach && reach <= kWidePointReach;
}

/// A float squared distance computed from floats a, b, c (each a rounded
/// difference: relative error <= 2^-24, or exact when subnormal), squared
/// and summed (four more roundings) is at most (1 + 2^-24)^6 times the
/// exact one; scaled by this and lowered by kWideDistanceFloor (all
/// underflow together stays far below it), it is a lower bound.
constexpr float kWideDistanceShrink = 1.0f - 0x1p-20f;
constexpr float kWideDistanceFloor = 1e-36f;

/// Lower bounds of the squared distances from a point to a wide node's
/// eight boxes; the point lies in [xlo, xhi] on each axis (floats). Bit i
/// set: lane i is a box whose bound is <= bound (bounds in d2).
inline int boxDistances8(const QuantizedBoxPack8& b, const float xlo[3], const float xhi[3], float bound, float d2[8])
{
#if VTKRT_CORE_SSE
  int mask = 0;
  const __m128 zero = _mm_setzero_ps();
  for (int half = 0; half < 2; ++half)
  {
    __m128 sum = zero;
    for (int a = 0; a < 3; ++a)
    {
      const __m128 origin = _mm_set1_ps(b.origin[a]), step = _mm_set1_ps(b.step(a));
      const __m128 lo = decodeRow4(b, 8 * a, 4 * half, origin, step);
      const __m128 hi = decodeRow4(b, 8 * (3 + a), 4 * half, origin, step);
      const __m128 d = _mm_max_ps(
        _mm_max_ps(_mm_sub_ps(lo, _mm_set1_ps(xhi[a])), _mm_sub_ps(_mm_set1_ps(xlo[a]), hi)), zero);
      sum = _mm_add_ps(sum, _mm_mul_ps(d, d));
    }
    sum = _mm_max_ps(
      _mm_sub_ps(_mm_mul_ps(sum, _mm_set1_ps(kWideDistanceShrink)), _mm_set1_ps(kWideDistanceFloor)), zero);
    _mm_storeu_ps(d2 + 4 * half, sum);
    mask |= _mm_movemask_ps(_mm_cmple_ps(sum, _mm_set1_ps(bound))) << (4 * half);
  }
  return mask & b.valid;
#else
  int mask = 0;
  for (int i = 0; i < 8; ++i)
  {
    float lo[3], hi[3];
    b.lane(i, lo, hi);
    float sum = 0.0f;
    for (int a = 0; a < 3; ++a)
    {
      const float d = std::max(std::max(lo[a] - xhi[a], xlo[a] - hi[a]), 0.0f);
      sum += d * d;
    }
    d2[i] = std::max(sum * kWideDistanceShrink - kWideDistanceFloor, 0.0f);
    mask |= d2[i] <= bound ? 1 << i : 0;
  }
  return mask & b.valid;
#endif
}

/// Bit i set: lane i is a box that may overlap [qlo, qhi] (floats holding
/// the query box).
inline int boxOverlaps8(const QuantizedBoxPack8& b, const float qlo[3], const float qhi[3])
{
#if VTKRT_CORE_SSE
  int mask = 0;
  for (int half = 0; half < 2; ++half)
  {
    __m128 overlap = _mm_castsi128_ps(_mm_set1_epi32(-1));
    for (int a = 0; a < 3; ++a)
    {
      const __m128 origin = _mm_set1_ps(b.origin[a]), step = _mm_set1_ps(b.step(a));
      const __m128 lo = decodeRow4(b, 8 * a, 4 * half, origin, step);
      const __m128 hi = decodeRow4(b, 8 * (3 + a), 4 * half, origin, step);
      overlap = _mm_and_ps(overlap,
        _mm_and_ps(_mm_cmple_ps(lo, _mm_set1_ps(qhi[a])), _mm_cmple_ps(_mm_set1_ps(qlo[a]), hi)));
    }
    mask |= _mm_movemask_ps(overlap) << (4 * half);
  }
  return mask & b.valid;
#else
  int mask = b.valid;
  for (int i = 0; i < 8 && mask; ++i)
  {
    float lo[3], hi[3];
    b.lane(i, lo, hi);
    for (int a = 0; a < 3; ++a)
    {
      if (!(lo[a] <= qhi[a] && qlo[a] <= hi[a]))
      {
        mask &= ~(1 << i);
      }
    }
  }
  return mask;
#endif
}

/// A child slot of a wide node while a walk waits to visit it.
struct WideSlot
{
  const WideNode* Nodes; ///< the node array Ref indexes (interior children)
  std::uint32_t Ref;
  std::uint32_t Count; ///< > 0: a leaf (Ref = first slot); kWideSubtree: not built yet
  float Dist;
};

/// Calls leaf(prim) for each primitive of a leaf slot.
template <class Scene, class Leaf>
inline void visitWideLeaf(const Scene& scene, const WideSlot& s, bool allTriangles, Leaf& leaf)
{
  const std::uint32_t* primIndex = allTriangles ? nullptr : scene.slotPrimitives();
  for (std::uint32_t k = 0; k < s.Count; ++k)
  {
    leaf(allTriangles ? s.Ref + k : primIndex[s.Ref + k]);
  }
}

/// A slot built on demand, built (once) and seen as the slot it stands for.
template <class Scene>
inline WideSlot resolveWideSlot(const Scene& scene, WideSlot s)
{
  if (s.Count == kWideSubtree)
  {
    const WideSubtree sub = scene.subtree(s.Ref);
    s = { sub.nodes, sub.child, sub.count, s.Dist };
  }
  return s;
}

/// The slots of w in mask (non-zero) at distances dist: returns the
/// nearest (the walk's next step) and pushes the others, farthest deepest.
inline WideSlot pushOrdered(const WideSlot& cur, const WideNode& w, int mask, const float dist[kWideArity],
  WideSlot* stack, std::uint32_t& sp)
{
  int i = countTrailingZeros(static_cast<unsigned>(mask));
  mask &= mask - 1;
  WideSlot nearest{ cur.Nodes, w.child[i], w.count[i], dist[i] };
  const std::uint32_t base = sp;
  while (mask)
  {
    i = countTrailingZeros(static_cast<unsigned>(mask));
    mask &= mask - 1;
    WideSlot c{ cur.Nodes, w.child[i], w.count[i], dist[i] };
    if (c.Dist < nearest.Dist)
    {
      std::swap(c, nearest);
    }
    std::uint32_t j = sp++;
    while (j > base && stack[j - 1].Dist < c.Dist)
    {
      stack[j] = stack[j - 1];
      --j;
    }
    stack[j] = c;
  }
  return nearest;
}

/// The float bound above a double squared distance (+inf beyond float).
inline float wideDistanceBound(double d2)
{
  return d2 < 1e38 ? ceilFloat(d2) : std::numeric_limits<float>::infinity();
}
} // namespace detail

/// Closest point to p (local coordinates) among the primitives within
/// maxDistance (inclusive), BVHTraversal.h's closestPoint contract (fn
/// computes a primitive's closest point and squared distance in double).
/// Returns 1 (found), 0 (none) or -1 when the float walk cannot take the
/// query (walk the binary tree instead).
template <class Scene, class PointFn>
int closestPointWide(const Scene& scene, const Vec3<double>& p, double maxDistance, PointFn&& fn, PointHit<double>& best)
{
  best = PointHit<double>();
  if (!isFinite(p) || std::isnan(maxDistance) || maxDistance < 0.0 || !scene.pickingRoot())
  {
    return 0;
  }
  const double reach = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
  if (!detail::widePointWalkUsable(scene.extent(), reach))
  {
    return -1;
  }
  float xlo[3], xhi[3];
  for (int a = 0; a < 3; ++a)
  {
    xlo[a] = detail::floorFloat(p[a]);
    xhi[a] = detail::ceilFloat(p[a]);
  }
  const bool allTriangles = scene.generalCount() == 0;
  best.dist2 = maxDistance * maxDistance;
  float bound = detail::wideDistanceBound(best.dist2);
  auto leaf = [&](std::uint32_t prim) {
    PointHit<double> cand;
    if (fn(prim, p, cand) && (cand.dist2 < best.dist2 || (!best.found() && cand.dist2 <= best.dist2)))
    {
      best = cand;
      best.prim = prim;
      bound = detail::wideDistanceBound(best.dist2);
    }
  };
  // Each wide level pushes at most kWideArity - 1 entries.
  detail::WideSlot stack[(kWideArity - 1) * kMaxStackSize + 4];
  std::uint32_t sp = 0;
  detail::WideSlot cur{ scene.pickingRoot(), 0, 0, 0.0f };
  for (;;)
  {
    cur = detail::resolveWideSlot(scene, cur);
    if (cur.Count == 0)
    {
      const WideNode& w = cur.Nodes[cur.Ref];
      alignas(16) float d2[kWideArity];
      const int mask = detail::boxDistances8(w.box, xlo, xhi, bound, d2);
      if (mask)
      {
        cur = detail::pushOrdered(cur, w, mask, d2, stack, sp);
        continue;
      }
    }
    else
    {
      detail::visitWideLeaf(scene, cur, allTriangles, leaf);
    }
    do
    {
      if (sp == 0)
      {
        return best.found() ? 1 : 0;
      }
      cur = stack[--sp];
    } while (cur.Dist > bound);
  }
}

/// Calls fn(prim) for every primitive in a leaf whose box may overlap box
/// (local coordinates, closed); fn does the exact test. Returns false when
/// the float walk cannot take the box (walk the binary tree instead).
template <class Scene, class Fn>
bool overlapBoxWide(const Scene& scene, const AABB<double>& box, Fn&& fn)
{
  if (box.isEmpty() || !scene.pickingRoot())
  {
    return true; // nothing overlaps an empty (or NaN) box
  }
  // Parts of the box beyond the tree's reach select nothing more.
  const double reach = detail::kWidePointReach;
  if (!detail::widePointWalkUsable(scene.extent(), 0.0))
  {
    return false;
  }
  float qlo[3], qhi[3];
  for (int a = 0; a < 3; ++a)
  {
    qlo[a] = detail::floorFloat(std::min(std::max(box.min[a], -reach), reach));
    qhi[a] = detail::ceilFloat(std::min(std::max(box.max[a], -reach), reach));
  }
  const bool allTriangles = scene.generalCount() == 0;
  // Each wide level pushes at most kWideArity entries.
  detail::WideSlot stack[kWideArity * kMaxStackSize + 4];
  std::uint32_t sp = 0;
  stack[sp++] = { scene.pickingRoot(), 0, 0, 0.0f };
  while (sp > 0)
  {
    const detail::WideSlot s = detail::resolveWideSlot(scene, stack[--sp]);
    if (s.Count > 0)
    {
      detail::visitWideLeaf(scene, s, allTriangles, fn);
      continue;
    }
    const WideNode& w = s.Nodes[s.Ref];
    for (int mask = detail::boxOverlaps8(w.box, qlo, qhi); mask; mask &= mask - 1)
    {
      const int i = detail::countTrailingZeros(static_cast<unsigned>(mask));
      stack[sp++] = { s.Nodes, w.child[i], w.count[i], 0.0f };
    }
  }
  return true;
}

} // namespace vtkrt::core

#endif
