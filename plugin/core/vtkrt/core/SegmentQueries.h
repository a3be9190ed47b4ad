// A segment's hits as the locator asks for them, within a tolerance: the
// closest, or every primitive whose box the segment meets, through the
// wide float walk (WideTraversal.h); where it cannot take the segment (a
// direction parallel to an axis, a far origin) the same wide tree walked
// in double; the binary tree only where the wide tree's boxes are beyond
// float's reach. The Scene of WideTraversal.h also provides
//   const BVH& binaryTree() const  -- the binary tree over the same
//     primitives (built first if it is not there yet).
#ifndef vtkrt_core_SegmentQueries_h
#define vtkrt_core_SegmentQueries_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/WidePointQueries.h"
#include "vtkrt/core/WideTraversal.h"

#include <cstddef>
#include <cstdint>

namespace vtkrt::core
{

/// A BVH's nodes with every box grown by `grow` (a primitive within that
/// tolerance of the segment may lie outside its box by up to it): a node
/// source for BVHTraversal.h's walks.
struct GrownNodeSource
{
  using Scalar = double;
  const BVHNode* nodes = nullptr;
  std::size_t size = 0;
  double grow = 0.0;
  Vec3<double> lo(std::uint32_t i) const { return nodes[i].min - Vec3<double>(grow); }
  Vec3<double> hi(std::uint32_t i) const { return nodes[i].max + Vec3<double>(grow); }
  std::uint32_t index(std::uint32_t i) const { return nodes[i].index; }
  std::uint32_t count(std::uint32_t i) const { return nodes[i].count; }
};

/// closestHitWide's walk in double over the same tree, for the segments
/// the float walk refuses: each slot's decoded box (exact floats holding
/// the exact one) grown by tol, the slab test of Ray.h. Returns 1 (hit), 0
/// (none) or -1 when the tree's boxes may not hold its primitives (extent
/// beyond float's reach): walk the binary tree then.
template <class Scene, class Isect>
int closestHitWideDouble(const Scene& scene, Ray<double> ray, double tol, Isect& isect, Hit<double>& hit)
{
  hit = Hit<double>();
  if (!(scene.extent() <= detail::kWidePointReach) || !scene.pickingRoot())
  {
    return -1;
  }
  const RayBoxPrecomputed<double> pre(ray);
  const bool allTriangles = scene.generalCount() == 0;
  bool found = false;
  auto leaf = [&](std::uint32_t prim) {
    Hit<double> candidate = hit;
    if (isect(prim, ray, candidate))
    {
      candidate.prim = prim;
      found = true;
      hit = candidate;
      ray.tmax = hit.t;
    }
  };
  detail::WideSlot stack[(kWideArity - 1) * kMaxStackSize + 4];
  std::uint32_t sp = 0;
  detail::WideSlot cur{ scene.pickingRoot(), 0, 0, 0.0f };
  for (;;)
  {
    cur = detail::resolveWideSlot(scene, cur);
    if (cur.Count == 0)
    {
      const WideNode& w = cur.Nodes[cur.Ref];
      float tnear[kWideArity];
      int mask = 0;
      for (int i = 0; i < kWideArity; ++i)
      {
        float lo[3], hi[3];
        double t;
        if (!w.slotUsed(i))
        {
          continue;
        }
        w.slotBox(i, lo, hi);
        const Vec3<double> grow(tol);
        if (intersectRayAABB(pre, Vec3<double>(lo[0], lo[1], lo[2]) - grow,
              Vec3<double>(hi[0], hi[1], hi[2]) + grow, ray.tmin, ray.tmax, t))
        {
          mask |= 1 << i;
          tnear[i] = detail::floorFloat(t); // a lower bound: never pops a slot too early
        }
      }
      if (mask)
      {
        cur = detail::pushOrdered(cur, w, mask, tnear, stack, sp);
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
        return found ? 1 : 0;
      }
      cur = stack[--sp];
    } while (static_cast<double>(cur.Dist) > ray.tmax);
  }
}

/// The closest hit of the segment `ray` (BVHTraversal.h's closestHit
/// contract), primitives within tol of it counting as hit by the caller's
/// isect.
template <class Scene, class Isect>
bool closestHitSegment(Scene scene, const Ray<double>& ray, const RayTrianglePrecomputed<double>& triPre,
  double tol, Isect& isect, Hit<double>& hit)
{
  int walked = closestHitWide(scene, ray, triPre, tol, isect, hit);
  if (walked < 0)
  {
    walked = closestHitWideDouble(scene, ray, tol, isect, hit); // axis-parallel or far segments
  }
  if (walked >= 0)
  {
    return walked != 0;
  }
  // Boxes beyond float's reach: the double traversal of the binary tree.
  const BVH& tree = scene.binaryTree();
  const GrownNodeSource nodes{ tree.nodes.data(), tree.nodes.size(), tol };
  return closestHit(nodes, tree.primIndex.data(), ray, isect, hit);
}

/// Every primitive in a leaf whose box, grown by tol, the segment meets
/// goes to isect (which collects what it wants and returns false), through
/// the wide float walk where it takes the segment. trianglePreTest: only
/// the triangles the exact watertight test might accept (at tol 0); off,
/// every triangle of those leaves.
template <class Scene, class Isect>
void allHitsSegment(Scene scene, const Ray<double>& ray, const RayTrianglePrecomputed<double>& triPre,
  double tol, bool trianglePreTest, Isect& isect)
{
  Hit<double> none;
  if (closestHitWide(scene, ray, triPre, tol, isect, none, trianglePreTest) >= 0 ||
    closestHitWideDouble(scene, ray, tol, isect, none) >= 0)
  {
    return;
  }
  const BVH& tree = scene.binaryTree();
  const GrownNodeSource nodes{ tree.nodes.data(), tree.nodes.size(), tol };
  allHits(nodes, tree.primIndex.data(), ray, isect);
}

} // namespace vtkrt::core

#endif
