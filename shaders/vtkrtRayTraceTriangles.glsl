// Triangle meshes: the watertight ray/triangle test and closest-hit BVH
// traversal. Included only in shaders of scenes that have triangles. The C++
// twins (core/GpuKernels.h, core/GpuTraversal.h) have the same names.

// Triangles in BVH leaf order (fetchTriangle): vertices relative to the
// mesh's center, and the VTK cell id.
uniform usamplerBuffer uTriangles;

#ifdef VTKRT_HAS_WIREFRAME
// vtkrtRayTraceEdges: a wireframe's triangles are hit on their wires only.
bool wireWalk();
vec3 wireGrowBy();
float wireReach(float tBest);
bool wireWins(float t, float tBest, bool haveBest, uint cell, uint cellBest);
#endif

// Per-ray data of the watertight test: the axis permutation and shear of
// core::RayTrianglePrecomputed (its constructor is precomputeRayTriangle).
struct RayTrianglePrecomputed
{
  vec3 org;
  int kx;
  int ky;
  int kz;
  float sx;
  float sy;
  float sz;
};

#ifdef VTKRT_HAS_WIREFRAME
bool wireHit(RayTrianglePrecomputed pre, Triangle t, vec3 org, vec3 dir, bool inside, float tmin,
  float tmax, inout vec3 hit);
#endif

RayTrianglePrecomputed precomputeRayTriangle(vec3 org, vec3 dir)
{
  RayTrianglePrecomputed r;
  r.org = org;
  vec3 ad = abs(dir);
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  r.kx = r.kz + 1 == 3 ? 0 : r.kz + 1;
  r.ky = r.kx + 1 == 3 ? 0 : r.kx + 1;
  // Keep the winding independent of the direction sign.
  if (dir[r.kz] < 0.0)
  {
    int tmp = r.kx;
    r.kx = r.ky;
    r.ky = tmp;
  }
  r.sx = dir[r.kx] / dir[r.kz];
  r.sy = dir[r.ky] / dir[r.kz];
  r.sz = 1.0 / dir[r.kz];
  return r;
}

// core::intersectRayTriangle (Woop, Benthin & Wald 2013), operation for
// operation. hit = (t, u, v) with the hit point (1 - u - v) * v0 + u * v1 +
// v * v2. Both windings hit; t must lie in [tmin, tmax]; degenerate
// triangles never hit.
bool intersectRayTriangle(RayTrianglePrecomputed r, vec3 v0, vec3 v1, vec3 v2, float tmin,
  float tmax, out vec3 hit)
{
  vec3 A = v0 - r.org;
  vec3 B = v1 - r.org;
  vec3 C = v2 - r.org;
  float Ax = A[r.kx] - r.sx * A[r.kz];
  float Ay = A[r.ky] - r.sy * A[r.kz];
  float Bx = B[r.kx] - r.sx * B[r.kz];
  float By = B[r.ky] - r.sy * B[r.kz];
  float Cx = C[r.kx] - r.sx * C[r.kz];
  float Cy = C[r.ky] - r.sy * C[r.kz];
  float U = Cx * By - Cy * Bx;
  float V = Ax * Cy - Ay * Cx;
  float W = Bx * Ay - By * Ax;
#ifdef VTKRT_HAS_FP64
  // An edge function that is exactly 0 in float is recomputed in double.
  if (U == 0.0 || V == 0.0 || W == 0.0)
  {
    U = float(double(Cx) * double(By) - double(Cy) * double(Bx));
    V = float(double(Ax) * double(Cy) - double(Ay) * double(Cx));
    W = float(double(Bx) * double(Ay) - double(By) * double(Ax));
  }
#endif
  hit = vec3(0.0);
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0))
  {
    return false;
  }
  float det = U + V + W;
  if (det == 0.0 || isnan(det))
  {
    return false;
  }
  float Az = r.sz * A[r.kz];
  float Bz = r.sz * B[r.kz];
  float Cz = r.sz * C[r.kz];
  float Tsc = U * Az + V * Bz + W * Cz;
  float rcpDet = 1.0 / det;
  float t = Tsc * rcpDet;
  if (!(t >= tmin && t <= tmax))
  {
    return false;
  }
  hit = vec3(t, V * rcpDet, W * rcpDet);
  return true;
}

#ifdef VTKRT_TILE_ENTRIES
// Where the walks of camera rays start: per screen tile, the tree's nodes
// that the tile's rays can reach (core::gpu::TileList and its node ids, four
// a texel); list 0 holds the root alone, for every other ray.
uniform usamplerBuffer uTileEntries;
// uTileGrid (a frame constant): tiles per unit of [0, 1] viewport
// coordinates (xy), tiles in x and y (zw).
// The list of the walks under way: the camera ray's tile (shadeRay), list 0
// while shadow and occlusion rays walk (rayVisibility, or
// traceTranslucentLayers with interleaved walks).
int gTileList = 0;

// The tile list of the camera ray through ndc (core::gpu::tileListOf).
int tileListOf(vec2 ndc)
{
  ivec2 t = clamp(ivec2(floor((ndc * 0.5 + 0.5) * uTileGrid.xy)), ivec2(0), ivec2(uTileGrid.zw) - 1);
  return 1 + t.y * int(uTileGrid.z) + t.x;
}

