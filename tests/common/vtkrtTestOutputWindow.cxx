#include "vtkrtTestOutputWindow.h"

#include "vtkLogger.h"
#include "vtkObjectFactory.h"

#include <iostream>

vtkStandardNewMacro(vtkrtTestOutputWindow);

vtkrtTestOutputWindow* vtkrtTestOutputWindow::Install()
{
  vtkrtTestOutputWindow* window = vtkrtTestOutputWindow::New();
  vtkOutputWindow::SetInstance(window);
  window->Delete(); // vtkOutputWindow holds the reference now
  // VTK 9.1 also sends errors/warnings through vtkLogger straight to stderr;
  // this window is the one place they are shown and counted.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return window;
}

void vtkrtTestOutputWindow::DisplayErrorText(const char* text)
{
  this->Errors.emplace_back(text ? text : "");
  if (this->Echo)
  {
    std::cerr << "[VTK error] " << this->Errors.back() << std::flush;
  }
}

void vtkrtTestOutputWindow::DisplayWarningText(const char* text)
{
  this->Warnings.emplace_back(text ? text : "");
  if (this->Echo)
  {
    std::cerr << "[VTK warning] " << this->Warnings.back() << std::flush;
  }
}

void vtkrtTestOutputWindow::DisplayGenericWarningText(const char* text)
{
  this->DisplayWarningText(text);
}

bool vtkrtTestOutputWindow::HasErrorContaining(const std::string& fragment) const
{
  for (const std::string& e : this->Errors)
  {
    if (e.find(fragment) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

void vtkrtTestOutputWindow::Clear()
{
  this->Errors.clear();
  this->Warnings.clear();
}
