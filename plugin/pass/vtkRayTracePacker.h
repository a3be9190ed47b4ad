// Private to vtkRayTracePass: the scene's cached geometry and colors
// concatenated into the buffers the shader reads, in the GPU's layout
// (core/GpuLayout.h), with each geometry's and colors entry's place in them.
// No GL here.
#ifndef vtkRayTracePacker_h
#define vtkRayTracePacker_h

#include "vtkRayTraceTypes.h"

#include <map>
#include <vector>

namespace vtkrt
{
namespace pass
{
class Scene;

/// Where a geometry's records start in the packed buffers.
struct GeometryPlacement
{
  std::uint32_t Root = 0;           ///< its root node
  std::uint32_t NormalBase = 0;     ///< its first point normal
  std::uint32_t CellNormalBase = 0; ///< its first cell normal (after its point normals)
};

/// Every traced geometry in the upload layout. Node indices are global:
/// interior nodes index nodes, leaves index their buffer's primitive slots
/// (triangles, or texels of the sphere buffer, which holds spheres and
/// ellipsoids).
struct PackedGeometry
{
  std::vector<core::gpu::Node> Nodes;
  std::vector<core::gpu::Triangle> Triangles;
  std::vector<core::gpu::TriangleVertices> TriangleVertices;
  std::vector<core::gpu::Texel> Spheres;
  std::vector<std::uint32_t> SphereIds; ///< one per sphere texel, padded to whole texels
  std::vector<core::gpu::Normal> Normals;
  std::map<const Geometry*, GeometryPlacement> Placements;
};

/// Every colors entry, four RGBA8 (or texture header/coordinate) words per
/// texel, with each entry's first word.
struct PackedColors
{
  std::vector<std::uint32_t> Words; ///< padded to whole texels
  std::map<const Colors*, std::uint32_t> Bases;
};

/// Where every geometry and colors entry of the uploaded buffers is: kept
/// from upload to upload, which the instance records of every frame read.
struct ScenePlacements
{
  std::map<const Geometry*, GeometryPlacement> GeometryPlaces;
  std::map<const Colors*, std::uint32_t> ColorBases;
  std::map<const TextureEntry*, std::uint32_t> TextureBases; ///< first words in uTextures
};

PackedGeometry PackGeometry(const Scene& scene);
PackedColors PackColors(const Scene& scene);

} // namespace pass
} // namespace vtkrt

#endif
