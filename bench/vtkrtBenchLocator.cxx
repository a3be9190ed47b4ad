// vtkrtBenchLocator: vtkBVHCellLocator against VTK's cell locators and
// Embree 3, in one run, on the same meshes and the same random segments.
//
// For every mesh and peer: build time, single-thread IntersectWithLine
// rate, first-pick latency (new locator + build + one query), heap held by
// the structure, heap left behind after deleting it, and agreement of the
// hits with vtkBVHCellLocator. Ratios are "peer / vtkBVHCellLocator" for
// rates (below 1: slower than ours) and for times (above 1: slower).
//
// Usage: vtkrtBenchLocator [--4m] [--rays N] [--rounds R] [--quick] [--only SUBSTR]...
//                          [--mesh SUBSTR] [--leaf N] [--part rays|queries|all]
//   --only: keep only the peers whose name contains SUBSTR (repeatable; the
//   first kept peer is the reference of the ratios); --mesh: only the meshes
//   whose name contains SUBSTR; --rounds: rate rounds (default 5 for rays, 3
//   for the other queries, below); --part: the ray tables (this file), the
//   tables of every other query (vtkrtBenchLocatorQueries.cxx), or both
//   (the default).
//
// Rates: this VM's speed drifts by tens of percent over seconds (shared
// cores and caches), so one timing per peer would compare peers measured at
// different moments. Every peer is built side by side and the rays are timed
// in R rounds, each round timing every peer in turn: a peer's rate is its
// median over the rounds, and its rate ratio the median (with the range) of
// the per-round ratios, each ratio from timings seconds apart.
#include "vtkBVHCellLocator.h"
#include "vtkrtBenchLocatorQueries.h"
#include "vtkrtBenchTiming.h"
#include "vtkrtDataFile.h"

#include "vtkCellLocator.h"
#include "vtkGenericCell.h"
#include "vtkCellArray.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkModifiedBSPTree.h"
#include "vtkNew.h"
#include "vtkOBBTree.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStaticCellLocator.h"
#include "vtkTriangleFilter.h"

#ifdef VTKRT_HAVE_EMBREE
#include "vtkrtBenchEmbreeGeometry.h"
#endif

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
using vtkrtBench::Clock;
using vtkrtBench::Seconds;
using vtkrtBench::ThreadSeconds;

#ifdef VTKRT_HAVE_EMBREE
/// Bytes Embree holds, from its device memory monitor: its BVH arenas are
/// mapped directly (mallinfo does not see them), its buffers are counted too.
long long g_EmbreeBytes = 0;
#endif

/// Bytes malloc currently hands out (arena + mmapped chunks).
long long HeapInUse()
{
  struct mallinfo2 mi = mallinfo2();
  return static_cast<long long>(mi.uordblks) + static_cast<long long>(mi.hblkhd);
}

struct Segment
{
  double P1[3], P2[3];
};

vtkSmartPointer<vtkPolyData> BumpySphere(int res)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  sphere->LatLongTessellationOff();
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(sphere->GetOutputPort());
  tri->Update();
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->DeepCopy(tri->GetOutput());
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(pd->GetNumberOfPoints());
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    const double s =
      1.0 + 0.15 * std::sin(7.0 * p[0]) * std::cos(5.0 * p[1]) + 0.05 * std::sin(13.0 * p[2]);
    pts->SetPoint(i, p[0] * s, p[1] * s, p[2] * s);
  }
  pd->SetPoints(pts);
  pd->GetPointData()->Initialize();
  return pd;
}

