// vtkrt ray tracing fragment shader: the color of a camera ray's closest hit.
// What the hit's primitive gives (normals, VTK id, scalar color) is read by
// primitive kind; the lighting and the property's looks (back faces, edges,
// wires, textures, opacity) are then applied as vtkOpenGLPolyDataMapper does.

// What shading needs from the primitive that was hit. Normals are local (the
// instance's coordinates); scalarColor.x < 0 when there is no scalar color.
struct HitSurface
{
  vec3 localNormal;
  vec3 geometricNormal;
  uint vtkId;
  vec4 scalarColor;
  float mirror; // -1 where the actor's matrix mirrors triangles' winding
#ifdef VTKRT_HAS_TEXTURES
  uvec3 textureIds; // the triangle's point ids, for texture coordinates
#endif
};

HitSurface emptyHitSurface(uint flags)
{
  HitSurface s;
  s.localNormal = vec3(0.0, 0.0, 1.0);
  s.geometricNormal = vec3(0.0, 0.0, 1.0);
  s.vtkId = 0u;
  s.scalarColor = vec4(-1.0);
  s.mirror = (flags & kInstanceMirrored) != 0u ? -1.0 : 1.0;
#ifdef VTKRT_HAS_TEXTURES
  s.textureIds = uvec3(0u);
#endif
  return s;
}

#ifdef VTKRT_HAS_SPHERES
#if defined(VTKRT_HAS_TUBES) && defined(VTKRT_HAS_COLORS)
// A tube's point colors interpolated along its segment (s from point i0 to i1).
vec4 tubePointColor(int cb, uint flags, int i0, int i1, float s)
{
#ifdef VTKRT_HAS_COLOR_TEXTURE
  if ((flags & kInstanceColorTexture) != 0u)
  {
    return lookupColorTexture(cb, mix(fetchColorCoordinate(cb, i0), fetchColorCoordinate(cb, i1), s));
  }
#endif
  return mix(fetchColor(cb + i0), fetchColor(cb + i1), s);
}
#endif

// The VTK id a sphere reports (ids, selection, cell colors) for the point
// or glyph id `pointId` of its uSphereIds: a point drawn as a sphere
// reports the cell that holds it where the instance has such cell ids
// (core::gpu::InstanceRecord::sphereCellIdBase), its id otherwise.
uint sphereCellId(int instance, uint flags, int primitive, uint pointId)
{
#ifdef VTKRT_SPHERE_CELL_IDS
  if ((flags & kInstanceSphereCellIds) != 0u)
  {
    return fetchPacked(uSpheres, int(instanceSphereCellIdBase(instance) + uint(primitive)));
  }
#endif
  return pointId;
}

// Spheres, ellipsoids and tubes, hit at localHit (instance coordinates).
HitSurface sphereHitSurface(int hitInstance, int hitPrimitive, uint flags, vec3 localHit)
{
  HitSurface s = emptyHitSurface(flags);
  s.localNormal = localHit - fetchSphere(uSpheres, hitPrimitive).center;
#ifdef VTKRT_HAS_TUBES
  // Tubes: the normal from the sphere touching the hit; point colors
  // interpolated along the segment, cell colors by its cell.
  float tubeS = 0.0;
  uvec2 tubePointIds = uvec2(0u);
  if ((flags & kInstanceTubes) != 0u)
  {
    s.localNormal = tubeHitNormal(hitPrimitive, localHit, instanceScreenRadiusPlane(hitInstance), tubeS, tubePointIds);
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
    vec3 u = vec3(dot(e0.xyz, localHit) + e0.w, dot(e1.xyz, localHit) + e1.w, dot(e2.xyz, localHit) + e2.w);
    s.localNormal = u.x * e0.xyz + u.y * e1.xyz + u.z * e2.xyz;
  }
#endif
  s.geometricNormal = s.localNormal;
  s.mirror = 1.0;
  uint pointId = fetchPacked(uSphereIds, hitPrimitive);
  s.vtkId = sphereCellId(hitInstance, flags, hitPrimitive, pointId);
#ifdef VTKRT_HAS_COLORS
  if ((flags & (kInstancePointColors | kInstanceCellColors)) != 0u)
  {
    int cb = int(instanceColorBase(hitInstance));
    int colorId = int((flags & kInstanceCellColors) != 0u ? s.vtkId : pointId);
#ifdef VTKRT_HAS_TUBES
    if ((flags & (kInstanceTubes | kInstancePointColors)) == (kInstanceTubes | kInstancePointColors))
    {
      s.scalarColor = tubePointColor(cb, flags, int(tubePointIds.x), int(tubePointIds.y), tubeS);
      return s;
    }
#endif
#ifdef VTKRT_HAS_COLOR_TEXTURE
    if ((flags & kInstanceColorTexture) != 0u)
    {
      s.scalarColor = lookupColorTexture(cb, fetchColorCoordinate(cb, colorId));
      return s;
    }
#endif
    s.scalarColor = fetchColor(cb + colorId);
  }
#endif
  return s;
}
#endif

