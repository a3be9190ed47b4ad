// vtkrt-render --scalars: colouring the meshes by a point or cell array
// through a named colormap, and the scalar bar.
#ifndef vtkrtRenderColoring_h
#define vtkrtRenderColoring_h

#include "vtkSmartPointer.h"

#include <string>

class vtkLookupTable;

namespace vtkrtRender
{
struct ScalarOptions;
struct Scene;

// A 256-entry table of the colormap `name` (one of ColormapNames()).
vtkSmartPointer<vtkLookupTable> NewColormap(const std::string& name);

// Maps the array `options` names (or each mesh's active scalars) through
// its colormap on every mesh of `scene`, over the given range or the union
// of the meshes' ranges, and adds the scalar bar when asked. Sets
// scene.Coloring. Throws UsageError for an array or component a mesh lacks.
void ColorByScalars(Scene& scene, const ScalarOptions& options);
} // namespace vtkrtRender

#endif
