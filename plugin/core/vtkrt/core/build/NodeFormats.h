// The node arrays a builder can write: double nodes (BVHNode, the
// locator's exact tree) or the GPU's float nodes (gpu::Node, what the pass
// uploads), so that the pass's tree is never held in double.
#ifndef vtkrt_core_build_NodeFormats_h
#define vtkrt_core_build_NodeFormats_h

#include "vtkrt/core/BVH.h"

#include <algorithm>
#include <type_traits>

namespace vtkrt::core
{

namespace detail
{

static_assert(std::is_trivially_default_constructible<gpu::Node>::value, "gpu::Node arrays are sized without a write");

/// Exact double boxes.
struct DoubleNodes
{
  using Node = BVHNode;
  void write(BVHNode& node, const AABB<double>& box) const { node.setBounds(box); }
  void merge(BVHNode& parent, const BVHNode& a, const BVHNode& b) const
  {
    AABB<double> box = a.bounds();
    box.extend(b.bounds());
    parent.setBounds(box);
  }
};

/// GPU float boxes relative to `origin`, rounded outward; a parent's is
/// its children's union (packGpuBox is monotone: the packed exact union).
struct GpuNodes
{
  using Node = gpu::Node;
  Vec3<double> origin;
  void write(gpu::Node& node, const AABB<double>& box) const { packGpuBox(node, box, origin); }
  void merge(gpu::Node& parent, const gpu::Node& a, const gpu::Node& b) const
  {
    for (int k = 0; k < 3; ++k)
    {
      parent.lo[k] = std::min(a.lo[k], b.lo[k]);
      parent.hi[k] = std::max(a.hi[k], b.hi[k]);
    }
  }
};

} // namespace detail

/// The area of a node's box (half the surface).
inline double nodeHalfArea(const BVHNode& n)
{
  return n.bounds().halfArea();
}
inline double nodeHalfArea(const gpu::Node& n)
{
  return AABB<double>(Vec3<double>(n.lo), Vec3<double>(n.hi)).halfArea();
}

} // namespace vtkrt::core

#endif
