// Scales and offsets across double's range: a mesh at 1e200, 1e-200, 1e307
// or offset by 1e200 answers every query as the same mesh at scale 1 does,
// exactly (same cell, t, point) when the scale is a power of two.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"

#include <algorithm>
#include <array>
#include <cmath>

using namespace locatortest;

namespace
{
void Map(const double p[3], double scale, const double offset[3], double out[3])
{
  for (int k = 0; k < 3; ++k)
  {
    out[k] = p[k] * scale + offset[k];
  }
}

struct LineAnswer
{
  int Hit = 0;
  double T = -1.0;
  double X[3] = { 0, 0, 0 };
  vtkIdType CellId = -1;
};

LineAnswer Intersect(vtkBVHCellLocator* loc, const double p1[3], const double p2[3], double tol)
{
  LineAnswer a;
  double pc[3];
  int sub;
  a.Hit = loc->IntersectWithLine(p1, p2, tol, a.T, a.X, pc, sub, a.CellId);
  return a;
}

struct PointAnswer
{
  double X[3] = { 0, 0, 0 };
  double Dist2 = -1.0;
  vtkIdType CellId = -1;
};

PointAnswer Closest(vtkBVHCellLocator* loc, const double q[3])
{
  PointAnswer a;
  int sub;
  loc->FindClosestPoint(q, a.X, a.CellId, sub, a.Dist2);
  return a;
}

/// Segments through the centroids of every 7th triangle (each must hit
/// that triangle's neighbourhood far from any edge), then random ones.
std::vector<Segment> TestSegments(vtkPolyData* pd, Random& rng)
{
  std::vector<Segment> segs;
  for (vtkIdType c = 0; c < pd->GetNumberOfCells(); c += 7)
  {
    vtkNew<vtkIdList> ids;
    pd->GetCellPoints(c, ids);
    double center[3] = { 0, 0, 0 };
    for (int i = 0; i < 3; ++i)
    {
      double p[3];
      pd->GetPoint(ids->GetId(i), p);
      for (int k = 0; k < 3; ++k)
      {
        center[k] += p[k] / 3.0;
      }
    }
    segs.push_back(SegmentThrough(pd, center, rng));
  }
  const std::vector<Segment> random = RandomSegments(pd, 150, rng);
  segs.insert(segs.end(), random.begin(), random.end());
  return segs;
}

constexpr double kTolerance = 0.02;

/// The queries and the answers at scale 1: the locator's, checked against
/// VTK's own cells.
struct Reference
{
  vtkSmartPointer<vtkPolyData> Mesh;
  vtkNew<vtkBVHCellLocator> Locator;
  std::vector<Segment> Segments;
  std::vector<std::array<double, 3>> Queries;
  std::vector<LineAnswer> Hits, TolHits;
  std::vector<PointAnswer> ClosestAnswers;
  int NumberOfHits = 0;

