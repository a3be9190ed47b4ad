#include "vtkRayTraceScene.h"

#include "vtkActor.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>

// The materials, scalar colors and textures of traced instances, as the
// raster mapper computes them.
namespace vtkrt
{
namespace pass
{

namespace
{
std::uint32_t packRGBA(const unsigned char* c, int comps)
{
  const std::uint32_t r = c[0];
  const std::uint32_t g = comps > 1 ? c[1] : c[0];
  const std::uint32_t b = comps > 2 ? c[2] : c[0];
  const std::uint32_t a = comps > 3 ? c[3] : 255u;
  return r | (g << 8) | (b << 16) | (a << 24);
}
} // namespace

/// A block color in place of the property's colors, each still weighted by
/// its coefficient. VTK 9.1's composite polydata mapper replaces the ambient
/// and diffuse colors; its glyph mapper calls the property's SetColor, which
/// replaces the specular color too.
void ApplyBlockColor(Instance& inst, vtkProperty* property, const double color[3], bool specularToo)
{
  for (int k = 0; k < 3; ++k)
  {
    inst.Ambient[k] = static_cast<float>(property->GetAmbient() * color[k]);
    inst.Diffuse[k] = static_cast<float>(property->GetDiffuse() * color[k]);
    if (specularToo)
    {
      inst.Specular[k] = static_cast<float>(property->GetSpecular() * color[k]);
    }
  }
}

void Scene::FillMaterial(vtkActor* actor, vtkMapper* mapper, Instance& inst) const
{
  vtkProperty* p = actor->GetProperty();
  double c[3];
  p->GetAmbientColor(c);
  for (int k = 0; k < 3; ++k)
  {
    inst.Ambient[k] = static_cast<float>(p->GetAmbient() * c[k]);
  }
  p->GetDiffuseColor(c);
  for (int k = 0; k < 3; ++k)
  {
    inst.Diffuse[k] = static_cast<float>(p->GetDiffuse() * c[k]);
  }
  p->GetSpecularColor(c);
  for (int k = 0; k < 3; ++k)
  {
    inst.Specular[k] = static_cast<float>(p->GetSpecular() * c[k]);
  }
  inst.SpecularPower = static_cast<float>(p->GetSpecularPower());
  inst.Lit = p->GetLighting();
  inst.AmbientIntensity = static_cast<float>(p->GetAmbient());
  inst.DiffuseIntensity = static_cast<float>(p->GetDiffuse());
  inst.CullBackfaces = p->GetBackfaceCulling();
  inst.CullFrontfaces = p->GetFrontfaceCulling();
  // vtkProperty clamps its opacity to [0, 1], which lets NaN through: that
  // draws as opaque.
  const double opacity = p->GetOpacity();
  inst.Translucent = actor->HasTranslucentPolygonalGeometry() != 0;
  inst.Opacity = opacity >= 0.0 ? static_cast<float>(std::min(opacity, 1.0)) : 1.0f;
  if (vtkProperty* back = actor->GetBackfaceProperty())
  {
    inst.BackfaceProperty = true;
    for (int k = 0; k < 3; ++k)
    {
      inst.BackAmbient[k] = static_cast<float>(back->GetAmbient() * back->GetAmbientColor()[k]);
      inst.BackDiffuse[k] = static_cast<float>(back->GetDiffuse() * back->GetDiffuseColor()[k]);
      inst.BackSpecular[k] = static_cast<float>(back->GetSpecular() * back->GetSpecularColor()[k]);
    }
    inst.BackSpecularPower = static_cast<float>(back->GetSpecularPower());
  }
  vtkMatrix4x4* m = actor->GetMatrix();
  for (int i = 0; i < 16; ++i)
  {
    inst.Matrix[i] = m->GetElement(i / 4, i % 4);
  }
  inst.ClipPlanes.clear();
  if (vtkPlaneCollection* planes = mapper->GetClippingPlanes())
  {
    for (int i = 0; i < planes->GetNumberOfItems(); ++i)
    {
      vtkPlane* plane = planes->GetItem(i);
      double n[3], o[3];
      plane->GetNormal(n);
      plane->GetOrigin(o);
      inst.ClipPlanes.push_back({ { n[0], n[1], n[2], -vtkMath::Dot(n, o) } });
    }
  }
}

bool Scene::AddTexture(vtkActor* actor, vtkPolyData* poly, Instance& inst)
{
  vtkTexture* texture = actor->GetTexture();
  if (!texture)
  {
    return true;
  }
  // Raster samples the texture at the color texture's coordinates then.
  if (inst.Color && inst.Color->Texture)
  {
    return false;
  }
  // Without 1- or 2-component texture coordinates raster draws no texture.
  const TextureEntry* coordinates = this->Textures.GetCoordinates(poly);
  if (!coordinates)
  {
    return true;
  }
  // Raster crashes on a texture without an image (VTK 9.1): drawn untextured.
  if (!TextureCache::HasImage(texture))
  {
    if (this->Textures.FirstWarning(texture))
    {
      vtkGenericWarningMacro("vtkRayTracePass: an actor's texture has no image (no input or no "
                             "scalars); the actor is traced untextured.");
    }
    return true;
  }
  const TextureEntry* image = this->Textures.GetImage(texture);
  if (!image)
  {
    return false;
  }
  inst.Texture = image;
  inst.TextureCoordinates = coordinates;
  inst.TextureOnBackface = actor->GetProperty()->GetShowTexturesOnBackface();
  return true;
}

namespace
{
/// True, with a warning, when the mapped colors (or the color texture
/// coordinates) are fewer than the points or cells they color: the
/// scalars array is shorter than its data set, raster reads past its end,
/// and the prop is drawn in its property's color instead.
bool ScalarsTooShort(vtkMapper* mapper, vtkDataSet* data, int cellFlag, vtkUnsignedCharArray* mapped,
  vtkFloatArray* coordinates)
{
  if (cellFlag == 2 || (!mapped && !coordinates))
  {
    return false; // field data: its own rules
  }
  const vtkIdType needed = cellFlag == 1 ? data->GetNumberOfCells() : data->GetNumberOfPoints();
  const vtkIdType given = mapped ? mapped->GetNumberOfTuples() : coordinates->GetNumberOfTuples();
  if (given >= needed)
  {
    return false;
  }
  int ignored = 0;
  vtkAbstractArray* scalars = vtkAbstractMapper::GetAbstractScalars(data, mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), ignored);
  const char* name = scalars && scalars->GetName() ? scalars->GetName() : "";
  vtkGenericWarningMacro("vtkRayTracePass: the scalars '"
    << name << "' of " << data->GetClassName() << " " << data << " have " << given << " tuples for " << needed
    << (cellFlag == 1 ? " cells" : " points") << ": drawn in the actor's color.");
  return true;
}
} // namespace

Colors* Scene::GetColors(vtkMapper* mapper, vtkDataSet* data, vtkMTimeType time)
{
  if (!mapper->GetScalarVisibility())
  {
    return nullptr;
  }
  vtkScalarsToColors* lut = mapper->GetLookupTable();
  time = std::max(time, mapper->GetMTime());
  if (lut)
  {
    time = std::max(time, lut->GetMTime());
  }
  auto key = std::make_pair(static_cast<const void*>(mapper), static_cast<const void*>(data));
  if (this->Keeping)
  {
    markCached(this->ColorCache, key);
    return nullptr;
  }
  auto it = this->ColorCache.find(key);
  if (it != this->ColorCache.end() && it->second->SourceTime == time)
  {
    it->second->Used = true;
    return it->second->Packed.empty() ? nullptr : it->second.get();
  }
  auto colors = std::make_unique<Colors>();
  colors->SourceTime = time;
  colors->Keep = data;
  colors->Used = true;
  // Mapped by a helper with the mapper's settings and `data` as its input:
  // vtkMapper caches its colors and color texture coordinates by its own
  // input's MTime, stale for the blocks of a composite mapper (which does
  // the same with its own per-block helpers).
  vtkNew<vtkPolyDataMapper> helper;
  helper->vtkMapper::ShallowCopy(mapper);
  helper->SetArrayName(mapper->GetArrayName());
  helper->SetArrayId(mapper->GetArrayId());
  helper->SetArrayAccessMode(mapper->GetArrayAccessMode());
  helper->SetArrayComponent(mapper->GetArrayComponent());
  helper->SetFieldDataTupleId(mapper->GetFieldDataTupleId());
  // MapScalars reads `data`; the helper's input is set where it can be (a
  // glyph mapper's points may be any data set).
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    helper->SetInputData(poly);
  }
  int cellFlag = 0;
  vtkUnsignedCharArray* mapped = helper->MapScalars(data, 1.0, cellFlag);
  // Mapping sets the shared table's range to the mapper's: that is what
  // the colors were made with, not a change to map them again for.
  if (vtkScalarsToColors* table = mapper->GetLookupTable())
  {
    colors->SourceTime = std::max(colors->SourceTime, table->GetMTime());
  }
  vtkFloatArray* coordinates = helper->GetColorCoordinates();
  vtkImageData* texture = helper->GetColorTextureMap();
  if (ScalarsTooShort(mapper, data, cellFlag, mapped, coordinates))
  {
    mapped = nullptr;
    coordinates = nullptr;
  }
  vtkUnsignedCharArray* texels =
    texture ? vtkArrayDownCast<vtkUnsignedCharArray>(texture->GetPointData()->GetScalars()) : nullptr;
  if (!mapped && cellFlag == 0 && coordinates && texels &&
    coordinates->GetNumberOfTuples() >= data->GetNumberOfPoints() && data->GetNumberOfPoints() > 0)
  {
    // InterpolateScalarsBeforeMapping: VTK's raster interpolates these
    // coordinates over each triangle and samples the texture with its
    // defaults (nearest texel, clamped to the edge; the second row is the
    // NaN color). The shader does the same.
    int dims[3];
    texture->GetDimensions(dims);
    const int comps = coordinates->GetNumberOfComponents();
    const vtkIdType n = data->GetNumberOfPoints(); // the first, one a point, as raster reads them
    const std::size_t texelCount = static_cast<std::size_t>(dims[0]) * dims[1];
    if (comps >= 1 && comps <= 2 && static_cast<std::size_t>(texels->GetNumberOfTuples()) >= texelCount)
    {
      colors->Texture = true;
      const std::size_t texelOffset = 4 + static_cast<std::size_t>(n) * comps;
      colors->Packed.reserve(texelOffset + texelCount);
      colors->Packed = { static_cast<std::uint32_t>(texelOffset),
        static_cast<std::uint32_t>(dims[0]), static_cast<std::uint32_t>(dims[1]),
        static_cast<std::uint32_t>(comps) };
      const float* c = coordinates->GetPointer(0);
      for (std::size_t i = 0; i < static_cast<std::size_t>(n) * comps; ++i)
      {
        std::uint32_t u;
        std::memcpy(&u, c + i, sizeof(u));
        colors->Packed.push_back(u);
      }
      const int texelComps = texels->GetNumberOfComponents();
      const unsigned char* t = texels->GetPointer(0);
      for (std::size_t i = 0; i < texelCount; ++i)
      {
        colors->Packed.push_back(packRGBA(t + i * texelComps, texelComps));
      }
    }
  }
  else if (mapped && cellFlag != 2 && mapped->GetNumberOfTuples() > 0)
  {
    const int comps = mapped->GetNumberOfComponents();
    const vtkIdType n = mapped->GetNumberOfTuples();
    colors->CellColors = cellFlag == 1;
    colors->Packed.resize(static_cast<std::size_t>(n));
    const unsigned char* ptr = mapped->GetPointer(0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      colors->Packed[static_cast<std::size_t>(i)] = packRGBA(ptr + i * comps, comps);
    }
  }
  else if (mapped && cellFlag == 2)
  {
    // Field data: vtkOpenGLPolyDataMapper gives every cell the color of the
    // tuple FieldDataTupleId, or with -1 cell i tuple i's (an array shorter
    // than the cells: colors past its end, left uncolored here).
    const vtkIdType tuple = mapper->GetFieldDataTupleId();
    const vtkIdType cells = data->GetNumberOfCells();
    const int comps = mapped->GetNumberOfComponents();
    if (tuple >= 0 && tuple < mapped->GetNumberOfTuples())
    {
      colors->CellColors = true;
      colors->Packed.assign(
        static_cast<std::size_t>(cells), packRGBA(mapped->GetPointer(tuple * comps), comps));
    }
    else if (tuple < 0 && mapped->GetNumberOfTuples() >= cells)
    {
      colors->CellColors = true;
      colors->Packed.resize(static_cast<std::size_t>(cells));
      for (vtkIdType i = 0; i < cells; ++i)
      {
        colors->Packed[static_cast<std::size_t>(i)] = packRGBA(mapped->GetPointer(i * comps), comps);
      }
    }
  }
  Colors* result = colors->Packed.empty() ? nullptr : colors.get();
  this->ColorCache[key] = std::move(colors);
  this->ColorsDirty = true;
  return result;
}

} // namespace pass
} // namespace vtkrt
