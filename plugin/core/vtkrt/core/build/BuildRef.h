// What every builder sorts and partitions: one valid primitive's box and id.
#ifndef vtkrt_core_build_BuildRef_h
#define vtkrt_core_build_BuildRef_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/HugePageArray.h"

#include <cstdint>

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
