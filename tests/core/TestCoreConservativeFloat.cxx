// The four-wide float pre-tests of ConservativeFloat.h never reject what the
// double tests accept: every triangle the double watertight test hits (any
// t) keeps its candidate bit, every box the double robust slab test hits
// keeps its bit with an entry distance <= the scaled tmax of any t inside it.
// Rays: random, aimed exactly at vertices, at points of edges, a relative
// 1e-12 outside edges, from near and far origins, at mesh scales 1e-6..1e6
// and local extents up to 1e6 x the triangle size (culling checked up to
// 100x); boxes hit at corners,
// edges and faces, with segments ending exactly on them, with and without a
// tolerance. The pre-tests must also cull: most clear misses are rejected.
// Boxes quantized to a wide node's grid (QuantizedBoxPack8) hold their float
// boxes with exact decoded planes, also far from 0 (offsets to 1e15, sizes
// 1e-6..1e3), and keep every double hit; their SSE and AVX2 tests give the float
// test's bits and entry distances on the decoded boxes.
// The triangle test reading a leaf's triangles one after another gives the
// same bits as the packed form, for one to eight lanes. The outward
// rounding helpers (ceilFloat, floorFloat, nextUp, nextDown) agree with
// std::nextafter on zeros, subnormals, exact floats and values between.
#include "CoreTestUtils.h"

#include "vtkrt/core/ConservativeFloat.h"

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace vtkrt::core;
using namespace vtkrt::test;

