// The eight-wide picking tree (WideNode.h) over a binary BVH: its nodes
// re-laid, eight children a node, with no new split decisions. The builds
// that make a binary tree (SAH qualities) get their picking tree this way;
// the fast build writes one directly (LazyWideBVH, WideBVH.h).
#ifndef vtkrt_core_WideCollapse_h
#define vtkrt_core_WideCollapse_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHBuild.h" // parallelChunks
#include "vtkrt/core/WideNode.h"
#include "vtkrt/core/simd/Dispatch.h"

#include <cstdint>
#include <vector>

namespace vtkrt::core
{
namespace detail
{

/// The up to kWideArity binary nodes a wide node over binary interior node
/// `b` holds: its children, then repeatedly the interior one of largest
/// area replaced by its two children.
inline int wideChildren(const BVH& tree, std::uint32_t b, std::uint32_t kids[kWideArity])
{
  const auto& nodes = tree.nodes;
  kids[0] = nodes[b].index;
  kids[1] = nodes[b].index + 1;
  int n = 2;
  while (n < kWideArity)
  {
    int best = -1;
    double bestArea = -1.0;
    for (int i = 0; i < n; ++i)
    {
      const BVHNode& c = nodes[kids[i]];
      if (!c.isLeaf())
      {
        const double area = c.bounds().halfArea();
        if (area > bestArea)
        {
          bestArea = area;
          best = i;
        }
      }
    }
    if (best < 0)
    {
      break;
    }
    const std::uint32_t first = nodes[kids[best]].index;
    kids[best] = first;
    kids[n++] = first + 1;
  }
  return n;
}

/// Appends the wide subtree over binary interior node `b` to `out` (depth
/// first, indices local to `out`); returns its root's index.
inline std::uint32_t collapseSubtree(const BVH& tree, std::uint32_t b, std::vector<WideNode>& out)
{
  std::uint32_t kids[kWideArity];
  const int n = wideChildren(tree, b, kids);
  const std::uint32_t w = static_cast<std::uint32_t>(out.size());
  out.emplace_back();
  WideNodeDraft node;
  node.clear();
#if VTKRT_CORE_SSE
  // The interior kids' own children are what their collapse reads first:
  // fetch them all now (a tree of millions of nodes is a cache miss per
  // read otherwise).
  for (int i = 0; i < n; ++i)
  {
    const BVHNode& c = tree.nodes[kids[i]];
    if (!c.isLeaf())
    {
      const char* pair = reinterpret_cast<const char*>(&tree.nodes[c.index]);
      _mm_prefetch(pair, _MM_HINT_T0);
      _mm_prefetch(pair + sizeof(BVHNode), _MM_HINT_T0);
    }
  }
#endif
  for (int i = 0; i < n; ++i)
  {
    const BVHNode& c = tree.nodes[kids[i]];
    node.setBox(i, c.bounds());
    if (c.isLeaf())
    {
      node.child[i] = c.index;
      node.count[i] = c.count;
    }
    else
    {
      node.child[i] = collapseSubtree(tree, kids[i], out);
    }
  }
  out[w] = node.pack();
  return w;
}

} // namespace detail

/// The wide view of `tree` (empty when the tree is): the root's wide node
/// here, the subtrees below its interior slots in parallel (options'
/// parallelFor, else its threads), then appended in slot order. Leaf slots
/// keep the binary leaves' primIndex ranges.
inline std::vector<WideNode> collapseToWide(const BVH& tree, const BuildOptions& options)
{
  std::vector<WideNode> wide;
  if (tree.empty())
  {
    return wide;
  }
  WideNodeDraft root;
  root.clear();
  std::uint32_t kids[kWideArity];
  int n = 1;
  if (tree.nodes[0].isLeaf())
  {
    kids[0] = 0; // one slot holding the root leaf
  }
  else
  {
    n = detail::wideChildren(tree, 0, kids);
  }
  // Storage from this thread (a worker thread's malloc arena would hand
  // large blocks back to the system after every build).
  std::vector<WideNode> sub[kWideArity];
  for (int i = 0; i < n; ++i)
  {
    sub[i].reserve(tree.nodes.size() / 2 + 16);
  }
  auto collapseSlots = [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      if (!tree.nodes[kids[i]].isLeaf())
      {
        detail::collapseSubtree(tree, kids[i], sub[i]);
      }
    }
  };
  if (options.parallelFor)
  {
    options.parallelFor(static_cast<std::size_t>(n), collapseSlots);
  }
  else
  {
    detail::parallelChunks(static_cast<std::size_t>(n), options.numThreads, collapseSlots, tree.nodes.size());
  }
  std::size_t total = 1;
  for (const auto& v : sub)
  {
    total += v.size();
  }
  wide.reserve(total);
  wide.emplace_back(); // the root, packed once its slots are known
  for (int i = 0; i < n; ++i)
  {
    const BVHNode& c = tree.nodes[kids[i]];
    root.setBox(i, c.bounds());
    if (c.isLeaf())
    {
      root.child[i] = c.index;
      root.count[i] = c.count;
      continue;
    }
    const std::uint32_t offset = static_cast<std::uint32_t>(wide.size());
    root.child[i] = offset; // the subtree's root comes first
    for (WideNode w : sub[i])
    {
      for (int k = 0; k < kWideArity; ++k)
      {
        w.child[k] += w.count[k] == 0 ? offset : 0;
      }
      wide.push_back(w);
    }
    std::vector<WideNode>().swap(sub[i]);
  }
  wide[0] = root.pack();
  return wide;
}

} // namespace vtkrt::core

#endif
