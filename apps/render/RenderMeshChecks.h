// Checks that keep a bad mesh file from crashing or hanging VTK 9.1's
// readers and filters: a PLY header against the file's size before reading,
// and every cell's point ids after reading.
#ifndef vtkrtRenderMeshChecks_h
#define vtkrtRenderMeshChecks_h

#include <string>

class vtkDataObject;

namespace vtkrtRender
{
// Throws Failure (runtime error) naming `path` when its PLY header is
// malformed or its data is shorter than the header declares (an element cut
// short, a line with too few values).
void CheckPlyFile(const std::string& path);

// Throws Failure (runtime error) naming `path` when a cell of `data` (poly
// data or an unstructured grid) refers to a point id outside
// [0, number of points).
void CheckPointIds(vtkDataObject* data, const std::string& path);
} // namespace vtkrtRender

#endif