  explicit Reference(vtkPolyData* mesh)
    : Mesh(mesh)
  {
    Random rng(24);
    this->Segments = TestSegments(mesh, rng);
    for (int i = 0; i < 100; ++i)
    {
      this->Queries.push_back({ { rng.Next(-2, 2), rng.Next(-2, 2), rng.Next(-2, 2) } });
    }
    this->Locator->SetDataSet(mesh);
    this->Locator->BuildLocator();
    for (const auto& s : this->Segments)
    {
      this->Hits.push_back(Intersect(this->Locator, s.P1, s.P2, 0.0));
      this->TolHits.push_back(Intersect(this->Locator, s.P1, s.P2, kTolerance));
      const RefHit brute = BruteForceHit(mesh, s.P1, s.P2, 0.0);
      LT_CHECK(this->Hits.back().Hit == brute.Hit);
      LT_CHECK(!brute.Hit || std::abs(this->Hits.back().T - brute.T) < 1e-12);
      this->NumberOfHits += this->Hits.back().Hit;
    }
    LT_CHECK(this->NumberOfHits > 150);
    for (const auto& q : this->Queries)
    {
      this->ClosestAnswers.push_back(Closest(this->Locator, q.data()));
      vtkIdType bruteCell;
      const double d2 = BruteForceClosest(mesh, q.data(), bruteCell);
      LT_CHECK(std::abs(this->ClosestAnswers.back().Dist2 - d2) <= 1e-12 * (1.0 + d2));
    }
  }
};

struct Case
{
  double Scale;
  double Offset[3];
  bool Exact; ///< a power of two, no offset: every answer is the reference's, scaled
  const char* Name;
};

/// Largest coordinate difference of x from the reference's point mapped by
/// the case, in units of the case's scale.
double PointError(const double x[3], const double ref[3], const Case& c)
{
  double rx[3];
  Map(ref, c.Scale, c.Offset, rx);
  return std::max({ std::abs(x[0] - rx[0]), std::abs(x[1] - rx[1]), std::abs(x[2] - rx[2]) }) /
    c.Scale;
}

/// The mapped segments against the reference: same hits (and, exactly,
/// same cells along them and same hits with a tolerance).
void CheckSegments(const Case& c, vtkBVHCellLocator* loc, const Reference& ref)
{
  int sameHit = 0, sameCell = 0, sameTol = 0;
  for (size_t i = 0; i < ref.Segments.size(); ++i)
  {
    double p1[3], p2[3];
    Map(ref.Segments[i].P1, c.Scale, c.Offset, p1);
    Map(ref.Segments[i].P2, c.Scale, c.Offset, p2);
    if (c.Exact)
    {
      vtkNew<vtkIdList> cells, refCells;
      loc->FindCellsAlongLine(p1, p2, kTolerance * c.Scale, cells);
      ref.Locator->FindCellsAlongLine(ref.Segments[i].P1, ref.Segments[i].P2, kTolerance, refCells);
      LT_CHECK_MSG(ToVector(cells) == ToVector(refCells), c.Name << " cells along segment " << i);
    }
    const LineAnswer a = Intersect(loc, p1, p2, 0.0);
    const LineAnswer& r = ref.Hits[i];
    sameHit += a.Hit == r.Hit ? 1 : 0;
    if (!(a.Hit && r.Hit))
    {
      continue;
    }
    sameCell += a.CellId == r.CellId ? 1 : 0;
    const double xErr = PointError(a.X, r.X, c);
    if (c.Exact)
    {
      LT_CHECK_MSG(a.CellId == r.CellId && a.T == r.T && xErr == 0.0,
        c.Name << " segment " << i << ": t " << a.T << " vs " << r.T);
      const LineAnswer at = Intersect(loc, p1, p2, kTolerance * c.Scale);
      const LineAnswer& rt = ref.TolHits[i];
      sameTol += at.Hit == rt.Hit && at.CellId == rt.CellId && at.T == rt.T ? 1 : 0;
    }
    else
    {
      LT_CHECK_MSG(std::abs(a.T - r.T) < 1e-9 && xErr < 1e-9,
        c.Name << " segment " << i << ": t " << a.T << " vs " << r.T << ", x off by " << xErr);
    }
  }
  std::cout << c.Name << ": " << sameHit << "/" << ref.Segments.size()
            << " segments hit or miss alike, " << sameCell << "/" << ref.NumberOfHits
            << " hits on the same cell" << std::endl;
  LT_CHECK(sameHit == static_cast<int>(ref.Segments.size()));
  // Rounding the mapped points and ends may move a random ray across a
  // shared edge (never at a power of two).
  LT_CHECK(c.Exact ? sameCell == ref.NumberOfHits : sameCell >= ref.NumberOfHits * 98 / 100);
  LT_CHECK(!c.Exact || sameTol == ref.NumberOfHits);
}

/// The mapped closest-point queries against the reference.
void CheckClosestPoints(const Case& c, vtkBVHCellLocator* loc, const Reference& ref)
{
  int sameClosest = 0;
  for (size_t i = 0; i < ref.Queries.size(); ++i)
  {
    double q[3];
    Map(ref.Queries[i].data(), c.Scale, c.Offset, q);
    const PointAnswer a = Closest(loc, q);
    const PointAnswer& r = ref.ClosestAnswers[i];
    const double xErr = PointError(a.X, r.X, c);
    sameClosest += a.CellId == r.CellId ? 1 : 0;
    LT_CHECK_MSG(xErr < (c.Exact ? 0.0 : 1e-9) || xErr == 0.0,
      c.Name << " closest point " << i << " off by " << xErr);
    // The squared distance is a double too: inf above its range, 0 or
    // subnormal below.
    const double d2 = r.Dist2 * c.Scale * c.Scale;
    if (std::isnormal(d2))
    {
      LT_CHECK_MSG(std::abs(a.Dist2 - d2) <= (c.Exact ? 0.0 : 1e-9) * d2,
        c.Name << " dist2 " << a.Dist2 << " vs " << d2);
    }
    else
    {
      LT_CHECK_MSG(std::isinf(d2) ? std::isinf(a.Dist2) : a.Dist2 < 1e-300,
        c.Name << " dist2 " << a.Dist2 << " vs " << d2);
    }
  }
  std::cout << c.Name << ": " << sameClosest << "/" << ref.Queries.size()
            << " closest points on the same cell" << std::endl;
  LT_CHECK(!c.Exact || sameClosest == static_cast<int>(ref.Queries.size()));
}

/// A mesh at 1e-200 queried from 1e120 away: no double holds that in the
/// mesh's frame (1e320 mesh sizes), so no answer, and one error a query.
void CheckBeyondLocalFrame(vtkPolyData* base)
{
  const double zero[3] = { 0, 0, 0 };
  auto tiny = Transformed(base, 1e-200, zero);
  vtkNew<vtkBVHCellLocator> loc;
  loc->SetDataSet(tiny);
  loc->BuildLocator();
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(loc);
  const double far1[3] = { -1e120, 0.0, 0.0 }, far2[3] = { 1e120, 0.0, 0.0 };
  LT_CHECK(!Intersect(loc, far1, far2, 0.0).Hit);
  LT_CHECK(Closest(loc, far2).CellId < 0);
  LT_CHECK_MSG(catcher->Errors.size() == 2, catcher->Errors.size() << " errors (2)");
  LT_CHECK(catcher->Errors.empty() || catcher->Errors[0].find("1e300") != std::string::npos);
  // The same ray from 1e-190 away hits, silently.
  const double near1[3] = { -1e-190, 0.0, 0.0 }, near2[3] = { 1e-190, 0.0, 0.0 };
  LT_CHECK(Intersect(loc, near1, near2, 0.0).Hit);
  LT_CHECK(catcher->Errors.size() == 2 && catcher->Warnings.empty());
}
} // namespace

