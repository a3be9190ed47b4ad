// Helpers of the tests of the shader's C++ twins (TestCoreGpuTwins,
// TestCoreGpuKernelTwins, TestCoreGpuWalkStarts, TestCoreGpuTranslucency):
// the shader's vector types, float rays as the shader receives them, the
// triangle texels the walks read.
#ifndef vtkrtGpuTwinTestUtils_h
#define vtkrtGpuTwinTestUtils_h

#include "CoreTestUtils.h"

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/GpuKernels.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vtkrt::test
{
using core::gpu::vec2;
using core::gpu::vec3;
using core::gpu::vec4;

inline vec3 toFloat(const Vec3<double>& v)
{
  return vec3(v);
}

/// A direction with some components zeroed (axis-parallel rays) now and then.
inline vec3 randomDirection(Rng& rng, const Vec3<double>& toward)
{
  vec3 d = toFloat(toward);
  const double pick = rng.uniform();
  if (pick < 0.15)
  {
    d[rng.index(3)] = 0.0f;
  }
  else if (pick < 0.25)
  {
    const int keep = int(rng.index(3));
    d = vec3(0.0f);
    d[keep] = toward[keep] < 0 ? -1.0f : 1.0f;
  }
  return d;
}
/// The shader's triangle texels, in leaf order: (v0, id), (v1, 0), (v2, 0),
/// id the triangle's index in `indices`.
inline std::vector<float> packTriangles(const core::BVH& bvh, const std::vector<Vec3<float>>& verts,
  const std::vector<std::uint32_t>& indices)
{
  std::vector<float> out(12 * bvh.primIndex.size(), 0.0f);
  for (std::size_t k = 0; k < bvh.primIndex.size(); ++k)
  {
    const std::uint32_t tri = bvh.primIndex[k];
    for (int v = 0; v < 3; ++v)
    {
      const Vec3<float>& p = verts[indices[3 * tri + v]];
      std::copy_n(&p.x, 3, out.begin() + 12 * k + 4 * v);
    }
    out[12 * k + 3] = core::uintBitsToFloat(tri);
  }
  return out;
}
} // namespace vtkrt::test

#endif
