// vtkrt ray tracing fragment shader, main part. The pass prepends the
// #version line, the feature #defines and the kernel chunks
// (vtkrtRayTraceKernels, and vtkrtRayTraceTriangles / vtkrtRayTraceSpheres /
// vtkrtRayTraceTubes only when the scene has such primitives,
// vtkrtRayTraceSurfaces when it has textured or culled triangles,
// vtkrtRayTraceEdges when it has cell edges or wireframes);
// vtkrtRayTraceTranslucent follows it when the scene has translucent
// instances.
//
// Coordinates: everything the shader sees is camera-relative world space
// (world minus the eye position, computed in double on the CPU), so a scene
// far from the origin keeps float precision. The ray of a pixel runs from its
// point on the near plane (t = 0) to its point on the far plane (t = 1),
// both from the inverse of VTK's own composite projection: images line up
// with raster pixel for pixel and the clipping range is honoured exactly.

in vec2 texCoord;
layout(location = 0) out vec4 fragOutput0;

uniform mat4 uClipToCamera; // inverse of uCameraToClip
uniform mat4 uCameraToClip; // VTK's world-to-clip matrix, translated by the eye
uniform vec3 uViewBack;     // unit +z axis of VTK's view coordinates
uniform int uNumberOfInstances;
#ifdef VTKRT_WORLD_COORDINATES
// WORLD precision mode: coordinates are plain float world coordinates and
// the eye is here (the comments' "camera-relative" then reads "world").
uniform vec3 uEye;
#else
const vec3 uEye = vec3(0.0);
#endif

// Per-instance records (core::gpu::InstanceRecord), rewritten every frame
// because their matrices are camera-relative; read a field at a time through
// the accessors instance<Field>(i) and flags kInstance<Name> that the pass
// generates from vtkrt/core/GpuLayout.h.

#ifdef VTKRT_HAS_COLORS
uniform usamplerBuffer uColors; // packed RGBA8, four per texel
#endif
#if defined(VTKRT_HAS_VERTEX_NORMALS) || defined(VTKRT_HAS_CELL_NORMALS)
uniform usamplerBuffer uNormals; // a Normal per point, or per VTK cell
#endif
#ifdef VTKRT_HAS_TRIANGLE_VERTICES
uniform usamplerBuffer uTriangleVertices; // TriangleVertices per triangle
#endif
#ifdef VTKRT_TEXTURE_CUTOUTS
uvec3 triangleVertexIds(int tri)
{
  return fetchTriangleVertices(uTriangleVertices, tri).ids;
}
#endif
#ifdef VTKRT_HAS_SPHERES
uniform usamplerBuffer uSphereIds; // VTK point id per sphere, four per texel
#endif
#if VTKRT_NUMBER_OF_CLIP_PLANES > 0
uniform vec4 uClipPlanes[VTKRT_NUMBER_OF_CLIP_PLANES]; // n.p + d >= 0 is kept
#endif
#if VTKRT_NUMBER_OF_LIGHTS > 0
uniform vec3 uLightColor[VTKRT_NUMBER_OF_LIGHTS];     // diffuse color * intensity
uniform vec3 uLightDirection[VTKRT_NUMBER_OF_LIGHTS]; // unit, from the light
uniform vec3 uLightPosition[VTKRT_NUMBER_OF_LIGHTS];  // camera-relative
uniform vec3 uLightAttenuation[VTKRT_NUMBER_OF_LIGHTS];
uniform vec3 uLightCone[VTKRT_NUMBER_OF_LIGHTS]; // (cone angle, exponent, positional)
#endif

#if defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
// Any hit of a ray from org along dir within (0, tmax] (the core's anyHit).
bool anyHit(vec3 org, vec3 dir, float tmax);

#ifdef VTKRT_TRANSLUCENT
float rayTransmittance(vec3 org, vec3 dir, float tmax); // vtkrtRayTraceTranslucent
#endif

// The fraction of light that passes from org along dir within (0, tmax]:
// 0 or 1, or with translucent surfaces the product of what each lets through.
float rayVisibility(vec3 org, vec3 dir, float tmax)
{
#ifdef VTKRT_TRANSLUCENT
  return rayTransmittance(org, dir, tmax);
#else
  return anyHit(org, dir, tmax) ? 0.0 : 1.0;
#endif
}