/// A closed torus of quads (n around the ring, n/2 around the tube), bumped
/// as BumpySphere: the quad meshes of structured surfaces and CAD exports.
vtkSmartPointer<vtkPolyData> BumpyQuadTorus(int n)
{
  const int m = std::max(3, n / 2);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(n) * m);
  for (int i = 0; i < n; ++i)
  {
    const double u = 2.0 * vtkMath::Pi() * i / n;
    for (int j = 0; j < m; ++j)
    {
      const double v = 2.0 * vtkMath::Pi() * j / m;
      const double r = 0.35 * (1.0 + 0.15 * std::sin(7.0 * u) * std::cos(5.0 * v));
      const double c = 1.0 + r * std::cos(v);
      pts->SetPoint(static_cast<vtkIdType>(i) * m + j, c * std::cos(u), c * std::sin(u), r * std::sin(v));
    }
  }
  vtkNew<vtkCellArray> quads;
  quads->AllocateExact(static_cast<vtkIdType>(n) * m, 4 * static_cast<vtkIdType>(n) * m);
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      const vtkIdType a = static_cast<vtkIdType>(i) * m + j, b = static_cast<vtkIdType>((i + 1) % n) * m + j;
      const vtkIdType c = static_cast<vtkIdType>((i + 1) % n) * m + (j + 1) % m;
      const vtkIdType d = static_cast<vtkIdType>(i) * m + (j + 1) % m;
      const vtkIdType quad[4] = { a, b, c, d };
      quads->InsertNextCell(4, quad);
    }
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(quads);
  return pd;
}

/// bunny.ply from $VTKRT_DATA_DIR or data/ (vtkrtDataFile.h); nullptr when neither has it.
vtkSmartPointer<vtkPolyData> Bunny()
{
  const std::string path = vtkrtDataFile::Find("bunny.ply");
  if (path.empty())
  {
    std::printf("\n%s: skipped\n", vtkrtDataFile::NotFound("bunny.ply").c_str());
    return nullptr;
  }
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->DeepCopy(reader->GetOutput());
  return pd->GetNumberOfCells() > 0 ? pd : nullptr;
}

/// Segments between random points of the grown bounds (about half hit).
std::vector<Segment> RandomSegments(vtkPolyData* pd, int count)
{
  vtkNew<vtkMinimalStandardRandomSequence> rng;
  rng->SetSeed(1234);
  double b[6];
  pd->GetBounds(b);
  std::vector<Segment> out(static_cast<size_t>(count));
  for (auto& s : out)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double c = 0.5 * (b[2 * k] + b[2 * k + 1]), h = 0.75 * (b[2 * k + 1] - b[2 * k]);
      s.P1[k] = rng->GetRangeValue(c - h, c + h);
      rng->Next();
      s.P2[k] = rng->GetRangeValue(c - h, c + h);
      rng->Next();
    }
  }
  return out;
}

std::vector<std::string> g_Only;
std::string g_Mesh;
int g_Rounds = 5;
int g_QueryRounds = 3;
bool g_Rays = true;    ///< --part: the ray tables
bool g_Queries = true; ///< --part: the other queries' tables
int g_LeafSize = 0; ///< > 0: vtkBVHCellLocator's NumberOfCellsPerNode (else its default)

struct Result
{
  std::string Name;
  double BuildSeconds = 0;
  double RaysPerSecond = 0;
  double FirstPickSeconds = 0;
  long long HeapBytes = 0;
  long long LeakBytes = 0;
  int RaysTimed = 0;
  int Hits = 0;
  int Agree = -1; // hits with the same t (1e-9) as vtkBVHCellLocator, of RaysTimed
  std::vector<double> RoundRates; ///< rays/s of each interleaved round
  double RatioMedian = 0, RatioMin = 0, RatioMax = 0; ///< of the per-round rate / the reference's
};

/// One peer: how to make it, build it and query it.
struct Peer
{
  std::string Name;
  std::function<void*(vtkPolyData*)> Create; // new + SetDataSet (not built)
  std::function<void(void*)> Build;
  std::function<bool(void*, const Segment&, double& t)> Query;
  std::function<void(void*)> Destroy;
  /// Before the rate and memory are measured (after one query): what the
  /// queries of a long session would have built by then.
  std::function<void(void*)> Complete;
  int MaxRays;
};

/// A peer built as the rate rounds see it: after one query (lazy peers,
/// vtkModifiedBSPTree, finish building there) and Complete.
void* BuildForRates(const Peer& peer, vtkPolyData* pd, const Segment& first)
{
  void* loc = peer.Create(pd);
  peer.Build(loc);
  double t;
  peer.Query(loc, first, t);
  if (peer.Complete)
  {
    peer.Complete(loc);
  }
  return loc;
}

