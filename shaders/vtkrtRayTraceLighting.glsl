// vtkrt ray tracing fragment shader: VTK's lighting at a hit, with shadow
// and ambient occlusion rays (anyHit, from vtkrtRayTraceTraversal; in
// translucent scenes rayTransmittance, or with interleaved walks the camera
// ray's layer loop).

#if defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
#ifdef VTKRT_INTERLEAVED_WALKS
// With interleaved walks (translucent scenes, GPUs) a hit's visibility rays
// are walked by the camera ray's layer loop (traceTranslucentLayers), at its
// one call of the walk, as a GPU compiler inlines a copy of the walk per
// call: a layer is shaded first to record the rays it casts, then again with
// what they let through.
#if VTKRT_LIGHT_COMPLEXITY == 1
const int kVisibilityRays = VTKRT_AMBIENT_OCCLUSION_SAMPLES + 1;
#elif VTKRT_AMBIENT_OCCLUSION_SAMPLES + VTKRT_NUMBER_OF_LIGHTS > 0
const int kVisibilityRays = VTKRT_AMBIENT_OCCLUSION_SAMPLES + VTKRT_NUMBER_OF_LIGHTS;
#else
const int kVisibilityRays = 1; // none is cast (GLSL has no empty arrays)
#endif

// A visibility ray: the segment org + t dir, t in (0, tmax].
struct VisibilityRay
{
  vec3 org;
  vec3 dir;
  float tmax;
  bool isCast;
};

bool gRecordingVisibilityRays = false;
VisibilityRay gVisibilityRays[kVisibilityRays];
float gVisibility[kVisibilityRays];

// The fraction of light that passes along the hit's visibility ray `ray`:
// recorded to be walked (1 meanwhile), or what the walk found.
float rayVisibility(int ray, vec3 org, vec3 dir, float tmax)
{
  if (gRecordingVisibilityRays)
  {
    gVisibilityRays[ray] = VisibilityRay(org, dir, tmax, true);
    return 1.0;
  }
  return gVisibility[ray];
}
#else
#ifdef VTKRT_TRANSLUCENT
float rayTransmittance(vec3 org, vec3 dir, float tmax); // vtkrtRayTraceTranslucent
#else
// Any hit of a ray from org along dir within (0, tmax] (the core's anyHit).
bool anyHit(vec3 org, vec3 dir, float tmax);
#endif

// The fraction of light that passes from org along dir within (0, tmax]
// (the hit's visibility ray `ray`): 0 or 1, or with translucent surfaces
// the product of what each lets through.
float rayVisibility(int ray, vec3 org, vec3 dir, float tmax)
{
#ifdef VTKRT_TILE_ENTRIES
  // Not a camera ray: its walks start at the root (list 0).
  int cameraList = gTileList;
  gTileList = 0;
#endif
#ifdef VTKRT_TRANSLUCENT
  float visibility = rayTransmittance(org, dir, tmax);
#else
  float visibility = anyHit(org, dir, tmax) ? 0.0 : 1.0;
#endif
#ifdef VTKRT_TILE_ENTRIES
  gTileList = cameraList;
#endif
  return visibility;
}
#endif

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

#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
// uAmbientOcclusionRadius (a frame constant): in world units.
int gSampleIndex = 0; // the pixel's sample (sub-pixel sampling), seeds the rays

