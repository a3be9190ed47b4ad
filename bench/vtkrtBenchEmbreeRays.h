// vtkrtBenchEmbreeRays: the camera rays a frame of vtkrtBenchPass casts,
// cast on the CPU by Embree 3 instead (packets of 8, every core), as a
// native tracer's time for the same pixels.
#ifndef vtkrtBenchEmbreeRays_h
#define vtkrtBenchEmbreeRays_h

#include <functional>

class vtkPolyData;
class vtkRenderer;

namespace vtkrtBench
{
/// What Embree took for a scene, ms.
struct EmbreeTiming
{
  double Build = 0;  ///< building its scene (high quality, robust)
  double Steady = 0; ///< per frame: the view's camera rays, one per pixel, and a facing-ratio shade
  double SteadyCpu = 0; ///< process CPU time per frame, every thread
};

/// Casts, `frames` times, one ray through each pixel centre of `ren`'s
/// viewport (width x height) from its active camera, moved by `step`
/// before each frame as the pass's orbit is, against the triangles of
/// `mesh` (its polygons, fan triangulated).
EmbreeTiming EmbreePrimaryRays(vtkPolyData* mesh, vtkRenderer* ren, int width, int height,
  int frames, const std::function<void(vtkRenderer*, int)>& step);
}

#endif
