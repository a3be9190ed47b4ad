#include "RenderProgress.h"

#include <unistd.h>

#include <cstdio>

namespace vtkrtRender
{
bool Progress::Shown = false;
bool Progress::Terminal = false;
bool Progress::Open = false;
std::string Progress::What;
std::chrono::steady_clock::time_point Progress::Start;

void Progress::Enable(bool force)
{
  Progress::Terminal = isatty(fileno(stderr)) != 0;
  Progress::Shown = force || Progress::Terminal;
}

void Progress::Begin(const std::string& what)
{
  Progress::What = what;
  Progress::Start = std::chrono::steady_clock::now();
  if (Progress::Shown)
  {
    std::fprintf(stderr, "vtkrt-render: %s ...", what.c_str());
    std::fflush(stderr);
    Progress::Open = true;
  }
}

void Progress::Update(int done, int total)
{
  // Rewriting a line needs a terminal; a log gets the final line only.
  if (Progress::Shown && Progress::Terminal)
  {
    const double s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - Progress::Start).count();
    std::fprintf(stderr, "\rvtkrt-render: %s ... %d/%d (%.1f s)\033[K", Progress::What.c_str(),
      done, total, s);
    std::fflush(stderr);
  }
}

void Progress::Interrupt()
{
  if (Progress::Open)
  {
    std::fprintf(stderr, "\n");
    Progress::Open = false;
  }
}

void Progress::End()
{
  if (Progress::Shown)
  {
    Progress::Open = false;
    const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - Progress::Start)
        .count();
    std::fprintf(stderr, "%s %.0f ms%s\n",
      Progress::Terminal ? ("\rvtkrt-render: " + Progress::What + " ... done in").c_str()
                         : " done in",
      ms, Progress::Terminal ? "\033[K" : "");
    std::fflush(stderr);
  }
}
} // namespace vtkrtRender
