// Translucent surfaces (VTKRT_TRANSLUCENT), appended after
// vtkrtRayTraceMain only in shaders of scenes with translucent instances:
// camera rays composite every layer they cross front to back, with no layer
// limit (raster's depth peeling is the same sum, capped at its peel count),
// and shadow and occlusion rays let through the product of what each layer
// transmits. The C++ twins (core/GpuTranslucency.h) have the same names.

// Accumulated alpha from which what lies behind adds under 1/1024: the ray stops.
const float kOpaqueAlpha = 1.0 - 1.0 / 1024.0;
// The next layer starts this many float ulps of t past a hit: the triangles
// about a shared edge or vertex, which the watertight test may hit at t a few
// ulps apart, count as one layer (a strict interval above the hit).
const uint kLayerGapUlps = 64u;

// The smallest t of the layer after a hit at t (t >= 0).
float nextLayerTMin(float t)
{
  return max(uintBitsToFloat(floatBitsToUint(t) + kLayerGapUlps), 1.0e-30);
}

// Front-to-back compositing ("under"): the layer (color, alpha) behind what
// is accumulated (premultiplied RGB, alpha) shows through what is left.
void compositeLayer(inout vec4 accumulated, vec3 color, float alpha)
{
  float weight = (1.0 - accumulated.a) * alpha;
  accumulated.rgb += weight * color;
  accumulated.a += weight;
}

#if defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0
// Transmittance below which a secondary ray counts as blocked.
const float kBlockedTransmittance = 1.0 / 1024.0;

float surfaceOpacity(int instance, int primitive, vec2 uv, vec3 dir);

// A visibility ray along dir crosses the layer hit (instance, primitive,
// uv): what it lets through multiplies the transmittance; false, and a
// transmittance of 0, once the ray counts as blocked.
bool crossLayer(inout float transmittance, int instance, int primitive, vec2 uv, vec3 dir)
{
  transmittance *= 1.0 - surfaceOpacity(instance, primitive, uv, dir);
  if (!(transmittance >= kBlockedTransmittance)) // a NaN blocks too
  {
    transmittance = 0.0;
    return false;
  }
  return true;
}
#endif

#ifdef VTKRT_INTERLEAVED_WALKS
// The first of the hit's visibility rays after `ray` that is cast (its
// transmittance walk starts over), or kVisibilityRays when none is left.
int nextVisibilityRay(int ray, out float transmittance, out float tMin)
{
  transmittance = 1.0;
  tMin = 0.0;
  do
  {
    ++ray;
  } while (ray < kVisibilityRays && !gVisibilityRays[ray].isCast);
  return ray;
}

// Takes the visibility ray `ray`'s closest hit from tMin (none:
// hitInstance < 0): true while the ray walks on past it; else its
// visibility is kept and `ray` moves to the next ray cast, if any (true).
bool stepVisibilityRay(inout int ray, inout float transmittance, inout float tMin, float t,
  int hitInstance, int hitPrimitive, vec2 hitUV)
{
  if (hitInstance >= 0 && crossLayer(transmittance, hitInstance, hitPrimitive, hitUV, gVisibilityRays[ray].dir))
  {
    tMin = nextLayerTMin(t);
    return true;
  }
  gVisibility[ray] = transmittance;
  ray = nextVisibilityRay(ray, transmittance, tMin);
  return ray < kVisibilityRays;
}
#endif

// Whether the instance is traced opaque: its hits end the camera ray and
// give the pixel its depth.
bool isOpaqueInstance(int instance)
{
  return (instanceFlags(instance) & kInstanceTranslucent) == 0u;
}

