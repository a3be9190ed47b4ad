// Building a BVH over a generic list of primitive bounds (centroid = box
// center), so one builder serves triangles, spheres and instances. The
// public entry: buildBVH, buildBVHConcurrentBounds (double nodes, BVH),
// buildGpuBVH, buildGpuBVHConcurrentBounds (the GPU's float nodes, GpuBVH),
// refit, computeTreeStats. The builders live in build/, one a file
// (LBVHBuilder, BinnedSAHBuilder, SweepSAHBuilder over the shared
// TopDownBuilder recursion, writing either node format of NodeFormats.h);
// DefaultBuilder picks one by BuildOptions::quality.
//
// Determinism: the tree depends only on the input, never on the thread count
// (build/TopDownBuilder.h says how).
#ifndef vtkrt_core_BVHBuild_h
#define vtkrt_core_BVHBuild_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/build/BuildRef.h"
#include "vtkrt/core/build/DefaultBuilder.h"
#include "vtkrt/core/build/Parallel.h"
#include "vtkrt/core/build/Refit.h"
#include "vtkrt/core/build/TreeStats.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <vector>

namespace vtkrt::core
{

namespace detail
{
template <class Tree>
void setBuildStats(Tree& bvh, std::size_t count, std::size_t built, const BuildOptions& options,
  std::chrono::steady_clock::time_point start)
{
  bvh.stats.inputPrimitives = count;
  bvh.stats.builtPrimitives = built;
  bvh.stats.skippedPrimitives = count - built;
  computeTreeStats(bvh.nodes, bvh.stats, options);
  bvh.stats.buildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The build from filled double references (valid boxes only, ascending
/// ids) into `tree` (a BVH or a GpuBVH, nodes of `format`).
template <class Format, class Tree>
void buildFromRefs(BuildRefs& refs, std::size_t count, const Format& format, const BuildOptions& options,
  std::chrono::steady_clock::time_point start, Tree& tree)
{
  const std::size_t built = refs.size();
  buildWithDoubleRefs(refs, format, options, tree);
  setBuildStats(tree, count, built, options, start);
}

/// The double references of the valid boxes among boundsOf(0 .. count-1),
/// in id order, and their union `root`; boundsOf is called from several
/// threads at once.
template <class BoundsFn>
BuildRefs fillDoubleRefs(std::size_t count, BoundsFn& boundsOf, const BuildOptions& options, AABB<double>& root)
{
  BuildRefs refs(count);
  const bool allValid = unionOfBuildable(count, boundsOf, options, root,
    [&refs](std::size_t i, const AABB<double>& box, bool valid) {
      refs[i] = { valid ? box : AABB<double>(), static_cast<std::uint32_t>(i) };
    });
  if (!allValid)
  {
    // Drop the skipped ones, keeping the order (what buildBVH's loop does).
    refs.erase(std::remove_if(refs.begin(), refs.end(), [](const BuildRef& r) { return r.box.isEmpty(); }),
      refs.end());
  }
  return refs;
}

/// The binned SAH build over filled references into `tree` (a BVH or a
/// GpuBVH, nodes of `format`); boundsOf is called from several threads.
template <class BoundsFn, class Format, class Tree>
void buildTreeOnFloatRefs(FloatRefs& refs, std::size_t count, BoundsFn& boundsOf, const Format& format,
  const BuildOptions& options, std::chrono::steady_clock::time_point start, Tree& tree)
{
  const std::size_t built = refs.size();
  auto leafBounds = [&boundsOf](std::uint32_t id) { return boundsOf(std::size_t(id)); };
  buildWithFloatRefs(refs, leafBounds, format, options, tree);
  setBuildStats(tree, count, built, options, start);
}

/// The build over boundsOf (called from several threads) into `tree`, a
/// BVH or a GpuBVH whose node format formatOf(root) gives; `root`: the
/// union of the valid boxes.
template <class BoundsFn, class FormatOf, class Tree>
void buildConcurrent(std::size_t count, BoundsFn& boundsOf, const BuildOptions& options,
  std::chrono::steady_clock::time_point start, FormatOf formatOf, AABB<double>& root, Tree& tree)
{
  if (buildsOnFloatRefs(options))
  {
    FloatRefs refs = fillFloatRefs(count, boundsOf, options, root);
    buildTreeOnFloatRefs(refs, count, boundsOf, formatOf(root), options, start, tree);
    return;
  }
  BuildRefs refs = fillDoubleRefs(count, boundsOf, options, root);
  buildFromRefs(refs, count, formatOf(root), options, start, tree);
}

/// The double nodes' format, whatever the root.
inline DoubleNodes doubleNodes(const AABB<double>&)
{
  return DoubleNodes();
}
} // namespace detail

/// Builds a BVH over primitives given by a callable: boundsOf(i) for i in
/// [0, count) returns primitive i's box. Primitives with empty, NaN or
/// infinite bounds are skipped and counted in stats.skippedPrimitives.
/// boundsOf is called on this thread only (the binned SAH keeps a copy of
/// the boxes; the others fill their references directly).
template <class BoundsFn>
BVH buildBVH(std::size_t count, BoundsFn&& boundsOf, const BuildOptions& options = BuildOptions())
{
  const auto start = std::chrono::steady_clock::now();
  if (detail::buildsOnFloatRefs(options))
  {
    NoFillArray<AABB<double>> boxes(count);
    for (std::size_t i = 0; i < count; ++i)
    {
      boxes[i] = boundsOf(i);
    }
    auto boxOf = [&boxes](std::size_t i) { return boxes[i]; };
    BVH bvh;
    AABB<double> root;
    detail::buildConcurrent(count, boxOf, options, start, detail::doubleNodes, root, bvh);
    return bvh;
  }
  detail::BuildRefs refs;
  refs.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const AABB<double> b = boundsOf(i);
    if (!detail::isBuildable(b))
    {
      continue;
    }
    refs.push_back({ b, static_cast<std::uint32_t>(i) });
  }
  BVH bvh;
  detail::buildFromRefs(refs, count, detail::DoubleNodes(), options, start, bvh);
  return bvh;
}

/// The same tree as buildBVH(count, boundsOf, options), with boundsOf called
/// from several threads at once (options.numThreads) on disjoint indices: it
/// must be safe to call concurrently (no shared state written). The binned
/// SAH calls it up to three times a primitive instead of keeping a copy of
/// the boxes.
template <class BoundsFn>
BVH buildBVHConcurrentBounds(std::size_t count, BoundsFn&& boundsOf, const BuildOptions& options = BuildOptions())
{
  BVH bvh;
  AABB<double> root;
  detail::buildConcurrent(count, boundsOf, options, std::chrono::steady_clock::now(), detail::doubleNodes, root, bvh);
  return bvh;
}

/// buildBVHConcurrentBounds straight into GPU nodes: the same tree as
/// packGpuNodes(bvh.nodes, origin) with origin the center of the built
/// primitives' box, never held in double nodes.
template <class BoundsFn>
GpuBVH buildGpuBVHConcurrentBounds(std::size_t count, BoundsFn&& boundsOf, const BuildOptions& options = BuildOptions())
{
  GpuBVH gpu;
  auto gpuNodes = [](const AABB<double>& root) { return detail::GpuNodes{ GpuBVH::originOf(root) }; };
  detail::buildConcurrent(count, boundsOf, options, std::chrono::steady_clock::now(), gpuNodes, gpu.bounds, gpu);
  return gpu;
}

/// buildGpuBVHConcurrentBounds over given bounds (primitive id = index).
inline GpuBVH buildGpuBVH(const std::vector<AABB<double>>& bounds, const BuildOptions& options = BuildOptions())
{
  return buildGpuBVHConcurrentBounds(bounds.size(), [&bounds](std::size_t i) { return bounds[i]; }, options);
}

/// Builds a BVH over primitives given by their bounds (primitive id = index
/// in `bounds`).
inline BVH buildBVH(const std::vector<AABB<double>>& bounds, const BuildOptions& options = BuildOptions())
{
  return buildBVHConcurrentBounds(bounds.size(), [&bounds](std::size_t i) { return bounds[i]; }, options);
}

} // namespace vtkrt::core

#endif
