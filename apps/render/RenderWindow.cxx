#include "RenderWindow.h"

#include "RenderErrors.h"
#include "RenderOptions.h"
#include "RenderPick.h"
#include "RenderReport.h"
#include "RenderScene.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkInteractorEventRecorder.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkObjectFactory.h"
#include "vtkRayTracePass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtksys/SystemTools.hxx"

#include <X11/Xlib.h>

#include <cstdlib>
#include <iomanip>
#include <iostream>

namespace vtkrtRender
{
namespace
{
// The trackball camera plus the viewer's keys; what a key changes is
// printed on stdout, so a session (or a test) can follow it.
class ViewerStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static ViewerStyle* New();
  vtkTypeMacro(ViewerStyle, vtkInteractorStyleTrackballCamera);

  Scene* TheScene = nullptr;
  const Options* TheOptions = nullptr;

  void OnChar() override;
  void OnKeyPress() override;

private:
  vtkRayTracePass* Pass()
  {
    return vtkRayTracePass::SafeDownCast(this->TheScene->Renderer->GetPass());
  }
  void ToggleShadows();
  void ToggleAmbientOcclusion();
  void PickUnderCursor();
};
vtkStandardNewMacro(ViewerStyle);

void ViewerStyle::OnChar()
{
  switch (this->Interactor->GetKeyCode())
  {
    case 'h':
    case 'H':
      this->ToggleShadows();
      break;
    case 'q':
    case 'Q':
      this->ToggleAmbientOcclusion();
      break;
    case 'b':
    case 'B':
      if (this->TheScene->ScalarBar)
      {
        this->TheScene->ScalarBar->SetVisibility(!this->TheScene->ScalarBar->GetVisibility());
        std::cout << "scalar bar " << (this->TheScene->ScalarBar->GetVisibility() ? "on" : "off")
                  << std::endl;
      }
      break;
    case 'p':
    case 'P':
      this->PickUnderCursor();
      return;
    default:
      this->Superclass::OnChar(); // r reset, w/s wireframe/surface, e quit, ...
      return;
  }
  this->Interactor->Render();
}

void ViewerStyle::OnKeyPress()
{
  const char* key = this->Interactor->GetKeySym();
  if (key && std::string(key) == "Escape")
  {
    this->Interactor->ExitCallback();
    return;
  }
  this->Superclass::OnKeyPress();
}

void ViewerStyle::ToggleShadows()
{
  vtkRayTracePass* pass = this->Pass();
  if (!pass)
  {
    std::cout << "shadows: raster mode has none" << std::endl;
    return;
  }
  pass->SetShadows(!pass->GetShadows());
  std::cout << "shadows " << (pass->GetShadows() ? "on" : "off") << std::endl;
}

void ViewerStyle::ToggleAmbientOcclusion()
{
  vtkRayTracePass* pass = this->Pass();
  if (!pass)
  {
    std::cout << "ambient occlusion: raster mode has none" << std::endl;
    return;
  }
  const int asked = this->TheOptions->Trace.AmbientOcclusion;
  pass->SetAmbientOcclusionSamples(
    pass->GetAmbientOcclusionSamples() > 0 ? 0 : (asked > 0 ? asked : 4));
  std::cout << "ambient occlusion " << pass->GetAmbientOcclusionSamples() << " rays" << std::endl;
}

void ViewerStyle::PickUnderCursor()
{
  const int* position = this->Interactor->GetEventPosition(); // bottom up
  const int* size = this->Interactor->GetRenderWindow()->GetSize();
  const Pixel pixel{ position[0], size[1] - 1 - position[1] };
  if (pixel.X < 0 || pixel.Y < 0 || pixel.X >= size[0] || pixel.Y >= size[1])
  {
    return;
  }
  std::cout << PickPixel(*this->TheScene, pixel, size[1]) << std::endl;
}

// What the window's timer needs to continue --progressive accumulation.
struct Accumulation
{
  Scene* TheScene;
  int Frames;
};

// Keeps rendering while the view is still until the pass holds the frames
// --progressive asks for, so a still window converges.
void ContinueAccumulating(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
  const auto* accumulation = static_cast<const Accumulation*>(clientData);
  auto* pass = vtkRayTracePass::SafeDownCast(accumulation->TheScene->Renderer->GetPass());
  if (pass && pass->GetAccumulatedFrames() < accumulation->Frames)
  {
    interactor->Render();
  }
}

void PlayEvents(vtkRenderWindowInteractor* interactor, const std::string& path)
{
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    throw Failure{ "cannot read events '" + path + "': no such file", ExitRuntimeError };
  }
  vtkNew<vtkInteractorEventRecorder> recorder;
  recorder->SetInteractor(interactor);
  recorder->SetFileName(path.c_str());
  recorder->Play();
  recorder->Off();
}
} // namespace

bool DisplayAvailable()
{
  const char* name = std::getenv("DISPLAY");
  if (!name || !*name)
  {
    return false;
  }
  Display* display = XOpenDisplay(nullptr);
  if (!display)
  {
    return false;
  }
  XCloseDisplay(display);
  return true;
}

int RunWindow(Scene& scene, const Options& opt)
{
  vtkSmartPointer<vtkRenderWindow> window = vtk::TakeSmartPointer(vtkRenderWindow::New());
  window->SetSize(opt.Width, opt.Height);
  window->SetMultiSamples(opt.Mode == "raster" && opt.Samples > 0 ? opt.Samples : 0);
  window->SetWindowName("vtkrt-render");
  window->AddRenderer(scene.Renderer);
  vtkSmartPointer<vtkRenderWindowInteractor> interactor =
    vtk::TakeSmartPointer(vtkRenderWindowInteractor::New());
  interactor->SetRenderWindow(window);
  vtkNew<ViewerStyle> style;
  style->TheScene = &scene;
  style->TheOptions = &opt;
  interactor->SetInteractorStyle(style);
  interactor->Initialize();

  const auto start = Clock::now();
  window->Render();
  std::cout << std::fixed << std::setprecision(1) << "vtkrt-render: " << opt.Mode << " window "
            << opt.Width << "x" << opt.Height << ", " << scene.Description << ", "
            << scene.Triangles << " triangles, first frame " << Milliseconds(start, Clock::now())
            << " ms" << std::endl;
  Accumulation accumulation{ &scene, opt.Trace.Progressive };
  vtkNew<vtkCallbackCommand> accumulate;
  if (opt.Trace.Progressive > 0)
  {
    accumulate->SetCallback(ContinueAccumulating);
    accumulate->SetClientData(&accumulation);
    interactor->AddObserver(vtkCommand::TimerEvent, accumulate);
    interactor->CreateRepeatingTimer(30);
  }
  if (!opt.InteractionPlay.empty())
  {
    PlayEvents(interactor, opt.InteractionPlay);
    const double* p = scene.Renderer->GetActiveCamera()->GetPosition();
    std::cout << std::setprecision(6) << "camera position (" << p[0] << ", " << p[1] << ", " << p[2]
              << ") after the events" << std::endl;
    return ExitOk;
  }
  interactor->Start();
  return ExitOk;
}
} // namespace vtkrtRender
