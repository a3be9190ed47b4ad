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

// Closest hit in the sphere BVH whose root node is `root`; see
// traverseTriangles.
bool traverseSpheres(int root, vec3 org, vec3 dir, float tmin, inout float tmax, out int sphere,
  bool stopAtFirstHit)
{
  sphere = -1;
  vec3 invDir = safeInverse(dir);
  float tnear;
  uvec4 rootLo = texelFetch(uNodes, 2 * root);
  uvec4 rootHi = texelFetch(uNodes, 2 * root + 1);
  if (!intersectRayAABB(org, invDir, boxCorner(rootLo), boxCorner(rootHi), tmin, tmax, tnear))
  {
    return false;
  }
  int stackNode[VTKRT_STACK_SIZE];
  float stackNear[VTKRT_STACK_SIZE];
  int sp = 0;
  int steps = 0;
  int node = root;
  uvec4 lo = rootLo;
  uvec4 hi = rootHi;
  for (;;)
  {
#if VTKRT_MAXIMUM_TRAVERSAL_STEPS > 0
    if (++steps > VTKRT_MAXIMUM_TRAVERSAL_STEPS)
    {
      break;
    }
#endif
    int index = int(lo.w);
    int count = int(hi.w);
    bool descended = false;
    if (count > 0)
    {
      for (int i = index; i < index + count; ++i)
      {
        vec4 s = uintBitsToFloat(texelFetch(uSpheres, i));
        float t;
        if (intersectRaySphere(org, dir, s.xyz, s.w, tmin, tmax, t))
        {
          tmax = t;
          sphere = i;
          if (stopAtFirstHit)
          {
            return true;
          }
        }
      }
    }
    else
    {
      uvec4 lo0 = texelFetch(uNodes, 2 * index);
      uvec4 hi0 = texelFetch(uNodes, 2 * index + 1);
      uvec4 lo1 = texelFetch(uNodes, 2 * index + 2);
      uvec4 hi1 = texelFetch(uNodes, 2 * index + 3);
      float t0, t1;
      bool h0 = intersectRayAABB(org, invDir, boxCorner(lo0), boxCorner(hi0), tmin, tmax, t0);
      bool h1 = intersectRayAABB(org, invDir, boxCorner(lo1), boxCorner(hi1), tmin, tmax, t1);
      if (h0 && h1)
      {
        bool firstNear = t0 <= t1;
        if (sp < VTKRT_STACK_SIZE)
        {
          stackNode[sp] = firstNear ? index + 1 : index;
          stackNear[sp] = firstNear ? t1 : t0;
          ++sp;
        }
        node = firstNear ? index : index + 1;
        lo = firstNear ? lo0 : lo1;
        hi = firstNear ? hi0 : hi1;
        descended = true;
      }
      else if (h0 || h1)
      {
        node = h0 ? index : index + 1;
        lo = h0 ? lo0 : lo1;
        hi = h0 ? hi0 : hi1;
        descended = true;
      }
    }
    if (!descended)
    {
      bool found = false;
      while (sp > 0)
      {
        --sp;
        if (stackNear[sp] <= tmax)
        {
          node = stackNode[sp];
          found = true;
          break;
        }
      }
      if (!found)
      {
        break;
      }
      lo = texelFetch(uNodes, 2 * node);
      hi = texelFetch(uNodes, 2 * node + 1);
    }
  }
  return sphere >= 0;
}
