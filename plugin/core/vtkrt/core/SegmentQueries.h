// A segment's hits as the locator asks for them, within a tolerance: the
// closest through the wide float walk (WideTraversal.h), in double over the
// binary tree where that walk cannot take the segment, and every hit over
// the binary tree. The Scene of WideTraversal.h also provides
//   const BVH& binaryTree() const  -- the binary tree over the same
//     primitives (built first if it is not there yet).
#ifndef vtkrt_core_SegmentQueries_h
#define vtkrt_core_SegmentQueries_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"
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

/// The closest hit of the segment `ray` (BVHTraversal.h's closestHit
/// contract), primitives within tol of it counting as hit by the caller's
/// isect.
template <class Scene, class Isect>
bool closestHitSegment(Scene scene, const Ray<double>& ray, const RayTrianglePrecomputed<double>& triPre,
  double tol, Isect& isect, Hit<double>& hit)
{
  const int walked = closestHitWide(scene, ray, triPre, tol, isect, hit);
  if (walked >= 0)
  {
    return walked != 0;
  }
  // Axis-parallel or extreme segments: the double traversal of the binary
  // tree.
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
  if (closestHitWide(scene, ray, triPre, tol, isect, none, trianglePreTest) >= 0)
  {
    return;
  }
  const BVH& tree = scene.binaryTree();
  const GrownNodeSource nodes{ tree.nodes.data(), tree.nodes.size(), tol };
  allHits(nodes, tree.primIndex.data(), ray, isect);
}

} // namespace vtkrt::core

#endif
