// Reading one mesh file of vtkrt-render: the reader of its extension, the
// checks that keep a bad file from crashing VTK, a dataset's outer surface,
// and the triangle strips of a PLY file (which vtkPLYReader skips).
#ifndef vtkrtRenderRead_h
#define vtkrtRenderRead_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace vtkrtRender
{
class CapturingOutputWindow;

// The extensions ReadMesh takes, for messages: ".vtp .vtu ...".
std::string MeshExtensions();

// The polygons (or, for a point cloud, the points) of the file at `path`;
// VTK's reader errors are caught through `output`. Throws Failure.
vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& path, CapturingOutputWindow* output);
} // namespace vtkrtRender

#endif
