// Refit: new boxes for a tree whose primitives moved, same topology.
#ifndef vtkrt_core_build_Refit_h
#define vtkrt_core_build_Refit_h

#include "vtkrt/core/BVH.h"

#include <cstddef>
#include <cstdint>

namespace vtkrt::core
{

/// Refit after the primitives moved (same topology, same validity): leaf
/// boxes from primitiveBounds(id), then interior boxes bottom-up (children
/// always follow their parent in the layout). Quality degrades as the motion
/// grows; rebuild when it matters.
template <class BoundsFn>
void refit(BVH& bvh, BoundsFn&& primitiveBounds)
{
  for (std::size_t i = bvh.nodes.size(); i-- > 0;)
  {
    BVHNode& n = bvh.nodes[i];
    AABB<double> box;
    if (n.isLeaf())
    {
      for (std::uint32_t k = 0; k < n.count; ++k)
      {
        box.extend(primitiveBounds(bvh.primIndex[n.index + k]));
      }
    }
    else
    {
      box = bvh.nodes[n.index].bounds();
      box.extend(bvh.nodes[n.index + 1].bounds());
    }
    n.setBounds(box);
  }
}

} // namespace vtkrt::core

#endif