Result Measure(const Peer& peer, vtkPolyData* pd, const std::vector<Segment>& segs,
  std::vector<double>* refT)
{
  Result r;
  r.Name = peer.Name;
  // First pick: a fresh locator, its build, one query (best of 3: wall
  // clock, the machine is shared). Round 0 is not counted: a process's first
  // builds pay for fresh heap pages, the SMP pool's start and symbol binding
  // (measured 5-6x slower for the first two builds at 100k), which would
  // bias whichever peer runs first.
  r.FirstPickSeconds = 1e30;
  r.BuildSeconds = 1e30;
  for (int rep = 0; rep < 4; ++rep)
  {
    auto t0 = Clock::now();
    void* loc = peer.Create(pd);
    peer.Build(loc);
    double t;
    peer.Query(loc, segs[0], t);
    if (rep == 0)
    {
      peer.Destroy(loc);
      continue;
    }
    r.FirstPickSeconds = std::min(r.FirstPickSeconds, Seconds(t0, Clock::now()));
    peer.Destroy(loc);
    loc = peer.Create(pd);
    t0 = Clock::now();
    peer.Build(loc);
    r.BuildSeconds = std::min(r.BuildSeconds, Seconds(t0, Clock::now()));
    peer.Destroy(loc);
  }
  r.RaysTimed = std::min(static_cast<int>(segs.size()), peer.MaxRays);
  std::vector<double> ts(static_cast<size_t>(r.RaysTimed), -1.0);
  const long long heap0 = HeapInUse();
#ifdef VTKRT_HAVE_EMBREE
  const long long embree0 = g_EmbreeBytes;
#endif
  void* loc = BuildForRates(peer, pd, segs[0]);
  r.HeapBytes = HeapInUse() - heap0;
#ifdef VTKRT_HAVE_EMBREE
  // While built (after the destroy, the monitor's count is back near zero).
  r.HeapBytes = std::max(r.HeapBytes, g_EmbreeBytes - embree0);
#endif
  // The hits, for the agreement column (the rates come from InterleavedRates).
  for (int i = 0; i < r.RaysTimed; ++i)
  {
    double tt;
    if (peer.Query(loc, segs[i], tt))
    {
      ts[i] = tt;
      ++r.Hits;
    }
  }
  peer.Destroy(loc);
  r.LeakBytes = HeapInUse() - heap0;
  if (refT)
  {
    if (refT->empty())
    {
      *refT = ts;
    }
    else
    {
      r.Agree = 0;
      for (int i = 0; i < r.RaysTimed; ++i)
      {
        const double a = ts[i], b = (*refT)[i];
        r.Agree += ((a < 0) == (b < 0) && (a < 0 || std::abs(a - b) < 1e-6)) ? 1 : 0;
      }
    }
  }
  return r;
}

template <class Locator>
Peer VtkPeer(const std::string& name, int maxRays, std::function<void(Locator*)> setup = nullptr)
{
  Peer p;
  p.Name = name;
  p.MaxRays = maxRays;
  p.Create = [setup](vtkPolyData* pd) -> void* {
    Locator* l = Locator::New();
    if (setup)
    {
      setup(l);
    }
    l->SetDataSet(pd);
    return l;
  };
  p.Build = [](void* l) { static_cast<Locator*>(l)->BuildLocator(); };
  p.Query = [](void* l, const Segment& s, double& t) {
    double x[3], pc[3];
    int sub;
    vtkIdType cellId;
    return static_cast<Locator*>(l)->IntersectWithLine(s.P1, s.P2, 0.0, t, x, pc, sub, cellId) != 0;
  };
  p.Destroy = [](void* l) { static_cast<Locator*>(l)->Delete(); };
  return p;
}

/// vtkOBBTree answers IntersectWithLine with the 9-argument form too.
Peer OBBPeer(int maxRays)
{
  return VtkPeer<vtkOBBTree>("vtkOBBTree", maxRays);
}

