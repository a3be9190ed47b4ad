// Cell edges on traced triangles, included only in shaders of scenes with
// edge visibility (VTKRT_SURFACE_EDGES) or the wireframe representation
// (VTKRT_HAS_WIREFRAME). Edges are measured in window pixels, as VTK 9.1's
// raster draws them: a local point goes through one matrix (local to
// camera, then uCameraToPixels) to homogeneous pixels (x, y, w),
// and the line through two of them is their cross product, right also when
// a vertex lies behind the eye. Triangle.cellEdges says which of a
// triangle's edges are its VTK cell's (a polygon's fan diagonals are not).
// The C++ twins (core/GpuEdgeKernels.h) have the same names.

// VTK's camera-to-clip matrix with x and y times half the viewport's size:
// camera-relative points to homogeneous pixels from the viewport's center.
uniform mat4 uCameraToPixels;

mat4 localToPixels(vec4 r0, vec4 r1, vec4 r2, mat4 cameraToPixels)
{
  return cameraToPixels * transpose(mat4(r0, r1, r2, vec4(0.0, 0.0, 0.0, 1.0)));
}

vec3 pixelPoint(mat4 toPixels, vec3 p)
{
  vec4 c = toPixels * vec4(p, 1.0);
  return vec3(c.x, c.y, c.w);
}

vec3 pixelLine(vec3 a, vec3 b)
{
  return cross(a, b);
}

// Perpendicular distance in pixels (VTK's edge equations).
float lineDistance(vec3 line, vec2 q)
{
  return abs(line.x * q.x + line.y * q.y + line.z) / length(vec2(line.x, line.y));
}

// Signed offset along the minor axis, as OpenGL widens aliased lines.
float minorAxisOffset(vec3 line, vec2 q)
{
  float along = abs(line.y) >= abs(line.x) ? line.y : line.x;
  return (line.x * q.x + line.y * q.y + line.z) / along;
}

// Within the segment along its major axis (half open); true when an end is
// at or behind the eye.
bool withinMajorExtent(vec3 a, vec3 b, vec3 line, vec2 q)
{
  if (!(a.z > 0.0 && b.z > 0.0))
  {
    return true;
  }
  int axis = abs(line.y) >= abs(line.x) ? 0 : 1;
  float pa = a[axis] / a.z;
  float pb = b[axis] / b.z;
  return q[axis] >= min(pa, pb) && q[axis] < max(pa, pb);
}

// The instance's local to homogeneous pixel matrix.
mat4 instanceLocalToPixels(int instance)
{
  return localToPixels(instanceLocalToCamera(instance, 0), instanceLocalToCamera(instance, 1),
    instanceLocalToCamera(instance, 2), uCameraToPixels);
}

// Where the local point p falls in the window (pixels from the viewport's center).
vec2 projectToPixels(mat4 toPixels, vec3 p)
{
  vec3 h = pixelPoint(toPixels, p);
  return h.xy / h.z;
}

#ifdef VTKRT_SURFACE_EDGES
// vtkOpenGLPolyDataMapper's emix: 1 on a cell edge, 0 away from it, a
// one-pixel ramp between; the line width is at least 1.1, as VTK's.
float surfaceEdgeMix(vec3 p0, vec3 p1, vec3 p2, uint edges, vec2 q, float lineWidth)
{
  float width = max(lineWidth, 1.1);
  float d01 = lineDistance(pixelLine(p0, p1), q) + ((edges & kEdge01) != 0u ? 0.0 : width);
  float d12 = lineDistance(pixelLine(p1, p2), q) + ((edges & kEdge12) != 0u ? 0.0 : width);
  float d20 = lineDistance(pixelLine(p2, p0), q) + ((edges & kEdge20) != 0u ? 0.0 : width);
  return clamp(0.5 + 0.5 * width - min(min(d01, d12), d20), 0.0, 1.0);
}

// The edge blend at the local hit point p of triangle t of the instance.
float instanceSurfaceEdgeMix(int instance, Triangle t, vec3 p)
{
  mat4 toPixels = instanceLocalToPixels(instance);
  return surfaceEdgeMix(pixelPoint(toPixels, t.v0), pixelPoint(toPixels, t.v1),
    pixelPoint(toPixels, t.v2), t.cellEdges, projectToPixels(toPixels, p),
    instanceLineWidth(instance));
}
#endif

#ifdef VTKRT_HAS_WIREFRAME
bool wireCovers(vec3 a, vec3 b, vec2 q, float lineWidth)
{
  vec3 line = pixelLine(a, b);
  float halfWidth = 0.5 * max(lineWidth, 1.0);
  float offset = minorAxisOffset(line, q);
  return offset >= -halfWidth && offset < halfWidth && withinMajorExtent(a, b, line, q);
}

