#include "vtkRayTraceBuffers.h"

#include "vtkRayTracePacker.h"
#include "vtkRayTraceTextures.h"

#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <sstream>
#include <utility>

namespace vtkrt
{
namespace pass
{

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
  this->Buffer->Upload(ptr, 4 * n, vtkOpenGLBufferObject::TextureBuffer);
  this->Texture->SetContext(win);
  // RGBA32UI (read by a usamplerBuffer): integer fields come back bit
  // exact, floats are reinterpreted in the shader.
  this->Texture->SetInternalFormat(GL_RGBA32UI);
  this->Texture->CreateTextureBuffer(static_cast<unsigned int>(n), 4, VTK_UNSIGNED_INT, this->Buffer);
  this->Texels = n;
  return core::gpu::kTexelBytes * n;
}

void TextureBuffer::Release(vtkWindow* w)
{
  this->Texture->ReleaseGraphicsResources(w);
  this->Buffer->ReleaseGraphicsResources();
  this->Texels = 0;
}

namespace
{
template <class Record>
std::size_t texelsIn(const std::vector<Record>& records)
{
  return records.size() * sizeof(Record) / core::gpu::kTexelBytes;
}
} // namespace

std::size_t SceneBuffers::UploadGeometry(vtkOpenGLRenderWindow* win, const PackedGeometry& packed,
  std::size_t limit, bool& fits, std::string& error)
{
  const std::size_t sizes[] = { texelsIn(packed.Nodes), texelsIn(packed.Triangles),
    texelsIn(packed.TriangleVertices), texelsIn(packed.Spheres), texelsIn(packed.SphereIds),
    texelsIn(packed.Normals) };
  fits = true;
  for (std::size_t texels : sizes)
  {
    if (texels > limit)
    {
      std::ostringstream s;
      s << "The ray-traced scene needs a texture buffer of " << texels
        << " texels, more than the limit of " << limit
        << " (GL_MAX_TEXTURE_BUFFER_SIZE or MaximumTextureBufferTexels): nothing is traced.";
      error = s.str();
      fits = false;
      return 0;
    }
  }
  std::size_t bytes = 0;
  bytes += this->Nodes.Upload(win, packed.Nodes);
  bytes += this->Triangles.Upload(win, packed.Triangles);
  bytes += this->TriangleVertices.Upload(win, packed.TriangleVertices);
  bytes += this->Spheres.Upload(win, packed.Spheres);
  bytes += this->SphereIds.Upload(win, packed.SphereIds);
  bytes += this->Normals.Upload(win, packed.Normals);
  return bytes;
}

std::size_t SceneBuffers::UploadColors(vtkOpenGLRenderWindow* win, const PackedColors& packed,
  std::size_t limit, bool& fits, std::string& error)
{
  const std::size_t texels = texelsIn(packed.Words);
  fits = texels <= limit;
  if (!fits)
  {
    std::ostringstream s;
    s << "The ray-traced scene's colors need " << texels << " texels, more than the limit of "
      << limit << ": nothing is traced.";
    error = s.str();
    return 0;
  }
  return this->Colors.Upload(win, packed.Words);
}

std::size_t SceneBuffers::UploadTextures(vtkOpenGLRenderWindow* win, const PackedTextures& packed,
  std::size_t limit, bool& fits, std::string& error)
{
  const std::size_t texels = texelsIn(packed.Words);
  fits = texels <= limit;
  if (!fits)
  {
    std::ostringstream s;
    s << "The ray-traced scene's textures need " << texels << " texels, more than the limit of "
      << limit << ": nothing is traced.";
    error = s.str();
    return 0;
  }
  return this->Textures.Upload(win, packed.Words);
}

std::vector<vtkTextureObject*> SceneBuffers::Bind(vtkShaderProgram* program)
{
  std::vector<vtkTextureObject*> active;
  const std::pair<const char*, TextureBuffer*> samplers[] = { { "uNodes", &this->Nodes },
    { "uTriangles", &this->Triangles }, { "uTriangleVertices", &this->TriangleVertices },
    { "uSpheres", &this->Spheres }, { "uSphereIds", &this->SphereIds },
    { "uNormals", &this->Normals }, { "uColors", &this->Colors },
    { "uInstances", &this->Instances }, { "uTopNodes", &this->TopNodes },
    { "uTextures", &this->Textures } };
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
         &this->TopNodes, &this->Textures })
  {
    b->Release(w);
  }
}

} // namespace pass
} // namespace vtkrt
