#include "vtkRayTraceDataSetSurfaces.h"

#include "vtkRayTraceTypes.h"

#include "vtkDataSet.h"
#include "vtkDataSetMapper.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkPlaneCollection.h"
#include "vtkPolyDataMapper.h"
#include "vtkScalarsToColors.h"

namespace vtkrt
{
namespace pass
{

void DataSetSurfaces::BeginFrame()
{
  markUnused(this->Entries);
}

void DataSetSurfaces::EndFrame()
{
  dropUnused(this->Entries);
}

vtkMapper* DataSetSurfaces::MapperFor(vtkMapper* mapper)
{
  auto* dataSetMapper = vtkDataSetMapper::SafeDownCast(mapper);
  if (!dataSetMapper)
  {
    return mapper;
  }
  Entry& e = this->Entries[mapper];
  e.Used = true;
  if (!e.Mapper)
  {
    e.Surface = vtkSmartPointer<vtkDataSetSurfaceFilter>::New();
    e.Mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  }
  Configure(dataSetMapper, e);
  return e.Mapper;
}

void DataSetSurfaces::Configure(vtkDataSetMapper* from, Entry& e)
{
  vtkPolyDataMapper* to = e.Mapper;
  // Setters that change nothing leave the mapper's MTime, so a frame that
  // changes nothing maps no colors again.
  if (from->GetClippingPlanes() != to->GetClippingPlanes())
  {
    to->SetClippingPlanes(from->GetClippingPlanes());
  }
  if (!from->GetStatic())
  {
    from->Update();
  }
  vtkDataSet* input = from->GetInput();
  if (input && input->GetDataObjectType() == VTK_POLY_DATA)
  {
    if (to->GetInputConnection(0, 0) != from->GetInputConnection(0, 0))
    {
      to->SetInputConnection(from->GetInputConnection(0, 0));
    }
  }
  else
  {
    // A new input connection each call would run the filter every frame.
    if (e.Surface->GetInputDataObject(0, 0) != input)
    {
      e.Surface->SetInputData(input);
    }
    if (to->GetInputConnection(0, 0) != e.Surface->GetOutputPort())
    {
      to->SetInputConnection(e.Surface->GetOutputPort());
    }
  }
  vtkScalarsToColors* table = from->GetLookupTable(); // made by default, as Render does
  table->Build();
  to->SetLookupTable(table);
  to->SetScalarVisibility(from->GetScalarVisibility());
  to->SetUseLookupTableScalarRange(from->GetUseLookupTableScalarRange());
  to->SetScalarRange(from->GetScalarRange());
  to->SetColorMode(from->GetColorMode());
  to->SetInterpolateScalarsBeforeMapping(from->GetInterpolateScalarsBeforeMapping());
  double factor, units;
  from->GetRelativeCoincidentTopologyPolygonOffsetParameters(factor, units);
  to->SetRelativeCoincidentTopologyPolygonOffsetParameters(factor, units);
  from->GetRelativeCoincidentTopologyLineOffsetParameters(factor, units);
  to->SetRelativeCoincidentTopologyLineOffsetParameters(factor, units);
  from->GetRelativeCoincidentTopologyPointOffsetParameter(units);
  to->SetRelativeCoincidentTopologyPointOffsetParameter(units);
  to->SetScalarMode(from->GetScalarMode());
  const int mode = from->GetScalarMode();
  if (mode == VTK_SCALAR_MODE_USE_POINT_FIELD_DATA || mode == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA)
  {
    if (from->GetArrayAccessMode() == VTK_GET_ARRAY_BY_ID)
    {
      to->ColorByArrayComponent(from->GetArrayId(), from->GetArrayComponent());
    }
    else
    {
      to->ColorByArrayComponent(from->GetArrayName(), from->GetArrayComponent());
    }
  }
}

} // namespace pass
} // namespace vtkrt
