// vtkrt-render's headless window and its frames: the first one, which
// creates the context, and the steady orbit frames that are timed.
#ifndef vtkrtRenderFrames_h
#define vtkrtRenderFrames_h

#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkSmartPointer.h"

class vtkRenderer;

namespace vtkrtRender
{
class CapturingOutputWindow;
struct Options;

// A window of the image's size holding `renderer`; MSAA samples in raster
// mode only.
vtkSmartPointer<vtkEGLHeadlessRenderWindow> NewWindow(const Options& opt, vtkRenderer* renderer);

// Renders the first frame and returns its milliseconds. A failure to create
// the context throws Failure with VTK's message (caught through `output`);
// anything else VTK says is passed on to stderr.
double RenderFirstFrame(vtkEGLHeadlessRenderWindow* window, CapturingOutputWindow* output);

// Waits for the pass's background builds and takes them with a frame: the
// timed orbit and the accumulation then run on the trees the pass keeps (a
// tree taken later would restart an accumulation).
void TakeBackgroundBuilds(vtkEGLHeadlessRenderWindow* window, vtkRenderer* renderer);

// Orbits one full turn in `frames` steps, then returns to the requested view
// exactly; the mean milliseconds of a step, 0 when `frames` is 0.
double SteadyFrameMilliseconds(
  vtkEGLHeadlessRenderWindow* window, vtkRenderer* renderer, int frames);

// Renders until the ray tracer has accumulated `frames` frames of the
// still view (--progressive); returns how many it holds (0 without a pass).
int AccumulateFrames(vtkEGLHeadlessRenderWindow* window, vtkRenderer* renderer, int frames);
} // namespace vtkrtRender

#endif
