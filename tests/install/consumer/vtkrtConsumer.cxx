// Renders a sphere headless with an installed vtkrt and checks one pixel.
#include "vtkEGLHeadlessRenderWindow.h"

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>

#include <iostream>

int main()
{
  vtkNew<vtkEGLHeadlessRenderWindow> window;
  window->SetSize(64, 64);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  window->AddRenderer(renderer);
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0, 1, 0);
  renderer->AddActor(actor);
  renderer->ResetCamera();
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(32, 32, 32, 32, 1, rgb);
  const bool green = rgb->GetValue(1) > 100 && rgb->GetValue(0) < 50;
  std::cout << "center pixel " << int(rgb->GetValue(0)) << " " << int(rgb->GetValue(1)) << " "
            << int(rgb->GetValue(2)) << (green ? " (green: ok)" : " (expected green)") << std::endl;
  return green ? 0 : 1;
}
