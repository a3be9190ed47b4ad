// The surface area heuristic's leaf-or-split decision, shared by the
// binned and the sweep SAH builders.
#ifndef vtkrt_core_build_SAH_h
#define vtkrt_core_build_SAH_h

#include "vtkrt/core/BVH.h"

#include <cstdint>

namespace vtkrt::core::detail
{

/// Whether a leaf over `count` primitives in a box of half area
/// `parentArea` costs no more than the best split found (bestCost: the
/// children's half areas times their counts, in the same units). Only a
/// range that fits in a leaf may stay one.
inline bool leafIsCheaper(const BuildOptions& options, std::uint32_t count, double bestCost, double parentArea)
{
  if (count > options.maxLeafSize)
  {
    return false;
  }
  const double splitCost = options.traversalCost +
    options.intersectionCost * (parentArea > 0.0 ? bestCost / parentArea : double(count));
  return splitCost >= options.intersectionCost * count;
}

} // namespace vtkrt::core::detail

#endif
