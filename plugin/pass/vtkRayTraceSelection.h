// Private to vtkRayTracePass: vtkHardwareSelector passes answered from the
// pass's own rays. For each selector pass the pass traces, per pixel, the
// hit prop, VTK id and composite index into a float buffer; then the
// selector renders the props as it does for raster (its prop ids, its
// colors, its pixel bookkeeping), the traced ones through stand-in mappers
// (vtkRayTraceSelectionMapper) that copy their own pixels out of that
// buffer in the encoding of the selector's current pass, with the traced
// depth, so raster props composite with them by depth.
#ifndef vtkRayTraceSelection_h
#define vtkRayTraceSelection_h

#include "vtkRayTraceTypes.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"

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

  /// Traces the id buffer over the frame's viewport (CameraFrame::
  /// ViewportSize) with `tracer` (built with Features::SelectIds, current,
  /// its samplers bound).
  void TraceIds(vtkOpenGLRenderWindow* win, const int viewportSize[2], vtkOpenGLQuadHelper* tracer);

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
  bool Traced = false;                     ///< the id buffer holds this pass's trace
  int Size[2] = { 0, 0 };
};

} // namespace pass
} // namespace vtkrt

#endif
