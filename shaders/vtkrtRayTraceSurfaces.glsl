// Triangle surfaces beyond their material, included only in shaders of
// scenes that use them: actor textures (a vtkTexture sampled as OpenGL
// samples vtkOpenGLTexture's), the faces raster does not draw (vtkProperty's
// BackfaceCulling / FrontfaceCulling, fully transparent texels). Needs
// vtkrtRayTraceTriangles.

#if defined(VTKRT_FACE_CULLING) || defined(VTKRT_TEXTURE_CUTOUTS)
#define VTKRT_SKIPS_FACES
#endif
#ifdef VTKRT_TEXTURE_CUTOUTS
uvec3 triangleVertexIds(int tri); // vtkrtRayTraceMain
#endif

#ifdef VTKRT_HAS_TEXTURES
// Packed by vtkRayTraceTextures: per texture a header (width, height, mode
// bits, border RGBA8) and its RGBA8 texels row by row; per mesh its points'
// (s, t) float bits, two points a texel. Every entry starts a texel.
uniform usamplerBuffer uTextures;

vec2 fetchTextureCoordinate(int base, uint point)
{
  uvec4 t = texelFetch(uTextures, (base >> 2) + int(point >> 1u));
  return uintBitsToFloat((point & 1u) == 0u ? t.xy : t.zw);
}

// A coordinate in texels brought into the range its wrap mode repeats
// (vtkTexture: ClampToEdge 0, Repeat 1, MirroredRepeat 2, ClampToBorder 3):
// [0, size) repeated, [0, 2 size) mirrored, else [-1, size].
float wrapTexelCoordinate(float x, float size, uint wrap)
{
  if (wrap == 1u)
  {
    return x - size * floor(x / size);
  }
  if (wrap == 2u)
  {
    return x - 2.0 * size * floor(x / (2.0 * size));
  }
  return clamp(x, -1.0, size);
}

// The texel of index i (the floor of a wrapped coordinate, or one more)
// under the wrap mode; -1 for the border color.
int wrapTexelIndex(int i, int size, uint wrap)
{
  if (wrap == 1u)
  {
    return i >= size ? i - size : i;
  }
  if (wrap == 2u)
  {
    i = i >= 2 * size ? i - 2 * size : i;
    return i < size ? i : 2 * size - 1 - i;
  }
  if (wrap == 3u)
  {
    return i < 0 || i >= size ? -1 : i;
  }
  return clamp(i, 0, size - 1);
}

vec4 fetchTexel(int base, int width, int x, int y, vec4 border)
{
  return x < 0 || y < 0 ? border : unpackRGBA8(fetchPacked(uTextures, base + 4 + y * width + x));
}

// The texture at `base` at (s, t) as OpenGL's level 0 gives it: the nearest
// texel, or (Interpolate) the bilinear blend of the four around it.
vec4 sampleTexture(int base, vec2 st)
{
  uvec4 header = texelFetch(uTextures, base >> 2);
  int w = int(header.x);
  int h = int(header.y);
  uint wrap = header.z & 3u;
  vec4 border = unpackRGBA8(header.w);
  vec2 size = vec2(header.xy);
  if ((header.z & 4u) == 0u)
  {
    ivec2 i = ivec2(floor(vec2(wrapTexelCoordinate(st.x * size.x, size.x, wrap),
      wrapTexelCoordinate(st.y * size.y, size.y, wrap))));
    return fetchTexel(base, w, wrapTexelIndex(i.x, w, wrap), wrapTexelIndex(i.y, h, wrap), border);
  }
  vec2 x = vec2(wrapTexelCoordinate(st.x * size.x - 0.5, size.x, wrap),
    wrapTexelCoordinate(st.y * size.y - 0.5, size.y, wrap));
  ivec2 i = ivec2(floor(x));
  vec2 a = x - vec2(i);
  int x0 = wrapTexelIndex(i.x, w, wrap);
  int x1 = wrapTexelIndex(i.x + 1, w, wrap);
  int y0 = wrapTexelIndex(i.y, h, wrap);
  int y1 = wrapTexelIndex(i.y + 1, h, wrap);
  vec4 bottom = mix(fetchTexel(base, w, x0, y0, border), fetchTexel(base, w, x1, y0, border), a.x);
  vec4 top = mix(fetchTexel(base, w, x0, y1, border), fetchTexel(base, w, x1, y1, border), a.x);
  return mix(bottom, top, a.y);
}

// The instance's texture color at a triangle hit: its points' (s, t)
// interpolated with the hit's barycentrics (w0, uv), as raster interpolates
// them (perspective-correct).
vec4 instanceTextureColor(int instance, uvec3 ids, vec2 uv)
{
  int cb = int(instanceTextureCoordinateBase(instance));
  vec2 st = (1.0 - uv.x - uv.y) * fetchTextureCoordinate(cb, ids.x) +
    uv.x * fetchTextureCoordinate(cb, ids.y) + uv.y * fetchTextureCoordinate(cb, ids.z);
  return sampleTexture(int(instanceTextureBase(instance)), st);
}
#endif

#ifdef VTKRT_SKIPS_FACES
const uint kInstanceSkipsFaces = kInstanceCullBackfaces | kInstanceCullFrontfaces |
  kInstanceTextureCutOuts;

// Whether raster leaves out the hit (tri, uv) of the instance by a ray along
// dir (local): a side it culls (camera rays only: shadow and occlusion rays
// meet a culled face), or a fully transparent texel, which raster discards.
// Raster culls by winding in the window, which is the side of the
// triangle's winding normal the eye is on (flipped by a mirroring matrix);
// back-face culling wins when both are on, as in vtkOpenGLProperty.
bool faceSkipped(int instance, int tri, vec2 uv, vec3 dir, uint flags, bool cameraRay)
{
  if ((flags & kInstanceSkipsFaces) == 0u)
  {
    return false;
  }
  Triangle t = fetchTriangle(uTriangles, tri);
  float facing = dot(cross(t.v1 - t.v0, t.v2 - t.v0), dir);
  bool front = (flags & kInstanceMirrored) != 0u ? facing > 0.0 : facing < 0.0;
#ifdef VTKRT_FACE_CULLING
  if (cameraRay && (flags & (kInstanceCullBackfaces | kInstanceCullFrontfaces)) != 0u &&
    ((flags & kInstanceCullBackfaces) != 0u ? !front : front))
  {
    return true;
  }
#endif
#ifdef VTKRT_TEXTURE_CUTOUTS
  if ((flags & kInstanceTextureCutOuts) != 0u && (front || (flags & kInstanceTextureOnBackface) != 0u))
  {
    return instanceTextureColor(instance, triangleVertexIds(tri), uv).a <= 0.0;
  }
#endif
  return false;
}

// After a closest hit at t of a triangle (tri, uv) of the instance's BVH at
// root: the first hit up to tEnd that raster draws, as it shows what lies
// behind a culled face or a cut-out texel.
bool walkPastSkippedFaces(int instance, int root, vec3 org, vec3 dir, float tEnd, inout float t,
  inout int tri, inout vec2 uv, uint flags, bool cameraRay)
{
  bool hit = true;
  while (hit && faceSkipped(instance, tri, uv, dir, flags, cameraRay))
  {
    float tmin = uintBitsToFloat(floatBitsToUint(t) + 1u);
    t = tEnd;
    hit = traverseTriangles(root, org, dir, tmin, t, tri, uv, false);
  }
  return hit;
}
#endif
