#include "vtkRayTraceSelectionMapper.h"

#include "vtkRayTraceSelection.h"

#include "vtkHardwareSelector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkRayTraceSelectionMapper);

vtkRayTraceSelectionMapper::vtkRayTraceSelectionMapper() = default;
vtkRayTraceSelectionMapper::~vtkRayTraceSelectionMapper() = default;

void vtkRayTraceSelectionMapper::SetStandIn(
  vtkrt::pass::Selection* selection, int index, std::uint32_t maximumId, vtkMapper* original)
{
  this->Selection = selection;
  this->Index = index;
  this->MaximumId = maximumId;
  this->Original = original;
}

void vtkRayTraceSelectionMapper::Render(vtkRenderer* ren, vtkActor*)
{
  vtkHardwareSelector* selector = ren->GetSelector();
  if (!selector || !this->Selection)
  {
    return;
  }
  selector->BeginRenderProp();
  selector->UpdateMaximumCellId(static_cast<vtkIdType>(this->MaximumId));
  this->Selection->DrawProp(selector, this->Index);
  selector->EndRenderProp();
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
  os << indent << "Index: " << this->Index << "\n";
  os << indent << "MaximumId: " << this->MaximumId << "\n";
  os << indent << "Original: " << this->Original << "\n";
}
