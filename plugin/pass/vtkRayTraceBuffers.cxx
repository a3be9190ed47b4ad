#include "vtkRayTraceBuffers.h"

#include "vtkRayTracePacker.h"
#include "vtkRayTraceTextures.h"

#include "vtkrt/core/HugePageArray.h"

#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>


namespace vtkrt
{
namespace pass
{

namespace
{
/// Bytes a pinned buffer has beyond its last texel: the renderer reads
/// whole vectors of texels.
constexpr std::size_t kPinnedSlack = 4096;
/// The alignment the driver asks of memory of ours it takes as storage.
constexpr std::size_t kPinnedAlignment = 4096;

/// Whether the current context renders on the CPU and takes memory of ours
/// as a buffer's storage (llvmpipe with GL_AMD_pinned_memory). A GPU's
/// driver would read such a buffer over the bus: only a CPU renderer pins.
/// VTKRT_NO_PINNED_MEMORY=1 pins nothing (the buffers a GPU driver gets,
/// mapped; for tests).
bool RendererPinsMemory()
{
  const char* noPinning = std::getenv("VTKRT_NO_PINNED_MEMORY");
  if (noPinning && *noPinning && std::strcmp(noPinning, "0") != 0)
  {
    return false;
  }
  if (!RendersOnCPU())
  {
    return false;
  }
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
  {
    const char* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (extension && std::strcmp(extension, "GL_AMD_pinned_memory") == 0)
    {
      return true;
    }
  }
  return false;
}
} // namespace

bool RendersOnCPU()
{
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
}

PinnedStorage::~PinnedStorage()
{
  this->Free();
}

void* PinnedStorage::Allocate(std::size_t bytes)
{
  this->Free();
  const std::size_t total = bytes + kPinnedSlack;
  // Huge pages for large blocks: their first touch costs far less than
  // that of 4 KiB pages (docs/benchmarks.md).
  if (core::detail::usesHugePages(total))
  {
    this->Memory = core::detail::mapHugePages(total);
  }
#if defined(__linux__)
  else if (posix_memalign(&this->Memory, kPinnedAlignment, total) != 0)
  {
    this->Memory = nullptr;
  }
#endif
  this->Bytes = this->Memory ? total : 0;
  return this->Memory;
}

void PinnedStorage::Free()
{
  if (this->Memory && core::detail::usesHugePages(this->Bytes))
  {
    core::detail::unmapHugePages(this->Memory, this->Bytes);
  }
  else
  {
    std::free(this->Memory);
  }
  this->Memory = nullptr;
  this->Bytes = 0;
}

void PinnedStorage::Swap(PinnedStorage& other) noexcept
{
  std::swap(this->Memory, other.Memory);
  std::swap(this->Bytes, other.Bytes);
}

TextureBuffer::TextureBuffer()
  : Buffer(vtkOpenGLBufferObject::New())
  , Texture(vtkTextureObject::New())
{
}

TextureBuffer::~TextureBuffer()
{
  this->Texture->Delete();
  this->Buffer->Delete();
}

std::size_t TextureBuffer::Upload(vtkOpenGLRenderWindow* win, const void* data, std::size_t texels)
{
  static const float zero[4] = { 0, 0, 0, 0 };
  const float* ptr = texels == 0 ? zero : static_cast<const float*>(data);
  const std::size_t n = texels == 0 ? 1 : texels;
  this->LeaveOwnStorage();
  this->Buffer->Upload(ptr, 4 * n, vtkOpenGLBufferObject::TextureBuffer);
  this->FreeOwnStorage();
  this->Texture->SetContext(win);
  // RGBA32UI (read by a usamplerBuffer): integer fields come back bit
  // exact, floats are reinterpreted in the shader.
  this->Texture->SetInternalFormat(GL_RGBA32UI);
  this->Texture->CreateTextureBuffer(static_cast<unsigned int>(n), 4, VTK_UNSIGNED_INT, this->Buffer);
  this->Texels = n;
  this->Capacity = n;
  return core::gpu::kTexelBytes * n;
}

void* TextureBuffer::Map(std::size_t texels, std::size_t capacity)
{
  const std::size_t n = std::max<std::size_t>({ texels, capacity, 1 });
  const std::size_t bytes = core::gpu::kTexelBytes * n;
  this->Texels = std::max<std::size_t>(texels, 1);
  this->Capacity = n;
  this->Mapped = false;
  void* storage = RendererPinsMemory() ? this->Pending.Allocate(bytes) : nullptr;
  if (!storage)
  {
    this->LeaveOwnStorage();
  }
  if (!storage && this->Buffer->GenerateBuffer(vtkOpenGLBufferObject::TextureBuffer) && this->Buffer->Bind())
  {
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_STATIC_DRAW);
    storage = glMapBufferRange(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(bytes),
      GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
    this->Buffer->Release();
    this->Mapped = storage != nullptr;
  }
  if (!storage)
  {
    this->Staging.reset(new unsigned char[bytes]);
    storage = this->Staging.get();
    // The room past the texels is uploaded too: zeros, not garbage.
    std::memset(static_cast<unsigned char*>(storage) + core::gpu::kTexelBytes * texels, 0,
      bytes - core::gpu::kTexelBytes * texels);
  }
  if (texels == 0)
  {
    std::memset(storage, 0, bytes);
  }
  return storage;
}

void* TextureBuffer::MapRange(std::size_t first, std::size_t texels)
{
  this->RangeFirst = first;
  this->RangeTexels = texels;
  this->Mapped = false;
  if (texels == 0 || first + texels > this->Capacity || this->Borrowed)
  {
    this->RangeTexels = 0;
    return nullptr;
  }
  const std::size_t offset = core::gpu::kTexelBytes * first;
  const std::size_t bytes = core::gpu::kTexelBytes * texels;
  if (this->Pinned.Data())
  {
    glFinish(); // frames in flight may still read the storage written now
    return static_cast<unsigned char*>(this->Pinned.Data()) + offset;
  }
  if (this->Buffer->Bind())
  {
    void* storage = glMapBufferRange(GL_TEXTURE_BUFFER, static_cast<GLintptr>(offset),
      static_cast<GLsizeiptr>(bytes), GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT);
    this->Buffer->Release();
    if (storage)
    {
      this->Mapped = true;
      return storage;
    }
  }
  this->Staging.reset(new unsigned char[bytes]);
  return this->Staging.get();
}

std::size_t TextureBuffer::UnmapRange()
{
  const std::size_t bytes = core::gpu::kTexelBytes * this->RangeTexels;
  if (bytes == 0 || this->Pinned.Data())
  {
    return bytes;
  }
  this->Buffer->Bind();
  if (this->Mapped)
  {
    glUnmapBuffer(GL_TEXTURE_BUFFER);
    this->Mapped = false;
  }
  else
  {
    glBufferSubData(GL_TEXTURE_BUFFER, static_cast<GLintptr>(core::gpu::kTexelBytes * this->RangeFirst),
      static_cast<GLsizeiptr>(bytes), this->Staging.get());
    this->Staging.reset();
  }
  this->Buffer->Release();
  return bytes;
}

bool TextureBuffer::Borrow(
  const void* data, std::size_t texels, std::size_t readablePastEnd, std::shared_ptr<const void> keep)
{
  const std::size_t bytes = core::gpu::kTexelBytes * texels;
  const bool fits = data && texels > 0 && reinterpret_cast<std::uintptr_t>(data) % kPinnedAlignment == 0 &&
    readablePastEnd >= kPinnedSlack;
  if (!fits || !RendererPinsMemory() || !this->AdoptStorage(data, bytes))
  {
    return false;
  }
  this->Borrowed = std::move(keep);
  this->BorrowPending = true;
  this->Texels = texels;
  this->Capacity = texels;
  this->Mapped = false;
  return true;
}

std::size_t TextureBuffer::Unmap(vtkOpenGLRenderWindow* win)
{
  const std::size_t n = this->Capacity;
  bool adopted = false;
  if (this->BorrowPending)
  {
    this->BorrowPending = false;
    adopted = true;
  }
  else if (this->Pending.Data())
  {
    adopted = this->AdoptStorage(this->Pending.Data(), core::gpu::kTexelBytes * n);
    if (adopted)
    {
      this->Pinned.Swap(this->Pending);
      this->Pending.Free();
    }
    else
    {
      this->LeaveOwnStorage();
      this->Buffer->Upload(
        static_cast<const float*>(this->Pending.Data()), 4 * n, vtkOpenGLBufferObject::TextureBuffer);
      this->Pending.Free();
    }
  }
  else if (this->Mapped)
  {
    this->Buffer->Bind();
    glUnmapBuffer(GL_TEXTURE_BUFFER);
    this->Buffer->Release();
    this->Mapped = false;
  }
  else
  {
    this->LeaveOwnStorage();
    this->Buffer->Upload(
      reinterpret_cast<const float*>(this->Staging.get()), 4 * n, vtkOpenGLBufferObject::TextureBuffer);
    this->Staging.reset();
  }
  if (!adopted)
  {
    // The buffer has storage of the driver's now: memory of ours of an
    // earlier upload is no longer what it reads (MapRange must not write there).
    this->FreeOwnStorage();
  }
  this->Texture->SetContext(win);
  this->Texture->SetInternalFormat(GL_RGBA32UI);
  this->Texture->CreateTextureBuffer(static_cast<unsigned int>(n), 4, VTK_UNSIGNED_INT, this->Buffer);
  return core::gpu::kTexelBytes * this->Texels;
}

bool TextureBuffer::AdoptStorage(const void* data, std::size_t bytes)
{
  if (!this->Buffer->GenerateBuffer(vtkOpenGLBufferObject::TextureBuffer))
  {
    return false;
  }
  vtkOpenGLClearErrorMacro(); // the next error is this call's
  glBindBuffer(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, static_cast<GLuint>(this->Buffer->GetHandle()));
  glBufferData(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
  const bool adopted = glGetError() == GL_NO_ERROR;
  glBindBuffer(GL_EXTERNAL_VIRTUAL_MEMORY_BUFFER_AMD, 0);
  if (adopted)
  {
    // The buffer no longer reads the storage it had.
    this->FreeOwnStorage();
  }
  return adopted;
}

void TextureBuffer::LeaveOwnStorage()
{
  if (this->Pinned.Data() || this->Borrowed)
  {
    this->Buffer->ReleaseGraphicsResources();
  }
}

void TextureBuffer::FreeOwnStorage()
{
  if (this->Pinned.Data() || this->Borrowed)
  {
    glFinish(); // frames in flight may still read it
  }
  this->Pinned.Free();
  this->Borrowed.reset();
}

void TextureBuffer::Release(vtkWindow* w)
{
  this->Texture->ReleaseGraphicsResources(w);
  this->Buffer->ReleaseGraphicsResources();
  this->FreeOwnStorage();
  this->Pending.Free();
  this->BorrowPending = false;
  this->Texels = 0;
  this->Capacity = 0;
}

namespace
{
/// Texels of `count` records.
template <class Record>
std::size_t texelsFor(std::size_t count)
{
  return count * core::gpu::texelsOf<Record>();
}

bool fitsLimit(std::size_t texels, std::size_t limit, const char* what, std::string& error)
{
  if (texels <= limit)
  {
    return true;
  }
  std::ostringstream s;
  s << "The ray-traced scene" << what << " needs a texture buffer of " << texels
    << " texels, more than the limit of " << limit
    << " (GL_MAX_TEXTURE_BUFFER_SIZE or MaximumTextureBufferTexels): nothing is traced.";
  error = s.str();
  return false;
}
} // namespace

namespace
{
/// Texels each geometry buffer takes for `sizes`, in GeometryBuffers() order.
std::array<std::size_t, 6> geometryTexels(const GeometrySizes& sizes)
{
  using namespace core::gpu;
  return { { texelsFor<Node>(sizes.Nodes), texelsFor<Triangle>(sizes.Triangles),
    texelsFor<core::gpu::TriangleVertices>(sizes.Triangles), sizes.SphereTexels, sizes.SphereTexels / 4,
    texelsFor<Normal>(sizes.Normals) } };
}

/// The geometry buffers' storage `p` (in GeometryBuffers() order) as records.
GeometryTargets targetsOf(const std::array<void*, 6>& p, const GeometrySizes& from)
{
  GeometryTargets out;
  out.Nodes = static_cast<core::gpu::Node*>(p[0]);
  out.Triangles = static_cast<core::gpu::Triangle*>(p[1]);
  out.TriangleVertices = static_cast<core::gpu::TriangleVertices*>(p[2]);
  out.Spheres = static_cast<core::gpu::Texel*>(p[3]);
  out.SphereIds = static_cast<std::uint32_t*>(p[4]);
  out.Normals = static_cast<core::gpu::Normal*>(p[5]);
  out.From = from;
  return out;
}
} // namespace

std::array<TextureBuffer*, 6> SceneBuffers::GeometryBuffers()
{
  return { { &this->Nodes, &this->Triangles, &this->TriangleVertices, &this->Spheres, &this->SphereIds,
    &this->Normals } };
}

bool SceneBuffers::Fits(const GeometryLayout& layout, std::size_t limit, std::string& error)
{
  for (std::size_t texels : geometryTexels(layout))
  {
    if (!fitsLimit(texels, limit, "", error))
    {
      return false;
    }
  }
  return true;
}

bool SceneBuffers::Fits(const ColorsLayout& layout, std::size_t limit, std::string& error)
{
  return fitsLimit(layout.Words / 4, limit, "'s colors", error);
}

GeometryTargets SceneBuffers::MapGeometry(const GeometryLayout& layout, GeometrySizes& capacity,
  const GeometryLoans& loans, const std::shared_ptr<const void>& keep)
{
  const std::array<std::size_t, 6> used = geometryTexels(layout);
  const std::array<TextureBuffer*, 6> buffers = this->GeometryBuffers();
  const std::array<const LentArray*, 6> lent = { { &loans.Nodes, &loans.Triangles, &loans.TriangleVertices,
    nullptr, nullptr, &loans.Normals } };
  std::array<bool, 6> borrowed{};
  for (std::size_t k = 0; k < buffers.size(); ++k)
  {
    const LentArray* loan = lent[k];
    borrowed[k] = loan && loan->Texels == used[k] &&
      buffers[k]->Borrow(loan->Data, loan->Texels, loan->ReadablePastEnd, keep);
  }
  // A borrowed buffer has no room: what shares its size appends nothing.
  capacity.Nodes = borrowed[0] ? layout.Nodes : capacity.Nodes;
  capacity.Triangles = (borrowed[1] || borrowed[2]) ? layout.Triangles : capacity.Triangles;
  capacity.Normals = borrowed[5] ? layout.Normals : capacity.Normals;
  const std::array<std::size_t, 6> room = geometryTexels(capacity);
  std::array<void*, 6> storage{};
  std::size_t borrowedTexels = 0;
  for (std::size_t k = 0; k < buffers.size(); ++k)
  {
    storage[k] = borrowed[k] ? nullptr : buffers[k]->Map(used[k], room[k]);
    borrowedTexels += borrowed[k] ? used[k] : 0;
  }
  GeometryTargets out = targetsOf(storage, GeometrySizes());
  out.BorrowedBytes = core::gpu::kTexelBytes * borrowedTexels;
  return out;
}

std::size_t SceneBuffers::UnmapGeometry(vtkOpenGLRenderWindow* win)
{
  std::size_t bytes = 0;
  for (TextureBuffer* b : this->GeometryBuffers())
  {
    bytes += b->Unmap(win);
  }
  return bytes;
}

GeometryTargets SceneBuffers::MapAppended(const GeometrySizes& from, const GeometrySizes& to)
{
  const std::array<std::size_t, 6> first = geometryTexels(from);
  const std::array<std::size_t, 6> end = geometryTexels(to);
  const std::array<TextureBuffer*, 6> buffers = this->GeometryBuffers();
  std::array<void*, 6> storage{};
  for (std::size_t k = 0; k < buffers.size(); ++k)
  {
    storage[k] = buffers[k]->MapRange(first[k], end[k] - first[k]);
  }
  return targetsOf(storage, from);
}

std::size_t SceneBuffers::UnmapAppended()
{
  std::size_t bytes = 0;
  for (TextureBuffer* b : this->GeometryBuffers())
  {
    bytes += b->UnmapRange();
  }
  return bytes;
}

std::size_t SceneBuffers::UploadTextures(vtkOpenGLRenderWindow* win, const PackedTextures& packed,
  std::size_t limit, bool& fits, std::string& error)
{
  fits = fitsLimit(packed.Words.size() / 4, limit, "'s textures", error);
  return fits ? this->Textures.Upload(win, packed.Words) : 0;
}

std::vector<vtkTextureObject*> SceneBuffers::Bind(vtkShaderProgram* program)
{
  std::vector<vtkTextureObject*> active;
  const std::pair<const char*, TextureBuffer*> samplers[] = { { "uNodes", &this->Nodes },
    { "uTriangles", &this->Triangles }, { "uTriangleVertices", &this->TriangleVertices },
    { "uSpheres", &this->Spheres }, { "uSphereIds", &this->SphereIds },
    { "uNormals", &this->Normals }, { "uColors", &this->Colors },
    { "uInstances", &this->Instances }, { "uTopNodes", &this->TopNodes },
    { "uTextures", &this->Textures }, { "uTileEntries", &this->TileEntries } };
  for (const auto& sampler : samplers)
  {
    if (program->IsUniformUsed(sampler.first))
    {
      vtkTextureObject* texture = sampler.second->GetTexture();
      texture->Activate();
      program->SetUniformi(sampler.first, texture->GetTextureUnit());
      active.push_back(texture);
    }
  }
  return active;
}

void SceneBuffers::Release(vtkWindow* w)
{
  for (TextureBuffer* b : { &this->Nodes, &this->Triangles, &this->TriangleVertices,
         &this->Spheres, &this->SphereIds, &this->Normals, &this->Colors, &this->Instances,
         &this->TopNodes, &this->Textures, &this->TileEntries })
  {
    b->Release(w);
  }
}

} // namespace pass
} // namespace vtkrt
