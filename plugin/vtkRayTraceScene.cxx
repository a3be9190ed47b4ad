#include "vtkRayTraceScene.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataObjectTree.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDataSet.h"
#include "vtkFloatArray.h"
#include "vtkGlyph3DMapper.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkQuaternion.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include "vtkrt/core/LocalFrame.h"
#include "vtkrt/core/Mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

namespace vtkrt
{
namespace pass
{

namespace
{
using core::Vec3;

std::uint32_t packRGBA(const unsigned char* c, int comps)
{
  const std::uint32_t r = c[0];
  const std::uint32_t g = comps > 1 ? c[1] : c[0];
  const std::uint32_t b = comps > 2 ? c[2] : c[0];
  const std::uint32_t a = comps > 3 ? c[3] : 255u;
  return r | (g << 8) | (b << 16) | (a << 24);
}

float bitsOf(std::uint32_t u)
{
  return core::uintBitsToFloat(u);
}

void readPoints(vtkPoints* pts, std::vector<Vec3<double>>& out)
{
  const vtkIdType n = pts ? pts->GetNumberOfPoints() : 0;
  out.resize(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    pts->GetPoint(i, &out[static_cast<std::size_t>(i)].x);
  }
}

/// Takes a freshly built BVH into `g`: its skipped-primitive count and, when
/// it is not empty, the local origin (the center of what is traced: NaN
/// primitives are not in the tree), the bounds relative to it and the packed
/// nodes. Returns the origin, or nothing for an empty tree.
std::optional<Vec3<double>> adoptBVH(Geometry& g, const core::BVH& bvh)
{
  g.SkippedPrimitives = bvh.stats.skippedPrimitives;
  if (bvh.empty())
  {
    return std::nullopt;
  }
  const core::AABB<double> b = bvh.bounds();
  const Vec3<double> origin = b.center();
  g.Origin = { { origin.x, origin.y, origin.z } };
  for (int k = 0; k < 3; ++k)
  {
    g.LocalBounds[2 * k] = b.min[k] - g.Origin[k];
    g.LocalBounds[2 * k + 1] = b.max[k] - g.Origin[k];
  }
  g.Nodes = core::packNodesForGpu(bvh, origin);
  return origin;
}

/// The polydata's verts/lines cells decide whether the pass can trace it.
bool hasUntraceableCells(vtkPolyData* poly, bool pointsAsSpheres)
{
  if (poly->GetNumberOfLines() > 0)
  {
    return true;
  }
  return poly->GetNumberOfVerts() > 0 && !pointsAsSpheres;
}

/// Triangles of polys (fan, as VTK's raster) and strips (VTK's winding),
/// with their VTK cell ids, and the BVH over them.
std::unique_ptr<Geometry> buildTriangles(vtkPolyData* poly, const core::BuildOptions& options)
{
  auto g = std::make_unique<Geometry>();
  std::vector<Vec3<double>> points;
  readPoints(poly->GetPoints(), points);
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> cellIds;
  vtkIdType cellId = poly->GetNumberOfVerts() + poly->GetNumberOfLines();
  vtkIdType npts;
  const vtkIdType* pts;
  auto polys = vtk::TakeSmartPointer(poly->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell(), ++cellId)
  {
    polys->GetCurrentCell(npts, pts);
    for (vtkIdType k = 1; k + 1 < npts; ++k)
    {
      indices.insert(indices.end(), { std::uint32_t(pts[0]), std::uint32_t(pts[k]), std::uint32_t(pts[k + 1]) });
      cellIds.push_back(std::uint32_t(cellId));
    }
  }
  auto strips = vtk::TakeSmartPointer(poly->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell(), ++cellId)
  {
    strips->GetCurrentCell(npts, pts);
    for (vtkIdType i = 0; i + 2 < npts; ++i)
    {
      indices.insert(indices.end(),
        { std::uint32_t(pts[i]), std::uint32_t(pts[i + 1 + i % 2]), std::uint32_t(pts[i + 1 + (i + 1) % 2]) });
      cellIds.push_back(std::uint32_t(cellId));
    }
  }

  core::TriangleMesh<double> mesh(points, indices);
  core::BVH bvh = core::buildTriangleBVH(mesh, options);
  g->Spheres = false;
  g->VertexCount = points.size();
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh);
  if (!adopted)
  {
    return g;
  }
  const Vec3<double> origin = *adopted;
  const std::vector<Vec3<float>> rel = core::relativeFloatPoints(points.data(), points.size(), origin);
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->Primitives.resize(12 * n);
  g->TriangleVertices.resize(4 * n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::uint32_t tri = bvh.primIndex[k];
    float* o = g->Primitives.data() + 12 * k;
    float* iv = g->TriangleVertices.data() + 4 * k;
    for (int v = 0; v < 3; ++v)
    {
      const std::uint32_t vi = indices[3 * tri + v];
      o[4 * v + 0] = rel[vi].x;
      o[4 * v + 1] = rel[vi].y;
      o[4 * v + 2] = rel[vi].z;
      o[4 * v + 3] = 0.0f;
      iv[v] = bitsOf(vi);
    }
    o[3] = bitsOf(cellIds[tri]);
    iv[3] = 0.0f;
  }
  if (vtkDataArray* normals = poly->GetPointData()->GetNormals())
  {
    if (normals->GetNumberOfComponents() == 3 &&
      normals->GetNumberOfTuples() == static_cast<vtkIdType>(points.size()))
    {
      g->Normals.resize(4 * points.size());
      double nv[3];
      for (std::size_t i = 0; i < points.size(); ++i)
      {
        normals->GetTuple(static_cast<vtkIdType>(i), nv);
        g->Normals[4 * i + 0] = static_cast<float>(nv[0]);
        g->Normals[4 * i + 1] = static_cast<float>(nv[1]);
        g->Normals[4 * i + 2] = static_cast<float>(nv[2]);
        g->Normals[4 * i + 3] = 0.0f;
      }
    }
  }
  return g;
}

/// Whether a glyph source is a closed sphere: every point within a small
/// relative tolerance of one distance from its bounds' center, and every
/// polygon edge shared by exactly two polygons (a cap, a wedge or an
/// ellipsoid is not one).
bool sphereOfPolyData(vtkPolyData* poly, double center[3], double& radius)
{
  const vtkIdType n = poly->GetNumberOfPoints();
  if (n < 4 || poly->GetNumberOfPolys() == 0 || poly->GetNumberOfStrips() > 0 ||
    poly->GetNumberOfLines() > 0 || poly->GetNumberOfVerts() > 0)
  {
    return false;
  }
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
  if (!(radius > 0.0) || hi - lo > relativeTolerance * radius)
  {
    return false;
  }
  // Closedness by position: points at the same place count as one (seams
  // of textured spheres), and polygons collapsed to an edge are skipped.
  // Positions are compared on a grid of radius * 1e-6 (seam points computed
  // as cos(2 pi) vs cos(0) differ in their last bits).
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

/// Spheres (centers, radii, VTK point ids) and the BVH over them.
std::unique_ptr<Geometry> buildSpheres(const std::vector<Vec3<double>>& centers,
  const std::vector<double>& radii, const std::vector<std::uint32_t>& ids,
  const core::BuildOptions& options)
{
  auto g = std::make_unique<Geometry>();
  g->Spheres = true;
  core::SphereSet<double> set(centers, radii);
  core::BVH bvh = core::buildSphereBVH(set, options);
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh);
  if (!adopted)
  {
    return g;
  }
  const Vec3<double> origin = *adopted;
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->Primitives.resize(4 * n);
  g->SphereIds.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::uint32_t s = bvh.primIndex[k];
    const Vec3<double> c = centers[s] - origin;
    float* o = g->Primitives.data() + 4 * k;
    o[0] = static_cast<float>(c.x);
    o[1] = static_cast<float>(c.y);
    o[2] = static_cast<float>(c.z);
    o[3] = static_cast<float>(radii[s]);
    g->SphereIds[k] = ids[s];
  }
  return g;
}

/// Ellipsoids, each given by the affine map of world space onto its unit
/// sphere (rows of [A | b]) and its box, with their VTK point ids. Each takes
/// three texels (the map's rows, relative to the local origin), so leaf
/// indices count texels: primitive k of a leaf starts at index + 3 k; ids
/// are repeated per texel (the shader indexes them by texel).
std::unique_ptr<Geometry> buildEllipsoids(const std::vector<std::array<double, 12>>& maps,
  const std::vector<core::AABB<double>>& boxes, const std::vector<std::uint32_t>& ids,
  const core::BuildOptions& options)
{
  auto g = std::make_unique<Geometry>();
  g->Spheres = true;
  g->Ellipsoids = true;
  core::BVH bvh = core::buildBVH(boxes, options);
  const std::optional<Vec3<double>> adopted = adoptBVH(*g, bvh);
  if (!adopted)
  {
    return g;
  }
  const Vec3<double> origin = *adopted;
  for (std::size_t i = 0; i < g->Nodes.size(); i += 8)
  {
    if (core::floatBitsToUint(g->Nodes[i + 7]) > 0)
    {
      g->Nodes[i + 3] = bitsOf(3 * core::floatBitsToUint(g->Nodes[i + 3]));
    }
  }
  const std::size_t n = bvh.primIndex.size();
  g->PrimitiveCount = n;
  g->Primitives.resize(12 * n);
  g->SphereIds.resize(3 * n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::array<double, 12>& m = maps[bvh.primIndex[k]];
    float* o = g->Primitives.data() + 12 * k;
    for (int r = 0; r < 3; ++r)
    {
      o[4 * r + 0] = static_cast<float>(m[4 * r + 0]);
      o[4 * r + 1] = static_cast<float>(m[4 * r + 1]);
      o[4 * r + 2] = static_cast<float>(m[4 * r + 2]);
      o[4 * r + 3] = static_cast<float>(m[4 * r + 3] + m[4 * r + 0] * origin.x +
        m[4 * r + 1] * origin.y + m[4 * r + 2] * origin.z);
      g->SphereIds[3 * k + r] = ids[bvh.primIndex[k]];
    }
  }
  return g;
}

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

/// The scale and orientation arrays the mapper reads from `set.Data`, as
/// vtkOpenGLGlyph3DMapper: glyph = translate(point) * rotate(orientation) *
/// scale (only with Scaling on), applied to the source sphere. False when
/// VTK would report an error for them (left to VTK).
bool findGlyphArrays(vtkGlyph3DMapper* mapper, GlyphSet& set)
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
  return !set.Orientation || set.Orientation->GetNumberOfComponents() == components;
}

