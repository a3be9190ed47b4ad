// Where the shader's triangle walks start, on the C++ twins
// (core/GpuTraversal.h), against the walk from the root:
// - tile entry lists (VTKRT_TILE_ENTRIES): camera rays through every pixel
//   of a tile, starting from the tile's list (the tree's nodes at a cut
//   level whose projected boxes touch the tile, the nearest last), find the
//   root walk's hit exactly (the same t; the same triangle but at ties),
//   list 0 (the root alone) finds it too, the walk stays within the stack
//   entriesFitStack allows, and a list missing its nearest or farthest node
//   is caught;
// - one-leaf trees (VTKRT_LEAF_TREES): the root's triangles alone give the
//   walk's hit, t, triangle and barycentrics, for closest and any hits.
#include "CoreTestUtils.h"
#include "GpuTwinTestUtils.h"

#include "vtkrt/core/GpuTraversal.h"

#include <algorithm>

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{
/// A pinhole camera of `size` square pixels: the ray through pixel
/// coordinates (x, y) starts at the eye (relative to the mesh origin).
struct PinholeCamera
{
  vec3 eye, forward, right, up;
  int size;
  vec3 direction(double x, double y) const
  {
    const float sx = float(2.0 * x / size - 1.0), sy = float(2.0 * y / size - 1.0);
    return forward + sx * right + sy * up;
  }
};

/// What the pass's tile lists hold, built here directly: for each tile, the
/// tree's nodes at depth `level` (and the leaves above it) whose boxes'
/// projections, a pixel wider, touch the tile (a box reaching behind the
/// eye touches every tile), the nearest (by its nearest corner's depth) last.
struct TileLists
{
  std::vector<std::uint32_t> words; // the uTileEntries buffer
  std::vector<std::uint32_t> heights; // per list: the most levels below an entry
};

TileLists makeTileLists(const std::vector<gpu::Node>& nodes, const std::vector<std::uint32_t>& height,
  const PinholeCamera& cam, int tile, int level, std::uint32_t root)
{
  const int tiles = cam.size / tile;
  // The cut: nodes at `level`, leaves above it.
  std::vector<std::uint32_t> cut;
  std::vector<std::pair<std::uint32_t, int>> stack{ { root, 0 } };
  while (!stack.empty())
  {
    const auto [n, depth] = stack.back();
    stack.pop_back();
    if (nodes[n].count == 0 && depth < level)
    {
      stack.push_back({ nodes[n].index, depth + 1 });
      stack.push_back({ nodes[n].index + 1, depth + 1 });
    }
    else
    {
      cut.push_back(n);
    }
  }
  const float scale = glm::length(cam.right);
  const vec3 r = cam.right / (scale * scale), u = cam.up / (scale * scale), f = glm::normalize(cam.forward);
  std::vector<std::vector<std::pair<float, std::uint32_t>>> lists(static_cast<std::size_t>(tiles * tiles));
  for (std::uint32_t n : cut)
  {
    double lo[2] = { 1e300, 1e300 }, hi[2] = { -1e300, -1e300 };
    float nearest = 1e30f;
    bool behind = false;
    for (int c = 0; c < 8; ++c)
    {
      const vec3 p((c & 1) ? nodes[n].hi.x : nodes[n].lo.x, (c & 2) ? nodes[n].hi.y : nodes[n].lo.y,
        (c & 4) ? nodes[n].hi.z : nodes[n].lo.z);
      const vec3 q = p - cam.eye;
      const double z = glm::dot(q, cam.forward) / glm::dot(cam.forward, cam.forward);
      nearest = std::min(nearest, glm::dot(q, f));
      behind = behind || z <= 1e-6;
      const double s[2] = { glm::dot(q, r) / z, glm::dot(q, u) / z };
      for (int k = 0; k < 2; ++k)
      {
        const double pixel = (s[k] + 1.0) * 0.5 * cam.size;
        lo[k] = std::min(lo[k], pixel - 1.0);
        hi[k] = std::max(hi[k], pixel + 1.0);
      }
    }
    for (int ty = 0; ty < tiles; ++ty)
    {
      for (int tx = 0; tx < tiles; ++tx)
      {
        if (behind || (hi[0] >= tx * tile && lo[0] <= (tx + 1) * tile && hi[1] >= ty * tile && lo[1] <= (ty + 1) * tile))
        {
          lists[static_cast<std::size_t>(ty * tiles + tx)].push_back({ nearest, n });
        }
      }
    }
  }
  // Headers: list 0 the root alone, then one a tile (an empty tile: the
  // root's list); the node ids after them.
  TileLists out;
  const std::size_t headerWords = 4 * (lists.size() + 1);
  out.words.assign(headerWords, 0u);
  out.words.push_back(root);
  out.words[0] = static_cast<std::uint32_t>(headerWords);
  out.words[1] = 1;
  out.heights.push_back(height[root]);
  for (std::size_t t = 0; t < lists.size(); ++t)
  {
    auto& list = lists[t];
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::uint32_t h = 0;
    out.words[4 * (t + 1)] = list.empty() ? out.words[0] : static_cast<std::uint32_t>(out.words.size());
    out.words[4 * (t + 1) + 1] = list.empty() ? 1u : static_cast<std::uint32_t>(list.size());
    for (const auto& entry : list)
    {
      out.words.push_back(entry.second);
      h = std::max(h, height[entry.second]);
    }
    out.heights.push_back(list.empty() ? height[root] : h);
  }
  out.words.resize((out.words.size() + 3) / 4 * 4, 0u);
  return out;
}

void checkTileWalks(const MeshData& mesh, const Vec3<double>& eyeWorld, double halfAngle, int expectHits)
{
  const BVH bvh = buildTriangleBVH(mesh.view());
  const Vec3<double> origin = bvh.bounds().center();
  const std::vector<float> packed = packNodesForGpu(bvh, origin);
  const std::vector<Vec3<float>> fverts = relativeFloatPoints(mesh.vertices.data(), mesh.vertices.size(), origin);
  const std::vector<float> triangles = packTriangles(bvh, fverts, mesh.indices);
  std::vector<gpu::Node> nodes(packed.size() / 8);
  std::memcpy(nodes.data(), packed.data(), nodes.size() * sizeof(gpu::Node));
  std::vector<std::uint32_t> height(nodes.size(), 0u);
  for (std::size_t i = nodes.size(); i-- > 0;)
  {
    if (nodes[i].count == 0)
    {
      height[i] = 1 + std::max(height[nodes[i].index], height[nodes[i].index + 1]);
    }
  }
  PinholeCamera cam;
  cam.size = 96;
  cam.eye = vec3(eyeWorld - origin);
  cam.forward = glm::normalize(-cam.eye);
  cam.right = glm::normalize(glm::cross(cam.forward, vec3(0.1f, 1.0f, 0.2f))) * float(halfAngle);
  cam.up = glm::cross(cam.right, cam.forward);
  const int tile = 16;
  const int tiles = cam.size / tile;
  int hits = 0, caught = 0;
  int deepest = -1000; // the most entries touched against the bound (0: the bound is tight)
  for (int level : { 1, 3, 6 })
  {
    const TileLists lists = makeTileLists(nodes, height, cam, tile, level, 0u);
    // The mutant: every tile's nearest entry dropped, or, where the level
    // is odd, its farthest (a list keeps one).
    TileLists mutant = lists;
    for (int t = 1; t <= tiles * tiles; ++t)
    {
      const bool more = mutant.words[4 * t + 1] > 1;
      mutant.words[4 * t] += level % 2 == 1 && more ? 1u : 0u;
      mutant.words[4 * t + 1] -= more ? 1u : 0u;
    }
    gpu::ShaderInputs u, m;
    u.uNodes = m.uNodes = gpu::TexelBuffer(packed);
    u.uTriangles = m.uTriangles = gpu::TexelBuffer(triangles);
    u.uTileEntries = gpu::TexelBuffer(lists.words);
    m.uTileEntries = gpu::TexelBuffer(mutant.words);
    for (int y = 0; y < cam.size; ++y)
    {
      for (int x = 0; x < cam.size; ++x)
      {
        const int list = 1 + (y / tile) * tiles + x / tile;
        const vec3 dir = cam.direction(x + 0.5, y + 0.5);
        float tRoot = 1e30f, tTile = 1e30f, tList0 = 1e30f, tMutant = 1e30f;
        int triRoot, triTile, triList0, triMutant;
        vec2 uv;
        gpu::traverseTriangles(u, 0, cam.eye, dir, 0.0f, tRoot, triRoot, uv, false);
        u.deepestStackEntry = -1;
        gpu::traverseTriangles(u, 0, cam.eye, dir, 0.0f, tTile, triTile, uv, false, list);
        // The smallest stack entriesFitStack accepts for the list holds
        // every entry the walk touched.
        std::uint32_t stackSize = 1;
        while (!gpu::entriesFitStack(lists.words[4 * list + 1], lists.heights[list], stackSize))
        {
          ++stackSize;
        }
        VTKRT_CHECK_MSG(u.deepestStackEntry < static_cast<int>(stackSize),
          "level %d, tile %d: stack entry %d touched, %u allowed", level, list, u.deepestStackEntry, stackSize);
        deepest = std::max(deepest, u.deepestStackEntry + 1 - static_cast<int>(stackSize));
        gpu::traverseTriangles(u, 0, cam.eye, dir, 0.0f, tList0, triList0, uv, false, 0);
        gpu::traverseTriangles(m, 0, cam.eye, dir, 0.0f, tMutant, triMutant, uv, false, list);
        VTKRT_CHECK_MSG(tTile == tRoot && tList0 == tRoot, "level %d, pixel (%d, %d): t %g, %g, root %g", level, x,
          y, tTile, tList0, tRoot);
        // The same triangle, or another at the same t (a shared edge).
        VTKRT_CHECK(triTile == triRoot || tTile == tRoot);
        hits += triRoot >= 0;
        caught += tMutant != tRoot;
      }
    }
  }
  VTKRT_CHECK_MSG(hits >= expectHits, "%d rays hit", hits);
  VTKRT_CHECK_MSG(caught > 0, "no ray needed the dropped entries");
  std::printf("  %d rays hit, %d caught with the nearest or farthest entries dropped; the deepest walk %d entries from the bound\n",
    hits, caught, -deepest);
}
/// Meshes of a few triangles whose tree is one leaf: the leafTrees twin
/// finds what the walk finds.
void checkLeafTrees()
{
  Rng rng(17);
  int hits = 0, leafTrees = 0;
  for (int round = 0; round < 80; ++round)
  {
    const MeshData mesh = makeTriangleSoup(rng, 1 + round % 4, 0.6);
    const BVH bvh = buildTriangleBVH(mesh.view());
    if (bvh.nodes.size() != 1)
    {
      continue;
    }
    ++leafTrees;
    const Vec3<double> origin = bvh.bounds().center();
    const std::vector<float> nodes = packNodesForGpu(bvh, origin);
    const std::vector<Vec3<float>> fverts = relativeFloatPoints(mesh.vertices.data(), mesh.vertices.size(), origin);
    const std::vector<float> triangles = packTriangles(bvh, fverts, mesh.indices);
    gpu::ShaderInputs walk, leaf;
    walk.uNodes = leaf.uNodes = gpu::TexelBuffer(nodes);
    walk.uTriangles = leaf.uTriangles = gpu::TexelBuffer(triangles);
    leaf.leafTrees = true;
    for (int i = 0; i < 500; ++i)
    {
      const vec3 org = vec3(rng.unitVector() * 2.0);
      const vec3 dir = vec3(rng.inBox(Vec3<double>(-0.5), Vec3<double>(0.5))) - org;
      for (bool any : { false, true })
      {
        float tWalk = 1e30f, tLeaf = 1e30f;
        int triWalk, triLeaf;
        vec2 uvWalk, uvLeaf;
        const bool found = gpu::traverseTriangles(walk, 0, org, dir, 0.0f, tWalk, triWalk, uvWalk, any);
        VTKRT_CHECK(gpu::traverseTriangles(leaf, 0, org, dir, 0.0f, tLeaf, triLeaf, uvLeaf, any) == found);
        VTKRT_CHECK(tLeaf == tWalk && triLeaf == triWalk && uvLeaf == uvWalk);
        hits += found ? 1 : 0;
      }
    }
  }
  VTKRT_CHECK_MSG(leafTrees >= 20 && hits > 1000, "%d one-leaf trees, %d hits", leafTrees, hits);
}
} // namespace

int main()
{
  // Outside, looking at the mesh; close, a box reaching behind the eye.
  checkTileWalks(makeIcosphere(5, 1.0, Vec3<double>(1e3, -2e3, 5e2)), Vec3<double>(1e3 + 0.4, -2e3 + 0.7, 5e2 + 2.6), 0.45, 12000);
  checkTileWalks(makeTorus(96, 48), Vec3<double>(0.2, 0.1, 0.15), 0.8, 8000);
  {
    Rng rng(5);
    checkTileWalks(makeTriangleSoup(rng, 4000, 0.05), Vec3<double>(0.3, 2.0, 0.8), 0.5, 3000);
  }
  checkLeafTrees();
  return testResult("TestCoreGpuWalkStarts");
}