#ifdef VTKRT_HAS_TRIANGLES
#ifdef VTKRT_HAS_TRIANGLE_VERTICES
// The point attributes of triangle vertices ids at barycentric (w0, uv):
// interpolated point normals and point colors, where the instance has them.
void readPointAttributes(int hitInstance, uint flags, uvec3 ids, float w0, vec2 uv, inout HitSurface s)
{
  int i0 = int(ids.x);
  int i1 = int(ids.y);
  int i2 = int(ids.z);
#ifdef VTKRT_HAS_VERTEX_NORMALS
  if ((flags & kInstanceVertexNormals) != 0u)
  {
    int nb = int(instanceNormalBase(hitInstance));
    s.localNormal = w0 * fetchNormal(uNormals, nb + i0).direction + uv.x * fetchNormal(uNormals, nb + i1).direction +
      uv.y * fetchNormal(uNormals, nb + i2).direction;
  }
#endif
#ifdef VTKRT_HAS_COLORS
  if ((flags & kInstancePointColors) != 0u)
  {
    int cb = int(instanceColorBase(hitInstance));
#ifdef VTKRT_HAS_COLOR_TEXTURE
    if ((flags & kInstanceColorTexture) != 0u)
    {
      vec2 st = w0 * fetchColorCoordinate(cb, i0) + uv.x * fetchColorCoordinate(cb, i1) +
        uv.y * fetchColorCoordinate(cb, i2);
      s.scalarColor = lookupColorTexture(cb, st);
      return;
    }
#endif
    s.scalarColor = w0 * fetchColor(cb + i0) + uv.x * fetchColor(cb + i1) + uv.y * fetchColor(cb + i2);
  }
#endif
}
#endif

// A triangle hit at barycentric hitUV.
HitSurface triangleHitSurface(int hitInstance, int hitPrimitive, uint flags, vec2 hitUV)
{
  HitSurface s = emptyHitSurface(flags);
  Triangle triangle = fetchTriangle(uTriangles, hitPrimitive);
  s.geometricNormal = cross(triangle.v1 - triangle.v0, triangle.v2 - triangle.v0);
  s.localNormal = s.geometricNormal;
  s.vtkId = triangle.cellId;
#ifdef VTKRT_HAS_TRIANGLE_VERTICES
  if ((flags & (kInstanceVertexNormals | kInstancePointColors | kInstanceTextured)) != 0u)
  {
    uvec3 ids = fetchTriangleVertices(uTriangleVertices, hitPrimitive).ids;
#ifdef VTKRT_HAS_TEXTURES
    s.textureIds = ids;
#endif
    readPointAttributes(hitInstance, flags, ids, 1.0 - hitUV.x - hitUV.y, hitUV, s);
  }
#endif
#ifdef VTKRT_HAS_CELL_NORMALS
  if ((flags & kInstanceCellNormals) != 0u)
  {
    // One normal per VTK cell, over all of its triangles (as raster).
    s.localNormal = fetchNormal(uNormals, int(instanceNormalBase(hitInstance)) + int(s.vtkId)).direction;
  }
#endif
#ifdef VTKRT_HAS_COLORS
  if ((flags & kInstanceCellColors) != 0u)
  {
    s.scalarColor = fetchColor(int(instanceColorBase(hitInstance)) + int(s.vtkId));
  }
#endif
  return s;
}
#endif