Peer BVHPeer(const std::string& name, int quality, int maxRays, bool onDemand = true)
{
  Peer p;
  p.Name = name;
  p.MaxRays = maxRays;
  p.Create = [quality, onDemand](vtkPolyData* pd) -> void* {
    vtkBVHCellLocator* l = vtkBVHCellLocator::New();
    l->SetBuildQuality(quality);
    l->SetPickingTreeOnDemand(onDemand);
    if (g_LeafSize > 0)
    {
      l->SetNumberOfCellsPerNode(g_LeafSize);
    }
    l->SetDataSet(pd);
    return l;
  };
  p.Build = [](void* l) { static_cast<vtkBVHCellLocator*>(l)->BuildLocator(); };
  // The vtkCellPicker call: the 9-argument form with the caller's cell.
  auto cell = std::make_shared<vtkSmartPointer<vtkGenericCell>>(vtkSmartPointer<vtkGenericCell>::New());
  p.Query = [cell](void* l, const Segment& s, double& t) {
    double x[3], pc[3];
    int sub;
    vtkIdType cellId;
    return static_cast<vtkBVHCellLocator*>(l)->IntersectWithLine(
             s.P1, s.P2, 0.0, t, x, pc, sub, cellId, *cell) != 0;
  };
  p.Destroy = [](void* l) { static_cast<vtkBVHCellLocator*>(l)->Delete(); };
  // Rates of the whole tree (the parts a long session's queries reach).
  p.Complete = [](void* l) {
    auto* loc = static_cast<vtkBVHCellLocator*>(l);
    loc->PickingTreeOnDemandOff();
    loc->BuildLocator();
  };
  return p;
}

#ifdef VTKRT_HAVE_EMBREE
struct EmbreeState
{
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
  vtkPolyData* Data = nullptr;
  double Origin[3] = { 0, 0, 0 };
};

bool EmbreeMemory(void*, ssize_t bytes, bool)
{
  g_EmbreeBytes += bytes;
  return true;
}

/// Embree 3, one thread, float geometry relative to the mesh center (its
/// best case for precision), rtcIntersect1 per segment.
Peer EmbreePeer(int maxRays)
{
  Peer p;
  p.Name = "Embree 3 (1 thread)";
  p.MaxRays = maxRays;
  p.Create = [](vtkPolyData* pd) -> void* {
    auto* e = new EmbreeState;
    e->Device = rtcNewDevice("threads=1");
    rtcSetDeviceMemoryMonitorFunction(e->Device, EmbreeMemory, nullptr);
    e->Data = pd;
    return e;
  };
  p.Build = [](void* v) {
    auto* e = static_cast<EmbreeState*>(v);
    vtkPolyData* pd = e->Data;
    double b[6];
    pd->GetBounds(b);
    for (int k = 0; k < 3; ++k)
    {
      e->Origin[k] = 0.5 * (b[2 * k] + b[2 * k + 1]);
    }
    e->Scene = rtcNewScene(e->Device);
    vtkrtBench::AttachEmbreeTriangles(e->Device, e->Scene, pd, e->Origin);
    rtcCommitScene(e->Scene);
  };
  p.Query = [](void* v, const Segment& s, double& t) {
    auto* e = static_cast<EmbreeState*>(v);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = static_cast<float>(s.P1[0] - e->Origin[0]);
    rh.ray.org_y = static_cast<float>(s.P1[1] - e->Origin[1]);
    rh.ray.org_z = static_cast<float>(s.P1[2] - e->Origin[2]);
    rh.ray.dir_x = static_cast<float>(s.P2[0] - s.P1[0]);
    rh.ray.dir_y = static_cast<float>(s.P2[1] - s.P1[1]);
    rh.ray.dir_z = static_cast<float>(s.P2[2] - s.P1[2]);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = 1.0f;
    rh.ray.mask = 0xffffffffu;
    rh.ray.flags = 0;
    rh.ray.time = 0.0f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(e->Scene, &ctx, &rh);
    t = rh.ray.tfar;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  };
  p.Destroy = [](void* v) {
    auto* e = static_cast<EmbreeState*>(v);
    if (e->Scene)
    {
      rtcReleaseScene(e->Scene);
    }
    rtcReleaseDevice(e->Device);
    delete e;
  };
  return p;
}
#endif

std::string Human(long long bytes)
{
  char buf[64];
  const double a = std::abs(static_cast<double>(bytes));
  if (a >= 1 << 20)
  {
    std::snprintf(buf, sizeof buf, "%.1f MiB", bytes / 1048576.0);
  }
  else if (a >= 1 << 10)
  {
    std::snprintf(buf, sizeof buf, "%.1f KiB", bytes / 1024.0);
  }
  else
  {
    std::snprintf(buf, sizeof buf, "%lld B", bytes);
  }
  return buf;
}


