// Two-level BVH: a top-level BVH over instances, each a bottom-level BVH
// placed by a double 4x4 transform (object -> world). Rays are carried into
// each instance's object space (t is preserved because the direction is
// transformed linearly, not renormalized), so hits of different instances
// compare directly.
#ifndef vtkrt_core_TwoLevel_h
#define vtkrt_core_TwoLevel_h

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"

#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>

namespace vtkrt::core
{

struct Instance
{
  const BVH* bvh = nullptr;                 ///< bottom level (not owned)
  glm::dmat4 objectToWorld = glm::dmat4(1.0); ///< column-major, GLM convention
};

/// Bounds of `box` after an affine transform (the 8 corners).
inline AABB<double> transformBounds(const glm::dmat4& m, const AABB<double>& box)
{
  AABB<double> out;
  if (box.isEmpty())
  {
    return out;
  }
  for (int i = 0; i < 8; ++i)
  {
    const glm::dvec4 p(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z, 1.0);
    out.extend(Vec3<double>(m * p));
  }
  // Rounding of the transform: widen by a few ulps of the magnitude.
  const Vec3<double> mag = glm::max(glm::abs(out.min), glm::abs(out.max));
  const Vec3<double> pad = mag * (8.0 * std::numeric_limits<double>::epsilon());
  return AABB<double>(out.min - pad, out.max + pad);
}

class TwoLevelBVH
{
public:
  /// Builds the top level. Instances with no bottom tree, an empty one, or a
  /// singular / non-finite transform are skipped (stats of top()).
  void build(std::vector<Instance> instances, const BuildOptions& options = BuildOptions())
  {
    Instances = std::move(instances);
    WorldToObject.resize(Instances.size());
    std::vector<AABB<double>> bounds(Instances.size());
    for (std::size_t i = 0; i < Instances.size(); ++i)
    {
      const Instance& inst = Instances[i];
      const double det = glm::determinant(inst.objectToWorld);
      if (!inst.bvh || inst.bvh->empty() || !(std::abs(det) > 0.0) || !std::isfinite(det))
      {
        continue;
      }
      WorldToObject[i] = glm::inverse(inst.objectToWorld);
      bounds[i] = transformBounds(inst.objectToWorld, inst.bvh->bounds());
    }
    Top = buildBVH(bounds, options);
  }

  /// Moves instance i. Call refitTop() after moving some, before querying.
  /// An instance skipped at build time stays skipped (rebuild to add it);
  /// a singular new transform keeps the previous one and returns false.
  bool setTransform(std::uint32_t instance, const glm::dmat4& objectToWorld)
  {
    const double det = glm::determinant(objectToWorld);
    if (instance >= Instances.size() || !(std::abs(det) > 0.0) || !std::isfinite(det))
    {
      return false;
    }
    Instances[instance].objectToWorld = objectToWorld;
    WorldToObject[instance] = glm::inverse(objectToWorld);
    return true;
  }

  /// Refits the top level to the current transforms (no rebuild).
  void refitTop()
  {
    refit(Top, [this](std::uint32_t i) {
      return transformBounds(Instances[i].objectToWorld, Instances[i].bvh->bounds());
    });
  }

  const BVH& top() const { return Top; }
  const std::vector<Instance>& instances() const { return Instances; }
  const glm::dmat4& worldToObject(std::uint32_t instance) const { return WorldToObject[instance]; }

  /// Ray in the object space of `instance` (same t parametrization).
  Ray<double> toObject(std::uint32_t instance, const Ray<double>& world) const
  {
    const glm::dmat4& m = WorldToObject[instance];
    return Ray<double>(Vec3<double>(m * glm::dvec4(world.org, 1.0)), Vec3<double>(m * glm::dvec4(world.dir, 0.0)),
      world.tmin, world.tmax);
  }

  /// Closest hit through both levels. isect has the signature
  ///   bool(std::uint32_t instance, std::uint32_t prim, const Ray<double>& objectRay, Hit<double>& hit)
  /// with the single-level contract (write t/u/v and return true on a hit in
  /// range). On return hit.instance is the instance, hit.prim the primitive
  /// of its bottom level.
  template <class Isect>
  bool closestHit(const Ray<double>& ray, Isect&& isect, Hit<double>& hit) const
  {
    return traverse<false>(ray, isect, hit);
  }

  template <class Isect>
  bool anyHit(const Ray<double>& ray, Isect&& isect, Hit<double>& hit) const
  {
    return traverse<true>(ray, isect, hit);
  }

private:
  template <bool Any, class Isect>
  bool traverse(const Ray<double>& ray, Isect& isect, Hit<double>& hit) const
  {
    std::uint32_t bestPrim = kInvalidIndex;
    auto instanceTest = [&](std::uint32_t instance, const Ray<double>& worldRay, Hit<double>& h) {
      const Ray<double> local = toObject(instance, worldRay);
      auto primTest = [&](std::uint32_t prim, const Ray<double>& r, Hit<double>& ph) {
        return isect(instance, prim, r, ph);
      };
      Hit<double> inner;
      const bool found = Any ? core::anyHit(*Instances[instance].bvh, local, primTest, inner)
                             : core::closestHit(*Instances[instance].bvh, local, primTest, inner);
      if (!found)
      {
        return false;
      }
      h.t = inner.t;
      h.u = inner.u;
      h.v = inner.v;
      bestPrim = inner.prim;
      return true;
    };
    const bool found = Any ? core::anyHit(Top, ray, instanceTest, hit) : core::closestHit(Top, ray, instanceTest, hit);
    if (found)
    {
      hit.instance = hit.prim;
      hit.prim = bestPrim;
    }
    return found;
  }

  std::vector<Instance> Instances;
  std::vector<glm::dmat4> WorldToObject;
  BVH Top;
};

/// The GPU's top level: a BVH over the instances' world boxes, its nodes
/// relative to `anchor` (the ray origin is moved there in double on the
/// CPU), and the instance of each leaf slot (records go in that order, so
/// leaves index them directly).
struct GpuTopLevel
{
  std::vector<gpu::Node> nodes;
  std::vector<std::uint32_t> order;
  Vec3<double> anchor{ 0.0 };
};

/// Builds the GPU top level over `worldBoxes`. The boxes are padded for the
/// float rounding of the anchor-relative ray origin, a millionth of the
/// root's extent.
inline GpuTopLevel buildGpuTopLevel(const std::vector<AABB<double>>& worldBoxes)
{
  GpuTopLevel top;
  const BVH bvh = buildBVH(worldBoxes);
  top.anchor = bvh.bounds().center();
  top.nodes = packGpuNodes(bvh.nodes, top.anchor);
  top.order = bvh.primIndex;
  if (top.nodes.empty())
  {
    return top;
  }
  float extent = 0.0f;
  for (int k = 0; k < 3; ++k)
  {
    extent = std::max({ extent, std::abs(top.nodes[0].lo[k]), std::abs(top.nodes[0].hi[k]) });
  }
  const float pad = 1e-6f * extent;
  for (gpu::Node& n : top.nodes)
  {
    for (int c = 0; c < 3; ++c)
    {
      n.lo[c] -= pad;
      n.hi[c] += pad;
    }
  }
  return top;
}

} // namespace vtkrt::core

#endif
