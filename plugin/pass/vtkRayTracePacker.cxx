#include "vtkRayTracePacker.h"

#include "vtkRayTraceScene.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cstring>

namespace vtkrt
{
namespace pass
{

namespace
{
/// Records per chunk of a parallel copy.
constexpr vtkIdType kCopyGrain = 1 << 16;

/// Copies n records to dst, in parallel chunks on VTK's SMP pool.
template <class Record>
void copyRecords(const Record* src, std::size_t n, Record* dst)
{
  vtkSMPTools::For(0, static_cast<vtkIdType>(n), kCopyGrain, [=](vtkIdType b, vtkIdType e) {
    std::memcpy(dst + b, src + b, static_cast<std::size_t>(e - b) * sizeof(Record));
  });
}

/// Words to whole texels (four words each).
std::size_t paddedWords(std::size_t words)
{
  return (words + 3) / 4 * 4;
}

/// Zeros the words from `used` up to whole texels.
void padWords(std::uint32_t* words, std::size_t used)
{
  std::fill(words + used, words + paddedWords(used), 0u);
}
} // namespace

GeometryLayout LayOutGeometry(const Scene& scene)
{
  GeometryLayout out;
  scene.ForEachGeometry([&out](const Geometry& g) {
    GeometryPlacement& place = out.Placements[&g];
    place.Root = static_cast<std::uint32_t>(out.Nodes);
    out.Nodes += g.Nodes.size();
    if (g.Spheres)
    {
      place.PrimitiveBase = static_cast<std::uint32_t>(out.SphereTexels);
      out.SphereTexels += g.SphereRecords.size() * core::gpu::texelsOf<core::gpu::Sphere>() +
        g.EllipsoidRecords.size() * core::gpu::texelsOf<core::gpu::Ellipsoid>() +
        g.SegmentRecords.size() * core::gpu::texelsOf<core::gpu::Segment>();
      out.SphereIdWords += g.SphereIds.size();
    }
    else
    {
      place.PrimitiveBase = static_cast<std::uint32_t>(out.Triangles);
      out.Triangles += g.Triangles.size();
      place.NormalBase = static_cast<std::uint32_t>(out.Normals);
      place.CellNormalBase = static_cast<std::uint32_t>(out.Normals + g.Normals.size());
      out.Normals += g.Normals.size() + g.CellNormals.size();
    }
  });
  out.SphereIdWords = paddedWords(out.SphereIdWords);
  return out;
}

void WriteGeometry(const Scene& scene, const GeometryLayout& layout, const GeometryTargets& out)
{
  std::size_t sphereIds = 0;
  scene.ForEachGeometry([&](const Geometry& g) {
    const GeometryPlacement& place = layout.Placements.at(&g);
    if (g.Spheres)
    {
      auto* spheres = reinterpret_cast<core::gpu::Sphere*>(out.Spheres + place.PrimitiveBase);
      copyRecords(g.SphereRecords.data(), g.SphereRecords.size(), spheres);
      copyRecords(g.EllipsoidRecords.data(), g.EllipsoidRecords.size(),
        reinterpret_cast<core::gpu::Ellipsoid*>(spheres + g.SphereRecords.size()));
      copyRecords(g.SegmentRecords.data(), g.SegmentRecords.size(),
        reinterpret_cast<core::gpu::Segment*>(out.Spheres + place.PrimitiveBase +
          g.SphereRecords.size() + g.EllipsoidRecords.size() * core::gpu::kEllipsoidTexels));
      copyRecords(g.SphereIds.data(), g.SphereIds.size(), out.SphereIds + sphereIds);
      sphereIds += g.SphereIds.size();
    }
    else
    {
      copyRecords(g.Triangles.data(), g.Triangles.size(), out.Triangles + place.PrimitiveBase);
      copyRecords(
        g.TriangleVertices.data(), g.TriangleVertices.size(), out.TriangleVertices + place.PrimitiveBase);
      copyRecords(g.Normals.data(), g.Normals.size(), out.Normals + place.NormalBase);
      copyRecords(g.CellNormals.data(), g.CellNormals.size(), out.Normals + place.CellNormalBase);
    }
    // Local child / primitive indices become global ones.
    core::gpu::Node* nodes = out.Nodes + place.Root;
    vtkSMPTools::For(0, static_cast<vtkIdType>(g.Nodes.size()), kCopyGrain, [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType i = b; i < e; ++i)
      {
        core::gpu::Node node = g.Nodes[static_cast<std::size_t>(i)];
        node.index += node.count == 0 ? place.Root : place.PrimitiveBase;
        nodes[i] = node;
      }
    });
  });
  padWords(out.SphereIds, sphereIds);
}

ColorsLayout LayOutColors(const Scene& scene)
{
  ColorsLayout out;
  scene.ForEachColors([&out](const Colors& c) {
    out.Bases[&c] = static_cast<std::uint32_t>(out.Words);
    out.Words += c.Packed.size();
  });
  out.Words = paddedWords(out.Words);
  return out;
}

void WriteColors(const Scene& scene, const ColorsLayout& layout, std::uint32_t* out)
{
  std::size_t used = 0;
  scene.ForEachColors([&](const Colors& c) {
    copyRecords(c.Packed.data(), c.Packed.size(), out + layout.Bases.at(&c));
    used += c.Packed.size();
  });
  padWords(out, used);
}

} // namespace pass
} // namespace vtkrt
