// vtkrtBenchTiming: the clocks the benchmarks read (wall, thread CPU,
// process CPU). Standard C++ and POSIX only: the core benchmark uses it too.
#ifndef vtkrtBenchTiming_h
#define vtkrtBenchTiming_h

#include <chrono>
#include <ctime>

namespace vtkrtBench
{
using Clock = std::chrono::steady_clock;

/// Wall-clock seconds from `a` to `b`.
inline double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// CPU time of the calling thread: single-threaded query loops timed this
/// way are far less disturbed by other processes than by the wall clock.
inline double ThreadSeconds()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// CPU time of the whole process, every thread counted (llvmpipe's too):
/// on a shared machine, less sensitive to other processes than wall time.
inline double ProcessSeconds()
{
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}

#endif
