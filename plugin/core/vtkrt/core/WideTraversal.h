// The picking walk: a segment's closest hit over the eight-wide tree
// (WideNode.h), culling in float with the conservative pre-tests of
// ConservativeFloat.h (a node's eight boxes and a leaf's triangles, eight
// per AVX2 step where the CPU has it, else four per SSE step), so that only
// the triangles the exact double test might accept reach it. The contract
// is BVHTraversal.h's closestHit: ordered, nearest first, and the
// intersector shrinks ray.tmax.
//
// The walk is a template over the adapter's Scene, a cheap handle copied
// into it (so its loads are those of the adapter's own members), which
// provides:
//   const WideNode* pickingRoot() const  -- the root node (non-null);
//   std::uint32_t triangleCount() const  -- triangles are primitives
//     [0, triangleCount()), in leaf slot order; the others are general;
//   std::size_t generalCount() const;
//   const std::uint32_t* slotPrimitives() const  -- each leaf slot's
//     primitive, read only when generalCount() > 0 (else slot = primitive);
//   const float* floatTriangles() const  -- each triangle's nine floats
//     (vertex 0, 1, 2; x, y, z; rounded to nearest), one readable float after;
//   double extent() const  -- a bound on |vertex| (inf norm);
//   WideSubtree subtree(std::uint32_t k) const  -- a slot marked
//     kWideSubtree, built on demand;
//   void prefetchTriangles(std::uint32_t first, std::uint32_t end) const,
//   void prefetchCandidates(std::size_t first, int mask) const  -- hints:
//     what the exact test of these triangles (and a hit) will read; mark
//     them VTKRT_ALWAYS_INLINE (GCC drops a call that was not inlined
//     early to a function that only prefetches).
#ifndef vtkrt_core_WideTraversal_h
#define vtkrt_core_WideTraversal_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h" // Hit
#include "vtkrt/core/ConservativeFloat.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/WideNode.h"
#include "vtkrt/core/simd/Dispatch.h"
#include "vtkrt/core/simd/WideKernels.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace vtkrt::core
{

/// The walk fetches children ahead (prefetchChildren) for trees over this
/// many primitives (their float triangles alone outgrow a core's L2), below
/// this many wide levels (the top levels and their children stay in L2
/// anyway); on small trees the fetches cost more than they save.
constexpr std::size_t kWidePrefetchChildrenMinPrimitives = 32768;
constexpr std::uint32_t kWidePrefetchChildrenDepth = 3;

namespace detail
{

inline int countTrailingZeros(unsigned x)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctz(x);
#else
  int n = 0;
  while (!(x & 1u))
  {
    x >>= 1;
    ++n;
  }
  return n;
#endif
}

#if VTKRT_CORE_SSE
/// Fetches the cache lines of [begin, end) (non-empty) into L1.
template <class T>
VTKRT_ALWAYS_INLINE inline void prefetchRange(const T* begin, const T* end)
{
  const char* p = reinterpret_cast<const char*>(begin);
  const char* last = reinterpret_cast<const char*>(end) - 1;
  for (; p < last; p += 64)
  {
    _mm_prefetch(p, _MM_HINT_T0);
  }
  _mm_prefetch(last, _MM_HINT_T0);
}
#endif

/// Triangles [first, end) in leaf order, Kernels::kTriangleLanes at a time,
/// each survivor of the float pre-test (or every one, without it) through
/// test. Inlined, so that in the AVX2 walk it is compiled for AVX2 too.
template <class Kernels, class Scene, class Test>
VTKRT_ALWAYS_INLINE inline void testWideTriangles(const Scene& scene, const ConservativeRay4& fray,
  bool preTest, std::uint32_t first, std::uint32_t end, Test& test)
{
  if (!preTest)
  {
    for (std::uint32_t prim = first; prim < end; ++prim)
    {
      test(prim);
    }
    return;
  }
#if VTKRT_CORE_SSE
  // A survivor's exact test reads what the adapter keeps beside the float
  // triangles: fetched now, not after the float test.
  scene.prefetchTriangles(first, end);
#endif
  for (std::uint32_t t = first; t < end; t += Kernels::kTriangleLanes)
  {
    const int n = static_cast<int>(std::min<std::uint32_t>(Kernels::kTriangleLanes, end - t));
    int mask = Kernels::triangles(fray, scene.floatTriangles() + 9 * static_cast<std::size_t>(t), n) & ((1 << n) - 1);
#if VTKRT_CORE_SSE
    // Every survivor's loads start before the first exact test.
    scene.prefetchCandidates(t, mask);
#endif
    while (mask)
    {
      const int lane = countTrailingZeros(static_cast<unsigned>(mask));
      mask &= mask - 1;
      test(t + static_cast<std::uint32_t>(lane));
    }
  }
}

/// The walk with the float constants of the ray set, its pre-tests from
/// Kernels; inlined into its (SSE or AVX2) caller with the caller's exact
/// test.
template <class Kernels, class Scene, class Isect>
VTKRT_ALWAYS_INLINE inline bool walkWide(Scene scene, const ConservativeRay4& fray, Ray<double> ray,
  double tol, bool trianglePreTest, Isect& isect, Hit<double>& hit)
{
  hit = Hit<double>();
  const std::uint32_t nTri = scene.triangleCount();
  const bool allTriangles = scene.generalCount() == 0;
  // Slots are primitives when all are triangles (the binary tree may be
  // under construction then: not read); otherwise through its primIndex.
  const std::uint32_t* primIndex = allTriangles ? nullptr : scene.slotPrimitives();
  // The float triangle test knows no tolerance.
  const bool preTest = trianglePreTest && tol == 0.0;
  // Below the top levels of a large tree, a node's children are fetched
  // while its boxes are tested (Kernels::prefetchChildren): the step to
  // the next node or leaf then seldom waits on memory.
  const bool prefetchChildren = nTri + scene.generalCount() >= kWidePrefetchChildrenMinPrimitives;
  // A leaf slot leads to its float triangles (all triangles) or to its
  // primIndex entries.
  const std::uintptr_t leafBase = allTriangles ? reinterpret_cast<std::uintptr_t>(scene.floatTriangles())
                                               : reinterpret_cast<std::uintptr_t>(primIndex);
  const std::uintptr_t leafStride = allTriangles ? 9 * sizeof(float) : sizeof(std::uint32_t);
  struct Entry
  {
    const WideNode* Nodes; ///< the node array Ref indexes (interior children)
    std::uint32_t Ref;
    std::uint32_t Count; ///< > 0: a leaf (Ref = first primIndex slot); kWideSubtree: not built yet
    float Dist;
    std::uint32_t Depth; ///< wide levels below the root
  };
  // Each wide level pushes at most kWideArity - 1 entries; there are at
  // most kMaxDepth levels.
  Entry stack[(kWideArity - 1) * kMaxStackSize + 4];
  std::uint32_t sp = 0;
  float tmaxF = ConservativeRay4::scaledTmax(ray.tmax);
  bool found = false;
  auto test = [&](std::uint32_t prim) VTKRT_ALWAYS_INLINE {
    Hit<double> candidate = hit;
    if (isect(prim, ray, candidate))
    {
      candidate.prim = prim;
      found = true;
      hit = candidate;
      ray.tmax = hit.t;
      tmaxF = ConservativeRay4::scaledTmax(ray.tmax);
    }
  };
  auto testTriangles = [&](std::uint32_t first, std::uint32_t end) VTKRT_ALWAYS_INLINE {
    testWideTriangles<Kernels>(scene, fray, preTest, first, end, test);
  };
  // A child that waits on the stack: its node's lines, or a leaf's float
  // triangles (what the float test reads), fetched meanwhile.
  auto prefetchEntry = [&](const Entry& c) VTKRT_ALWAYS_INLINE {
#if VTKRT_CORE_SSE
    if (c.Count == 0)
    {
      const char* next = reinterpret_cast<const char*>(&c.Nodes[c.Ref]);
      for (std::size_t line = 0; line < sizeof(WideNode); line += 64)
      {
        _mm_prefetch(next + line, _MM_HINT_T0);
      }
    }
    else if (allTriangles && c.Count != kWideSubtree)
    {
      prefetchRange(scene.floatTriangles() + 9 * static_cast<std::size_t>(c.Ref),
        scene.floatTriangles() + 9 * static_cast<std::size_t>(c.Ref + c.Count));
    }
#else
    (void)c;
#endif
  };
  const typename Kernels::BoxRay boxRay(fray);
  Entry cur{ scene.pickingRoot(), 0, 0, 0.0f, 0 };
  for (;;)
  {
    if (cur.Count == kWideSubtree)
    {
      // A bucket of the fast build that no query has reached yet: built
      // now (once; thread-safe), then walked as if it had been there.
      const WideSubtree sub = scene.subtree(cur.Ref);
      cur = { sub.nodes, sub.child, sub.count, cur.Dist, cur.Depth };
    }
    if (cur.Count == 0)
    {
      const WideNode& w = cur.Nodes[cur.Ref];
      if (prefetchChildren && cur.Depth >= kWidePrefetchChildrenDepth)
      {
        Kernels::prefetchChildren(w, reinterpret_cast<std::uintptr_t>(cur.Nodes), leafBase, leafStride);
      }
      alignas(32) float tnear[kWideArity];
      int mask = Kernels::boxes(boxRay, w, tmaxF, tnear);
      if (mask)
      {
        // The nearest hit child is walked next (one hit, the most common
        // case, is just that); the others go on the stack farthest first,
        // their first loads started now (below the top levels too, where
        // prefetchChildren fetched only a leaf's first lines).
        int i = countTrailingZeros(static_cast<unsigned>(mask));
        mask &= mask - 1;
        Entry nearest{ cur.Nodes, w.child[i], w.count[i], tnear[i], cur.Depth + 1 };
        const std::uint32_t base = sp;
        while (mask)
        {
          i = countTrailingZeros(static_cast<unsigned>(mask));
          mask &= mask - 1;
          Entry c{ cur.Nodes, w.child[i], w.count[i], tnear[i], cur.Depth + 1 };
          if (c.Dist < nearest.Dist)
          {
            std::swap(c, nearest);
          }
          prefetchEntry(c);
          std::uint32_t j = sp++;
          while (j > base && stack[j - 1].Dist < c.Dist)
          {
            stack[j] = stack[j - 1];
            --j;
          }
          stack[j] = c;
        }
        cur = nearest;
        continue;
      }
    }
    else if (allTriangles)
    {
      testTriangles(cur.Ref, cur.Ref + cur.Count); // primIndex is the identity
    }
    else
    {
      for (std::uint32_t k = 0; k < cur.Count; ++k)
      {
        const std::uint32_t prim = primIndex[cur.Ref + k];
        if (prim < nTri)
        {
          testTriangles(prim, prim + 1);
        }
        else
        {
          test(prim);
        }
      }
    }
    do
    {
      if (sp == 0)
      {
        return found;
      }
      cur = stack[--sp];
    } while (cur.Dist > tmaxF);
  }
}

} // namespace detail

