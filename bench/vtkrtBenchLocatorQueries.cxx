// The query part of vtkrtBenchLocator: every query of vtkAbstractCellLocator
// on vtkBVHCellLocator and on VTK 9.1's cell locators, in one run, on the
// same probes.
//
// Steady rates: every locator is built and has answered one query of each
// kind first (vtkModifiedBSPTree builds at its first query); then R
// interleaved rounds, each timing every (query, locator) pair in turn from
// thread CPU time: a time is the median over the rounds (see the top of
// vtkrtBenchLocator.cxx for why rounds); a slow locator asks fewer probes
// (as many as a quarter second allows in the first round). First queries:
// BuildLocator() timed, then the first query of each kind timed (wall
// clock: a build may use the SMP pool); for vtkBVHCellLocator a fresh
// locator before each kind, so that no kind finds what another built (best
// of 3: the machine is shared).
//
// A locator gets a query only where VTK 9.1 implements it; where it does
// not, vtkAbstractCellLocator reports an error (FindClosestPoint,
// FindClosestPointWithinRadius, FindCellsWithinBounds, FindCellsAlongLine,
// the all-hits IntersectWithLine) or, for FindCell, falls back to
// vtkDataSet::FindCell (a slow walk over point neighbourhoods, with a
// warning): those cells print "-".
#include "vtkrtBenchLocatorQueries.h"

#include "vtkBVHCellLocator.h"
#include "vtkrtBenchTiming.h"

