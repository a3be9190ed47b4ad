// Watertightness on closed meshes generated here (subdivided icosphere,
// torus): rays from random origins outside, aimed EXACTLY at vertices and at
// points of edges, from directions at least ~17 degrees off the tangent
// plane, must cross the surface no later than the aim point (t <= 1 + tol).
// Checked at two levels, in double and in float (float vertices relative to
// the mesh center, the packed float GPU node copy walked on the CPU):
//  - kernel: at least one of the triangles around the vertex / on both sides
//    of the edge is hit;
//  - BVH: the closest hit exists with t <= 1 + tol (no leak through the
//    tree's boxes either).
// About 1e6 rays in total.
#include "CoreTestUtils.h"

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{

struct Adjacency
{
  std::vector<std::vector<std::uint32_t>> vertexTriangles;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edgeTriangles;
  std::vector<Vec3<double>> vertexNormals;
};

Adjacency buildAdjacency(const MeshData& m)
{
  Adjacency adj;
  adj.vertexTriangles.resize(m.vertices.size());
  adj.vertexNormals.assign(m.vertices.size(), Vec3<double>(0.0));
  for (std::uint32_t t = 0; t < m.triangleCount(); ++t)
  {
    const std::uint32_t* i = &m.indices[3 * t];
    const Vec3<double> n = triangleNormal(m.vertices[i[0]], m.vertices[i[1]], m.vertices[i[2]]);
    for (int k = 0; k < 3; ++k)
    {
      adj.vertexTriangles[i[k]].push_back(t);
      adj.vertexNormals[i[k]] += n;
      const std::uint32_t a = i[k], b = i[(k + 1) % 3];
      adj.edgeTriangles[{ std::min(a, b), std::max(a, b) }].push_back(t);
    }
  }
  for (auto& n : adj.vertexNormals)
  {
    n = glm::normalize(n);
  }
  return adj;
}

/// Random origin outside, seen from p along a direction making at least
/// acos(0.3) with the tangent plane of normal n.
Vec3<double> originFacing(Rng& rng, const Vec3<double>& p, const Vec3<double>& n, double dist)
{
  for (;;)
  {
    const Vec3<double> w = rng.unitVector();
    if (glm::dot(w, n) > 0.3)
    {
      return p + dist * w;
    }
  }
}

struct LeakCounter
{
  long rays = 0;
  long kernelLeaks = 0;
  long bvhLeaks = 0;
};

template <class T>
struct Precision;

template <>
struct Precision<double>
{
  static constexpr double tol = 1e-9;
};
template <>
struct Precision<float>
{
  static constexpr double tol = 1e-4;
};

/// Fires one ray org -> aim and checks both levels.
template <class T, class Nodes>
void fire(const Vec3<T>& org, const Vec3<T>& aim, const std::vector<std::uint32_t>& ring,
  const TriangleMesh<T>& mesh, const Nodes& nodes, const std::uint32_t* primIndex, LeakCounter& leaks)
{
  const T tmax = T(1 + Precision<T>::tol);
  const Ray<T> ray(org, aim - org, T(0), tmax);
  ++leaks.rays;
  bool ringHit = false;
  const RayTrianglePrecomputed<T> pre(ray);
  for (std::uint32_t t : ring)
  {
    Vec3<T> a(T(0)), b(T(0)), c(T(0));
    mesh.triangle(t, a, b, c);
    TriangleHit<T> h;
    ringHit = ringHit || intersectRayTriangle(pre, a, b, c, ray.tmin, ray.tmax, h);
  }
  leaks.kernelLeaks += !ringHit;
  TriangleIntersector<T> isect(mesh);
  Hit<T> hit;
  leaks.bvhLeaks += !closestHit(nodes, primIndex, ray, isect, hit);
}

void runMesh(const char* name, const MeshData& m, int originsPerVertex, int originsPerEdge, Rng& rng)
{
  const Adjacency adj = buildAdjacency(m);
  const BVH bvh = buildTriangleBVH(m.view());
  VTKRT_CHECK(bvh.primIndex.size() == m.triangleCount());
  const Vec3<double> center = localOrigin(m.vertices.data(), m.vertices.size());
  const std::vector<float> packed = packNodesForGpu(bvh, center);
  const std::vector<Vec3<float>> fverts = relativeFloatPoints(m.vertices.data(), m.vertices.size(), center);
  const TriangleMesh<float> fmesh(fverts, m.indices);
  const TriangleMesh<double> dmesh = m.view();
  const NodeSource dnodes(bvh);
  const GpuNodeSource fnodes(packed);
  const std::uint32_t* prims = bvh.primIndex.data();
  LeakCounter dleaks, fleaks;

  // Vertices.
  for (std::uint32_t v = 0; v < m.vertices.size(); ++v)
  {
    for (int k = 0; k < originsPerVertex; ++k)
    {
      const Vec3<double> o = originFacing(rng, m.vertices[v], adj.vertexNormals[v], rng.uniform(0.05, 6.0));
      fire<double>(o, m.vertices[v], adj.vertexTriangles[v], dmesh, dnodes, prims, dleaks);
      fire<float>(Vec3<float>(o - center), fverts[v], adj.vertexTriangles[v], fmesh, fnodes, prims, fleaks);
    }
  }
  // Edge points: midpoints, random points, points one ulp-ish from the ends.
  for (const auto& [edge, tris] : adj.edgeTriangles)
  {
    VTKRT_CHECK(tris.size() == 2); // closed, manifold
    const Vec3<double> n = glm::normalize(adj.vertexNormals[edge.first] + adj.vertexNormals[edge.second]);
    for (int k = 0; k < originsPerEdge; ++k)
    {
      const double s = k == 0 ? 0.5 : (k == 1 ? 1e-7 : rng.uniform());
      const Vec3<double> a = m.vertices[edge.first], b = m.vertices[edge.second];
      const Vec3<double> p = a + s * (b - a);
      const Vec3<double> o = originFacing(rng, p, n, rng.uniform(0.05, 6.0));
      fire<double>(o, p, tris, dmesh, dnodes, prims, dleaks);
      // In float, a + s (b - a) is rounded off the edge line (and s = 1e-7
      // rounds onto the vertex a): the kernel check then needs the
      // neighbourhood, i.e. the triangles around both end points.
      const Vec3<float> fa = fverts[edge.first], fb = fverts[edge.second];
      const Vec3<float> fp = fa + float(s) * (fb - fa);
      std::vector<std::uint32_t> around = adj.vertexTriangles[edge.first];
      around.insert(around.end(), adj.vertexTriangles[edge.second].begin(), adj.vertexTriangles[edge.second].end());
      fire<float>(Vec3<float>(o - center), fp, around, fmesh, fnodes, prims, fleaks);
    }
  }
  std::printf("%s: %zu triangles, %ld rays per precision; leaks double kernel %ld bvh %ld, float kernel %ld bvh %ld\n",
    name, m.triangleCount(), dleaks.rays, dleaks.kernelLeaks, dleaks.bvhLeaks, fleaks.kernelLeaks, fleaks.bvhLeaks);
  VTKRT_CHECK(dleaks.kernelLeaks == 0);
  VTKRT_CHECK(dleaks.bvhLeaks == 0);
  VTKRT_CHECK(fleaks.kernelLeaks == 0);
  VTKRT_CHECK(fleaks.bvhLeaks == 0);
}

} // namespace

int main()
{
  Rng rng(99);
  runMesh("icosphere", makeIcosphere(5), 6, 6, rng);
  // An off-center torus with an irrational-ish size: vertices are not "nice".
  MeshData torus = makeTorus(96, 48, 1.7, 0.45);
  for (auto& v : torus.vertices)
  {
    v = v * 0.731 + Vec3<double>(3.1, -2.7, 10.3);
  }
  runMesh("torus", torus, 12, 12, rng);
  return testResult("TestCoreWatertight");
}
