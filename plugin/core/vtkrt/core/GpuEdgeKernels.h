// The C++ twins of the shader's edge kernels (shaders/vtkrtRayTraceEdges.glsl):
// cell edges drawn LineWidth pixels wide on traced triangles, as VTK 9.1's
// raster draws them. Everything is measured in window pixels: a local point
// goes through one matrix (local to camera, then VTK's camera-to-clip with x
// and y times half the viewport's size: cameraToPixels) to homogeneous
// pixels (x, y, w), origin at the viewport's center;
// the line through two such points is their cross product, which stays
// right when a point lies behind the eye (w <= 0). Each function has the
// GLSL function's name, arguments and float operations in its order (see
// GpuKernels.h); TestCoreGpuTwins checks them against double references.
#ifndef vtkrt_core_GpuEdgeKernels_h
#define vtkrt_core_GpuEdgeKernels_h

#include "vtkrt/core/GpuKernels.h"
#include "vtkrt/core/GpuLayout.h"

#include <glm/glm.hpp>

#include <cmath>

namespace vtkrt::core::gpu
{

using mat4 = glm::mat4;

/// Local coordinates to homogeneous pixels: rows r0..r2 of the local to
/// camera affine map, then cameraToPixels.
inline mat4 localToPixels(const vec4& r0, const vec4& r1, const vec4& r2, const mat4& cameraToPixels)
{
  return cameraToPixels * glm::transpose(mat4(r0, r1, r2, vec4(0.0f, 0.0f, 0.0f, 1.0f)));
}

/// A local point in homogeneous pixels (x, y, w).
inline vec3 pixelPoint(const mat4& toPixels, const vec3& p)
{
  const vec4 c = toPixels * vec4(p, 1.0f);
  return vec3(c.x, c.y, c.w);
}

/// Where a local point falls in the window (pixels from the viewport's center).
inline vec2 projectToPixels(const mat4& toPixels, const vec3& p)
{
  const vec3 h = pixelPoint(toPixels, p);
  return vec2(h.x, h.y) / h.z;
}

/// The homogeneous line (a, b, c: a x + b y + c = 0) through two homogeneous
/// pixel points.
inline vec3 pixelLine(const vec3& a, const vec3& b)
{
  return glm::cross(a, b);
}

/// Distance in pixels from q to the line, perpendicular to it (VTK's edge
/// equations for surfaces with edges).
inline float lineDistance(const vec3& line, const vec2& q)
{
  return std::abs(line.x * q.x + line.y * q.y + line.z) / glm::length(vec2(line.x, line.y));
}

/// Signed offset in pixels of q from the line along its minor axis (y for a
/// line nearer horizontal, else x), as OpenGL widens aliased lines.
inline float minorAxisOffset(const vec3& line, const vec2& q)
{
  const float along = std::abs(line.y) >= std::abs(line.x) ? line.y : line.x;
  return (line.x * q.x + line.y * q.y + line.z) / along;
}

/// Whether q lies within the segment a-b along its major axis (half open,
/// as a rasterized line's ends); true when an end is at or behind the eye
/// (the segment's projection is unbounded there).
inline bool withinMajorExtent(const vec3& a, const vec3& b, const vec3& line, const vec2& q)
{
  if (!(a.z > 0.0f && b.z > 0.0f))
  {
    return true;
  }
  const int axis = std::abs(line.y) >= std::abs(line.x) ? 0 : 1;
  const float pa = a[axis] / a.z;
  const float pb = b[axis] / b.z;
  return q[axis] >= std::min(pa, pb) && q[axis] < std::max(pa, pb);
}

/// VTK 9.1's surface-with-edges blend at pixel q of a triangle (homogeneous
/// pixel vertices p0..p2, cell edges `edges`): 1 on an edge, 0 away from
/// it, a one-pixel ramp between (vtkOpenGLPolyDataMapper's emix, with its
/// line width of at least 1.1).
inline float surfaceEdgeMix(
  const vec3& p0, const vec3& p1, const vec3& p2, std::uint32_t edges, const vec2& q, float lineWidth)
{
  const float width = std::max(lineWidth, 1.1f);
  const float d01 = lineDistance(pixelLine(p0, p1), q) + ((edges & kEdge01) != 0u ? 0.0f : width);
  const float d12 = lineDistance(pixelLine(p1, p2), q) + ((edges & kEdge12) != 0u ? 0.0f : width);
  const float d20 = lineDistance(pixelLine(p2, p0), q) + ((edges & kEdge20) != 0u ? 0.0f : width);
  return glm::clamp(0.5f + 0.5f * width - std::min(std::min(d01, d12), d20), 0.0f, 1.0f);
}

/// Whether the wire of edge a-b, lineWidth pixels wide (at least 1), covers
/// pixel q: within half the width along the minor axis and within the
/// segment along the major one.
inline bool wireCovers(const vec3& a, const vec3& b, const vec2& q, float lineWidth)
{
  const vec3 line = pixelLine(a, b);
  const float halfWidth = 0.5f * std::max(lineWidth, 1.0f);
  const float offset = minorAxisOffset(line, q);
  return offset >= -halfWidth && offset < halfWidth && withinMajorExtent(a, b, line, q);
}

/// The cell edge of a triangle (0: p0-p1, 1: p1-p2, 2: p2-p0) whose wire
/// covers pixel q, the nearest along the minor axis; -1 when none does.
inline int wireEdgeAt(
  const vec3& p0, const vec3& p1, const vec3& p2, std::uint32_t edges, const vec2& q, float lineWidth)
{
  int found = -1;
  float nearest = 3.0e38f;
  const vec3 ends[4] = { p0, p1, p2, p0 };
  const std::uint32_t bits[3] = { kEdge01, kEdge12, kEdge20 };
  for (int k = 0; k < 3; ++k)
  {
    if ((edges & bits[k]) != 0u && wireCovers(ends[k], ends[k + 1], q, lineWidth))
    {
      const float offset = std::abs(minorAxisOffset(pixelLine(ends[k], ends[k + 1]), q));
      if (offset < nearest)
      {
        nearest = offset;
        found = k;
      }
    }
  }
  return found;
}

/// Where pixel q falls along the projected edge a-b (0 at a, 1 at b; both
/// ends in front of the eye).
inline float edgeParameter(const vec3& a, const vec3& b, const vec2& q)
{
  const vec2 a2 = vec2(a.x, a.y) / a.z;
  const vec2 e2 = vec2(b.x, b.y) / b.z - a2;
  return glm::dot(q - a2, e2) / glm::dot(e2, e2);
}

/// The ray's t nearest the point of edge va-vb (local; a, b its homogeneous
/// pixels) at screen parameter s, clamped to the edge and made perspective
/// correct (s3: the parameter along va-vb): where a camera ray beside a
/// triangle meets the cell edge drawn there.
inline float edgePointUnder(const vec3& a, const vec3& b, const vec3& va, const vec3& vb, float s,
  const vec3& org, const vec3& dir, float& s3)
{
  s = glm::clamp(s, 0.0f, 1.0f);
  s3 = s * a.z / (s * a.z + (1.0f - s) * b.z);
  const vec3 x = va + s3 * (vb - va);
  return glm::dot(x - org, dir) / glm::dot(dir, dir);
}

/// Whether a ray that misses the triangle may pass within `reach` of it: the
/// ray origin's distance to the triangle in the watertight test's sheared
/// plane (along the ray onto the plane across its dominant axis), which is
/// at most sqrt(3) times the ray's distance to the triangle; the shader's
/// cheap reject before projecting a wireframe triangle (wireMayBeBeside).
inline bool mayPassWithin(const RayTrianglePrecomputed& r, const vec3& v0, const vec3& v1, const vec3& v2, float reach)
{
  const vec3 A = v0 - r.org;
  const vec3 B = v1 - r.org;
  const vec3 C = v2 - r.org;
  const vec2 a(A[r.kx] - r.sx * A[r.kz], A[r.ky] - r.sy * A[r.kz]);
  const vec2 b(B[r.kx] - r.sx * B[r.kz], B[r.ky] - r.sy * B[r.kz]);
  const vec2 c(C[r.kx] - r.sx * C[r.kz], C[r.ky] - r.sy * C[r.kz]);
  const float U = c.x * b.y - c.y * b.x;
  const float V = a.x * c.y - a.y * c.x;
  const float W = b.x * a.y - b.y * a.x;
  const float side = U + V + W < 0.0f ? -1.0f : 1.0f;
  const float d = std::max(std::max(-side * U / glm::length(c - b), -side * V / glm::length(a - c)),
    -side * W / glm::length(b - a));
  return !(d > 1.75f * reach);
}

} // namespace vtkrt::core::gpu

#endif