// Every hit of the camera ray in depth order up to tEnd (the far plane, or
// the depth below: vtkrtRayTraceMain), shaded and composited: the
// premultiplied color and, as VTK's translucent pass leaves the opaque depth
// in the depth buffer, the depth of the nearest hit of an opaque instance
// (the far plane if there is none: translucent layers write no depth, even
// where their composite is opaque). Once the composite is opaque, the
// layers behind are walked unshaded, only to find that depth. False when
// the ray hits nothing.
// With interleaved walks, the loop also walks each layer's visibility rays,
// each through every layer it crosses (the product of 1 - alpha): an
// iteration walks one ray at the shader's one call of traceClosest; a layer
// is shaded at one call of shadeHit, first recording its rays, then, once
// the last is walked, with what they let through.
bool traceTranslucentLayers(vec3 org, vec3 dir, vec3 invDir, float tEnd, out vec4 outColor, out float outDepth)
{
  vec4 accumulated = vec4(0.0);
  outDepth = 1.0;
  bool hitAny = false;
  float tMin = 0.0;
  // The camera ray's hit being shaded.
  float tLayer = 1.0;
  int layerInstance = -1;
  int layerPrimitive = -1;
  vec2 layerUV = vec2(0.0);
#ifdef VTKRT_INTERLEAVED_WALKS
  int ray = -1; // the ray walked: -1 the camera ray, else the layer's visibility ray
  float transmittance = 1.0;
#ifdef VTKRT_TILE_ENTRIES
  int cameraList = gTileList;
#endif
#else
  const int ray = -1;
#endif
  bool saturated = false; // the composite is opaque: only the opaque depth is left to find
  for (;;)
  {
    vec3 walkOrg = org;
    vec3 walkDir = dir;
    vec3 walkInvDir = invDir;
    float t = tEnd;
#ifdef VTKRT_INTERLEAVED_WALKS
    if (ray >= 0)
    {
      walkOrg = gVisibilityRays[ray].org;
      walkDir = gVisibilityRays[ray].dir;
      walkInvDir = safeInverse(walkDir);
      t = gVisibilityRays[ray].tmax;
    }
#endif
    int hitInstance;
    int hitPrimitive;
    vec2 hitUV;
    traceClosest(walkOrg, walkDir, walkInvDir, tMin, t, hitInstance, hitPrimitive, hitUV);
#ifdef VTKRT_INTERLEAVED_WALKS
    if (ray >= 0)
    {
      if (stepVisibilityRay(ray, transmittance, tMin, t, hitInstance, hitPrimitive, hitUV))
      {
        continue;
      }
#ifdef VTKRT_TILE_ENTRIES
      gTileList = cameraList;
#endif
    }
#endif
    if (ray < 0)
    {
      if (hitInstance < 0)
      {
        break;
      }
      hitAny = true;
      tLayer = t;
      layerInstance = hitInstance;
      layerPrimitive = hitPrimitive;
      layerUV = hitUV;
      if (saturated)
      {
        if (isOpaqueInstance(layerInstance))
        {
          outDepth = windowDepth(org, dir, tLayer);
          break;
        }
        tMin = nextLayerTMin(tLayer);
        continue;
      }
#ifdef VTKRT_INTERLEAVED_WALKS
      for (int i = 0; i < kVisibilityRays; ++i)
      {
        gVisibilityRays[i].isCast = false;
      }
      gRecordingVisibilityRays = true;
#endif
    }
    vec4 layer = shadeHit(org, dir, tLayer, layerInstance, layerPrimitive, layerUV);
#ifdef VTKRT_INTERLEAVED_WALKS
    if (gRecordingVisibilityRays)
    {
      // The layer's rays are recorded: walk them, then shade it again;
      // without any, what was shaded is the layer's color.
      gRecordingVisibilityRays = false;
      ray = nextVisibilityRay(-1, transmittance, tMin);
      if (ray < kVisibilityRays)
      {
#ifdef VTKRT_TILE_ENTRIES
        gTileList = 0; // not camera rays: their walks start at the root
#endif
        continue;
      }
    }
    ray = -1;
#endif
    compositeLayer(accumulated, layer.rgb, layer.a);
    if (isOpaqueInstance(layerInstance))
    {
      outDepth = windowDepth(org, dir, tLayer);
      break;
    }
    saturated = accumulated.a >= kOpaqueAlpha;
    tMin = nextLayerTMin(tLayer);
  }
#ifdef VTKRT_FLOAT_COLORS
  outColor = accumulated;
#else
  outColor = vec4(min(accumulated.rgb, vec3(1.0)), accumulated.a);
#endif
  return hitAny;
}

