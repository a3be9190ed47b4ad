// Private to vtkRayTracePass: the depth a renderer draws over (it keeps the
// depth buffer: PreserveDepthBuffer, Erase off, or raster's opaque props
// drawn before the trace), taken from the drawn viewport into a texture
// that the tracer samples (uDepthBelow) to end its camera rays there.
#ifndef vtkRayTraceDepthBelow_h
#define vtkRayTraceDepthBelow_h

#include "vtkNew.h"

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace vtkrt
{
namespace pass
{

class DepthBelow
{
public:
  DepthBelow();
  ~DepthBelow();

  /// The depth of `size` pixels at `origin` in the framebuffer drawn to, as
  /// a texture of that size: copied from a single-sample framebuffer, or
  /// resolved by a blit into a texture of the same depth format from a
  /// multisampled one (GL blits depth only between equal formats). Where
  /// it cannot be taken (a depth format vtkTextureObject does not make), a
  /// texture of the far plane's depth, with one VTK warning.
  vtkTextureObject* Take(vtkOpenGLRenderWindow* win, const int size[2], const int origin[2]);

  void Release(vtkWindow* w);

private:
  vtkTextureObject* Copy(vtkOpenGLRenderWindow* win, unsigned int width, unsigned int height,
    const int origin[2]);
  vtkTextureObject* Resolve(vtkOpenGLRenderWindow* win, unsigned int width, unsigned int height,
    const int origin[2]);
  /// One texel of depth 1: nothing below.
  vtkTextureObject* Nothing(vtkOpenGLRenderWindow* win);

  vtkNew<vtkTextureObject> Copied;
  vtkNew<vtkTextureObject> Resolved;
  vtkNew<vtkOpenGLFramebufferObject> ResolveTarget;
  vtkNew<vtkTextureObject> Far;
  int ResolvedFormat = 0; ///< the GL internal format Resolved was allocated with
  int WarnedFormat = 0;   ///< the last format that could not be resolved (warned once)
};

} // namespace pass
} // namespace vtkrt

#endif
