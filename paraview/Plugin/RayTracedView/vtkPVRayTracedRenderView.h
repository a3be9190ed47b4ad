/**
 * @class   vtkPVRayTracedRenderView
 * @brief   ParaView render view that ray traces with vtkRayTracePass.
 *
 * A vtkPVRenderView whose renderer draws through vtkRayTracePass (set with
 * vtkPVSynchronizedRenderer::SetRenderPass, so in parallel the pass runs
 * inside IceT's composite pass on each rank's own piece and IceT composites
 * by the depth the tracer writes). What the pass does not trace (axes,
 * widgets, text, selection highlights, volumes, translucent geometry) is
 * drawn by its raster delegate, i.e. ParaView's usual passes.
 *
 * The pass's knobs and its quality preset are view properties (see the
 * server-manager XML "RayTracedRenderView"; a preset other than Custom
 * rules the knobs it sets). EnableRayTracing off gives ParaView's raster
 * rendering back in the same view.
 *
 * The view's FXAA (UseFXAA) applies to traced images as to raster ones, in
 * serial (the pass's raster steps apply the renderer's FXAA) and under IceT
 * (ParaView applies it to the composited image).
 *
 * Selection (SelectCells / SelectPoints, i.e. a click or a rubber band in the
 * GUI, SelectSurfaceCells/Points in Python) does not use the hardware
 * selector: each pixel of the region casts the ray the tracer casts, in
 * double, through a vtkBVHCellLocator per rendered block (cached per data
 * object and modification time), so a pick returns the cell that is drawn
 * there. With several rendering processes each rank casts against its own
 * piece, the nearest hit per pixel wins across ranks (ties: lowest rank), and
 * the driver process makes the selection, as ParaView's hardware selector
 * does. Point selection returns the hit cell's point nearest the hit.
 * Only props drawn as surfaces are selectable (rays meet surfaces; points,
 * including points rendered as spheres, and wireframes are not).
 * Hits map to original ids through the representation's id arrays
 * (vtkOriginalCellIds / vtkOriginalPointIds), like the hardware selector.
 */
#ifndef vtkPVRayTracedRenderView_h
#define vtkPVRayTracedRenderView_h

#include "vtkPVRenderView.h"
#include "vtkrtParaViewRayTracedViewModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkRayTracePass;

class VTKRTPARAVIEWRAYTRACEDVIEW_EXPORT vtkPVRayTracedRenderView : public vtkPVRenderView
{
public:
  static vtkPVRayTracedRenderView* New();
  vtkTypeMacro(vtkPVRayTracedRenderView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Ray tracing on (default) or ParaView's raster passes.
   */
  void SetEnableRayTracing(bool enable);
  vtkGetMacro(EnableRayTracing, bool);
  ///@}

  ///@{
  /**
   * The pass's quality preset (vtkRayTracePass::QualityPresets; default
   * CUSTOM). Under CUSTOM the pass takes the knobs below; under another
   * preset it takes the preset's knobs whatever the knob properties say
   * (except AmbientOcclusionRadius, which no preset sets). Unlike
   * vtkRayTracePass, where a knob set after a preset wins, the view does
   * not depend on the order its properties arrive in: ParaView pushes a
   * state's or an Apply's properties together, in no set order.
   */
  void SetQualityPreset(int preset);
  vtkGetMacro(QualityPreset, int);
  ///@}

  ///@{
  /**
   * The pass's knobs (see vtkRayTracePass), in effect under the CUSTOM
   * quality preset; the getters return the property values.
   */
  void SetSamplesPerPixel(int samples);
  int GetSamplesPerPixel();
  void SetProgressiveAccumulation(bool accumulate);
  bool GetProgressiveAccumulation();
  void SetShadows(bool shadows);
  bool GetShadows();
  void SetAmbientOcclusionSamples(int samples);
  int GetAmbientOcclusionSamples();
  void SetAmbientOcclusionRadius(double radius);
  double GetAmbientOcclusionRadius();
  void SetBuildQuality(int quality);
  int GetBuildQuality();
  void SetMaximumTraversalSteps(int steps);
  int GetMaximumTraversalSteps();
  void SetLeafSize(int size);
  int GetLeafSize();
  void SetPrecisionMode(int mode);
  int GetPrecisionMode();
  void SetTraceTranslucency(bool trace);
  bool GetTraceTranslucency();
  ///@}

  ///@{
  /**
   * vtkRayTracePass::BackgroundBuildThreshold, whatever the quality preset
   * (it changes the first frame, not the images).
   */
  void SetBackgroundBuildThreshold(vtkIdType triangles);
  vtkIdType GetBackgroundBuildThreshold();
  ///@}

  ///@{
  /**
   * What the pass traced in this process's last frame (primitives and
   * instances; 0 when nothing was traced, e.g. with ray tracing off), the
   * meshes whose background build is not taken yet, and the background
   * builds taken since the view was made.
   */
  vtkTypeInt64 GetLastTracedPrimitives();
  int GetLastTracedInstances();
  int GetNumberOfBackgroundBuilds();
  vtkIdType GetNumberOfBackgroundBuildsTaken();
  ///@}

  /**
   * The pass this view renders with.
   */
  vtkRayTracePass* GetRayTracePass();

  ///@{
  /**
   * Selection through vtkBVHCellLocator (see the class documentation);
   * with EnableRayTracing off, ParaView's hardware selector.
   * These hide vtkPVRenderView's (not virtual) methods of the same names:
   * ParaView's proxies call them by name, which reaches these.
   */
  void SelectCells(int region[4], const char* array = nullptr);
  void SelectCells(int region0, int region1, int region2, int region3, const char* array = nullptr)
  {
    int r[4] = { region0, region1, region2, region3 };
    this->SelectCells(r, array);
  }
  void SelectPoints(int region[4], const char* array = nullptr);
  void SelectPoints(int region0, int region1, int region2, int region3, const char* array = nullptr)
  {
    int r[4] = { region0, region1, region2, region3 };
    this->SelectPoints(r, array);
  }
  ///@}

  ///@{
  /**
   * Polygon selections go through ParaView's hardware selector, with the
   * ray tracing pass taken out for the selection renders (the selector
   * reads ids that raster passes write).
   */
  void SelectPolygonPoints(int* polygon2DArray, vtkIdType arrayLen);
  void SelectPolygonCells(int* polygon2DArray, vtkIdType arrayLen);
  ///@}

  /**
   * Rays cast by the last locator selection on this process, and the number
   * of locator trees built for it (for tests and diagnostics).
   */
  vtkGetMacro(LastSelectionRays, vtkIdType);
  vtkGetMacro(LastSelectionLocatorBuilds, int);

protected:
  vtkPVRayTracedRenderView();
  ~vtkPVRayTracedRenderView() override;

  void SelectWithLocator(int fieldAssociation, int region[4], const char* array);

  /**
   * Sets the pass's knobs from the knob properties, then the preset's.
   */
  void ApplyKnobs();

  bool EnableRayTracing = true;
  int QualityPreset = 0;
  vtkIdType LastSelectionRays = 0;
  int LastSelectionLocatorBuilds = 0;

private:
  vtkPVRayTracedRenderView(const vtkPVRayTracedRenderView&) = delete;
  void operator=(const vtkPVRayTracedRenderView&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