// Wächter & Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection" (Ray Tracing Gems, ch. 6): moves a hit point off its
// surface along the unit geometric normal n by a fixed number of float ulps
// (integer arithmetic on the bits, so the offset scales with the point's
// magnitude), or by a tiny absolute amount near the origin.
vec3 offsetRayOrigin(vec3 p, vec3 n)
{
  const float kOrigin = 1.0 / 32.0;
  const float kFloatScale = 1.0 / 65536.0;
  const float kIntScale = 256.0;
  ivec3 offset = ivec3(kIntScale * n);
  vec3 pi = intBitsToFloat(floatBitsToInt(p) +
    ivec3(p.x < 0.0 ? -offset.x : offset.x, p.y < 0.0 ? -offset.y : offset.y,
      p.z < 0.0 ? -offset.z : offset.z));
  return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : pi.x,
    abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : pi.y,
    abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : pi.z);
}
#endif

#ifdef VTKRT_SHADOWS
// 1 when nothing lies between the surface point p (unit geometric normal ng)
// and the light along toLight within tmax, else 0 (hard shadows; translucent
// surfaces in between let their share through).
float lightVisibility(vec3 p, vec3 ng, vec3 toLight, float tmax)
{
  vec3 side = dot(ng, toLight) >= 0.0 ? ng : -ng;
  return rayVisibility(offsetRayOrigin(p, side), toLight, tmax);
}
#endif

#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
uniform float uAmbientOcclusionRadius; // world units
int gSampleIndex = 0; // the pixel's sample (sub-pixel sampling), seeds the rays

