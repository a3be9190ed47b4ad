#include "vtkRayTraceCompositePieces.h"

#include "vtkAbstractMapper.h"
#include "vtkColorTransferFunction.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkDataObject.h"
#include "vtkDataObjectTree.h"
#include "vtkDataObjectTreeRange.h"
#include "vtkLookupTable.h"
#include "vtkPolyData.h"

#include <algorithm>

namespace vtkrt
{
namespace pass
{

bool CollectPieces(vtkDataObject* object, vtkCompositeDataDisplayAttributes* attributes,
  bool visible, Piece inherited, unsigned int& flatIndex, std::vector<Piece>& pieces)
{
  inherited.FlatIndex = flatIndex++;
  if (!object)
  {
    return true;
  }
  if (attributes)
  {
    if (attributes->HasBlockVisibility(object))
    {
      visible = attributes->GetBlockVisibility(object);
    }
    if (attributes->HasBlockOpacity(object))
    {
      inherited.Opacity = attributes->GetBlockOpacity(object);
    }
    if (attributes->HasBlockPickability(object))
    {
      inherited.Pickable = attributes->GetBlockPickability(object);
    }
    if (attributes->HasBlockColor(object))
    {
      inherited.HasColor = true;
      attributes->GetBlockColor(object, inherited.Color.data());
    }
  }
  if (auto* poly = vtkPolyData::SafeDownCast(object))
  {
    inherited.Poly = poly;
    inherited.Visible = visible;
    pieces.push_back(inherited);
    return true;
  }
  if (auto* tree = vtkDataObjectTree::SafeDownCast(object))
  {
    bool ok = true;
    for (vtkDataObject* child : vtk::Range(tree, vtk::DataObjectTreeOptions::None))
    {
      ok = CollectPieces(child, attributes, visible, inherited, flatIndex, pieces) && ok;
    }
    return ok;
  }
  return false;
}

void ColorMissingArrays(vtkMapper* mapper, std::vector<Piece>& pieces)
{
  auto* m2 = vtkCompositePolyDataMapper2::SafeDownCast(mapper);
  if (!m2 || !m2->GetColorMissingArraysWithNanColor() || !m2->GetScalarVisibility())
  {
    return;
  }
  double nan[4] = { 0.0, 0.0, 0.0, 1.0 };
  vtkScalarsToColors* colors = m2->GetLookupTable();
  if (auto* lut = vtkLookupTable::SafeDownCast(colors))
  {
    lut->GetNanColor(nan);
  }
  else if (auto* ctf = vtkColorTransferFunction::SafeDownCast(colors))
  {
    ctf->GetNanColor(nan);
  }
  else
  {
    return;
  }
  for (Piece& piece : pieces)
  {
    int cellFlag = 0;
    if (!vtkAbstractMapper::GetAbstractScalars(piece.Poly, m2->GetScalarMode(),
          m2->GetArrayAccessMode(), m2->GetArrayId(), m2->GetArrayName(), cellFlag))
    {
      piece.HasColor = true;
      std::copy(nan, nan + 3, piece.Color.begin());
    }
  }
}

} // namespace pass
} // namespace vtkrt
