// vtkrt ray tracing fragment shader: the walks over the scene. Rays visit
// instances (each: clip planes, box, bottom-level BVH), through the
// top-level BVH when the scene has one; the closest hit for camera rays, any
// hit for shadow and occlusion rays.

// Closest hit of the ray with one instance (its clip planes, its
// camera-space box, then its bottom-level BVH) within [tMin, tBest];
// updates the best hit.
void traceInstance(int instance, vec3 org, vec3 dir, vec3 invDir, float tMin, inout float tBest,
  inout int hitInstance, inout int hitPrimitive, inout vec2 hitUV, bool stopAtFirstHit)
{
  vec3 boxMin = instanceBoxMin(instance);
  vec3 boxMax = instanceBoxMax(instance);
  uint flags = instanceFlags(instance);
  float t0 = tMin;
  float t1 = tBest;
#if VTKRT_NUMBER_OF_CLIP_PLANES > 0
  int firstPlane = int(instanceFirstClipPlane(instance));
  int planeCount = int(instanceClipPlaneCount(instance));
  bool clippedAway = false;
  for (int c = 0; c < planeCount; ++c)
  {
    if (!clipRayByPlane(org, dir, uClipPlanes[firstPlane + c], t0, t1))
    {
      clippedAway = true;
    }
  }
  if (clippedAway)
  {
    return;
  }
#endif
#if !defined(VTKRT_TILE_ENTRIES) && !(defined(VTKRT_LEAF_TREES) && !defined(VTKRT_HAS_SPHERES))
  // The branch-free test: it accepts a superset of the boxes the ray
  // meets, which never changes a hit (t0 >= 0 as it needs). Where the
  // walk starts at tested entry boxes, or at the one leaf of every tree,
  // it would only repeat their work.
  float tnear;
  if (!intersectRayBoxConservative(org, invDir, parallelAxisBias(invDir), boxMin, boxMax, t0, t1, tnear))
  {
    return;
  }
#endif
#ifdef VTKRT_SKIPS_FACES
  float tEnd = t1;
#endif
  vec4 r0 = instanceCameraToLocal(instance, 0);
  vec4 r1 = instanceCameraToLocal(instance, 1);
  vec4 r2 = instanceCameraToLocal(instance, 2);
  vec3 localOrg = rowsPoint(r0, r1, r2, org);
  vec3 localDir = rowsDir(r0, r1, r2, dir);
  int root = int(instanceRoot(instance));
#ifdef VTKRT_HAS_WIREFRAME
  beginWireInstance(instance, flags, !stopAtFirstHit, localOrg);
#endif
  int primitive = -1;
  vec2 uv = vec2(0.0);
#if defined(VTKRT_SCREEN_SPHERES) || defined(VTKRT_HAS_TUBES)
  vec4 radiusPlane = instanceScreenRadiusPlane(instance);
  float grow = instanceSphereGrow(instance);
#else
  vec4 radiusPlane = vec4(0.0);
  float grow = 0.0;
#endif
  bool hit = false;
#ifdef VTKRT_HAS_TUBES
  if ((flags & kInstanceTubes) != 0u)
  {
    hit = traverseTubes(root, localOrg, localDir, t0, t1, primitive, stopAtFirstHit, radiusPlane, grow);
  }
  else
#endif
  {
#if defined(VTKRT_HAS_TRIANGLES) && defined(VTKRT_HAS_SPHERES)
    hit = (flags & kInstanceSpheres) != 0u
      ? traverseSpheres(root, localOrg, localDir, t0, t1, primitive, stopAtFirstHit, radiusPlane, grow,
          (flags & kInstanceEllipsoids) != 0u)
      : traverseTriangles(root, localOrg, localDir, t0, t1, primitive, uv, stopAtFirstHit);
#elif defined(VTKRT_HAS_TRIANGLES)
    hit = traverseTriangles(root, localOrg, localDir, t0, t1, primitive, uv, stopAtFirstHit);
#elif defined(VTKRT_HAS_SPHERES)
    hit = traverseSpheres(root, localOrg, localDir, t0, t1, primitive, stopAtFirstHit,
      radiusPlane, grow, (flags & kInstanceEllipsoids) != 0u);
#endif
  }
#ifdef VTKRT_SKIPS_FACES
  if (hit && (flags & kInstanceSpheres) == 0u &&
    faceSkipped(instance, primitive, uv, localDir, flags, !stopAtFirstHit))
  {
    if (stopAtFirstHit)
    {
      // Any hit is not the nearest: walk on from the nearest one.
      t1 = tEnd;
      hit = traverseTriangles(root, localOrg, localDir, t0, t1, primitive, uv, false);
    }
    hit = hit &&
      walkPastSkippedFaces(instance, root, localOrg, localDir, tEnd, t1, primitive, uv, flags, !stopAtFirstHit);
  }
#endif
  if (hit)
  {
    tBest = t1;
    hitInstance = instance;
    hitPrimitive = primitive;
    hitUV = uv;
  }
}

#ifdef VTKRT_HAS_TOP_LEVEL
// Top-level BVH over the instances (Nodes, as every BVH; leaves index
// instance records), boxes relative to an anchor: uCameraToAnchor moves the
// camera-relative ray origin there.
uniform usamplerBuffer uTopNodes;
uniform vec3 uCameraToAnchor;

