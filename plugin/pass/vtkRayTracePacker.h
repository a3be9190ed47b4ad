// Private to vtkRayTracePass: the scene's cached geometry and colors
// concatenated into the buffers the shader reads, in the GPU's layout
// (core/GpuLayout.h): first where each geometry and colors entry goes, then
// the records written straight into the storage given. Geometry keeps its
// place from upload to upload: what changed is appended after the rest, so
// a small prop modified beside a large mesh writes only its own records.
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
  std::uint64_t Serial = 0;         ///< the Geometry placed (Geometry::Serial)
  std::uint32_t Root = 0;           ///< its root node
  std::uint32_t NormalBase = 0;     ///< its first point normal
  std::uint32_t CellNormalBase = 0; ///< its first cell normal (after its point normals)
  std::uint32_t PrimitiveBase = 0;  ///< its first triangle, or sphere texel (a multiple of 4)
};

/// The InstanceRecord::sphereCellIdBase of a placed geometry: its cell ids
/// (Geometry::SphereCellIds) follow its sphere records in the sphere buffer,
/// four a texel; 0 where it has none.
std::uint32_t SphereCellIdBase(const Geometry& g, const GeometryPlacement& place);

/// How much each geometry buffer holds (records; the sphere buffer in
/// texels), from its start.
struct GeometrySizes
{
  std::size_t Nodes = 0;
  std::size_t Triangles = 0;    ///< and triangle vertex records
  std::size_t SphereTexels = 0; ///< whole texels of ids too: one id word a sphere texel
  std::size_t Normals = 0;
};

/// What `to` holds past `from` (`to` holds at least as much everywhere).
GeometrySizes SizesPast(const GeometrySizes& from, const GeometrySizes& to);

/// Where every traced geometry goes in the upload layout, and each
/// buffer's size. Node indices are global: interior nodes index nodes,
/// leaves index their buffer's primitive slots (triangles, or texels of the
/// sphere buffer, which holds spheres and ellipsoids).
struct GeometryLayout : GeometrySizes
{
  std::map<const Geometry*, GeometryPlacement> Placements;
};

/// Storage of a layout's sizes with room to append, within `limit` texels:
/// a quarter more, at least 1024 records a buffer, and at least 32 times
/// what the last append wrote to it (a prop that changes every frame then
/// appends 32 frames or more before everything is packed anew).
GeometrySizes WithRoom(const GeometrySizes& used, std::size_t limit, const GeometrySizes& lastAppend);

/// Storage that WriteGeometry fills in place (the GPU buffers themselves,
/// from the record at `From` on): nothing is packed twice. A null pointer:
/// the buffer has its contents already (a lent array), nothing to write.
struct GeometryTargets
{
  core::gpu::Node* Nodes = nullptr;
  core::gpu::Triangle* Triangles = nullptr;
  core::gpu::TriangleVertices* TriangleVertices = nullptr;
  core::gpu::Texel* Spheres = nullptr;
  std::uint32_t* SphereIds = nullptr;
  core::gpu::Normal* Normals = nullptr;
  GeometrySizes From; ///< the records the pointers above point at
  std::size_t BorrowedBytes = 0; ///< what the buffers with null pointers hold
};

/// A cache array that is a geometry buffer's whole contents as they are.
struct LentArray
{
  const void* Data = nullptr; ///< null: nothing to lend
  std::size_t Texels = 0;
  std::size_t ReadablePastEnd = 0; ///< bytes past the last texel that may be read
};

/// What a scene of one geometry may lend the geometry buffers instead of
/// a copy (see LendableArrays).
struct GeometryLoans
{
  LentArray Nodes, Triangles, TriangleVertices, Normals;
};

/// The arrays of `sole`, the layout's only geometry, that are their
/// buffers' contents as they are: its nodes (its root and first primitive
/// are at 0, so no index moves), triangles, triangle vertices, and its
/// point or cell normals when it has only one kind. The sphere buffer is
/// padded per geometry: not lent.
GeometryLoans LendableArrays(const Geometry& sole);

/// Where a colors entry starts in the packed colors (a whole texel).
struct ColorsPlacement
{
  std::uint64_t Serial = 0; ///< the Colors placed (Colors::Serial)
  std::uint32_t Base = 0;   ///< its first word
};

/// Every colors entry, four RGBA8 (or texture header/coordinate) words per
/// texel: where each entry starts and the words in all, padded to whole
/// texels.
struct ColorsLayout
{
  std::size_t Words = 0;
  std::map<const Colors*, ColorsPlacement> Placements;
};

/// What the uploaded buffers hold, where: kept from upload to upload
/// (appends extend it), read by the instance records of every frame.
struct ScenePlacements
{
  GeometryLayout Geometry;
  ColorsLayout Colors;
  std::map<const TextureEntry*, std::uint32_t> TextureBases; ///< first words in uTextures
};

/// Node `i` of `g` as the uploaded buffer holds it at `place`: its child or
/// primitive index made global.
core::gpu::Node PlacedNode(const Geometry& g, const GeometryPlacement& place, std::size_t i);

GeometryLayout LayOutGeometry(const Scene& scene);
/// Writes every record of the layout, padding included.
void WriteGeometry(const Scene& scene, const GeometryLayout& layout, const GeometryTargets& out);

/// The scene's layout when the buffers hold `current` and have room for
/// `capacity`: geometry already there keeps its place, the rest is
/// appended (`appended`, in order). False when something does not fit the
/// room, or when what is gone would leave more than half of the buffers'
/// records unused: then a new LayOutGeometry packs everything again.
bool ExtendLayout(const Scene& scene, const GeometryLayout& current, const GeometrySizes& capacity,
  GeometryLayout& next, std::vector<const Geometry*>& appended);
/// Writes the records of `appended` (placed by `layout`, after out.From).
void WriteAppended(
  const std::vector<const Geometry*>& appended, const GeometryLayout& layout, const GeometryTargets& out);

ColorsLayout LayOutColors(const Scene& scene);
/// Writes layout.Words words, padding included.
void WriteColors(const Scene& scene, const ColorsLayout& layout, std::uint32_t* out);
/// As ExtendLayout, for the colors: `capacity` words of room.
bool ExtendColors(const Scene& scene, const ColorsLayout& current, std::size_t capacity, ColorsLayout& next,
  std::vector<const Colors*>& appended);
/// Writes the words of `appended` (placed by `layout`), padding included,
/// into `out`, which holds word `from`.
void WriteAppendedColors(
  const std::vector<const Colors*>& appended, const ColorsLayout& layout, std::uint32_t* out, std::size_t from);
/// Colors words with room to append (as WithRoom), within `limit` texels.
std::size_t ColorWordsWithRoom(std::size_t words, std::size_t limit, std::size_t lastAppend);

} // namespace pass
} // namespace vtkrt

#endif