/// A block color in place of the property's colors, each still weighted by
/// its coefficient. VTK 9.1's composite polydata mapper replaces the ambient
/// and diffuse colors; its glyph mapper calls the property's SetColor, which
/// replaces the specular color too.
void applyBlockColor(Instance& inst, vtkProperty* property, const double color[3], bool specularToo)
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

/// A cache entry's "used this frame" flag (entries held by pointer or by value).
template <class T>
bool& usedFlag(std::unique_ptr<T>& entry)
{
  return entry->Used;
}
template <class T>
bool& usedFlag(T& entry)
{
  return entry.Used;
}

/// Marks every entry of a cache unused (the frame's props mark theirs).
template <class Cache>
void markUnused(Cache& cache)
{
  for (auto& e : cache)
  {
    usedFlag(e.second) = false;
  }
}

/// Drops the entries no prop used this frame; returns whether any went.
template <class Cache>
bool dropUnused(Cache& cache)
{
  bool dropped = false;
  for (auto it = cache.begin(); it != cache.end();)
  {
    if (usedFlag(it->second))
    {
      ++it;
      continue;
    }
    it = cache.erase(it);
    dropped = true;
  }
  return dropped;
}

/// A polydata leaf of a composite input with its inherited block color.
struct Piece
{
  vtkPolyData* Poly;
  bool HasColor;
  std::array<double, 3> Color;
};