#include "vtkCellLocator.h"
#include "vtkCellTreeLocator.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkModifiedBSPTree.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStaticCellLocator.h"
#include "vtkTriangle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace vtkrtBench
{
namespace
{
enum Kind
{
  Nearest,
  AllHits,
  AlongLine,
  InBounds,
  Closest,
  WithinRadius,
  PointInCell,
  KindCount
};
const char* const kKindNames[KindCount] = { "IntersectWithLine (nearest hit)",
  "IntersectWithLine (all hits)", "FindCellsAlongLine", "FindCellsWithinBounds", "FindClosestPoint",
  "FindClosestPointWithinRadius", "FindCell" };

struct Point
{
  double X[3];
};
struct Segment
{
  double P1[3], P2[3];
};

/// What the queries ask, as a user's probes would: points on the surface,
/// near it, anywhere around it and far from it.
struct Probes
{
  std::vector<Segment> Segments; ///< ends anywhere in the bounds grown by half (about half hit)
  std::vector<Point> Points;     ///< a mix: on / near the surface, in the grown bounds, far away
  std::vector<Point> CellPoints; ///< FindCell: half on the surface, half in the grown bounds
  double Radius = 0.0;           ///< FindClosestPointWithinRadius: 2% of the diagonal
  double BoxHalf = 0.0;          ///< FindCellsWithinBounds: a cube of 2% of the diagonal a side
  double Tol2 = 0.0;             ///< FindCell
};

class Random
{
public:
  double Next(double lo, double hi)
  {
    const double v = this->Rng->GetRangeValue(lo, hi);
    this->Rng->Next();
    return v;
  }

private:
  vtkNew<vtkMinimalStandardRandomSequence> Rng;
};

/// A random point of a random triangle and its unit normal.
void SurfacePoint(vtkPolyData* pd, Random& rng, double x[3], double n[3])
{
  const vtkIdType cell = std::min<vtkIdType>(
    pd->GetNumberOfCells() - 1, static_cast<vtkIdType>(rng.Next(0, pd->GetNumberOfCells())));
  vtkIdType npts;
  const vtkIdType* ids;
  pd->GetCellPoints(cell, npts, ids);
  double p[3][3];
  for (int k = 0; k < 3; ++k)
  {
    pd->GetPoint(ids[k], p[k]);
  }
  double u = rng.Next(0, 1), v = rng.Next(0, 1);
  if (u + v > 1)
  {
    u = 1 - u;
    v = 1 - v;
  }
  for (int a = 0; a < 3; ++a)
  {
    x[a] = p[0][a] + u * (p[1][a] - p[0][a]) + v * (p[2][a] - p[0][a]);
  }
  vtkTriangle::ComputeNormal(p[0], p[1], p[2], n);
}

Probes MakeProbes(vtkPolyData* pd, int nSegments, int nPoints)
{
  Probes out;
  Random rng;
  double b[6];
  pd->GetBounds(b);
  const double diag = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  out.Radius = 0.02 * diag;
  out.BoxHalf = 0.01 * diag;
  out.Tol2 = 1e-12 * diag * diag;
  auto inBounds = [&](double x[3]) {
    for (int k = 0; k < 3; ++k)
    {
      const double c = 0.5 * (b[2 * k] + b[2 * k + 1]), h = 0.75 * (b[2 * k + 1] - b[2 * k]);
      x[k] = rng.Next(c - h, c + h);
    }
  };
  out.Segments.resize(static_cast<size_t>(nSegments));
  for (auto& s : out.Segments)
  {
    inBounds(s.P1);
    inBounds(s.P2);
  }
  out.Points.resize(static_cast<size_t>(nPoints));
  out.CellPoints.resize(static_cast<size_t>(nPoints));
  for (int i = 0; i < nPoints; ++i)
  {
    double* x = out.Points[i].X;
    double n[3];
    switch (i % 10)
    {
      case 0: case 1: case 2: case 3: // on or near the surface, within 1% of the diagonal
      {
        SurfacePoint(pd, rng, x, n);
        const double off = (i % 10 == 0) ? 0.0 : rng.Next(-0.01, 0.01) * diag;
        for (int a = 0; a < 3; ++a)
        {
          x[a] += off * n[a];
        }
        break;
      }
      case 4: case 5: case 6: // anywhere in the bounds grown by half
        inBounds(x);
        break;
      default: // far: 1 to 3 diagonals from the center
      {
        double d[3], len = 0;
        for (double& c : d)
        {
          c = rng.Next(-1, 1);
          len += c * c;
        }
        const double r = rng.Next(1, 3) * diag / std::sqrt(std::max(len, 1e-12));
        for (int a = 0; a < 3; ++a)
        {
          x[a] = 0.5 * (b[2 * a] + b[2 * a + 1]) + r * d[a];
        }
      }
    }
    if (i % 2 == 0)
    {
      SurfacePoint(pd, rng, out.CellPoints[i].X, n);
    }
    else
    {
      inBounds(out.CellPoints[i].X);
    }
  }
  return out;
}

/// One locator: how to make it and which queries VTK 9.1 gives it.
struct LocatorKind
{
  std::string Name;
  std::function<vtkAbstractCellLocator*()> New;
  std::array<bool, KindCount> Has;
  /// First-query table: a fresh build before each kind's first query
  /// (else one build, then each kind's first query in turn).
  bool FreshPerKind = false;
};

std::vector<LocatorKind> Locators()
{
  // Nearest, all hits, along line, in bounds, closest, within radius, FindCell.
  return {
    { "vtkBVHCellLocator", [] { return static_cast<vtkAbstractCellLocator*>(vtkBVHCellLocator::New()); },
      { true, true, true, true, true, true, true }, true },
    { "vtkStaticCellLocator", [] { return static_cast<vtkAbstractCellLocator*>(vtkStaticCellLocator::New()); },
      { true, false, true, true, true, true, true } },
    { "vtkCellLocator", [] { return static_cast<vtkAbstractCellLocator*>(vtkCellLocator::New()); },
      { true, false, true, true, true, true, true } },
    { "vtkCellTreeLocator", [] { return static_cast<vtkAbstractCellLocator*>(vtkCellTreeLocator::New()); },
      { true, false, false, true, false, false, true } },
    // All hits: its own form with a tolerance.
    { "vtkModifiedBSPTree", [] { return static_cast<vtkAbstractCellLocator*>(vtkModifiedBSPTree::New()); },
      { true, true, false, false, false, false, true } },
  };
}

/// A query's scratch: what a caller keeps between calls.
struct Scratch
{
  vtkNew<vtkGenericCell> Cell;
  vtkNew<vtkIdList> Ids;
  vtkNew<vtkPoints> Points;
  double Weights[64];
};

/// Query i of `kind`; returns its answer as one number (a t, a dist2, a
/// count, a cell id) for the agreement counts.
double Ask(vtkAbstractCellLocator* loc, Kind kind, const Probes& pr, size_t i, Scratch& s)
{
  double x[3], pc[3], t, d2;
  int sub;
  vtkIdType cellId = -1;
  const Segment& seg = pr.Segments[i % pr.Segments.size()];
  Point p = pr.Points[i % pr.Points.size()];
  switch (kind)
  {
    case Nearest:
      return loc->IntersectWithLine(seg.P1, seg.P2, 0.0, t, x, pc, sub, cellId, s.Cell) ? t : -1.0;
    case AllHits:
      if (auto* bsp = vtkModifiedBSPTree::SafeDownCast(loc))
      {
        bsp->IntersectWithLine(seg.P1, seg.P2, 0.0, s.Points, s.Ids);
      }
      else
      {
        loc->IntersectWithLine(seg.P1, seg.P2, s.Points, s.Ids);
      }
      return static_cast<double>(s.Ids->GetNumberOfIds());
    case AlongLine:
      loc->FindCellsAlongLine(seg.P1, seg.P2, 0.0, s.Ids);
      return static_cast<double>(s.Ids->GetNumberOfIds());
    case InBounds:
    {
      double box[6];
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = p.X[a] - pr.BoxHalf;
        box[2 * a + 1] = p.X[a] + pr.BoxHalf;
      }
      loc->FindCellsWithinBounds(box, s.Ids);
      return static_cast<double>(s.Ids->GetNumberOfIds());
    }
    case Closest:
      loc->FindClosestPoint(p.X, x, s.Cell, cellId, sub, d2);
      return d2;
    case WithinRadius:
      return loc->FindClosestPointWithinRadius(p.X, pr.Radius, x, s.Cell, cellId, sub, d2) ? d2 : -1.0;
    case PointInCell:
    {
      Point c = pr.CellPoints[i % pr.CellPoints.size()];
      return static_cast<double>(loc->FindCell(c.X, pr.Tol2, s.Cell, pc, s.Weights));
    }
    default:
      return 0.0;
  }
}

/// The smallest squared distance from x to the surface as it is drawn, over
/// every cell: who is right where the locators disagree. Quads and polygons
/// are the fans from their first point that the locator and raster draw
/// (VTK's own EvaluatePosition measures a warped quad's bilinear patch).
double BruteForceClosest(vtkPolyData* pd, const double x[3], Scratch& s)
{
  double best = VTK_DOUBLE_MAX;
  double xx[3] = { x[0], x[1], x[2] };
  vtkNew<vtkTriangle> tri;
  auto consider = [&](vtkCell* cell) {
    double cp[3], pc[3], d2;
    int sub;
    if (cell->EvaluatePosition(xx, cp, sub, pc, d2, s.Weights) >= 0 && d2 < best)
    {
      best = d2;
    }
  };
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
  {
    pd->GetCell(c, s.Cell);
    const int type = s.Cell->GetCellType();
    if (type != VTK_QUAD && type != VTK_POLYGON)
    {
      consider(s.Cell);
      continue;
    }
    vtkPoints* p = s.Cell->GetPoints();
    for (vtkIdType k = 1; k + 1 < p->GetNumberOfPoints(); ++k)
    {
      tri->GetPoints()->SetPoint(0, p->GetPoint(0));
      tri->GetPoints()->SetPoint(1, p->GetPoint(k));
      tri->GetPoints()->SetPoint(2, p->GetPoint(k + 1));
      consider(tri);
    }
  }
  return best;
}

/// How many of each kind a round asks (the slowest locator sets these).
std::array<int, KindCount> QueryCounts(vtkIdType cells, bool quick)
{
  const int scale = quick ? 5 : 1;
  const bool big = cells > 500000;
  return { 2000 / scale, 500 / scale, (big ? 100 : 300) / scale, 1000 / scale, (big ? 200 : 500) / scale,
    (big ? 200 : 500) / scale, 1000 / scale };
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// Whether two answers agree: the same number, or distances within 1e-9
/// relative, or 1e-10 of the diagonal for squared distances (VTK computes
/// the closest point its own way: on the surface, both are rounding noise).
bool Same(Kind kind, double a, double b, const Probes& pr)
{
  if (kind == Closest || kind == WithinRadius || kind == Nearest)
  {
    const double floor = kind == Nearest ? 1e-300 : 1e-8 * pr.Tol2;
    return (a < 0) == (b < 0) && std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)) + floor;
  }
  return a == b;
}

