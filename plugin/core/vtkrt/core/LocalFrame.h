// Helpers for the GPU upload: meshes are expressed relative to a local
// origin (the center of their bounds), so coordinates far from the world
// origin (1e8) become small numbers that float represents well, and the
// translation goes into the (double) instance transform instead.
#ifndef vtkrt_core_LocalFrame_h
#define vtkrt_core_LocalFrame_h

#include "vtkrt/core/BVH.h"

#include <vector>

namespace vtkrt::core
{

/// The local origin of a set of points: the center of their (finite) bounds.
/// (0,0,0) for an empty set.
template <class T>
inline Vec3<double> localOrigin(const Vec3<T>* points, std::size_t count)
{
  AABB<double> box;
  for (std::size_t i = 0; i < count; ++i)
  {
    const Vec3<double> p(points[i]);
    if (isFinite(p))
    {
      box.extend(p);
    }
  }
  return box.isEmpty() ? Vec3<double>(0.0) : box.center();
}

/// Vertices minus `origin`, rounded to nearest float, `components` floats
/// per vertex (3 for RGB32F, 4 for RGBA32F with w = 1). Shared vertices stay
/// shared bit for bit, which is what keeps the float watertight test
/// watertight. Rounding to nearest keeps every vertex inside the outward
/// rounded boxes of packNodesForGpu with the same origin.
template <class T>
inline std::vector<float> relativeFloatVertices(
  const Vec3<T>* points, std::size_t count, const Vec3<double>& origin, int components = 4)
{
  std::vector<float> out(count * components);
  for (std::size_t i = 0; i < count; ++i)
  {
    const Vec3<double> p = Vec3<double>(points[i]) - origin;
    float* o = out.data() + i * components;
    o[0] = static_cast<float>(p.x);
    o[1] = static_cast<float>(p.y);
    o[2] = static_cast<float>(p.z);
    if (components > 3)
    {
      o[3] = 1.0f;
    }
  }
  return out;
}

template <class T>
inline std::vector<Vec3<float>> relativeFloatPoints(const Vec3<T>* points, std::size_t count, const Vec3<double>& origin)
{
  std::vector<Vec3<float>> out(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    out[i] = Vec3<float>(Vec3<double>(points[i]) - origin);
  }
  return out;
}

} // namespace vtkrt::core

#endif
