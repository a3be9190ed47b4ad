// Axis-aligned bounding box. An empty box has min = +inf, max = -inf so that
// extending it by anything yields that thing.
#ifndef vtkrt_core_AABB_h
#define vtkrt_core_AABB_h

#include "vtkrt/core/Math.h"

#include <algorithm>
#include <limits>

namespace vtkrt::core
{

template <class T>
struct AABB
{
  Vec3<T> min = Vec3<T>(std::numeric_limits<T>::infinity());
  Vec3<T> max = Vec3<T>(-std::numeric_limits<T>::infinity());

  AABB() = default;
  AABB(const Vec3<T>& lo, const Vec3<T>& hi)
    : min(lo)
    , max(hi)
  {
  }

  static AABB empty() { return AABB(); }

  /// True when min <= max on every axis (a point is not empty). NaN boxes are empty.
  bool isEmpty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
  bool isFinite() const { return core::isFinite(min) && core::isFinite(max); }

  void extend(const Vec3<T>& p)
  {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const AABB& b)
  {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }

  Vec3<T> center() const { return (min + max) * T(0.5); }
  Vec3<T> diagonal() const { return max - min; }

  /// Half the surface area (the SAH only needs ratios); 0 for an empty box.
  T halfArea() const
  {
    if (isEmpty())
    {
      return T(0);
    }
    const Vec3<T> d = diagonal();
    return d.x * d.y + d.y * d.z + d.z * d.x;
  }

  int largestAxis() const
  {
    const Vec3<T> d = diagonal();
    return d.x >= d.y ? (d.x >= d.z ? 0 : 2) : (d.y >= d.z ? 1 : 2);
  }

  bool contains(const Vec3<T>& p) const
  {
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z &&
      p.z <= max.z;
  }
  bool contains(const AABB& b) const { return contains(b.min) && contains(b.max); }

  /// Closed-interval overlap (touching boxes overlap).
  bool overlaps(const AABB& b) const
  {
    return min.x <= b.max.x && b.min.x <= max.x && min.y <= b.max.y && b.min.y <= max.y &&
      min.z <= b.max.z && b.min.z <= max.z;
  }

  /// Squared distance from p to the box (0 inside).
  T distance2(const Vec3<T>& p) const
  {
    const Vec3<T> d = glm::max(glm::max(min - p, p - max), Vec3<T>(T(0)));
    return glm::dot(d, d);
  }

  bool operator==(const AABB& o) const { return min == o.min && max == o.max; }
};

} // namespace vtkrt::core

#endif
