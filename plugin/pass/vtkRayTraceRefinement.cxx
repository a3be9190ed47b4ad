#include "vtkRayTraceRefinement.h"

#include "vtkRayTraceGeometry.h"
#include "vtkSurfaceTriangulation.h"

#include "vtkrt/core/SurfaceTriangulation.h"
#include "vtkrt/core/build/Parallel.h"

#include <algorithm>
#include <atomic>
#include <limits>
#if defined(__linux__)
#include <sys/resource.h> // setpriority
#include <sys/syscall.h>  // SYS_gettid
#include <unistd.h>       // syscall
#endif
#include <system_error>
#include <utility>

namespace vtkrt
{
namespace pass
{

BVHRefinement::BVHRefinement(
  std::shared_ptr<const Geometry> fast, RefinementInput input, const core::BuildOptions& options)
  : Fast(std::move(fast))
  , Input(std::move(input))
  , Options(options)
{
}

BVHRefinement::~BVHRefinement()
{
  if (this->Worker.joinable())
  {
    this->Worker.join();
  }
}

void BVHRefinement::Launch()
{
  if (this->Started)
  {
    return;
  }
  this->Started = true;
  try
  {
    this->Worker = std::thread([this]() { this->Run(); });
  }
  catch (const std::system_error&)
  {
    this->Finished.store(true, std::memory_order_release); // no thread: no refinement
  }
}

void BVHRefinement::Wait()
{
  this->Launch();
  if (this->Worker.joinable())
  {
    this->Worker.join();
  }
}

std::shared_ptr<Geometry> BVHRefinement::Take()
{
  if (!this->Done())
  {
    return nullptr;
  }
  this->Wait(); // the thread has ended: a join without a wait
  return std::move(this->Result);
}

namespace
{
/// Gives the calling thread (and the threads it starts) the lowest CPU
/// priority: the frames drawn meanwhile keep the cores, the build takes
/// what they leave.
void lowerThreadPriority()
{
#if defined(__linux__)
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
#endif
}

/// `refined`'s triangle records: the fast ones in its leaf order
/// (`leafOrder`, the triangle at each leaf position; `fastOrder`, the fast
/// tree's). False when it holds a triangle the fast tree left out.
bool reorderRecords(const Geometry& fast, const std::vector<std::uint32_t>& fastOrder,
  const std::vector<std::uint32_t>& leafOrder, std::size_t triangleCount, const core::BuildOptions& options,
  Geometry& refined)
{
  const std::size_t n = leafOrder.size();
  std::vector<std::uint32_t> fastPosition(triangleCount, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t k = 0; k < n; ++k)
  {
    fastPosition[fastOrder[k]] = static_cast<std::uint32_t>(k);
  }
  refined.PrimitiveCount = n;
  refined.Triangles.resize(n);
  refined.TriangleVertices.resize(n);
  std::atomic<bool> sameTriangles{ true };
  core::detail::parallelChunks(n, options, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k)
    {
      const std::uint32_t from = fastPosition[leafOrder[k]];
      if (from >= n)
      {
        sameTriangles = false;
        return;
      }
      refined.Triangles[k] = fast.Triangles[from];
      refined.TriangleVertices[k] = fast.TriangleVertices[from];
    }
  });
  return sameTriangles;
}
} // namespace

void BVHRefinement::Run()
{
  lowerThreadPriority();
  if (!this->Input.Triangulation)
  {
    this->Finished.store(true, std::memory_order_release); // nothing to build from
    return;
  }
  try
  {
    const core::SurfaceTriangles& triangles = this->Input.Triangulation->GetTriangles();
    core::GpuBVH bvh = BuildTriangleBVH(triangles, this->Input.Points, this->Options);
    auto g = std::make_shared<Geometry>();
    g->Spheres = false;
    g->VertexCount = this->Fast->VertexCount;
    adoptBVH(*g, bvh, this->Input.Frame);
    // The same triangles in the same frame (the origin is the center of
    // their bounds): the fast records, reordered, are the new ones.
    const std::size_t n = bvh.primIndex.size();
    if (g->Origin == this->Fast->Origin && n == this->Fast->Triangles.size() && this->Input.Order.size() == n &&
      reorderRecords(*this->Fast, this->Input.Order, bvh.primIndex, triangles.count, this->Options, *g))
    {
      g->MaximumId = this->Fast->MaximumId;
      g->Normals = this->Fast->Normals;
      g->CellNormals = this->Fast->CellNormals;
      this->Result = std::move(g);
    }
  }
  catch (const std::exception&)
  {
    this->Result.reset(); // out of memory: the fast tree stays
  }
  this->Finished.store(true, std::memory_order_release);
}

