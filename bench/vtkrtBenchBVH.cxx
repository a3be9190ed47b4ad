// vtkrtBenchBVH: the core BVH on generated terrains (~100k, 1M, 4M
// triangles) and the Stanford bunny (bunny.ply from $VTKRT_DATA_DIR or the
// project's data/, see vtkrtDataFile.h): build time per builder, SAH cost,
// memory, closest-hit rays/s on one thread and on all threads, against brute
// force (small case) and Embree 3 (when found at build time) in the same run.
// Usage: vtkrtBenchBVH [--quick] [--rays N]
#include "vtkrt/core/Core.h"
#include "vtkrtBenchTiming.h"
#include "vtkrtDataFile.h"

#ifdef VTKRT_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

using namespace vtkrt::core;

namespace
{

using vtkrtBench::Clock;
using vtkrtBench::Seconds;
using vtkrtBench::ThreadSeconds;

struct Mesh
{
  std::string name;
  std::vector<Vec3<double>> vertices;
  std::vector<std::uint32_t> indices;
  TriangleMesh<double> view() const { return TriangleMesh<double>(vertices, indices); }
  std::size_t triangles() const { return indices.size() / 3; }
};

/// n x n height field with a few octaves of noise: 2 (n-1)^2 triangles.
Mesh makeTerrain(int n, std::uint64_t seed)
{
  Mesh m;
  m.name = "terrain " + std::to_string(2ull * (n - 1) * (n - 1) / 1000) + "k";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  double phase[8];
  for (double& p : phase)
  {
    p = 6.283 * u(rng);
  }
  m.vertices.reserve(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      double h = 0.0;
      for (int o = 0; o < 4; ++o)
      {
        const double f = 3.0 * (1 << o);
        h += std::sin(f * x + phase[2 * o]) * std::cos(f * y + phase[2 * o + 1]) / (1 << o);
      }
      h = 0.1 * h + 0.002 * u(rng);
      m.vertices.emplace_back(x, y, h);
    }
  }
  m.indices.reserve(6ull * (n - 1) * (n - 1));
  for (int j = 0; j + 1 < n; ++j)
  {
    for (int i = 0; i + 1 < n; ++i)
    {
      const std::uint32_t a = std::uint32_t(j * n + i);
      m.indices.insert(m.indices.end(), { a, a + 1, a + n + 1, a, a + n + 1, a + std::uint32_t(n) });
    }
  }
  return m;
}

/// Minimal ASCII PLY reader (vertex x y z first, faces as lists). Returns
/// false when the file is absent or not ASCII PLY.
bool readAsciiPly(const std::string& path, Mesh& m)
{
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line) || line.rfind("ply", 0) != 0)
  {
    return false;
  }
  std::size_t nv = 0, nf = 0, vertexProps = 0;
  bool ascii = false, inVertex = false;
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0)
  {
    std::istringstream s(line);
    std::string w;
    s >> w;
    if (w == "format")
    {
      s >> w;
      ascii = w == "ascii";
    }
    else if (w == "element")
    {
      s >> w;
      inVertex = w == "vertex";
      (inVertex ? nv : nf) = 0;
      if (w == "vertex")
      {
        s >> nv;
      }
      else if (w == "face")
      {
        s >> nf;
      }
    }
    else if (w == "property" && inVertex)
    {
      ++vertexProps;
    }
  }
  if (!ascii || nv == 0 || vertexProps < 3)
  {
    return false;
  }
  m.vertices.resize(nv);
  for (std::size_t i = 0; i < nv && std::getline(in, line); ++i)
  {
    std::istringstream s(line);
    s >> m.vertices[i].x >> m.vertices[i].y >> m.vertices[i].z;
  }
  for (std::size_t f = 0; f < nf && std::getline(in, line); ++f)
  {
    std::istringstream s(line);
    std::size_t k;
    s >> k;
    std::vector<std::uint32_t> ids(k);
    for (auto& id : ids)
    {
      s >> id;
    }
    for (std::size_t t = 1; t + 1 < k; ++t)
    {
      m.indices.insert(m.indices.end(), { ids[0], ids[t], ids[t + 1] });
    }
  }
  return !m.indices.empty();
}

/// Rays from a sphere around the mesh through random points of its bounds.
std::vector<Ray<double>> makeRays(const Mesh& m, std::size_t count, std::uint64_t seed)
{
  AABB<double> box;
  for (const auto& v : m.vertices)
  {
    box.extend(v);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  const Vec3<double> c = box.center();
  const double r = glm::length(box.diagonal());
  std::vector<Ray<double>> rays;
  rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    Vec3<double> d;
    do
    {
      d = Vec3<double>(s(rng), s(rng), s(rng));
    } while (glm::dot(d, d) > 1.0 || glm::dot(d, d) < 1e-4);
    const Vec3<double> o = c + r * glm::normalize(d);
    const Vec3<double> t = box.min + Vec3<double>(u(rng), u(rng), u(rng)) * box.diagonal();
    rays.emplace_back(o, t - o);
  }
  return rays;
}