#if defined(VTKRT_SELECT_IDS)
// Hardware selection (floats, exact below 2^24): prop index + 1, the VTK
// cell (or point, for spheres) id's low 24 and high bits, composite index.
vec4 hitIdColor(int hitInstance, uint vtkId)
{
  return vec4(float(instancePropIndex(hitInstance) + 1u), float(vtkId & 0xFFFFFFu), float(vtkId >> 24u),
    float(instanceCompositeIndex(hitInstance)));
}
#elif defined(VTKRT_ID_MODE)
// RGB: the VTK cell (or point, for spheres) id, 24 bits; A: prop index + 1.
vec4 hitIdColor(int hitInstance, uint vtkId)
{
  uint prop = instancePropIndex(hitInstance) + 1u;
  return vec4(float(vtkId & 255u), float((vtkId >> 8) & 255u), float((vtkId >> 16) & 255u), float(prop & 255u)) /
    255.0;
}
#else
// The colors a hit is lit with: the property's, or its back face's, or the
// scalar color times the intensities, with cell edges blended in.
struct HitMaterial
{
  vec3 ambient;
  vec3 diffuse;
  vec3 specular;
  float specularPower;
};

HitMaterial hitMaterial(int hitInstance, uint flags, HitSurface s, bool frontFacing)
{
  HitMaterial m;
  m.ambient = instanceAmbient(hitInstance);
  m.diffuse = instanceDiffuse(hitInstance);
  m.specular = instanceSpecular(hitInstance);
  m.specularPower = instanceSpecularPower(hitInstance);
  if (s.scalarColor.x >= 0.0)
  {
    m.ambient = instanceAmbientIntensity(hitInstance) * s.scalarColor.rgb;
    m.diffuse = instanceDiffuseIntensity(hitInstance) * s.scalarColor.rgb;
  }
#ifdef VTKRT_BACKFACE_PROPERTIES
  // As vtkOpenGLPolyDataMapper: the BackfaceProperty's colors on back faces
  // of actors without scalar colors.
  if (!frontFacing && (flags & kInstanceBackfaceProperty) != 0u && s.scalarColor.x < 0.0)
  {
    m.ambient = instanceBackAmbient(hitInstance);
    m.diffuse = instanceBackDiffuse(hitInstance);
    m.specular = instanceBackSpecular(hitInstance);
    m.specularPower = instanceBackSpecularPower(hitInstance);
  }
#endif
  return m;
}

// The shading normal: VTK flips point and cell normals on back-facing
// triangles; spheres, and VTK's derivative normal where there are no
// normals, face the eye (the ray), not just the view plane.
vec3 shadingNormal(uint flags, vec3 n, vec3 ng, vec3 dir)
{
  bool given = (flags & (kInstanceVertexNormals | kInstanceCellNormals)) != 0u;
  return dot(given ? ng : n, dir) > 0.0 ? -n : n;
}

#ifdef VTKRT_SCREEN_SPHERES
// VTK 9.1 lights a point drawn as a sphere as a sprite seen head-on: its
// normal comes from the pixel's offset from the point in the view plane
// through it, (x, y, sqrt(1 - x^2 - y^2)) in view coordinates. p is the
// camera ray's hit on the sphere of center p - radius * n (n unit).
vec3 spriteNormal(vec3 p, vec3 dir, vec3 n, float radius)
{
  vec3 center = p - radius * n;
  vec3 inPlane = p + (dot(center - p, uViewBack) / dot(dir, uViewBack)) * dir - center;
  vec3 xy = inPlane / radius;
  xy -= dot(xy, uViewBack) * uViewBack;
  return normalize(xy + sqrt(max(0.0, 1.0 - dot(xy, xy))) * uViewBack);
}
#endif