void BackgroundBuilds::Start(
  const void* key, std::shared_ptr<const Geometry> fast, RefinementInput input, const core::BuildOptions& options)
{
  auto queued = this->Queue.find(key);
  if (queued != this->Queue.end())
  {
    this->Release(std::move(queued->second.Build));
    this->Queue.erase(queued);
  }
  Queued& entry = this->Queue[key];
  entry.Build = std::make_unique<BVHRefinement>(std::move(fast), std::move(input), options);
  entry.Arrival = this->Arrivals++;
  this->LaunchNext();
}

void BackgroundBuilds::Release(std::unique_ptr<BVHRefinement> build)
{
  if (build->Launched() && !build->Done())
  {
    this->LetGo.push_back(std::move(build));
  }
}

bool BackgroundBuilds::IsLaunched(const void* key) const
{
  const auto queued = this->Queue.find(key);
  return queued != this->Queue.end() && queued->second.Build->Launched();
}

void BackgroundBuilds::LaunchNext()
{
  const auto running = [](const BVHRefinement& b) { return b.Launched() && !b.Done(); };
  if (std::any_of(this->LetGo.begin(), this->LetGo.end(),
        [&](const std::unique_ptr<BVHRefinement>& b) { return running(*b); }))
  {
    return;
  }
  const Queued* oldest = nullptr;
  for (const auto& queued : this->Queue)
  {
    if (running(*queued.second.Build))
    {
      return;
    }
    if (!queued.second.Build->Launched() && (!oldest || queued.second.Arrival < oldest->Arrival))
    {
      oldest = &queued.second;
    }
  }
  if (oldest)
  {
    oldest->Build->Launch();
  }
}

std::shared_ptr<Geometry> BackgroundBuilds::TakeDone(const void* key, const Geometry& current)
{
  auto queued = this->Queue.find(key);
  if (queued == this->Queue.end() || !queued->second.Build->Done() ||
    queued->second.Build->Refines() != &current)
  {
    return nullptr;
  }
  std::shared_ptr<Geometry> refined = queued->second.Build->Take();
  this->Queue.erase(queued);
  this->LaunchNext();
  return refined;
}

void BackgroundBuilds::LetGoAll()
{
  for (auto& queued : this->Queue)
  {
    this->Release(std::move(queued.second.Build));
  }
  this->Queue.clear();
  this->FreeFinished();
}

void BackgroundBuilds::WaitAll()
{
  for (const std::unique_ptr<BVHRefinement>& build : this->LetGo)
  {
    build->Wait();
  }
  this->LetGo.clear();
  std::vector<const Queued*> order;
  for (const auto& queued : this->Queue)
  {
    order.push_back(&queued.second);
  }
  std::sort(order.begin(), order.end(), [](const Queued* a, const Queued* b) { return a->Arrival < b->Arrival; });
  for (const Queued* queued : order)
  {
    queued->Build->Wait();
  }
}

void BackgroundBuilds::FreeFinished()
{
  this->LetGo.erase(std::remove_if(this->LetGo.begin(), this->LetGo.end(),
                      [](const std::unique_ptr<BVHRefinement>& r) { return r->Done(); }),
    this->LetGo.end());
}

core::BuildOptions BackgroundBuildOptions(const core::BuildOptions& options)
{
  core::BuildOptions out = options;
  out.parallelFor = nullptr;
  const unsigned cores = std::thread::hardware_concurrency();
  out.numThreads = cores > 1 ? cores - 1 : 1;
  return out;
}

} // namespace pass
} // namespace vtkrt
