// BuildStats of a finished tree: what the builder's output looks like.
#ifndef vtkrt_core_build_TreeStats_h
#define vtkrt_core_build_TreeStats_h

#include "vtkrt/core/BVH.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vtkrt::core
{

/// Depth, leaf count and SAH cost of a finished tree (parents precede
/// children in the layout, so one forward pass suffices).
inline void computeTreeStats(BVH& bvh, const BuildOptions& options = BuildOptions())
{
  BuildStats& s = bvh.stats;
  s.nodeCount = bvh.nodes.size();
  s.leafCount = 0;
  s.maxDepth = 0;
  s.maxLeafPrimitives = 0;
  s.sahCost = 0.0;
  if (bvh.nodes.empty())
  {
    return;
  }
  // A byte a node (depths stay under 256), written before it is read: no
  // zero fill of a node-sized array.
  NoFillArray<std::uint8_t> depth(bvh.nodes.size());
  depth[0] = 0;
  const double rootArea = bvh.nodes[0].bounds().halfArea();
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i)
  {
    const BVHNode& n = bvh.nodes[i];
    const double rel = rootArea > 0.0 ? n.bounds().halfArea() / rootArea : 1.0;
    s.maxDepth = std::max<std::uint32_t>(s.maxDepth, depth[i]);
    if (n.isLeaf())
    {
      s.leafCount++;
      s.maxLeafPrimitives = std::max(s.maxLeafPrimitives, n.count);
      s.sahCost += rel * options.intersectionCost * n.count;
    }
    else
    {
      depth[n.index] = depth[n.index + 1] = static_cast<std::uint8_t>(depth[i] + 1);
      s.sahCost += rel * options.traversalCost;
    }
  }
}

} // namespace vtkrt::core

#endif
