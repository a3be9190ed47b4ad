// Uses an installed vtkrt as a VTK application would: renders a sphere
// headless with the ray tracing pass, checks a pixel, and intersects a line
// with the locator.
#include "vtkBVHCellLocator.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
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
  vtkNew<vtkRayTracePass> pass;
  renderer->SetPass(pass);
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(32, 32, 32, 32, 1, rgb, 0);
  const bool green = rgb->GetValue(1) > 100 && rgb->GetValue(0) < 50;
  std::cout << "center pixel " << int(rgb->GetValue(0)) << " " << int(rgb->GetValue(1)) << " "
            << int(rgb->GetValue(2)) << (green ? " (green: ok)" : " (expected green)") << std::endl;

  sphere->Update();
  vtkNew<vtkBVHCellLocator> locator;
  locator->SetDataSet(sphere->GetOutput());
  locator->BuildLocator();
  const double p1[3] = { 0.01, 0.02, 2.0 }, p2[3] = { 0.01, 0.02, -2.0 };
  double t, x[3], pcoords[3];
  int subId;
  vtkIdType cellId = -1;
  const int hit = locator->IntersectWithLine(p1, p2, 0.0, t, x, pcoords, subId, cellId);
  std::cout << "locator hit " << hit << " cell " << cellId << " z " << x[2] << std::endl;
  const bool picked = hit && cellId >= 0 && x[2] > 0.45 && x[2] <= 0.5;
  return green && picked && pass->GetNumberOfTracedProps() == 1 ? 0 : 1;
}
