// The builder that BuildOptions::quality picks: Fast -> LBVH, Medium ->
// binned SAH (on float references), High -> full-sweep SAH.
#ifndef vtkrt_core_build_DefaultBuilder_h
#define vtkrt_core_build_DefaultBuilder_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/build/BinnedSAHBuilder.h"
#include "vtkrt/core/build/BuildRef.h"
#include "vtkrt/core/build/FloatRef.h"
#include "vtkrt/core/build/LBVHBuilder.h"
#include "vtkrt/core/build/Parallel.h"
#include "vtkrt/core/build/SweepSAHBuilder.h"

#include <cstdint>
#include <vector>

namespace vtkrt::core::detail
{

/// bvh.nodes and bvh.primIndex from `builder`'s build over `n` references
/// (a BVH or a GpuBVH).
template <class Builder, class Tree>
void buildWith(Builder& builder, std::size_t n, const BuildOptions& options, Tree& bvh)
{
  bvh.nodes = builder.build();
  bvh.primIndex.resize(n);
  parallelChunks(n, options, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      bvh.primIndex[i] = builder.idAt(static_cast<std::uint32_t>(i));
    }
  });
}

/// Whether options.quality builds on float references (the binned SAH,
/// also for an unknown value) rather than double ones.
inline bool buildsOnFloatRefs(const BuildOptions& options)
{
  return options.quality != BuildQuality::Fast && options.quality != BuildQuality::High;
}

/// The double-reference builders (Fast -> LBVH, High -> full-sweep SAH)
/// into nodes of `format`; the refs may be reordered.
template <class Format, class Tree>
void buildWithDoubleRefs(BuildRefs& refs, const Format& format, const BuildOptions& options, Tree& bvh)
{
  if (options.quality == BuildQuality::Fast)
  {
    LBVHBuilder<Format> builder(refs, options, format);
    buildWith(builder, refs.size(), options, bvh);
    return;
  }
  SweepSAHBuilder<Format> builder(refs, options, format);
  buildWith(builder, refs.size(), options, bvh);
}

/// The binned SAH over float references into nodes of `format`;
/// leafBounds(id) gives the exact boxes (called from several threads).
template <class LeafBoundsFn, class Format, class Tree>
void buildWithFloatRefs(
  FloatRefs& refs, const LeafBoundsFn& leafBounds, const Format& format, const BuildOptions& options, Tree& bvh)
{
  BinnedSAHBuilder<LeafBoundsFn, Format> builder(refs, options, leafBounds, format);
  buildWith(builder, refs.size(), options, bvh);
}

} // namespace vtkrt::core::detail

#endif
