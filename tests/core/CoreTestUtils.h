// Shared by the core tests: check macros, deterministic random numbers,
// closed test meshes (icosphere, torus), random triangle soups, brute force.
#ifndef vtkrt_tests_CoreTestUtils_h
#define vtkrt_tests_CoreTestUtils_h

#include "vtkrt/core/Core.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace vtkrt::test
{
using namespace vtkrt::core;

inline int& failureCount()
{
  static int failures = 0;
  return failures;
}

#define VTKRT_CHECK(cond)                                                                          \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);               \
      ++::vtkrt::test::failureCount();                                                             \
    }                                                                                              \
  } while (0)

#define VTKRT_CHECK_MSG(cond, ...)                                                                 \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);               \
      std::fprintf(stderr, __VA_ARGS__);                                                           \
      std::fprintf(stderr, "\n");                                                                  \
      ++::vtkrt::test::failureCount();                                                             \
    }                                                                                              \
  } while (0)

#define VTKRT_CHECK_NEAR(a, b, tol)                                                                \
  VTKRT_CHECK_MSG(std::abs(double(a) - double(b)) <= double(tol), "%.17g vs %.17g (tol %g)", double(a), \
    double(b), double(tol))

inline int testResult(const char* name)
{
  if (failureCount() == 0)
  {
    std::printf("%s: all checks passed\n", name);
    return EXIT_SUCCESS;
  }
  std::fprintf(stderr, "%s: %d check(s) failed\n", name, failureCount());
  return EXIT_FAILURE;
}

struct Rng
{
  std::mt19937_64 engine;
  explicit Rng(std::uint64_t seed)
    : engine(seed)
  {
  }
  double uniform(double lo = 0.0, double hi = 1.0)
  {
    return std::uniform_real_distribution<double>(lo, hi)(engine);
  }
  std::uint32_t index(std::size_t n) { return std::uniform_int_distribution<std::uint32_t>(0, std::uint32_t(n - 1))(engine); }
  Vec3<double> inBox(const Vec3<double>& lo, const Vec3<double>& hi)
  {
    return Vec3<double>(uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z));
  }
  Vec3<double> unitVector()
  {
    for (;;)
    {
      const Vec3<double> v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      const double l2 = glm::dot(v, v);
      if (l2 > 1e-6 && l2 <= 1.0)
      {
        return v / std::sqrt(l2);
      }
    }
  }
};

/// An indexed mesh that owns its arrays.
struct MeshData
{
  std::vector<Vec3<double>> vertices;
  std::vector<std::uint32_t> indices;
  TriangleMesh<double> view() const { return TriangleMesh<double>(vertices, indices); }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// Closed icosphere (shared vertices, consistent winding) of radius r.
inline MeshData makeIcosphere(int subdivisions, double r = 1.0, Vec3<double> center = Vec3<double>(0.0))
{
  MeshData m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double base[12][3] = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t },
    { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
  for (auto& b : base)
  {
    m.vertices.push_back(glm::normalize(Vec3<double>(b[0], b[1], b[2])));
  }
  m.indices = { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6,
    7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1 };
  for (int s = 0; s < subdivisions; ++s)
  {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end())
      {
        return it->second;
      }
      m.vertices.push_back(glm::normalize(m.vertices[a] + m.vertices[b]));
      const std::uint32_t id = std::uint32_t(m.vertices.size() - 1);
      mid[key] = id;
      return id;
    };
    std::vector<std::uint32_t> next;
    for (std::size_t i = 0; i < m.indices.size(); i += 3)
    {
      const std::uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), { a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca });
    }
    m.indices.swap(next);
  }
  for (auto& v : m.vertices)
  {
    v = center + r * v;
  }
  return m;
}

/// Closed torus around z (major radius R, minor r), nu x nv quads split in two.
inline MeshData makeTorus(int nu, int nv, double R = 1.0, double r = 0.35)
{
  MeshData m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
      m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return std::uint32_t((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      m.indices.insert(m.indices.end(), { id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.indices.insert(m.indices.end(), { id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return m;
}

/// Random triangle soup in [0,1]^3 with edge lengths up to `size`.
inline MeshData makeTriangleSoup(Rng& rng, std::size_t count, double size)
{
  MeshData m;
  for (std::size_t i = 0; i < count; ++i)
  {
    const Vec3<double> c = rng.inBox(Vec3<double>(0.0), Vec3<double>(1.0));
    for (int k = 0; k < 3; ++k)
    {
      m.vertices.push_back(c + size * Vec3<double>(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
      m.indices.push_back(std::uint32_t(m.vertices.size() - 1));
    }
  }
  return m;
}

/// Brute-force closest hit with the same kernel; `secondT` gets the nearest
/// t of any other primitive (to tell whether the closest is unique).
template <class T, class Isect>
Hit<T> bruteForceClosest(std::size_t primCount, const Ray<T>& ray, Isect&& isect, T* secondT = nullptr)
{
  Hit<T> best;
  T second = std::numeric_limits<T>::infinity();
  for (std::uint32_t p = 0; p < primCount; ++p)
  {
    Hit<T> h;
    if (isect(p, ray, h))
    {
      if (h.t < best.t || (h.t == best.t && !best.found()))
      {
        second = std::min(second, best.t);
        best = h;
        best.prim = p;
      }
      else
      {
        second = std::min(second, h.t);
      }
    }
  }
  if (secondT)
  {
    *secondT = second;
  }
  return best;
}

} // namespace vtkrt::test
#endif
