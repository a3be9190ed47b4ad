// An ordinary VTK application, ray traced by adding two lines:
//   vtkNew<vtkRayTracePass> pass;  renderer->SetPass(pass);
// Given an output file it renders, writes the PNG and exits: in a desktop
// window when there is a display, headless through EGL without one or with
// --offscreen. Without an output file and with a display it opens the
// window to look around in (close it to quit).
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRayTracePass.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkGlyph3DMapper.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointSource.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkSuperquadricSource.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>
#include <cstring>
#include <iostream>

int main(int argc, char* argv[])
{
  bool offscreen = std::getenv("DISPLAY") == nullptr;
  const char* output = nullptr;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--offscreen") == 0)
      offscreen = true;
    else
      output = argv[i];
  }
  const bool interactive = !offscreen && output == nullptr;
  if (output == nullptr)
    output = "SwapInRayTracing.png";

  // The scene, exactly as any VTK app builds it: a mesh and sphere glyphs.
  vtkNew<vtkSuperquadricSource> shape;
  shape->SetThetaResolution(64);
  shape->SetPhiResolution(64);
  shape->ToroidalOn();
  vtkNew<vtkPolyDataMapper> shapeMapper;
  shapeMapper->SetInputConnection(shape->GetOutputPort());
  vtkNew<vtkActor> shapeActor;
  shapeActor->SetMapper(shapeMapper);
  shapeActor->GetProperty()->SetColor(0.9, 0.6, 0.3);
  shapeActor->GetProperty()->SetSpecular(0.4);
  shapeActor->GetProperty()->SetSpecularPower(30);

  vtkNew<vtkPointSource> centers;
  centers->SetNumberOfPoints(200);
  centers->SetRadius(0.9);
  vtkNew<vtkSphereSource> glyph;
  vtkNew<vtkGlyph3DMapper> glyphMapper;
  glyphMapper->SetInputConnection(centers->GetOutputPort());
  glyphMapper->SetSourceConnection(glyph->GetOutputPort());
  glyphMapper->SetScaleFactor(0.08);
  glyphMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphMapper);
  glyphActor->GetProperty()->SetColor(0.3, 0.6, 0.9);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(shapeActor);
  renderer->AddActor(glyphActor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  renderer->GetActiveCamera()->Elevation(35);
  renderer->ResetCamera();

  // The two lines that make it ray traced.
  vtkNew<vtkRayTracePass> pass;
  renderer->SetPass(pass);

  vtkSmartPointer<vtkRenderWindow> window;
  if (offscreen)
    window = vtkSmartPointer<vtkEGLHeadlessRenderWindow>::New();
  else
    window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(480, 360);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->Render();

  if (interactive)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Start();
    return EXIT_SUCCESS;
  }
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(output);
  writer->Write();
  std::cout << "wrote " << output << " (" << pass->GetNumberOfTracedProps() << " props ray traced)"
            << std::endl;
  return pass->GetNumberOfTracedProps() == 2 ? EXIT_SUCCESS : EXIT_FAILURE;
}
