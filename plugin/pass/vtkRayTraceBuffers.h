// Private to vtkRayTracePass: the GPU copies of the packed scene, one
// RGBA32UI texture buffer each (read by usamplerBuffer), uploaded only when
// what they hold changed, within the texel limit.
#ifndef vtkRayTraceBuffers_h
#define vtkRayTraceBuffers_h

#include "vtkNew.h"

#include "vtkrt/core/GpuLayout.h"

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

namespace vtkrt
{
namespace pass
{
struct ColorsLayout;
struct GeometryLayout;
struct GeometryLoans;
struct GeometrySizes;
struct GeometryTargets;
struct PackedTextures;

/// Whether the current context renders on the CPU (Mesa's llvmpipe or
/// softpipe): its buffers live in our memory, its pixels run in SIMD lanes.
bool RendersOnCPU();

/// Page-aligned memory that a GL buffer may use as its own storage
/// (GL_AMD_pinned_memory); large blocks on huge pages.
class PinnedStorage
{
public:
  PinnedStorage() = default;
  ~PinnedStorage();
  PinnedStorage(const PinnedStorage&) = delete;
  PinnedStorage& operator=(const PinnedStorage&) = delete;
  /// Frees what it held and allocates `bytes` (nullptr when that fails).
  void* Allocate(std::size_t bytes);
  void Free();
  void* Data() const { return this->Memory; }
  void Swap(PinnedStorage& other) noexcept;

private:
  void* Memory = nullptr;
  std::size_t Bytes = 0;
};

/// One texture buffer of 16-byte texels.
class TextureBuffer
{
public:
  TextureBuffer();
  ~TextureBuffer();
  TextureBuffer(const TextureBuffer&) = delete;
  TextureBuffer& operator=(const TextureBuffer&) = delete;

  /// Uploads `texels` texels (an empty array gets one zero texel so the
  /// sampler is always complete). Returns the bytes uploaded.
  std::size_t Upload(vtkOpenGLRenderWindow* win, const void* data, std::size_t texels);
  template <class Record>
  std::size_t Upload(vtkOpenGLRenderWindow* win, const std::vector<Record>& records)
  {
    return this->Upload(win, records.data(), records.size() * sizeof(Record) / core::gpu::kTexelBytes);
  }
  /// Storage for `texels` texels (an empty array gets one zero texel) to
  /// write in place before Unmap(): on a CPU renderer that lends buffers
  /// user memory (llvmpipe's GL_AMD_pinned_memory), memory of ours that
  /// becomes the buffer; else the buffer's own memory mapped, or a staging
  /// array when it does not map.
  /// With `capacity` (at least `texels`), the buffer has room for that
  /// many texels, which MapRange() writes later without a new buffer.
  void* Map(std::size_t texels, std::size_t capacity = 0);
  /// Instead of Map(): takes `texels` texels at `data` as the buffer's
  /// storage as they are, no copy, where Map() would hand out memory of
  /// ours (llvmpipe) and `data` is page-aligned with enough bytes readable
  /// past its end. `keep` keeps the memory until the buffer lets go of it;
  /// nothing may write it meanwhile (the buffer has no room: MapRange()
  /// gives nothing). False when it cannot: nothing changed.
  bool Borrow(const void* data, std::size_t texels, std::size_t readablePastEnd, std::shared_ptr<const void> keep);
  /// Makes what Map() gave (or Borrow() took) the texture buffer's
  /// contents. Returns the bytes uploaded.
  std::size_t Unmap(vtkOpenGLRenderWindow* win);
  /// Storage for texels [first, first + texels) of the buffer made by
  /// Map(), within its capacity, to write before UnmapRange(); the other
  /// texels keep what they hold. Null for no texels.
  void* MapRange(std::size_t first, std::size_t texels);
  /// Makes what MapRange() gave part of the buffer. Returns the bytes uploaded.
  std::size_t UnmapRange();
  void Release(vtkWindow* w);
  std::size_t GetTexels() const { return this->Texels; }
  vtkTextureObject* GetTexture() const { return this->Texture; }

private:
  vtkOpenGLBufferObject* Buffer;
  vtkTextureObject* Texture;
  std::size_t Texels = 0;
  std::size_t Capacity = 0; ///< texels the buffer and its texture hold
  bool Mapped = false;
  std::size_t RangeFirst = 0, RangeTexels = 0; ///< MapRange()'s texels
  std::unique_ptr<unsigned char[]> Staging; ///< Map()'s storage when the buffer does not map
  PinnedStorage Pinned;  ///< the buffer's storage when it uses ours
  PinnedStorage Pending; ///< Map()'s pinned storage until Unmap()
  std::shared_ptr<const void> Borrowed; ///< keeps the storage Borrow() took
  bool BorrowPending = false;           ///< Borrow() took storage, Unmap() not called yet

  /// Makes `bytes` at `data` (page-aligned, ours) the buffer's storage;
  /// false when the driver refuses.
  bool AdoptStorage(const void* data, std::size_t bytes);
  /// Lets go of memory of ours that the buffer used as storage, once
  /// frames in flight are done with it.
  void FreeOwnStorage();
  /// Before the buffer gets storage of the driver's: a new GL buffer when
  /// the current one uses memory of ours, which glBufferData of the same
  /// size would write into (Mesa updates such a buffer in place).
  void LeaveOwnStorage();
};

/// The scene's buffers, named as the shader's samplers.
class SceneBuffers
{
public:
  TextureBuffer Nodes, Triangles, TriangleVertices, Spheres, SphereIds, Normals, Colors, Instances,
    TopNodes, Textures, TileEntries;

  /// The geometry's buffers: nodes, triangles, triangle vertices, spheres,
  /// sphere ids, normals.
  std::array<TextureBuffer*, 6> GeometryBuffers();

  /// Whether every buffer of the layout fits `limit` texels; if not,
  /// `error` says which is too large.
  static bool Fits(const GeometryLayout& layout, std::size_t limit, std::string& error);
  static bool Fits(const ColorsLayout& layout, std::size_t limit, std::string& error);

  /// The geometry buffers' storage for the layout, for WriteGeometry; then
  /// UnmapGeometry, which returns the bytes uploaded.
  /// The buffers get room for `capacity`.
  /// The buffers borrow what they can of `loans` (owned by `keep`): their
  /// targets are null and `capacity` shrinks to what they hold.
  GeometryTargets MapGeometry(const GeometryLayout& layout, GeometrySizes& capacity,
    const GeometryLoans& loans, const std::shared_ptr<const void>& keep);
  std::size_t UnmapGeometry(vtkOpenGLRenderWindow* win);
  /// The geometry buffers' storage past `from` up to `to` (both within the
  /// capacity MapGeometry gave), for WriteAppended; then UnmapAppended,
  /// which returns the bytes uploaded.
  GeometryTargets MapAppended(const GeometrySizes& from, const GeometrySizes& to);
  std::size_t UnmapAppended();
  /// Uploads the packed textures when they fit `limit` texels; otherwise
  /// `error` says so and nothing is uploaded. Returns the bytes uploaded.
  std::size_t UploadTextures(vtkOpenGLRenderWindow* win, const PackedTextures& packed,
    std::size_t limit, bool& fits, std::string& error);

  /// Activates the textures of the samplers `program` uses and points them
  /// at their units; returns the textures to deactivate after drawing.
  std::vector<vtkTextureObject*> Bind(vtkShaderProgram* program);
  void Release(vtkWindow* w);
};

} // namespace pass
} // namespace vtkrt

#endif
