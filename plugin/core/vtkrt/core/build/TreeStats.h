// BuildStats of a finished tree: what the builder's output looks like.
#ifndef vtkrt_core_build_TreeStats_h
#define vtkrt_core_build_TreeStats_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/build/NodeFormats.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vtkrt::core
{

/// Depth, leaf count and SAH cost of a finished tree's nodes (BVHNode or
/// gpu::Node; parents precede children in the layout, so one forward pass
/// suffices).
template <class Nodes>
void computeTreeStats(const Nodes& nodes, BuildStats& s, const BuildOptions& options = BuildOptions())
{
  s.nodeCount = nodes.size();
  s.leafCount = 0;
  s.maxDepth = 0;
  s.maxLeafPrimitives = 0;
  s.sahCost = 0.0;
  if (nodes.empty())
  {
    return;
  }
  // A byte a node (depths stay under 256), written before it is read: no
  // zero fill of a node-sized array.
  NoFillArray<std::uint8_t> depth(nodes.size());
  depth[0] = 0;
  const double rootArea = nodeHalfArea(nodes[0]);
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    const auto& n = nodes[i];
    const double rel = rootArea > 0.0 ? nodeHalfArea(n) / rootArea : 1.0;
    s.maxDepth = std::max<std::uint32_t>(s.maxDepth, depth[i]);
    if (n.count > 0)
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

inline void computeTreeStats(BVH& bvh, const BuildOptions& options = BuildOptions())
{
  computeTreeStats(bvh.nodes, bvh.stats, options);
}

} // namespace vtkrt::core

#endif
