#include "TradeStage.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace vtkrtTrade
{
double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return kNaN;
  }
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

bool NoContext()
{
  std::cerr << "vtkrtBenchTrade: no EGL context\n";
  return false;
}

Scene MakeScene(vtkPolyData* mesh)
{
  Scene s;
  double b[6];
  mesh->GetBounds(b);
  for (int k = 0; k < 3; ++k)
  {
    s.Center[k] = 0.5 * (b[2 * k] + b[2 * k + 1]);
  }
  s.Diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  s.Radius = 0.5 * s.Diagonal;
  const double d[3] = { 0.35, 0.25, 1.0 };
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  s.Direction = { { d[0] / n, d[1] / n, d[2] / n } };
  // Fill most of a 30-degree view with the bounding sphere.
  s.Distance = 0.8 * s.Radius / std::sin(vtkMath::RadiansFromDegrees(15.0));
  return s;
}

void SetupCamera(vtkCamera* camera, const Scene& s, const Point& offset)
{
  double focal[3], position[3];
  for (int k = 0; k < 3; ++k)
  {
    focal[k] = s.Center[k] + offset[k];
    position[k] = focal[k] + s.Distance * s.Direction[k];
  }
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30.0);
  camera->SetClippingRange(
    std::max(0.05 * s.Distance, s.Distance - 1.1 * s.Radius), s.Distance + 1.1 * s.Radius);
}

Stage::~Stage()
{
  if (this->Window)
  {
    this->Window->Finalize();
  }
}

vtkSmartPointer<vtkImageData> Stage::GrabImage() const
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(this->Window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOn();
  grab->ShouldRerenderOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

namespace
{
/// `count` scene lights of total intensity 1 around the camera's side of the
/// object: directional and positional (spot) lights alternately, above.
void AddSceneLights(vtkRenderer* ren, const Scene& s, const Point& offset, int count)
{
  for (int i = 0; i < count; ++i)
  {
    const double phi = 2.0 * vtkMath::Pi() * (i + 0.25) / count;
    const double dir[3] = { 0.8 * std::cos(phi) + 0.3 * s.Direction[0], 1.0,
      0.8 * std::sin(phi) + 0.6 * s.Direction[2] };
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    double focal[3], position[3];
    for (int k = 0; k < 3; ++k)
    {
      focal[k] = s.Center[k] + offset[k];
      position[k] = focal[k] + 2.0 * s.Radius * dir[k];
    }
    light->SetFocalPoint(focal);
    light->SetPosition(position);
    light->SetIntensity(1.0 / count);
    if (i % 2 == 1)
    {
      light->SetPositional(true);
      light->SetConeAngle(60.0);
    }
    ren->AddLight(light);
  }
}

/// The pass of a traced stage, set up with `knobs`.
vtkSmartPointer<vtkRayTracePass> MakePass(const PassSettings& knobs)
{
  auto pass = vtkSmartPointer<vtkRayTracePass>::New();
  if (knobs.Preset != vtkRayTracePass::CUSTOM)
  {
    pass->SetQualityPreset(knobs.Preset);
    return pass;
  }
  if (knobs.Quality >= 0)
  {
    pass->SetBuildQuality(knobs.Quality);
  }
  pass->SetSamplesPerPixel(knobs.SamplesPerPixel);
  pass->SetMaximumTraversalSteps(knobs.MaximumTraversalSteps);
  pass->SetShadows(knobs.Shadows);
  pass->SetAmbientOcclusionSamples(knobs.AmbientOcclusionSamples);
  pass->SetProgressiveAccumulation(knobs.Progressive);
  pass->SetLeafSize(knobs.LeafSize);
  pass->SetPrecisionMode(knobs.PrecisionMode);
  return pass;
}

/// Window, renderer, actor, camera, pass and lights of a stage, not yet
/// initialized.
std::unique_ptr<Stage> MakeStage(vtkPolyData* mesh, const Scene& scene, const Point& offset,
  bool traced, const Options& opt, const PassSettings& knobs)
{
  auto st = std::make_unique<Stage>();
  st->Offset = offset;
  st->Window = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  st->Window->SetSize(opt.Size, opt.Size);
  st->Window->SetMultiSamples(0);
  st->Renderer = vtkSmartPointer<vtkRenderer>::New();
  st->Renderer->SetBackground(0.12, 0.12, 0.15);
  st->Window->AddRenderer(st->Renderer);

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->ScalarVisibilityOff();
  st->Actor = vtkSmartPointer<vtkActor>::New();
  st->Actor->SetMapper(mapper);
  st->Actor->GetProperty()->SetColor(0.92, 0.82, 0.66);
  st->Actor->GetProperty()->SetSpecular(0.3);
  st->Actor->GetProperty()->SetSpecularPower(30.0);
  st->Renderer->AddActor(st->Actor);
  SetupCamera(st->Renderer->GetActiveCamera(), scene, offset);
  if (traced)
  {
    st->Pass = MakePass(knobs);
    st->Renderer->SetPass(st->Pass);
  }
  if (knobs.Lights > 0)
  {
    AddSceneLights(st->Renderer, scene, offset, knobs.Lights);
  }
  return st;
}

/// The first frame, then `frames` timed steady frames. Between them,
/// untimed, the pass's background builds are waited for and taken (a tree
/// taken later would restart an accumulation at a frame that depends on the
/// machine's load).
void TimeFrames(Stage& st, int frames)
{
  auto t0 = Clock::now();
  st.Window->Render();
  st.Window->WaitForCompletion();
  st.FirstSeconds = Seconds(t0, Clock::now());
  if (st.Pass && st.Pass->GetNumberOfBackgroundBuilds() > 0)
  {
    st.Pass->WaitForBackgroundBuilds();
    st.Window->Render();
    st.Window->WaitForCompletion();
  }
  std::vector<double> times;
  for (int f = 0; f < frames; ++f)
  {
    t0 = Clock::now();
    st.Window->Render();
    st.Window->WaitForCompletion();
    times.push_back(Seconds(t0, Clock::now()));
  }
  if (!times.empty())
  {
    st.SteadySeconds = Median(times);
    st.SteadyMinSeconds = *std::min_element(times.begin(), times.end());
  }
}

/// The last frame's image, depth buffer and display-to-world matrix.
void Capture(Stage& st)
{
  st.Image = st.GrabImage();

  const int* size = st.Window->GetSize();
  st.Width = size[0];
  st.Height = size[1];
  st.Depth.resize(static_cast<size_t>(st.Width) * st.Height);
  st.Window->GetZbufferData(0, 0, st.Width - 1, st.Height - 1, st.Depth.data());

  vtkCamera* camera = st.Renderer->GetActiveCamera();
  st.DisplayToWorld->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(st.Renderer->GetTiledAspectRatio(), -1, 1));
  st.DisplayToWorld->Invert();
}
}

std::unique_ptr<Stage> RenderStage(vtkPolyData* mesh, const Scene& scene, const Point& offset,
  bool traced, const Options& opt, const PassSettings& knobs)
{
  std::unique_ptr<Stage> st = MakeStage(mesh, scene, offset, traced, opt, knobs);
  st->Window->Initialize();
  if (!st->Window->IsContextReady())
  {
    return nullptr;
  }
  TimeFrames(*st, opt.Frames);
  Capture(*st);
  return st;
}
}
