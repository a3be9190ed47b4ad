/**
 * @class   vtkRayTraceSelectionMapper
 * @brief   private to vtkRayTracePass: a traced actor's mapper while a
 *          vtkHardwareSelector renders it.
 *
 * vtkHardwareSelector::Render gives each pickable prop its prop id and
 * color and calls RenderOpaqueGeometry. For an actor the pass traces, this
 * stand-in takes the place of the actor's mapper during that call: it
 * announces the prop to the selector as VTK's mappers do (BeginRenderProp,
 * the largest id its pixels carry) and draws the prop's traced pixels,
 * instead of rasterizing the geometry again. It reports the bounds of the
 * mapper it stands in for, and leaves the selector's pixel buffers as they
 * are (the traced ids are already VTK's cell and point ids).
 */
#ifndef vtkRayTraceSelectionMapper_h
#define vtkRayTraceSelectionMapper_h

#include "vtkMapper.h"

#include <cstdint>

namespace vtkrt
{
namespace pass
{
class Selection;
}
}

class vtkRayTraceSelectionMapper : public vtkMapper
{
public:
  static vtkRayTraceSelectionMapper* New();
  vtkTypeMacro(vtkRayTraceSelectionMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * What to draw: traced prop `index` of `selection`, whose ids go up to
   * `maximumId`, standing in for `original` (kept, for its bounds).
   */
  void SetStandIn(
    vtkrt::pass::Selection* selection, int index, std::uint32_t maximumId, vtkMapper* original);

  void Render(vtkRenderer* ren, vtkActor* actor) override;
  double* GetBounds() override;
  using vtkMapper::GetBounds;

protected:
  vtkRayTraceSelectionMapper();
  ~vtkRayTraceSelectionMapper() override;

private:
  vtkRayTraceSelectionMapper(const vtkRayTraceSelectionMapper&) = delete;
  void operator=(const vtkRayTraceSelectionMapper&) = delete;

  vtkrt::pass::Selection* Selection = nullptr;
  int Index = 0;
  std::uint32_t MaximumId = 0;
  vtkMapper* Original = nullptr;
};

#endif
