// Private to vtkRayTracePass: vtkHardwareSelector passes answered from the
// pass's own rays. The first pass of a selector's capture traces, per pixel
// of the selection's area, the hit prop, VTK id and composite index into a
// float buffer, which its later passes (and later selections of the same
// pixels while nothing changes) read again; then the
// selector renders the props as it does for raster (its prop ids, its
// colors, its pixel bookkeeping), the traced ones through stand-in mappers
// (vtkRayTraceSelectionMapper) that copy their own pixels out of that
// buffer in the encoding of the selector's current pass, with the traced
// depth, so raster props composite with them by depth.
#ifndef vtkRayTraceSelection_h
#define vtkRayTraceSelection_h

#include "vtkRayTraceAccumulation.h"
#include "vtkRayTraceTypes.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

class vtkActor;
class vtkHardwareSelector;
class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkProp;
class vtkRayTraceSelectionMapper;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

namespace vtkrt
{
namespace pass
{

/// A traced prop as the selector sees it.
struct SelectableProp
{
  vtkProp* Prop = nullptr; ///< the renderer's prop
  /// The actors it draws (an assembly's parts), whose mappers draw its ids.
  std::vector<vtkActor*> Actors;
  std::uint32_t MaximumId = 0; ///< the largest VTK id its pixels can carry
};

/// The traced props (prop index order) with the actors they draw and the
/// largest id their instances carry.
std::vector<SelectableProp> SelectablePropsOf(
  const std::vector<vtkProp*>& traced, const std::vector<Instance>& instances);

/// The props a selector pass renders, as vtkOpenGLRenderer::UpdateGeometry
/// hands them to vtkHardwareSelector::Render: the renderer's pick list
/// (its visible props) when it has one, else the render state's props.
std::vector<vtkProp*> SelectionProps(vtkRenderer* ren, vtkProp** props, int count);

class Selection
{
public:
  Selection();
  ~Selection();

  /// The part of `selector`'s area (display pixels) inside the viewport of
  /// size `viewportSize` at `viewportOrigin`, as (x, y, width, height)
  /// from the viewport's corner: the pixels a selection reads.
  static std::array<int, 4> AreaInViewport(
    vtkHardwareSelector* selector, const int viewportOrigin[2], const int viewportSize[2]);

  /// Whether the id buffer holds a trace over `area` of the scene and
  /// camera that `signature` describes: the passes of one capture, and
  /// later selections of the same pixels while nothing changes, read it
  /// again.
  bool Holds(const ImageSignature& signature, const std::array<int, 4>& area) const;

  /// Forgets the trace: the next selection pass traces again.
  void Invalidate();

  /// Traces the id buffer over `area` of the frame's viewport (CameraFrame::
  /// ViewportSize, at ViewportOrigin) with `tracer` (built with
  /// Features::SelectIds, current, its samplers bound), for the scene and
  /// camera of `signature`; the rest of the buffer holds no hit.
  void TraceIds(vtkOpenGLRenderWindow* win, const int viewportOrigin[2], const int viewportSize[2],
    const std::array<int, 4>& area, vtkOpenGLQuadHelper* tracer, ImageSignature signature);

  /// Renders the selector's current pass over `props` through
  /// vtkHardwareSelector::Render, traced prop i (traced[i]) drawn from the
  /// id buffer by a stand-in mapper; returns the props rendered.
  int RenderPass(vtkOpenGLRenderWindow* win, vtkRenderer* ren, vtkHardwareSelector* selector,
    std::vector<vtkProp*>& props, const std::vector<SelectableProp>& traced,
    FrameCounters& counters);

  /// Which traced prop the selector is rendering (-1: one the pass left to
  /// raster), so that an actor in two props (assemblies) draws each one's
  /// pixels.
  int CurrentIndex(vtkHardwareSelector* selector) const;
  /// The largest VTK id traced prop `index`'s pixels carry.
  std::uint32_t MaximumId(int index) const;

  /// Draws traced prop `index`'s pixels in the encoding of the selector's
  /// current pass (what its stand-in mapper renders).
  void DrawProp(vtkHardwareSelector* selector, int index);

  void Release(vtkWindow* w);

private:
  void Allocate(vtkOpenGLRenderWindow* win, int width, int height);

  vtkNew<vtkOpenGLFramebufferObject> FBO;
  vtkNew<vtkTextureObject> Ids;
  vtkNew<vtkTextureObject> Depth;
  std::unique_ptr<vtkOpenGLQuadHelper> DrawProgram;
  std::vector<vtkSmartPointer<vtkRayTraceSelectionMapper>> StandIns;
  const std::vector<SelectableProp>* Props = nullptr; ///< during RenderPass
  vtkOpenGLRenderWindow* Window = nullptr; ///< during RenderPass
  FrameCounters* Counters = nullptr;       ///< during RenderPass
  bool Traced = false; ///< the id buffer holds a trace
  /// What it traced: the scene and camera, the area (viewport pixels),
  /// the viewport's corner in the window.
  ImageSignature TracedSignature;
  std::array<int, 4> TracedArea = { 0, 0, 0, 0 };
  int TracedOrigin[2] = { 0, 0 };
  int Size[2] = { 0, 0 };
};

} // namespace pass
} // namespace vtkrt

#endif