/// Walks a composite dataset as vtkCompositePolyDataMapper2 does: block
/// visibility, color and opacity apply to the block and everything below
/// it. Returns false when something cannot be traced (a translucent block,
/// a non-polydata leaf).
bool collectPieces(vtkDataObject* object, vtkCompositeDataDisplayAttributes* attributes,
  bool visible, double opacity, Piece inherited, std::vector<Piece>& pieces)
{
  if (!object)
  {
    return true;
  }
  if (attributes)
  {
    if (attributes->HasBlockVisibility(object))
    {
      visible = attributes->GetBlockVisibility(object);
    }
    if (attributes->HasBlockOpacity(object))
    {
      opacity = attributes->GetBlockOpacity(object);
    }
    if (attributes->HasBlockColor(object))
    {
      inherited.HasColor = true;
      attributes->GetBlockColor(object, inherited.Color.data());
    }
  }
  if (auto* poly = vtkPolyData::SafeDownCast(object))
  {
    if (!visible)
    {
      return true;
    }
    if (opacity < 1.0)
    {
      return false;
    }
    inherited.Poly = poly;
    pieces.push_back(inherited);
    return true;
  }
  if (auto* tree = vtkDataObjectTree::SafeDownCast(object))
  {
    auto it = vtk::TakeSmartPointer(tree->NewTreeIterator());
    it->TraverseSubTreeOff();
    it->VisitOnlyLeavesOff();
    bool ok = true;
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      ok = collectPieces(it->GetCurrentDataObject(), attributes, visible, opacity, inherited, pieces) && ok;
    }
    return ok;
  }
  return false;
}

} // namespace