uint hashUint(uint x)
{
  // PCG-style integer hash (Jarzynski & Olano 2020).
  uint state = x * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Unoccluded fraction of the hemisphere above p (unit geometric normal ng
// facing the viewer): cosine-weighted rays of length uAmbientOcclusionRadius,
// deterministic per pixel and sample.
float ambientVisibility(vec3 p, vec3 ng)
{
  vec3 org = offsetRayOrigin(p, ng);
  vec3 helper = abs(ng.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 tangent = normalize(cross(helper, ng));
  vec3 bitangent = cross(ng, tangent);
  uint seed = hashUint(uint(gl_FragCoord.x) + hashUint(uint(gl_FragCoord.y) +
    hashUint(uint(gSampleIndex))));
  float unoccluded = 0.0;
  for (int k = 0; k < VTKRT_AMBIENT_OCCLUSION_SAMPLES; ++k)
  {
    seed = hashUint(seed);
    float u1 = float(seed >> 8) / 16777216.0;
    seed = hashUint(seed);
    float u2 = float(seed >> 8) / 16777216.0;
    float r = sqrt(u1);
    float phi = 6.283185307179586 * u2;
    vec3 d = r * cos(phi) * tangent + r * sin(phi) * bitangent + sqrt(max(0.0, 1.0 - u1)) * ng;
    unoccluded += rayVisibility(org, d * uAmbientOcclusionRadius, 1.0);
  }
  return unoccluded / float(VTKRT_AMBIENT_OCCLUSION_SAMPLES);
}
#endif

// VTK's vtkOpenGLPolyDataMapper lighting, for the renderer's lighting
// complexity (0: none, 1: headlight, 2: directional lights, 3: positional),
// evaluated in camera-relative world space (a rotation of VTK's view space,
// so every dot product is the same).
// With shadows, a light blocked from p contributes nothing; with ambient
// occlusion, the ambient and diffuse terms are scaled by the unoccluded
// fraction of the hemisphere (ng: unit geometric normal facing the viewer).
vec3 shadeLikeVTK(vec3 p, vec3 n, vec3 ng, vec3 ambientColor, vec3 diffuseColor,
  vec3 specularColor, float specularPower, bool lit)
{
#if VTKRT_LIGHT_COMPLEXITY == 0 || VTKRT_NUMBER_OF_LIGHTS == 0
  return ambientColor + diffuseColor;
#else
  if (!lit)
  {
    return ambientColor + diffuseColor;
  }
#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
  float ao = ambientVisibility(p, ng);
#else
  float ao = 1.0;
#endif
#if VTKRT_LIGHT_COMPLEXITY == 1
  float df = max(0.0, dot(n, uViewBack));
#ifdef VTKRT_SHADOWS
  if (df > 0.0)
  {
    df *= lightVisibility(p, ng, uViewBack, 1.0e30);
  }
#endif
  float sf = df > 0.0 ? pow(df, specularPower) : 0.0;
  return ao * (ambientColor + df * diffuseColor * uLightColor[0]) +
    sf * specularColor * uLightColor[0];
#else
  vec3 diffuse = vec3(0.0);
  vec3 specular = vec3(0.0);
  vec3 viewDirection = normalize(uEye - p);
  for (int i = 0; i < VTKRT_NUMBER_OF_LIGHTS; ++i)
  {
    vec3 lightDirection = uLightDirection[i];
    float attenuation = 1.0;
#if VTKRT_LIGHT_COMPLEXITY == 3
    if (uLightCone[i].z != 0.0)
    {
      lightDirection = p - uLightPosition[i];
      float distance = length(lightDirection);
      lightDirection = normalize(lightDirection);
      vec3 att = uLightAttenuation[i];
      attenuation = 1.0 / (att.x + att.y * distance + att.z * distance * distance);
      if (uLightCone[i].x < 90.0)
      {
        float coneDot = dot(lightDirection, uLightDirection[i]);
        if (coneDot >= cos(radians(uLightCone[i].x)))
        {
          attenuation = attenuation * pow(coneDot, uLightCone[i].y);
        }
        else
        {
          attenuation = 0.0;
        }
      }
    }
#endif
#ifdef VTKRT_SHADOWS
    if (attenuation > 0.0 && dot(n, -lightDirection) > 0.0)
    {
#if VTKRT_LIGHT_COMPLEXITY == 3
      // Positional lights: the segment to the light (t in (0, 1]).
      attenuation *= uLightCone[i].z != 0.0
        ? lightVisibility(p, ng, uLightPosition[i] - p, 1.0)
        : lightVisibility(p, ng, -lightDirection, 1.0e30);
#else
      attenuation *= lightVisibility(p, ng, -lightDirection, 1.0e30);
#endif
    }
#endif
    float df = max(0.0, attenuation * dot(n, -lightDirection));
    diffuse += df * uLightColor[i];
    float sf = sign(df) * attenuation *
      pow(max(0.0, dot(reflect(lightDirection, n), viewDirection)), specularPower);
    specular += sf * uLightColor[i];
  }
  return ao * (ambientColor + diffuse * diffuseColor) + specular * specularColor;
#endif
#endif
}

#ifdef VTKRT_HAS_COLORS
vec4 fetchColor(int i)
{
  return unpackUnorm4x8(fetchPacked(uColors, i));
}
#endif

#ifdef VTKRT_HAS_COLOR_TEXTURE
// InterpolateScalarsBeforeMapping: at `base` a header (texel offset, width,
// height, coordinate components), the points' texture coordinates, then the
// mapper's color texture (the second row: the NaN color).
vec2 fetchColorCoordinate(int base, int point)
{
  int comps = int(fetchPacked(uColors, base + 3));
  int at = base + 4 + comps * point;
  float t = comps > 1 ? uintBitsToFloat(fetchPacked(uColors, at + 1)) : 0.0;
  return vec2(uintBitsToFloat(fetchPacked(uColors, at)), t);
}

// Sampled as VTK's raster samples it: nearest texel, clamped to the edge.
vec4 lookupColorTexture(int base, vec2 st)
{
  int offset = int(fetchPacked(uColors, base));
  int w = int(fetchPacked(uColors, base + 1));
  int h = int(fetchPacked(uColors, base + 2));
  int x = clamp(int(floor(st.x * float(w))), 0, w - 1);
  int y = clamp(int(floor(st.y * float(h))), 0, h - 1);
  return fetchColor(base + offset + y * w + x);
}
#endif

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
  // The branch-free test: it accepts a superset of the boxes the ray
  // meets, which never changes a hit (t0 >= 0 as it needs).
  float tnear;
  if (!intersectRayBoxConservative(org, invDir, parallelAxisBias(invDir), boxMin, boxMax, t0, t1, tnear))
  {
    return;
  }
#ifdef VTKRT_SKIPS_FACES
  float tEnd = t1;
#endif
  vec4 r0 = instanceCameraToLocal(instance, 0);
  vec4 r1 = instanceCameraToLocal(instance, 1);
  vec4 r2 = instanceCameraToLocal(instance, 2);
  vec3 localOrg = vec3(dot(r0.xyz, org) + r0.w, dot(r1.xyz, org) + r1.w, dot(r2.xyz, org) + r2.w);
  vec3 localDir = vec3(dot(r0.xyz, dir), dot(r1.xyz, dir), dot(r2.xyz, dir));
  int root = int(instanceRoot(instance));
#ifdef VTKRT_HAS_WIREFRAME
  beginWireInstance(instance, flags, !stopAtFirstHit);
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

// The walk is core's nearer-first walk (core::detail::OrderedWalk: descend,
// pop) with the node at hand carried as its Node; its C++ twin is
// core::gpu::traceTopLevel (core/GpuTraversal.h). The stack never overflows
// (depth <= kMaxDepth < VTKRT_STACK_SIZE, which is kMaxStackSize with a top
// level, core/BVH.h).
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
  int stackNode[VTKRT_STACK_SIZE];
  float stackNear[VTKRT_STACK_SIZE];
  int sp = 0;
  for (;;)
  {
    int index = int(node.index);
    int count = int(node.count);
    bool descended = false;
    if (count > 0)
    {
      for (int i = index; i < index + count; ++i)
      {
        traceInstance(i, org, dir, invDir, tMin, tBest, hitInstance, hitPrimitive, hitUV, stopAtFirstHit);
        if (stopAtFirstHit && hitInstance >= 0)
        {
          return;
        }
      }
    }
    else
    {
      Node n0 = fetchNode(uTopNodes, index);
      Node n1 = fetchNode(uTopNodes, index + 1);
      float t0, t1;
      bool h0 = intersectRayAABB(anchorOrg, invDir, n0.lo, n0.hi, 0.0, tBest, t0);
      bool h1 = intersectRayAABB(anchorOrg, invDir, n1.lo, n1.hi, 0.0, tBest, t1);
      // OrderedWalk::descend
      if (h0 && h1)
      {
        bool firstNear = t0 <= t1;
        stackNode[sp] = firstNear ? index + 1 : index;
        stackNear[sp] = firstNear ? t1 : t0;
        ++sp;
        node = firstNear ? n0 : n1;
        descended = true;
      }
      else if (h0 || h1)
      {
        node = h0 ? n0 : n1;
        descended = true;
      }
    }
    if (!descended)
    {
      // OrderedWalk::pop
      bool found = false;
      int next = 0;
      while (sp > 0)
      {
        --sp;
        if (stackNear[sp] <= tBest)
        {
          next = stackNode[sp];
          found = true;
          break;
        }
      }
      if (!found)
      {
        break;
      }
      node = fetchNode(uTopNodes, next);
    }
  }
}
#endif

#if defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
bool anyHit(vec3 org, vec3 dir, float tmax)
{
  vec3 invDir = safeInverse(dir);
  float t = tmax;
  int hitInstance = -1;
  int hitPrimitive = -1;
  vec2 hitUV = vec2(0.0);
#ifdef VTKRT_HAS_TOP_LEVEL
  traceTopLevel(org, dir, invDir, 0.0, t, hitInstance, hitPrimitive, hitUV, true);
#else
  for (int instance = 0; instance < uNumberOfInstances && hitInstance < 0; ++instance)
  {
    traceInstance(instance, org, dir, invDir, 0.0, t, hitInstance, hitPrimitive, hitUV, true);
  }
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
#else
  for (int instance = 0; instance < uNumberOfInstances; ++instance)
  {
    traceInstance(instance, org, dir, invDir, tMin, tBest, hitInstance, hitPrimitive, hitUV, false);
  }
#endif
}

// Raster lines and points lying on a traced surface (VTK's pick outline,
// wireframes, edges) pass the depth test as they do over raster's own
// triangles: the traced depth is pushed back by a few steps of a 24-bit depth
// buffer, more than the float error of the hit's depth.
const float kCoincidentDepthBias = 16.0 / 16777216.0;

// The window depth of the camera-relative point p.
float windowDepth(vec3 p)
{
  vec4 clip = uCameraToClip * vec4(p, 1.0);
  return clamp(0.5 * (clip.z / clip.w) + 0.5 + kCoincidentDepthBias, 0.0, 1.0);
}

// The color of the hit (tBest, hitInstance, hitPrimitive, hitUV) of the
// camera ray org + t dir: lit RGB and its alpha (1 unless the instance is
// translucent), or the encoded id in id mode.
vec4 shadeHit(vec3 org, vec3 dir, float tBest, int hitInstance, int hitPrimitive, vec2 hitUV)
{
  vec4 outColor = vec4(0.0);
  vec3 p = org + tBest * dir;
  vec4 r0 = instanceCameraToLocal(hitInstance, 0);
  vec4 r1 = instanceCameraToLocal(hitInstance, 1);
  vec4 r2 = instanceCameraToLocal(hitInstance, 2);
  uint flags = instanceFlags(hitInstance);

  // Local normals map to camera space by the transpose of the camera-to-local
  // matrix (the inverse transpose of local-to-camera).
  vec3 localNormal = vec3(0.0, 0.0, 1.0);
  vec3 geometricNormal = vec3(0.0, 0.0, 1.0);
  uint vtkId = 0u;
  vec4 scalarColor = vec4(-1.0);
#ifdef VTKRT_HAS_TEXTURES
  uvec3 textureIds = uvec3(0u);
#endif
  float mirror = (flags & kInstanceMirrored) != 0u ? -1.0 : 1.0;
#ifdef VTKRT_HAS_SPHERES
  if ((flags & kInstanceSpheres) != 0u)
  {
    vec3 localOrg = vec3(dot(r0.xyz, org) + r0.w, dot(r1.xyz, org) + r1.w, dot(r2.xyz, org) + r2.w);
    vec3 localDir = vec3(dot(r0.xyz, dir), dot(r1.xyz, dir), dot(r2.xyz, dir));
    localNormal = localOrg + tBest * localDir - fetchSphere(uSpheres, hitPrimitive).center;
#ifdef VTKRT_HAS_TUBES
    // Tubes: the normal from the sphere touching the hit; point colors
    // interpolated along the segment, cell colors by its cell.
    float tubeS = 0.0;
    uvec2 tubePointIds = uvec2(0u);
    if ((flags & kInstanceTubes) != 0u)
    {
      localNormal = tubeHitNormal(hitPrimitive, localOrg + tBest * localDir,
        instanceScreenRadiusPlane(hitInstance), tubeS, tubePointIds);
    }
#endif
#ifdef VTKRT_HAS_ELLIPSOIDS
    if ((flags & kInstanceEllipsoids) != 0u)
    {
      // The gradient of |A p + b|^2: A^T (A p + b), rows of [A | b] (the
      // first row's texel is the one read as a sphere above).
      Ellipsoid e = fetchEllipsoid(uSpheres, hitPrimitive);
      vec4 e0 = e.rows[0];
      vec4 e1 = e.rows[1];
      vec4 e2 = e.rows[2];
      vec3 hitLocal = localOrg + tBest * localDir;
      vec3 u = vec3(dot(e0.xyz, hitLocal) + e0.w, dot(e1.xyz, hitLocal) + e1.w,
        dot(e2.xyz, hitLocal) + e2.w);
      localNormal = u.x * e0.xyz + u.y * e1.xyz + u.z * e2.xyz;
    }
#endif
    geometricNormal = localNormal;
    mirror = 1.0;
    vtkId = fetchPacked(uSphereIds, hitPrimitive);
#ifdef VTKRT_HAS_COLORS
    if ((flags & (kInstancePointColors | kInstanceCellColors)) != 0u)
    {
      int cb = int(instanceColorBase(hitInstance));
#ifdef VTKRT_HAS_TUBES
      if ((flags & (kInstanceTubes | kInstancePointColors)) == (kInstanceTubes | kInstancePointColors))
      {
        int i0 = int(tubePointIds.x);
        int i1 = int(tubePointIds.y);
#ifdef VTKRT_HAS_COLOR_TEXTURE
        if ((flags & kInstanceColorTexture) != 0u)
        {
          scalarColor = lookupColorTexture(cb,
            mix(fetchColorCoordinate(cb, i0), fetchColorCoordinate(cb, i1), tubeS));
        }
        else
#endif
        {
          scalarColor = mix(fetchColor(cb + i0), fetchColor(cb + i1), tubeS);
        }
      }
      else
#endif
#ifdef VTKRT_HAS_COLOR_TEXTURE
      if ((flags & kInstanceColorTexture) != 0u)
      {
        scalarColor = lookupColorTexture(cb, fetchColorCoordinate(cb, int(vtkId)));
      }
      else
#endif
      {
        scalarColor = fetchColor(cb + int(vtkId));
      }
    }
#endif
  }
#endif
#ifdef VTKRT_HAS_TRIANGLES
  if ((flags & kInstanceSpheres) == 0u)
  {
    Triangle triangle = fetchTriangle(uTriangles, hitPrimitive);
    geometricNormal = cross(triangle.v1 - triangle.v0, triangle.v2 - triangle.v0);
    localNormal = geometricNormal;
    vtkId = triangle.cellId;
    float w0 = 1.0 - hitUV.x - hitUV.y;
#ifdef VTKRT_HAS_TRIANGLE_VERTICES
    if ((flags & (kInstanceVertexNormals | kInstancePointColors | kInstanceTextured)) != 0u)
    {
      uvec3 ids = fetchTriangleVertices(uTriangleVertices, hitPrimitive).ids;
#ifdef VTKRT_HAS_TEXTURES
      textureIds = ids;
#endif
      int i0 = int(ids.x);
      int i1 = int(ids.y);
      int i2 = int(ids.z);
#ifdef VTKRT_HAS_VERTEX_NORMALS
      if ((flags & kInstanceVertexNormals) != 0u)
      {
        int nb = int(instanceNormalBase(hitInstance));
        localNormal = w0 * fetchNormal(uNormals, nb + i0).direction +
          hitUV.x * fetchNormal(uNormals, nb + i1).direction +
          hitUV.y * fetchNormal(uNormals, nb + i2).direction;
      }
#endif
#ifdef VTKRT_HAS_COLORS
      if ((flags & kInstancePointColors) != 0u)
      {
        int cb = int(instanceColorBase(hitInstance));
#ifdef VTKRT_HAS_COLOR_TEXTURE
        if ((flags & kInstanceColorTexture) != 0u)
        {
          vec2 st = w0 * fetchColorCoordinate(cb, i0) + hitUV.x * fetchColorCoordinate(cb, i1) +
            hitUV.y * fetchColorCoordinate(cb, i2);
          scalarColor = lookupColorTexture(cb, st);
        }
        else
#endif
        {
          scalarColor = w0 * fetchColor(cb + i0) + hitUV.x * fetchColor(cb + i1) +
            hitUV.y * fetchColor(cb + i2);
        }
      }
#endif
    }
#endif
#ifdef VTKRT_HAS_CELL_NORMALS
    if ((flags & kInstanceCellNormals) != 0u)
    {
      // One normal per VTK cell, over all of its triangles (as raster).
      int nb = int(instanceNormalBase(hitInstance));
      localNormal = fetchNormal(uNormals, nb + int(vtkId)).direction;
    }
#endif
#ifdef VTKRT_HAS_COLORS
    if ((flags & kInstanceCellColors) != 0u)
    {
      scalarColor = fetchColor(int(instanceColorBase(hitInstance)) + int(vtkId));
    }
#endif
  }
#endif

#if defined(VTKRT_SELECT_IDS)
  // Hardware selection (floats, exact below 2^24): prop index + 1, the VTK
  // cell (or point, for spheres) id's low 24 and high bits, composite index.
  outColor = vec4(float(instancePropIndex(hitInstance) + 1u), float(vtkId & 0xFFFFFFu),
    float(vtkId >> 24u), float(instanceCompositeIndex(hitInstance)));
#elif defined(VTKRT_ID_MODE)
  // RGB: the VTK cell (or point, for spheres) id, 24 bits; A: prop index + 1.
  uint prop = instancePropIndex(hitInstance) + 1u;
  outColor = vec4(float(vtkId & 255u), float((vtkId >> 8) & 255u),
                float((vtkId >> 16) & 255u), float(prop & 255u)) / 255.0;
#else
  mat3 cameraToLocal = mat3(r0.xyz, r1.xyz, r2.xyz); // columns = rows of the matrix
  vec3 n = normalize(cameraToLocal * localNormal);
  vec3 ng = mirror * (cameraToLocal * geometricNormal);
  if ((flags & (kInstanceVertexNormals | kInstanceCellNormals)) != 0u)
  {
    // VTK flips point and cell normals on back-facing triangles.
    if (dot(ng, dir) > 0.0)
    {
      n = -n;
    }
  }
  else if (dot(n, dir) > 0.0)
  {
    // Spheres, and VTK's derivative normal where there are no normals, face
    // the eye (the ray), not just the view plane.
    n = -n;
  }

  vec3 ambientColor = instanceAmbient(hitInstance);
  vec3 diffuseColor = instanceDiffuse(hitInstance);
  vec3 specularColor = instanceSpecular(hitInstance);
  float specularPower = instanceSpecularPower(hitInstance);
  if (scalarColor.x >= 0.0)
  {
    ambientColor = instanceAmbientIntensity(hitInstance) * scalarColor.rgb;
    diffuseColor = instanceDiffuseIntensity(hitInstance) * scalarColor.rgb;
  }
#if defined(VTKRT_BACKFACE_PROPERTIES) || defined(VTKRT_HAS_TEXTURES)
  // Raster's gl_FrontFacing: the ray meets the side its winding faces.
  bool frontFacing = dot(ng, dir) <= 0.0;
#endif
#ifdef VTKRT_BACKFACE_PROPERTIES
  // As vtkOpenGLPolyDataMapper: the BackfaceProperty's colors on back faces
  // of actors without scalar colors.
  if (!frontFacing && (flags & kInstanceBackfaceProperty) != 0u && scalarColor.x < 0.0)
  {
    ambientColor = instanceBackAmbient(hitInstance);
    diffuseColor = instanceBackDiffuse(hitInstance);
    specularColor = instanceBackSpecular(hitInstance);
    specularPower = instanceBackSpecularPower(hitInstance);
  }
#endif
#if defined(VTKRT_SURFACE_EDGES) || defined(VTKRT_HAS_WIREFRAME)
  vec3 localHit = vec3(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
#endif
#ifdef VTKRT_SURFACE_EDGES
  if ((flags & kInstanceSurfaceEdges) != 0u)
  {
    // As vtkOpenGLPolyDataMapper: on an edge the edge color replaces the
    // ambient color and the diffuse color fades out.
    float edgeMix = instanceSurfaceEdgeMix(hitInstance, fetchTriangle(uTriangles, hitPrimitive), localHit);
    diffuseColor = mix(diffuseColor, vec3(0.0), edgeMix);
    ambientColor = mix(ambientColor, instanceEdgeColor(hitInstance), edgeMix);
  }
#endif
#ifdef VTKRT_HAS_WIREFRAME
  if ((flags & kInstanceWireframe) != 0u)
  {
    // Lines are front facing: normals are never flipped; without any, VTK's
    // line normal.
    n = (flags & (kInstanceVertexNormals | kInstanceCellNormals)) != 0u
      ? normalize(cameraToLocal * localNormal)
      : wireNormal(hitInstance, fetchTriangle(uTriangles, hitPrimitive), localHit, uViewBack);
  }
#endif
  // Unit geometric normal on the viewer's side (secondary ray offsets).
  vec3 ngView = normalize(ng);
  if (dot(ngView, dir) > 0.0)
  {
    ngView = -ngView;
  }
  vec3 color = shadeLikeVTK(p, n, ngView, ambientColor, diffuseColor, specularColor, specularPower,
    (flags & kInstanceLit) != 0u);
  float alpha = 1.0;
#ifdef VTKRT_TRANSLUCENT
  // As vtkOpenGLPolyDataMapper: the property's opacity times the scalar
  // color's alpha (times the texel's, below).
  if ((flags & kInstanceTranslucent) != 0u)
  {
    alpha = instanceOpacity(hitInstance) * (scalarColor.x >= 0.0 ? scalarColor.a : 1.0);
  }
#endif
#ifdef VTKRT_HAS_TEXTURES
  // As vtkOpenGLPolyDataMapper: the lit color times the texture's, on back
  // faces too unless ShowTexturesOnBackface is off.
  if ((flags & kInstanceTextured) != 0u && (frontFacing || (flags & kInstanceTextureOnBackface) != 0u))
  {
    vec4 texel = instanceTextureColor(hitInstance, textureIds, hitUV);
    color *= texel.rgb;
#ifdef VTKRT_TRANSLUCENT
    alpha *= (flags & kInstanceTranslucent) != 0u ? texel.a : 1.0;
#endif
  }
#endif
#ifdef VTKRT_TRANSLUCENT
  // A translucent layer is not clamped before blending, as raster's depth
  // peeling blends its float layers (the composite is clamped).
  if ((flags & kInstanceTranslucent) != 0u)
  {
    return vec4(max(color, 0.0), alpha);
  }
#endif
  outColor = vec4(clamp(color, 0.0, 1.0), alpha);
#endif
  return outColor;
}

#ifdef VTKRT_TRANSLUCENT
// Every layer along the camera ray, composited (vtkrtRayTraceTranslucent).
bool traceTranslucentLayers(vec3 org, vec3 dir, vec3 invDir, out vec4 outColor, out float outDepth);
#endif

// Traces and shades the ray through a point of the viewport (normalized
// device coordinates): false on a miss, else the shaded color (the encoded
// id in id mode; premultiplied by its alpha) and the window depth.
bool shadeRay(vec2 ndc, out vec4 outColor, out float outDepth)
{
  outColor = vec4(0.0);
  outDepth = 1.0;
  vec4 nearPoint = uClipToCamera * vec4(ndc, -1.0, 1.0);
  vec4 farPoint = uClipToCamera * vec4(ndc, 1.0, 1.0);
  vec3 org = nearPoint.xyz / nearPoint.w;
  vec3 dir = farPoint.xyz / farPoint.w - org;
  vec3 invDir = safeInverse(dir);
#ifdef VTKRT_TRANSLUCENT
  return traceTranslucentLayers(org, dir, invDir, outColor, outDepth);
#else
  float tBest = 1.0;
  int hitInstance;
  int hitPrimitive;
  vec2 hitUV;
  traceClosest(org, dir, invDir, 0.0, tBest, hitInstance, hitPrimitive, hitUV);
  if (hitInstance < 0)
  {
    return false;
  }
  outDepth = windowDepth(org + tBest * dir);
  outColor = shadeHit(org, dir, tBest, hitInstance, hitPrimitive, hitUV);
  return true;
#endif
}

#ifdef VTKRT_SAMPLES_PER_PIXEL
// Jittered sub-pixel sampling: VTKRT_SAMPLES_PER_PIXEL rays per pixel, the
// k-th at the R2 low-discrepancy point k of the pixel square (point 0 is the
// pixel center), k counting on from uFirstSample so successive accumulated
// frames continue one sequence. The output is the sum of the hits' colors in
// RGB (premultiplied) and the number of hits in A (their alphas' sum) (added into the pass's float accumulation
// buffer); the depth is the nearest hit's.
uniform int uFirstSample;
uniform vec2 uPixelSize; // one pixel in normalized device coordinates

vec2 samplePoint(int k)
{
  // R2 (Roberts 2018): fract(0.5 + k / (g, g^2)), g the plastic number, in
  // 0.32 fixed point (uint arithmetic wraps like fract, exactly, for any k).
  const uvec2 alpha = uvec2(3242174889u, 2447445414u);
  uvec2 q = uvec2(0x80000000u) + uint(k) * alpha;
  return vec2(q >> 8u) * (1.0 / 16777216.0);
}

void main()
{
  vec2 pixelCorner = texCoord * 2.0 - 1.0 - 0.5 * uPixelSize;
  vec3 sum = vec3(0.0);
  float hits = 0.0;
  float nearest = 1.0;
  for (int s = 0; s < VTKRT_SAMPLES_PER_PIXEL; ++s)
  {
    vec4 color;
    float depth;
#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
    gSampleIndex = uFirstSample + s;
#endif
    if (shadeRay(pixelCorner + samplePoint(uFirstSample + s) * uPixelSize, color, depth))
    {
      sum += color.rgb;
      hits += color.a;
      nearest = min(nearest, depth);
    }
  }
  if (hits == 0.0)
  {
    discard;
  }
  fragOutput0 = vec4(sum, hits);
  gl_FragDepth = nearest;
}
#else
void main()
{
  vec4 color;
  float depth;
  if (!shadeRay(texCoord * 2.0 - 1.0, color, depth))
  {
#ifdef VTKRT_ID_MODE
    fragOutput0 = vec4(0.0);
    gl_FragDepth = 1.0;
    return;
#else
    discard;
#endif
  }
  fragOutput0 = color;
  gl_FragDepth = depth;
}
#endif
