// Private to vtkRayTracePass: actor textures (vtkActor::SetTexture) as the
// shader samples them. Each vtkTexture's image and each polydata's texture
// coordinates are made once per MTime and packed into one word buffer
// (uTextures), uploaded only when one of them changed: a camera move uploads
// nothing. No GL here.
#ifndef vtkRayTraceTextures_h
#define vtkRayTraceTextures_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkActor;
class vtkObject;
class vtkPolyData;
class vtkTexture;

namespace vtkrt
{
namespace pass
{

/// One cached entry of the texture buffer: a texture's header and texels,
/// or a polydata's texture coordinates.
struct TextureEntry
{
  vtkMTimeType SourceTime = 0;
  /// Image: width, height, mode (TextureModeBits), border RGBA8, then the
  /// RGBA8 texels row by row. Coordinates: (s, t) float bits per point.
  std::vector<std::uint32_t> Packed;
  bool CutOuts = false; ///< image: some texels fully transparent (raster discards them)
  bool Used = false;
  vtkSmartPointer<vtkObject> Keep;
};

/// Bits of an image header's mode word: vtkTexture's wrap (ClampToEdge 0,
/// Repeat 1, MirroredRepeat 2, ClampToBorder 3) and its interpolation.
enum TextureModeBits : std::uint32_t
{
  kTextureWrapMask = 3u,
  kTextureInterpolate = 4u
};

/// The texture buffer's words (entries start on whole texels) and each
/// entry's first word.
struct PackedTextures
{
  std::vector<std::uint32_t> Words;
  std::map<const TextureEntry*, std::uint32_t> Bases;
};

/// Images per vtkTexture and coordinates per polydata, cached by MTime.
class TextureCache
{
public:
  /// Why the actor's textures cannot be traced, or empty when they can (or
  /// it has none): one actor texture, 2D, untransformed, sampled without
  /// mipmaps in linear color (not sRGB), with 8-bit colors.
  static std::string Untraceable(vtkActor* actor);

  /// Whether the texture has an image with scalars (its input updated).
  static bool HasImage(vtkTexture* texture);
  /// True once per texture and MTime: whether to warn about it now.
  bool FirstWarning(vtkTexture* texture);

  /// The texture's image, made when it changed; null when the shader
  /// cannot sample it as raster does (no scalars, 3D, 16-bit or float
  /// colors).
  const TextureEntry* GetImage(vtkTexture* texture);
  /// The polydata's 1- or 2-component texture coordinates; null when it
  /// has none (raster then draws it untextured).
  const TextureEntry* GetCoordinates(vtkPolyData* poly);

  /// Frame bracket: entries no actor asked for since BeginFrame are dropped.
  void BeginFrame();
  void EndFrame();

  bool Changed() const { return this->Dirty; }
  void MarkPacked() { this->Dirty = false; }
  bool Empty() const { return this->Images.empty() && this->Coordinates.empty(); }
  void Clear();

  PackedTextures Pack() const;

private:
  std::map<const void*, std::unique_ptr<TextureEntry>> Images;
  std::map<const void*, std::unique_ptr<TextureEntry>> Coordinates;
  std::map<const void*, vtkMTimeType> Warned;
  bool Dirty = true;
};

} // namespace pass
} // namespace vtkrt

#endif
