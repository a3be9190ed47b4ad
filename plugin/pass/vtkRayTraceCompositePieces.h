// Private to vtkRayTracePass: a composite input's polydata leaves as
// vtkCompositePolyDataMapper2 walks and draws them (block visibility,
// color, opacity, pickability, the NaN color of blocks without the colored
// array). No GL here.
#ifndef vtkRayTraceCompositePieces_h
#define vtkRayTraceCompositePieces_h

#include <array>
#include <vector>

class vtkCompositeDataDisplayAttributes;
class vtkDataObject;
class vtkMapper;
class vtkPolyData;

namespace vtkrt
{
namespace pass
{

/// A polydata leaf of a composite input with what its blocks give it.
struct Piece
{
  vtkPolyData* Poly;
  bool HasColor;
  std::array<double, 3> Color;
  unsigned int FlatIndex; ///< the composite index hardware selection reports
  double Opacity = -1.0;  ///< the block opacity it inherits; negative: none
  bool Pickable = true;   ///< the block pickability it inherits
  bool Visible = true;    ///< false: a hidden block, whose geometry is only kept
};

/// Walks a composite dataset as vtkCompositePolyDataMapper2 does: block
/// visibility, color and opacity apply to the block and everything below
/// it (pickability too, for selections), and blocks are numbered in its
/// order (flatIndex: the next block's number; an empty child takes one
/// too). A block opacity replaces the property's, as
/// vtkCompositePolyDataMapper2 draws it. Hidden leaves are listed, not
/// Visible. Returns false when something cannot be traced (a non-polydata
/// leaf).
bool CollectPieces(vtkDataObject* object, vtkCompositeDataDisplayAttributes* attributes,
  bool visible, Piece inherited, unsigned int& flatIndex, std::vector<Piece>& pieces);

/// vtkCompositePolyDataMapper2's ColorMissingArraysWithNanColor: a block
/// without the array the mapper colors by is drawn in the lookup table's
/// NaN color (its RGB replaces the ambient and diffuse colors, as a block
/// color does; the block keeps its opacity).
void ColorMissingArrays(vtkMapper* mapper, std::vector<Piece>& pieces);

} // namespace pass
} // namespace vtkrt

#endif