// The cell edge (0: v0-v1, 1: v1-v2, 2: v2-v0) whose wire covers pixel q,
// the nearest along the minor axis; -1 when none does.
int wireEdgeAt(vec3 p0, vec3 p1, vec3 p2, uint edges, vec2 q, float lineWidth)
{
  int found = -1;
  float nearest = 3.0e38;
  vec3 ends[4] = vec3[4](p0, p1, p2, p0);
  uint bits[3] = uint[3](kEdge01, kEdge12, kEdge20);
  for (int k = 0; k < 3; ++k)
  {
    if ((edges & bits[k]) != 0u && wireCovers(ends[k], ends[k + 1], q, lineWidth))
    {
      float offset = abs(minorAxisOffset(pixelLine(ends[k], ends[k + 1]), q));
      if (offset < nearest)
      {
        nearest = offset;
        found = k;
      }
    }
  }
  return found;
}
#endif

#ifdef VTKRT_HAS_WIREFRAME
// Where pixel q falls along the projected edge a-b (0 at a, 1 at b; both
// ends in front of the eye).
float edgeParameter(vec3 a, vec3 b, vec2 q)
{
  vec2 a2 = a.xy / a.z;
  vec2 e2 = b.xy / b.z - a2;
  return dot(q - a2, e2) / dot(e2, e2);
}

// The ray's t nearest the point of edge va-vb (local; a, b its homogeneous
// pixels) at screen parameter s, clamped to the edge and made perspective
// correct (s3: the parameter along va-vb).
float edgePointUnder(vec3 a, vec3 b, vec3 va, vec3 vb, float s, vec3 org, vec3 dir, out float s3)
{
  s = clamp(s, 0.0, 1.0);
  s3 = s * a.z / (s * a.z + (1.0 - s) * b.z);
  vec3 x = va + s3 * (vb - va);
  return dot(x - org, dir) / dot(dir, dir);
}

// The wireframe instance the triangle walk is in (set by traceInstance):
// a triangle hit counts only where a wire covers it, so rays pass through
// the faces and the walk goes on behind them; a camera ray that misses the
// triangle by less than half a wire meets the wire's outer half (at a
// mesh's boundary or silhouette no neighbour holds it), the BVH boxes grown
// by gWireGrow local units for it.
bool gWireActive = false;
mat4 gWireToPixels;
float gWireWidth;
float gWireGrow; // < 0: not a camera ray
vec2 gWirePixel;  // a camera ray's pixel (its origin's), the same for every triangle

void beginWireInstance(int instance, uint flags, bool cameraRay, vec3 localOrg)
{
  gWireActive = (flags & kInstanceWireframe) != 0u;
  if (gWireActive)
  {
    gWireToPixels = instanceLocalToPixels(instance);
    gWireWidth = instanceLineWidth(instance);
    gWireGrow = cameraRay ? instanceSphereGrow(instance) : -1.0;
    gWirePixel = projectToPixels(gWireToPixels, localOrg);
  }
}

bool wireWalk()
{
  return gWireActive;
}

// The BVH boxes' growth for the walk (local units).
vec3 wireGrowBy()
{
  return vec3(gWireActive ? max(gWireGrow, 0.0) : 0.0);
}

// Wires this close in t (relative; 64 float ulps) are coincident: faces
// sharing an edge, each with its own copy of the edge's points.
const float kWireTie = 64.0 / 8388608.0;

// How far a wire walk looks past the best hit tBest: far enough to meet the
// wires coincident with it.
float wireReach(float tBest)
{
  return gWireActive ? tBest * (1.0 + kWireTie) : tBest;
}

// Whether a wire hit at t of VTK cell `cell` replaces the best one so far
// (tBest; `cellBest` when `haveBest`): the nearer wins, and of coincident
// wires the highest cell id, as raster's depth test (GL_LEQUAL) keeps the
// cell it draws last.
bool wireWins(float t, float tBest, bool haveBest, uint cell, uint cellBest)
{
  if (!haveBest || t < tBest * (1.0 - kWireTie))
  {
    return t <= tBest;
  }
  return cell > cellBest || (cell == cellBest && t < tBest);
}

