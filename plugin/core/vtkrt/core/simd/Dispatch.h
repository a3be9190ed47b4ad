// Which SIMD kernels the core compiles, and which of them run.
//
// SSE is the baseline where the compiler targets it (x86-64 always), plain
// loops otherwise. The eight-wide AVX2 kernels are compiled for AVX2
// function by function (VTKRT_TARGET_AVX2, the target attribute) and chosen
// at run time (useAvx2()), so the library still runs on any x86-64. They do
// the same float operations in the same order as the SSE ones (no FMA:
// target("avx2") does not enable it), so their bits are the same and so is
// the proof in ConservativeFloat.h.
#ifndef vtkrt_core_simd_Dispatch_h
#define vtkrt_core_simd_Dispatch_h

#if defined(__SSE2__) || defined(_M_X64)
#define VTKRT_CORE_SSE 1
#include <emmintrin.h>
#include <xmmintrin.h>
#else
#define VTKRT_CORE_SSE 0
#endif

#if VTKRT_CORE_SSE && (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#define VTKRT_CORE_AVX2 1
#define VTKRT_TARGET_AVX2 __attribute__((target("avx2")))
#include <cstdlib>
#include <immintrin.h>
#else
#define VTKRT_CORE_AVX2 0
#define VTKRT_TARGET_AVX2
#endif

// For the walk's inner lambdas and bodies, which must be compiled into
// their (AVX2 or SSE) caller rather than called.
#if defined(__GNUC__) || defined(__clang__)
#define VTKRT_ALWAYS_INLINE __attribute__((always_inline))
#else
#define VTKRT_ALWAYS_INLINE
#endif

namespace vtkrt::core
{

/// Whether the AVX2 kernels run: the CPU has AVX2 and the environment
/// variable VTKRT_NO_AVX2 is unset (set: the SSE kernels, e.g. to compare).
inline bool useAvx2()
{
#if VTKRT_CORE_AVX2
  static const bool use = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && !std::getenv("VTKRT_NO_AVX2");
  }();
  return use;
#else
  return false;
#endif
}

} // namespace vtkrt::core

#endif
