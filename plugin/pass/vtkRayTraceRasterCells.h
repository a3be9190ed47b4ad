// Private to vtkRayTracePass: the cells of a traced actor that raster still
// draws (plain lines, vertices not drawn as spheres), as a stand-in actor
// over a polydata of those cells alone, with the actor's property, matrix
// and mapper settings, so that the actor's surfaces and tubes are traced and
// its thin lines and points still appear. No GL here.
#ifndef vtkRayTraceRasterCells_h
#define vtkRayTraceRasterCells_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <map>
#include <utility>

class vtkActor;
class vtkMapper;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkProp;

namespace vtkrt
{
namespace pass
{

/// Which cells of a polydata raster draws for a traced actor.
struct RasterCellKinds
{
  bool Verts = false; ///< vertices, when the actor does not draw them as spheres
  bool Lines = false; ///< lines, when the actor does not draw them as tubes
  bool Any() const { return this->Verts || this->Lines; }
};

/// Stand-in actors per traced actor (a prop, or a part of an assembly),
/// kept while the actor is traced.
class RasterCells
{
public:
  /// Marks every stand-in unused (the frame's actors mark theirs).
  void BeginFrame();
  /// The stand-in drawing `kinds` of `poly` as part `part` of renderer prop
  /// `owner`, `actor`, draws them through `mapper` (the actor's, or the
  /// polydata mapper of its vtkDataSetMapper), brought up to date with the
  /// actor (property, matrix as it is now), the mapper's settings and the
  /// data.
  vtkActor* Get(vtkProp* owner, int part, vtkActor* actor, vtkMapper* mapper, vtkPolyData* poly,
    RasterCellKinds kinds);
  /// Forgets the stand-ins no actor used this frame.
  void EndFrame();
  /// The renderer's traced prop a stand-in draws for, or null when `prop`
  /// is none.
  vtkProp* OwnerOf(vtkProp* prop) const;

private:
  struct Entry
  {
    vtkSmartPointer<vtkActor> Actor;
    vtkSmartPointer<vtkPolyData> Cells;
    vtkPolyData* Source = nullptr;
    vtkMapper* SourceMapper = nullptr; ///< whose settings the stand-in's mapper has
    vtkMTimeType SourceTime = 0;
    RasterCellKinds Kinds;
    bool Used = false;
  };
  /// Rebuilds the polydata of the chosen cells (shared points and point
  /// data, the cells' own cell data).
  static void CopyCells(vtkPolyData* poly, RasterCellKinds kinds, vtkPolyData* out);
  std::map<std::pair<vtkProp*, int>, Entry> Entries;
};

} // namespace pass
} // namespace vtkrt

#endif