std::string Features::Key() const
{
  std::ostringstream s;
  s << "T" << this->Triangles << "S" << this->Spheres << "N" << this->VertexNormals << "C"
    << this->Colors << "P" << this->ClipPlanes << "L" << this->Lights << "x"
    << this->LightComplexity << "I" << this->IdMode << "D" << this->Fp64 << "X"
    << this->TopLevel << "A" << this->SamplesPerPixel << "H" << this->Shadows << "O"
    << this->AmbientOcclusionSamples << "M" << this->MaximumTraversalSteps << "W"
    << this->WorldCoordinates << "Q" << this->ScreenSpheres << "E" << this->Ellipsoids << "X"
    << this->ColorTexture;
  return s.str();
}

bool Scene::IsTraceable(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  if (!actor || !actor->GetVisibility() || !actor->GetMapper())
  {
    return false;
  }
  vtkMapper* mapper = actor->GetMapper();
  const bool glyphs = vtkGlyph3DMapper::SafeDownCast(mapper) != nullptr;
  if (!glyphs && !vtkPolyDataMapper::SafeDownCast(mapper) &&
    !vtkCompositePolyDataMapper::SafeDownCast(mapper))
  {
    return false;
  }
  vtkProperty* property = actor->GetProperty();
  if (property->GetOpacity() < 1.0 || actor->GetTexture() || property->GetNumberOfTextures() > 0 ||
    property->GetEdgeVisibility() || actor->GetBackfaceProperty() ||
    property->GetBackfaceCulling() || property->GetFrontfaceCulling() ||
    property->GetInterpolation() == VTK_PBR)
  {
    return false;
  }
  const int representation = property->GetRepresentation();
  if (representation == VTK_WIREFRAME ||
    (representation == VTK_POINTS && (glyphs || !property->GetRenderPointsAsSpheres())))
  {
    return false;
  }
  // Translucent scalars (colors with alpha) or a forced translucency.
  return !actor->HasTranslucentPolygonalGeometry();
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

Colors* Scene::GetColors(vtkMapper* mapper, vtkPolyData* data, vtkMTimeType time)
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
  helper->SetInputData(data);
  int cellFlag = 0;
  vtkUnsignedCharArray* mapped = helper->MapScalars(data, 1.0, cellFlag);
  vtkFloatArray* coordinates = helper->GetColorCoordinates();
  vtkImageData* texture = helper->GetColorTextureMap();
  vtkUnsignedCharArray* texels =
    texture ? vtkArrayDownCast<vtkUnsignedCharArray>(texture->GetPointData()->GetScalars()) : nullptr;
  if (!mapped && cellFlag == 0 && coordinates && texels &&
    coordinates->GetNumberOfTuples() == data->GetNumberOfPoints() && data->GetNumberOfPoints() > 0)
  {
    // InterpolateScalarsBeforeMapping: VTK's raster interpolates these
    // coordinates over each triangle and samples the texture with its
    // defaults (nearest texel, clamped to the edge; the second row is the
    // NaN color). The shader does the same.
    int dims[3];
    texture->GetDimensions(dims);
    const int comps = coordinates->GetNumberOfComponents();
    const vtkIdType n = coordinates->GetNumberOfTuples();
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
  Colors* result = colors->Packed.empty() ? nullptr : colors.get();
  this->ColorCache[key] = std::move(colors);
  this->ColorsDirty = true;
  return result;
}

bool Scene::AddPolyData(vtkActor* actor, vtkMapper* mapper, vtkPolyData* poly, int propIndex,
  vtkRenderer* ren, FrameCounters& counters, const double* blockColor)
{
  vtkProperty* property = actor->GetProperty();
  const bool pointsAsSpheres = property->GetRenderPointsAsSpheres() &&
    (property->GetRepresentation() == VTK_POINTS || poly->GetNumberOfVerts() > 0);
  const vtkMTimeType time = poly->GetMTime();
  Instance inst;
  inst.PropIndex = propIndex;
  this->FillMaterial(actor, mapper, inst);
  if (blockColor)
  {
    applyBlockColor(inst, property, blockColor, false);
  }

  if (property->GetRepresentation() == VTK_SURFACE &&
    (poly->GetNumberOfPolys() > 0 || poly->GetNumberOfStrips() > 0))
  {
    auto& entry = this->TriangleCache[poly];
    if (!entry || entry->SourceTime != time || entry->Quality != this->BuildQuality ||
      entry->LeafSize != this->LeafSize)
    {
      entry = buildTriangles(poly, this->Options());
      entry->Quality = this->BuildQuality;
      entry->LeafSize = this->LeafSize;
      entry->SourceTime = time;
      entry->Keep = poly;
      ++counters.BVHBuilds;
      this->GeometryDirty = true;
    }
    if (!entry->Used)
    {
      entry->Used = true;
    }
    if (!entry->Empty())
    {
      Instance tri = inst;
      tri.Geom = entry.get();
      tri.Color = this->GetColors(mapper, poly, time);
      tri.UseVertexNormals = !entry->Normals.empty() && property->GetInterpolation() != VTK_FLAT;
      this->Instances.push_back(tri);
    }
  }

  if (pointsAsSpheres)
  {
    // VTK draws these PointSize pixels wide at any distance: the BVH is
    // over the bare centers, the radii come with each frame's camera
    // (ScreenSphereRadii), so neither a camera move nor a new point size
    // rebuilds anything.
    std::ostringstream key;
    key << "points:" << property->GetRepresentation();
    auto& entry = this->SphereCache[std::make_pair(static_cast<const void*>(poly), nullptr)];
    if (!entry || entry->SourceTime != time || entry->SourceKey != key.str() ||
      entry->Quality != this->BuildQuality)
    {
      std::vector<Vec3<double>> all;
      readPoints(poly->GetPoints(), all);
      std::vector<char> used(all.size(), 0);
      vtkIdType npts;
      const vtkIdType* pts;
      auto mark = [&](vtkCellArray* cells) {
        auto it = vtk::TakeSmartPointer(cells->NewIterator());
        for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
        {
          it->GetCurrentCell(npts, pts);
          for (vtkIdType k = 0; k < npts; ++k)
          {
            if (pts[k] >= 0 && static_cast<std::size_t>(pts[k]) < used.size())
            {
              used[static_cast<std::size_t>(pts[k])] = 1;
            }
          }
        }
      };
      mark(poly->GetVerts());
      if (property->GetRepresentation() == VTK_POINTS)
      {
        mark(poly->GetPolys());
        mark(poly->GetStrips());
        mark(poly->GetLines());
      }
      std::vector<Vec3<double>> centers;
      std::vector<double> radii;
      std::vector<std::uint32_t> ids;
      for (std::size_t i = 0; i < all.size(); ++i)
      {
        if (used[i])
        {
          centers.push_back(all[i]);
          ids.push_back(static_cast<std::uint32_t>(i));
        }
      }
      // Bare centers: the smallest radius the builder accepts (boxes of
      // points); the shader adds each frame's radius.
      radii.assign(centers.size(), std::numeric_limits<double>::min());
      entry = buildSpheres(centers, radii, ids, this->SphereOptions());
      entry->ScreenSized = true;
      for (std::size_t k = 3; k < entry->Primitives.size(); k += 4)
      {
        entry->Primitives[k] = 0.0f;
      }
      entry->Quality = this->BuildQuality;
      entry->SourceTime = time;
      entry->SourceKey = key.str();
      entry->Keep = poly;
      ++counters.BVHBuilds;
      this->GeometryDirty = true;
    }
    entry->Used = true;
    if (!entry->Empty())
    {
      Instance sph = inst;
      sph.Geom = entry.get();
      sph.PointSize = std::max(0.0, static_cast<double>(property->GetPointSize()));
      Colors* colors = this->GetColors(mapper, poly, time);
      sph.Color = colors && !colors->CellColors ? colors : nullptr;
      this->Instances.push_back(sph);
    }
  }
  return true;
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
    cached.Sphere = sphereOfPolyData(source, cached.Shape.Center.data(), cached.Shape.Radius);
  }
  sphere = cached.Shape;
  return cached.Sphere;
}

