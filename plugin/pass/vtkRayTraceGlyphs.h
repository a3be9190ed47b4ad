// Private to vtkRayTracePass: how a vtkGlyph3DMapper's glyphs are traced:
// whether its source is a sphere, which arrays scale and orient the glyphs,
// and each glyph as an analytic sphere or ellipsoid. No GL here.
#ifndef vtkRayTraceGlyphs_h
#define vtkRayTraceGlyphs_h

#include "vtkType.h"

#include "vtkrt/core/AABB.h"

#include <array>
#include <cstdint>
#include <vector>

class vtkDataArray;
class vtkDataSet;
class vtkGlyph3DMapper;
class vtkPolyData;

namespace vtkrt
{
namespace pass
{

/// The sphere a glyph mapper's source is: every glyph scales it.
struct GlyphSphere
{
  std::array<double, 3> Center{ { 0, 0, 0 } };
  double Radius = 0.0;
  vtkMTimeType Time = 0; ///< MTime of the source it was read from
};

/// One dataset a glyph mapper draws: its plain input, or one visible leaf
/// of its composite input, with the arrays its glyphs read.
struct GlyphSet
{
  vtkDataSet* Data = nullptr;
  vtkDataArray* Scale = nullptr; ///< null: unscaled (Scaling off or no array)
  bool PerComponent = false;     ///< scaled per component: ellipsoids
  vtkDataArray* Orientation = nullptr;
  bool HasBlockColor = false; ///< the leaf's block color replaces the property's colors
  std::array<double, 3> BlockColor{ { 0, 0, 0 } };
  unsigned int FlatIndex = 1; ///< the composite index selection reports (leaf flat index)
};

/// The glyphs of one set, ready to build: spheres (centers and radii) or,
/// scaled per component, ellipsoids (the map onto their unit sphere and
/// their boxes), with the VTK point id of each.
struct GlyphPrimitives
{
  std::vector<core::Vec3<double>> Centers;
  std::vector<double> Radii;
  std::vector<std::array<double, 12>> UnitMaps;
  std::vector<core::AABB<double>> Boxes;
  std::vector<std::uint32_t> Ids;
};

/// Whether a glyph source is a closed sphere, and which.
bool SphereOfPolyData(vtkPolyData* poly, double center[3], double& radius);

/// The scale and orientation arrays the mapper reads from `set.Data`;
/// false when the glyphs cannot be traced.
bool FindGlyphArrays(vtkGlyph3DMapper* mapper, GlyphSet& set);

/// Every unmasked, finite glyph of `set` as VTK's glyph mapper places it.
GlyphPrimitives CollectGlyphPrimitives(
  vtkGlyph3DMapper* mapper, const GlyphSphere& sphere, const GlyphSet& set);

} // namespace pass
} // namespace vtkrt

#endif
