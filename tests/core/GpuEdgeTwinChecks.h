// Checks of the edge kernels' twins (core/GpuEdgeKernels.h), part of
// TestCoreGpuTwins: pixel distances, VTK's surface-with-edges blend, the
// wires' coverage and the edge point under a pixel against double references,
// the wires' cheap reject never rejecting a ray within reach under a perspective camera
// (vertices behind the eye included), and exact values in a pixel-aligned
// orthographic view (fan diagonals blend nothing, line widths below VTK's
// minimum act as it).
#ifndef vtkrt_test_GpuEdgeTwinChecks_h
#define vtkrt_test_GpuEdgeTwinChecks_h

#include "CoreTestUtils.h"

#include "vtkrt/core/GpuEdgeKernels.h"

#include <glm/gtc/matrix_transform.hpp>

#include <iostream>

namespace vtkrt::test
{
namespace edgechecks
{
using namespace vtkrt::core;
using gpu::vec2;
using gpu::vec3;
using gpu::vec4;

/// A point of homogeneous pixels in double, projected.
inline glm::dvec2 projected(const glm::dmat4& toPixels, const glm::dvec3& p)
{
  const glm::dvec4 c = toPixels * glm::dvec4(p, 1.0);
  return glm::dvec2(c.x, c.y) / c.w;
}

/// Perpendicular distance and minor-axis offset from q to the line a-b (2D, double).
inline double distanceToLine(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& q)
{
  const glm::dvec2 d = b - a;
  return std::abs(d.x * (q.y - a.y) - d.y * (q.x - a.x)) / glm::length(d);
}
inline double minorOffset(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& q)
{
  const glm::dvec2 d = b - a;
  return std::abs(d.x) >= std::abs(d.y) ? q.y - (a.y + d.y * (q.x - a.x) / d.x)
                                        : q.x - (a.x + d.x * (q.y - a.y) / d.y);
}

/// Random triangles seen through a perspective camera, compared with double.
inline void checkAgainstDouble()
{
  Rng rng(21);
  const glm::dvec2 half(320.0, 240.0);
  const glm::dmat4 clip = glm::perspective(glm::radians(30.0), 640.0 / 480.0, 0.1, 100.0) *
    glm::lookAt(glm::dvec3(0.0), glm::dvec3(0.2, -0.1, -1.0), glm::dvec3(0.0, 1.0, 0.0));
  glm::dmat4 cameraToPixels = glm::scale(glm::dmat4(1.0), glm::dvec3(half, 1.0)) * clip;
  // Local to camera: a rotation, scale 0.5 and a shift, as an instance's.
  const glm::dmat4 localToCamera = glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, 0.1, -6.0)) *
    glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(0.3, 0.8, 0.5)) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.5));
  const glm::dmat4 rows = glm::transpose(localToCamera);
  const gpu::mat4 toPixels = gpu::localToPixels(vec4(rows[0]), vec4(rows[1]), vec4(rows[2]), gpu::mat4(cameraToPixels));
  const glm::dmat4 reference = cameraToPixels * localToCamera;
  int compared = 0, covered = 0, behind = 0;
  for (int i = 0; i < 4000; ++i)
  {
    // Some triangles reach behind the eye (local z beyond 12 is camera z > 0).
    const double reach = i % 3 == 0 ? 30.0 : 4.0;
    const glm::dvec3 v[3] = { glm::dvec3(rng.inBox(Vec3<double>(-4.0), Vec3<double>(4.0, 4.0, reach))),
      glm::dvec3(rng.inBox(Vec3<double>(-4.0), Vec3<double>(4.0))),
      glm::dvec3(rng.inBox(Vec3<double>(-4.0), Vec3<double>(4.0))) };
    double b0 = rng.uniform(), b1 = rng.uniform() * (1.0 - b0);
    const glm::dvec3 p = b0 * v[0] + b1 * v[1] + (1.0 - b0 - b1) * v[2];
    const glm::dvec4 pc = reference * glm::dvec4(p, 1.0);
    if (!(pc.w > 0.1))
    {
      continue; // the hit itself lies in front of the eye
    }
    vec3 h[3];
    glm::dvec2 s[3];
    bool anyBehind = false;
    for (int k = 0; k < 3; ++k)
    {
      h[k] = gpu::pixelPoint(toPixels, vec3(v[k]));
      s[k] = projected(reference, v[k]);
      anyBehind = anyBehind || (reference * glm::dvec4(v[k], 1.0)).w <= 0.0;
    }
    const glm::dvec2 q = projected(reference, p);
    if (std::abs(q.x) > 2.0 * half.x || std::abs(q.y) > 2.0 * half.y)
    {
      continue; // far outside the window: no pixel's ray hits there
    }
    behind += anyBehind;
    const vec2 qf = gpu::projectToPixels(toPixels, vec3(p));
    VTKRT_CHECK(glm::length(glm::dvec2(qf) - q) < 1e-2);
    for (int k = 0; k < 3; ++k)
    {
      const glm::dvec2 a = s[k], b = s[(k + 1) % 3];
      const double d = distanceToLine(a, b, q);
      if (glm::length(b - a) < 1.0 || d > 50.0)
      {
        continue; // too short or too far for float pixels to matter
      }
      const vec3 line = gpu::pixelLine(h[k], h[(k + 1) % 3]);
      VTKRT_CHECK(std::abs(gpu::lineDistance(line, qf) - d) < 2e-2);
      ++compared;
      if (std::abs(std::abs(b.x - a.x) - std::abs(b.y - a.y)) < 1e-3 * glm::length(b - a))
      {
        continue; // near 45 degrees float and double may take different minor axes
      }
      const double offset = minorOffset(a, b, q);
      VTKRT_CHECK(std::abs(gpu::minorAxisOffset(line, qf) - offset) < 3e-2);
      if (std::abs(std::abs(offset) - 1.0) > 0.05 && !anyBehind)
      {
        const bool majorX = std::abs(b.x - a.x) >= std::abs(b.y - a.y);
        const double lo = majorX ? std::min(a.x, b.x) : std::min(a.y, b.y);
        const double hi = majorX ? std::max(a.x, b.x) : std::max(a.y, b.y);
        const double along = majorX ? q.x : q.y;
        if (along > lo + 0.05 && along < hi - 0.05)
        {
          const bool want = std::abs(offset) < 1.0;
          VTKRT_CHECK(gpu::wireCovers(h[k], h[(k + 1) % 3], qf, 2.0f) == want);
          covered += want;
        }
      }
    }
    // A camera ray through the edge's point at parameter s3 (from the eye,
    // the local origin of the camera) finds that point and parameter.
    if (!anyBehind)
    {
      const double s3 = rng.uniform();
      const glm::dvec3 x = v[0] + s3 * (v[1] - v[0]);
      const glm::dvec3 eye = glm::dvec3(glm::inverse(localToCamera) * glm::dvec4(0.0, 0.0, 0.0, 1.0));
      const vec3 org(eye + 0.05 * (x - eye)), dir(x - eye);
      const vec2 qx = gpu::projectToPixels(toPixels, vec3(x));
      float s3f = 0.0f;
      const float t = gpu::edgePointUnder(h[0], h[1], vec3(v[0]), vec3(v[1]), gpu::edgeParameter(h[0], h[1], qx), org, dir, s3f);
      VTKRT_CHECK(std::abs(s3f - s3) < 1e-3 && glm::length(glm::dvec3(org + t * dir) - x) < 1e-3 * glm::length(x - eye));
    }
    // VTK's emix in double: 1.1 pixels wide, every edge a cell edge.
    const double d0 = distanceToLine(s[0], s[1], q), d1 = distanceToLine(s[1], s[2], q),
                 d2 = distanceToLine(s[2], s[0], q);
    const double mix = glm::clamp(0.5 + 0.55 - std::min({ d0, d1, d2 }), 0.0, 1.0);
    if (std::min({ glm::length(s[1] - s[0]), glm::length(s[2] - s[1]), glm::length(s[0] - s[2]) }) > 1.0)
    {
      VTKRT_CHECK(std::abs(gpu::surfaceEdgeMix(h[0], h[1], h[2], gpu::kAllEdges, qf, 1.0f) - mix) < 3e-2);
    }
  }
  std::cout << "edge twins: " << compared << " edges compared, " << covered << " covered, " << behind << " reaching behind the eye\n";
  VTKRT_CHECK(compared > 5000 && covered > 20 && behind > 100);
}

