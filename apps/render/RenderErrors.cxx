#include "RenderErrors.h"

#include "vtkLogger.h"
#include "vtkObjectFactory.h"

namespace vtkrtRender
{
vtkStandardNewMacro(CapturingOutputWindow);

void CapturingOutputWindow::StartCapture()
{
  this->Captured.clear();
  this->Capturing = true;
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

void CapturingOutputWindow::StopCapture()
{
  if (this->Capturing)
  {
    this->Capturing = false;
    // VTK 9.1 cannot query the level; INFO is loguru's default.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_INFO);
  }
}

void CapturingOutputWindow::Handle(const char* text)
{
  if (this->Capturing)
  {
    this->Captured.emplace_back(text ? text : "");
  }
  else
  {
    this->Superclass::DisplayErrorText(text);
  }
}

std::string MessageOf(const std::string& vtkText)
{
  std::string text = vtkText;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  const size_t nl = text.rfind('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  const size_t paren = line.find("): ");
  return paren == std::string::npos ? line : line.substr(paren + 3);
}
} // namespace vtkrtRender