void SteadyTable(const std::vector<LocatorKind>& kinds, vtkPolyData* pd, const Probes& pr,
  const std::array<int, KindCount>& counts, int rounds)
{
  std::vector<vtkAbstractCellLocator*> locs;
  Scratch s;
  for (const auto& k : kinds)
  {
    vtkAbstractCellLocator* loc = k.New();
    loc->SetDataSet(pd);
    loc->BuildLocator();
    for (int q = 0; q < KindCount; ++q)
    {
      if (k.Has[q])
      {
        Ask(loc, static_cast<Kind>(q), pr, 0, s);
      }
    }
    locs.push_back(loc);
  }
  // times[kind][locator][round], answers[kind][locator][query], and how
  // many probes each (kind, locator) asks: the first round stops a slow
  // locator after kRoundBudget seconds, the later ones ask as many (the
  // probes are mixed evenly, so a prefix is the same mix).
  constexpr double kRoundBudget = 0.25;
  std::vector<std::vector<std::vector<double>>> times(KindCount, std::vector<std::vector<double>>(kinds.size()));
  std::vector<std::vector<std::vector<double>>> answers(KindCount, std::vector<std::vector<double>>(kinds.size()));
  std::vector<std::vector<int>> asked(KindCount, std::vector<int>(kinds.size(), 0));
  for (int round = 0; round < rounds; ++round)
  {
    for (int q = 0; q < KindCount; ++q)
    {
      for (size_t l = 0; l < kinds.size(); ++l)
      {
        if (!kinds[l].Has[q])
        {
          continue;
        }
        std::vector<double>& ans = answers[q][l];
        ans.resize(static_cast<size_t>(counts[q]));
        const int n = round == 0 ? counts[q] : asked[q][l];
        const double c0 = ThreadSeconds();
        int i = 0;
        while (i < n && (round > 0 || i < 10 || ThreadSeconds() - c0 < kRoundBudget))
        {
          ans[i] = Ask(locs[l], static_cast<Kind>(q), pr, static_cast<size_t>(i), s);
          ++i;
        }
        asked[q][l] = i;
        times[q][l].push_back(1e6 * (ThreadSeconds() - c0) / i);
      }
    }
  }
  for (auto* loc : locs)
  {
    loc->Delete();
  }
  std::printf("| query (probes a round) |");
  for (const auto& k : kinds)
  {
    std::printf(" %s us |", k.Name.c_str());
  }
  std::printf(" fastest VTK / ours | answers against the fastest VTK |\n|---|");
  for (size_t l = 0; l <= kinds.size() + 1; ++l)
  {
    std::printf("---:|");
  }
  std::printf("\n");
  for (int q = 0; q < KindCount; ++q)
  {
    std::printf("| %s (%d) |", kKindNames[q], counts[q]);
    double fastest = 0;
    size_t fastestId = 0;
    for (size_t l = 0; l < kinds.size(); ++l)
    {
      if (!kinds[l].Has[q])
      {
        std::printf(" - |");
        continue;
      }
      const double us = Median(times[q][l]);
      if (asked[q][l] < counts[q])
      {
        std::printf(" %.3g (%d) |", us, asked[q][l]);
      }
      else
      {
        std::printf(" %.3g |", us);
      }
      if (l > 0 && (fastest == 0 || us < fastest))
      {
        fastest = us;
        fastestId = l;
      }
    }
    const double ours = Median(times[q][0]);
    const int both = std::min(asked[q][0], asked[q][fastestId]);
    if (fastest > 0 && (q == AllHits || q == AlongLine || q == InBounds))
    {
      // Lists: VTK's hold other cells (bins' cells, a tolerance), so their sizes.
      double mine = 0, theirs = 0;
      for (int i = 0; i < both; ++i)
      {
        mine += answers[q][0][i];
        theirs += answers[q][fastestId][i];
      }
      std::printf(" %.2fx | cells a query %.1f, %s %.1f |\n", fastest / ours, mine / both,
        kinds[fastestId].Name.c_str(), theirs / both);
    }
    else if (fastest > 0)
    {
      int same = 0, oursRight = 0;
      for (int i = 0; i < both; ++i)
      {
        if (Same(static_cast<Kind>(q), answers[q][0][i], answers[q][fastestId][i], pr))
        {
          ++same;
        }
        else if (q == Closest)
        {
          // Where they differ, brute force says who found the closest.
          oursRight += Same(Closest, answers[q][0][i], BruteForceClosest(pd, pr.Points[i].X, s), pr) ? 1 : 0;
        }
      }
      std::printf(" %.2fx | %d/%d (%s)", fastest / ours, same, both, kinds[fastestId].Name.c_str());
      if (q == Closest && same < both)
      {
        std::printf("; of the others, ours is the drawn surface's (brute force) on %d", oursRight);
      }
      std::printf(" |\n");
    }
    else
    {
      std::printf(" no VTK locator | - |\n");
    }
  }
}

