// Chunked parallel loops for the builders: on their own std::threads, or
// through the caller's pool (BuildOptions::parallelFor).
#ifndef vtkrt_core_build_Parallel_h
#define vtkrt_core_build_Parallel_h

#include "vtkrt/core/BVH.h"

#include <algorithm>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

namespace vtkrt::core::detail
{

/// The fewest elements worth a thread of their own.
constexpr std::size_t kMinChunk = 32768;

/// Runs fn(begin, end) over [0, n) split into contiguous chunks, on up to
/// `threads` threads (the calling one included); small ranges stay on the
/// calling thread. fn must be safe to run concurrently on disjoint ranges.
/// `work`: the elements the n chunks cover (n itself when 0), which decides
/// whether threads pay off.
template <class Fn>
void parallelChunks(std::size_t n, unsigned threads, Fn&& fn, std::size_t work = 0)
{
  work = work ? work : n;
  std::size_t t = std::max<std::size_t>(1,
    std::min<std::size_t>({ threads ? threads : std::thread::hardware_concurrency(), work / kMinChunk, n }));
  if (t <= 1)
  {
    fn(std::size_t(0), n);
    return;
  }
  std::vector<std::thread> workers;
  workers.reserve(t - 1);
  std::size_t inlineFrom = t;
  for (std::size_t i = 1; i < t; ++i)
  {
    try
    {
      workers.emplace_back([&fn, i, t, n]() { fn(i * n / t, (i + 1) * n / t); });
    }
    catch (const std::system_error&)
    {
      inlineFrom = i; // no thread from the system: the rest runs here
      break;
    }
  }
  fn(std::size_t(0), n / t);
  for (std::size_t i = inlineFrom; i < t; ++i)
  {
    fn(i * n / t, (i + 1) * n / t);
  }
  for (std::thread& w : workers)
  {
    w.join();
  }
}

/// parallelChunks through the options' parallelFor when they have one.
template <class Fn>
void parallelChunks(std::size_t n, const BuildOptions& options, Fn&& fn, std::size_t work = 0)
{
  if (options.parallelFor && (work ? work : n) >= 2 * kMinChunk && n > 1)
  {
    options.parallelFor(n, [&fn](std::size_t b, std::size_t e) { fn(b, e); });
    return;
  }
  parallelChunks(n, options.parallelFor ? 1u : options.numThreads, fn, work);
}

} // namespace vtkrt::core::detail

#endif
