// vtkrt GLSL kernels shared by every ray-traced scene: the robust ray/AABB
// slab test, ray/plane clipping and the BVH walk's steps. Each function has
// a C++ twin of the same name and float operations in namespace
// vtkrt::core::gpu (plugin/core/vtkrt/core/GpuKernels.h, GpuTraversal.h),
// which is the core function where one exists (Ray.h, Plane.h) and which
// TestCoreGpuTwins checks against the double core: change both together.

// core::gpu::unpackRGBA8: the 8-bit color channels of a word, lowest byte
// red, as GLSL 4.00's unpackUnorm4x8 (these shaders are GLSL 3.30).
vec4 unpackRGBA8(uint v)
{
  return vec4(uvec4(v, v >> 8u, v >> 16u, v >> 24u) & 0xFFu) / 255.0;
}

// Ize 2013: the far distance is scaled by 1 + 2*gamma(3) so rounding never
// culls a box the ray touches. gamma(3) = 3u/(1-3u), u = 2^-24.
const float kFarScale = 1.0 + 2.0 * (3.0 * 5.9604645e-8) / (1.0 - 3.0 * 5.9604645e-8);

// core::RayBoxPrecomputed::safeInverse: a zero (or subnormal)
// direction component, whose inverse is not finite, maps to 0, which marks
// the axis as parallel for clipSlab.
float safeInverse(float d)
{
  float inv = 1.0 / d;
  return abs(inv) <= 3.40282347e38 ? inv : 0.0;
}

vec3 safeInverse(vec3 d)
{
  return vec3(safeInverse(d.x), safeInverse(d.y), safeInverse(d.z));
}