namespace
{

struct Counts
{
  long long doubleHits = 0, missedByFloat = 0, clearMisses = 0, clearRejected = 0;
};

/// One triangle, one ray, all four lanes (the same triangle in a rotated
/// lane, the other lanes noise): checks the lane of interest.
void checkTriangle(const Vec3<double>& v0, const Vec3<double>& v1, const Vec3<double>& v2,
  const Ray<double>& ray, double extent, int lane, bool clearMiss, Counts& c)
{
  const RayTrianglePrecomputed<double> pre(ray);
  ConservativeRay4 fray;
  if (!fray.init(ray, pre, 0.0, extent))
  {
    return; // the caller falls back to double: nothing to check
  }
  TrianglePack4 pack;
  // The same four triangles stored one after another (a leaf's layout),
  // eight times over so that the eight-wide form can read lanes 4-7 too.
  float tri[9 * 8 + 1];
  for (int i = 0; i < 4; ++i)
  {
    const Vec3<double> a = i == lane ? v0 : v0 + Vec3<double>(i);
    const Vec3<double> b = i == lane ? v1 : v1 - Vec3<double>(i);
    const Vec3<double> d = i == lane ? v2 : v2 + Vec3<double>(2 * i);
    pack.set(i, a, b, d);
    const Vec3<double> verts[3] = { a, b, d };
    for (int k = 0; k < 3; ++k)
    {
      for (int ax = 0; ax < 3; ++ax)
      {
        tri[9 * i + 3 * k + ax] = tri[9 * (i + 4) + 3 * k + ax] = static_cast<float>(verts[k][ax]);
      }
    }
  }
  tri[9 * 8] = 0.0f;
  const int packBits = triangleCandidates4(fray, pack);
  const bool candidate = (packBits >> lane) & 1;
  // The leaf form computes the same float coordinates: the same bits on its
  // n lanes, for every n.
  for (int n = 1; n <= 4; ++n)
  {
    const int lanes = (1 << n) - 1;
    VTKRT_CHECK((triangleCandidates4(fray, tri, n) & lanes) == (packBits & lanes));
    // Read from the last n triangles of the array (its end padding in reach).
    VTKRT_CHECK((triangleCandidates4(fray, tri + 9 * (8 - n), n) & lanes) == ((packBits | packBits << 4) >> (8 - n) & lanes));
  }
#if VTKRT_CORE_AVX2
  if (useAvx2())
  {
    // The eight-wide AVX2 form: the same bits on each of its n lanes (lanes
    // 4-7 repeat lanes 0-3).
    for (int n = 1; n <= 8; ++n)
    {
      const int lanes = (1 << n) - 1;
      VTKRT_CHECK((triangleCandidates8(fray, tri, n) & lanes) == ((packBits | packBits << 4) & lanes));
    }
  }
#endif
  TriangleHit<double> hit;
  const double inf = std::numeric_limits<double>::infinity();
  const bool hits = intersectRayTriangle(pre, v0, v1, v2, -inf, inf, hit);
  if (hits)
  {
    ++c.doubleHits;
    if (!candidate)
    {
      ++c.missedByFloat;
      if (c.missedByFloat <= 5)
      {
        std::fprintf(stderr, "float pre-test rejects a double hit: org (%.17g %.17g %.17g) dir (%.17g %.17g %.17g)\n",
          ray.org.x, ray.org.y, ray.org.z, ray.dir.x, ray.dir.y, ray.dir.z);
      }
    }
  }
  if (clearMiss)
  {
    VTKRT_CHECK(!hits);
    ++c.clearMisses;
    c.clearRejected += candidate ? 0 : 1;
  }
}

void triangles(Counts& c)
{
  Rng rng(20261124);
  const double scales[] = { 1e-6, 1e-2, 1.0, 1e3, 1e6 };
  const double extents[] = { 1.0, 100.0, 1e6 }; // local extent / triangle size
  for (const double s : scales)
  {
    for (const double ext : extents)
    {
      const double R = ext * s;
      for (int n = 0; n < 6000; ++n)
      {
        // A triangle somewhere in [-R, R]^3 (local frame), size ~s.
        const Vec3<double> base = rng.inBox(Vec3<double>(-R + s), Vec3<double>(R - s));
        const Vec3<double> v0 = base + s * 0.5 * rng.unitVector();
        const Vec3<double> v1 = base + s * 0.5 * rng.unitVector();
        const Vec3<double> v2 = base + s * 0.5 * rng.unitVector();
        // Origin near (a few sizes) or far (up to the extent, and beyond).
        const double dist = s * (n % 3 == 0 ? 3.0 : (n % 3 == 1 ? 50.0 : 2.0 * ext));
        const Vec3<double> org = base + dist * rng.unitVector();
        const double w0 = rng.uniform(), w1 = rng.uniform() * (1.0 - w0);
        const Vec3<double> targets[] = {
          v0, v1, v2,                                  // vertices
          v0 + rng.uniform() * (v1 - v0),              // edges
          v1 + rng.uniform() * (v2 - v1),
          v2 + rng.uniform() * (v0 - v2),
          v0 + w0 * (v1 - v0) + w1 * (v2 - v0),        // inside
        };
        const int lane = n % 4;
        double maxExtent = R + 2.0 * s;
        for (const Vec3<double>& t : targets)
        {
          // Exactly at the target, and a relative 1e-12 / 1e-9 off it.
          for (const double off : { 0.0, 1e-12, -1e-12, 1e-9 })
          {
            const Vec3<double> aim = t + off * s * rng.unitVector();
            checkTriangle(v0, v1, v2, Ray<double>(org, aim - org, 0.0, 1.0), maxExtent, lane, false, c);
          }
        }
        // A clear miss: aimed at a point beyond an edge by a tenth of the size.
        const Vec3<double> mid = 0.5 * (v0 + v1);
        const Vec3<double> away = mid + 0.1 * glm::length(v1 - v0) * glm::normalize(mid - v2);
        const Vec3<double> n0 = triangleNormal(v0, v1, v2);
        const Vec3<double> dir = away - org;
        if (glm::length(n0) > 1e-3 * s * s && std::abs(glm::dot(glm::normalize(n0), glm::normalize(dir))) > 0.3)
        {
          // Culling is asked for where float resolves the triangle: a
          // local extent up to 100 sizes (at 1e6 sizes float's ulp is
          // about a triangle: everything stays a candidate, correctly).
          checkTriangle(v0, v1, v2, Ray<double>(org, dir, 0.0, 1.0), maxExtent, lane, ext <= 100.0, c);
        }
      }
    }
  }
}

void boxes(Counts& c)
{
  Rng rng(77);
  for (int n = 0; n < 200000; ++n)
  {
    const double s = std::pow(10.0, rng.uniform(-5.0, 5.0));
    const Vec3<double> center = rng.inBox(Vec3<double>(-1e3 * s), Vec3<double>(1e3 * s));
    const Vec3<double> half(s * rng.uniform(0.0, 1.0), s * rng.uniform(0.0, 1.0), s * (n % 7 == 0 ? 0.0 : rng.uniform()));
    const AABB<double> box(center - half, center + half);
    const double grow = (n % 5 == 0) ? s * rng.uniform(0.0, 0.1) : 0.0;
    // Target: a corner, a point of an edge, a point of a face, or inside.
    Vec3<double> target;
    for (int k = 0; k < 3; ++k)
    {
      const int kind = (n / 3 + k) % 3;
      target[k] = kind == 0 ? box.min[k] : (kind == 1 ? box.max[k] : rng.uniform(box.min[k], box.max[k]));
    }
    const Vec3<double> org = target + s * std::pow(10.0, rng.uniform(-1.0, 3.0)) * rng.unitVector();
    // Segment ends at the target (exactly on the box) or beyond it.
    const double tmax = (n % 2 == 0) ? 1.0 : 2.0;
    const Ray<double> ray(org, target - org, 0.0, tmax);
    ConservativeRay4 fray;
    const RayTrianglePrecomputed<double> pre(ray);
    const double extent = 0.0;
    if (!fray.init(ray, pre, grow, extent))
    {
      continue;
    }
    BoxPack4 pack;
    const int lane = n % 4;
    for (int i = 0; i < 4; ++i)
    {
      pack.clear(i);
    }
    for (int k = 0; k < 3; ++k)
    {
      pack.lo[k][lane] = roundDownToFloat(box.min[k]);
      pack.hi[k][lane] = roundUpToFloat(box.max[k]);
    }
    alignas(16) float tnear[4];
    const float tmaxF = ConservativeRay4::scaledTmax(ray.tmax);
    const int mask = intersectBoxes4(fray, pack, tmaxF, tnear);
    // The eight-lane test (the pack in both halves): the same bits and entry
    // distances.
    BoxPack8 pack8;
    for (int i = 0; i < 8; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        pack8.lo[k][i] = pack.lo[k][i % 4];
        pack8.hi[k][i] = pack.hi[k][i % 4];
      }
    }
    alignas(32) float tnear8[8];
    VTKRT_CHECK(intersectBoxes8(ConservativeBoxRay4(fray), pack8, tmaxF, tnear8) == (mask | mask << 4));
    VTKRT_CHECK(std::memcmp(tnear8, tnear, sizeof tnear) == 0 && std::memcmp(tnear8 + 4, tnear, sizeof tnear) == 0);
    VTKRT_CHECK((mask & ~(1 << lane)) == 0); // empty lanes never hit
    // The wide node's form: the box quantized on a grid over it and seven
    // siblings (one lane unused). Its decoded boxes hold the float ones; the
    // SSE and AVX2 decoding tests give the bits and entry distances of the
    // float test on the decoded boxes.
    BoxPack8 siblings = pack8;
    for (int i = 0; i < 8; ++i)
    {
      if (i == lane)
      {
        continue;
      }
      if (i == (lane + 5) % 8)
      {
        siblings.clear(i);
        continue;
      }
      const Vec3<double> shift = 2.0 * (half + Vec3<double>(s * 0.01)) *
        Vec3<double>(i - lane, (i * 3) % 5 - 2, (i * 7) % 3 - 1) * rng.uniform(0.5, 1.5);
      for (int k = 0; k < 3; ++k)
      {
        siblings.lo[k][i] = roundDownToFloat(box.min[k] + shift[k]);
        siblings.hi[k][i] = roundUpToFloat(box.max[k] + shift[k]);
      }
    }
    const QuantizedBoxPack8 quant = QuantizedBoxPack8::quantize(siblings);
    VTKRT_CHECK(quant.valid == (0xff & ~(1 << (lane + 5) % 8)));
    const BoxPack8 decoded = quant.decoded();
    for (int i = 0; i < 8; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        VTKRT_CHECK(!(quant.valid >> i & 1) ||
          (decoded.lo[k][i] <= siblings.lo[k][i] && siblings.hi[k][i] <= decoded.hi[k][i]));
      }
    }
    alignas(32) float tnearQ[8], tnearD[8];
    const int maskQ = intersectBoxes8(ConservativeBoxRay4(fray), quant, tmaxF, tnearQ);
    const int maskD = intersectBoxes8(ConservativeBoxRay4(fray), decoded, tmaxF, tnearD) & quant.valid;
    VTKRT_CHECK(maskQ == maskD);
    for (int i = 0; i < 8; ++i)
    {
      VTKRT_CHECK(!(maskQ >> i & 1) || std::memcmp(&tnearQ[i], &tnearD[i], sizeof(float)) == 0);
    }
#if VTKRT_CORE_AVX2
    if (useAvx2())
    {
      alignas(32) float tnearQ8[8];
      VTKRT_CHECK(intersectBoxes8(ConservativeBoxRay8(fray), quant, tmaxF, tnearQ8) == maskQ);
      for (int i = 0; i < 8; ++i)
      {
        VTKRT_CHECK(!(maskQ >> i & 1) || std::memcmp(&tnearQ8[i], &tnearQ[i], sizeof(float)) == 0);
      }
    }
#endif
    double tn;
    const bool hits = intersectRayAABB(
      RayBoxPrecomputed<double>(ray), box.min - Vec3<double>(grow), box.max + Vec3<double>(grow), ray.tmin, ray.tmax, tn);
    if (hits)
    {
      ++c.doubleHits;
      const bool ok = ((mask >> lane) & 1) && tnear[lane] <= ConservativeRay4::scaledTmax(tn) &&
        ((maskQ >> lane) & 1) && tnearQ[lane] <= ConservativeRay4::scaledTmax(tn);
      if (!ok)
      {
        ++c.missedByFloat;
        if (c.missedByFloat <= 5)
        {
          std::fprintf(stderr, "float box test rejects a double hit (n %d, tnear %.9g vs %.17g)\n", n,
            double(tnear[lane]), tn);
        }
      }
    }
    // A clear miss: the same box, aimed a full size beside it.
    const Vec3<double> beside = center + Vec3<double>(3.0 * (glm::length(half) + grow + s));
    const Ray<double> miss(org, beside - org, 0.0, 1.0);
    ConservativeRay4 fmiss;
    if (fmiss.init(miss, RayTrianglePrecomputed<double>(miss), grow, extent) &&
      !intersectRayAABB(miss, AABB<double>(box.min - Vec3<double>(grow), box.max + Vec3<double>(grow)), tn))
    {
      ++c.clearMisses;
      c.clearRejected += ((intersectBoxes4(fmiss, pack, ConservativeRay4::scaledTmax(1.0), tnear) >> lane) & 1) ? 0 : 1;
    }
  }
}

