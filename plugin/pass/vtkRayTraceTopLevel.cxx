#include "vtkRayTraceTopLevel.h"

#include "vtkRayTraceBuffers.h"

#include "vtkrt/core/TwoLevel.h"

namespace vtkrt
{
namespace pass
{

void TopLevel::Update(vtkOpenGLRenderWindow* win, const std::vector<core::AABB<double>>& worldBoxes,
  TextureBuffer& nodes, FrameCounters& counters)
{
  std::vector<double> signature;
  signature.reserve(6 * worldBoxes.size());
  for (const auto& b : worldBoxes)
  {
    signature.insert(signature.end(), { b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z });
  }
  if (signature == this->Signature && nodes.GetTexels())
  {
    return;
  }
  const core::GpuTopLevel top = core::buildGpuTopLevel(worldBoxes);
  this->Anchor = top.anchor;
  this->Order = top.order;
  this->Signature.swap(signature);
  counters.GeometryBytesUploaded += nodes.Upload(win, top.nodes);
  ++counters.TopLevelBuilds;
}

void TopLevel::Reorder(std::vector<core::gpu::InstanceRecord>& records) const
{
  std::vector<core::gpu::InstanceRecord> ordered(this->Order.size());
  for (std::size_t k = 0; k < this->Order.size(); ++k)
  {
    ordered[k] = records[this->Order[k]];
  }
  records.swap(ordered);
}

} // namespace pass
} // namespace vtkrt
