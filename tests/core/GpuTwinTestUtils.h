// Helpers of the tests of the shader's C++ twins (TestCoreGpuTwins,
// TestCoreGpuKernelTwins, TestCoreGpuWalkStarts, TestCoreGpuTranslucency):
// the shader's vector types, float rays as the shader receives them.
#ifndef vtkrtGpuTwinTestUtils_h
#define vtkrtGpuTwinTestUtils_h

#include "CoreTestUtils.h"

#include "vtkrt/core/GpuKernels.h"

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
} // namespace vtkrt::test

#endif
