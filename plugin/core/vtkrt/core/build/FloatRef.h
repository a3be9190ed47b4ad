// The binned SAH builder's references: 32-byte float boxes in the build's
// frame (the valid boxes' corner at the origin, their largest extent 1; a
// range far smaller than its frame gets one of its own), half the bytes of
// a double reference, each pass over them in SSE. Only the splits are
// decided on them: every node box is the exact double box, merged up from
// the leaves' primitives.
#ifndef vtkrt_core_build_FloatRef_h
#define vtkrt_core_build_FloatRef_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/build/BuildRef.h"
#include "vtkrt/core/build/Parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace vtkrt::core::detail
{

/// One valid primitive: its box in the build's frame (rounded to nearest)
/// and its id (lo and hi are each one SSE load; lane 3 of lo holds the id,
/// of hi 0).
struct alignas(16) FloatRef
{
  float lo[3];
  std::uint32_t id;
  float hi[3];
  std::uint32_t zero;

  /// lo + hi on one axis: twice the centroid, what splits compare.
  float centroid2(int axis) const { return lo[axis] + hi[axis]; }
};
static_assert(sizeof(FloatRef) == 32, "two SSE loads a reference");

using FloatRefs = HugePageArray<FloatRef>;

/// The build's frame: a box's corner at the origin, the largest extent 1.
/// Scaled by a power of two first (exact), so that a box spanning the
/// whole double range does not overflow its subtraction.
struct RefFrame
{
  double pre = 1.0;
  Vec3<double> origin;
  double post = 1.0;

  explicit RefFrame(const AABB<double>& root)
  {
    double largest = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      largest = std::max(largest, std::max(std::abs(root.min[k]), std::abs(root.max[k])));
    }
    int exponent = 0;
    std::frexp(largest, &exponent);
    // Clamped so that both scales stay finite for subnormal input.
    pre = std::ldexp(1.0, -std::max(exponent, -1020));
    origin = root.min * pre;
    const Vec3<double> d = root.max * pre - origin;
    const double extent = std::max(d.x, std::max(d.y, d.z));
    post = extent > 0.0 ? std::min(1.0 / extent, 0x1p1000) : 1.0;
  }

  FloatRef toRef(const AABB<double>& box, std::uint32_t id) const
  {
    FloatRef r;
    for (int k = 0; k < 3; ++k)
    {
      r.lo[k] = static_cast<float>((box.min[k] * pre - origin[k]) * post);
      r.hi[k] = static_cast<float>((box.max[k] * pre - origin[k]) * post);
    }
    r.id = id;
    r.zero = 0;
    return r;
  }
};

/// The references of the valid boxes among boundsOf(0 .. count-1), in id
/// order, in the frame of their union `root`; boundsOf is called from
/// several threads at once (twice a primitive: the frame, then the
/// references).
template <class BoundsFn>
FloatRefs fillFloatRefs(std::size_t count, BoundsFn& boundsOf, const BuildOptions& options, AABB<double>& root)
{
  const bool allValid = unionOfBuildable(count, boundsOf, options, root, [](std::size_t, const AABB<double>&, bool) {});
  if (root.isEmpty())
  {
    return FloatRefs();
  }
  const RefFrame frame(root);
  FloatRefs refs(count);
  constexpr float skipped = std::numeric_limits<float>::infinity(); // never a frame coordinate
  parallelChunks(count, options, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
    {
      const AABB<double> box = boundsOf(i);
      const bool buildable = isBuildable(box);
      refs[i] = frame.toRef(buildable ? box : root, static_cast<std::uint32_t>(i));
      refs[i].lo[0] = buildable ? refs[i].lo[0] : skipped;
    }
  });
  if (!allValid)
  {
    refs.erase(std::remove_if(refs.begin(), refs.end(), [](const FloatRef& r) { return r.lo[0] == skipped; }),
      refs.end());
  }
  return refs;
}

} // namespace vtkrt::core::detail

#endif
