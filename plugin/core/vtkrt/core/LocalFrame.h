// Helpers for the GPU upload: meshes are expressed relative to a local
// origin (the center of their bounds), so coordinates far from the world
// origin (1e8) become small numbers that float represents well, and the
// translation goes into the (double) instance transform instead.
#ifndef vtkrt_core_LocalFrame_h
#define vtkrt_core_LocalFrame_h

#include "vtkrt/core/BVH.h"

#include <algorithm>
#include <cmath>
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

/// The power of two that brings a positive, finite half-size into
/// [0.5, 1) (clamped to 2^-1000 .. 2^1000, normal doubles); 1 for anything
/// else. Scaling by it rounds nothing (short of double's limits).
inline double powerOfTwoScale(double halfSize)
{
  if (!(halfSize > 0.0) || !std::isfinite(halfSize))
  {
    return 1.0;
  }
  int exponent = 0;
  std::frexp(halfSize, &exponent); // halfSize in [0.5, 1) * 2^exponent
  return std::ldexp(1.0, -std::max(-1000, std::min(1000, exponent)));
}

/// A box's local frame: its center and the power of two that brings its
/// half-size near 1, so products of local coordinates stay in range
/// whatever the box's size. local = (p - origin) * scale, computed so that
/// neither the shift nor the product overflows (see toLocal).
struct ScaledFrame
{
  Vec3<double> origin{ 0.0 };
  double scale = 1.0;

  /// The frame of `box` (the identity for an empty or non-finite box).
  static ScaledFrame of(const AABB<double>& box)
  {
    ScaledFrame f;
    if (box.isEmpty() || !box.isFinite())
    {
      return f;
    }
    // Halves first: bounds spanning more than the largest double overflow
    // neither their center nor their half-size.
    const Vec3<double> half = box.max * 0.5 - box.min * 0.5;
    f.origin = box.min * 0.5 + box.max * 0.5;
    f.scale = powerOfTwoScale(std::max(half.x, std::max(half.y, half.z)));
    return f;
  }

  /// Scaling down multiplies before the shift (p - origin could overflow),
  /// scaling up after it (p * scale could).
  Vec3<double> toLocal(const Vec3<double>& p) const
  {
    return this->scale < 1.0 ? p * this->scale - this->origin * this->scale
                             : (p - this->origin) * this->scale;
  }
  Vec3<double> toModel(const Vec3<double>& local) const { return local / this->scale + this->origin; }
};

} // namespace vtkrt::core

#endif
