// vtkrt::core: the pure C++ (GLM + std, no VTK, no GL) geometry, kernel and
// BVH library under both the locator (CPU, double) and the GLSL tracer (GPU,
// float). Header-only; include this umbrella or the single headers.
//
// API overview
//   Math.h       Vec3<T>, gammaBound<T>(n), roundDown/UpToFloat, kInvalidIndex
//   AABB.h       AABB<T>: extend, halfArea, overlaps, distance2
//   Ray.h        Ray<T>{org, dir, tmin, tmax} (dir any length: segment p1->p2
//                is dir = p2 - p1, t in [0,1]); intersectRayAABB (Ize-robust)
//   Triangle.h   intersectRayTriangle (watertight, Woop et al. 2013; u, v are
//                the weights of v1, v2 like VTK pcoords), closestPointOnTriangle
//   Sphere.h     raySphereRoots / intersectRaySphere (Ray Tracing Gems ch. 7)
//   Capsule.h    intersectRayTube: a line segment drawn as a round tube (two spheres and their cone)
//   Plane.h      intersectRayPlane -> Hit / Miss / Parallel; clipRayByPlane
//                (an interval clipped to a PlaneEquation's kept side)
//   BVH.h        the flattened layout (read its header comment: the GPU walks
//                it as is), BVHNode, BVH{nodes, primIndex, stats},
//                BuildQuality/BuildOptions/BuildStats, kMaxDepth, kMaxStackSize,
//                packGpuNodes(bvh.nodes, origin) -> gpu::Node per node
//                (packNodesForGpu: the same as 8 floats per node)
//   GpuLayout.h  the records the GPU reads (gpu::Node, Triangle, Sphere,
//                Ellipsoid, Segment, InstanceRecord, Light, flags) and glslLayout(),
//                the GLSL generated from them (a struct and a reader
//                fetch<Record> per record)
//   BVHBuild.h   buildBVH(vector<AABB<double>>, options): generic builder
//                (Fast = LBVH, Medium = binned SAH, High = sweep SAH);
//                buildGpuBVH: the same tree as GpuBVH{gpu::Node per node,
//                primIndex, origin}, never held in double;
//                refit(bvh, boundsOf) after primitives moved
//   build/       the builders, one a file (LBVHBuilder, BinnedSAHBuilder on
//                FloatRef, SweepSAHBuilder over TopDownBuilder; NodeFormats:
//                BVHNode or gpu::Node; DefaultBuilder picks by quality),
//                parallelChunks, TreeStats, Refit
//   BVHTraversal.h closestHit / anyHit / allHits (ray + intersector callable),
//                closestPoint (point + callable, max distance), queryBox;
//                also over the packed float copy (GpuNodeSource)
//   Mesh.h       TriangleMesh<T>, SphereSet<T> views; buildTriangleBVH,
//                buildSphereBVH; TriangleIntersector, SphereIntersector,
//                TriangleClosestPoint, SphereClosestPoint callables;
//                trianglesOverlappingBox; refitTriangles
//   LocalFrame.h localOrigin, relativeFloatVertices (GPU upload helpers)
//   TwoLevel.h   Instance (bottom BVH + double 4x4), TwoLevelBVH: closest and
//                any hit through both levels; setTransform + refitTop
//   ConservativeFloat.h  float pre-tests that never reject a double hit (and
//                why): FloatRounding.h, ConservativeRay.h, simd/Packs.h,
//                simd/QuantizedBox.h, simd/Sse.h or simd/Scalar.h, simd/Avx2.h;
//                simd/Dispatch.h: VTKRT_CORE_SSE/AVX2, useAvx2(), VTKRT_NO_AVX2
//   WideNode.h   the eight-wide picking node (quantized child boxes)
//   WideBVH.h    LazyWideBVH: the wide tree built directly, mostly on demand
//   WideCollapse.h collapseToWide(bvh, options): the wide view of a binary BVH
//   WideTraversal.h closestHitWide: the float SIMD picking walk over a Scene
//   SegmentQueries.h closestHitSegment / allHitsSegment (tolerance-grown
//                boxes; double fallback over the binary tree)
//   HugePageArray.h vectors without zero fill, on huge pages when large
//   GpuKernels.h   namespace gpu: the shader's kernels, its names and float
//                  operations (box test, slab, plane clip, triangle, sphere)
//   GpuTraversal.h namespace gpu: the shader's walks over the packed arrays
//                  (traverseTriangles, traverseSpheres, traceTopLevel), read
//                  by the shader's record readers (fetchNode ...)
//
// Typical use (locator):
//   TriangleMesh<double> mesh(points, indices);
//   BVH bvh = buildTriangleBVH(mesh);                 // binned SAH
//   TriangleIntersector<double> isect(mesh);
//   Hit<double> hit;
//   if (closestHit(bvh, Ray<double>(p1, p2 - p1, 0.0, 1.0), isect, hit))
//     -> hit.prim (triangle id), hit.t, hit.u, hit.v
// Typical use (GPU upload):
//   Vec3<double> o = localOrigin(mesh.vertices, mesh.vertexCount);
//   std::vector<gpu::Node> nodes = packGpuNodes(bvh.nodes, o); // RGBA32UI, 2 texels/node
//   std::vector<float> verts = relativeFloatVertices(mesh.vertices, n, o);
//   primitives are stored in leaf order (bvh.primIndex[k] is the original
//   id of slot k), so the GPU needs no index buffer
// Threads: builds are deterministic whatever BuildOptions::numThreads; all
// queries are const on the tree, but intersector objects cache per-ray data:
// give each thread its own.
#ifndef vtkrt_core_Core_h
#define vtkrt_core_Core_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/ConservativeFloat.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/GpuKernels.h"
#include "vtkrt/core/GpuTraversal.h"
#include "vtkrt/core/LocalFrame.h"
#include "vtkrt/core/GpuLayout.h"
#include "vtkrt/core/Math.h"
#include "vtkrt/core/Mesh.h"
#include "vtkrt/core/Plane.h"
#include "vtkrt/core/Ray.h"
#include "vtkrt/core/SegmentQueries.h"
#include "vtkrt/core/Sphere.h"
#include "vtkrt/core/Capsule.h"
#include "vtkrt/core/Triangle.h"
#include "vtkrt/core/TwoLevel.h"
#include "vtkrt/core/WideBVH.h"
#include "vtkrt/core/WideCollapse.h"
#include "vtkrt/core/WideNode.h"
#include "vtkrt/core/WideTraversal.h"

#endif