bool Scene::AddGlyphs(vtkActor* actor, vtkGlyph3DMapper* mapper, int propIndex, FrameCounters& counters)
{
  GlyphSphere sphere;
  if (!this->GetGlyphSphere(mapper, sphere))
  {
    return false;
  }
  mapper->Update();
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
    if (!findGlyphArrays(mapper, set))
    {
      return false;
    }
  }
  for (const GlyphSet& set : sets)
  {
    this->AddGlyphSet(actor, mapper, sphere, set, propIndex, counters);
  }
  return true;
}

void Scene::AddGlyphSet(vtkActor* actor, vtkGlyph3DMapper* mapper, const GlyphSphere& sphere,
  const GlyphSet& set, int propIndex, FrameCounters& counters)
{
  vtkDataSet* input = set.Data;
  vtkDataArray* scale = set.Scale;
  const int scaleMode = mapper->GetScaleMode();
  const bool perComponent = set.PerComponent;
  vtkDataArray* orientation = set.Orientation;
  const int orientationMode = mapper->GetOrientationMode();
  const double r0 = sphere.Radius;
  const double* sourceCenter = sphere.Center.data();
  const vtkMTimeType sourceTime = sphere.Time;
  // The mapper's own MTime (its GetMTime() adds the lookup table's, which
  // colors depend on, not the spheres).
  vtkMTimeType time =
    std::max({ mapper->vtkObject::GetMTime(), input->GetMTime(), sourceTime });
  // Keyed by (mapper, dataset): each leaf of a composite input has its own
  // entry, rebuilt only when that leaf, the mapper or the source changes.
  auto& entry = this->SphereCache[std::make_pair(
    static_cast<const void*>(mapper), static_cast<const void*>(input))];
  if (!entry || entry->SourceTime != time || entry->Quality != this->BuildQuality)
  {
    vtkDataArray* mask = mapper->GetMasking() ? glyphArray(mapper, vtkGlyph3DMapper::MASK, input) : nullptr;
    const double* range = mapper->GetRange();
    double den = range[1] - range[0];
    if (den == 0.0)
    {
      den = 1.0;
    }
    const vtkIdType n = input->GetNumberOfPoints();
    std::vector<Vec3<double>> centers;
    std::vector<double> radii;
    std::vector<std::uint32_t> ids;
    std::vector<std::array<double, 12>> unitMaps; // ellipsoids
    std::vector<core::AABB<double>> boxes;        // ellipsoids
    if (perComponent)
    {
      unitMaps.reserve(static_cast<std::size_t>(n));
      boxes.reserve(static_cast<std::size_t>(n));
    }
    else
    {
      centers.reserve(static_cast<std::size_t>(n));
      radii.reserve(static_cast<std::size_t>(n));
    }
    ids.reserve(static_cast<std::size_t>(n));
    std::vector<double> tuple(scale ? scale->GetNumberOfComponents() : 1);
    double orient[4] = { 0, 0, 0, 0 };
    // Scaling off: VTK ignores the scale factor too.
    const double factor = mapper->GetScaling() ? mapper->GetScaleFactor() : 1.0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (mask && mask->GetComponent(i, 0) == 0.0)
      {
        continue;
      }
      double sc[3] = { 1.0, 1.0, 1.0 };
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
        centers.push_back(center);
        radii.push_back(std::abs(sk[0]) * r0);
        ids.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      // Ellipsoid: the image of the unit sphere under l = m * r0.
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
      std::array<double, 12> map;
      core::AABB<double> box;
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
      if (!finite || !(r0 > 0.0))
      {
        continue;
      }
      unitMaps.push_back(map);
      boxes.push_back(box);
      ids.push_back(static_cast<std::uint32_t>(i));
    }
    entry = perComponent ? buildEllipsoids(unitMaps, boxes, ids, this->SphereOptions())
                         : buildSpheres(centers, radii, ids, this->SphereOptions());
    entry->Quality = this->BuildQuality;
    entry->SourceTime = time;
    entry->Keep = mapper;
    entry->KeepData = input;
    ++counters.BVHBuilds;
    this->GeometryDirty = true;
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
    applyBlockColor(inst, actor->GetProperty(), set.BlockColor.data(), true);
  }
  if (!entry->Empty())
  {
    inst.Geom = entry.get();
    vtkPolyData* asPoly = vtkPolyData::SafeDownCast(input);
    Colors* colors = nullptr;
    if (asPoly)
    {
      colors = this->GetColors(mapper, asPoly, input->GetMTime());
    }
    // With InterpolateScalarsBeforeMapping (a color texture) VTK 9.1's
    // glyph mapper gets no colors and draws the property's color: so do we.
    inst.Color = colors && !colors->CellColors && !colors->Texture ? colors : nullptr;
    this->Instances.push_back(inst);
  }
}

