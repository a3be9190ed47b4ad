#include "vtkRayTraceGlyphs.h"

#include "vtkRayTraceGeometry.h"
#include "vtkRayTraceScene.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkBitArray.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkGlyph3DMapper.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkQuaternion.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace vtkrt
{
namespace pass
{

using core::Vec3;

namespace
{
/// Whether the n points of poly lie within a small relative tolerance of
/// one distance (radius) from their bounds' center.
bool PointsOnSphere(vtkPolyData* poly, vtkIdType n, double center[3], double& radius)
{
  double b[6];
  poly->GetBounds(b);
  for (int k = 0; k < 3; ++k)
  {
    center[k] = 0.5 * (b[2 * k] + b[2 * k + 1]);
  }
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    poly->GetPoint(i, p);
    const double d = std::sqrt(vtkMath::Distance2BetweenPoints(p, center));
    if (!std::isfinite(d))
    {
      return false;
    }
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  radius = 0.5 * (lo + hi);
  constexpr double relativeTolerance = 1e-4; // float coordinates of a double sphere
  return radius > 0.0 && !(hi - lo > relativeTolerance * radius);
}

/// Each point's id, or that of the first point at the same place: points
/// are compared on a grid of radius * 1e-6 (seam points computed as
/// cos(2 pi) vs cos(0) differ in their last bits).
std::vector<vtkIdType> MergedPointIds(
  vtkPolyData* poly, vtkIdType n, const double center[3], double radius)
{
  const double cellSize = radius * 1e-6;
  std::map<std::array<long long, 3>, vtkIdType> byPosition;
  std::vector<vtkIdType> merged(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    poly->GetPoint(i, p);
    const std::array<long long, 3> key{ { std::llround((p[0] - center[0]) / cellSize),
      std::llround((p[1] - center[1]) / cellSize), std::llround((p[2] - center[2]) / cellSize) } };
    merged[static_cast<std::size_t>(i)] = byPosition.emplace(key, i).first->second;
  }
  return merged;
}

/// The cosine of the widest angle a glyph source's polygon edge (a
/// triangle's diagonal aside) may subtend at its center to be traced as a
/// sphere: 45 degrees (VTK's default vtkSphereSource, 8 around), and a
/// little more for rounding.
constexpr double kWidestEdgeCosine = 0.7009; // cos(45.5 degrees)

/// Whether the polygons of poly (points merged by position, degenerate
/// polygons skipped) stay near the sphere and close it: every edge shared
/// by exactly two of them.
bool PolygonsCloseSphere(vtkPolyData* poly, const std::vector<vtkIdType>& merged,
  const double center[3], double radius)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  vtkCellArray* polys = poly->GetPolys();
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  std::vector<vtkIdType> cell;
  // A coarse polyhedron whose corners lie on a sphere (a cube, an
  // octahedron) is not one: its faces must stay near the sphere too.
  constexpr double minimumCentroidDistance = 0.85; // of the radius
  for (polys->InitTraversal(); polys->GetNextCell(count, ids);)
  {
    double centroid[3] = { 0, 0, 0 };
    for (vtkIdType k = 0; k < count; ++k)
    {
      double p[3];
      poly->GetPoint(ids[k], p);
      for (int j = 0; j < 3; ++j)
      {
        centroid[j] += (p[j] - center[j]) / static_cast<double>(count);
      }
    }
    if (count > 0 && vtkMath::Norm(centroid) < minimumCentroidDistance * radius)
    {
      return false;
    }
    // Facets no coarser than VTK's default sphere's: a polyhedral marker is
    // drawn by raster, with its facets. A triangle's widest edge is left
    // out: the diagonal that splits a sphere source's quad.
    std::vector<double> cosines;
    for (vtkIdType k = 0; k < count; ++k)
    {
      double a[3], b[3];
      poly->GetPoint(ids[k], a);
      poly->GetPoint(ids[(k + 1) % count], b);
      vtkMath::Subtract(a, center, a);
      vtkMath::Subtract(b, center, b);
      const double lengths = vtkMath::Norm(a) * vtkMath::Norm(b);
      cosines.push_back(lengths > 0.0 ? vtkMath::Dot(a, b) / lengths : 1.0);
    }
    std::sort(cosines.begin(), cosines.end());
    const std::size_t widest = count == 3 ? 1 : 0;
    if (cosines.size() > widest && cosines[widest] < kWidestEdgeCosine)
    {
      return false;
    }
    cell.clear();
    for (vtkIdType k = 0; k < count; ++k)
    {
      const vtkIdType id = merged[static_cast<std::size_t>(ids[k])];
      if (cell.empty() || cell.back() != id)
      {
        cell.push_back(id);
      }
    }
    while (cell.size() > 1 && cell.back() == cell.front())
    {
      cell.pop_back();
    }
    if (cell.size() < 3)
    {
      continue; // degenerate
    }
    for (std::size_t k = 0; k < cell.size(); ++k)
    {
      const vtkIdType a = cell[k];
      const vtkIdType c = cell[(k + 1) % cell.size()];
      ++edges[std::make_pair(std::min(a, c), std::max(a, c))];
    }
  }
  if (edges.empty())
  {
    return false;
  }
  return std::all_of(edges.begin(), edges.end(),
    [](const std::pair<const std::pair<vtkIdType, vtkIdType>, int>& e) { return e.second == 2; });
}

/// Whether a vtkSphereSource makes a sphere the pass traces: all of it
/// (a dome or a wedge is open), its edges subtending 45 degrees at most, as
/// VTK's default resolution's (8 around; 5 or more from pole to pole).
bool WholeFineSphere(vtkSphereSource* source)
{
  return source->GetStartTheta() <= 0.0 && source->GetEndTheta() >= 360.0 &&
    source->GetStartPhi() <= 0.0 && source->GetEndPhi() >= 180.0 && source->GetThetaResolution() >= 8 &&
    source->GetPhiResolution() >= 5;
}
} // namespace

/// Whether a glyph source is a closed sphere: every point within a small
/// relative tolerance of one distance from its bounds' center, no polygon
/// edge subtending more than 45 degrees, and every polygon edge shared by
/// exactly two polygons (a cap, a wedge, a polyhedron or an ellipsoid is
/// not one).
bool SphereOfPolyData(vtkPolyData* poly, double center[3], double& radius)
{
  const vtkIdType n = poly->GetNumberOfPoints();
  if (n < 4 || poly->GetNumberOfPolys() == 0 || poly->GetNumberOfStrips() > 0 ||
    poly->GetNumberOfLines() > 0 || poly->GetNumberOfVerts() > 0)
  {
    return false;
  }
  if (!PointsOnSphere(poly, n, center, radius))
  {
    return false;
  }
  // Closedness by position: points at the same place count as one (seams
  // of textured spheres), and polygons collapsed to an edge are skipped.
  const std::vector<vtkIdType> merged = MergedPointIds(poly, n, center, radius);
  return PolygonsCloseSphere(poly, merged, center, radius);
}

namespace
{
/// The rotation vtkOpenGLGlyph3DMapper gives a glyph for its orientation
/// tuple: ROTATION (degrees about z, then x, then y), DIRECTION (x axis
/// turned onto the vector by a half turn about the bisector), QUATERNION.
void glyphRotation(int mode, const double orientation[4], double rotation[3][3])
{
  vtkQuaterniond q(1.0, 0.0, 0.0, 0.0);
  if (mode == vtkGlyph3DMapper::ROTATION)
  {
    double angle = vtkMath::RadiansFromDegrees(orientation[2]);
    const vtkQuaterniond qz(std::cos(0.5 * angle), 0.0, 0.0, std::sin(0.5 * angle));
    angle = vtkMath::RadiansFromDegrees(orientation[0]);
    const vtkQuaterniond qx(std::cos(0.5 * angle), std::sin(0.5 * angle), 0.0, 0.0);
    angle = vtkMath::RadiansFromDegrees(orientation[1]);
    const vtkQuaterniond qy(std::cos(0.5 * angle), 0.0, std::sin(0.5 * angle), 0.0);
    q = qz * qx * qy;
  }
  else if (mode == vtkGlyph3DMapper::DIRECTION)
  {
    if (orientation[1] == 0.0 && orientation[2] == 0.0)
    {
      if (orientation[0] < 0.0)
      {
        q.Set(0.0, 0.0, 1.0, 0.0);
      }
    }
    else
    {
      const double magnitude = vtkMath::Norm(orientation);
      double axis[3] = { (orientation[0] + magnitude) / 2.0, orientation[1] / 2.0,
        orientation[2] / 2.0 };
      vtkMath::Normalize(axis);
      q.Set(0.0, axis[0], axis[1], axis[2]);
    }
  }
  else
  {
    q.Set(orientation[0], orientation[1], orientation[2], orientation[3]);
  }
  q.ToMatrix3x3(rotation);
}

/// The array a glyph mapper reads for `idx` (SCALE, MASK, ...), as VTK's
/// GetInputArrayToProcess would find it among the point data.
vtkDataArray* glyphArray(vtkGlyph3DMapper* mapper, int idx, vtkDataSet* input)
{
  vtkInformation* info = mapper->GetInputArrayInformation(idx);
  if (!info)
  {
    return nullptr;
  }
  vtkPointData* pd = input->GetPointData();
  if (info->Has(vtkDataObject::FIELD_NAME()))
  {
    return pd->GetArray(info->Get(vtkDataObject::FIELD_NAME()));
  }
  if (info->Has(vtkDataObject::FIELD_ATTRIBUTE_TYPE()))
  {
    return vtkDataArray::SafeDownCast(
      pd->GetAbstractAttribute(info->Get(vtkDataObject::FIELD_ATTRIBUTE_TYPE())));
  }
  return nullptr;
}

} // namespace

/// The scale and orientation arrays the mapper reads from `set.Data`, as
/// vtkOpenGLGlyph3DMapper: glyph = translate(point) * rotate(orientation) *
/// scale (only with Scaling on), applied to the source sphere. False when
/// VTK would report an error for them (left to VTK).
bool FindGlyphArrays(vtkGlyph3DMapper* mapper, GlyphSet& set)
{
  vtkDataSet* input = set.Data;
  set.Scale = mapper->GetScaling() ? glyphArray(mapper, vtkGlyph3DMapper::SCALE, input) : nullptr;
  set.PerComponent = set.Scale && mapper->GetScaleMode() == vtkGlyph3DMapper::SCALE_BY_COMPONENTS &&
    set.Scale->GetNumberOfComponents() != 1;
  if (set.PerComponent && set.Scale->GetNumberOfComponents() != 3)
  {
    return false; // VTK reports an error and draws unscaled glyphs
  }
  set.Orientation =
    mapper->GetOrient() ? glyphArray(mapper, vtkGlyph3DMapper::ORIENTATION, input) : nullptr;
  const int components = mapper->GetOrientationMode() == vtkGlyph3DMapper::QUATERNION ? 4 : 3;
  // A bit mask of several components: VTK reports an error and draws none.
  auto* mask =
    mapper->GetMasking() ? vtkArrayDownCast<vtkBitArray>(glyphArray(mapper, vtkGlyph3DMapper::MASK, input)) : nullptr;
  return (!set.Orientation || set.Orientation->GetNumberOfComponents() == components) &&
    (!mask || mask->GetNumberOfComponents() == 1);
}

namespace
{
/// Room in out for n glyphs: spheres, or ellipsoids when scaled per component.
void ReserveGlyphPrimitives(GlyphPrimitives& out, bool perComponent, vtkIdType n)
{
  if (perComponent)
  {
    out.UnitMaps.reserve(static_cast<std::size_t>(n));
    out.Boxes.reserve(static_cast<std::size_t>(n));
  }
  else
  {
    out.Centers.reserve(static_cast<std::size_t>(n));
    out.Radii.reserve(static_cast<std::size_t>(n));
  }
  out.Ids.reserve(static_cast<std::size_t>(n));
}

/// Glyph i's scale from the data (sc left as it is without a scale array or
/// with NO_DATA_SCALING): its tuple's magnitude or components, clamped to
/// the mapper's range when it clamps.
void GlyphDataScale(vtkGlyph3DMapper* mapper, vtkDataArray* scale, int scaleMode,
  bool perComponent, const double* range, double den, vtkIdType i, std::vector<double>& tuple,
  double sc[3])
{
  if (scale && scaleMode != vtkGlyph3DMapper::NO_DATA_SCALING)
  {
    scale->GetTuple(i, tuple.data());
    for (int k = 0; k < 3; ++k)
    {
      sc[k] = scaleMode == vtkGlyph3DMapper::SCALE_BY_MAGNITUDE
        ? vtkMath::Norm(tuple.data(), static_cast<int>(tuple.size()))
        : tuple[perComponent ? k : 0];
      if (mapper->GetClamping())
      {
        sc[k] = (std::min(std::max(sc[k], range[0]), range[1]) - range[0]) / den;
      }
    }
  }
}

/// The ellipsoid image of the unit sphere under l = m * r0 around center:
/// its bounding box and the map from world to unit-sphere coordinates (rows
/// of inverse(l), then the translation). False when anything is not finite.
bool GlyphEllipsoid(const double m[3][3], double r0, const Vec3<double>& center,
  std::array<double, 12>& map, core::AABB<double>& box)
{
  double l[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      l[r][c] = m[r][c] * r0;
    }
  }
  double a[3][3];
  vtkMath::Invert3x3(l, a);
  bool finite = std::isfinite(center.x) && std::isfinite(center.y) && std::isfinite(center.z);
  for (int r = 0; r < 3; ++r)
  {
    const double half = std::sqrt(l[r][0] * l[r][0] + l[r][1] * l[r][1] + l[r][2] * l[r][2]);
    box.min[r] = center[r] - half;
    box.max[r] = center[r] + half;
    map[4 * r + 0] = a[r][0];
    map[4 * r + 1] = a[r][1];
    map[4 * r + 2] = a[r][2];
    map[4 * r + 3] = -(a[r][0] * center.x + a[r][1] * center.y + a[r][2] * center.z);
    finite = finite && std::isfinite(half) && half > 0.0 && std::isfinite(map[4 * r]) &&
      std::isfinite(map[4 * r + 1]) && std::isfinite(map[4 * r + 2]);
  }
  return finite;
}
} // namespace

