// vtkrt ray tracing fragment shader, main part: a camera ray per pixel (or
// per sample), its window depth, the fragment's outputs. The pass assembles
// the shader (vtkRayTraceShader.cxx) from the #version line, the feature
// #defines, the kernel chunks (vtkrtRayTraceKernels, and
// vtkrtRayTraceTriangles / vtkrtRayTraceSpheres / vtkrtRayTraceTubes only
// when the scene has such primitives, vtkrtRayTraceSurfaces when it has
// textured or culled triangles, vtkrtRayTraceEdges when it has cell edges or
// wireframes), then vtkrtRayTraceInputs, vtkrtRayTraceLighting,
// vtkrtRayTraceTraversal, vtkrtRayTraceShading and this chunk;
// vtkrtRayTraceTranslucent follows it when the scene has translucent
// instances.
//
// Coordinates: everything the shader sees is camera-relative world space
// (world minus the eye position, computed in double on the CPU), so a scene
// far from the origin keeps float precision. The ray of a pixel runs from its
// point on the near plane (t = 0) to its point on the far plane (t = 1),
// both from the inverse of VTK's own composite projection: images line up
// with raster pixel for pixel and the clipping range is honoured exactly.
// For VTK's cameras both points are affine in the pixel, so the CPU
// unprojects three rays per frame and the shader combines them; an explicit
// projective matrix gets the per-pixel unprojection (VTKRT_PROJECTIVE_RAYS).

// Raster lines and points lying on a traced surface (VTK's pick outline,
// wireframes, edges) pass the depth test as they do over raster's own
// triangles: the traced depth is pushed back by a few steps of a 24-bit depth
// buffer, more than the float error of the hit's depth.
const float kCoincidentDepthBias = 16.0 / 16777216.0;

// The window depth of the camera ray's point at t.
float windowDepth(vec3 org, vec3 dir, float t)
{
#ifdef VTKRT_PROJECTIVE_RAYS
  vec4 clip = uCameraToClip * vec4(org + t * dir, 1.0);
  float ndcDepth = clip.z / clip.w;
#else
  float ndcDepth = affineRayDepth(uRayDepth, t);
#endif
  return clamp(0.5 * ndcDepth + 0.5 + kCoincidentDepthBias, 0.0, 1.0);
}

#ifdef VTKRT_TRANSLUCENT
// Every layer along the camera ray up to tEnd, composited
// (vtkrtRayTraceTranslucent).
bool traceTranslucentLayers(vec3 org, vec3 dir, vec3 invDir, float tEnd, out vec4 outColor, out float outDepth);
#endif

#ifdef VTKRT_DEPTH_BELOW
// The window depth already in this renderer's viewport (that the renderers
// before it left: PreserveDepthBuffer, or Erase off; or its own opaque
// raster props, drawn before traced translucent layers), taken before
// tracing: a camera ray ends there, as raster geometry behind it would be
// hidden, translucent layers included.
uniform sampler2D uDepthBelow;
uniform float uDepthBelowSide;

// The t of the camera ray through ndc at window depth `depth`
// (core::gpu::affineRayT, core::gpu::projectiveRayT); 1 (the far plane) at
// depth 1.
float cameraRayEnd(vec2 ndc, vec3 org, vec3 dir, float depth)
{
  if (depth >= 1.0)
  {
    return 1.0;
  }
#ifdef VTKRT_PROJECTIVE_RAYS
  return clamp(projectiveRayT(uClipToCamera, ndc, 2.0 * depth - 1.0, org, dir), 0.0, 1.0);
#else
  return clamp(affineRayT(uRayDepth, 2.0 * depth - 1.0), 0.0, 1.0);
#endif
}

// The depth a hit writes over the depth below: never behind it (a layer of
// translucent surfaces alone leaves the far plane's depth, a hit coincident
// with it the depth pushed back by kCoincidentDepthBias), at most about half
// a step of a 24-bit depth buffer before it, so that the depth test passes
// and the depth below changes by a step at most.
float depthOverBelow(float depth, float depthBelow)
{
  return min(depth, depthBelow - 0.5 / 16777216.0);
}
#endif

// Traces and shades the ray through a point of the viewport (normalized
// device coordinates): false on a miss, else the shaded color (the encoded
// id in id mode; premultiplied by its alpha) and the window depth.
bool shadeRay(vec2 ndc, out vec4 outColor, out float outDepth)
{
  outColor = vec4(0.0);
  outDepth = 1.0;
#ifdef VTKRT_PROJECTIVE_RAYS
  vec4 nearPoint = uClipToCamera * vec4(ndc, -1.0, 1.0);
  vec4 farPoint = uClipToCamera * vec4(ndc, 1.0, 1.0);
  vec3 org = nearPoint.xyz / nearPoint.w;
  vec3 dir = farPoint.xyz / farPoint.w - org;
#else
  vec3 org = uRayOrigin[0] + ndc.x * uRayOrigin[1] + ndc.y * uRayOrigin[2];
  vec3 dir = uRayDirection[0] + ndc.x * uRayDirection[1] + ndc.y * uRayDirection[2];
#endif
  vec3 invDir = safeInverse(dir);
#ifdef VTKRT_TILE_ENTRIES
  gTileList = tileListOf(ndc);
#endif
  float tEnd = 1.0;
#ifdef VTKRT_DEPTH_BELOW
  // uDepthBelowSide (+1 or -1) decides a surface coincident with what lies
  // below: drawn over a renderer below (+, raster's less-or-equal test draws
  // the same triangles over themselves), under this renderer's own raster
  // props (-, as its lines and points pass the test over the traced depth
  // when drawn after the trace).
  float depthBelow = texture(uDepthBelow, ndc * 0.5 + 0.5).r;
  tEnd = depthBelow >= 1.0 ? 1.0
                           : cameraRayEnd(ndc, org, dir, clamp(depthBelow + uDepthBelowSide * kCoincidentDepthBias, 0.0, 1.0));
#endif
#ifdef VTKRT_TRANSLUCENT
  bool hit = traceTranslucentLayers(org, dir, invDir, tEnd, outColor, outDepth);
#ifdef VTKRT_DEPTH_BELOW
  outDepth = depthOverBelow(outDepth, depthBelow);
#endif
  return hit;
#else
  float tBest = tEnd;
  int hitInstance;
  int hitPrimitive;
  vec2 hitUV;
  traceClosest(org, dir, invDir, 0.0, tBest, hitInstance, hitPrimitive, hitUV);
  if (hitInstance < 0)
  {
    return false;
  }
  outDepth = windowDepth(org, dir, tBest);
#ifdef VTKRT_DEPTH_BELOW
  outDepth = depthOverBelow(outDepth, depthBelow);
#endif
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
// buffer); the depth is the nearest hit's. uPixelSize (a frame constant):
// one pixel in normalized device coordinates.

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
