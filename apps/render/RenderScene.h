// What vtkrt-render draws: a mesh file, or the demo scene (the bunny and
// sphere glyphs), in one renderer.
#ifndef vtkrtRenderScene_h
#define vtkrtRenderScene_h

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <string>

namespace vtkrtRender
{
class CapturingOutputWindow;
struct Options;

struct Scene
{
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkPolyData> Mesh;       // the triangle mesh (picking locator input)
  vtkSmartPointer<vtkActor> MeshActor;
  vtkSmartPointer<vtkPolyData> SphereCentres; // glyph centres with a "radius" array
  vtkIdType Triangles = 0;
  vtkIdType Spheres = 0;
  std::string Description;
};

// Fills `scene` with the demo or the mesh file of `opt`, its background and
// (in raytrace mode) the ray tracer. VTK's reader errors are caught through
// `output`; throws Failure.
void BuildScene(Scene& scene, const Options& opt, CapturingOutputWindow* output);

// Puts the vtkrt ray tracer in charge of the renderer. Returns false when
// this build has no vtkRayTracePass.
bool UseRayTracing(vtkRenderer* renderer);
} // namespace vtkrtRender

#endif
