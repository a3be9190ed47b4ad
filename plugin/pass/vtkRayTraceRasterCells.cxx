#include "vtkRayTraceRasterCells.h"

#include "vtkRayTraceTypes.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"

namespace vtkrt
{
namespace pass
{

void RasterCells::BeginFrame()
{
  markUnused(this->Entries);
}

void RasterCells::EndFrame()
{
  dropUnused(this->Entries);
}

vtkProp* RasterCells::OwnerOf(vtkProp* prop) const
{
  for (const auto& e : this->Entries)
  {
    if (e.second.Actor.GetPointer() == prop)
    {
      return e.first.first;
    }
  }
  return nullptr;
}

void RasterCells::CopyCells(vtkPolyData* poly, RasterCellKinds kinds, vtkPolyData* out)
{
  out->Initialize();
  out->SetPoints(poly->GetPoints());
  out->GetPointData()->ShallowCopy(poly->GetPointData());
  // VTK numbers cells verts, lines, polys, strips: the chosen kinds are one
  // run of them.
  const vtkIdType verts = poly->GetNumberOfVerts();
  const vtkIdType first = kinds.Verts ? 0 : verts;
  const vtkIdType count = (kinds.Verts ? verts : 0) + (kinds.Lines ? poly->GetNumberOfLines() : 0);
  if (kinds.Verts)
  {
    out->SetVerts(poly->GetVerts());
  }
  if (kinds.Lines)
  {
    out->SetLines(poly->GetLines());
  }
  vtkCellData* in = poly->GetCellData();
  vtkCellData* cells = out->GetCellData();
  cells->CopyAllocate(in, count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    cells->CopyData(in, first + i, i);
  }
}

vtkActor* RasterCells::Get(vtkProp* owner, int part, vtkActor* actor, vtkMapper* source,
  vtkPolyData* poly, RasterCellKinds kinds)
{
  Entry& e = this->Entries[{ owner, part }];
  e.Used = true;
  if (!e.Actor)
  {
    e.Actor = vtkSmartPointer<vtkActor>::New();
    e.Actor->SetMapper(vtkSmartPointer<vtkPolyDataMapper>::New());
    e.Actor->SetUserMatrix(vtkSmartPointer<vtkMatrix4x4>::New());
    e.Cells = vtkSmartPointer<vtkPolyData>::New();
  }
  if (e.Source != poly || e.SourceTime != poly->GetMTime() || e.Kinds.Verts != kinds.Verts ||
    e.Kinds.Lines != kinds.Lines)
  {
    CopyCells(poly, kinds, e.Cells);
    e.Source = poly;
    e.SourceTime = poly->GetMTime();
    e.Kinds = kinds;
  }
  // The actor's mapper settings (colors, lookup table, clipping planes,
  // coincident topology), then its cells: vtkMapper's copy, not the OpenGL
  // mapper's, which copies (deprecated) shader code too.
  auto* mapper = vtkPolyDataMapper::SafeDownCast(e.Actor->GetMapper());
  // A part index may pass to another actor of its assembly (one hidden).
  if (e.SourceMapper != source || mapper->GetMTime() < source->GetMTime() ||
    mapper->GetInput() != e.Cells)
  {
    mapper->vtkMapper::ShallowCopy(source);
    mapper->SetInputData(e.Cells);
    e.SourceMapper = source;
  }
  if (e.Actor->GetProperty() != actor->GetProperty())
  {
    e.Actor->SetProperty(actor->GetProperty());
  }
  if (e.Actor->GetBackfaceProperty() != actor->GetBackfaceProperty())
  {
    e.Actor->SetBackfaceProperty(actor->GetBackfaceProperty());
  }
  vtkMatrix4x4* matrix = e.Actor->GetUserMatrix();
  vtkMatrix4x4* wanted = actor->GetMatrix();
  bool same = true;
  for (int i = 0; i < 16 && same; ++i)
  {
    same = matrix->GetData()[i] == wanted->GetData()[i];
  }
  if (!same)
  {
    matrix->DeepCopy(wanted);
  }
  e.Actor->SetVisibility(actor->GetVisibility());
  e.Actor->SetPickable(false);
  return e.Actor;
}

} // namespace pass
} // namespace vtkrt