/// Every double hit kept by the float test, and at least 99% of the clear
/// misses culled, over enough of both.
void checkCounts(const char* what, void (*run)(Counts&))
{
  Counts c;
  run(c);
  std::printf("%s: %lld double hits, %lld rejected in float; %lld clear misses, %lld culled\n", what,
    c.doubleHits, c.missedByFloat, c.clearMisses, c.clearRejected);
  VTKRT_CHECK_MSG(c.doubleHits > 100000, "%s: too few double hits", what);
  VTKRT_CHECK_MSG(c.missedByFloat == 0, "%s: double hits rejected in float", what);
  VTKRT_CHECK_MSG(c.clearMisses > 10000, "%s: too few clear misses", what);
  VTKRT_CHECK_MSG(c.clearRejected >= c.clearMisses * 99 / 100, "%s: clear misses not culled", what);
}

/// ceilFloat / floorFloat: the smallest float >= x / largest <= x, and
/// nextUp / nextDown the neighbours, checked against std::nextafter.
void roundingHelpers()
{
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<double> xs = { 0.0, -0.0, 1e-50, -1e-50, 1.0, -1.0, 0.1, -0.1, 3e38, -3e38, 1e-40, -1e-40,
    std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
    std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(),
    0.5 * std::numeric_limits<float>::denorm_min(), 1.5 * std::numeric_limits<float>::denorm_min() };
  std::uint64_t state = 12345;
  for (int i = 0; i < 20000; ++i)
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double mant = static_cast<double>(state >> 11) * 0x1p-53 * 2.0 - 1.0;
    const int e = static_cast<int>((state >> 3) % 260) - 150;
    xs.push_back(std::ldexp(mant, e));
    xs.push_back(static_cast<double>(static_cast<float>(std::ldexp(mant, e)))); // exact floats
  }
  for (const double x : xs)
  {
    const float c = detail::ceilFloat(x), f = detail::floorFloat(x);
    VTKRT_CHECK_MSG(static_cast<double>(c) >= x && !(static_cast<double>(std::nextafter(c, -inf)) >= x),
      "ceilFloat(%.17g) = %.9g", x, static_cast<double>(c));
    VTKRT_CHECK_MSG(static_cast<double>(f) <= x && !(static_cast<double>(std::nextafter(f, inf)) <= x),
      "floorFloat(%.17g) = %.9g", x, static_cast<double>(f));
    const float xf = static_cast<float>(x);
    VTKRT_CHECK_MSG(detail::nextUp(xf) == std::nextafter(xf, inf), "nextUp(%.9g)", static_cast<double>(xf));
    VTKRT_CHECK_MSG(detail::nextDown(xf) == std::nextafter(xf, -inf), "nextDown(%.9g)", static_cast<double>(xf));
  }
}

