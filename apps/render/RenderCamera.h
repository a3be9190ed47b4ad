// vtkrt-render's view: the requested orbit of the camera, zoomed until the
// scene fills the image.
#ifndef vtkrtRenderCamera_h
#define vtkrtRenderCamera_h

namespace vtkrtRender
{
struct Options;
struct Scene;

// Resets the camera on the scene, orbits it by opt.Azimuth and
// opt.Elevation, then frames the scene for the image's aspect.
void AimCamera(Scene& scene, const Options& opt);
} // namespace vtkrtRender

#endif