int TestRobustExtremeScales()
{
  auto base = MakeBumpySphere(20);
  const Reference ref(base);
  const Case cases[] = { { std::ldexp(1.0, 665), { 0, 0, 0 }, true, "2^665 (1e200)" },
    { std::ldexp(1.0, -665), { 0, 0, 0 }, true, "2^-665 (1e-200)" },
    { std::ldexp(1.0, 1021), { 0, 0, 0 }, true, "2^1021 (2e307)" },
    { std::ldexp(1.0, -960), { 0, 0, 0 }, true, "2^-960 (1e-289)" },
    { 1e200, { 0, 0, 0 }, false, "1e200" }, { 1e-200, { 0, 0, 0 }, false, "1e-200" },
    { 1e196, { 3e200, -2e200, 1e200 }, false, "1e196 at 1e200" },
    { 1e-204, { -1e-200, 2e-200, 0.0 }, false, "1e-204 at 1e-200" } };
  for (const Case& c : cases)
  {
    auto pd = Transformed(base, c.Scale, c.Offset);
    vtkNew<vtkBVHCellLocator> loc;
    loc->SetDataSet(pd);
    loc->BuildLocator();
    CheckSegments(c, loc, ref);
    CheckClosestPoints(c, loc, ref);
  }
  CheckBeyondLocalFrame(base);
  return 0;
}