/// Closest hits for rays[begin, end); returns the hit count.
std::size_t traceRange(const BVH& bvh, const Mesh& m, const std::vector<Ray<double>>& rays, std::size_t begin,
  std::size_t end, std::vector<std::uint32_t>* prims)
{
  TriangleIntersector<double> isect(m.view());
  std::size_t hits = 0;
  for (std::size_t i = begin; i < end; ++i)
  {
    Hit<double> h;
    hits += closestHit(bvh, rays[i], isect, h);
    if (prims)
    {
      (*prims)[i] = h.prim;
    }
  }
  return hits;
}

/// Rays per CPU-second on the calling thread.
double raysPerCpuSecond(const BVH& bvh, const Mesh& m, const std::vector<Ray<double>>& rays)
{
  static volatile std::size_t sink; // keeps the traversal from being optimized away
  const double c0 = ThreadSeconds();
  sink = traceRange(bvh, m, rays, 0, rays.size(), nullptr);
  return rays.size() / (ThreadSeconds() - c0);
}

/// Rays per second with `threads` threads (rays split in equal chunks).
double raysPerSecond(const BVH& bvh, const Mesh& m, const std::vector<Ray<double>>& rays, unsigned threads,
  std::size_t& hits)
{
  const auto t0 = Clock::now();
  std::vector<std::size_t> counts(threads, 0);
  std::vector<std::thread> pool;
  for (unsigned k = 0; k < threads; ++k)
  {
    pool.emplace_back([&, k]() {
      counts[k] = traceRange(bvh, m, rays, rays.size() * k / threads, rays.size() * (k + 1) / threads, nullptr);
    });
  }
  for (auto& t : pool)
  {
    t.join();
  }
  hits = 0;
  for (std::size_t c : counts)
  {
    hits += c;
  }
  return rays.size() / Seconds(t0, Clock::now());
}

#ifdef VTKRT_HAVE_EMBREE
struct EmbreeResult
{
  double buildSeconds = 0, raysPerSecond = 0;
  std::size_t hits = 0, disagreements = 0;
};

