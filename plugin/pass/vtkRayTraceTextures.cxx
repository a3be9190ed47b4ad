#include "vtkRayTraceTextures.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProp.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>

namespace vtkrt
{
namespace pass
{

namespace
{
/// RGBA8 of a float color in [0, 1].
std::uint32_t packUnitRGBA(const float c[4])
{
  std::uint32_t word = 0;
  for (int k = 0; k < 4; ++k)
  {
    const float v = std::min(1.0f, std::max(0.0f, c[k]));
    word |= static_cast<std::uint32_t>(v * 255.0f + 0.5f) << (8 * k);
  }
  return word;
}

/// RGBA8 of a texel of 1 to 4 8-bit components, as the raster mapper
/// expands them (luminance, luminance-alpha, RGB, RGBA).
std::uint32_t packTexel(const unsigned char* c, int comps)
{
  const std::uint32_t r = c[0];
  const std::uint32_t g = comps >= 3 ? c[1] : c[0];
  const std::uint32_t b = comps >= 3 ? c[2] : c[0];
  const std::uint32_t a = comps == 2 ? c[1] : (comps >= 4 ? c[3] : 255u);
  return r | (g << 8) | (b << 16) | (a << 24);
}

/// The entry of `key` in `cache`, marked used; null when it is missing or
/// older than `time`.
TextureEntry* usedEntry(
  std::map<const void*, std::unique_ptr<TextureEntry>>& cache, const void* key, vtkMTimeType time)
{
  auto it = cache.find(key);
  if (it == cache.end() || it->second->SourceTime != time)
  {
    return nullptr;
  }
  it->second->Used = true;
  return it->second.get();
}

/// What decides a texture's image: the texture, its input and its table.
vtkMTimeType imageTime(vtkTexture* texture)
{
  vtkMTimeType time = texture->GetMTime();
  if (vtkImageData* input = texture->GetInput())
  {
    time = std::max(time, input->GetMTime());
  }
  if (vtkScalarsToColors* lut = texture->GetLookupTable())
  {
    time = std::max(time, lut->GetMTime());
  }
  return time;
}
} // namespace

std::string TextureCache::Untraceable(vtkActor* actor)
{
  vtkProperty* property = actor->GetProperty();
  if (property->GetNumberOfTextures() > 0)
  {
    return "property textures";
  }
  vtkTexture* texture = actor->GetTexture();
  if (!texture)
  {
    return std::string();
  }
  vtkInformation* keys = actor->GetPropertyKeys();
  if (texture->GetCubeMap())
  {
    return "a cube map";
  }
  if (texture->GetTransform() || (keys && keys->Has(vtkProp::GeneralTextureTransform())))
  {
    return "a texture transform";
  }
  if (texture->GetMipmap() && texture->GetInterpolate())
  {
    return "mipmaps";
  }
  if (texture->GetUseSRGBColorSpace())
  {
    return "an sRGB texture";
  }
  return std::string();
}

bool TextureCache::HasImage(vtkTexture* texture)
{
  if (vtkAlgorithm* source = texture->GetInputAlgorithm())
  {
    source->UpdateWholeExtent();
  }
  vtkImageData* input = texture->GetInput();
  vtkDataArray* scalars = input ? input->GetPointData()->GetScalars() : nullptr;
  if (input && !scalars)
  {
    scalars = input->GetCellData()->GetScalars();
  }
  return scalars && scalars->GetNumberOfTuples() > 0;
}

bool TextureCache::FirstWarning(vtkTexture* texture)
{
  vtkMTimeType& warned = this->Warned[texture];
  const bool first = warned != texture->GetMTime();
  warned = texture->GetMTime();
  return first;
}

const TextureEntry* TextureCache::GetImage(vtkTexture* texture)
{
  vtkMTimeType time = imageTime(texture);
  if (TextureEntry* entry = usedEntry(this->Images, texture, time))
  {
    return entry;
  }
  vtkImageData* input = texture->GetInput();
  vtkDataArray* scalars = input ? input->GetPointData()->GetScalars() : nullptr;
  if (input && !scalars)
  {
    scalars = input->GetCellData()->GetScalars();
  }
  if (!scalars || scalars->GetNumberOfTuples() == 0)
  {
    return nullptr;
  }
  int dims[3];
  input->GetDimensions(dims);
  if (scalars == input->GetCellData()->GetScalars())
  {
    for (int& d : dims)
    {
      d = d > 1 ? d - 1 : d;
    }
  }
  // A 2D image in any two of the three axes (as vtkOpenGLTexture reads it).
  const int width = dims[0] == 1 ? dims[1] : dims[0];
  const int height = dims[0] == 1 ? dims[2] : (dims[1] == 1 ? dims[2] : dims[1]);
  if (dims[0] > 1 && dims[1] > 1 && dims[2] > 1)
  {
    return nullptr;
  }
  const std::size_t texels = static_cast<std::size_t>(width) * height;
  const int type = scalars->GetDataType();
  const int colorMode = texture->GetColorMode();
  if (colorMode == VTK_COLOR_MODE_DIRECT_SCALARS && (type == VTK_UNSIGNED_SHORT || type == VTK_FLOAT))
  {
    return nullptr;
  }
  // As vtkOpenGLTexture: 8-bit RGB(A) as they are, the rest through the
  // texture's lookup table.
  const bool direct = colorMode != VTK_COLOR_MODE_MAP_SCALARS && type == VTK_UNSIGNED_CHAR &&
    scalars->GetNumberOfComponents() >= 3;
  const unsigned char* colors = direct
    ? static_cast<const unsigned char*>(scalars->GetVoidPointer(0))
    : texture->MapScalarsToColors(scalars);
  const int comps = direct ? std::min(4, scalars->GetNumberOfComponents()) : 4;
  const int stride = direct ? scalars->GetNumberOfComponents() : 4;
  if (!colors || static_cast<std::size_t>(scalars->GetNumberOfTuples()) < texels)
  {
    return nullptr;
  }
  auto entry = std::make_unique<TextureEntry>();
  float border[4];
  texture->GetBorderColor(border);
  const std::uint32_t mode = static_cast<std::uint32_t>(texture->GetWrap()) & kTextureWrapMask;
  entry->Packed = { static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height),
    mode | (texture->GetInterpolate() ? kTextureInterpolate : 0u), packUnitRGBA(border) };
  entry->Packed.reserve(4 + texels);
  for (std::size_t i = 0; i < texels; ++i)
  {
    const std::uint32_t texel = packTexel(colors + i * stride, comps);
    entry->CutOuts = entry->CutOuts || (texel >> 24) == 0u;
    entry->Packed.push_back(texel);
  }
  entry->SourceTime = imageTime(texture); // mapping may have set its table's range
  entry->Keep = texture;
  entry->Used = true;
  auto& slot = this->Images[texture];
  slot = std::move(entry);
  this->Dirty = true;
  return slot.get();
}

const TextureEntry* TextureCache::GetCoordinates(vtkPolyData* poly)
{
  vtkDataArray* tcoords = poly->GetPointData()->GetTCoords();
  // The first coordinates, one a point, as raster reads them by point id.
  if (!tcoords || tcoords->GetNumberOfComponents() > 2 ||
    tcoords->GetNumberOfTuples() < poly->GetNumberOfPoints())
  {
    return nullptr;
  }
  const vtkMTimeType time = std::max(poly->GetMTime(), tcoords->GetMTime());
  if (TextureEntry* entry = usedEntry(this->Coordinates, poly, time))
  {
    return entry;
  }
  auto entry = std::make_unique<TextureEntry>();
  const vtkIdType n = poly->GetNumberOfPoints();
  const bool hasT = tcoords->GetNumberOfComponents() == 2;
  entry->Packed.resize(2 * static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    const float st[2] = { static_cast<float>(tcoords->GetComponent(i, 0)),
      hasT ? static_cast<float>(tcoords->GetComponent(i, 1)) : 0.0f };
    std::memcpy(entry->Packed.data() + 2 * i, st, sizeof(st));
  }
  entry->SourceTime = time;
  entry->Keep = poly;
  entry->Used = true;
  auto& slot = this->Coordinates[poly];
  slot = std::move(entry);
  this->Dirty = true;
  return slot.get();
}

void TextureCache::BeginFrame()
{
  for (auto* cache : { &this->Images, &this->Coordinates })
  {
    for (auto& e : *cache)
    {
      e.second->Used = false;
    }
  }
}

void TextureCache::EndFrame()
{
  for (auto* cache : { &this->Images, &this->Coordinates })
  {
    for (auto it = cache->begin(); it != cache->end();)
    {
      if (it->second->Used)
      {
        ++it;
        continue;
      }
      it = cache->erase(it);
      this->Dirty = true;
    }
  }
}

void TextureCache::Clear()
{
  this->Images.clear();
  this->Coordinates.clear();
  this->Warned.clear();
  this->Dirty = true;
}

PackedTextures TextureCache::Pack() const
{
  PackedTextures out;
  for (const auto* cache : { &this->Images, &this->Coordinates })
  {
    for (const auto& e : *cache)
    {
      // Whole texels: a texel then holds two points' (s, t).
      out.Words.resize((out.Words.size() + 3) / 4 * 4, 0u);
      out.Bases[e.second.get()] = static_cast<std::uint32_t>(out.Words.size());
      out.Words.insert(out.Words.end(), e.second->Packed.begin(), e.second->Packed.end());
    }
  }
  out.Words.resize((out.Words.size() + 3) / 4 * 4, 0u);
  return out;
}

} // namespace pass
} // namespace vtkrt
