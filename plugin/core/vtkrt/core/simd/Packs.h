// The structure-of-arrays packs the float pre-tests read: four triangles,
// and four or eight boxes, one lane each.
#ifndef vtkrt_core_simd_Packs_h
#define vtkrt_core_simd_Packs_h

#include "vtkrt/core/Math.h"

#include <limits>

namespace vtkrt::core
{

/// Four triangles, structure of arrays: v[3 * vertex + axis][lane], in the
/// local frame of the double vertices (rounded to nearest float).
struct alignas(16) TrianglePack4
{
  float v[9][4];

  void set(int lane, const Vec3<double>& v0, const Vec3<double>& v1, const Vec3<double>& v2)
  {
    const Vec3<double>* vs[3] = { &v0, &v1, &v2 };
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        v[3 * k + a][lane] = static_cast<float>((*vs[k])[a]);
      }
    }
  }
  void clear(int lane)
  {
    for (auto& row : v)
    {
      row[lane] = 0.0f;
    }
  }
};

/// Four (BoxPack4) or eight (BoxPack8) boxes, structure of arrays:
/// lo[axis][lane], hi[axis][lane], float, rounded outward. An unused lane
/// holds lo = +inf, hi = -inf (never hit).
template <int N>
struct alignas(4 * N) BoxPack
{
  float lo[3][N];
  float hi[3][N];

  void clear(int lane)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a][lane] = std::numeric_limits<float>::infinity();
      hi[a][lane] = -std::numeric_limits<float>::infinity();
    }
  }
};
using BoxPack4 = BoxPack<4>;
using BoxPack8 = BoxPack<8>; ///< the children of a wide node

} // namespace vtkrt::core

#endif
