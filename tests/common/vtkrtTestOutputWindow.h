/**
 * @class   vtkrtTestOutputWindow
 * @brief   vtkOutputWindow for tests: records VTK error and warning text.
 *
 * Passing tests must print no VTK error or warning. Install() makes this the
 * global output window; every error/warning is echoed to stderr (so a
 * failing test shows it) and counted. A test that provokes an error on
 * purpose checks the count and the text, then calls Clear().
 */
#ifndef vtkrtTestOutputWindow_h
#define vtkrtTestOutputWindow_h

#include "vtkOutputWindow.h"

#include <string>
#include <vector>

class vtkrtTestOutputWindow : public vtkOutputWindow
{
public:
  static vtkrtTestOutputWindow* New();
  vtkTypeMacro(vtkrtTestOutputWindow, vtkOutputWindow);

  /**
   * Creates one and makes it vtkOutputWindow's instance; returns it
   * (owned by vtkOutputWindow). Also silences vtkLogger's own copy on stderr.
   */
  static vtkrtTestOutputWindow* Install();

  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override;

  int GetNumberOfErrors() const { return static_cast<int>(this->Errors.size()); }
  int GetNumberOfWarnings() const { return static_cast<int>(this->Warnings.size()); }
  const std::vector<std::string>& GetErrors() const { return this->Errors; }
  const std::vector<std::string>& GetWarnings() const { return this->Warnings; }

  /**
   * True when any recorded error contains `fragment`.
   */
  bool HasErrorContaining(const std::string& fragment) const;

  /**
   * Whether recorded text is also echoed to stderr (default true).
   */
  void SetEcho(bool echo) { this->Echo = echo; }

  void Clear();

protected:
  vtkrtTestOutputWindow() = default;
  ~vtkrtTestOutputWindow() override = default;

private:
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  bool Echo = true;

  vtkrtTestOutputWindow(const vtkrtTestOutputWindow&) = delete;
  void operator=(const vtkrtTestOutputWindow&) = delete;
};

#endif
