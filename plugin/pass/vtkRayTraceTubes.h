// Private to vtkRayTracePass: lines drawn as tubes (vtkProperty::
// RenderLinesAsTubes): which actors' lines are traced, and their segments
// as a Geometry whose BVH is over the bare segments (the radii come with
// each frame's camera, as for points drawn as spheres). No GL here.
#ifndef vtkRayTraceTubes_h
#define vtkRayTraceTubes_h

#include "vtkRayTraceTypes.h"

#include <memory>

class vtkPolyData;
class vtkProperty;

namespace vtkrt
{
namespace core
{
struct BuildOptions;
}
namespace pass
{

/// Whether the pass traces this property's line cells as tubes: in surface
/// representation, where VTK 9.1's vtkOpenGLPolyDataMapper draws them as
/// tubes (RenderLinesAsTubes with a LineWidth over one pixel; thinner
/// ones, LineWidth 0 included, are plain lines).
bool DrawsLinesAsTubes(vtkProperty* property);

/// One segment per pair of consecutive points of every line and polyline
/// cell, with the cell's VTK id (verts come first in VTK's cell order) and
/// its two point ids. Segments of zero length or with a non-finite point
/// are not traced (raster draws nothing for them either), nor are lines of
/// fewer than two points; their number is the geometry's SkippedPrimitives.
std::unique_ptr<Geometry> BuildTubes(vtkPolyData* poly, const core::BuildOptions& options);

} // namespace pass
} // namespace vtkrt

#endif
