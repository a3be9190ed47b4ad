// Private to vtkRayTracePass: the polydata mapper a vtkDataSetMapper draws
// through, made as vtkDataSetMapper::Render makes its own (a
// vtkDataSetSurfaceFilter unless the input is polydata, the mapper's color
// settings copied), so that its surface is traced with the same cells, ids
// and colors as raster draws. No GL here.
#ifndef vtkRayTraceDataSetSurfaces_h
#define vtkRayTraceDataSetSurfaces_h

#include "vtkSmartPointer.h"

#include <map>

class vtkDataSetMapper;
class vtkDataSetSurfaceFilter;
class vtkMapper;
class vtkPolyDataMapper;

namespace vtkrt
{
namespace pass
{

/// A polydata mapper per vtkDataSetMapper, kept while the mapper is traced.
class DataSetSurfaces
{
public:
  /// Marks every surface unused (the frame's actors mark theirs).
  void BeginFrame();
  /// The mapper that draws `mapper`'s data: itself unless it is a
  /// vtkDataSetMapper, whose polydata mapper is brought up to date with it.
  vtkMapper* MapperFor(vtkMapper* mapper);
  /// Forgets the surfaces no actor used this frame.
  void EndFrame();

private:
  struct Entry
  {
    vtkSmartPointer<vtkDataSetSurfaceFilter> Surface;
    vtkSmartPointer<vtkPolyDataMapper> Mapper;
    bool Used = false;
  };
  /// What vtkDataSetMapper::Render gives its polydata mapper.
  static void Configure(vtkDataSetMapper* from, Entry& e);
  std::map<vtkMapper*, Entry> Entries;
};

} // namespace pass
} // namespace vtkrt

#endif
