// What every builder sorts and partitions: one valid primitive's box and id.
#ifndef vtkrt_core_build_BuildRef_h
#define vtkrt_core_build_BuildRef_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/build/Parallel.h"
#include "vtkrt/core/simd/Dispatch.h" // VTKRT_ALWAYS_INLINE

#include <algorithm>
#include <cstdint>
#include <mutex>

namespace vtkrt::core::detail
{

/// A primitive as the builders see it (centroid = box center).
struct BuildRef
{
  AABB<double> box;
  std::uint32_t id;
  Vec3<double> centroid() const { return box.center(); }
};

/// The references of one build: no zero fill (every element is written
/// before it is read), huge pages when large (fresh 4 KiB pages cost more
/// than the builder's arithmetic on them).
using BuildRefs = HugePageArray<BuildRef>;

/// a.extend(b) in the builders' passes over references, compiled into them
/// whatever the compiler's inlining budget (not inlined, the call is about
/// a quarter of a build); component by component: glm::min and glm::max's order of
/// operands, so the same box, NaN and signed zeros included.
VTKRT_ALWAYS_INLINE inline void extendBox(AABB<double>& a, const Vec3<double>& lo, const Vec3<double>& hi)
{
  a.min.x = std::min(a.min.x, lo.x);
  a.min.y = std::min(a.min.y, lo.y);
  a.min.z = std::min(a.min.z, lo.z);
  a.max.x = std::max(a.max.x, hi.x);
  a.max.y = std::max(a.max.y, hi.y);
  a.max.z = std::max(a.max.z, hi.z);
}
VTKRT_ALWAYS_INLINE inline void extendBox(AABB<double>& a, const AABB<double>& b)
{
  extendBox(a, b.min, b.max);
}
VTKRT_ALWAYS_INLINE inline void extendBox(AABB<double>& a, const Vec3<double>& p)
{
  extendBox(a, p, p);
}

/// Whether the builders take a primitive with this box (empty, NaN or
/// infinite ones are skipped).
inline bool isBuildable(const AABB<double>& box)
{
  return !box.isEmpty() && box.isFinite();
}

/// The union `root` of the valid boxes among boundsOf(0 .. count-1), with
/// visit(i, box, valid) on each (boundsOf and visit run on several threads
/// at once, on disjoint indices); whether every box was valid.
template <class BoundsFn, class Visit>
bool unionOfBuildable(std::size_t count, BoundsFn& boundsOf, const BuildOptions& options, AABB<double>& root,
  Visit visit)
{
  root = AABB<double>();
  bool allValid = true;
  std::mutex merge;
  parallelChunks(count, options, [&](std::size_t b, std::size_t e) {
    AABB<double> chunk;
    bool valid = true;
    for (std::size_t i = b; i < e; ++i)
    {
      const AABB<double> box = boundsOf(i);
      const bool ok = isBuildable(box);
      if (ok)
      {
        extendBox(chunk, box);
      }
      visit(i, box, ok);
      valid = valid && ok;
    }
    std::lock_guard<std::mutex> lock(merge);
    root.extend(chunk);
    allValid = allValid && valid;
  });
  return allValid;
}

/// A range's box and the box of its centroids.
struct RangeBounds
{
  AABB<double> box;
  AABB<double> centroids;
};

/// Total order on (centroid[axis], id): makes median splits and sorts
/// independent of the input order's ties.
struct AxisLess
{
  int axis;
  bool operator()(const BuildRef& a, const BuildRef& b) const
  {
    const double ca = a.box.min[axis] + a.box.max[axis];
    const double cb = b.box.min[axis] + b.box.max[axis];
    return ca < cb || (ca == cb && a.id < b.id);
  }
};

} // namespace vtkrt::core::detail

#endif
