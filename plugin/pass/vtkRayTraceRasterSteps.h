/**
 * @class   vtkRayTraceRasterSteps
 * @brief   private to vtkRayTracePass: its default delegate, which draws the
 *          props the pass does not trace as vtkOpenGLRenderer draws them.
 *
 * After the traced image and its depth are in place (or the opaque steps
 * before it, where traced translucent layers lie over raster's props), the steps of
 * vtkOpenGLRenderer::UpdateGeometry without a pass, minus its clear: lights,
 * opaque geometry (through vtkHiddenLineRemovalPass when the renderer's
 * UseHiddenLineRemoval is on and a wireframe is among the props, as the
 * renderer does), translucent geometry (only when some prop has any) in
 * depth order as the renderer says — order-independent blending, or depth
 * peeling (dual when the context supports it) with the renderer's
 * MaximumNumberOfPeels and OcclusionRatio, volumes peeled with them when
 * UseDepthPeelingForVolumes —, the renderer's FXAA when UseFXAA is on
 * (over the traced image and the raster one alike), volumes, overlays.
 */
#ifndef vtkRayTraceRasterSteps_h
#define vtkRayTraceRasterSteps_h

#include "vtkRenderPass.h"
#include "vtkSmartPointer.h"

class vtkDepthPeelingPass;
class vtkOpenGLFXAAFilter;
class vtkOpenGLRenderer;
class vtkOrderIndependentTranslucentPass;

class vtkRayTraceRasterSteps : public vtkRenderPass
{
public:
  static vtkRayTraceRasterSteps* New();
  vtkTypeMacro(vtkRayTraceRasterSteps, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  /// Render in two parts: lights and opaque geometry, then the rest.
  /// vtkRayTracePass draws the first before its trace when traced
  /// translucent layers must composite over raster's opaque props.
  void RenderOpaque(const vtkRenderState* s);
  void RenderAfterOpaque(const vtkRenderState* s);

protected:
  vtkRayTraceRasterSteps();
  ~vtkRayTraceRasterSteps() override;

private:
  vtkRayTraceRasterSteps(const vtkRayTraceRasterSteps&) = delete;
  void operator=(const vtkRayTraceRasterSteps&) = delete;

  /// Resets the count; the renderer of `s`, or nullptr with an error.
  vtkOpenGLRenderer* Begin(const vtkRenderState* s);
  /// Renders `pass` over `s` and counts its props.
  void Step(vtkRenderPass* pass, const vtkRenderState* s);
  /// The translucent step; true when it peeled the volumes too.
  bool Translucent(const vtkRenderState* s, vtkOpenGLRenderer* ren);
  /// The renderer's FXAA over what is drawn so far, as vtkOpenGLRenderer
  /// applies it between translucent geometry and volumes.
  void FXAA(vtkOpenGLRenderer* ren);

  vtkSmartPointer<vtkRenderPass> Lights;
  vtkSmartPointer<vtkRenderPass> Opaque;
  vtkSmartPointer<vtkRenderPass> HiddenLines; ///< made on first use
  vtkSmartPointer<vtkRenderPass> Volumes;
  vtkSmartPointer<vtkRenderPass> Overlay;
  vtkSmartPointer<vtkOrderIndependentTranslucentPass> Blended;
  vtkSmartPointer<vtkDepthPeelingPass> Peeled; ///< made on first use: dual when supported
  vtkSmartPointer<vtkOpenGLFXAAFilter> FXAAFilter; ///< made on first use
};

#endif