// The lit color and alpha of a surface hit (alpha 1 unless translucent);
// r0..r2: the instance's camera-to-local rows.
vec4 shadeSurface(vec3 p, vec3 dir, int hitInstance, uint flags, HitSurface s, vec2 hitUV, int hitPrimitive,
  vec4 r0, vec4 r1, vec4 r2)
{
  // Local normals map to camera space by the transpose of the camera-to-local
  // matrix (the inverse transpose of local-to-camera).
  mat3 cameraToLocal = mat3(r0.xyz, r1.xyz, r2.xyz); // columns = rows of the matrix
  vec3 ng = s.mirror * (cameraToLocal * s.geometricNormal);
  // A zero normal (given so, or past a short normals array) shades as the
  // geometric one instead of normalize's NaN.
  vec3 given = cameraToLocal * s.localNormal;
  vec3 unitGiven = dot(given, given) > 0.0 ? normalize(given) : normalize(ng);
  vec3 n = shadingNormal(flags, unitGiven, ng, dir);
#ifdef VTKRT_SCREEN_SPHERES
  if ((flags & kInstanceScreenSpheres) != 0u)
  {
    // The actor's scale is uniform here: the rows' length is 1 / scale.
    n = spriteNormal(p, dir, normalize(cameraToLocal * s.localNormal), length(s.localNormal) / length(r0.xyz));
  }
#endif
  // Raster's gl_FrontFacing: the ray meets the side its winding faces.
  bool frontFacing = dot(ng, dir) <= 0.0;
  HitMaterial m = hitMaterial(hitInstance, flags, s, frontFacing);
#if defined(VTKRT_SURFACE_EDGES) || defined(VTKRT_HAS_WIREFRAME)
  vec3 localHit = rowsPoint(r0, r1, r2, p);
#endif
#ifdef VTKRT_SURFACE_EDGES
  if ((flags & kInstanceSurfaceEdges) != 0u)
  {
    // As vtkOpenGLPolyDataMapper: on an edge the edge color replaces the
    // ambient color and the diffuse color fades out.
    float edgeMix = instanceSurfaceEdgeMix(hitInstance, fetchTriangle(uTriangles, hitPrimitive), localHit);
    m.diffuse = mix(m.diffuse, vec3(0.0), edgeMix);
    m.ambient = mix(m.ambient, instanceEdgeColor(hitInstance), edgeMix);
  }
#endif
#ifdef VTKRT_HAS_WIREFRAME
  if ((flags & kInstanceWireframe) != 0u)
  {
    // Lines are front facing: normals are never flipped; without any, VTK's
    // line normal.
    n = (flags & (kInstanceVertexNormals | kInstanceCellNormals)) != 0u
      ? unitGiven
      : wireNormal(hitInstance, fetchTriangle(uTriangles, hitPrimitive), localHit, uViewBack);
  }
#endif
  // Unit geometric normal on the viewer's side (secondary ray offsets).
  vec3 ngView = normalize(ng);
  if (dot(ngView, dir) > 0.0)
  {
    ngView = -ngView;
  }
  vec3 color = shadeLikeVTK(p, n, ngView, m.ambient, m.diffuse, m.specular, m.specularPower,
    (flags & kInstanceLit) != 0u);
  float alpha = 1.0;
#ifdef VTKRT_TRANSLUCENT
  // As vtkOpenGLPolyDataMapper: the property's opacity times the scalar
  // color's alpha (times the texel's, below).
  if ((flags & kInstanceTranslucent) != 0u)
  {
    alpha = instanceOpacity(hitInstance) * (s.scalarColor.x >= 0.0 ? s.scalarColor.a : 1.0);
  }
#endif
#ifdef VTKRT_HAS_TEXTURES
  // As vtkOpenGLPolyDataMapper: the lit color times the texture's, on back
  // faces too unless ShowTexturesOnBackface is off.
  if ((flags & kInstanceTextured) != 0u && (frontFacing || (flags & kInstanceTextureOnBackface) != 0u))
  {
    vec4 texel = instanceTextureColor(hitInstance, s.textureIds, hitUV);
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
#ifdef VTKRT_FLOAT_COLORS
  return vec4(max(color, 0.0), alpha);
#else
  return vec4(clamp(color, 0.0, 1.0), alpha);
#endif
}
#endif

// The color of the hit (tBest, hitInstance, hitPrimitive, hitUV) of the
// camera ray org + t dir: lit RGB and its alpha (1 unless the instance is
// translucent), or the encoded id in id mode.
vec4 shadeHit(vec3 org, vec3 dir, float tBest, int hitInstance, int hitPrimitive, vec2 hitUV)
{
  uint flags = instanceFlags(hitInstance);
  vec4 r0 = instanceCameraToLocal(hitInstance, 0);
  vec4 r1 = instanceCameraToLocal(hitInstance, 1);
  vec4 r2 = instanceCameraToLocal(hitInstance, 2);
  HitSurface s = emptyHitSurface(flags);
#ifdef VTKRT_HAS_SPHERES
  if ((flags & kInstanceSpheres) != 0u)
  {
    s = sphereHitSurface(hitInstance, hitPrimitive, flags, rowsPoint(r0, r1, r2, org) + tBest * rowsDir(r0, r1, r2, dir));
  }
#endif
#ifdef VTKRT_HAS_TRIANGLES
  if ((flags & kInstanceSpheres) == 0u)
  {
    s = triangleHitSurface(hitInstance, hitPrimitive, flags, hitUV);
  }
#endif
#if defined(VTKRT_SELECT_IDS) || defined(VTKRT_ID_MODE)
  return hitIdColor(hitInstance, s.vtkId);
#else
  return shadeSurface(org + tBest * dir, dir, hitInstance, flags, s, hitUV, hitPrimitive, r0, r1, r2);
#endif
}
