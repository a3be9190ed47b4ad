// Four-wide float pre-tests for a double-precision ray: four boxes, or four
// triangles, at once (SSE when the compiler targets it, plain loops
// otherwise). They are CONSERVATIVE: they never reject a box that the
// double slab test (Ray.h) accepts, nor a triangle that the double
// watertight test (Triangle.h) accepts, so a traversal can cull in float
// and decide every surviving candidate exactly in double.
//
// Why they are conservative (u = 2^-24, float unit roundoff):
// - Boxes are rounded outward to float (BVH.h); a wide node's are then
//   rounded outward again to its grid, whose decoded planes are exact floats
//   (QuantizedBoxPack8), so they too are float boxes holding the exact ones.
//   The ray origin o is rounded to a float o_f; the residual |o - o_f| (plus an optional
//   tolerance) is added to each box side by using for the lower planes the
//   float roundUp(o_f + m) and for the upper planes roundDown(o_f - m) as
//   origin, so the grown box holds the exact ray. The slab distances then
//   carry only relative errors (subtraction, rounded 1/d, product: gamma(3)),
//   covered as in Ize 2013 by scaling the far distances (and tmax) by
//   1 + 4 gamma(3); a tiny absolute term covers gradual underflow.
// - Triangles: vertices rounded to nearest float, Q = R + |o|inf with R a
//   bound on |vertex|inf. Each sheared coordinate (Woop et al.'s Ax, Ay, ...)
//   is then within E = 16 u Q of the exact one the double test approximates
//   (the derivation gives 10 u Q), and each edge function (U, V, W) within
//   2 E S + 6 E^2 + 3 u S^2 of it, where S bounds |X| + |Y| of the computed
//   sheared vertices. The double test's own error is below 2^-29 of that.
//   A lane is rejected only when one edge function is below -m and another
//   above +m, with m = 4 E S + 8 E^2 + 8 u S^2 (twice the bound): the double
//   test then sees mixed signs too. The t range is left to the double test.
//
// The parts: FloatRounding.h (outward rounding), simd/Packs.h and
// simd/QuantizedBox.h (what the tests read), ConservativeRay.h (the per-ray
// constants and their preconditions), simd/Sse.h or simd/Scalar.h (four
// lanes a step), simd/Avx2.h (eight, chosen at run time: simd/Dispatch.h).
#ifndef vtkrt_core_ConservativeFloat_h
#define vtkrt_core_ConservativeFloat_h

#include "vtkrt/core/ConservativeRay.h"
#include "vtkrt/core/FloatRounding.h"
#include "vtkrt/core/simd/Avx2.h"
#include "vtkrt/core/simd/Dispatch.h"
#include "vtkrt/core/simd/Packs.h"
#include "vtkrt/core/simd/QuantizedBox.h"
#include "vtkrt/core/simd/Scalar.h"
#include "vtkrt/core/simd/Sse.h"

#endif