// core::gpu::bvhStartFromEntries: each entry whose box the ray meets is
// pushed, the nearest last, then the first pop. False when none is met.
bool bvhStartFromEntries(vec3 org, vec3 invDir, vec3 parallelBias, float tmin, float tmax, int list,
  inout int sp, inout uint index, inout uint count)
{
  TileList tile = fetchTileList(uTileEntries, list);
  int e = int(tile.first);
  int end = e + int(tile.count);
  do
  {
    Node n = fetchNode(uNodes, int(fetchPacked(uTileEntries, e)));
    float tnear;
    bool hit = intersectRayBoxConservative(org, invDir, parallelBias, n.lo, n.hi, tmin, tmax, tnear);
    bvhStack[sp] = stackEntry(n.index, n.count);
    sp += hit ? 1 : 0;
  } while (++e < end);
  return bvhPopAfterLeaf(sp, index, count);
}
#endif

// Closest hit in the triangle BVH whose root node is `root`: on a hit, tmax
// becomes the hit distance, tri the triangle's leaf-order index (global) and
// uv its barycentrics. stopAtFirstHit: any hit (core::anyHit) instead, for
// occlusion rays. Nearer child first, the hit's t pruning what is left on
// the stack, organised as "while-while" (Aila & Laine 2009): an inner loop
// descends interior nodes until every ray of the SIMD group (llvmpipe shades
// 8 pixels at once and runs a loop while any of them is in it) sits in a
// leaf or is done, and only then are leaf triangles tested, so the group
// pays the masked leaf loop once for all its rays. The stack walk itself is
// bvhInteriorStep and bvhPopAfterLeaf (vtkrtRayTraceKernels.glsl), shared
// with traverseSpheres. With VTKRT_LEAF_TREES (every triangle tree is one
// leaf) the root's triangles are tested and nothing is walked.
bool traverseTriangles(int root, vec3 org, vec3 dir, float tmin, inout float tmax, out int tri,
  out vec2 uv, bool stopAtFirstHit)
{
  tri = -1;
  uv = vec2(0.0);
  vec3 invDir = safeInverse(dir);
  vec3 parallelBias = parallelAxisBias(invDir);
  RayTrianglePrecomputed pre = precomputeRayTriangle(org, dir);
  int sp = 0;
  int steps = 0;
#ifdef VTKRT_TILE_ENTRIES
  uint index = 0u;
  uint count = 0u;
  if (!bvhStartFromEntries(org, invDir, parallelBias, tmin, tmax, gTileList, sp, index, count))
  {
    return false;
  }
#else
  // No test of the root's box: traceInstance has tested the instance's
  // box, which bounds it.
  Node rootNode = rootNodeOf(root);
  uint index = rootNode.index;
  uint count = rootNode.count;
#endif
#ifdef VTKRT_HAS_WIREFRAME
  uint bestCell = 0u; // the cell of the best wire hit (coincident wires)
#endif
  for (;;)
  {
#ifdef VTKRT_HAS_WIREFRAME
    vec3 growBy = wireGrowBy();
    float reach = wireReach(tmax);
#else
    vec3 growBy = vec3(0.0);
    float reach = tmax;
#endif
#ifndef VTKRT_LEAF_TREES
    if (!bvhDescend(
      org, invDir, parallelBias, growBy, tmin, reach, sp, steps, index, count))
    {
      break;
    }
#if VTKRT_MAXIMUM_TRAVERSAL_STEPS > 0
    if (++steps > VTKRT_MAXIMUM_TRAVERSAL_STEPS)
    {
      break;
    }
#endif
#endif
    // A leaf: its triangles [index, index + count), count >= 1 (a
    // do-while: see bvhDescend).
    int i = int(index);
    int end = i + int(count);
    do
    {
      Triangle triangle = fetchTriangle(uTriangles, i);
      vec3 h;
#ifdef VTKRT_HAS_WIREFRAME
      reach = wireReach(tmax);
      bool hit = intersectRayTriangle(pre, triangle.v0, triangle.v1, triangle.v2, tmin, reach, h);
      if (wireWalk())
      {
        hit = wireHit(pre, triangle, org, dir, hit, tmin, reach, h) &&
          wireWins(h.x, tmax, tri >= 0, triangle.cellId, bestCell);
      }
      bestCell = hit ? triangle.cellId : bestCell;
#else
      bool hit = intersectRayTriangle(pre, triangle.v0, triangle.v1, triangle.v2, tmin, tmax, h);
#endif
      if (hit)
      {
        tmax = h.x;
        tri = i;
        uv = h.yz;
      }
    } while (++i < end);
    if (stopAtFirstHit && tri >= 0)
    {
      return true;
    }
#ifdef VTKRT_LEAF_TREES
    // Every triangle tree is one leaf, the root: no walk.
    break;
#endif
    if (!bvhPopAfterLeaf(sp, index, count))
    {
      break;
    }
  }
  return tri >= 0;
}
