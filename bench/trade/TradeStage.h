// vtkrtBenchTrade's rendering: the fixed view of the run (Scene), the pass
// knobs of a traced view (PassSettings), and one rendered view of one mesh
// with its timings, image and depth (Stage).
#ifndef vtkrtTradeStage_h
#define vtkrtTradeStage_h

#include "TradeCommon.h"

#include "vtkActor.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRayTracePass.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <memory>
#include <vector>

class vtkCamera;

namespace vtkrtTrade
{
/// Where the camera looks from, fixed for the whole run.
struct Scene
{
  Point Center{ { 0, 0, 0 } };
  double Radius = 1.0;
  double Diagonal = 1.0;
  Point Direction{ { 0, 0, 1 } };
  double Distance = 1.0;
};

Scene MakeScene(vtkPolyData* mesh);

/// Points `camera` at the scene moved by `offset`.
void SetupCamera(vtkCamera* camera, const Scene& s, const Point& offset);

/// Pass knobs of one traced stage (defaults: the pass's own).
struct PassSettings
{
  int Preset = vtkRayTracePass::CUSTOM; // a quality preset instead of the knobs below
  int Quality = -1; // BuildQuality; -1 keeps the default
  int SamplesPerPixel = 1;
  int MaximumTraversalSteps = 0;
  bool Shadows = false;
  int AmbientOcclusionSamples = 0;
  bool Progressive = false;
  int LeafSize = 8;
  int PrecisionMode = vtkRayTracePass::CAMERA_RELATIVE;
  int Lights = 0; // > 0: this many scene lights instead of the headlight
};

/// One rendered view of one mesh: window, timings, image and depth.
struct Stage
{
  vtkSmartPointer<vtkEGLHeadlessRenderWindow> Window;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkActor> Actor;
  vtkSmartPointer<vtkRayTracePass> Pass;
  Point Offset{ { 0, 0, 0 } };
  double FirstSeconds = kNaN;
  double SteadySeconds = kNaN;    // median of the timed frames
  double SteadyMinSeconds = kNaN; // fastest of them (least disturbed by other load)
  int Width = 0, Height = 0;
  vtkSmartPointer<vtkImageData> Image;
  std::vector<float> Depth;
  vtkNew<vtkMatrix4x4> DisplayToWorld; // NDC -> world, inverse of the composite matrix

  ~Stage();

  /// The window's current image (RGB, no re-render).
  vtkSmartPointer<vtkImageData> GrabImage() const;

  /// World point under pixel (i, j) from the depth buffer, translation
  /// removed; false where the pixel shows background.
  bool Unproject(int i, int j, Point& x) const
  {
    const float z = this->Depth[static_cast<size_t>(j) * this->Width + i];
    if (!(z < 1.0f))
    {
      return false;
    }
    const double ndc[4] = { 2.0 * (i + 0.5) / this->Width - 1.0,
      2.0 * (j + 0.5) / this->Height - 1.0, 2.0 * z - 1.0, 1.0 };
    double w[4];
    this->DisplayToWorld->MultiplyPoint(ndc, w);
    for (int k = 0; k < 3; ++k)
    {
      x[k] = w[k] / w[3] - this->Offset[k];
    }
    return true;
  }
};

/// Renders `mesh` moved by `offset` in a fresh window (so the first frame
/// pays for everything: BVH build, upload, shader compile), traced with
/// `knobs` or raster, then opt.Frames timed frames; nullptr when no EGL
/// context could be made.
std::unique_ptr<Stage> RenderStage(vtkPolyData* mesh, const Scene& scene, const Point& offset,
  bool traced, const Options& opt, const PassSettings& knobs = PassSettings());
}

#endif