GlyphPrimitives CollectGlyphPrimitives(
  vtkGlyph3DMapper* mapper, const GlyphSphere& sphere, const GlyphSet& set)
{
  GlyphPrimitives out;
  vtkDataSet* input = set.Data;
  vtkDataArray* scale = set.Scale;
  const int scaleMode = mapper->GetScaleMode();
  const bool perComponent = set.PerComponent;
  vtkDataArray* orientation = set.Orientation;
  const int orientationMode = mapper->GetOrientationMode();
  const double r0 = sphere.Radius;
  const double* sourceCenter = sphere.Center.data();
  // As vtkOpenGLGlyph3DMapper: only a bit array masks (another is ignored).
  vtkBitArray* mask =
    mapper->GetMasking() ? vtkArrayDownCast<vtkBitArray>(glyphArray(mapper, vtkGlyph3DMapper::MASK, input)) : nullptr;
  const double* range = mapper->GetRange();
  double den = range[1] - range[0];
  if (den == 0.0)
  {
    den = 1.0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  ReserveGlyphPrimitives(out, perComponent, n);
  std::vector<double> tuple(scale ? scale->GetNumberOfComponents() : 1);
  double orient[4] = { 0, 0, 0, 0 };
  // Scaling off: VTK ignores the scale factor too.
  const double factor = mapper->GetScaling() ? mapper->GetScaleFactor() : 1.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (mask && i < mask->GetNumberOfTuples() && mask->GetValue(i) == 0)
    {
      continue;
    }
    double sc[3] = { 1.0, 1.0, 1.0 };
    GlyphDataScale(mapper, scale, scaleMode, perComponent, range, den, i, tuple, sc);
    // VTK makes a zero scale 1e-10: an ellipsoid with such an axis is a
    // visible flat disk, a sphere with it invisible (skipped here as
    // degenerate).
    double sk[3];
    for (int k = 0; k < 3; ++k)
    {
      sk[k] = factor * sc[k];
      sk[k] = perComponent && sk[k] == 0.0 ? 1.0e-10 : sk[k];
    }
    double rotation[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    if (orientation)
    {
      orientation->GetTuple(i, orient);
      glyphRotation(orientationMode, orient, rotation);
    }
    double m[3][3]; // rotation * scale
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        m[r][c] = rotation[r][c] * sk[c];
      }
    }
    double p[3];
    input->GetPoint(i, p);
    double offset[3];
    vtkMath::Multiply3x3(m, sourceCenter, offset);
    const Vec3<double> center(p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
    if (!perComponent)
    {
      // A sphere whatever the rotation (only its center turns with it).
      out.Centers.push_back(center);
      out.Radii.push_back(std::abs(sk[0]) * r0);
      out.Ids.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    // Ellipsoid: the image of the unit sphere under l = m * r0.
    std::array<double, 12> map;
    core::AABB<double> box;
    const bool finite = GlyphEllipsoid(m, r0, center, map, box);
    if (!finite || !(r0 > 0.0))
    {
      continue;
    }
    out.UnitMaps.push_back(map);
    out.Boxes.push_back(box);
    out.Ids.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

bool Scene::GetGlyphSphere(vtkGlyph3DMapper* mapper, GlyphSphere& sphere)
{
  if (mapper->GetNumberOfInputConnections(1) != 1 || mapper->GetSourceIndexing() ||
    mapper->GetUseSourceTableTree())
  {
    return false;
  }
  vtkAlgorithmOutput* conn = mapper->GetInputConnection(1, 0);
  vtkAlgorithm* producer = conn ? conn->GetProducer() : nullptr;
  if (!producer)
  {
    return false;
  }
  if (auto* source = vtkSphereSource::SafeDownCast(producer))
  {
    if (!WholeFineSphere(source))
    {
      return false;
    }
    sphere.Radius = source->GetRadius();
    source->GetCenter(sphere.Center.data());
    sphere.Time = source->GetMTime();
    return true;
  }
  // Any other source (a filter, SetSourceData): a sphere if its geometry
  // is one (ParaView's sphere glyphs come through its own filter).
  producer->Update(conn->GetIndex());
  vtkPolyData* source = vtkPolyData::SafeDownCast(producer->GetOutputDataObject(conn->GetIndex()));
  if (!source)
  {
    return false;
  }
  auto& cached = this->GlyphSourceCache[mapper];
  cached.Used = true;
  if (cached.Data != source || cached.Shape.Time != source->GetMTime())
  {
    cached.Data = source;
    cached.Shape.Time = source->GetMTime();
    cached.Sphere = SphereOfPolyData(source, cached.Shape.Center.data(), cached.Shape.Radius);
  }
  sphere = cached.Shape;
  return cached.Sphere;
}

bool Scene::AddGlyphs(vtkActor* actor, vtkGlyph3DMapper* mapper, int propIndex, FrameCounters& counters)
{
  // Flat shading shows the source's facets, which a traced sphere has not.
  GlyphSphere sphere;
  if (actor->GetProperty()->GetInterpolation() == VTK_FLAT || !this->GetGlyphSphere(mapper, sphere))
  {
    return false;
  }
  if (!this->Keeping)
  {
    mapper->Update();
  }
  vtkDataObject* input = mapper->GetInputDataObject(0, 0);
  std::vector<GlyphSet> sets;
  if (auto* data = vtkDataSet::SafeDownCast(input))
  {
    sets.emplace_back();
    sets.back().Data = data;
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    // As vtkOpenGLGlyph3DMapper::Render (VTK 9.1): every leaf that is a
    // dataset with points, skipped when the mapper's block attributes hide
    // that leaf (only the leaf's own entry counts: inner blocks' attributes
    // are not inherited), drawn in its block color when it has one. Block
    // opacity is ignored, as VTK's glyph mapper does.
    vtkCompositeDataDisplayAttributes* attributes = mapper->GetBlockAttributes();
    auto it = vtk::TakeSmartPointer(composite->NewIterator());
    it->SkipEmptyNodesOn();
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      vtkDataObject* leaf = it->GetCurrentDataObject();
      auto* data = vtkDataSet::SafeDownCast(leaf);
      if (!data || data->GetNumberOfPoints() == 0 ||
        (attributes && attributes->HasBlockVisibility(leaf) && !attributes->GetBlockVisibility(leaf)))
      {
        continue;
      }
      GlyphSet set;
      set.Data = data;
      set.FlatIndex = it->GetCurrentFlatIndex();
      if (attributes && attributes->HasBlockColor(leaf))
      {
        set.HasBlockColor = true;
        attributes->GetBlockColor(leaf, set.BlockColor.data());
      }
      sets.push_back(set);
    }
  }
  else
  {
    return false;
  }
  // Every set checked before any is built: one untraceable set leaves the
  // whole actor to raster.
  for (GlyphSet& set : sets)
  {
    if (!FindGlyphArrays(mapper, set))
    {
      return false;
    }
  }
  for (const GlyphSet& set : sets)
  {
    const std::size_t first = this->Instances.size();
    this->AddGlyphSet(actor, mapper, sphere, set, propIndex, counters);
    for (std::size_t i = first; i < this->Instances.size(); ++i)
    {
      this->Instances[i].CompositeIndex = set.FlatIndex;
    }
  }
  return true;
}

void Scene::AddGlyphSet(vtkActor* actor, vtkGlyph3DMapper* mapper, const GlyphSphere& sphere,
  const GlyphSet& set, int propIndex, FrameCounters& counters)
{
  vtkDataSet* input = set.Data;
  const vtkMTimeType sourceTime = sphere.Time;
  // The mapper's own MTime (its GetMTime() adds the lookup table's, which
  // colors depend on, not the spheres).
  vtkMTimeType time =
    std::max({ mapper->vtkObject::GetMTime(), input->GetMTime(), sourceTime });
  // Keyed by (mapper, dataset): each leaf of a composite input has its own
  // entry, rebuilt only when that leaf, the mapper or the source changes.
  const auto key = std::make_pair(static_cast<const void*>(mapper), static_cast<const void*>(input));
  if (this->Keeping)
  {
    if (markCached(this->SphereCache, key))
    {
      this->GetColors(mapper, input, input->GetMTime());
    }
    return;
  }
  auto& entry = this->SphereCache[key];
  if (!entry || entry->SourceTime != time || entry->Quality != this->BuildQuality)
  {
    const auto start = std::chrono::steady_clock::now();
    const GlyphPrimitives glyphs = CollectGlyphPrimitives(mapper, sphere, set);
    entry = set.PerComponent
      ? BuildEllipsoids(glyphs.UnitMaps, glyphs.Boxes, glyphs.Ids, this->SphereOptions())
      : BuildSpheres(glyphs.Centers, glyphs.Radii, glyphs.Ids, this->SphereOptions());
    counters.AddBuild(*entry, SecondsSince(start));
    entry->Quality = this->BuildQuality;
    entry->SourceTime = time;
    entry->Keep = mapper;
    entry->KeepData = input;
    this->MarkPrimitivesChanged();
  }
  entry->Used = true;
  // Id mode reports a hit as (prop index, point id within this set's
  // dataset): vtkHardwareSelector would add the leaf's flat index, which the
  // pass's id image has no channel for.
  Instance inst;
  inst.PropIndex = propIndex;
  this->FillMaterial(actor, mapper, inst);
  if (set.HasBlockColor)
  {
    ApplyBlockColor(inst, actor->GetProperty(), set.BlockColor.data(), true);
  }
  if (!entry->Empty())
  {
    inst.Geom = entry.get();
    Colors* colors = this->GetColors(mapper, input, input->GetMTime());
    // With InterpolateScalarsBeforeMapping (a color texture) VTK 9.1's
    // glyph mapper gets no colors and draws the property's color: so do we.
    inst.Color = colors && !colors->CellColors && !colors->Texture ? colors : nullptr;
    this->Instances.push_back(inst);
  }
}

} // namespace pass
} // namespace vtkrt
