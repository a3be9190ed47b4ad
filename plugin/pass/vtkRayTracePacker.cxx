#include "vtkRayTracePacker.h"

#include "vtkRayTraceScene.h"

#include <cstring>

namespace vtkrt
{
namespace pass
{

namespace
{
/// Appends records of any texel-sized type to a texel buffer.
template <class Record>
void appendTexels(std::vector<core::gpu::Texel>& out, const std::vector<Record>& records)
{
  static_assert(sizeof(Record) % core::gpu::kTexelBytes == 0, "records are whole texels");
  const std::size_t first = out.size();
  out.resize(first + records.size() * core::gpu::texelsOf<Record>());
  if (!records.empty())
  {
    std::memcpy(out.data() + first, records.data(), records.size() * sizeof(Record));
  }
}

/// Pads a word buffer to whole texels (four words each).
void padToTexels(std::vector<std::uint32_t>& words)
{
  words.resize((words.size() + 3) / 4 * 4, 0u);
}
} // namespace

PackedGeometry PackGeometry(const Scene& scene)
{
  PackedGeometry out;
  scene.ForEachGeometry([&out](const Geometry& g) {
    GeometryPlacement& place = out.Placements[&g];
    const auto nodeBase = static_cast<std::uint32_t>(out.Nodes.size());
    std::uint32_t primitiveBase = 0;
    place.Root = nodeBase;
    if (g.Spheres)
    {
      primitiveBase = static_cast<std::uint32_t>(out.Spheres.size());
      appendTexels(out.Spheres, g.SphereRecords);
      appendTexels(out.Spheres, g.EllipsoidRecords);
      out.SphereIds.insert(out.SphereIds.end(), g.SphereIds.begin(), g.SphereIds.end());
    }
    else
    {
      primitiveBase = static_cast<std::uint32_t>(out.Triangles.size());
      out.Triangles.insert(out.Triangles.end(), g.Triangles.begin(), g.Triangles.end());
      out.TriangleVertices.insert(
        out.TriangleVertices.end(), g.TriangleVertices.begin(), g.TriangleVertices.end());
      place.NormalBase = static_cast<std::uint32_t>(out.Normals.size());
      out.Normals.insert(out.Normals.end(), g.Normals.begin(), g.Normals.end());
      place.CellNormalBase = static_cast<std::uint32_t>(out.Normals.size());
      out.Normals.insert(out.Normals.end(), g.CellNormals.begin(), g.CellNormals.end());
    }
    // Local child / primitive indices become global ones.
    for (core::gpu::Node node : g.Nodes)
    {
      node.index += node.count == 0 ? nodeBase : primitiveBase;
      out.Nodes.push_back(node);
    }
  });
  padToTexels(out.SphereIds);
  return out;
}

PackedColors PackColors(const Scene& scene)
{
  PackedColors out;
  scene.ForEachColors([&out](const Colors& c) {
    out.Bases[&c] = static_cast<std::uint32_t>(out.Words.size());
    out.Words.insert(out.Words.end(), c.Packed.begin(), c.Packed.end());
  });
  padToTexels(out.Words);
  return out;
}

} // namespace pass
} // namespace vtkrt
