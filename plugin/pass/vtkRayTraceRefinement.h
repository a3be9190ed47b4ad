// Private to vtkRayTracePass: a large mesh's first frame is traced on a
// fast tree (LBVH) while the tree of the pass's BuildQuality is built on a
// thread of its own; a later frame takes the better tree in its place. The
// records are the same triangles in the new leaf order, so the images and
// picks are those of the better tree built at once. No GL here.
#ifndef vtkRayTraceRefinement_h
#define vtkRayTraceRefinement_h

#include "vtkRayTraceTypes.h"

#include "vtkrt/core/BVH.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/LocalFrame.h"

#include "vtkSmartPointer.h"

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <thread>
#include <vector>

class vtkSurfaceTriangulation;

namespace vtkrt
{
namespace pass
{

/// What BuildTriangles hands a refinement of the geometry it built: the
/// triangles, their points in the build's local frame, and the leaf order
/// of its (fast) tree.
struct RefinementInput
{
  vtkSmartPointer<vtkSurfaceTriangulation> Triangulation; ///< never changed once made
  core::ScaledFrame Frame;
  core::NoFillArray<core::Vec3<double>> Points;
  std::vector<std::uint32_t> Order; ///< triangle at each leaf position of the fast tree
};

/// One geometry's better tree, built on a thread of its own once
/// launched. Everything it reads is its own or never changes while it runs
/// (the fast geometry's arrays); it is made, asked and destroyed on the
/// render thread only.
class BVHRefinement
{
public:
  /// Will build `fast`'s triangles again with `options` (its own threads:
  /// options.parallelFor must be empty).
  BVHRefinement(std::shared_ptr<const Geometry> fast, RefinementInput input, const core::BuildOptions& options);
  /// Waits for the build: a refinement never outlives what it reads.
  ~BVHRefinement();
  BVHRefinement(const BVHRefinement&) = delete;
  BVHRefinement& operator=(const BVHRefinement&) = delete;

  /// Starts the build on its thread (once).
  void Launch();
  bool Launched() const { return this->Started; }
  bool Done() const { return this->Finished.load(std::memory_order_acquire); }
  /// Launches it if need be and waits for it.
  void Wait();
  /// Once Done(): the refined geometry (arrays and frame; the cache's key
  /// fields are the caller's to copy), or null when the build could not
  /// stand in for the fast one. Takes it.
  std::shared_ptr<Geometry> Take();
  /// The fast geometry it refines.
  const Geometry* Refines() const { return this->Fast.get(); }

private:
  void Run();

  std::shared_ptr<const Geometry> Fast;
  RefinementInput Input;
  core::BuildOptions Options;
  std::shared_ptr<Geometry> Result;
  bool Started = false;
  std::atomic<bool> Finished{ false };
  std::thread Worker;
};

/// Options for a background build of `options`' quality: the same builder
/// on threads of its own, leaving a core to the renderer where there are
/// several.
core::BuildOptions BackgroundBuildOptions(const core::BuildOptions& options);

/// The background builds of one scene's geometry, by cache key. One runs
/// at a time, the others wait their turn in the order they came (a mesh
/// changing every frame, or many large meshes, hold one build's threads and
/// memory, and the ones waiting); a build let go before its turn never
/// runs, one let go while it runs finishes on its own (it cannot be
/// stopped) and is freed after.
class BackgroundBuilds
{
public:
  /// Queues the refinement of `fast`, the cache entry of `key` (the
  /// previous one for the key is let go).
  void Start(
    const void* key, std::shared_ptr<const Geometry> fast, RefinementInput input, const core::BuildOptions& options);
  /// The refined geometry of `key` when its build is done and refines
  /// `current`; else null. The caller gives it `current`'s place.
  std::shared_ptr<Geometry> TakeDone(const void* key, const Geometry& current);
  /// Lets go of the builds whose geometry is no longer `current(key)` and
  /// frees those let go that have finished (never waits).
  template <class CurrentFn>
  void Tidy(CurrentFn&& current)
  {
    for (auto it = this->Queue.begin(); it != this->Queue.end();)
    {
      if (current(it->first) == it->second.Build->Refines())
      {
        ++it;
        continue;
      }
      this->Release(std::move(it->second.Build));
      it = this->Queue.erase(it);
    }
    this->FreeFinished();
    this->LaunchNext();
  }
  /// Lets go of every build.
  void LetGoAll();
  /// Waits for every build, those let go first, then the others one at a
  /// time in their order of coming.
  void WaitAll();
  /// The builds not taken yet (waiting, running or done).
  int Size() const { return static_cast<int>(this->Queue.size()); }
  /// Whether the build of `key` has been launched (for tests).
  bool IsLaunched(const void* key) const;

private:
  /// A build let go: dropped when it never ran, else kept until it ends.
  void Release(std::unique_ptr<BVHRefinement> build);
  void FreeFinished();
  /// Launches the oldest waiting build when none is running.
  void LaunchNext();

  struct Queued
  {
    std::unique_ptr<BVHRefinement> Build;
    std::uint64_t Arrival = 0; ///< its place in the order of coming
  };
  std::map<const void*, Queued> Queue; ///< by key: waiting, running or done
  std::uint64_t Arrivals = 0;
  std::vector<std::unique_ptr<BVHRefinement>> LetGo; ///< launched and let go, until they end
};

} // namespace pass
} // namespace vtkrt

#endif