#ifdef VTKRT_HAS_COLORS
// The scalar color of a hit of the instance (as shadeHit fetches it), or
// vec4(-1) when the instance has none.
vec4 hitScalarColor(int instance, uint flags, int primitive, vec2 uv)
{
  if ((flags & (kInstancePointColors | kInstanceCellColors)) == 0u)
  {
    return vec4(-1.0);
  }
  int cb = int(instanceColorBase(instance));
#ifdef VTKRT_HAS_SPHERES
  if ((flags & kInstanceSpheres) != 0u)
  {
    uint pointId = fetchPacked(uSphereIds, primitive);
    int id = int((flags & kInstanceCellColors) != 0u ? sphereCellId(instance, flags, primitive, pointId) : pointId);
#ifdef VTKRT_HAS_COLOR_TEXTURE
    if ((flags & kInstanceColorTexture) != 0u)
    {
      return lookupColorTexture(cb, fetchColorCoordinate(cb, id));
    }
#endif
    return fetchColor(cb + id);
  }
#endif
#ifdef VTKRT_HAS_TRIANGLES
  if ((flags & kInstanceCellColors) != 0u)
  {
    return fetchColor(cb + int(fetchTriangle(uTriangles, primitive).cellId));
  }
  uvec3 ids = fetchTriangleVertices(uTriangleVertices, primitive).ids;
  float w0 = 1.0 - uv.x - uv.y;
#ifdef VTKRT_HAS_COLOR_TEXTURE
  if ((flags & kInstanceColorTexture) != 0u)
  {
    vec2 st = w0 * fetchColorCoordinate(cb, int(ids.x)) + uv.x * fetchColorCoordinate(cb, int(ids.y)) +
      uv.y * fetchColorCoordinate(cb, int(ids.z));
    return lookupColorTexture(cb, st);
  }
#endif
  return w0 * fetchColor(cb + int(ids.x)) + uv.x * fetchColor(cb + int(ids.y)) +
    uv.y * fetchColor(cb + int(ids.z));
#else
  return vec4(-1.0);
#endif
}
#endif

// The alpha shadeHit gives the hit (primitive, uv) of the instance by a ray
// along dir (camera-relative), without shading it.
float surfaceOpacity(int instance, int primitive, vec2 uv, vec3 dir)
{
  uint flags = instanceFlags(instance);
  if ((flags & kInstanceTranslucent) == 0u)
  {
    return 1.0;
  }
  float alpha = instanceOpacity(instance);
#ifdef VTKRT_HAS_COLORS
  vec4 scalarColor = hitScalarColor(instance, flags, primitive, uv);
  alpha *= scalarColor.x >= 0.0 ? scalarColor.a : 1.0;
#endif
#ifdef VTKRT_HAS_TEXTURES
  if ((flags & kInstanceTextured) != 0u)
  {
    // Raster's gl_FrontFacing, as shadeHit and faceSkipped decide it.
    vec3 localDir = rowsDir(instanceCameraToLocal(instance, 0), instanceCameraToLocal(instance, 1),
      instanceCameraToLocal(instance, 2), dir);
    Triangle t = fetchTriangle(uTriangles, primitive);
    float facing = dot(cross(t.v1 - t.v0, t.v2 - t.v0), localDir);
    bool front = (flags & kInstanceMirrored) != 0u ? facing >= 0.0 : facing <= 0.0;
    if (front || (flags & kInstanceTextureOnBackface) != 0u)
    {
      alpha *= instanceTextureColor(instance, fetchTriangleVertices(uTriangleVertices, primitive).ids, uv).a;
    }
  }
#endif
  return alpha;
}

#if (defined(VTKRT_SHADOWS) || VTKRT_AMBIENT_OCCLUSION_SAMPLES > 0) && !defined(VTKRT_INTERLEAVED_WALKS)
// The fraction of light passing from org along dir within (0, tmax]: the
// product of (1 - alpha) over every layer, in depth order (each once).
float rayTransmittance(vec3 org, vec3 dir, float tmax)
{
  vec3 invDir = safeInverse(dir);
  float transmittance = 1.0;
  float tMin = 0.0;
  for (;;)
  {
    float t = tmax;
    int hitInstance;
    int hitPrimitive;
    vec2 hitUV;
    traceClosest(org, dir, invDir, tMin, t, hitInstance, hitPrimitive, hitUV);
    if (hitInstance < 0)
    {
      return transmittance;
    }
    if (!crossLayer(transmittance, hitInstance, hitPrimitive, hitUV, dir))
    {
      return 0.0;
    }
    tMin = nextLayerTMin(t);
  }
  return transmittance;
}
#endif
