// Private modules of vtkOpenMeshDecimation: the greedy collapse loop and the
// costs and guards it consults (boundary-aware quadrics, a two-sided
// distance guard), over OpenMesh's halfedge mesh.
#ifndef vtkOpenMeshDecimationModules_h
#define vtkOpenMeshDecimationModules_h

#include "vtkOpenMeshInternals.h"

#include <cstddef>

class vtkStaticCellLocator;

namespace vtkrt_filters
{
namespace decimation
{

struct DecimationLimits
{
  double MaximumError = -1.0; // < 0: unbounded
  double MaximumNormalDeviation = 180.0;
  double MaximumAspectRatio = 0.0;
  double BoundaryWeight = 1.0;
};

// Collapses halfedges of `mesh` until it has `targetFaces` faces or no legal
// collapse is left; `input` (may be null) locates the input surface for the
// distance guard when limits.MaximumError >= 0.
void Decimate(vtkrt_filters::OpenMeshTriMesh& mesh, size_t targetFaces,
  const DecimationLimits& limits, vtkStaticCellLocator* input);

} // namespace decimation
} // namespace vtkrt_filters

#endif