// The top-level walk's stack: pushed nodes and the distances at which the
// ray enters them (depth <= kMaxDepth < VTKRT_STACK_SIZE, which is
// kMaxStackSize with a top level, core/BVH.h: it never overflows).
int topStackNode[VTKRT_STACK_SIZE];
float topStackNear[VTKRT_STACK_SIZE];

// OrderedWalk::pop: the nearest pushed node the ray may still meet before
// tBest becomes `next`. False when none is left.
bool topLevelPop(inout int sp, float tBest, out int next)
{
  next = 0;
  while (sp > 0)
  {
    --sp;
    if (topStackNear[sp] <= tBest)
    {
      next = topStackNode[sp];
      return true;
    }
  }
  return false;
}

// The walk is core's nearer-first walk (core::detail::OrderedWalk: descend,
// pop) with the node at hand carried as its Node; its C++ twin is
// core::gpu::traceTopLevel (core/GpuTraversal.h). Organised as the bottom
// walks are ("while-while"): interior steps until every ray of the group
// holds a leaf or is done, then the leaves' instances, so that the group
// runs an instance's walk (masked for the rays elsewhere) once a leaf, not
// once a step.
void traceTopLevel(vec3 org, vec3 dir, vec3 invDir, float tMin, inout float tBest,
  inout int hitInstance, inout int hitPrimitive, inout vec2 hitUV, bool stopAtFirstHit)
{
  vec3 anchorOrg = org + uCameraToAnchor;
  float tnear;
  Node node = fetchNode(uTopNodes, 0);
  if (!intersectRayAABB(anchorOrg, invDir, node.lo, node.hi, 0.0, tBest, tnear))
  {
    return;
  }
  int sp = 0;
  int next;
  for (;;)
  {
    // A do-while with the step guarded: see bvhDescend.
    bool walking = true;
    do
    {
      if (node.count == 0u)
      {
        int index = int(node.index);
        Node n0 = fetchNode(uTopNodes, index);
        Node n1 = fetchNode(uTopNodes, index + 1);
        float t0, t1;
        bool h0 = intersectRayAABB(anchorOrg, invDir, n0.lo, n0.hi, 0.0, tBest, t0);
        bool h1 = intersectRayAABB(anchorOrg, invDir, n1.lo, n1.hi, 0.0, tBest, t1);
        // OrderedWalk::descend, or pop at a dead end.
        if (h0 && h1)
        {
          bool firstNear = t0 <= t1;
          topStackNode[sp] = firstNear ? index + 1 : index;
          topStackNear[sp] = firstNear ? t1 : t0;
          ++sp;
          node = firstNear ? n0 : n1;
        }
        else if (h0 || h1)
        {
          node = h0 ? n0 : n1;
        }
        else
        {
          walking = topLevelPop(sp, tBest, next);
          node = walking ? fetchNode(uTopNodes, next) : node;
        }
      }
    } while (walking && node.count == 0u);
    if (!walking)
    {
      break;
    }
    // A leaf: its instances (count >= 1; a do-while: see bvhDescend).
    int index = int(node.index);
    int count = int(node.count);
    int i = index;
    do
    {
      traceInstance(i, org, dir, invDir, tMin, tBest, hitInstance, hitPrimitive, hitUV, stopAtFirstHit);
      if (stopAtFirstHit && hitInstance >= 0)
      {
        return;
      }
    } while (++i < index + count);
    if (!topLevelPop(sp, tBest, next))
    {
      break;
    }
    node = fetchNode(uTopNodes, next);
  }
}
#endif

#if (defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0) && !defined(VTKRT_TRANSLUCENT)
bool anyHit(vec3 org, vec3 dir, float tmax)
{
  vec3 invDir = safeInverse(dir);
  float t = tmax;
  int hitInstance = -1;
  int hitPrimitive = -1;
  vec2 hitUV = vec2(0.0);
#ifdef VTKRT_HAS_TOP_LEVEL
  traceTopLevel(org, dir, invDir, 0.0, t, hitInstance, hitPrimitive, hitUV, true);
#elif defined(VTKRT_SINGLE_INSTANCE)
  traceInstance(0, org, dir, invDir, 0.0, t, hitInstance, hitPrimitive, hitUV, true);
#else
  // Do-whiles (a scene traced has an instance): see bvhDescend.
  int instance = 0;
  do
  {
    traceInstance(instance, org, dir, invDir, 0.0, t, hitInstance, hitPrimitive, hitUV, true);
  } while (++instance < uNumberOfInstances && hitInstance < 0);
#endif
  return hitInstance >= 0;
}
#endif

// Closest hit of a camera ray within [tMin, tBest] over every instance:
// hitInstance stays -1 on a miss.
void traceClosest(vec3 org, vec3 dir, vec3 invDir, float tMin, inout float tBest,
  out int hitInstance, out int hitPrimitive, out vec2 hitUV)
{
  hitInstance = -1;
  hitPrimitive = -1;
  hitUV = vec2(0.0);
#ifdef VTKRT_HAS_TOP_LEVEL
  traceTopLevel(org, dir, invDir, tMin, tBest, hitInstance, hitPrimitive, hitUV, false);
#elif defined(VTKRT_SINGLE_INSTANCE)
  traceInstance(0, org, dir, invDir, tMin, tBest, hitInstance, hitPrimitive, hitUV, false);
#else
  int instance = 0;
  do
  {
    traceInstance(instance, org, dir, invDir, tMin, tBest, hitInstance, hitPrimitive, hitUV, false);
  } while (++instance < uNumberOfInstances);
#endif
}
