// Checks that keep a bad mesh file from crashing or hanging VTK 9.1's
// readers and filters: a PLY header against the file's size before reading,
// and every cell's point ids and size after reading.
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

// Throws Failure (runtime error) naming `path` when it is empty, or is a
// binary STL (by content, as vtkSTLReader decides) shorter than its
// triangle count says: vtkSTLReader reads such a file's first triangles
// without a word.
void CheckStlFile(const std::string& path);

// Throws Failure (runtime error) naming `path` when a cell of `data` (poly
// data or an unstructured grid) refers to a point id outside
// [0, number of points), or a polydata cell has fewer points than its kind
// needs (a polygon or strip 3, a line 2, a vertex cell 1).
void CheckCells(vtkDataObject* data, const std::string& path);
} // namespace vtkrtRender

#endif
