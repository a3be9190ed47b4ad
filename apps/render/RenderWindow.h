// vtkrt-render's interactive window: VTK's desktop window (X11, from the
// default factory) traced by the pass, a trackball camera and keys to
// toggle shadows, ambient occlusion and the scalar bar, and to pick the cell
// under the cursor.
#ifndef vtkrtRenderWindow_h
#define vtkrtRenderWindow_h

namespace vtkrtRender
{
struct Options;
struct Scene;

// True when an X display can be opened (DISPLAY set and a server behind it).
bool DisplayAvailable();

// Opens the window on `scene` and runs its event loop until closed, or plays
// opt.InteractionPlay's events and returns. Returns the exit status.
int RunWindow(Scene& scene, const Options& opt);
} // namespace vtkrtRender

#endif
