// vtkrt-render's progress line on stderr for long work (reading, the first
// frame with its BVH build, accumulation), with times; shown only when
// stderr is a terminal (or with --verbose), so pipes and logs stay clean.
#ifndef vtkrtRenderProgress_h
#define vtkrtRenderProgress_h

#include <chrono>
#include <string>

namespace vtkrtRender
{
class Progress
{
public:
  // Shown when stderr is a terminal, or always when `force`.
  static void Enable(bool force);

  // Starts a step: "vtkrt-render: <what> ..." (no newline yet).
  static void Begin(const std::string& what);

  // Rewrites the current step's line with "<done> of <total>".
  static void Update(int done, int total);

  // Ends the current step with its time and a newline.
  static void End();

  // Ends a step that failed with a newline, so the error starts its own line.
  static void Interrupt();

private:
  static bool Shown;
  static bool Terminal;
  static bool Open; // a step's line is started and not ended
  static std::string What;
  static std::chrono::steady_clock::time_point Start;
};
} // namespace vtkrtRender

#endif
