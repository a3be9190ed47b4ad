// core::triangulateSurface against the rules written out cell by cell
// (fans from the first point, strips with their subIds and flipped odd
// triangles), the uniform form of triangle-only polygons, the counts of
// degenerate and out-of-range cells, any chunking of the parallel loop; and
// core::finitePointBounds.
#include "CoreTestUtils.h"

#include "vtkrt/core/SurfaceTriangulation.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace vtkrt::test;

namespace
{
/// parallelFor that runs body over [0, n) in pieces of `step` (any order of
/// pieces gives the same output: each chunk writes its own place).
struct PiecesFor
{
  std::size_t step;
  template <class Body>
  void operator()(std::size_t n, Body&& body) const
  {
    for (std::size_t b = n; b > 0;)
    {
      const std::size_t lo = b > this->step ? b - this->step : 0;
      body(lo, b);
      b = lo;
    }
  }
};

struct Cells
{
  std::vector<std::int64_t> offsets{ 0 };
  std::vector<std::int64_t> connectivity;
  void add(std::vector<std::int64_t> ids)
  {
    connectivity.insert(connectivity.end(), ids.begin(), ids.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  CellArrayView<std::int64_t> view() const
  {
    return { offsets.data(), connectivity.data(), static_cast<std::int64_t>(offsets.size()) - 1 };
  }
};

struct Expected
{
  std::vector<std::uint32_t> ids;
  std::vector<std::int64_t> cells;
  std::vector<std::int32_t> subs;
  std::vector<std::uint8_t> parts;
};

Expected writtenOut(const Cells& polys, const Cells& strips, std::int64_t firstCell)
{
  Expected e;
  std::int64_t cell = firstCell;
  for (std::size_t c = 0; c + 1 < polys.offsets.size(); ++c, ++cell)
  {
    const std::int64_t* p = polys.connectivity.data() + polys.offsets[c];
    const std::int64_t n = polys.offsets[c + 1] - polys.offsets[c];
    for (std::int64_t k = 1; k + 1 < n; ++k)
    {
      e.ids.insert(e.ids.end(), { std::uint32_t(p[0]), std::uint32_t(p[k]), std::uint32_t(p[k + 1]) });
      e.cells.push_back(cell);
      e.subs.push_back(0);
      e.parts.push_back(n == 3 ? WholeTriangle : FanTriangle);
    }
  }
  for (std::size_t c = 0; c + 1 < strips.offsets.size(); ++c, ++cell)
  {
    const std::int64_t* p = strips.connectivity.data() + strips.offsets[c];
    const std::int64_t n = strips.offsets[c + 1] - strips.offsets[c];
    for (std::int64_t k = 0; k + 2 < n; ++k)
    {
      e.ids.insert(e.ids.end(), { std::uint32_t(p[k]), std::uint32_t(p[k + 1]), std::uint32_t(p[k + 2]) });
      e.cells.push_back(cell);
      e.subs.push_back(static_cast<std::int32_t>(k));
      e.parts.push_back((k & 1) ? FlippedStripTriangle : 0);
    }
  }
  return e;
}

void checkSame(const SurfaceTriangles& t, const Expected& e)
{
  VTKRT_CHECK(t.count == e.cells.size());
  VTKRT_CHECK(std::vector<std::uint32_t>(t.pointIds.begin(), t.pointIds.end()) == e.ids);
  for (std::size_t i = 0; i < t.count && i < e.cells.size(); ++i)
  {
    VTKRT_CHECK_MSG(t.cellId(i) == e.cells[i] && t.subId(i) == e.subs[i] && t.part(i) == e.parts[i],
      "triangle %zu", i);
  }
}

void mixedCells()
{
  Rng rng(7);
  Cells polys, strips;
  const std::int64_t points = 1000;
  for (int c = 0; c < 700; ++c)
  {
    const int n = 3 + static_cast<int>(rng.uniform(0.0, 1.0) * 6.0); // 3..8 points
    std::vector<std::int64_t> ids;
    for (int k = 0; k < n; ++k)
    {
      ids.push_back(static_cast<std::int64_t>(rng.uniform(0.0, 1.0) * (points - 1)));
    }
    polys.add(ids);
  }
  for (int c = 0; c < 90; ++c)
  {
    const int n = 3 + c % 11;
    std::vector<std::int64_t> ids;
    for (int k = 0; k < n; ++k)
    {
      ids.push_back((c * 13 + k) % points);
    }
    strips.add(ids);
  }
  const Expected e = writtenOut(polys, strips, 40);
  for (std::size_t step : { 1, 3, 1000 })
  {
    const SurfaceTriangles t = triangulateSurface(polys.view(), 40, strips.view(), points, PiecesFor{ step });
    VTKRT_CHECK(!t.uniform && t.degenerateCells == 0 && t.invalidPointIdCells == 0);
    checkSame(t, e);
  }
}

void triangleOnlyPolys()
{
  Cells polys, strips;
  for (int c = 0; c < 600; ++c)
  {
    polys.add({ c, c + 1, c + 2 });
  }
  const SurfaceTriangles t = triangulateSurface(polys.view(), 5, strips.view(), 602, PiecesFor{ 7 });
  VTKRT_CHECK(t.uniform && t.count == 600 && t.cellIds.empty() && t.subIds.empty() && t.parts.empty());
  checkSame(t, writtenOut(polys, strips, 5));
  // A strip triangle makes it per-triangle again.
  strips.add({ 0, 1, 2, 3 });
  const SurfaceTriangles u = triangulateSurface(polys.view(), 5, strips.view(), 602, PiecesFor{ 7 });
  VTKRT_CHECK(!u.uniform && u.count == 602);
  checkSame(u, writtenOut(polys, strips, 5));
}

void degenerateAndInvalid()
{
  Cells polys, strips;
  polys.add({ 0, 1, 2 });
  polys.add({ 0, 1 });       // no triangle
  polys.add({ 0, 1, 9, 3 }); // 9 is out of range
  polys.add({ -1, 1, 2 });   // so is -1
  strips.add({ 3 });         // no triangle
  strips.add({ 0, 1, 2, 3, 4 });
  const SurfaceTriangles t = triangulateSurface(polys.view(), 0, strips.view(), 5, PiecesFor{ 2 });
  VTKRT_CHECK(t.degenerateCells == 2);
  VTKRT_CHECK(t.invalidPointIdCells == 2);
  VTKRT_CHECK(!t.uniform);
  checkSame(t, writtenOut(polys, strips, 0)); // every triangle kept: users decide
  const Cells none;
  const SurfaceTriangles empty = triangulateSurface(none.view(), 0, none.view(), 5, PiecesFor{ 2 });
  VTKRT_CHECK(empty.count == 0 && !empty.uniform);
}

void finiteBounds()
{
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> xyz = { 1, 2, 3, -4, 5, 0.5, std::nan(""), 0, 0, 2, inf, 1, 0, -1, 7 };
  std::size_t nonFinite = 0;
  for (std::size_t step : { 1, 5, 64 })
  {
    const AABB<double> b = finitePointBounds(xyz.data(), 5, nonFinite, PiecesFor{ step });
    VTKRT_CHECK(nonFinite == 2);
    VTKRT_CHECK(b.min == Vec3<double>(-4, -1, 0.5) && b.max == Vec3<double>(1, 5, 7));
  }
  const std::vector<float> none = { std::nanf("") , 0.0f, 0.0f };
  const AABB<double> e = finitePointBounds(none.data(), 1, nonFinite, PiecesFor{ 64 });
  VTKRT_CHECK(e.isEmpty() && nonFinite == 1);
}
} // namespace

int main()
{
  mixedCells();
  triangleOnlyPolys();
  degenerateAndInvalid();
  finiteBounds();
  return testResult("TestCoreSurfaceTriangulation");
}
