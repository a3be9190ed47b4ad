// vtkrt GLSL kernels shared by every ray-traced scene: the robust ray/AABB
// slab test and ray/plane clipping. Each function mirrors the core function
// of the same name (plugin/core/vtkrt/core/Ray.h, Plane.h) operation for
// operation, so the CPU (double) and the GPU (float) agree on what is hit.

// Ize 2013: the far distance is scaled by 1 + 2*gamma(3) so rounding never
// culls a box the ray touches. gamma(3) = 3u/(1-3u), u = 2^-24.
const float kFarScale = 1.0 + 2.0 * (3.0 * 5.9604645e-8) / (1.0 - 3.0 * 5.9604645e-8);

// Zero direction component maps to +inf, as core::RayBoxPrecomputed does.
vec3 safeInverse(vec3 d)
{
  const float inf = uintBitsToFloat(0x7f800000u);
  return vec3(d.x == 0.0 ? inf : 1.0 / d.x, d.y == 0.0 ? inf : 1.0 / d.y,
    d.z == 0.0 ? inf : 1.0 / d.z);
}

// Mirrors core::intersectRayAABB: NaN (origin on a slab plane with a zero
// direction component) leaves the interval unchanged, i.e. counts as hit.
bool intersectRayAABB(vec3 org, vec3 invDir, vec3 bmin, vec3 bmax, float tmin, float tmax,
  out float tnear)
{
  vec3 t0 = (bmin - org) * invDir;
  vec3 t1 = (bmax - org) * invDir;
  vec3 tlo = min(t0, t1);
  vec3 thi = max(t0, t1) * kFarScale;
  tmin = tlo.x > tmin ? tlo.x : tmin;
  tmax = thi.x < tmax ? thi.x : tmax;
  tmin = tlo.y > tmin ? tlo.y : tmin;
  tmax = thi.y < tmax ? thi.y : tmax;
  tmin = tlo.z > tmin ? tlo.z : tmin;
  tmax = thi.z < tmax ? thi.z : tmax;
  tnear = tmin;
  return tmin <= tmax && !isinf(tmin);
}

// Mirrors core::intersectRayPlane for a plane n.p + d = 0, used to clip the
// ray's [tmin, tmax] to the half-space n.p + d >= 0 (what VTK keeps).
// Returns false when nothing of the interval survives.
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
// integers are), float fields are uintBitsToFloat of their bits.

// Node i of the flattened BVH: two texels, lo = (min, index), hi = (max,
// count) (the core's layout: floats stored as bits); count == 0: interior
// with children index and index + 1; count > 0: leaf over primitives
// [index, index + count).
uniform usamplerBuffer uNodes;

vec3 boxCorner(uvec4 texel)
{
  return uintBitsToFloat(texel.xyz);
}

// Four 32-bit values packed per texel (ids and RGBA8 colors).
uint fetchPacked(usamplerBuffer buffer, int i)
{
  uvec4 texel = texelFetch(buffer, i >> 2);
  int c = i & 3;
  return c == 0 ? texel.x : (c == 1 ? texel.y : (c == 2 ? texel.z : texel.w));
}
