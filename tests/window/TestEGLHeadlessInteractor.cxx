// Interactors on vtkEGLHeadlessRenderWindow. One executable, one CTest
// entry per case: TestEGLHeadlessInteractor <Case>.
//   Generic    MakeRenderWindowInteractor() gives a
//              vtkGenericRenderWindowInteractor, through which an
//              interactor style turns the camera on a mouse drag and a
//              picker picks
//   XRefused   a vtkXRenderWindowInteractor (what VTK's factory gives in
//              this X11 build) is refused with a VTK error and left
//              detached, so its Initialize() reports no window instead of
//              crashing in Xlib (it crashed before)
#include "vtkrtCheck.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkrtTestOutputWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkGenericRenderWindowInteractor.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropPicker.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkXRenderWindowInteractor.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

namespace
{
using vtkrtTest::Failures;
vtkrtTestOutputWindow* Output = nullptr;

using vtkrtTest::Check;

/// A window with a sphere in the middle.
struct Scene
{
  vtkNew<vtkEGLHeadlessRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkActor> Ball;

  Scene()
  {
    vtkNew<vtkSphereSource> sphere;
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    this->Ball->SetMapper(mapper);
    this->Renderer->AddActor(this->Ball);
    this->Renderer->SetBackground(0.0, 0.0, 0.0);
    this->Window->SetSize(160, 160);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->ResetCamera();
  }
};

void TestGeneric()
{
  Scene scene;
  // As vtkRenderWindow::MakeRenderWindowInteractor: the window points to the
  // interactor it makes, whose reference the caller does not take.
  vtkRenderWindowInteractor* interactor = scene.Window->MakeRenderWindowInteractor();
  Check(interactor && interactor->IsA("vtkGenericRenderWindowInteractor") &&
      interactor->GetRenderWindow() == scene.Window.Get() && scene.Window->GetInteractor() == interactor,
    std::string("MakeRenderWindowInteractor: a vtkGenericRenderWindowInteractor on the window (") +
      (interactor ? interactor->GetClassName() : "none") + ")");
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  interactor->Initialize();
  scene.Window->Render();
  double before[3], after[3];
  scene.Renderer->GetActiveCamera()->GetPosition(before);
  // A drag from the middle to the right, as an application forwards it.
  interactor->SetEventInformation(80, 80);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  for (int x = 84; x <= 120; x += 4)
  {
    interactor->SetEventInformation(x, 80);
    interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  }
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
  scene.Renderer->GetActiveCamera()->GetPosition(after);
  std::ostringstream s;
  s << "a drag turns the camera through the interactor style (x " << before[0] << " -> " << after[0] << ")";
  Check(std::abs(after[0] - before[0]) > 0.1, s.str());
  // The style's 'p' key picks with the interactor's picker where the
  // event is.
  vtkNew<vtkPropPicker> picker;
  interactor->SetPicker(picker);
  interactor->SetEventInformation(80, 80, 0, 0, 'p');
  interactor->InvokeEvent(vtkCommand::KeyPressEvent);
  interactor->InvokeEvent(vtkCommand::CharEvent);
  Check(picker->GetViewProp() == scene.Ball.Get(), "the 'p' key picks the sphere through the interactor");
  Check(Output->GetNumberOfErrors() == 0 && Output->GetNumberOfWarnings() == 0, "no VTK error or warning");
}

void TestXRefused()
{
  Scene scene;
  vtkNew<vtkXRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(scene.Window);
  Check(Output->HasErrorContaining("vtkGenericRenderWindowInteractor"),
    "a vtkXRenderWindowInteractor is refused with a VTK error naming the interactor to use");
  Check(interactor->GetRenderWindow() == nullptr && scene.Window->GetInteractor() == nullptr,
    "and left detached");
  const int errors = Output->GetNumberOfErrors();
  interactor->Initialize(); // crashed in XSync before
  Check(Output->GetNumberOfErrors() == errors + 1, "its Initialize() reports the missing window");
  scene.Window->Render();
  Check(scene.Window->GetNeverRendered() == 0, "the window still renders");
}
} // namespace

int main(int argc, char* argv[])
{
  Output = vtkrtTestOutputWindow::Install();
  const std::map<std::string, std::function<void()>> cases = {
    { "Generic", TestGeneric },
    { "XRefused", TestXRefused },
  };
  const std::string which = argc > 1 ? argv[1] : "";
  auto it = cases.find(which);
  if (it == cases.end())
  {
    std::cerr << "usage: TestEGLHeadlessInteractor <case>\n";
    return 1;
  }
  it->second();
  std::cout << (Failures == 0 ? "passed" : "FAILED") << ": " << Failures << " failure(s)\n";
  return Failures == 0 ? 0 : 1;
}