/// Embree 3 peer (float, robust mode, high build quality), single thread
/// rtcIntersect1 over the same rays; compares hit/miss with ours.
EmbreeResult runEmbree(const Mesh& m, const std::vector<Ray<double>>& rays, const std::vector<std::uint32_t>& ours)
{
  EmbreeResult r;
  RTCDevice device = rtcNewDevice("threads=1");
  const double c0 = ThreadSeconds();
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
    geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()));
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
  {
    v[3 * i] = float(m.vertices[i].x);
    v[3 * i + 1] = float(m.vertices[i].y);
    v[3 * i + 2] = float(m.vertices[i].z);
  }
  unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
    geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.triangles()));
  std::memcpy(idx, m.indices.data(), m.indices.size() * sizeof(unsigned));
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  r.buildSeconds = ThreadSeconds() - c0;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  const double c1 = ThreadSeconds();
  std::vector<std::uint32_t> prims(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    RTCRayHit rh;
    rh.ray.org_x = float(rays[i].org.x);
    rh.ray.org_y = float(rays[i].org.y);
    rh.ray.org_z = float(rays[i].org.z);
    rh.ray.dir_x = float(rays[i].dir.x);
    rh.ray.dir_y = float(rays[i].dir.y);
    rh.ray.dir_z = float(rays[i].dir.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.ray.time = 0.0f;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    prims[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kInvalidIndex : rh.hit.primID;
  }
  r.raysPerSecond = rays.size() / (ThreadSeconds() - c1);
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    r.hits += prims[i] != kInvalidIndex;
    r.disagreements += (prims[i] == kInvalidIndex) != (ours[i] == kInvalidIndex);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return r;
}
#endif

void benchMesh(const Mesh& m, std::size_t rayCount, bool brute, bool sweep, unsigned threads)
{
  std::printf("\n== %s: %zu triangles, %zu vertices ==\n", m.name.c_str(), m.triangles(), m.vertices.size());
  const std::vector<Ray<double>> rays = makeRays(m, rayCount, 42);
  std::printf("(1T columns: CPU time of the one thread; allT and build: wall time with %u threads)\n", threads);
  std::printf("%-12s %9s %9s %9s %8s %6s %8s %8s %10s %10s %11s\n", "builder", "build 1T", "build", "nodes", "SAH",
    "depth", "CPU MiB", "GPU MiB", "Mray/s 1T", "Mray/s 1Tw", "Mray/s allT");
  const BuildQuality qualities[] = { BuildQuality::Fast, BuildQuality::Medium, BuildQuality::High };
  const char* names[] = { "fast", "binned-sah", "sweep-sah" };
  BVH reference;
  for (int q = 0; q < 3; ++q)
  {
    if (q == 2 && !sweep)
    {
      std::printf("%-12s (skipped)\n", names[q]);
      continue;
    }
    BuildOptions opt;
    opt.quality = qualities[q];
    opt.numThreads = 1;
    const double c0 = ThreadSeconds();
    const BVH single = buildTriangleBVH(m.view(), opt);
    const double buildCpu = ThreadSeconds() - c0;
    opt.numThreads = threads;
    BVH bvh = buildTriangleBVH(m.view(), opt);
    std::size_t hits1 = 0, hitsN = 0;
    const double rCpu = raysPerCpuSecond(bvh, m, rays);
    const double r1 = raysPerSecond(bvh, m, rays, 1, hits1);
    const double rN = raysPerSecond(bvh, m, rays, threads, hitsN);
    const double gpuBytes = bvh.nodes.size() * 32.0 + bvh.primIndex.size() * 4.0;
    std::printf("%-12s %8.3fs %8.3fs %9zu %8.2f %6u %8.1f %8.1f %10.3f %10.3f %11.3f\n", names[q], buildCpu,
      bvh.stats.buildSeconds, bvh.nodes.size(), bvh.stats.sahCost, bvh.stats.maxDepth, bvh.memoryBytes() / 1048576.0,
      gpuBytes / 1048576.0, rCpu / 1e6, r1 / 1e6, rN / 1e6);
    if (hits1 != hitsN || !(single.nodes == bvh.nodes))
    {
      std::printf("  WARNING: results differ between 1 and %u threads\n", threads);
    }
    if (q == 1)
    {
      reference = std::move(bvh);
    }
  }
  std::vector<std::uint32_t> ours(rays.size());
  traceRange(reference, m, rays, 0, rays.size(), &ours);
  std::size_t ourHits = 0;
  for (std::uint32_t p : ours)
  {
    ourHits += p != kInvalidIndex;
  }
  std::printf("binned-sah hits: %zu of %zu rays\n", ourHits, rays.size());
  if (brute)
  {
    const std::size_t n = std::min<std::size_t>(rays.size(), 300);
    TriangleIntersector<double> isect(m.view());
    const double c0 = ThreadSeconds();
    std::size_t disagree = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      Hit<double> best;
      for (std::uint32_t p = 0; p < m.triangles(); ++p)
      {
        Hit<double> h;
        Ray<double> r = rays[i];
        r.tmax = best.t;
        if (isect(p, r, h))
        {
          best = h;
          best.prim = p;
        }
      }
      disagree += best.prim != ours[i];
    }
    const double rate = n / (ThreadSeconds() - c0);
    const double bvhRate = raysPerCpuSecond(reference, m, rays);
    std::printf("brute force: %.1f rays per CPU-second; binned-sah BVH is %.0fx faster; %zu of %zu rays "
                "disagree on the hit triangle\n",
      rate, bvhRate / rate, disagree, n);
  }
#ifdef VTKRT_HAVE_EMBREE
  const EmbreeResult e = runEmbree(m, rays, ours);
  const double oursRate = raysPerCpuSecond(reference, m, rays);
  std::printf("embree3 (float, robust, high quality, 1 thread, CPU time): build %.3fs, %.3f Mray/s; "
              "vtkrt binned-sah/embree ray rate %.2f; hit/miss disagreements %zu of %zu\n",
    e.buildSeconds, e.raysPerSecond / 1e6, oursRate / e.raysPerSecond, e.disagreements, rays.size());
#else
  std::printf("embree3: not found at build time\n");
#endif
}

} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  std::size_t rayCount = 200000;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else if (!std::strcmp(argv[i], "--rays") && i + 1 < argc)
    {
      rayCount = std::strtoull(argv[++i], nullptr, 10);
    }
  }
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::printf("vtkrtBenchBVH: %u hardware threads, %zu random rays per mesh, closest hit in double\n", threads,
    rayCount);

  benchMesh(makeTerrain(225, 1), rayCount, true, true, threads); // ~100k
  if (!quick)
  {
    benchMesh(makeTerrain(708, 2), rayCount, false, true, threads);  // ~1M
    benchMesh(makeTerrain(1415, 3), rayCount, false, true, threads); // ~4M
  }
  const std::string bunnyPath = vtkrtDataFile::Find("bunny.ply");
  Mesh bunny;
  bunny.name = "bunny";
  if (readAsciiPly(bunnyPath, bunny))
  {
    benchMesh(bunny, rayCount, true, true, threads);
  }
  else if (bunnyPath.empty())
  {
    std::printf("\n%s: skipped\n", vtkrtDataFile::NotFound("bunny.ply").c_str());
  }
  else
  {
    std::printf("\nbunny: %s is not an ASCII PLY, skipped\n", bunnyPath.c_str());
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("\npeak resident memory of the whole run: %.0f MiB\n", usage.ru_maxrss / 1024.0);
  return 0;
}