uint hashUint(uint x)
{
  // PCG-style integer hash (Jarzynski & Olano 2020).
  uint state = x * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The hemisphere above a hit point (unit geometric normal facing the
// viewer) that its ambient occlusion rays sample: their origin, a frame,
// and the seed of the next ray, deterministic per pixel and sample.
struct OcclusionRays
{
  vec3 origin;
  vec3 tangent;
  vec3 bitangent;
  vec3 normal;
  uint seed;
};

OcclusionRays beginOcclusionRays(vec3 p, vec3 ng)
{
  OcclusionRays o;
  o.origin = offsetRayOrigin(p, ng);
  vec3 helper = abs(ng.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  o.tangent = normalize(cross(helper, ng));
  o.bitangent = cross(ng, o.tangent);
  o.normal = ng;
  o.seed = hashUint(uint(gl_FragCoord.x) + hashUint(uint(gl_FragCoord.y) +
    hashUint(uint(gSampleIndex))));
  return o;
}

// The next cosine-weighted occlusion ray, of length uAmbientOcclusionRadius.
vec3 nextOcclusionRay(inout OcclusionRays o)
{
  o.seed = hashUint(o.seed);
  float u1 = float(o.seed >> 8) / 16777216.0;
  o.seed = hashUint(o.seed);
  float u2 = float(o.seed >> 8) / 16777216.0;
  float r = sqrt(u1);
  float phi = 6.283185307179586 * u2;
  vec3 d = r * cos(phi) * o.tangent + r * sin(phi) * o.bitangent + sqrt(max(0.0, 1.0 - u1)) * o.normal;
  return d * uAmbientOcclusionRadius;
}
#endif

#if VTKRT_LIGHT_COMPLEXITY >= 2 && VTKRT_NUMBER_OF_LIGHTS > 0
// The direction from `light` at p and its attenuation there, as VTK's
// raster lights it (positional lights: distance and cone).
float lightAttenuation(int light, vec3 p, out vec3 lightDirection)
{
  lightDirection = uLightDirection[light];
  float attenuation = 1.0;
#if VTKRT_LIGHT_COMPLEXITY == 3
  if (uLightCone[light].z != 0.0)
  {
    lightDirection = p - uLightPosition[light];
    float distance = length(lightDirection);
    lightDirection = normalize(lightDirection);
    vec3 att = uLightAttenuation[light];
    attenuation = 1.0 / (att.x + att.y * distance + att.z * distance * distance);
    if (uLightCone[light].x < 90.0)
    {
      float coneDot = dot(lightDirection, uLightDirection[light]);
      if (coneDot >= cos(radians(uLightCone[light].x)))
      {
        attenuation = attenuation * pow(coneDot, uLightCone[light].y);
      }
      else
      {
        attenuation = 0.0;
      }
    }
  }
#endif
  return attenuation;
}

// Adds `light`'s diffuse and specular terms at p (normal n) to the sums.
void addLight(int light, vec3 n, vec3 lightDirection, float attenuation, vec3 viewDirection,
  float specularPower, inout vec3 diffuse, inout vec3 specular)
{
  float df = max(0.0, attenuation * dot(n, -lightDirection));
  diffuse += df * uLightColor[light];
#ifdef VTKRT_SPECULAR
  float sf = sign(df) * attenuation *
    pow(max(0.0, dot(reflect(lightDirection, n), viewDirection)), specularPower);
  specular += sf * uLightColor[light];
#endif
}
#endif

#if defined(VTKRT_SHADOWS) && VTKRT_LIGHT_COMPLEXITY > 0 && VTKRT_NUMBER_OF_LIGHTS > 0
// The shadow ray from p toward `light` (lightDirection: from the light):
// a direction, and the end of its segment in units of it.
vec3 shadowRayDirection(int light, vec3 p, vec3 lightDirection, out float tEnd)
{
  tEnd = 1.0e30;
#if VTKRT_LIGHT_COMPLEXITY == 3
  if (uLightCone[light].z != 0.0)
  {
    // Positional lights: the segment to the light (t in (0, 1]).
    tEnd = 1.0;
    return uLightPosition[light] - p;
  }
#endif
  return -lightDirection;
}
#endif

// VTK's vtkOpenGLPolyDataMapper lighting, for the renderer's lighting
// complexity (0: none, 1: headlight, 2: directional lights, 3: positional),
// evaluated in camera-relative world space (a rotation of VTK's view space,
// so every dot product is the same). With shadows a light blocked from p
// contributes nothing; with ambient occlusion the ambient and diffuse terms
// are scaled by the unoccluded fraction of the hemisphere (ng: unit
// geometric normal facing the viewer).
// Every visibility ray of the hit is cast at the loop's one call of
// rayVisibility, because a GPU compiler inlines a copy of the walk per call.
// Without VTKRT_SPECULAR no lit surface has a specular color: its term
// would add nothing, or NaN where pow is undefined.
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
#if VTKRT_LIGHT_COMPLEXITY == 1
  const int kLights = 1;
  float headlight = max(0.0, dot(n, uViewBack));
#else
  const int kLights = VTKRT_NUMBER_OF_LIGHTS;
  vec3 diffuse = vec3(0.0);
  vec3 specular = vec3(0.0);
  vec3 viewDirection = normalize(uEye - p);
#endif
#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
  OcclusionRays occlusion = beginOcclusionRays(p, ng);
  float unoccluded = 0.0;
#endif
  // The occlusion rays first, then the lights.
  for (int ray = 0; ray < VTKRT_AMBIENT_OCCLUSION_SAMPLES + kLights; ++ray)
  {
    int light = ray - VTKRT_AMBIENT_OCCLUSION_SAMPLES;
#if VTKRT_LIGHT_COMPLEXITY >= 2
    vec3 lightDirection = vec3(0.0);
    float attenuation = light >= 0 ? lightAttenuation(light, p, lightDirection) : 0.0;
#endif
#if defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
    bool castRay = false;
    vec3 rayOrigin = p;
    vec3 rayDirection = vec3(0.0);
    float rayEnd = 1.0;
#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
    if (light < 0)
    {
      castRay = true;
      rayOrigin = occlusion.origin;
      rayDirection = nextOcclusionRay(occlusion);
    }
#endif
#ifdef VTKRT_SHADOWS
    if (light >= 0)
    {
#if VTKRT_LIGHT_COMPLEXITY == 1
      vec3 lightDirection = -uViewBack;
      castRay = headlight > 0.0;
#else
      castRay = attenuation > 0.0 && dot(n, -lightDirection) > 0.0;
#endif
      rayDirection = shadowRayDirection(light, p, lightDirection, rayEnd);
      if (castRay)
      {
        rayOrigin = offsetRayOrigin(p, dot(ng, rayDirection) >= 0.0 ? ng : -ng);
      }
    }
#endif
    float visibility = castRay ? rayVisibility(ray, rayOrigin, rayDirection, rayEnd) : 1.0;
#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
    if (light < 0)
    {
      unoccluded += visibility;
      continue;
    }
#endif
#if VTKRT_LIGHT_COMPLEXITY == 1
    headlight *= visibility;
#else
    attenuation *= visibility;
#endif
#endif
#if VTKRT_LIGHT_COMPLEXITY >= 2
    addLight(light, n, lightDirection, attenuation, viewDirection, specularPower, diffuse, specular);
#endif
  }
#if VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
  float ao = unoccluded / float(VTKRT_AMBIENT_OCCLUSION_SAMPLES);
#else
  float ao = 1.0;
#endif
#if VTKRT_LIGHT_COMPLEXITY == 1
  vec3 color = ao * (ambientColor + headlight * diffuseColor * uLightColor[0]);
#ifdef VTKRT_SPECULAR
  float sf = headlight > 0.0 ? pow(headlight, specularPower) : 0.0;
  color += sf * specularColor * uLightColor[0];
#endif
  return color;
#else
  return ao * (ambientColor + diffuse * diffuseColor) + specular * specularColor;
#endif
#endif
}
