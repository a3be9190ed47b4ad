// Analytic spheres: the stable ray/sphere test and closest-hit BVH
// traversal. Included only in shaders of scenes that have spheres.

// Spheres in BVH leaf order, one texel each: (center, radius), center
// relative to the sphere set's center.
uniform usamplerBuffer uSpheres;

// Mirrors core::raySphereRoots (Haines, Guenther & Akenine-Moeller, Ray
// Tracing Gems ch. 7): discriminant a * (r^2 - |f - (b'/a) d|^2), roots
// c / q and q / a. roots.x <= roots.y.
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
  float q = -(bPrime + (bPrime < 0.0 ? -s : s));
  if (q == 0.0)
  {
    return true;
  }
  float t0 = c / q;
  float t1 = q / a;
  roots = vec2(min(t0, t1), max(t0, t1));
  return true;
}

// Mirrors core::intersectRaySphere: the nearest root within [tmin, tmax].
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

// Closest hit in the sphere BVH whose root node is `root`, nearer child
// first, the hit's t pruning what is left on the stack. Organised as
// "while-while" (Aila & Laine 2009): an inner loop descends interior nodes
// until it reaches a leaf (popping past dead ends), and only then are the
// leaf's spheres tested. Pixels are shaded in SIMD groups (llvmpipe: 8 at
// once), so a single loop that does either a node or a leaf per iteration
// pays the masked leaf loop whenever any pixel of the group sits in a leaf;
// here the group descends together and tests leaves together.
//
// Screen-sized spheres (VTKRT_SCREEN_SPHERES, points drawn as spheres) have
// radius 0 in uSpheres: each gets max(0, dot(radiusPlane.xyz, center) +
// radiusPlane.w), this frame's radius, and every box grows by `grow`, a bound
// of that radius over the instance (zero for other sphere sets).
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
  vec3 parallelBias = vec3(equal(invDir, vec3(0.0))) * 3.0e38;
  float tnear;
  uvec4 lo = texelFetch(uNodes, 2 * root);
  uvec4 hi = texelFetch(uNodes, 2 * root + 1);
  if (!intersectRayAABB(
        org, invDir, boxCorner(lo) - vec3(grow), boxCorner(hi) + vec3(grow), tmin, tmax, tnear))
  {
    return false;
  }
  int stackNode[VTKRT_STACK_SIZE];
  float stackNear[VTKRT_STACK_SIZE];
  int sp = 0;
  int steps = 0;
  bool done = false;
  while (!done)
  {
    // Interior nodes: descend to the nearer child hit, push the farther;
    // at a dead end, pop the nearest entry the best hit does not prune.
    while (hi.w == 0u)
    {
#if VTKRT_MAXIMUM_TRAVERSAL_STEPS > 0
      if (++steps > VTKRT_MAXIMUM_TRAVERSAL_STEPS)
      {
        done = true;
        break;
      }
#endif
      int index = int(lo.w);
      uvec4 lo0 = texelFetch(uNodes, 2 * index);
      uvec4 hi0 = texelFetch(uNodes, 2 * index + 1);
      uvec4 lo1 = texelFetch(uNodes, 2 * index + 2);
      uvec4 hi1 = texelFetch(uNodes, 2 * index + 3);
      float t0, t1;
#ifdef VTKRT_SCREEN_SPHERES
      bool h0 = intersectRayBoxConservative(org, invDir, parallelBias, boxCorner(lo0) - vec3(grow),
        boxCorner(hi0) + vec3(grow), tmin, tmax, t0);
      bool h1 = intersectRayBoxConservative(org, invDir, parallelBias, boxCorner(lo1) - vec3(grow),
        boxCorner(hi1) + vec3(grow), tmin, tmax, t1);
#else
      bool h0 = intersectRayBoxConservative(
        org, invDir, parallelBias, boxCorner(lo0), boxCorner(hi0), tmin, tmax, t0);
      bool h1 = intersectRayBoxConservative(
        org, invDir, parallelBias, boxCorner(lo1), boxCorner(hi1), tmin, tmax, t1);
#endif
      if (h0 && h1)
      {
        bool firstNear = t0 <= t1;
        if (sp < VTKRT_STACK_SIZE)
        {
          stackNode[sp] = firstNear ? index + 1 : index;
          stackNear[sp] = firstNear ? t1 : t0;
          ++sp;
        }
        lo = firstNear ? lo0 : lo1;
        hi = firstNear ? hi0 : hi1;
      }
      else if (h0 || h1)
      {
        lo = h0 ? lo0 : lo1;
        hi = h0 ? hi0 : hi1;
      }
      else
      {
        int next = -1;
        while (sp > 0)
        {
          --sp;
          if (stackNear[sp] <= tmax)
          {
            next = stackNode[sp];
            break;
          }
        }
        if (next < 0)
        {
          done = true;
          break;
        }
        lo = texelFetch(uNodes, 2 * next);
        hi = texelFetch(uNodes, 2 * next + 1);
      }
    }
    if (done)
    {
      break;
    }
#if VTKRT_MAXIMUM_TRAVERSAL_STEPS > 0
    if (++steps > VTKRT_MAXIMUM_TRAVERSAL_STEPS)
    {
      break;
    }
#endif
    // A leaf: its spheres [index, index + count).
    int index = int(lo.w);
#ifdef VTKRT_HAS_ELLIPSOIDS
    if (ellipsoids)
    {
      int last = index + 3 * int(hi.w);
      for (int i = index; i < last; i += 3)
      {
        vec4 r0 = uintBitsToFloat(texelFetch(uSpheres, i));
        vec4 r1 = uintBitsToFloat(texelFetch(uSpheres, i + 1));
        vec4 r2 = uintBitsToFloat(texelFetch(uSpheres, i + 2));
        vec3 unitOrg =
          vec3(dot(r0.xyz, org) + r0.w, dot(r1.xyz, org) + r1.w, dot(r2.xyz, org) + r2.w);
        vec3 unitDir = vec3(dot(r0.xyz, dir), dot(r1.xyz, dir), dot(r2.xyz, dir));
        float t;
        if (intersectRaySphere(unitOrg, unitDir, vec3(0.0), 1.0, tmin, tmax, t))
        {
          tmax = t;
          sphere = i;
        }
      }
    }
    int end = ellipsoids ? index : index + int(hi.w);
#else
    int end = index + int(hi.w);
#endif
    for (int i = index; i < end; ++i)
    {
      vec4 s = uintBitsToFloat(texelFetch(uSpheres, i));
#ifdef VTKRT_SCREEN_SPHERES
      s.w += max(0.0, dot(radiusPlane.xyz, s.xyz) + radiusPlane.w);
#endif
      float t;
      if (intersectRaySphere(org, dir, s.xyz, s.w, tmin, tmax, t))
      {
        tmax = t;
        sphere = i;
      }
    }
    if (stopAtFirstHit && sphere >= 0)
    {
      return true;
    }
    int next = -1;
    while (sp > 0)
    {
      --sp;
      if (stackNear[sp] <= tmax)
      {
        next = stackNode[sp];
        break;
      }
    }
    if (next < 0)
    {
      break;
    }
    lo = texelFetch(uNodes, 2 * next);
    hi = texelFetch(uNodes, 2 * next + 1);
  }
  return sphere >= 0;
}