/// The cheap reject never rejects a ray passing within reach of a triangle
/// (distance in double, sampled densely), and rejects far ones.
inline void checkReject()
{
  Rng rng(22);
  int near = 0, rejected = 0;
  for (int i = 0; i < 3000; ++i)
  {
    const Vec3<double> v[3] = { rng.inBox(Vec3<double>(-1.0), Vec3<double>(1.0)),
      rng.inBox(Vec3<double>(-1.0), Vec3<double>(1.0)), rng.inBox(Vec3<double>(-1.0), Vec3<double>(1.0)) };
    const Vec3<double> from = 6.0 * rng.unitVector();
    const Vec3<double> dir = rng.inBox(Vec3<double>(-1.2), Vec3<double>(1.2)) - from;
    // The ray's distance to the triangle, over a dense set of its points.
    double distance = 1e30;
    for (int a = 0; a <= 40; ++a)
    {
      for (int b = 0; a + b <= 40; ++b)
      {
        const Vec3<double> p = v[0] + (a / 40.0) * (v[1] - v[0]) + (b / 40.0) * (v[2] - v[0]);
        const Vec3<double> d = glm::normalize(dir);
        const Vec3<double> w = p - from;
        distance = std::min(distance, glm::length(w - glm::dot(w, d) * d));
      }
    }
    const float reach = 0.1f;
    const bool may = gpu::mayPassWithin(gpu::precomputeRayTriangle(vec3(from), vec3(dir)), vec3(v[0]),
      vec3(v[1]), vec3(v[2]), reach);
    if (distance <= reach)
    {
      VTKRT_CHECK(may);
      ++near;
    }
    rejected += !may;
  }
  VTKRT_CHECK(near > 50 && rejected > 1000);
}

