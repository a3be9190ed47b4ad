// The builder that BuildOptions::quality picks: Fast -> LBVH, Medium ->
// binned SAH, High -> full-sweep SAH.
#ifndef vtkrt_core_build_DefaultBuilder_h
#define vtkrt_core_build_DefaultBuilder_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/build/BinnedSAHBuilder.h"
#include "vtkrt/core/build/BuildRef.h"
#include "vtkrt/core/build/LBVHBuilder.h"
#include "vtkrt/core/build/Parallel.h"
#include "vtkrt/core/build/SweepSAHBuilder.h"

#include <cstdint>
#include <vector>

namespace vtkrt::core::detail
{

/// bvh.nodes and bvh.primIndex from `refs` with the builder `Builder` (the
/// refs may be reordered).
template <class Builder>
void buildWith(BuildRefs& refs, const BuildOptions& options, BVH& bvh)
{
  Builder builder(refs, options);
  bvh.nodes = builder.build();
  bvh.primIndex.resize(refs.size());
  parallelChunks(refs.size(), options, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      bvh.primIndex[i] = builder.idAt(static_cast<std::uint32_t>(i));
    }
  });
}

/// buildWith the builder of options.quality (an unknown value: binned SAH).
inline void buildWithDefaultBuilder(BuildRefs& refs, const BuildOptions& options, BVH& bvh)
{
  switch (options.quality)
  {
    case BuildQuality::Fast:
      buildWith<LBVHBuilder>(refs, options, bvh);
      return;
    case BuildQuality::High:
      buildWith<SweepSAHBuilder>(refs, options, bvh);
      return;
    case BuildQuality::Medium:
    default:
      buildWith<BinnedSAHBuilder>(refs, options, bvh);
      return;
  }
}

} // namespace vtkrt::core::detail

#endif
