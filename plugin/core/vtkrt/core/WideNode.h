// The eight-wide BVH node of the CPU picking walk (WideTraversal.h), built
// by LazyWideBVH (WideBVH.h) or collapsed from a binary tree
// (WideCollapse.h).
//
// A closest-hit query walks one root-to-leaf chain of dependent node loads,
// so the number of levels, not the bytes, sets its cache-miss latency: eight
// children a node is a third of the binary levels. Boxes are quantized to a
// byte a plane on a grid of exact floats, rounded outward
// (QuantizedBoxPack8: a node is two cache lines; one AVX2 step, or two SSE
// steps); an unused slot is never hit.
#ifndef vtkrt_core_WideNode_h
#define vtkrt_core_WideNode_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/simd/Packs.h"
#include "vtkrt/core/simd/QuantizedBox.h"

#include <cstdint>

namespace vtkrt::core
{

constexpr int kWideArity = 8;

/// Two cache lines: the boxes of the eight children (QuantizedBoxPack8),
/// then where they lead. Written through a WideNodeDraft.
struct alignas(64) WideNode
{
  QuantizedBoxPack8 box;
  std::uint32_t child[kWideArity]; ///< wide node index (count 0) or first primitive slot
  std::uint32_t count[kWideArity]; ///< primitives of a leaf child; 0 for an interior child

  /// Slot i's box as the walk sees it (holds the float box it was given).
  void slotBox(int i, float lo[3], float hi[3]) const { box.lane(i, lo, hi); }
  bool slotUsed(int i) const { return (box.valid >> i & 1) != 0; }
};
static_assert(sizeof(WideNode) == 16 * kWideArity, "a wide node is 16 bytes a child");

/// A wide node while its slots are filled: float boxes, rounded outward;
/// pack() puts them on the node's grid. Slots left clear are unused.
struct WideNodeDraft
{
  BoxPack8 box;
  std::uint32_t child[kWideArity];
  std::uint32_t count[kWideArity];

  void clear()
  {
    for (int i = 0; i < kWideArity; ++i)
    {
      box.clear(i);
      child[i] = 0;
      count[i] = 0;
    }
  }
  /// Slot i's box, already float and rounded outward.
  void setBox(int i, const float lo[3], const float hi[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      box.lo[a][i] = lo[a];
      box.hi[a][i] = hi[a];
    }
  }
  /// Slot i's box from a double box, rounded outward to float.
  void setBox(int i, const AABB<double>& b)
  {
    for (int a = 0; a < 3; ++a)
    {
      box.lo[a][i] = detail::floorFloat(b.min[a]);
      box.hi[a][i] = detail::ceilFloat(b.max[a]);
    }
  }
  WideNode pack() const
  {
    WideNode n;
    n.box = QuantizedBoxPack8::quantize(box);
    for (int i = 0; i < kWideArity; ++i)
    {
      n.child[i] = child[i];
      n.count[i] = count[i];
    }
    return n;
  }
};

/// A slot's count that marks a subtree built on demand: child is its index
/// (LazyWideBVH::subtree). Any other count > 0 is a leaf, 0 an interior node.
constexpr std::uint32_t kWideSubtree = 0xffffffffu;

/// What a slot marked kWideSubtree leads to: the subtree's nodes (null when
/// it is one leaf) and its root's child/count as a slot would hold.
struct WideSubtree
{
  const WideNode* nodes;
  std::uint32_t child;
  std::uint32_t count;
};

} // namespace vtkrt::core

#endif
