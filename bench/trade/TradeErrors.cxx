#include "TradeErrors.h"

#include "vtkCellArray.h"
#include "vtkCellPicker.h"
#include "vtkGenericCell.h"
#include "vtkImageDifference.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace vtkrtTrade
{
namespace
{
/// Distance from each sample to the locator's surface (parallel).
std::vector<double> DistancesTo(vtkBVHCellLocator* locator, const std::vector<Point>& samples)
{
  std::vector<double> d(samples.size(), kNaN);
  vtkSMPThreadLocalObject<vtkGenericCell> cells;
  vtkSMPTools::For(0, static_cast<vtkIdType>(samples.size()), [&](vtkIdType begin, vtkIdType end) {
    vtkGenericCell* cell = cells.Local();
    for (vtkIdType k = begin; k < end; ++k)
    {
      double closest[3], dist2;
      vtkIdType cellId;
      int subId;
      locator->FindClosestPoint(samples[k].data(), closest, cell, cellId, subId, dist2);
      d[k] = cellId >= 0 ? std::sqrt(dist2) : kNaN;
    }
  });
  return d;
}
}

double ImageRMSE(vtkImageData* a, vtkImageData* b)
{
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  const vtkIdType n = a->GetNumberOfPoints() * a->GetNumberOfScalarComponents();
  if (n != b->GetNumberOfPoints() * b->GetNumberOfScalarComponents())
  {
    return kNaN;
  }
  double sum = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double d = double(pa[i]) - double(pb[i]);
    sum += d * d;
  }
  return std::sqrt(sum / std::max<vtkIdType>(1, n));
}

double ImageDifference(vtkImageData* a, vtkImageData* b)
{
  vtkNew<vtkImageDifference> diff;
  diff->SetInputData(a);
  diff->SetImageData(b);
  diff->SetThreshold(16);
  diff->AllowShiftOff();
  diff->AveragingOn();
  diff->Update();
  return diff->GetThresholdedError();
}

DepthError CompareDepth(const Stage& ref, const Stage& cand)
{
  DepthError e;
  long both = 0, either = 0, one = 0;
  double sum = 0.0;
  for (int j = 0; j < ref.Height; ++j)
  {
    for (int i = 0; i < ref.Width; ++i)
    {
      Point a, b;
      const bool ha = ref.Unproject(i, j, a);
      const bool hb = cand.Unproject(i, j, b);
      either += (ha || hb) ? 1 : 0;
      one += (ha != hb) ? 1 : 0;
      if (ha && hb)
      {
        ++both;
        sum += std::sqrt(vtkMath::Distance2BetweenPoints(a.data(), b.data()));
      }
    }
  }
  e.Mean = both ? sum / both : kNaN;
  e.Coverage = either ? double(one) / either : 0.0;
  return e;
}

Pixels PickPixels(const Stage& ref, int grid)
{
  int lo[2] = { ref.Width, ref.Height }, hi[2] = { -1, -1 };
  for (int j = 0; j < ref.Height; ++j)
  {
    for (int i = 0; i < ref.Width; ++i)
    {
      if (ref.Depth[static_cast<size_t>(j) * ref.Width + i] < 1.0f)
      {
        lo[0] = std::min(lo[0], i);
        lo[1] = std::min(lo[1], j);
        hi[0] = std::max(hi[0], i);
        hi[1] = std::max(hi[1], j);
      }
    }
  }
  Pixels pixels;
  if (hi[0] < 0)
  {
    return pixels;
  }
  for (int b = 0; b < grid; ++b)
  {
    for (int a = 0; a < grid; ++a)
    {
      const int i = lo[0] + static_cast<int>((a + 0.5) / grid * (hi[0] - lo[0] + 1));
      const int j = lo[1] + static_cast<int>((b + 0.5) / grid * (hi[1] - lo[1] + 1));
      pixels.push_back({ { i + 0.5, j + 0.5 } });
    }
  }
  return pixels;
}