/// QuantizedBoxPack8 at the extremes: boxes of size 1e-6..1e3 at offsets up
/// to 1e15 from 0 (far out, a box is a few float steps wide, or flat), flat
/// boxes, one to eight lanes. Every decoded plane is the exact value
/// origin + q * step, and the decoded lanes hold the boxes.
void quantizedExtremes()
{
  Rng rng(7);
  int packs = 0;
  for (const double offset : { 0.0, 1.0, -1e3, 1e7, -1e7, 1e12, 1e15 })
  {
    for (const double size : { 1e-6, 1e-3, 1.0, 1e3 })
    {
      for (int rep = 0; rep < 200; ++rep)
      {
        BoxPack8 b;
        const int used = 1 + rep % 8;
        for (int i = 0; i < 8; ++i)
        {
          b.clear(i);
          if (i >= used)
          {
            continue;
          }
          for (int a = 0; a < 3; ++a)
          {
            const double lo = offset + size * rng.uniform(-4.0, 4.0);
            const double hi = lo + size * (rep % 5 == 0 ? 0.0 : rng.uniform(0.0, 2.0));
            b.lo[a][i] = roundDownToFloat(lo);
            b.hi[a][i] = roundUpToFloat(hi);
          }
        }
        const QuantizedBoxPack8 q = QuantizedBoxPack8::quantize(b);
        VTKRT_CHECK(q.valid == (1 << used) - 1);
        const BoxPack8 d = q.decoded();
        for (int i = 0; i < used; ++i)
        {
          for (int a = 0; a < 3; ++a)
          {
            const double step = std::ldexp(1.0, q.exp[a]);
            VTKRT_CHECK(static_cast<double>(d.lo[a][i]) == static_cast<double>(q.origin[a]) + q.q[a][i] * step);
            VTKRT_CHECK(static_cast<double>(d.hi[a][i]) == static_cast<double>(q.origin[a]) + q.q[3 + a][i] * step);
            VTKRT_CHECK_MSG(d.lo[a][i] <= b.lo[a][i] && b.hi[a][i] <= d.hi[a][i],
              "offset %g size %g: lane %d axis %d [%.9g, %.9g] not in [%.9g, %.9g]", offset, size, i, a,
              double(b.lo[a][i]), double(b.hi[a][i]), double(d.lo[a][i]), double(d.hi[a][i]));
          }
        }
        ++packs;
      }
    }
  }
  std::printf("quantized boxes: %d packs at offsets 0..1e15, sizes 1e-6..1e3\n", packs);
}

