// Private to vtkRayTracePass: sub-pixel sampling and progressive
// accumulation. The tracer adds each frame's samples into a float buffer
// (sum of hit colors, hit count) with the first frame's depth; the resolve
// draws their average, blended by coverage over the background. Any change
// of what the image is traced from restarts the sum.
#ifndef vtkRayTraceAccumulation_h
#define vtkRayTraceAccumulation_h

#include "vtkRayTraceTypes.h"

#include "vtkNew.h"

#include <memory>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

namespace vtkrt
{
namespace pass
{

/// What an accumulated image is traced from: the camera's matrices, the
/// same within a relative 1e-6 of each matrix's largest entry (a camera
/// moved by float rounding alone, as vtkWindowToImageFilter leaves its
/// view angle, is the same camera; a non-finite entry only bit for bit),
/// and the rest bit for bit. An accumulation compares with the signature of
/// its first frame.
struct ImageSignature
{
  std::vector<float> Camera;
  std::vector<float> Scene;

  bool Same(const ImageSignature& other) const;
  void Clear()
  {
    this->Camera.clear();
    this->Scene.clear();
  }
};

class Accumulation
{
public:
  Accumulation();
  ~Accumulation();

  /// Starts a frame: the frames accumulated so far, the count then 0 until
  /// Trace() says otherwise.
  int BeginFrame();

  /// Traces `samplesPerPixel` rays per pixel with `tracer` (current, its
  /// samplers bound) into the buffer. It restarts when `restart`, when the
  /// viewport was resized, when nothing was accumulated before
  /// (`framesBefore` 0) or when `signature` (what the image is traced from)
  /// changed; else it continues the sample sequence. With a `footprint`
  /// (window x, y, width, height; see TracedFootprint) only its pixels are
  /// traced: none outside it can hold a hit. The buffer covers the
  /// viewport (CameraFrame::ViewportSize, at ViewportOrigin in the target).
  void Trace(vtkOpenGLRenderWindow* win, const int viewportSize[2], const int viewportOrigin[2],
    vtkOpenGLQuadHelper* tracer, ImageSignature signature, bool restart, int framesBefore,
    int samplesPerPixel, const int* footprint);

  /// Draws the average into the bound framebuffer; false when the resolve
  /// shader does not compile.
  bool Resolve(vtkOpenGLRenderWindow* win, int samplesPerPixel, FrameCounters& counters);

  /// Frames averaged into the last image (0: the pass drew straight).
  int GetFrames() const { return this->Frames; }

  void Release(vtkWindow* w);

private:
  void Allocate(vtkOpenGLRenderWindow* win, int width, int height);

  vtkNew<vtkOpenGLFramebufferObject> FBO;
  vtkNew<vtkTextureObject> Color;
  vtkNew<vtkTextureObject> Depth;
  std::unique_ptr<vtkOpenGLQuadHelper> ResolveProgram;
  int Size[2] = { 0, 0 };
  ImageSignature Signature;
  int Frames = 0;
};

} // namespace pass
} // namespace vtkrt

#endif