// core::detail::clipSlab: one slab of the box. A parallel axis is
// decided by the origin alone (closed interval), so no NaN can arise.
bool clipSlab(float lo, float hi, float org, float invDir, inout float tmin, inout float tmax)
{
  if (invDir == 0.0)
  {
    return org >= lo && org <= hi;
  }
  float t0 = (lo - org) * invDir;
  float t1 = (hi - org) * invDir;
  if (t1 < t0)
  {
    float tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  t1 *= kFarScale;
  tmin = t0 > tmin ? t0 : tmin;
  tmax = t1 < tmax ? t1 : tmax;
  return true;
}

// core::intersectRayAABB: on hit, tnear is the entry distance clamped to
// [tmin, tmax].
bool intersectRayAABB(vec3 org, vec3 invDir, vec3 bmin, vec3 bmax, float tmin, float tmax,
  out float tnear)
{
  tnear = tmin;
  if (!clipSlab(bmin.x, bmax.x, org.x, invDir.x, tmin, tmax) ||
    !clipSlab(bmin.y, bmax.y, org.y, invDir.y, tmin, tmax) ||
    !clipSlab(bmin.z, bmax.z, org.z, invDir.z, tmin, tmax))
  {
    return false;
  }
  tnear = tmin;
  return tmin <= tmax;
}

// A point through the rows of an affine map (an instance's camera-to-local
// rows, an ellipsoid's world-to-unit rows), then a direction (no translation).
vec3 rowsPoint(vec4 r0, vec4 r1, vec4 r2, vec3 p)
{
  return vec3(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
}

vec3 rowsDir(vec4 r0, vec4 r1, vec4 r2, vec3 d)
{
  return vec3(dot(r0.xyz, d), dot(r1.xyz, d), dot(r2.xyz, d));
}

// The parallelBias of intersectRayBoxConservative for a ray's invDir.
vec3 parallelAxisBias(vec3 invDir)
{
  return vec3(equal(invDir, vec3(0.0))) * 3.0e38;
}

// The slab test of core::intersectRayAABB without its per-axis branches
// (llvmpipe runs both sides of every branch, masked): the same arithmetic on
// every axis the ray is not parallel to, so the same result there. On a
// parallel axis (invDir 0, so t0 = t1 = 0; parallelBias 3e38 there, 0
// elsewhere) the origin decides: inside the closed slab the axis bounds
// nothing, outside it tnear becomes parallelBias, past every tfar of the
// ray's other axes. A parallel projection along an axis makes every camera
// ray parallel to two axes: accepting every box there would walk most of
// the tree. Needs tmin >= 0 (a parallel axis contributes tnear 0).
bool intersectRayBoxConservative(vec3 org, vec3 invDir, vec3 parallelBias, vec3 bmin, vec3 bmax,
  float tmin, float tmax, out float tnear)
{
  vec3 d0 = bmin - org;
  vec3 d1 = bmax - org;
  vec3 t0 = d0 * invDir;
  vec3 t1 = d1 * invDir;
  vec3 outside = max(max(d0, -d1), vec3(0.0));
  vec3 tn = min(t0, t1) + sign(outside) * parallelBias;
  vec3 tf = max(t0, t1) * kFarScale + parallelBias;
  tnear = max(max(tn.x, tn.y), max(tn.z, tmin));
  float tfar = min(min(tf.x, tf.y), min(tf.z, tmax));
  return tnear <= tfar;
}

// core::gpu::affineRayDepth: the normalized device depth of a camera ray's
// point at t, clip z over clip w, both affine along the ray (rayDepth:
// their values at t = 0 and their slopes, the same for every camera ray).
float affineRayDepth(vec4 rayDepth, float t)
{
  return (rayDepth.x + t * rayDepth.y) / (rayDepth.z + t * rayDepth.w);
}

// core::gpu::affineRayT: affineRayDepth inverted, the t at which the camera
// ray's normalized device depth is ndcDepth.
float affineRayT(vec4 rayDepth, float ndcDepth)
{
  return (rayDepth.x - ndcDepth * rayDepth.z) / (ndcDepth * rayDepth.w - rayDepth.y);
}

// core::gpu::projectiveRayT: the t at which the camera ray (org, dir)
// through ndc reaches normalized device depth ndcDepth, for any projective
// clipToCamera matrix.
float projectiveRayT(mat4 clipToCamera, vec2 ndc, float ndcDepth, vec3 org, vec3 dir)
{
  vec4 p = clipToCamera * vec4(ndc, ndcDepth, 1.0);
  return dot(p.xyz / p.w - org, dir) / dot(dir, dir);
}

// core::clipRayByPlane (Plane.h): clips the ray's [tmin, tmax] to the
// half-space n.p + d >= 0 of the plane (n, d) (what VTK keeps); a parallel
// ray is kept or clipped whole by its origin's side. Returns false when
// nothing of the interval survives.
bool clipRayByPlane(vec3 org, vec3 dir, vec4 plane, inout float tmin, inout float tmax)
{
  float denom = dot(plane.xyz, dir);
  float f0 = dot(plane.xyz, org) + plane.w;
  if (denom == 0.0)
  {
    // Parallel: either entirely kept or entirely clipped.
    return f0 >= 0.0;
  }
  float t = -f0 / denom;
  if (denom > 0.0)
  {
    tmin = max(tmin, t);
  }
  else
  {
    tmax = min(tmax, t);
  }
  return tmin <= tmax;
}

// Every scene buffer is an RGBA32UI texture buffer read through a
// usamplerBuffer: integer fields (indices, counts, ids, packed colors) come
// back bit exact (a float view may flush the denormal floats that small
// integers are), float fields are uintBitsToFloat of their bits. Records
// are read by the generated readers (fetchNode ...) into structs of the
// core's layout (vtkrt/core/GpuLayout.h).

// The Nodes of every bottom-level BVH (fetchNode): count == 0: interior
// with children index and index + 1; count > 0: leaf over primitives
// [index, index + count).
uniform usamplerBuffer uNodes;

// The root node of the tree at `root`, where a walk starts. A shader of one
// instance walks one tree: its root is the frame constant uRootNode, the
// same for every pixel, so not fetched per pixel.
#ifdef VTKRT_SINGLE_INSTANCE
Node rootNodeOf(int root)
{
  return unpackNode(uRootNode);
}
#else
Node rootNodeOf(int root)
{
  return fetchNode(uNodes, root);
}
#endif

// Four 32-bit values packed per texel (ids and RGBA8 colors).
uint fetchPacked(usamplerBuffer buffer, int i)
{
  uvec4 texel = texelFetch(buffer, i >> 2);
  int c = i & 3;
  return c == 0 ? texel.x : (c == 1 ? texel.y : (c == 2 ? texel.z : texel.w));
}

// The BVH walk of traverseTriangles and traverseSpheres ("while-while", Aila
// & Laine 2009): nearer child first, the farther pushed. The node at hand is
// its (index, count) pair alone: a pushed node keeps its pair on the stack,
// so popping fetches nothing. A popped node is not checked against the best
// hit: the next step's box tests against it do that (an interior node's
// children lie in its box), and keeping no distance on the stack costs
// llvmpipe less than the leaves it would spare. One walk at a time uses this
// stack (shading and occlusion rays walk one after another, never one
// inside another). An entry is one word, the index and count packed
// (core::gpu::kStackCountBits, VTKRT_PACKED_STACK_ENTRIES), or two where the
// buffers are too large for it: llvmpipe gathers and scatters each lane's
// word of an indexed array one by one. The C++ twins (core::gpu::stackEntry
// ...) pack alike.
#ifdef VTKRT_PACKED_STACK_ENTRIES
#define StackEntry uint
StackEntry stackEntry(uint index, uint count)
{
  return (index << kStackCountBits) | count;
}
uint entryIndex(StackEntry e) { return e >> kStackCountBits; }
uint entryCount(StackEntry e) { return e & kMaxPackedStackCount; }
#else
#define StackEntry uvec2
StackEntry stackEntry(uint index, uint count)
{
  return uvec2(index, count);
}
uint entryIndex(StackEntry e) { return e.x; }
uint entryCount(StackEntry e) { return e.y; }
#endif
StackEntry bvhStack[VTKRT_STACK_SIZE];

// One interior step: the children of the node at hand are n0 and n1, h0/h1
// say whether the ray meets their boxes, t0/t1 where. index/count become the
// next node. Returns false when the walk is over (a dead end, nothing on the
// stack).
// Branch free (llvmpipe would run every branch, masked): the farther child
// is written above the stack top every step and kept only when both
// children are hit; the top entry is read every step and used only at a
// dead end. sp never exceeds the depth of the node at hand, and the entry
// read is at most one above: VTKRT_STACK_SIZE holds entries 0 to the depth
// of the scene's deepest tree (core::gpu::stackSizeForDepth): no bound check.
bool bvhInteriorStep(Node n0, bool h0, float t0, Node n1, bool h1, float t1, inout int sp,
  inout uint index, inout uint count)
{
  bool nearIs1 = h1 && (!h0 || t1 < t0);
  bvhStack[sp] = nearIs1 ? stackEntry(n0.index, n0.count) : stackEntry(n1.index, n1.count);
  bool anyHit = h0 || h1;
  if (!anyHit && sp == 0)
  {
    return false;
  }
  sp += h0 && h1 ? 1 : 0;
  int top = anyHit ? sp : max(sp - 1, 0);
  StackEntry popped = bvhStack[top];
  sp = top;
  index = anyHit ? (nearIs1 ? n1.index : n0.index) : entryIndex(popped);
  count = anyHit ? (nearIs1 ? n1.count : n0.count) : entryCount(popped);
  return true;
}

// After a leaf: the next node from the stack. Returns false when the stack
// is empty.
bool bvhPopAfterLeaf(inout int sp, inout uint index, inout uint count)
{
  if (sp == 0)
  {
    return false;
  }
  --sp;
  StackEntry popped = bvhStack[sp];
  index = entryIndex(popped);
  count = entryCount(popped);
  return true;
}

// The interior part of the walk that traverseTriangles and traverseSpheres
// share: from the node at hand, descends to the nearer child hit (pushing
// the farther) and pops at dead ends, until the node at hand is a leaf.
// Boxes grow by growBy (screen-sized spheres; 0 otherwise). Returns false
// when the walk is over (nothing left, or the traversal step cap reached).
// A do-while with the step guarded, not a while: llvmpipe runs a loop's
// body once more, fully masked, after every lane has left at its top, so a
// while loop would pay one extra node step per call.
bool bvhDescend(vec3 org, vec3 invDir, vec3 parallelBias, vec3 growBy, float tmin, float tmax,
  inout int sp, inout int steps, inout uint index, inout uint count)
{
  bool walking = true;
  do
  {
    if (count == 0u)
    {
#if VTKRT_MAXIMUM_TRAVERSAL_STEPS > 0
      // The traversal step cap (a speed/accuracy knob): what is not reached
      // within the cap is missed.
      walking = ++steps <= VTKRT_MAXIMUM_TRAVERSAL_STEPS;
#endif
      Node n0 = fetchNode(uNodes, int(index));
      Node n1 = fetchNode(uNodes, int(index) + 1);
      float t0, t1;
      bool h0 = intersectRayBoxConservative(org, invDir, parallelBias, n0.lo - growBy, n0.hi + growBy,
                  tmin, tmax, t0);
      bool h1 = intersectRayBoxConservative(org, invDir, parallelBias, n1.lo - growBy, n1.hi + growBy,
                  tmin, tmax, t1);
      walking = walking && bvhInteriorStep(n0, h0, t0, n1, h1, t1, sp, index, count);
    }
  } while (walking && count == 0u);
  return walking;
}
