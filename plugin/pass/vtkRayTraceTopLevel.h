// Private to vtkRayTracePass: the top-level BVH over the instances' world
// boxes (core::buildGpuTopLevel), for scenes with many instances; rebuilt
// and uploaded only when an instance's world box changes, never for a
// camera move.
#ifndef vtkRayTraceTopLevel_h
#define vtkRayTraceTopLevel_h

#include "vtkRayTraceTypes.h"

#include "vtkrt/core/AABB.h"

#include <cstddef>
#include <vector>

class vtkOpenGLRenderWindow;

namespace vtkrt
{
namespace pass
{
class TextureBuffer;

class TopLevel
{
public:
  /// Scenes with more instances than this walk a top-level BVH over them
  /// instead of testing every instance's box.
  static constexpr std::size_t kMinInstances = 8;
  static bool IsNeeded(std::size_t instances) { return instances > kMinInstances; }

  /// Builds and uploads the top level when the boxes changed (or nothing is
  /// on the GPU yet); counts what it did.
  void Update(vtkOpenGLRenderWindow* win, const std::vector<core::AABB<double>>& worldBoxes,
    TextureBuffer& nodes, FrameCounters& counters);

  /// Puts the records in the top level's leaf order (leaves index them directly).
  void Reorder(std::vector<core::gpu::InstanceRecord>& records) const;

  /// The anchor the top-level boxes are relative to, in world coordinates.
  const core::Vec3<double>& GetAnchor() const { return this->Anchor; }

  void Clear() { this->Signature.clear(); }

private:
  std::vector<double> Signature;
  std::vector<std::uint32_t> Order;
  core::Vec3<double> Anchor{ 0.0 };
};

} // namespace pass
} // namespace vtkrt

#endif