// Whether a ray that misses the triangle may pass within `reach` of it: the
// origin's distance to it in the watertight test's sheared plane (along the
// ray onto the plane across its dominant axis), which is at most sqrt(3)
// times the ray's distance to it; a cheap reject before any projection.
bool mayPassWithin(RayTrianglePrecomputed r, vec3 v0, vec3 v1, vec3 v2, float reach)
{
  vec3 A = v0 - r.org;
  vec3 B = v1 - r.org;
  vec3 C = v2 - r.org;
  vec2 a = vec2(A[r.kx] - r.sx * A[r.kz], A[r.ky] - r.sy * A[r.kz]);
  vec2 b = vec2(B[r.kx] - r.sx * B[r.kz], B[r.ky] - r.sy * B[r.kz]);
  vec2 c = vec2(C[r.kx] - r.sx * C[r.kz], C[r.ky] - r.sy * C[r.kz]);
  float U = c.x * b.y - c.y * b.x;
  float V = a.x * c.y - a.y * c.x;
  float W = b.x * a.y - b.y * a.x;
  float side = U + V + W < 0.0 ? -1.0 : 1.0;
  // Outside an edge's line by its edge function over its length; the
  // distance to the triangle is at least the largest of these.
  float d = max(max(-side * U / length(c - b), -side * V / length(a - c)), -side * W / length(b - a));
  return !(d > 1.75 * reach);
}

// Whether the ray (local org, dir) meets triangle t of the current
// wireframe instance within [tmin, tmax] on a wire: a hit inside it where
// a wire covers it, or, for camera rays, a wire of t beside it; hit = (t,
// u, v) as intersectRayTriangle's, on the wire's edge for the latter.
bool wireHit(RayTrianglePrecomputed pre, Triangle t, vec3 org, vec3 dir, bool inside, float tmin,
  float tmax, inout vec3 hit)
{
  if (!inside && (gWireGrow < 0.0 || !mayPassWithin(pre, t.v0, t.v1, t.v2, gWireGrow)))
  {
    return false;
  }
  vec3 p0 = pixelPoint(gWireToPixels, t.v0);
  vec3 p1 = pixelPoint(gWireToPixels, t.v1);
  vec3 p2 = pixelPoint(gWireToPixels, t.v2);
  if (inside && gWireGrow < 0.0)
  {
    // Shadow and occlusion rays: where a wire crosses the triangle.
    vec2 q = projectToPixels(gWireToPixels, org + hit.x * dir);
    return wireEdgeAt(p0, p1, p2, t.cellEdges, q, gWireWidth) >= 0;
  }
  // Camera rays meet a wire at the depth of its line, as raster draws it,
  // on either side of the edge: coincident wires of faces sharing an edge
  // are then equally near, and wireWins picks one as raster does.
  vec2 q = gWirePixel;
  vec3 ends[4] = vec3[4](p0, p1, p2, p0);
  vec3 verts[4] = vec3[4](t.v0, t.v1, t.v2, t.v0);
  uint bits[3] = uint[3](kEdge01, kEdge12, kEdge20);
  bool found = false;
  for (int k = 0; k < 3; ++k)
  {
    vec3 a = ends[k];
    vec3 b = ends[k + 1];
    if ((t.cellEdges & bits[k]) == 0u || !(a.z > 0.0 && b.z > 0.0) || !wireCovers(a, b, q, gWireWidth))
    {
      continue;
    }
    float s3;
    float tx = edgePointUnder(a, b, verts[k], verts[k + 1], edgeParameter(a, b, q), org, dir, s3);
    if (tx >= tmin && tx <= tmax && (!found || tx < hit.x))
    {
      found = true;
      hit = vec3(tx, k == 0 ? s3 : (k == 1 ? 1.0 - s3 : 0.0), k == 0 ? 0.0 : (k == 1 ? s3 : 1.0 - s3));
    }
  }
  return found;
}

// The shading normal of a wire hit at local point p of triangle t, as VTK
// shades wireframe lines without normals: perpendicular to the line and
// as near the view direction (viewBack, towards the eye) as it can be.
vec3 wireNormal(int instance, Triangle t, vec3 p, vec3 viewBack)
{
  mat4 toPixels = instanceLocalToPixels(instance);
  vec3 p0 = pixelPoint(toPixels, t.v0);
  vec3 p1 = pixelPoint(toPixels, t.v1);
  vec3 p2 = pixelPoint(toPixels, t.v2);
  int k = wireEdgeAt(p0, p1, p2, t.cellEdges, projectToPixels(toPixels, p), instanceLineWidth(instance));
  vec3 a = k == 0 ? t.v0 : (k == 1 ? t.v1 : t.v2);
  vec3 b = k == 0 ? t.v1 : (k == 1 ? t.v2 : t.v0);
  mat3 linear = transpose(mat3(instanceLocalToCamera(instance, 0).xyz,
    instanceLocalToCamera(instance, 1).xyz, instanceLocalToCamera(instance, 2).xyz));
  vec3 e = normalize(linear * (b - a));
  vec3 n = viewBack - dot(viewBack, e) * e;
  return dot(n, n) > 0.0 ? normalize(n) : viewBack;
}
#endif
