// vtkrt ray tracing fragment shader: the pass's inputs (the quad's
// coordinate, the camera, lights and clip planes, the attribute buffers) and
// the readers of scalar colors. First of the shader's main chunks (see
// vtkrtRayTraceMain).

in vec2 texCoord;
layout(location = 0) out vec4 fragOutput0;

// The frame constants (uniforms, or flat inputs under the same names) are
// declared first, by the pass (vtkRayTraceFrameConstants.cxx):
// - VTKRT_PROJECTIVE_RAYS: uCameraToClip, VTK's world-to-clip matrix
//   translated by the eye, and uClipToCamera, its inverse;
// - otherwise the camera ray through (x, y) (normalized device coordinates)
//   from uRayOrigin[0] + x uRayOrigin[1] + y uRayOrigin[2] along
//   uRayDirection[0] + x uRayDirection[1] + y uRayDirection[2] (VTK's
//   cameras' rays are affine in x, y, unprojected once per frame in double:
//   CameraFrame::AffineRays), and uRayDepth, a camera ray's depth at t
//   (affineRayDepth; CameraFrame::RayDepth: a division instead of a matrix
//   product per pixel);
// - uViewBack, the unit +z axis of VTK's view coordinates;
// - VTKRT_SINGLE_INSTANCE: uRootNode, the instance's root node, and its
//   record, uInstance and uInstanceTail (read through the accessors below);
//   the general shader without a top level: uNumberOfInstances;
// - VTKRT_WORLD_COORDINATES: uEye, the eye (WORLD precision mode: coordinates
//   are plain float world coordinates; the comments' "camera-relative" then
//   reads "world");
// - uClipPlanes[VTKRT_NUMBER_OF_CLIP_PLANES], (n, d) with n.p + d >= 0 kept;
// - per light: uLightColor (diffuse color * intensity), uLightDirection
//   (unit, from the light), uLightPosition (camera-relative),
//   uLightAttenuation, uLightCone (cone angle, exponent, positional).
#ifndef VTKRT_WORLD_COORDINATES
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

#ifdef VTKRT_HAS_COLORS
vec4 fetchColor(int i)
{
  return unpackRGBA8(fetchPacked(uColors, i));
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
