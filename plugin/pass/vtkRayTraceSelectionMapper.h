/**
 * @class   vtkRayTraceSelectionMapper
 * @brief   private to vtkRayTracePass: a traced actor's mapper while a
 *          vtkHardwareSelector renders it.
 *
 * vtkHardwareSelector::Render gives each pickable prop its prop id and
 * color and calls RenderOpaqueGeometry. For an actor the pass traces, this
 * stand-in takes the place of the actor's mapper during that call: it
 * announces the prop to the selector as VTK's mappers do (BeginRenderProp,
 * the largest id its pixels carry) and draws the traced pixels of the prop
 * being rendered (an actor may be a part of two assemblies), instead of
 * rasterizing the geometry again; for a prop the pass left to raster it
 * renders the actor with the original mapper. It reports the bounds of the
 * mapper it stands in for. The traced ids are already VTK's cell ids; where
 * the original mapper names a cell id array (CellIdArrayName, as ParaView's
 * vtkOriginalCellIds), ProcessSelectorPixelBuffers maps them through it, as
 * vtkOpenGLPolyDataMapper and vtkCompositePolyDataMapper2 do (a block's own
 * array by its composite index), and its CompositeIdArrayName gives the
 * cells their composite indices.
 */
#ifndef vtkRayTraceSelectionMapper_h
#define vtkRayTraceSelectionMapper_h

#include "vtkMapper.h"

#include <cstdint>
#include <map>
#include <vector>

class vtkHardwareSelector;

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
   * What to draw: the pixels of the traced prop of `selection` the selector
   * renders, standing in for `original` (kept, for its bounds and to draw
   * the actor for a prop the pass left to raster).
   */
  void SetStandIn(vtkrt::pass::Selection* selection, vtkMapper* original);

  void Render(vtkRenderer* ren, vtkActor* actor) override;
  void ProcessSelectorPixelBuffers(
    vtkHardwareSelector* sel, std::vector<unsigned int>& pixeloffsets, vtkProp* prop) override;
  double* GetBounds() override;
  using vtkMapper::GetBounds;

protected:
  vtkRayTraceSelectionMapper();
  ~vtkRayTraceSelectionMapper() override;

private:
  vtkRayTraceSelectionMapper(const vtkRayTraceSelectionMapper&) = delete;
  void operator=(const vtkRayTraceSelectionMapper&) = delete;

  /// The original mapper's cell data arrays named `name` of type ArrayT by
  /// composite flat index (key 0: a polydata input's), empty when it names
  /// none (its CellIdArrayName, vtkIdTypeArray; CompositeIdArrayName,
  /// vtkUnsignedIntArray).
  template <typename ArrayT>
  std::map<unsigned int, ArrayT*> CellArrays(const char* name) const;

  /// Writes, into the current pass's pixels, the value `arrays` hold for
  /// each pixel's traced cell (its block's array by the raw composite
  /// index), shifted right by `shift` bits.
  template <typename ArrayT>
  void MapCells(vtkHardwareSelector* sel, const std::vector<unsigned int>& pixeloffsets,
    const std::map<unsigned int, ArrayT*>& arrays, int shift);

  vtkrt::pass::Selection* Selection = nullptr;
  vtkMapper* Original = nullptr;
};

#endif
