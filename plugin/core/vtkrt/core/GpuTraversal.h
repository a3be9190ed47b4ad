// The C++ twins of the shader's BVH walks: the while-while walk of
// traverseTriangles, traverseSpheres and traverseTubes (bvhInteriorStep, bvhPopAfterLeaf)
// and the top-level walk of traceTopLevel, reading the packed arrays the
// pass uploads (packNodesForGpu and the primitive records) the way the
// shader reads its texture buffers: a record at a time, by readers named as
// the shader's generated ones (fetchNode ...), on a TexelBuffer.
// Names, arguments and operations are the shader's (see GpuKernels.h);
// uniforms and feature #defines the walks read are a ShaderInputs.
#ifndef vtkrt_core_GpuTraversal_h
#define vtkrt_core_GpuTraversal_h

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/BVHTraversal.h"
#include "vtkrt/core/GpuKernels.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <vector>

namespace vtkrt::core::gpu
{

/// A texture buffer of four 32-bit components per texel (the pass's
/// RGBA32UI buffers), over an array the caller keeps alive. The one place
/// the twins read packed data.
class TexelBuffer
{
public:
  TexelBuffer() = default;
  explicit TexelBuffer(const std::vector<float>& components)
    : Bytes(reinterpret_cast<const unsigned char*>(components.data()))
    , Texels(components.size() / 4)
  {
  }
  explicit TexelBuffer(const std::vector<std::uint32_t>& components)
    : Bytes(reinterpret_cast<const unsigned char*>(components.data()))
    , Texels(components.size() / 4)
  {
  }

  /// Texel i as bits; a texel beyond the buffer reads as zero, as under
  /// GL's robust buffer access (the shader never reads one).
  uvec4 fetch(int i) const
  {
    assert(i >= 0 && static_cast<std::size_t>(i) < Texels);
    uvec4 texel(0u);
    if (i >= 0 && static_cast<std::size_t>(i) < Texels)
    {
      std::memcpy(&texel, Bytes + kTexelBytes * static_cast<std::size_t>(i), sizeof texel);
    }
    return texel;
  }
  std::size_t size() const { return Texels; }

