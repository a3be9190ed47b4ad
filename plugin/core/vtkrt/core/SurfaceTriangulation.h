// The triangles of a surface's polygons and triangle strips, in the order
// and with the rules VTK's raster mapper draws them, made once so that the
// ray tracer and the cell locator can share them, and the finite bounds of
// the points they index.
#ifndef vtkrt_core_SurfaceTriangulation_h
#define vtkrt_core_SurfaceTriangulation_h

#include "vtkrt/core/AABB.h"
#include "vtkrt/core/HugePageArray.h"
#include "vtkrt/core/Math.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace vtkrt::core
{

/// A cell array in VTK 9's layout: cell i's point ids are
/// connectivity[offsets[i]] .. connectivity[offsets[i + 1] - 1].
template <class IdT>
struct CellArrayView
{
  const IdT* offsets = nullptr;
  const IdT* connectivity = nullptr;
  std::int64_t cells = 0;
};

/// What a triangle is of its cell (flags).
enum SurfaceTrianglePart : std::uint8_t
{
  FlippedStripTriangle = 1, ///< odd triangle of a strip: drawn as (k, k + 2, k + 1)
  FanTriangle = 2,          ///< part of a polygon of four or more points
  WholeTriangle = 4,        ///< a polygon of three points, in the cell's order
};

/// Polygons then strips, cell by cell: a polygon of n >= 3 points is the fan
/// (0, k, k + 1), k = 1 .. n - 2; a strip of n >= 3 points the triangles
/// (k, k + 1, k + 2), k = 0 .. n - 3, subId k (odd ones FlippedStripTriangle).
/// Cells of fewer than three points make no triangle. Every triangle is
/// kept, whatever its point ids hold: each user decides what it skips.
struct SurfaceTriangles
{
  NoFillArray<std::uint32_t> pointIds; ///< three per triangle
  /// Per triangle; all three empty when `uniform`.
  NoFillArray<std::int64_t> cellIds;
  NoFillArray<std::int32_t> subIds;
  NoFillArray<std::uint8_t> parts; ///< SurfaceTrianglePart
  /// Every polygon has three points and no strip makes a triangle: triangle
  /// t is the WholeTriangle cell firstCellId + t, subId 0.
  bool uniform = false;
  std::int64_t firstCellId = 0; ///< the first polygon's cell id
  std::size_t count = 0;
  std::size_t degenerateCells = 0;     ///< polygons and strips of fewer than three points
  std::size_t invalidPointIdCells = 0; ///< polygons and strips naming an id outside [0, points)

  std::int64_t cellId(std::size_t t) const
  {
    return this->uniform ? this->firstCellId + static_cast<std::int64_t>(t) : this->cellIds[t];
  }
  std::int32_t subId(std::size_t t) const { return this->uniform ? 0 : this->subIds[t]; }
  std::uint8_t part(std::size_t t) const
  {
    return this->uniform ? std::uint8_t(WholeTriangle) : this->parts[t];
  }
  std::size_t memoryBytes() const
  {
    return this->pointIds.capacity() * sizeof(std::uint32_t) +
      this->cellIds.capacity() * sizeof(std::int64_t) +
      this->subIds.capacity() * sizeof(std::int32_t) + this->parts.capacity();
  }
};

namespace detail
{
/// Fixed chunks of cells (the same output for any thread count): each
/// chunk's triangles are counted first, then written at their place.
constexpr std::int64_t kTriangulationChunks = 256;

inline std::int64_t chunkFirstCell(std::int64_t cells, std::int64_t chunk, std::int64_t chunks)
{
  return chunks > 0 ? cells * chunk / chunks : 0;
}

template <class IdT>
std::size_t cellTriangles(const CellArrayView<IdT>& view, std::int64_t i)
{
  const IdT n = view.offsets[i + 1] - view.offsets[i];
  return n > 2 ? static_cast<std::size_t>(n - 2) : 0;
}

/// One cell array's triangles, counted per chunk, then written.
template <class IdT>
struct CellArrayTriangles
{
  CellArrayTriangles(const CellArrayView<IdT>& cells, bool stripCells, std::int64_t firstCell)
    : view(cells)
    , strips(stripCells)
    , firstCellId(firstCell)
  {
  }

  CellArrayView<IdT> view;
  bool strips = false;
  std::int64_t firstCellId = 0;
  std::vector<std::size_t> chunkFirst; ///< triangles before each chunk, then the total
  std::vector<std::size_t> chunkDegenerate, chunkInvalid;
  bool allTriangles = true; ///< every cell has three points

  std::int64_t chunks() const { return static_cast<std::int64_t>(this->chunkFirst.size()) - 1; }

  template <class ParallelFor>
  void count(ParallelFor&& parallelFor)
  {
    const std::int64_t chunks = std::min(kTriangulationChunks, this->view.cells);
    this->chunkFirst.assign(static_cast<std::size_t>(std::max<std::int64_t>(chunks, 0)) + 1, 0);
    this->chunkDegenerate.assign(this->chunkFirst.size(), 0);
    this->chunkInvalid.assign(this->chunkFirst.size(), 0);
    std::vector<char> chunkAllTriangles(this->chunkFirst.size(), 1);
    parallelFor(static_cast<std::size_t>(std::max<std::int64_t>(chunks, 0)), [&](std::size_t cb, std::size_t ce) {
      for (std::size_t c = cb; c < ce; ++c)
      {
        std::size_t n = 0, degenerate = 0;
        const std::int64_t e = chunkFirstCell(this->view.cells, static_cast<std::int64_t>(c) + 1, chunks);
        for (std::int64_t i = chunkFirstCell(this->view.cells, static_cast<std::int64_t>(c), chunks); i < e; ++i)
        {
          const std::size_t t = cellTriangles(this->view, i);
          n += t;
          degenerate += t == 0 ? 1 : 0;
          chunkAllTriangles[c] &= static_cast<char>(this->view.offsets[i + 1] - this->view.offsets[i] == 3);
        }
        this->chunkFirst[c + 1] = n;
        this->chunkDegenerate[c] = degenerate;
      }
    });
    std::partial_sum(this->chunkFirst.begin(), this->chunkFirst.end(), this->chunkFirst.begin());
    this->allTriangles = std::all_of(chunkAllTriangles.begin(), chunkAllTriangles.end(), [](char a) { return a != 0; });
  }

  std::size_t total() const { return this->chunkFirst.back(); }

  /// Writes triangles from `first` on (per-triangle arrays when `out` is not uniform).
  template <class ParallelFor>
  void write(SurfaceTriangles& out, std::size_t first, std::int64_t points, ParallelFor&& parallelFor)
  {
    const std::int64_t chunks = this->chunks();
    parallelFor(static_cast<std::size_t>(chunks), [&](std::size_t cb, std::size_t ce) {
      for (std::size_t c = cb; c < ce; ++c)
      {
        std::size_t t = first + this->chunkFirst[c];
        std::size_t invalid = 0;
        const std::int64_t e = chunkFirstCell(this->view.cells, static_cast<std::int64_t>(c) + 1, chunks);
        for (std::int64_t i = chunkFirstCell(this->view.cells, static_cast<std::int64_t>(c), chunks); i < e; ++i)
        {
          const IdT* pts = this->view.connectivity + this->view.offsets[i];
          const IdT npts = this->view.offsets[i + 1] - this->view.offsets[i];
          bool valid = true;
          for (IdT k = 0; k < npts; ++k)
          {
            valid = valid && pts[k] >= 0 && static_cast<std::int64_t>(pts[k]) < points;
          }
          invalid += valid ? 0 : 1;
          this->writeCell(out, t, pts, npts, this->firstCellId + i);
        }
        this->chunkInvalid[c] = invalid;
      }
    });
  }

  void writeCell(SurfaceTriangles& out, std::size_t& t, const IdT* pts, IdT npts, std::int64_t cellId) const
  {
    for (IdT k = 0; k + 2 < npts; ++k, ++t)
    {
      std::uint32_t* tri = &out.pointIds[3 * t];
      tri[0] = static_cast<std::uint32_t>(this->strips ? pts[k] : pts[0]);
      tri[1] = static_cast<std::uint32_t>(pts[k + 1]);
      tri[2] = static_cast<std::uint32_t>(pts[k + 2]);
      if (!out.uniform)
      {
        out.cellIds[t] = cellId;
        out.subIds[t] = this->strips ? static_cast<std::int32_t>(k) : 0;
        out.parts[t] = this->strips ? std::uint8_t((k & 1) ? FlippedStripTriangle : 0)
                                    : std::uint8_t(npts == 3 ? WholeTriangle : FanTriangle);
      }
    }
  }

  std::size_t degenerate() const
  {
    return std::accumulate(this->chunkDegenerate.begin(), this->chunkDegenerate.end(), std::size_t(0));
  }
  std::size_t invalid() const
  {
    return std::accumulate(this->chunkInvalid.begin(), this->chunkInvalid.end(), std::size_t(0));
  }
};
} // namespace detail

/// The triangles of `polys` (cell ids from firstPolyCell on) and of `strips`
/// (numbered after the polygons) over `points` points (ids at or beyond it
/// count as invalid). parallelFor(n, body) runs body(begin, end) over [0, n).
template <class PolyIdT, class StripIdT, class ParallelFor>
SurfaceTriangles triangulateSurface(const CellArrayView<PolyIdT>& polys, std::int64_t firstPolyCell,
  const CellArrayView<StripIdT>& strips, std::int64_t points, ParallelFor&& parallelFor)
{
  detail::CellArrayTriangles<PolyIdT> p(polys, false, firstPolyCell);
  detail::CellArrayTriangles<StripIdT> s(strips, true, firstPolyCell + polys.cells);
  p.count(parallelFor);
  s.count(parallelFor);
  SurfaceTriangles out;
  out.count = p.total() + s.total();
  out.firstCellId = firstPolyCell;
  out.uniform = out.count > 0 && p.allTriangles && s.total() == 0;
  out.pointIds.resize(3 * out.count);
  if (!out.uniform)
  {
    out.cellIds.resize(out.count);
    out.subIds.resize(out.count);
    out.parts.resize(out.count);
  }
  p.write(out, 0, points, parallelFor);
  s.write(out, p.total(), points, parallelFor);
  out.degenerateCells = p.degenerate() + s.degenerate();
  out.invalidPointIdCells = p.invalid() + s.invalid();
  return out;
}

/// The bounds of the finite points among `count` x y z triples, and how many
/// are not finite; in fixed chunks (the same result for any thread count).
template <class T, class ParallelFor>
AABB<double> finitePointBounds(const T* xyz, std::size_t count, std::size_t& nonFinite, ParallelFor&& parallelFor)
{
  constexpr std::size_t kChunks = 64;
  std::vector<AABB<double>> chunkBox(kChunks);
  std::vector<std::size_t> chunkNonFinite(kChunks, 0);
  parallelFor(kChunks, [&](std::size_t cb, std::size_t ce) {
    for (std::size_t c = cb; c < ce; ++c)
    {
      AABB<double> box;
      std::size_t bad = 0;
      for (std::size_t i = c * count / kChunks, e = (c + 1) * count / kChunks; i < e; ++i)
      {
        const Vec3<double> p(static_cast<double>(xyz[3 * i]), static_cast<double>(xyz[3 * i + 1]),
          static_cast<double>(xyz[3 * i + 2]));
        if (isFinite(p))
        {
          box.extend(p);
        }
        else
        {
          ++bad;
        }
      }
      chunkBox[c] = box;
      chunkNonFinite[c] = bad;
    }
  });
  AABB<double> all;
  for (const AABB<double>& box : chunkBox)
  {
    all.extend(box);
  }
  nonFinite = std::accumulate(chunkNonFinite.begin(), chunkNonFinite.end(), std::size_t(0));
  return all;
}

} // namespace vtkrt::core

#endif
