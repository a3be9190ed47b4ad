// Private to vtkBVHCellLocator's query units: the locator's arrays as the
// core's walks see them, and a world segment as a local ray.
#ifndef vtkBVHCellLocatorPickingScene_h
#define vtkBVHCellLocatorPickingScene_h

#include "vtkBVHCellLocatorInternals.h"

#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/WidePointQueries.h"
#include "vtkrt/core/WideTraversal.h"

#include <cmath>

namespace vtkrt
{
namespace locator
{

/// Whether p1 -> p2 is a zero-length segment at a finite point.
inline bool IsFinitePoint(const double p1[3], const double p2[3])
{
  return p1[0] == p2[0] && p1[1] == p2[1] && p1[2] == p2[2] && std::isfinite(p1[0]) &&
    std::isfinite(p1[1]) && std::isfinite(p1[2]);
}

//------------------------------------------------------------------------------
/// The locator's arrays as the core's walks see them (core/WideTraversal.h,
/// core/SegmentQueries.h): a pointer, copied into the walk, so that its
/// loads are those of the data's own members.
struct BVHCellLocatorData::PickingScene
{
  const BVHCellLocatorData* D;

  const core::WideNode* pickingRoot() const { return this->D->PickingRoot(); }
  std::uint32_t triangleCount() const { return static_cast<std::uint32_t>(this->D->TriCell.size()); }
  std::size_t generalCount() const { return this->D->GenCell.size(); }
  const std::uint32_t* slotPrimitives() const { return this->D->Tree.primIndex.data(); }
  const float* floatTriangles() const { return this->D->TrianglesF.data(); }
  double extent() const { return this->D->Extent; }
  core::WideSubtree subtree(std::uint32_t k) const { return this->D->Lazy->subtree(k); }
  const core::BVH& binaryTree() const
  {
    this->D->EnsureTree();
    return this->D->Tree;
  }
  /// fn(prim) for every primitive in a leaf whose box overlaps q (local):
  /// through the wide walk, or the binary tree where it cannot be trusted.
  template <class Fn>
  void forPrimitivesInBox(const Box& q, Fn&& fn) const
  {
    if (!core::overlapBoxWide(*this, q, fn))
    {
      core::queryBox(this->binaryTree(), q, fn);
    }
  }
#if VTKRT_CORE_SSE
  /// The exact test of a leaf's triangles reads their point ids.
  VTKRT_ALWAYS_INLINE void prefetchTriangles(std::uint32_t first, std::uint32_t end) const
  {
    core::detail::prefetchRange(this->D->TriIds.data() + 3 * static_cast<std::size_t>(first),
      this->D->TriIds.data() + 3 * static_cast<std::size_t>(end));
  }
  /// The exact test reads the double points (which then fill the caller's
  /// cell), a hit its cell id, subId and flags: for triangles t + lane of
  /// each lane set in mask.
  VTKRT_ALWAYS_INLINE void prefetchCandidates(std::size_t t, int mask) const
  {
    const BVHCellLocatorData* d = this->D;
    const double* coords = d->WorldCoords();
    for (int m = mask; m; m &= m - 1)
    {
      const std::size_t prim = t + static_cast<std::size_t>(core::detail::countTrailingZeros(static_cast<unsigned>(m)));
      for (int k = 0; k < 3; ++k)
      {
        _mm_prefetch(reinterpret_cast<const char*>(coords + 3 * static_cast<std::size_t>(d->TriIds[3 * prim + k])), _MM_HINT_T0);
      }
      _mm_prefetch(reinterpret_cast<const char*>(&d->TriCell[prim]), _MM_HINT_T0);
      if (d->UniformCellBase < 0) // else TriangleSubId / TriangleFlags read neither
      {
        _mm_prefetch(reinterpret_cast<const char*>(&d->TriSub[prim]), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(&d->TriFlags[prim]), _MM_HINT_T0);
      }
    }
  }
#endif
};

//------------------------------------------------------------------------------
inline bool BVHCellLocatorData::MakeSegment(const double p1[3], const double p2[3], core::Ray<double>& ray) const
{
  if (!this->PickingRoot()) // every build with primitives makes the picking tree
  {
    return false;
  }
  // Scaled as ToLocal scales, so the direction is that of the world
  // segment times Scale, exactly.
  const double pre = this->PreScale, post = this->PostScale;
  const Vec3d dir((p2[0] * pre - p1[0] * pre) * post, (p2[1] * pre - p1[1] * pre) * post,
    (p2[2] * pre - p1[2] * pre) * post);
  // VTK cells never hit a zero-length segment either.
  ray = core::Ray<double>(this->ToLocal(p1), dir, 0.0, 1.0);
  return ray.isValid();
}

} // namespace locator
} // namespace vtkrt

#endif
