// The float pre-tests of the wide walk (WideTraversal.h), as the walk calls
// them: a node's eight boxes, a leaf's triangles, and the fetch of a node's
// children. Four lanes a step (WideSseKernels: SSE, or plain loops without
// it) or eight (WideAvx2Kernels, compiled for AVX2): the same bits either
// way.
#ifndef vtkrt_core_simd_WideKernels_h
#define vtkrt_core_simd_WideKernels_h

#include "vtkrt/core/ConservativeFloat.h"
#include "vtkrt/core/WideNode.h"
#include "vtkrt/core/simd/Dispatch.h"

#include <cstdint>

namespace vtkrt::core
{

struct WideSseKernels
{
  using BoxRay = ConservativeBoxRay4;
  static constexpr int kTriangleLanes = 4;
  static int boxes(const BoxRay& r, const WideNode& w, float tmaxScaled, float tnear[kWideArity])
  {
    return intersectBoxes8(r, w.box, tmaxScaled, tnear);
  }
  static int triangles(const ConservativeRay4& r, const float* tri, int n)
  {
    return triangleCandidates4(r, tri, n);
  }
  /// Starts the loads of node w's children: both lines of each child node,
  /// the first two lines of each leaf's slots (leafBase + slot * leafStride).
  /// Without branches: an unused slot fetches node 0 of the array, a slot
  /// built on demand some line of the leaf data, both harmless. Addresses
  /// are integers: a prefetch never faults, and no pointer is formed out of
  /// its array.
  VTKRT_ALWAYS_INLINE static void prefetchChildren(
    const WideNode& w, std::uintptr_t nodeBase, std::uintptr_t leafBase, std::uintptr_t leafStride)
  {
#if VTKRT_CORE_SSE
    for (int i = 0; i < kWideArity; ++i)
    {
      const std::uintptr_t c = w.child[i];
      const std::uintptr_t p = w.count[i] == 0 ? nodeBase + c * sizeof(WideNode) : leafBase + c * leafStride;
      _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0);
      _mm_prefetch(reinterpret_cast<const char*>(p + 64), _MM_HINT_T0);
    }
#else
    (void)w;
    (void)nodeBase;
    (void)leafBase;
    (void)leafStride;
#endif
  }
};

#if VTKRT_CORE_AVX2
struct WideAvx2Kernels
{
  using BoxRay = ConservativeBoxRay8;
  static constexpr int kTriangleLanes = 8;
  VTKRT_TARGET_AVX2 static int boxes(const BoxRay& r, const WideNode& w, float tmaxScaled, float tnear[kWideArity])
  {
    return intersectBoxes8(r, w.box, tmaxScaled, tnear);
  }
  VTKRT_TARGET_AVX2 static int triangles(const ConservativeRay4& r, const float* tri, int n)
  {
    return triangleCandidates8(r, tri, n);
  }
  /// prefetchChildren's eight addresses in two AVX2 steps.
  VTKRT_TARGET_AVX2 static void prefetchChildren(
    const WideNode& w, std::uintptr_t nodeBase, std::uintptr_t leafBase, std::uintptr_t leafStride)
  {
    static_assert(sizeof(WideNode) == 128, "a child node's offset is its index shifted by 7");
    const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(w.child));
    const __m256i interior =
      _mm256_cmpeq_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(w.count)), _mm256_setzero_si256());
    alignas(32) std::uint64_t address[kWideArity];
    for (int half = 0; half < 2; ++half)
    {
      const __m256i c = _mm256_cvtepu32_epi64(
        half ? _mm256_extracti128_si256(child, 1) : _mm256_castsi256_si128(child));
      const __m256i isNode = _mm256_cvtepi32_epi64(
        half ? _mm256_extracti128_si256(interior, 1) : _mm256_castsi256_si128(interior));
      const __m256i node = _mm256_add_epi64(_mm256_set1_epi64x(static_cast<long long>(nodeBase)), _mm256_slli_epi64(c, 7));
      const __m256i leaf = _mm256_add_epi64(_mm256_set1_epi64x(static_cast<long long>(leafBase)),
        _mm256_mul_epu32(c, _mm256_set1_epi64x(static_cast<long long>(leafStride))));
      _mm256_store_si256(reinterpret_cast<__m256i*>(address + 4 * half), _mm256_blendv_epi8(leaf, node, isNode));
    }
    for (const std::uint64_t p : address)
    {
      _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0);
      _mm_prefetch(reinterpret_cast<const char*>(p + 64), _MM_HINT_T0);
    }
  }
};
#endif

} // namespace vtkrt::core

#endif