/// BuildLocator() and the first query of each kind after it: for ours each
/// on a fresh locator, best of 3 (the build time is the fastest of those
/// builds), for
/// VTK's (whose builds are slower, and BuildLocator builds what they query
/// but for vtkModifiedBSPTree's, made at its first query) one build, then
/// each kind's first query in turn.
void FirstQueryTable(const std::vector<LocatorKind>& kinds, vtkPolyData* pd, const Probes& pr)
{
  Scratch s;
  std::printf("\n| locator | BuildLocator ms (best) |");
  for (const char* name : kKindNames)
  {
    std::printf(" first %s ms |", name);
  }
  std::printf("\n|---|---:|");
  for (int q = 0; q < KindCount; ++q)
  {
    std::printf("---:|");
  }
  std::printf("\n");
  for (const auto& k : kinds)
  {
    // One untimed build: a process's first build of a kind pays for fresh
    // heap pages and the SMP pool's start.
    vtkAbstractCellLocator* warm = k.New();
    warm->SetDataSet(pd);
    warm->BuildLocator();
    warm->Delete();
    double build = 1e30;
    std::array<double, KindCount> first;
    first.fill(1e30);
    vtkAbstractCellLocator* loc = nullptr;
    for (int rep = 0; rep < (k.FreshPerKind ? 3 : 1); ++rep)
    {
      for (int q = 0; q < KindCount; ++q)
      {
        if (!k.Has[q])
        {
          continue;
        }
        if (!loc || k.FreshPerKind)
        {
          if (loc)
          {
            loc->Delete();
          }
          loc = k.New();
          loc->SetDataSet(pd);
          auto t0 = Clock::now();
          loc->BuildLocator();
          build = std::min(build, Seconds(t0, Clock::now()));
        }
        auto t1 = Clock::now();
        Ask(loc, static_cast<Kind>(q), pr, 0, s);
        first[q] = std::min(first[q], Seconds(t1, Clock::now()));
      }
    }
    loc->Delete();
    std::printf("| %s | %.1f |", k.Name.c_str(), 1e3 * build);
    for (int q = 0; q < KindCount; ++q)
    {
      if (k.Has[q])
      {
        std::printf(" %.3g |", 1e3 * first[q]);
      }
      else
      {
        std::printf(" - |");
      }
    }
    std::printf("\n");
  }
}
} // namespace

void RunLocatorQueries(const std::string& name, vtkPolyData* pd, int rounds, bool quick)
{
  const std::array<int, KindCount> counts = QueryCounts(pd->GetNumberOfCells(), quick);
  const Probes pr = MakeProbes(pd, *std::max_element(counts.begin(), counts.end()),
    *std::max_element(counts.begin(), counts.end()));
  std::printf("\n## %s: every query, %lld cells\n\nSteady microseconds a query (single thread, "
              "median of %d interleaved rounds); '-': not in VTK 9.1 for that locator. Points: 40%% on "
              "or within 1%% of the diagonal of the surface, 30%% in the bounds grown by half, 30%% "
              "1-3 diagonals away; radius and box half-side 2%% and 1%% of the diagonal; segments "
              "between points of the grown bounds; FindCell: half on the surface.\n\n",
    name.c_str(), static_cast<long long>(pd->GetNumberOfCells()), rounds);
  const std::vector<LocatorKind> kinds = Locators();
  SteadyTable(kinds, pd, pr, counts, rounds);
  FirstQueryTable(kinds, pd, pr);
  std::fflush(stdout);
}

} // namespace vtkrtBench
