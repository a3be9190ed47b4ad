// How vtkrt-render fails: its exit codes, the Failure it throws for a
// runtime error, and an output window that turns VTK's error text into one
// message of ours.
#ifndef vtkrtRenderErrors_h
#define vtkrtRenderErrors_h

#include "vtkOutputWindow.h"

#include <string>
#include <vector>

namespace vtkrtRender
{
// Exit codes.
constexpr int ExitOk = 0;
constexpr int ExitRuntimeError = 1; // unreadable input, no GL context, cannot write
constexpr int ExitUsage = 2;        // wrong arguments
constexpr int ExitUnavailable = 3;  // a mode this build does not have

// Thrown for a runtime error: one message and the exit status.
struct Failure
{
  std::string Message;
  int Code;
};

// Records VTK's error/warning text while a file is read, so that a bad file
// gives one message of ours instead of a reader's stack of errors.
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);
  std::vector<std::string> Captured;

  // While capturing, VTK's text is kept here and vtkLogger's own copy on
  // stderr is muted; our one message replaces both.
  void StartCapture();
  void StopCapture();
  void DisplayErrorText(const char* text) override { this->Handle(text); }
  void DisplayWarningText(const char* text) override { this->Handle(text); }
  void DisplayGenericWarningText(const char* text) override { this->Handle(text); }

private:
  bool Capturing = false;

  void Handle(const char* text);
};

// The last line of VTK's "ERROR: In file, line N\nclass (ptr): message" text.
std::string MessageOf(const std::string& vtkText);
} // namespace vtkrtRender

#endif
