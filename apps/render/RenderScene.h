// What vtkrt-render draws: mesh files, or the demo scene (the bunny and
// sphere glyphs), in one renderer, traced by vtkRayTracePass unless raster.
#ifndef vtkrtRenderScene_h
#define vtkrtRenderScene_h

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkProp.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

namespace vtkrtRender
{
class CapturingOutputWindow;
struct Options;

// One file of the scene: what was read, what is drawn.
struct SceneMesh
{
  std::string File;
  vtkSmartPointer<vtkPolyData> Mesh; // as drawn (with normals): the picking locator's input
  vtkSmartPointer<vtkActor> Actor;
  bool ComputedNormals = false; // Mesh's point normals are ours, not the file's
};

struct Scene
{
  vtkNew<vtkRenderer> Renderer;
  std::vector<SceneMesh> Meshes;
  vtkSmartPointer<vtkPolyData> SphereCentres; // glyph centres with a "radius" array
  vtkSmartPointer<vtkProp> ScalarBar;         // with --bar
  vtkIdType Triangles = 0;
  vtkIdType Points = 0; // of point clouds, drawn as spheres
  vtkIdType Spheres = 0;
  std::string Description;
  std::string Coloring; // what --scalars coloured by; empty without
};

// Fills `scene` with the demo or the mesh files of `opt`, coloured and lit
// as asked, its background and (in raytrace mode) the ray tracer with its
// knobs. VTK's reader errors are caught through `output`; throws Failure
// (UsageError for an array the files lack).
void BuildScene(Scene& scene, const Options& opt, CapturingOutputWindow* output);

// Puts the vtkrt ray tracer in charge of the renderer with the knobs of
// `opt`. Returns false when this build has no vtkRayTracePass.
bool UseRayTracing(vtkRenderer* renderer, const Options& opt);
} // namespace vtkrtRender

#endif
