// An offscreen regression test of your own scene: render it ray traced
// headless and compare with a baseline PNG (written on the first run, or with
// --update).   Usage: RegressionTest BASELINE.png [--update]
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"

#include <vtkActor.h>
#include <vtkConeSource.h>
#include <vtkImageDifference.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>
#include <vtksys/SystemTools.hxx>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: " << argv[0] << " BASELINE.png [--update]" << std::endl;
    return 2;
  }
  const std::string baseline = argv[1];
  const bool update = argc > 2 && std::strcmp(argv[2], "--update") == 0;

  // Your scene here.
  vtkNew<vtkConeSource> cone;
  cone->SetResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cone->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.3, 0.3);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(1, 1, 1);
  renderer->ResetCamera();
  vtkNew<vtkRayTracePass> pass;
  renderer->SetPass(pass);

  vtkNew<vtkEGLHeadlessRenderWindow> window;
  window->SetSize(300, 300);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();

  if (update || !vtksys::SystemTools::FileExists(baseline))
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputConnection(grab->GetOutputPort());
    writer->SetFileName(baseline.c_str());
    writer->Write();
    std::cout << "wrote baseline " << baseline << std::endl;
    return EXIT_SUCCESS;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  vtkNew<vtkImageDifference> difference;
  difference->SetInputConnection(grab->GetOutputPort());
  difference->SetImageConnection(reader->GetOutputPort());
  difference->Update();
  const double error = difference->GetThresholdedError();
  std::cout << "image error against " << baseline << ": " << error << std::endl;
  return error <= 10.0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