bool Wanted(const std::string& name)
{
  if (g_Only.empty())
  {
    return true;
  }
  for (const auto& o : g_Only)
  {
    if (name.find(o) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// The interleaved rate rounds (see the top of this file): every peer built
/// and completed first, then each round times each peer's rays in turn.
void InterleavedRates(const std::vector<Peer>& peers, vtkPolyData* pd, const std::vector<Segment>& segs,
  std::vector<Result>& results)
{
  std::vector<void*> locs;
  for (const auto& peer : peers)
  {
    locs.push_back(BuildForRates(peer, pd, segs[0]));
  }
  for (int round = 0; round < g_Rounds; ++round)
  {
    for (size_t p = 0; p < peers.size(); ++p)
    {
      const int n = std::min(static_cast<int>(segs.size()), peers[p].MaxRays);
      const double c0 = ThreadSeconds();
      for (int i = 0; i < n; ++i)
      {
        double t;
        peers[p].Query(locs[p], segs[i], t);
      }
      results[p].RoundRates.push_back(n / (ThreadSeconds() - c0));
    }
  }
  for (size_t p = 0; p < peers.size(); ++p)
  {
    peers[p].Destroy(locs[p]);
    Result& r = results[p];
    r.RaysPerSecond = Median(r.RoundRates);
    std::vector<double> ratios;
    for (int round = 0; round < g_Rounds; ++round)
    {
      ratios.push_back(r.RoundRates[round] / results[0].RoundRates[round]);
    }
    r.RatioMedian = Median(ratios);
    r.RatioMin = *std::min_element(ratios.begin(), ratios.end());
    r.RatioMax = *std::max_element(ratios.begin(), ratios.end());
  }
}

void RunMesh(const std::string& name, vtkPolyData* pd, int rays, bool quick)
{
  if (g_Queries)
  {
    vtkrtBench::RunLocatorQueries(name, pd, g_QueryRounds, quick);
  }
  if (!g_Rays)
  {
    return;
  }
  const vtkIdType tris = pd->GetNumberOfCells();
  std::printf("\n## %s: %lld triangles, %d random segments\n\n", name.c_str(),
    static_cast<long long>(tris), rays);
  const std::vector<Segment> segs = RandomSegments(pd, rays);
  // Slow peers get fewer rays (their rate is still per second).
  const int vtkRays = std::max(200, std::min(rays, quick ? 500 : 3000));
  std::vector<Peer> peers;
  peers.push_back(BVHPeer("vtkBVHCellLocator (fast build, default)", vtkBVHCellLocator::FAST, rays));
  peers.push_back(BVHPeer("vtkBVHCellLocator (fast, whole tree up front)", vtkBVHCellLocator::FAST, rays, false));
  peers.push_back(BVHPeer("vtkBVHCellLocator (SAH)", vtkBVHCellLocator::SAH, rays));
  peers.push_back(BVHPeer("vtkBVHCellLocator (high)", vtkBVHCellLocator::HIGH, rays));
  peers.push_back(VtkPeer<vtkStaticCellLocator>("vtkStaticCellLocator", vtkRays));
  peers.push_back(VtkPeer<vtkCellLocator>("vtkCellLocator", vtkRays));
  peers.push_back(VtkPeer<vtkModifiedBSPTree>("vtkModifiedBSPTree", vtkRays));
  peers.push_back(OBBPeer(quick ? 50 : 200));
#ifdef VTKRT_HAVE_EMBREE
  peers.push_back(EmbreePeer(rays));
#endif
  peers.erase(std::remove_if(peers.begin(), peers.end(), [](const Peer& p) { return !Wanted(p.Name); }),
    peers.end());
  if (peers.empty())
  {
    return;
  }
  std::vector<double> refT;
  std::vector<Result> results;
  for (const auto& p : peers)
  {
    Result r = Measure(p, pd, segs, &refT);
    results.push_back(r);
    std::fflush(stdout);
  }
  InterleavedRates(peers, pd, segs, results);
  const Result& ours = results[0];
  std::printf("| locator | build s | rays/s (1 thread, median of %d rounds) | rate ratio (median, "
              "range) | first pick ms | first-pick ratio | memory | left after delete | same hits |\n",
    g_Rounds);
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& r : results)
  {
    char agree[32] = "ref";
    if (r.Agree >= 0)
    {
      std::snprintf(agree, sizeof agree, "%d/%d", r.Agree, r.RaysTimed);
    }
    char ratio[64];
    std::snprintf(ratio, sizeof ratio, "%.3g (%.3g-%.3g)", r.RatioMedian, r.RatioMin, r.RatioMax);
    std::printf("| %s | %.3f | %.0f | %s | %.1f | %.3g | %s | %s | %s |\n", r.Name.c_str(),
      r.BuildSeconds, r.RaysPerSecond, ratio,
      1e3 * r.FirstPickSeconds, r.FirstPickSeconds / ours.FirstPickSeconds,
      Human(r.HeapBytes).c_str(), Human(r.LeakBytes).c_str(), agree);
  }
  std::fflush(stdout);
}
} // namespace

int main(int argc, char* argv[])
{
  // glibc's default malloc returns big blocks to the kernel and page-faults
  // them back on the next build, which dominates build times on this VM
  // (NOTES-vtk91.md): same setting for every peer.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  bool big = false, quick = false;
  int rays = 100000;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--4m"))
    {
      big = true;
    }
    else if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
      rays = 5000;
    }
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc)
    {
      g_Only.emplace_back(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc)
    {
      g_Mesh = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--leaf") && i + 1 < argc)
    {
      g_LeafSize = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc)
    {
      g_Rounds = std::max(1, std::atoi(argv[++i]));
      g_QueryRounds = g_Rounds;
    }
    else if (!std::strcmp(argv[i], "--part") && i + 1 < argc)
    {
      const std::string part = argv[++i];
      g_Rays = part != "queries";
      g_Queries = part != "rays";
    }
    else if (!std::strcmp(argv[i], "--rays") && i + 1 < argc)
    {
      rays = std::max(10, std::atoi(argv[++i]));
    }
  }
  std::printf("# vtkrtBenchLocator\n\nVTK SMP backend %s (builds may use it).\n", vtkSMPTools::GetBackend());
  if (g_Rays)
  {
    std::printf("Ray tables: IntersectWithLine(p1, p2, tol=0, ...) over random segments, "
              "single thread (rates from thread CPU time, %d interleaved rounds; build and first pick: best of 3, wall "
              "clock; malloc tuned as NOTES-vtk91.md says, for every peer).\nRatios: peer / "
              "vtkBVHCellLocator (default, fast build). Same hits: t within 1e-6.\n"
              "Embree built with 1 thread.\n"
              "vtkBVHCellLocator's fast build makes each part of its picking tree when a query first "
              "reaches it (PickingTreeOnDemand, default): its build and first pick are that; its rate "
              "and memory are the whole tree's, as in the row that builds it up front.\n",
      g_Rounds);
  }
  auto wantMesh = [](const char* name) { return g_Mesh.empty() || std::strstr(name, g_Mesh.c_str()); };
  if (wantMesh("bunny"))
  {
    if (auto bunny = Bunny())
    {
      RunMesh("bunny", bunny, rays, quick);
    }
  }
  // --quick shrinks the small generated mesh: its name says which it is.
  const char* smallMesh = quick ? "generated 20k" : "generated 100k";
  if (wantMesh(smallMesh))
  {
    RunMesh(smallMesh, BumpySphere(quick ? 100 : 224), rays, quick);
  }
  // Quads: cells of two triangles each, whose bounds and hits the locator
  // makes from its triangles.
  const char* quadMesh = quick ? "generated 20k quads" : "generated 500k quads";
  if (wantMesh(quadMesh))
  {
    RunMesh(quadMesh, BumpyQuadTorus(quick ? 200 : 1000), rays, quick);
  }
  if (!quick && wantMesh("generated 1M"))
  {
    RunMesh("generated 1M", BumpySphere(708), rays, quick);
  }
  if (big && wantMesh("generated 4M"))
  {
    RunMesh("generated 4M", BumpySphere(1415), rays, quick);
  }
  return 0;
}