/// A pixel-aligned orthographic view (one local unit a pixel): exact values.
inline void checkExactValues()
{
  const gpu::mat4 toPixels = gpu::localToPixels(vec4(1, 0, 0, 0), vec4(0, 1, 0, 0), vec4(0, 0, 1, 0), gpu::mat4(1.0f));
  // The fan triangle 0 of the square (0,0) (10,0) (10,10) (0,10): its edge
  // v2-v0 is the square's diagonal, not a cell edge.
  const vec3 p0 = gpu::pixelPoint(toPixels, vec3(0, 0, 0));
  const vec3 p1 = gpu::pixelPoint(toPixels, vec3(10, 0, 0));
  const vec3 p2 = gpu::pixelPoint(toPixels, vec3(10, 10, 0));
  const std::uint32_t first = gpu::kEdge01 | gpu::kEdge12;
  VTKRT_CHECK(gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(5.0f, 0.0f), 1.0f) == 1.0f);
  VTKRT_CHECK(std::abs(gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(5.0f, 0.5f), 1.0f) - 0.55f) < 1e-6f);
  VTKRT_CHECK(gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(5.0f, 1.2f), 1.0f) == 0.0f);
  VTKRT_CHECK(gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(6.0f, 5.5f), 1.0f) == 0.0f); // near the diagonal
  VTKRT_CHECK(gpu::surfaceEdgeMix(p0, p1, p2, gpu::kAllEdges, vec2(6.0f, 5.5f), 1.0f) > 0.0f);
  // Widths under VTK's 1.1 act as 1.1 (0 and negative too); 4 pixels is 4.
  for (float w : { -3.0f, 0.0f, 0.5f })
  {
    VTKRT_CHECK(gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(5.0f, 0.5f), w) ==
      gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(5.0f, 0.5f), 1.1f));
  }
  VTKRT_CHECK(gpu::surfaceEdgeMix(p0, p1, p2, first, vec2(5.0f, 1.5f), 4.0f) == 1.0f);
  // Wires: half open along the minor axis, within the segment along the major one.
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(5.0f, 0.4f), 1.0f) == 0);
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(5.0f, 0.5f), 1.0f) == -1);
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(5.0f, 0.5f), 0.0f) == -1); // at least 1 wide
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(5.0f, 1.4f), 3.0f) == 0);
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(9.0f, 0.3f), 1.0f) == 0);
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(9.8f, 0.3f), 1.0f) == 1); // the nearer of two
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(9.8f, 5.0f), 1.0f) == 1);
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, first, vec2(6.0f, 5.8f), 1.0f) == -1); // the diagonal
  VTKRT_CHECK(gpu::wireEdgeAt(p0, p1, p2, gpu::kAllEdges, vec2(6.0f, 5.8f), 1.0f) == 2);
  VTKRT_CHECK(!gpu::wireCovers(p0, p1, vec2(10.2f, 0.0f), 1.0f)); // past the segment's end
}
} // namespace edgechecks

inline void testEdgeKernels()
{
  edgechecks::checkAgainstDouble();
  edgechecks::checkReject();
  edgechecks::checkExactValues();
}
} // namespace vtkrt::test

#endif