void Scene::Extract(vtkRenderer* ren, vtkProp** props, int count, std::vector<vtkProp*>& traced,
  std::vector<vtkProp*>& others, FrameCounters& counters)
{
  traced.clear();
  others.clear();
  this->Instances.clear();
  markUnused(this->TriangleCache);
  markUnused(this->SphereCache);
  markUnused(this->ColorCache);
  markUnused(this->GlyphSourceCache);

  for (int i = 0; i < count; ++i)
  {
    vtkProp* prop = props[i];
    if (!IsTraceable(prop))
    {
      others.push_back(prop);
      continue;
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    vtkMapper* mapper = actor->GetMapper();
    const int propIndex = static_cast<int>(traced.size());
    const std::size_t firstInstance = this->Instances.size();
    bool ok = false;
    if (auto* glyphs = vtkGlyph3DMapper::SafeDownCast(mapper))
    {
      ok = this->AddGlyphs(actor, glyphs, propIndex, counters);
    }
    else
    {
      mapper->Update();
      vtkDataObject* input = mapper->GetInputDataObject(0, 0);
      const bool pointsAsSpheres = actor->GetProperty()->GetRenderPointsAsSpheres();
      std::vector<Piece> pieces;
      ok = true;
      if (auto* poly = vtkPolyData::SafeDownCast(input))
      {
        pieces.push_back({ poly, false, { { 0, 0, 0 } } });
      }
      else if (vtkCompositeDataSet::SafeDownCast(input))
      {
        vtkCompositeDataDisplayAttributes* attributes = nullptr;
        if (auto* m2 = vtkCompositePolyDataMapper2::SafeDownCast(mapper))
        {
          attributes = m2->GetCompositeDataDisplayAttributes();
        }
        Piece root{ nullptr, false, { { 0, 0, 0 } } };
        ok = collectPieces(input, attributes, true, 1.0, root, pieces);
      }
      else if (input)
      {
        ok = false;
      }
      for (const Piece& piece : pieces)
      {
        ok = ok && !hasUntraceableCells(piece.Poly, pointsAsSpheres);
      }
      if (ok)
      {
        for (const Piece& piece : pieces)
        {
          this->AddPolyData(actor, mapper, piece.Poly, propIndex, ren, counters,
            piece.HasColor ? piece.Color.data() : nullptr);
        }
      }
    }
    if (ok)
    {
      traced.push_back(prop);
    }
    else
    {
      this->Instances.resize(firstInstance);
      others.push_back(prop);
    }
  }

  // Forget what no prop uses any more.
  const bool trianglesDropped = dropUnused(this->TriangleCache);
  const bool spheresDropped = dropUnused(this->SphereCache);
  this->GeometryDirty = this->GeometryDirty || trianglesDropped || spheresDropped;
  this->ColorsDirty = dropUnused(this->ColorCache) || this->ColorsDirty;
  dropUnused(this->GlyphSourceCache);
  counters.TracedInstances = static_cast<int>(this->Instances.size());
  for (const Instance& inst : this->Instances)
  {
    counters.TracedPrimitives += inst.Geom->PrimitiveCount;
  }
}

void Scene::PackGeometry(std::vector<float>& nodes, std::vector<float>& triangles,
  std::vector<float>& triangleVertices, std::vector<float>& spheres, std::vector<float>& sphereIds,
  std::vector<float>& normals)
{
  nodes.clear();
  triangles.clear();
  triangleVertices.clear();
  spheres.clear();
  sphereIds.clear();
  normals.clear();
  std::vector<std::uint32_t> ids;
  auto place = [&](Geometry& g) {
    g.NodeBase = static_cast<std::uint32_t>(nodes.size() / 8);
    if (g.Spheres)
    {
      g.PrimitiveBase = static_cast<std::uint32_t>(spheres.size() / 4);
      spheres.insert(spheres.end(), g.Primitives.begin(), g.Primitives.end());
      ids.insert(ids.end(), g.SphereIds.begin(), g.SphereIds.end());
    }
    else
    {
      g.PrimitiveBase = static_cast<std::uint32_t>(triangles.size() / 12);
      triangles.insert(triangles.end(), g.Primitives.begin(), g.Primitives.end());
      triangleVertices.insert(triangleVertices.end(), g.TriangleVertices.begin(), g.TriangleVertices.end());
      g.NormalBase = static_cast<std::uint32_t>(normals.size() / 4);
      normals.insert(normals.end(), g.Normals.begin(), g.Normals.end());
    }
    const std::size_t first = nodes.size();
    nodes.insert(nodes.end(), g.Nodes.begin(), g.Nodes.end());
    // Local child / primitive indices become global ones.
    for (std::size_t i = first; i < nodes.size(); i += 8)
    {
      const std::uint32_t index = core::floatBitsToUint(nodes[i + 3]);
      const std::uint32_t count = core::floatBitsToUint(nodes[i + 7]);
      nodes[i + 3] = bitsOf(index + (count == 0 ? g.NodeBase : g.PrimitiveBase));
    }
  };
  for (auto& e : this->TriangleCache)
  {
    if (!e.second->Empty())
    {
      place(*e.second);
    }
  }
  for (auto& e : this->SphereCache)
  {
    if (!e.second->Empty())
    {
      place(*e.second);
    }
  }
  ids.resize((ids.size() + 3) / 4 * 4, 0u);
  sphereIds.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    sphereIds[i] = bitsOf(ids[i]);
  }
  this->GeometryDirty = false;
}