#if VTKRT_CORE_AVX2
/// The ray's float constants and the walk compiled for AVX2 (the walk is
/// inlined here, with the caller's exact test): only called when the CPU
/// has it. closestHitWide's return values.
template <class Scene, class Isect>
VTKRT_TARGET_AVX2 int closestHitWideAvx2(Scene scene, const Ray<double>& ray,
  const RayTrianglePrecomputed<double>& triPre, double tol, bool trianglePreTest, Isect& isect, Hit<double>& hit)
{
  ConservativeRay4 fray;
  if (!fray.initAvx2(ray, triPre, tol, scene.extent()))
  {
    return -1;
  }
  return detail::walkWide<WideAvx2Kernels>(scene, fray, ray, tol, trianglePreTest, isect, hit) ? 1 : 0;
}
#endif

/// The closest hit of `ray` within the boxes grown by tol (the triangles'
/// float pre-test only runs at tol 0, and only with trianglePreTest: off,
/// isect sees every triangle of every leaf the walk reaches). Returns 1
/// (hit), 0 (none), or -1 when the float walk cannot take the ray
/// (ConservativeRay4::init refuses it: walk in double instead, e.g.
/// closestHitSegment). An isect that never reports a hit sees every
/// primitive of every leaf whose box the segment meets.
template <class Scene, class Isect>
int closestHitWide(Scene scene, const Ray<double>& ray, const RayTrianglePrecomputed<double>& triPre, double tol,
  Isect& isect, Hit<double>& hit, bool trianglePreTest = true)
{
#if VTKRT_CORE_AVX2
  if (useAvx2())
  {
    return closestHitWideAvx2(scene, ray, triPre, tol, trianglePreTest, isect, hit);
  }
#endif
  ConservativeRay4 fray;
  if (!fray.init(ray, triPre, tol, scene.extent()))
  {
    return -1;
  }
  return detail::walkWide<WideSseKernels>(scene, fray, ray, tol, trianglePreTest, isect, hit) ? 1 : 0;
}

} // namespace vtkrt::core

#endif
