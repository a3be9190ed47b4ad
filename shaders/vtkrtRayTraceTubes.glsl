// Lines drawn as round tubes (vtkProperty::RenderLinesAsTubes): each
// segment is the hull of its two end spheres, whose radii come from the
// instance's screenRadiusPlane every frame (LineWidth pixels wide, as VTK
// draws them). Included only in shaders of scenes that have tubes, after
// vtkrtRayTraceSpheres (whose sphere test and buffer the tubes share). The
// C++ twins (core/Capsule.h through core/GpuKernels.h) have the same names.

// core::intersectRayTube, operation for operation: the nearest hit within
// [tmin, tmax] of the two end spheres and the cone tangent to both (the
// body's quadratic after moving the origin to the ray's point nearest the
// segment's middle, its discriminant a difference of two squares).
bool intersectRayTube(vec3 org, vec3 dir, vec3 a, vec3 b, float ra, float rb, float tmin,
  float tmax, out float t)
{
  t = 0.0;
  bool found = false;
  float best = tmax;
  float hit;
  if (intersectRaySphere(org, dir, a, ra, tmin, best, hit))
  {
    best = hit;
    found = true;
  }
  if (intersectRaySphere(org, dir, b, rb, tmin, best, hit))
  {
    best = hit;
    found = true;
  }
  vec3 ba = b - a;
  float m0 = dot(ba, ba);
  float rr = ra - rb;
  float d2 = m0 - rr * rr;
  float dd = dot(dir, dir);
  if (d2 > 0.0 && dd > 0.0)
  {
    float len = sqrt(m0);
    vec3 u = ba / len;
    vec3 mid = a + 0.5 * ba;
    float shift = dot(mid - org, dir) / dd;
    vec3 oa = (org + shift * dir) - a;
    float zo = dot(oa, u);
    float zd = dot(dir, u);
    vec3 po = oa - zo * u;
    vec3 pd = dir - zd * u;
    float c = len / sqrt(d2);
    float slope = c * rr / len;
    float w0 = c * ra - slope * zo;
    float w1 = -slope * zd;
    float qa = dot(pd, pd) - w1 * w1;
    float qb = dot(po, pd) - w0 * w1;
    float qc = dot(po, po) - w0 * w0;
    vec3 e = w0 * pd - w1 * po;
    vec3 x = cross(po, pd);
    float disc = dot(e, e) - dot(x, x);
    if (disc >= 0.0 && qa != 0.0)
    {
      float s = sqrt(disc);
      float q = -(qb + copySign(s, qb));
      float zlo = ra * rr / len;
      float zhi = (d2 + ra * rr) / len;
      vec2 roots = vec2(qc / q, q / qa);
      for (int k = 0; k < 2; ++k)
      {
        float z = zo + roots[k] * zd;
        float tr = shift + roots[k];
        if (z > zlo && z < zhi && tr >= tmin && tr <= best)
        {
          best = tr;
          found = true;
        }
      }
    }
  }
  if (found)
  {
    t = best;
  }
  return found;
}

// core::tubeParameter: the parameter along the segment of the sphere that
// touches the surface at p (the normal is p minus its center).
float tubeParameter(vec3 p, vec3 a, vec3 b, float ra, float rb)
{
  vec3 ba = b - a;
  float rr = ra - rb;
  float d2 = dot(ba, ba) - rr * rr;
  if (!(d2 > 0.0))
  {
    return ra >= rb ? 0.0 : 1.0;
  }
  float s = (dot(p - a, ba) - ra * rr) / d2;
  return min(1.0, max(0.0, s));
}

// A point's tube radius this frame (the radius plane of screen-sized spheres).
float tubeRadius(vec4 radiusPlane, vec3 p)
{
  return max(0.0, dot(radiusPlane.xyz, p) + radiusPlane.w);
}

// Closest hit in the segment BVH whose root node is `root`: the walk of
// traverseSpheres step for step. The BVH is over the bare segments and every
// box grows by `grow`, the largest radius over the instance this frame, so
// the boxes bound the tubes under any camera and a camera move uploads no
// geometry. Leaves count segments; their indices are texels (two each).
bool traverseTubes(int root, vec3 org, vec3 dir, float tmin, inout float tmax, out int segment,
  bool stopAtFirstHit, vec4 radiusPlane, float grow)
{
  segment = -1;
  vec3 invDir = safeInverse(dir);
  vec3 parallelBias = parallelAxisBias(invDir);
  vec3 growBy = vec3(grow);
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
    // A leaf: count >= 1 segments (a do-while: see bvhDescend).
    int i = int(index);
    int last = i + VTKRT_SEGMENT_TEXELS * int(count);
    do
    {
      Segment s = fetchSegment(uSpheres, i);
      float t;
      if (intersectRayTube(org, dir, s.a, s.b, tubeRadius(radiusPlane, s.a),
            tubeRadius(radiusPlane, s.b), tmin, tmax, t))
      {
        tmax = t;
        segment = i;
      }
    } while ((i += VTKRT_SEGMENT_TEXELS) < last);
    if (stopAtFirstHit && segment >= 0)
    {
      return true;
    }
    if (!bvhPopAfterLeaf(sp, index, count))
    {
      break;
    }
  }
  return segment >= 0;
}

// The hit on segment texel `segment` at local point p: the outward local
// normal, the parameter along the segment (for point colors) and its point ids.
vec3 tubeHitNormal(int segment, vec3 p, vec4 radiusPlane, out float s, out uvec2 pointIds)
{
  Segment seg = fetchSegment(uSpheres, segment);
  s = tubeParameter(p, seg.a, seg.b, tubeRadius(radiusPlane, seg.a), tubeRadius(radiusPlane, seg.b));
  pointIds = uvec2(seg.pointId0, seg.pointId1);
  return p - (seg.a + s * (seg.b - seg.a));
}
