// The shader's translucency twins (core/GpuTranslucency.h): front-to-back
// compositing equals back-to-front "over" in double; the layer step is a
// strict interval; the layer walk over packed real BVHs crosses every layer
// exactly once, also where rays meet the shared edges and vertices of a
// closed mesh (hit by several triangles at t a few ulps apart) and the
// diagonals of stacked quads; transmittance is the product over the layers.
#include "CoreTestUtils.h"
#include "GpuTwinTestUtils.h"

#include "vtkrt/core/GpuTranslucency.h"
#include "vtkrt/core/LocalFrame.h"

#include <vector>

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{
/// A packed mesh the twins walk: its BVH, nodes and triangle texels.
struct PackedMesh
{
  BVH Bvh;
  Vec3<double> Origin;
  std::vector<float> Nodes;
  std::vector<float> Triangles;
  gpu::ShaderInputs Inputs;

  explicit PackedMesh(const MeshData& mesh)
    : Bvh(buildTriangleBVH(mesh.view()))
    , Origin(Bvh.bounds().center())
  {
    this->Nodes = packNodesForGpu(this->Bvh, this->Origin);
    const std::vector<Vec3<float>> fverts =
      relativeFloatPoints(mesh.vertices.data(), mesh.vertices.size(), this->Origin);
    this->Triangles.assign(12 * this->Bvh.primIndex.size(), 0.0f);
    for (std::size_t k = 0; k < this->Bvh.primIndex.size(); ++k)
    {
      const std::uint32_t tri = this->Bvh.primIndex[k];
      for (int v = 0; v < 3; ++v)
      {
        const Vec3<float>& p = fverts[mesh.indices[3 * tri + v]];
        std::copy_n(&p.x, 3, this->Triangles.begin() + 12 * k + 4 * v);
      }
    }
    this->Inputs.uNodes = gpu::TexelBuffer(this->Nodes);
    this->Inputs.uTriangles = gpu::TexelBuffer(this->Triangles);
  }

  /// The t of every layer the walk crosses along the ray from `from` through `target`.
  std::vector<float> Layers(const Vec3<double>& from, const Vec3<double>& target) const
  {
    std::vector<float> ts;
    gpu::walkLayers(this->Inputs, 0, vec3(from - this->Origin), vec3(target - from), 1e30f,
      [&ts](float t, int, vec2) {
        ts.push_back(t);
        return ts.size() < 64;
      });
    return ts;
  }
};

void testCompositing()
{
  Rng rng(11);
  for (int trial = 0; trial < 2000; ++trial)
  {
    const int count = 1 + int(rng.index(8));
    std::vector<Vec3<double>> colors;
    std::vector<double> alphas;
    for (int i = 0; i < count; ++i)
    {
      colors.push_back(rng.inBox(Vec3<double>(0.0), Vec3<double>(1.0)));
      alphas.push_back(trial % 7 == 0 && i == 0 ? 1.0 : rng.uniform());
    }
    vec4 front(0.0f);
    for (int i = 0; i < count; ++i)
    {
      gpu::compositeLayer(front, vec3(colors[i]), float(alphas[i]));
    }
    // Back to front with "over", in double.
    Vec3<double> color(0.0);
    double alpha = 0.0;
    for (int i = count - 1; i >= 0; --i)
    {
      color = alphas[i] * colors[i] + (1.0 - alphas[i]) * color;
      alpha = alphas[i] + (1.0 - alphas[i]) * alpha;
    }
    VTKRT_CHECK_NEAR(front.r, color.x, 1e-5);
    VTKRT_CHECK_NEAR(front.g, color.y, 1e-5);
    VTKRT_CHECK_NEAR(front.b, color.z, 1e-5);
    VTKRT_CHECK_NEAR(front.a, alpha, 1e-5);
  }
  // An opaque first layer is exactly its color; a layer of alpha 0 adds nothing.
  vec4 acc(0.0f);
  gpu::compositeLayer(acc, vec3(0.3f, 0.6f, 0.9f), 1.0f);
  VTKRT_CHECK(acc == vec4(0.3f, 0.6f, 0.9f, 1.0f));
  gpu::compositeLayer(acc, vec3(1.0f), 0.5f);
  VTKRT_CHECK(acc == vec4(0.3f, 0.6f, 0.9f, 1.0f));
  vec4 none(0.0f);
  gpu::compositeLayer(none, vec3(1.0f), 0.0f);
  VTKRT_CHECK(none == vec4(0.0f));
}

void testLayerStep()
{
  for (float t : { 0.0f, 1e-40f, 1e-30f, 1e-7f, 0.25f, 0.5f, 0.999f, 1.0f, 3e7f })
  {
    const float next = gpu::nextLayerTMin(t);
    VTKRT_CHECK(next > t);
    if (t >= 1e-30f)
    {
      VTKRT_CHECK(floatBitsToUint(next) == floatBitsToUint(t) + gpu::kLayerGapUlps);
    }
  }
}

/// Rays from outside a closed convex mesh at points on its near side: at
/// vertices, at edge midpoints (each met by several triangles) and inside
/// faces. Each crosses exactly two layers, entering and leaving.
void testClosedMeshLayers()
{
  const Vec3<double> center(3.0, -2.0, 1.5);
  const MeshData mesh = makeIcosphere(3, 0.8, center);
  const PackedMesh packed(mesh);
  Rng rng(12);
  int rays = 0, twoLayers = 0, atVertices = 0, atEdges = 0;
  for (int i = 0; rays < 3000 && i < 100000; ++i)
  {
    const Vec3<double> u = rng.unitVector();
    const Vec3<double> from = center + 4.0 * u;
    const std::uint32_t* tri = mesh.indices.data() + 3 * rng.index(mesh.triangleCount());
    const Vec3<double>& a = mesh.vertices[tri[0]];
    const Vec3<double>& b = mesh.vertices[tri[1]];
    const Vec3<double>& c = mesh.vertices[tri[2]];
    const int kind = i % 3;
    const Vec3<double> target = kind == 0 ? a : (kind == 1 ? 0.5 * (a + b) : (a + b + c) / 3.0);
    if (glm::dot(target - center, u) < 0.4 * 0.8)
    {
      continue; // far side or near the silhouette: not a clear crossing
    }
    ++rays;
    atVertices += kind == 0;
    atEdges += kind == 1;
    const std::vector<float> ts = packed.Layers(from, target);
    twoLayers += ts.size() == 2;
    VTKRT_CHECK_MSG(ts.size() == 2, "ray %d (kind %d): %zu layers", rays, kind, ts.size());
    if (ts.size() == 2)
    {
      VTKRT_CHECK(ts[1] > ts[0]);
      VTKRT_CHECK_NEAR(ts[0], 1.0, 1e-5); // the target lies at t = 1
    }
  }
  VTKRT_CHECK(rays == 3000 && twoLayers == rays && atVertices > 900 && atEdges > 900);
}

/// Six parallel quads of two triangles each: rays through their shared
/// diagonals and through random points cross six layers, one per quad.
void testStackedQuadLayers()
{
  MeshData mesh;
  const int quads = 6;
  for (int q = 0; q < quads; ++q)
  {
    const double z = 0.1 * q;
    const std::uint32_t base = std::uint32_t(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(),
      { Vec3<double>(0, 0, z), Vec3<double>(1, 0, z), Vec3<double>(1, 1, z), Vec3<double>(0, 1, z) });
    mesh.indices.insert(mesh.indices.end(), { base, base + 1, base + 2, base, base + 2, base + 3 });
  }
  const PackedMesh packed(mesh);
  Rng rng(13);
  for (int i = 0; i < 2000; ++i)
  {
    const double s = rng.uniform(0.2, 0.8);
    const bool diagonal = i % 2 == 0;
    const Vec3<double> through(s, diagonal ? s : rng.uniform(0.2, 0.8), 0.25);
    // Along the diagonal's plane x = y (both tilts equal) or any tilt.
    const double tx = rng.uniform(-0.2, 0.2);
    const Vec3<double> tilt(tx, diagonal ? tx : rng.uniform(-0.2, 0.2), 1.0);
    const std::vector<float> ts = packed.Layers(through - tilt, through);
    VTKRT_CHECK_MSG(ts.size() == quads, "ray %d (%s): %zu layers", i, diagonal ? "diagonal" : "face", ts.size());
  }
}

/// Shadow rays: the product of (1 - alpha) over the layers, in depth order,
/// through a translucent sphere (two layers), stopping when blocked.
void testTransmittance()
{
  const Vec3<double> center(0.0);
  const PackedMesh packed(makeIcosphere(3, 1.0, center));
  for (float alpha : { 0.0f, 0.3f, 0.6f, 1.0f })
  {
    float transmittance = 1.0f;
    int layers = 0;
    gpu::walkLayers(packed.Inputs, 0, vec3(Vec3<double>(0.1, 0.2, -5.0) - packed.Origin),
      vec3(0.0f, 0.0f, 1.0f), 1e30f, [&](float, int, vec2) {
        ++layers;
        return gpu::crossLayer(transmittance, alpha);
      });
    VTKRT_CHECK(layers == (alpha == 1.0f ? 1 : 2));
    VTKRT_CHECK(transmittance == (1.0f - alpha) * (alpha == 1.0f ? 1.0f : 1.0f - alpha));
  }
}

} // namespace

int main()
{
  testCompositing();
  testLayerStep();
  testClosedMeshLayers();
  testStackedQuadLayers();
  testTransmittance();
  return testResult("TestCoreGpuTranslucency");
}
