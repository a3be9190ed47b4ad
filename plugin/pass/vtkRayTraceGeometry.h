// Private to vtkRayTracePass: builds one Geometry (the BVH and its
// primitives in the GPU's layout) from VTK data. No GL here.
#ifndef vtkRayTraceGeometry_h
#define vtkRayTraceGeometry_h

#include "vtkRayTraceTypes.h"

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/BVH.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/LocalFrame.h"

#include <array>
#include <functional>
#include <memory>
#include <optional>

class vtkPoints;
class vtkPolyData;

namespace vtkrt
{
namespace core
{
struct SurfaceTriangles;
}
namespace pass
{
struct RefinementInput;

/// The frame the primitives are built in: that of the finite boxes' union.
core::ScaledFrame buildFrame(std::size_t count, const std::function<core::AABB<double>(std::size_t)>& boxOf);

/// Takes a tree built in `frame`'s coordinates into `g` (nodes, moved out
/// of `bvh`, local origin and bounds); returns the origin in the frame's coordinates, or nothing
/// for an empty tree.
std::optional<core::Vec3<double>> adoptBVH(Geometry& g, core::GpuBVH& bvh, const core::ScaledFrame& frame);

/// The points as double vectors (empty for null points).
void ReadPoints(vtkPoints* pts, core::NoFillArray<core::Vec3<double>>& out);

/// What BuildTriangles (and BuildScreenSpheres, a part of it) reads of a
/// polydata: its geometry (points and cell arrays, as
/// vtkSurfaceTriangulation::GetGeometryMTime), its point and cell normals
/// and point edge flags; which objects they are and their latest MTime.
/// Scalars are not in it: a color change keeps the BVH.
struct GeometrySource
{
  std::array<const void*, 8> Parts{};
  vtkMTimeType Time = 0;
};
GeometrySource GeometrySourceOf(vtkPolyData* poly);

/// A 64-bit fingerprint of the contents GeometrySourceOf names (values,
/// types, sizes): equal fingerprints, equal geometry. 0 when an array is
/// not in one contiguous block (not worth copying to hash).
std::uint64_t GeometryFingerprint(vtkPolyData* poly);

/// The GPU tree over `triangles` whose points are `points` (in the build's
/// local frame): what BuildTriangles builds, and a background build again.
core::GpuBVH BuildTriangleBVH(const core::SurfaceTriangles& triangles,
  const core::NoFillArray<core::Vec3<double>>& points, const core::BuildOptions& options);

/// Triangles of polys (fan, as VTK's raster) and strips (VTK's winding),
/// with their VTK cell ids, point normals when the data has them, and the
/// BVH over them. With `refinement`, what a background build of a better
/// tree over the same triangles needs is moved there (RefinementInput).
std::unique_ptr<Geometry> BuildTriangles(
  vtkPolyData* poly, const core::BuildOptions& options, RefinementInput* refinement = nullptr);

/// Spheres (centers, radii, VTK point ids) and the BVH over them.
std::unique_ptr<Geometry> BuildSpheres(const std::vector<core::Vec3<double>>& centers,
  const std::vector<double>& radii, const std::vector<std::uint32_t>& ids,
  const core::BuildOptions& options);

/// Points drawn as spheres (the vertices' points, or every point of a
/// cell with the points representation): spheres of radius 0 in the GPU
/// records, their BVH over the bare centers (each frame gives the radii).
std::unique_ptr<Geometry> BuildScreenSpheres(
  vtkPolyData* poly, bool everyCellPoint, const core::BuildOptions& options);

/// Ellipsoids, each given by the affine map of world space onto its unit
/// sphere (rows of [A | b]) and its box, with their VTK point ids.
std::unique_ptr<Geometry> BuildEllipsoids(const std::vector<std::array<double, 12>>& maps,
  const std::vector<core::AABB<double>>& boxes, const std::vector<std::uint32_t>& ids,
  const core::BuildOptions& options);

} // namespace pass
} // namespace vtkrt

#endif
