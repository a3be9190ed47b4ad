// Ray picking with vtkCellPicker + vtkBVHCellLocator: the picker asks the
// locator (exact, double precision) instead of testing every cell.
#include "vtkBVHCellLocator.h"
#include "vtkEGLHeadlessRenderWindow.h"

#include <vtkActor.h>
#include <vtkCellPicker.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include <cstdlib>
#include <iostream>

int main()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(128);
  sphere->SetPhiResolution(64);
  sphere->Update();
  vtkPolyData* mesh = sphere->GetOutput();

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkEGLHeadlessRenderWindow> window; // any vtkRenderWindow works
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  window->Render();

  // Build once; vtkCellPicker never builds the locators it is given.
  vtkNew<vtkBVHCellLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();

  vtkNew<vtkCellPicker> picker;
  picker->AddLocator(locator);
  picker->SetTolerance(0.0);
  if (!picker->Pick(230, 215, 0, renderer))
  {
    std::cerr << "nothing picked at pixel (230, 215)" << std::endl;
    return EXIT_FAILURE;
  }
  double p[3];
  picker->GetPickPosition(p);
  std::cout << "picked cell " << picker->GetCellId() << " at (" << p[0] << ", " << p[1] << ", "
            << p[2] << "), normal z " << picker->GetPickNormal()[2] << std::endl;

  // The same pick without the locator agrees.
  vtkNew<vtkCellPicker> plain;
  plain->SetTolerance(0.0);
  plain->Pick(230, 215, 0, renderer);
  std::cout << "without the locator: cell " << plain->GetCellId() << std::endl;
  return plain->GetCellId() == picker->GetCellId() ? EXIT_SUCCESS : EXIT_FAILURE;
}
