// Analytic spheres: the stable ray/sphere test and closest-hit BVH
// traversal. Included only in shaders of scenes that have spheres. The C++
// twins (core/GpuKernels.h, core/GpuTraversal.h) have the same names.

// Spheres in BVH leaf order (fetchSphere), centers relative to the sphere
// set's center; or Ellipsoids (fetchEllipsoid), each read at its first
// texel, as their leaves count texels.
uniform usamplerBuffer uSpheres;

// std::copysign: x's magnitude with y's sign bit (so -0 counts as negative).
float copySign(float x, float y)
{
  return uintBitsToFloat((floatBitsToUint(x) & 0x7fffffffu) | (floatBitsToUint(y) & 0x80000000u));
}

// core::raySphereRoots (Haines, Guenther & Akenine-Moeller, Ray Tracing Gems
// ch. 7), operation for operation: discriminant a * (r^2 - |f - (b'/a) d|^2),
// roots c / q and q / a. roots.x <= roots.y.
bool raySphereRoots(vec3 org, vec3 dir, vec3 center, float radius, out vec2 roots)
{
  roots = vec2(0.0);
  vec3 f = org - center;
  float a = dot(dir, dir);
  float bPrime = dot(f, dir);
  float c = dot(f, f) - radius * radius;
  vec3 l = f - (bPrime / a) * dir;
  float disc = a * (radius * radius - dot(l, l));
  if (!(disc >= 0.0) || !(a > 0.0))
  {
    return false;
  }
  float s = sqrt(disc);
  float q = -(bPrime + copySign(s, bPrime));
  if (q == 0.0)
  {
    return true;
  }
  float t0 = c / q;
  float t1 = q / a;
  roots = t1 < t0 ? vec2(t1, t0) : vec2(t0, t1);
  return true;
}

// core::intersectRaySphere: the nearest root within [tmin, tmax].
bool intersectRaySphere(vec3 org, vec3 dir, vec3 center, float radius, float tmin, float tmax,
  out float t)
{
  t = 0.0;
  vec2 roots;
  if (!raySphereRoots(org, dir, center, radius, roots))
  {
    return false;
  }
  if (roots.x >= tmin && roots.x <= tmax)
  {
    t = roots.x;
    return true;
  }
  if (roots.y >= tmin && roots.y <= tmax)
  {
    t = roots.y;
    return true;
  }
  return false;
}

// Closest hit in the sphere BVH whose root node is `root`: the walk of
// traverseTriangles (bvhInteriorStep, bvhPopAfterLeaf), step for step; only
// the boxes' growth and the leaf test differ.
//
// Screen-sized spheres (VTKRT_SCREEN_SPHERES, points drawn as spheres) have
// radius 0 in uSpheres: each gets max(0, dot(radiusPlane.xyz, center) +
// radiusPlane.w), this frame's radius, and every box grows by `grow`, a bound
// of that radius over the instance (0.0 for other sphere sets, so one form of
// the box test serves both at no cost).
// Ellipsoids (VTKRT_HAS_ELLIPSOIDS, `ellipsoids` set: sphere glyphs scaled
// per component) take three texels each, the rows of the affine map of local
// space onto their unit sphere: the ray is mapped there (t is unchanged by
// an affine map) and meets the unit sphere by the same stable test; `sphere`
// is then the hit's first texel.
bool traverseSpheres(int root, vec3 org, vec3 dir, float tmin, inout float tmax, out int sphere,
  bool stopAtFirstHit, vec4 radiusPlane, float grow, bool ellipsoids)
{
  sphere = -1;
  vec3 invDir = safeInverse(dir);
  vec3 parallelBias = parallelAxisBias(invDir);
  vec3 growBy = vec3(grow);
  // No test of the root's box: traceInstance has tested the instance's
  // box, which bounds it.
  Node rootNode = rootNodeOf(root);
  int sp = 0;
  int steps = 0;
  uint index = rootNode.index;
  uint count = rootNode.count;
  for (;;)
  {
    if (!bvhDescend(org, invDir, parallelBias, growBy, tmin, tmax, sp, steps, index, count))
    {
      break;
    }
#if VTKRT_MAXIMUM_TRAVERSAL_STEPS > 0
    if (++steps > VTKRT_MAXIMUM_TRAVERSAL_STEPS)
    {
      break;
    }
#endif
    // A leaf: its spheres [index, index + count), count >= 1 (do-while
    // loops: see bvhDescend).
    int first = int(index);
#ifdef VTKRT_HAS_ELLIPSOIDS
    if (ellipsoids)
    {
      int last = first + VTKRT_ELLIPSOID_TEXELS * int(count);
      int i = first;
      do
      {
        Ellipsoid e = fetchEllipsoid(uSpheres, i);
        vec3 unitOrg = rowsPoint(e.rows[0], e.rows[1], e.rows[2], org);
        vec3 unitDir = rowsDir(e.rows[0], e.rows[1], e.rows[2], dir);
        float t;
        if (intersectRaySphere(unitOrg, unitDir, vec3(0.0), 1.0, tmin, tmax, t))
        {
          tmax = t;
          sphere = i;
        }
      } while ((i += VTKRT_ELLIPSOID_TEXELS) < last);
    }
    int end = ellipsoids ? first : first + int(count);
#else
    int end = first + int(count);
#endif
    int i = first;
    do
    {
#ifdef VTKRT_HAS_ELLIPSOIDS
      if (i < end) // an ellipsoid leaf has no spheres
#endif
      {
        Sphere s = fetchSphere(uSpheres, i);
#ifdef VTKRT_SCREEN_SPHERES
        s.radius += max(0.0, dot(radiusPlane.xyz, s.center) + radiusPlane.w);
#endif
        float t;
        if (intersectRaySphere(org, dir, s.center, s.radius, tmin, tmax, t))
        {
          tmax = t;
          sphere = i;
        }
      }
    } while (++i < end);
    if (stopAtFirstHit && sphere >= 0)
    {
      return true;
    }
    if (!bvhPopAfterLeaf(sp, index, count))
    {
      break;
    }
  }
  return sphere >= 0;
}