Picks PickWithPicker(const Stage& st, const Pixels& pixels, vtkAbstractCellLocator* locator)
{
  vtkNew<vtkCellPicker> picker;
  if (locator)
  {
    picker->AddLocator(locator);
  }
  Picks p;
  p.Hit.resize(pixels.size());
  p.X.resize(pixels.size());
  p.CellId.assign(pixels.size(), -1);
  const auto t0 = Clock::now();
  for (size_t k = 0; k < pixels.size(); ++k)
  {
    p.Hit[k] = picker->Pick(pixels[k][0], pixels[k][1], 0.0, st.Renderer) != 0;
    if (p.Hit[k])
    {
      double x[3];
      picker->GetPickPosition(x);
      p.CellId[k] = picker->GetCellId();
      for (int c = 0; c < 3; ++c)
      {
        p.X[k][c] = x[c] - st.Offset[c];
      }
    }
  }
  p.SecondsPerPick = pixels.empty() ? kNaN : Seconds(t0, Clock::now()) / pixels.size();
  return p;
}

Picks PickFromDepth(const Stage& st, const Pixels& pixels)
{
  Picks p;
  p.Hit.resize(pixels.size());
  p.X.resize(pixels.size());
  for (size_t k = 0; k < pixels.size(); ++k)
  {
    p.Hit[k] = st.Unproject(static_cast<int>(pixels[k][0]), static_cast<int>(pixels[k][1]), p.X[k]);
  }
  return p;
}

PickError ComparePicks(const Picks& ref, const Picks& cand)
{
  PickError e;
  long both = 0, either = 0, one = 0;
  double sum = 0.0, mx = 0.0;
  for (size_t k = 0; k < ref.Hit.size() && k < cand.Hit.size(); ++k)
  {
    either += (ref.Hit[k] || cand.Hit[k]) ? 1 : 0;
    one += (ref.Hit[k] != cand.Hit[k]) ? 1 : 0;
    if (ref.Hit[k] && cand.Hit[k])
    {
      ++both;
      const double d = std::sqrt(vtkMath::Distance2BetweenPoints(ref.X[k].data(), cand.X[k].data()));
      sum += d;
      mx = std::max(mx, d);
    }
  }
  if (both)
  {
    e.Mean = sum / both;
    e.Max = mx;
  }
  e.Miss = either ? double(one) / either : 0.0;
  return e;
}

std::vector<Point> SampleSurface(vtkPolyData* mesh, int count, unsigned seed)
{
  std::vector<std::array<vtkIdType, 3>> tris;
  std::vector<double> cumulative;
  double total = 0.0;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType npts;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    if (npts != 3)
    {
      continue;
    }
    double a[3], b[3], c[3], u[3], v[3], n[3];
    mesh->GetPoint(ids[0], a);
    mesh->GetPoint(ids[1], b);
    mesh->GetPoint(ids[2], c);
    vtkMath::Subtract(b, a, u);
    vtkMath::Subtract(c, a, v);
    vtkMath::Cross(u, v, n);
    total += 0.5 * vtkMath::Norm(n);
    tris.push_back({ { ids[0], ids[1], ids[2] } });
    cumulative.push_back(total);
  }
  std::vector<Point> samples;
  if (tris.empty() || total <= 0.0)
  {
    return samples;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  samples.reserve(count);
  for (int s = 0; s < count; ++s)
  {
    const double r = uni(rng) * total;
    const size_t t = std::min(tris.size() - 1,
      static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()));
    double a[3], b[3], c[3];
    mesh->GetPoint(tris[t][0], a);
    mesh->GetPoint(tris[t][1], b);
    mesh->GetPoint(tris[t][2], c);
    double r1 = std::sqrt(uni(rng)), r2 = uni(rng);
    const double wa = 1.0 - r1, wb = r1 * (1.0 - r2), wc = r1 * r2;
    samples.push_back({ { wa * a[0] + wb * b[0] + wc * c[0], wa * a[1] + wb * b[1] + wc * c[1],
      wa * a[2] + wb * b[2] + wc * c[2] } });
  }
  return samples;
}

GeomError SurfaceDistance(vtkBVHCellLocator* a, const std::vector<Point>& samplesA,
  vtkBVHCellLocator* b, const std::vector<Point>& samplesB)
{
  std::vector<double> d = DistancesTo(b, samplesA);
  std::vector<double> back = DistancesTo(a, samplesB);
  d.insert(d.end(), back.begin(), back.end());
  GeomError e;
  double sum = 0.0, mx = 0.0;
  long n = 0;
  for (double v : d)
  {
    if (std::isfinite(v))
    {
      sum += v;
      mx = std::max(mx, v);
      ++n;
    }
  }
  if (n)
  {
    e.Mean = sum / n;
    e.Max = mx;
  }
  return e;
}
}