void Scene::PackColors(std::vector<float>& colors)
{
  colors.clear();
  for (auto& e : this->ColorCache)
  {
    e.second->Base = static_cast<std::uint32_t>(colors.size());
    for (std::uint32_t c : e.second->Packed)
    {
      colors.push_back(bitsOf(c));
    }
  }
  colors.resize((colors.size() + 3) / 4 * 4, 0.0f);
  this->ColorsDirty = false;
}

bool Scene::HasTriangles() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return !i.Geom->Spheres; });
}
bool Scene::HasSpheres() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->Spheres; });
}
bool Scene::HasScreenSpheres() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->ScreenSized; });
}
bool Scene::HasEllipsoids() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Geom->Ellipsoids; });
}
bool Scene::HasVertexNormals() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.UseVertexNormals; });
}
bool Scene::HasColors() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Color != nullptr; });
}
bool Scene::HasColorTexture() const
{
  return std::any_of(this->Instances.begin(), this->Instances.end(),
    [](const Instance& i) { return i.Color != nullptr && i.Color->Texture; });
}
int Scene::MaxClipPlanes() const
{
  std::size_t total = 0;
  for (const Instance& i : this->Instances)
  {
    total += i.ClipPlanes.size();
  }
  return static_cast<int>(total);
}

ScreenSphereRadii ComputeScreenSphereRadii(const Instance& inst, vtkRenderer* ren,
  const double localToShader[16], const double eyeInShader[3])
{
  ScreenSphereRadii out;
  const Geometry& g = *inst.Geom;
  if (!g.ScreenSized || !ren || !ren->GetActiveCamera())
  {
    return out;
  }
  vtkCamera* cam = ren->GetActiveCamera();
  int size[2];
  int origin[2];
  ren->GetTiledSizeAndOrigin(size, size + 1, origin, origin + 1);
  const double pixels = static_cast<double>(std::max(1, size[1]));
  // World radius per unit of view depth (perspective) or constant (parallel).
  const double perDepth =
    inst.PointSize * std::tan(vtkMath::RadiansFromDegrees(cam->GetViewAngle()) / 2.0) / pixels;
  const double constant = inst.PointSize * cam->GetParallelScale() / pixels;
  // Local units -> world units: the actor's (uniform) scale.
  double m3[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m3[r][c] = localToShader[4 * r + c];
    }
  }
  const double scale = std::cbrt(std::abs(vtkMath::Determinant3x3(m3)));
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return out;
  }
  if (cam->GetParallelProjection())
  {
    out.Plane[3] = constant / scale;
  }
  else
  {
    // depth(c) = dop . (M c + t - eye), affine in the local center c.
    double dop[3];
    cam->GetDirectionOfProjection(dop);
    double w = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      w += dop[r] * (localToShader[4 * r + 3] - eyeInShader[r]);
    }
    for (int c = 0; c < 3; ++c)
    {
      out.Plane[c] = perDepth / scale * (dop[0] * m3[0][c] + dop[1] * m3[1][c] + dop[2] * m3[2][c]);
    }
    out.Plane[3] = perDepth / scale * w;
  }
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[3] = { g.LocalBounds[(corner & 1) ? 1 : 0], g.LocalBounds[(corner & 2) ? 3 : 2],
      g.LocalBounds[(corner & 4) ? 5 : 4] };
    out.MaxLocal = std::max(out.MaxLocal,
      out.Plane[0] * p[0] + out.Plane[1] * p[1] + out.Plane[2] * p[2] + out.Plane[3]);
  }
  out.MaxWorld = out.MaxLocal * scale;
  return out;
}

core::BuildOptions Scene::Options() const
{
  core::BuildOptions options;
  options.quality = this->BuildQuality == 0
    ? core::BuildQuality::Fast
    : (this->BuildQuality == 2 ? core::BuildQuality::High : core::BuildQuality::Medium);
  options.maxLeafSize = this->LeafSize;
  return options;
}

core::BuildOptions Scene::SphereOptions() const
{
  core::BuildOptions options = this->Options();
  // A sphere test (one texel fetch, a few flops) costs the shader far less
  // than a node visit (four fetches, two box tests): shallower trees with
  // larger leaves trace faster (about 5% on random sphere clouds, llvmpipe).
  options.traversalCost = 3.0;
  options.maxLeafSize = 16;
  return options;
}

void Scene::Clear()
{
  this->TriangleCache.clear();
  this->SphereCache.clear();
  this->ColorCache.clear();
  this->GlyphSourceCache.clear();
  this->Instances.clear();
  this->GeometryDirty = true;
  this->ColorsDirty = true;
}

} // namespace pass
} // namespace vtkrt
