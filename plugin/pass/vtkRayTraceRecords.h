// Private to vtkRayTracePass: the per-frame instance records. Each traced
// instance gets its camera-relative matrix and box (made in double on the
// CPU), its material, its places in the packed buffers and, for points drawn
// as spheres, this frame's radii; clip planes and the instances' world boxes
// (for the top level) come with them.
#ifndef vtkRayTraceRecords_h
#define vtkRayTraceRecords_h

#include "vtkRayTraceFootprint.h"
#include "vtkRayTraceTypes.h"

#include "vtkNew.h"

#include "vtkrt/core/AABB.h"

#include <array>
#include <vector>

class vtkMatrix4x4;
class vtkOpenGLCamera;
class vtkOpenGLRenderer;
class vtkCamera;
class vtkRenderer;

namespace vtkrt
{
namespace pass
{
struct ScenePlacements;

/// The frame's camera in the shader's coordinates, from VTK's own matrices
/// (the ones raster uses). Shader coordinates are (world - Origin) * Scale.
struct CameraFrame
{
  /// The shader's origin: the eye (camera-relative) or the world origin
  /// (WORLD precision mode: plain float world values).
  double Origin[3] = { 0, 0, 0 };
  /// Shader units per world unit (ViewScale): a power of two that keeps
  /// what is drawn near 1, so float products of shader coordinates
  /// (lengths, normals, lighting) neither overflow nor underflow.
  double Scale = 1.0;
  double Eye[3] = { 0, 0, 0 }; ///< in world coordinates
  double DirectionOfProjection[3] = { 0, 0, 1 };
  vtkNew<vtkMatrix4x4> CameraToClip; ///< row-major, from the shader's coordinates
  vtkNew<vtkMatrix4x4> ClipToCamera;
  /// CameraToClip with x and y times half the viewport's size in pixels:
  /// to homogeneous pixels from the viewport's center (edges are measured there).
  vtkNew<vtkMatrix4x4> CameraToPixels;
  /// The camera ray of a point of the viewport (normalized device
  /// coordinates x, y) runs from RayOrigin[0] + x RayOrigin[1] + y
  /// RayOrigin[2] (on the near plane) along RayDirection[0] + x
  /// RayDirection[1] + y RayDirection[2] (to the far plane): the rays are
  /// affine in x, y for VTK's perspective and parallel cameras. False for a
  /// projection whose rays are not (an explicit projective matrix, or an
  /// inverse too ill-conditioned to tell): the shader unprojects each pixel
  /// instead.
  bool AffineRays = true;
  double RayOrigin[3][3] = {};
  double RayDirection[3][3] = {};
  /// With affine rays, the normalized device depth of every camera ray's
  /// point at t is (RayDepth[0] + t RayDepth[1]) / (RayDepth[2] + t
  /// RayDepth[3]): clip z and w are affine along a ray, and the same at
  /// both ends of every ray (the near and far planes).
  double RayDepth[4] = { -1.0, 2.0, 1.0, 0.0 };
  /// The pixels drawn: the renderer's tiled viewport in the window, or the
  /// whole framebuffer a wrapping pass (vtkSSAAPass, vtkGaussianBlurPass,
  /// ...) hands over in the render state, as VTK's vtkCameraPass draws.
  int ViewportSize[2] = { 1, 1 };
  int ViewportOrigin[2] = { 0, 0 };

  void Set(vtkOpenGLRenderer* ren, vtkOpenGLCamera* cam, bool worldCoordinates, double scale,
    const int viewportSize[2], const int viewportOrigin[2]);
  /// The same over the renderer's tiled viewport.
  void Set(vtkOpenGLRenderer* ren, vtkOpenGLCamera* cam, bool worldCoordinates, double scale);
  /// RayOrigin, RayDirection and AffineRays from ClipToCamera.
  void SetAffineRays();

  /// The ray through (x, y) from RayOrigin and RayDirection (what the
  /// shader computes for affine rays).
  void AffineRay(double x, double y, double org[3], double dir[3]) const;

  /// The clip w of the near plane, where every camera ray starts (one value
  /// over the plane for VTK's cameras); 0 for a projection whose rays are
  /// not affine.
  double NearPlaneW() const;