/// ConservativeRay4::initAvx2 fills the same fields as init, bit for bit,
/// and refuses the same rays: random directions and origins over many
/// scales, exact floats, signed zeros, axis-parallel, subnormal and huge
/// components, growths and extents.
void initForms()
{
#if VTKRT_CORE_AVX2
  if (!useAvx2())
  {
    std::printf("init forms: no AVX2 here, skipped\n");
    return;
  }
  Rng rng(77);
  const double specials[] = { 0.0, -0.0, 1.0, -1.0, 0.5, 1e-300, -1e-310, 1e-45, 3e38, -1e17, 1e18,
    0x1p-149, 16777217.0, -0.1, 1e8 + 0.3 };
  auto component = [&](int kind) {
    switch (kind % 4)
    {
      case 0:
        return specials[rng.index(sizeof specials / sizeof specials[0])];
      case 1:
        return static_cast<double>(static_cast<float>(rng.uniform(-10, 10))); // an exact float
      default:
        return rng.uniform(-1, 1) * std::pow(10.0, rng.uniform(-30, 20));
    }
  };
  int compared = 0, refused = 0;
  for (int i = 0; i < 200000; ++i)
  {
    Ray<double> ray;
    for (int a = 0; a < 3; ++a)
    {
      ray.org[a] = component(static_cast<int>(rng.index(4)));
      ray.dir[a] = component(static_cast<int>(rng.index(4)));
    }
    ray.tmin = rng.index(4) == 0 ? rng.uniform(0, 1) : 0.0;
    ray.tmax = 1.0;
    if (!ray.isValid())
    {
      continue;
    }
    const double grow = rng.index(3) == 0 ? rng.uniform(0, 1e-3) : 0.0;
    const double extent = std::pow(10.0, rng.uniform(-6, 18));
    const RayTrianglePrecomputed<double> pre(ray);
    ConservativeRay4 a, b;
    std::memset(&a, 0, sizeof a);
    std::memset(&b, 0, sizeof b);
    const bool okA = a.init(ray, pre, grow, extent);
    const bool okB = b.initAvx2(ray, pre, grow, extent);
    VTKRT_CHECK(okA == okB);
    if (okA && okB)
    {
      ++compared;
      VTKRT_CHECK(std::memcmp(&a, &b, sizeof a) == 0);
    }
    refused += okA ? 0 : 1;
  }
  VTKRT_CHECK(compared > 50000 && refused > 1000);
  std::printf("init forms: %d rays the same bit for bit, %d refused by both\n", compared, refused);
#endif
}

} // namespace

int main()
{
  initForms();
  roundingHelpers();
  quantizedExtremes();
  checkCounts("triangles", triangles);
  checkCounts("boxes", boxes);

  // Preconditions: no float path for axis-parallel or overflowing rays.
  ConservativeRay4 fray;
  const Ray<double> parallel(Vec3<double>(0.0), Vec3<double>(1.0, 0.0, 1.0), 0.0, 1.0);
  VTKRT_CHECK(!fray.init(parallel, RayTrianglePrecomputed<double>(parallel), 0.0, 1.0));
  const Ray<double> far(Vec3<double>(1e20), Vec3<double>(1.0), 0.0, 1.0);
  VTKRT_CHECK(!fray.init(far, RayTrianglePrecomputed<double>(far), 0.0, 1.0));
  return testResult("TestCoreConservativeFloat");
}