  /// The Record whose first texel is `first`, texel by texel.
  template <class Record>
  Record record(int first) const
  {
    Record r;
    unsigned char* out = reinterpret_cast<unsigned char*>(&r);
    for (std::uint32_t k = 0; k < texelsOf<Record>(); ++k)
    {
      const uvec4 texel = fetch(first + static_cast<int>(k));
      std::memcpy(out + kTexelBytes * k, &texel, sizeof texel);
    }
    return r;
  }

private:
  const unsigned char* Bytes = nullptr;
  std::size_t Texels = 0;
};

inline uvec4 texelFetch(const TexelBuffer& buffer, int i)
{
  return buffer.fetch(i);
}

/// The shader's record readers, one per record of VTKRT_GPU_RECORDS
/// (fetchNode, fetchTriangle, fetchTriangleVertices, fetchSphere,
/// fetchEllipsoid, fetchNormal, fetchInstanceRecord): record i of a buffer
/// (for an Ellipsoid, the one at texel i).
#define VTKRT_GPU_FETCH(type, NAME, indexing, fields)                                              \
  inline type fetch##type(const TexelBuffer& buffer, int i)                                        \
  {                                                                                                \
    return buffer.record<type>(firstTexel<type>(Indexing::indexing, i));                           \
  }
VTKRT_GPU_RECORDS(VTKRT_GPU_FETCH, VTKRT_GPU_NO_FIELD, VTKRT_GPU_NO_FIELD)
#undef VTKRT_GPU_FETCH

/// Value i of a buffer of four 32-bit values per texel (ids, RGBA8 colors).
inline std::uint32_t fetchPacked(const TexelBuffer& buffer, int i)
{
  const uvec4 texel = texelFetch(buffer, i >> 2);
  const int c = i & 3;
  return c == 0 ? texel.x : (c == 1 ? texel.y : (c == 2 ? texel.z : texel.w));
}

/// What the walks read besides their arguments: the texture buffers (named
/// as the shader's uniforms) and the #defines that change a walk.
struct ShaderInputs
{
  TexelBuffer uNodes;     ///< every bottom-level BVH's Nodes (packNodesForGpu)
  TexelBuffer uTriangles; ///< Triangles in leaf order
  TexelBuffer uSpheres;   ///< Spheres, or Ellipsoids or Segments (a texel index each), in leaf order
  TexelBuffer uTopNodes;  ///< the Nodes of the top-level BVH over the instance records
  TexelBuffer uTileEntries; ///< TileLists (list 0: the root's), then their node ids, four a texel
  vec3 uCameraToAnchor = vec3(0.0f);
  vec4 uTileGrid = vec4(1.0f); ///< tiles per unit of [0, 1] viewport coordinates (xy), tiles in x, y (zw)
  int maximumTraversalSteps = 0; ///< VTKRT_MAXIMUM_TRAVERSAL_STEPS (0: no cap)
  bool screenSpheres = false;    ///< VTKRT_SCREEN_SPHERES
  bool hasEllipsoids = false;    ///< VTKRT_HAS_ELLIPSOIDS
  bool leafTrees = false;        ///< VTKRT_LEAF_TREES: every triangle tree is one leaf
  bool packedStackEntries = true; ///< VTKRT_PACKED_STACK_ENTRIES: walk stack entries of one word
  bool singleInstance = false;   ///< VTKRT_SINGLE_INSTANCE: every walk starts at uRootNode
  Node uRootNode{};              ///< the one instance's root node, as uploaded (global indices)
  /// Not the shader's: the deepest stack entry the walks have touched so far
  /// (what VTKRT_STACK_SIZE must hold; see stackSizeForDepth).
  mutable int deepestStackEntry = -1;
};

/// The root node of the tree at `root`, where a walk starts: in a shader of
/// one instance the frame constant uRootNode, not fetched per pixel.
inline Node rootNodeOf(const ShaderInputs& u, int root)
{
  return u.singleInstance ? u.uRootNode : fetchNode(u.uNodes, root);
}

/// The entries of the shader's walk stack (VTKRT_STACK_SIZE) for bottom-level
/// trees no deeper than maxDepth (root depth 0): an interior step at depth d
/// writes entry sp <= d and reads the entry above, so entries 0..maxDepth;
/// rounded up to a power of two (at least 8) so that few shader variants
/// exist. llvmpipe clears the whole stack for every group of pixels: a
/// smaller stack is a cheaper pixel.
inline std::uint32_t stackSizeForDepth(std::uint32_t maxDepth)
{
  const std::uint32_t needed = std::min(maxDepth, kMaxDepth) + 1;
  std::uint32_t size = 8;
  while (size < needed)
  {
    size *= 2;
  }
  return std::min(size, kMaxStackSize);
}

/// The shader's bvhStack: each entry a node's index and count, `packed`
/// into one word (index << kStackCountBits | count; the second unused) or
/// not (index, count). No entry distance: a popped node meets the best hit
/// in the next step's box tests.
struct BvhStack
{
  uvec2 entry[kMaxStackSize] = {};
  bool packed = true; ///< VTKRT_PACKED_STACK_ENTRIES
  int deepest = -1;   ///< not the shader's: the deepest entry touched
};

/// The shader's stackEntry, entryIndex and entryCount.
inline uvec2 stackEntry(const BvhStack& stack, std::uint32_t index, std::uint32_t count)
{
  if (!stack.packed)
  {
    return uvec2(index, count);
  }
  assert(index <= kMaxPackedStackIndex && count <= kMaxPackedStackCount);
  return uvec2((index << kStackCountBits) | count, 0u);
}

inline std::uint32_t entryIndex(const BvhStack& stack, const uvec2& e)
{
  return stack.packed ? e.x >> kStackCountBits : e.x;
}

inline std::uint32_t entryCount(const BvhStack& stack, const uvec2& e)
{
  return stack.packed ? e.x & kMaxPackedStackCount : e.y;
}

/// One interior step (see the shader): the farther child is written above
/// the stack top and kept only when both children are hit; the top entry
/// is read every step and used only at a dead end. False when the walk is
/// over.
inline bool bvhInteriorStep(BvhStack& stack, const Node& n0, bool h0, float t0, const Node& n1, bool h1,
  float t1, int& sp, std::uint32_t& index, std::uint32_t& count)
{
  assert(sp >= 0 && sp + 1 < static_cast<int>(kMaxStackSize));
  const bool nearIs1 = h1 && (!h0 || t1 < t0);
  stack.entry[sp] = nearIs1 ? stackEntry(stack, n0.index, n0.count) : stackEntry(stack, n1.index, n1.count);
  stack.deepest = std::max(stack.deepest, sp);
  const bool anyHit = h0 || h1;
  if (!anyHit && sp == 0)
  {
    return false;
  }
  sp += h0 && h1 ? 1 : 0;
  const int top = anyHit ? sp : std::max(sp - 1, 0);
  stack.deepest = std::max(stack.deepest, top);
  const uvec2 popped = stack.entry[top];
  sp = top;
  index = anyHit ? (nearIs1 ? n1.index : n0.index) : entryIndex(stack, popped);
  count = anyHit ? (nearIs1 ? n1.count : n0.count) : entryCount(stack, popped);
  return true;
}

/// After a leaf: the next node from the stack. False when the stack is
/// empty.
inline bool bvhPopAfterLeaf(BvhStack& stack, int& sp, std::uint32_t& index, std::uint32_t& count)
{
  if (sp == 0)
  {
    return false;
  }
  --sp;
  const uvec2 popped = stack.entry[sp];
  index = entryIndex(stack, popped);
  count = entryCount(stack, popped);
  return true;
}

/// The start of a walk from the entries of tile list `list` (the shader's
/// VTKRT_TILE_ENTRIES): each entry node whose box the ray meets is pushed,
/// in the list's order, then the first is popped
/// as by bvhPopAfterLeaf. Every list has an entry (a do-while: see the
/// shader's bvhDescend). False when the ray meets no entry's box. A list of
/// l entries whose subtrees are at most h levels deep fits a stack of
/// l + h entries (entriesFitStack).
inline bool bvhStartFromEntries(BvhStack& stack, const ShaderInputs& u, const vec3& org, const vec3& invDir,
  const vec3& parallelBias, float tmin, float tmax, int list, int& sp, std::uint32_t& index,
  std::uint32_t& count)
{
  const TileList tile = fetchTileList(u.uTileEntries, list);
  int e = static_cast<int>(tile.first);
  const int end = e + static_cast<int>(tile.count);
  do
  {
    const Node n = fetchNode(u.uNodes, static_cast<int>(fetchPacked(u.uTileEntries, e)));
    float tnear;
    const bool hit = intersectRayBoxConservative(org, invDir, parallelBias, n.lo, n.hi, tmin, tmax, tnear);
    assert(sp < static_cast<int>(kMaxStackSize));
    stack.entry[sp] = stackEntry(stack, n.index, n.count);
    stack.deepest = std::max(stack.deepest, sp);
    sp += hit ? 1 : 0;
  } while (++e < end);
  return bvhPopAfterLeaf(stack, sp, index, count);
}

/// The tile list of the camera ray through the normalized device
/// coordinates ndc (the shader's tileListOf).
inline int tileListOf(const ShaderInputs& u, const vec2& ndc)
{
  const glm::ivec2 t = glm::clamp(glm::ivec2(glm::floor((ndc * 0.5f + 0.5f) * vec2(u.uTileGrid.x, u.uTileGrid.y))),
    glm::ivec2(0), glm::ivec2(u.uTileGrid.z, u.uTileGrid.w) - 1);
  return 1 + t.y * static_cast<int>(u.uTileGrid.z) + t.x;
}

/// Whether a walk from a tile list of `entries` nodes, none with more than
/// `height` levels below it (a leaf: 0), stays within a stack of
/// `stackSize` entries: pushes up to entries - 1 below the node popped
/// first, then one a level below it, and an interior step reads the entry
/// above its top (a lone root: entries 0..depth, stackSizeForDepth).
inline bool entriesFitStack(std::uint32_t entries, std::uint32_t height, std::uint32_t stackSize)
{
  return entries + height <= stackSize;
}

/// The interior part of the walk (see the shader): descends from the node at
/// hand to a leaf, boxes grown by growBy; false when the walk is over.
inline bool bvhDescend(BvhStack& stack, const ShaderInputs& u, const vec3& org, const vec3& invDir,
  const vec3& parallelBias, const vec3& growBy, float tmin, float tmax, int& sp, int& steps,
  std::uint32_t& index, std::uint32_t& count)
{
  while (count == 0u)
  {
    if (u.maximumTraversalSteps > 0 && ++steps > u.maximumTraversalSteps)
    {
      return false;
    }
    const Node n0 = fetchNode(u.uNodes, static_cast<int>(index));
    const Node n1 = fetchNode(u.uNodes, static_cast<int>(index) + 1);
    float t0, t1;
    const bool h0 =
      intersectRayBoxConservative(org, invDir, parallelBias, n0.lo - growBy, n0.hi + growBy, tmin, tmax, t0);
    const bool h1 =
      intersectRayBoxConservative(org, invDir, parallelBias, n1.lo - growBy, n1.hi + growBy, tmin, tmax, t1);
    if (!bvhInteriorStep(stack, n0, h0, t0, n1, h1, t1, sp, index, count))
    {
      return false;
    }
  }
  return true;
}

namespace detail
{
/// The walk that traverseTriangles and traverseSpheres share (the shader
/// spells it out in both): leaf(first, count) tests a leaf's primitives
/// and returns true to end the walk; it shrinks tmax (the caller's, so the
/// walk prunes by it) on a hit. Grow: boxes grow by `grow` (spheres).
template <bool Grow, class Leaf>
inline void whileWhileWalk(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, float grow, Leaf&& leaf, int tileList = -1)
{
  const vec3 invDir = safeInverse(dir);
  const vec3 parallelBias = parallelAxisBias(invDir);
  const vec3 growBy = vec3(grow);
  // No test of the root's box: the caller (the shader's traceInstance) has
  // tested the instance's box, which bounds it.
  const Node rootNode = rootNodeOf(u, root);
  BvhStack stack;
  stack.packed = u.packedStackEntries;
  struct RecordDeepest
  {
    const ShaderInputs& u;
    const BvhStack& stack;
    ~RecordDeepest() { u.deepestStackEntry = std::max(u.deepestStackEntry, stack.deepest); }
  } recordDeepest{ u, stack };
  int sp = 0;
  int steps = 0;
  std::uint32_t index = rootNode.index;
  std::uint32_t count = rootNode.count;
  if (tileList >= 0 &&
    !bvhStartFromEntries(stack, u, org, invDir, parallelBias, tmin, tmax, tileList, sp, index, count))
  {
    return;
  }
  for (;;)
  {
    if (!bvhDescend(stack, u, org, invDir, parallelBias, Grow ? growBy : vec3(0.0f), tmin, tmax, sp,
      steps, index, count))
    {
      break;
    }
    if (u.maximumTraversalSteps > 0 && ++steps > u.maximumTraversalSteps)
    {
      break;
    }
    if (leaf(static_cast<int>(index), static_cast<int>(count)))
    {
      return;
    }
    if (!bvhPopAfterLeaf(stack, sp, index, count))
    {
      break;
    }
  }
}
} // namespace detail

/// Closest hit (any hit with stopAtFirstHit) in the triangle BVH whose root
/// node is `root`: tmax becomes the hit's t, tri its leaf-order index into
/// uTriangles, uv its barycentrics. tileList >= 0: the walk starts from that
/// list's entries (bvhStartFromEntries), which must hold every node the ray
/// can reach. u.leafTrees: the root is a leaf, whose triangles alone are
/// tested.
inline bool traverseTriangles(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, int& tri, vec2& uv, bool stopAtFirstHit, int tileList = -1)
{
  tri = -1;
  uv = vec2(0.0f);
  const RayTrianglePrecomputed pre = precomputeRayTriangle(org, dir);
  const auto leaf = [&](int first, int count) {
    const int end = first + count;
    for (int i = first; i < end; ++i)
    {
      const Triangle triangle = fetchTriangle(u.uTriangles, i);
      vec3 h;
      if (intersectRayTriangle(pre, triangle.v0, triangle.v1, triangle.v2, tmin, tmax, h))
      {
        tmax = h.x;
        tri = i;
        uv = vec2(h.y, h.z);
      }
    }
    return stopAtFirstHit && tri >= 0;
  };
  if (u.leafTrees)
  {
    const Node rootNode = rootNodeOf(u, root);
    assert(rootNode.count > 0 && "VTKRT_LEAF_TREES: the root is a leaf");
    leaf(static_cast<int>(rootNode.index), static_cast<int>(rootNode.count));
    return tri >= 0;
  }
  detail::whileWhileWalk<false>(u, root, org, dir, tmin, tmax, 0.0f, leaf, tileList);
  return tri >= 0;
}

/// Closest hit (any hit with stopAtFirstHit) in the sphere BVH whose root
/// node is `root`: tmax becomes the hit's t, sphere its texel in uSpheres.
/// Screen-sized spheres get this frame's radius from radiusPlane and grow
/// every box by `grow`; an ellipsoid set (`ellipsoids`) maps the ray onto
/// each one's unit sphere.
inline bool traverseSpheres(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, int& sphere, bool stopAtFirstHit, const vec4& radiusPlane, float grow, bool ellipsoids)
{
  sphere = -1;
  detail::whileWhileWalk<true>(u, root, org, dir, tmin, tmax, grow, [&](int first, int count) {
    int end = first + count;
    if (u.hasEllipsoids)
    {
      if (ellipsoids)
      {
        const int texels = static_cast<int>(kEllipsoidTexels);
        const int last = first + texels * count;
        for (int i = first; i < last; i += texels)
        {
          const Ellipsoid e = fetchEllipsoid(u.uSpheres, i);
          const vec3 unitOrg = rowsPoint(e.rows[0], e.rows[1], e.rows[2], org);
          const vec3 unitDir = rowsDir(e.rows[0], e.rows[1], e.rows[2], dir);
          float t;
          if (intersectRaySphere(unitOrg, unitDir, vec3(0.0f), 1.0f, tmin, tmax, t))
          {
            tmax = t;
            sphere = i;
          }
        }
      }
      end = ellipsoids ? first : first + count;
    }
    for (int i = first; i < end; ++i)
    {
      Sphere s = fetchSphere(u.uSpheres, i);
      if (u.screenSpheres)
      {
        s.radius += glm::max(0.0f, glm::dot(vec3(radiusPlane), s.center) + radiusPlane.w);
      }
      float t;
      if (intersectRaySphere(org, dir, s.center, s.radius, tmin, tmax, t))
      {
        tmax = t;
        sphere = i;
      }
    }
    return stopAtFirstHit && sphere >= 0;
  });
  return sphere >= 0;
}

/// A point's tube radius this frame (the shader's tubeRadius).
inline float tubeRadius(const vec4& radiusPlane, const vec3& p)
{
  return glm::max(0.0f, glm::dot(vec3(radiusPlane), p) + radiusPlane.w);
}

/// Closest hit (any hit with stopAtFirstHit) in the segment BVH whose root
/// node is `root` (the shader's traverseTubes): tmax becomes the hit's t,
/// segment its first texel in uSpheres. Each segment is a tube piece of this
/// frame's radii (radiusPlane); every box grows by `grow`, their bound.
inline bool traverseTubes(const ShaderInputs& u, int root, const vec3& org, const vec3& dir, float tmin,
  float& tmax, int& segment, bool stopAtFirstHit, const vec4& radiusPlane, float grow)
{
  segment = -1;
  detail::whileWhileWalk<true>(u, root, org, dir, tmin, tmax, grow, [&](int first, int count) {
    const int texels = static_cast<int>(kSegmentTexels);
    const int last = first + texels * count;
    for (int i = first; i < last; i += texels)
    {
      const Segment s = fetchSegment(u.uSpheres, i);
      float t;
      if (intersectRayTube(org, dir, s.a, s.b, tubeRadius(radiusPlane, s.a), tubeRadius(radiusPlane, s.b),
            tmin, tmax, t))
      {
        tmax = t;
        segment = i;
      }
    }
    return stopAtFirstHit && segment >= 0;
  });
  return segment >= 0;
}

/// The top-level walk over the instance records: core's nearer-first walk
/// (detail::OrderedWalk) over uTopNodes, whose boxes are relative to an
/// anchor (uCameraToAnchor moves the ray origin there); a leaf's records
/// [index, index + count) go to traceInstance, the shader's function of
/// that name: traceInstance(instance, org, dir, invDir, tBest, hitInstance,
/// hitPrimitive, hitUV, stopAtFirstHit) updates the best hit.
template <class TraceInstance>
inline void traceTopLevel(const ShaderInputs& u, const vec3& org, const vec3& dir, const vec3& invDir,
  float& tBest, int& hitInstance, int& hitPrimitive, vec2& hitUV, bool stopAtFirstHit,
  TraceInstance&& traceInstance)
{
  const vec3 anchorOrg = org + u.uCameraToAnchor;
  float tnear;
  const Node rootNode = fetchNode(u.uTopNodes, 0);
  if (!intersectRayAABB(anchorOrg, invDir, rootNode.lo, rootNode.hi, 0.0f, tBest, tnear))
  {
    return;
  }
  core::detail::OrderedWalk<float> walk;
  std::uint32_t cur = 0;
  for (;;)
  {
    const Node node = fetchNode(u.uTopNodes, static_cast<int>(cur));
    const int index = static_cast<int>(node.index);
    const int count = static_cast<int>(node.count);
    if (count > 0)
    {
      for (int i = index; i < index + count; ++i)
      {
        traceInstance(i, org, dir, invDir, tBest, hitInstance, hitPrimitive, hitUV, stopAtFirstHit);
        if (stopAtFirstHit && hitInstance >= 0)
        {
          return;
        }
      }
    }
    else
    {
      float t0, t1;
      const Node n0 = fetchNode(u.uTopNodes, index);
      const Node n1 = fetchNode(u.uTopNodes, index + 1);
      const bool h0 = intersectRayAABB(anchorOrg, invDir, n0.lo, n0.hi, 0.0f, tBest, t0);
      const bool h1 = intersectRayAABB(anchorOrg, invDir, n1.lo, n1.hi, 0.0f, tBest, t1);
      if (walk.descend(static_cast<std::uint32_t>(index), h0, t0, h1, t1, cur))
      {
        continue;
      }
    }
    if (!walk.pop(tBest, cur))
    {
      return;
    }
  }
}

} // namespace vtkrt::core::gpu

#endif
