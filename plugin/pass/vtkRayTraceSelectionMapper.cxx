#include "vtkRayTraceSelectionMapper.h"

#include "vtkRayTraceSelection.h"

#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedIntArray.h"

#include <algorithm>

namespace
{
/// A value of the selector's 24-bit color encoding (low byte first), with
/// the high pass's byte when there is one.
vtkIdType decode(const unsigned char* low, const unsigned char* high, unsigned int pos)
{
  vtkIdType value = high ? static_cast<vtkIdType>(high[pos]) << 24 : 0;
  return value | (static_cast<vtkIdType>(low[pos + 2]) << 16) |
    (static_cast<vtkIdType>(low[pos + 1]) << 8) | low[pos];
}
} // namespace

vtkStandardNewMacro(vtkRayTraceSelectionMapper);

vtkRayTraceSelectionMapper::vtkRayTraceSelectionMapper() = default;
vtkRayTraceSelectionMapper::~vtkRayTraceSelectionMapper() = default;

void vtkRayTraceSelectionMapper::SetStandIn(vtkrt::pass::Selection* selection, vtkMapper* original)
{
  this->Selection = selection;
  this->Original = original;
}

void vtkRayTraceSelectionMapper::Render(vtkRenderer* ren, vtkActor* actor)
{
  vtkHardwareSelector* selector = ren->GetSelector();
  if (!selector || !this->Selection)
  {
    return;
  }
  const int index = this->Selection->CurrentIndex(selector);
  if (index < 0)
  {
    // The actor is also a part of a prop the pass left to raster.
    if (this->Original)
    {
      this->Original->Render(ren, actor);
    }
    return;
  }
  selector->BeginRenderProp();
  vtkIdType maximum = static_cast<vtkIdType>(this->Selection->MaximumId(index));
  auto* gl = vtkOpenGLPolyDataMapper::SafeDownCast(this->Original);
  for (const auto& ids : this->CellArrays<vtkIdTypeArray>(gl ? gl->GetCellIdArrayName() : nullptr))
  {
    if (ids.second->GetNumberOfTuples() > 0)
    {
      maximum = std::max(maximum, static_cast<vtkIdType>(ids.second->GetRange(0)[1]));
    }
  }
  selector->UpdateMaximumCellId(maximum);
  this->Selection->DrawProp(selector, index);
  selector->EndRenderProp();
}

template <typename ArrayT>
std::map<unsigned int, ArrayT*> vtkRayTraceSelectionMapper::CellArrays(const char* name) const
{
  std::map<unsigned int, ArrayT*> arrays;
  auto* gl = vtkOpenGLPolyDataMapper::SafeDownCast(this->Original);
  if (!gl || !name)
  {
    return arrays;
  }
  vtkDataObject* input = gl->GetInputDataObject(0, 0);
  if (auto* poly = vtkPolyData::SafeDownCast(input))
  {
    if (auto* values = ArrayT::SafeDownCast(poly->GetCellData()->GetArray(name)))
    {
      arrays[0] = values;
    }
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it = vtk::TakeSmartPointer(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* poly = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
      auto* values = poly ? ArrayT::SafeDownCast(poly->GetCellData()->GetArray(name)) : nullptr;
      if (values)
      {
        arrays[it->GetCurrentFlatIndex()] = values;
      }
    }
  }
  return arrays;
}

template <typename ArrayT>
void vtkRayTraceSelectionMapper::MapCells(vtkHardwareSelector* sel,
  const std::vector<unsigned int>& pixeloffsets, const std::map<unsigned int, ArrayT*>& arrays,
  int shift)
{
  const unsigned char* low = sel->GetRawPixelBuffer(vtkHardwareSelector::CELL_ID_LOW24);
  const unsigned char* high = sel->GetRawPixelBuffer(vtkHardwareSelector::CELL_ID_HIGH24);
  const unsigned char* composite = sel->GetRawPixelBuffer(vtkHardwareSelector::COMPOSITE_INDEX_PASS);
  unsigned char* out = sel->GetPixelBuffer(sel->GetCurrentPass());
  const bool plain = arrays.size() == 1 && arrays.begin()->first == 0;
  // The raw cell ids exist once the selector has rendered its cell passes
  // (VTK 9.1 renders the composite pass again in its second run over the
  // passes, after them).
  if (arrays.empty() || !low || !out || (shift > 0 && !high) || (!plain && !composite))
  {
    return;
  }
  // The traced pixels hold the cell id and the block's flat index as the
  // selector reads them (VTK's mappers convert their primitive ids to that).
  for (unsigned int pos : pixeloffsets)
  {
    const vtkIdType cell = decode(low, high, pos);
    const auto found = plain ? arrays.begin()
                             : arrays.find(static_cast<unsigned int>(decode(composite, nullptr, pos)));
    if (found == arrays.end() || cell >= found->second->GetNumberOfTuples())
    {
      continue;
    }
    const vtkIdType value = static_cast<vtkIdType>(found->second->GetValue(cell));
    out[pos] = static_cast<unsigned char>((value >> shift) & 0xff);
    out[pos + 1] = static_cast<unsigned char>((value >> (shift + 8)) & 0xff);
    out[pos + 2] = static_cast<unsigned char>((value >> (shift + 16)) & 0xff);
  }
}

void vtkRayTraceSelectionMapper::ProcessSelectorPixelBuffers(
  vtkHardwareSelector* sel, std::vector<unsigned int>& pixeloffsets, vtkProp*)
{
  auto* gl = vtkOpenGLPolyDataMapper::SafeDownCast(this->Original);
  if (!gl)
  {
    return;
  }
  const char* cellIds = gl->GetCellIdArrayName();
  switch (sel->GetCurrentPass())
  {
    case vtkHardwareSelector::CELL_ID_LOW24:
      this->MapCells(sel, pixeloffsets, this->CellArrays<vtkIdTypeArray>(cellIds), 0);
      break;
    case vtkHardwareSelector::CELL_ID_HIGH24:
      this->MapCells(sel, pixeloffsets, this->CellArrays<vtkIdTypeArray>(cellIds), 24);
      break;
    case vtkHardwareSelector::COMPOSITE_INDEX_PASS:
      this->MapCells(sel, pixeloffsets,
        this->CellArrays<vtkUnsignedIntArray>(gl->GetCompositeIdArrayName()), 0);
      break;
    default:
      break;
  }
}

double* vtkRayTraceSelectionMapper::GetBounds()
{
  if (this->Original)
  {
    return this->Original->GetBounds();
  }
  vtkMath::UninitializeBounds(this->Bounds);
  return this->Bounds;
}

void vtkRayTraceSelectionMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Original: " << this->Original << "\n";
}