  /// The near and far points of the ray through (x, y), unprojected in double.
  void UnprojectRay(double x, double y, double org[3], double dir[3]) const;

  /// A world point in shader coordinates.
  void ToShader(const double world[3], double out[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      out[k] = (world[k] - this->Origin[k]) * this->Scale;
    }
  }
};

/// The shader scale for this camera (CameraFrame::Scale): the power of
/// 2^16 that brings the far clipping distance into [2^-8, 2^8). Whatever
/// is drawn lies within it, so float holds its shader coordinates and their
/// squares; views of common sizes keep scale 1 (no constant of the shader
/// moves) and only a zoom by orders of magnitude changes it (which
/// rebuilds the top level, made in shader units).
double ViewScale(vtkCamera* cam);

/// Radii of screen-sized spheres (points drawn as spheres) for one frame.
/// VTK draws such a point PointSize pixels wide whatever its distance, so
/// the pass gives it the world radius PointSize * tan(viewAngle / 2) * z / H
/// at view depth z (perspective; H: the viewport's height in pixels) or
/// PointSize * parallelScale / H (parallel). That radius is affine in the
/// center, so the shader evaluates it per sphere from one plane, and the
/// BVH over the bare centers stays valid for every camera: its boxes grow by
/// the largest radius over the geometry's box. A camera move builds nothing.
/// Wireframes take the same bound for their wires' outer halves (plus an
/// eighth of a pixel): the boxes the shader's walk grows by.
struct ScreenSphereRadii
{
  std::array<double, 4> Plane{ { 0, 0, 0, 0 } }; ///< local radius: max(0, Plane . (c, 1))
  double MaxLocal = 0.0; ///< bound of that radius over the geometry's local box
  double MaxWorld = 0.0; ///< the same bound in world units
};

/// `localToShader`: row-major local (Geometry) to shader coordinates,
/// `eyeInShader`: the camera position in shader coordinates, `dop`: the
/// direction of projection in the rays' coordinates (CameraFrame's),
/// `shaderScale`: shader units per world unit.
ScreenSphereRadii ComputeScreenSphereRadii(const Instance& inst, vtkRenderer* ren, int viewportHeight,
  const double localToShader[16], const double eyeInShader[3], const double dop[3], double shaderScale);

/// The smallest instance size in shader units float can shade: 2^-60 (a
/// normal's squared length in shader units grows as the inverse square of
/// it times the mesh's resolution, and float ends at 2^128).
constexpr double kSmallestShadedSize = 0x1p-60;

/// The records of one frame, in instance order.
struct FrameRecords
{
  std::vector<core::gpu::InstanceRecord> Records;
  /// The root node of each record's tree as uploaded, in the records'
  /// order before a top level reorders them (a shader of one instance, which
  /// has no top level, reads its root as a frame constant, not per pixel).
  std::vector<core::gpu::Node> RootNodes;
  std::vector<float> ClipPlanes; ///< (n, d) per plane in the shader's coordinates
  /// World boxes of the instances (camera independent; grown by the largest
  /// screen-sphere radius rounded up to a power of two).
  std::vector<core::AABB<double>> WorldBoxes;
  /// The instances' outlines (their trees' upper boxes), for TracedTiles.
  std::vector<InstanceOutline> Outlines;
  /// Prop indices of instances too small in the view for float to shade
  /// (below kSmallestShadedSize: their normals' squared lengths leave
  /// float's range), each once.
  std::vector<int> TooSmallProps;

  /// A tenth of the diagonal of the world boxes' union.
  double DefaultOcclusionRadius() const;
  /// The diagonal of the traced props' world boxes.
  double SceneDiagonal() const;
};

/// Fails (returns false) only when an instance's geometry or colors have no
/// place in the uploaded buffers.
bool MakeFrameRecords(const std::vector<Instance>& instances, const ScenePlacements& places,
  const CameraFrame& camera, vtkRenderer* ren, FrameRecords& out);

/// Drops the records (with their world boxes and outlines) of the props `traced` leaves out
/// (indexed by prop index) and of unpickable instances: what a selection sees.
void KeepPickableInstances(
  const std::vector<bool>& traced, const std::vector<Instance>& instances, FrameRecords& frame);

} // namespace pass
} // namespace vtkrt

#endif
