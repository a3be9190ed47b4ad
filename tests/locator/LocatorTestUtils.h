// Shared helpers for the locator tests: check macros, mesh generators, ray
// sets, brute-force references built from VTK's own cell tests, error
// capture so that provoked VTK errors do not reach the output, and the
// oracle checks of each query kind (defined in LocatorTestUtils.cxx).
#ifndef LocatorTestUtils_h
#define LocatorTestUtils_h

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataSet.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTriangle.h"
#include "vtkTriangleFilter.h"
#include "vtkCellType.h"

#include "vtkrtDataFile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

class vtkAbstractCellLocator;
class vtkBVHCellLocator;
class vtkCellLocator;
class vtkModifiedBSPTree;
class vtkStaticCellLocator;

namespace locatortest
{

inline int& Failures()
{
  static int failures = 0;
  return failures;
}

#define LT_CHECK(cond)                                                                             \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl;           \
      ++locatortest::Failures();                                                                   \
    }                                                                                              \
  } while (0)

#define LT_CHECK_MSG(cond, msg)                                                                    \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << " -- " << msg        \
                << std::endl;                                                                      \
      ++locatortest::Failures();                                                                   \
    }                                                                                              \
  } while (0)

/// Output window that counts VTK errors/warnings; a passing test prints none.
class CountingOutputWindow : public vtkOutputWindow
{
public:
  static CountingOutputWindow* New() { return new CountingOutputWindow; }
  void DisplayErrorText(const char* t) override
  {
    ++this->Errors;
    std::cerr << "VTK ERROR: " << t << std::endl;
  }
  void DisplayWarningText(const char* t) override
  {
    ++this->Warnings;
    std::cerr << "VTK WARNING: " << t << std::endl;
  }
  void DisplayGenericWarningText(const char* t) override { this->DisplayWarningText(t); }
  int Errors = 0;
  int Warnings = 0;
};

inline CountingOutputWindow* InstallOutputWindow()
{
  static vtkSmartPointer<CountingOutputWindow> w = vtkSmartPointer<CountingOutputWindow>::New();
  vtkOutputWindow::SetInstance(w);
  return w;
}

/// Records ErrorEvent / WarningEvent of one object (and keeps them off the
/// output).
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    const std::string text = data ? static_cast<const char*>(data) : "";
    if (event == vtkCommand::ErrorEvent)
    {
      this->Errors.push_back(text);
    }
    else
    {
      this->Warnings.push_back(text);
    }
  }
  void Watch(vtkObject* o)
  {
    o->AddObserver(vtkCommand::ErrorEvent, this);
    o->AddObserver(vtkCommand::WarningEvent, this);
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

/// Deterministic uniform numbers.
class Random
{
public:
  explicit Random(int seed) { this->Seq->SetSeed(seed); }
  double Next(double lo = 0.0, double hi = 1.0)
  {
    const double v = this->Seq->GetRangeValue(lo, hi);
    this->Seq->Next();
    return v;
  }

private:
  vtkNew<vtkMinimalStandardRandomSequence> Seq;
};

/// A closed triangulated sphere with deterministic radial bumps (~2*res^2
/// triangles): irregular enough to exercise the tree, cheap to generate.
inline vtkSmartPointer<vtkPolyData> MakeBumpySphere(int res, double radius = 1.0)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(res);
  sphere->SetPhiResolution(res);
  sphere->SetRadius(radius);
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
    const double s = 1.0 + 0.15 * std::sin(7.0 * p[0] / radius) * std::cos(5.0 * p[1] / radius) +
      0.05 * std::sin(13.0 * p[2] / radius);
    pts->SetPoint(i, p[0] * s, p[1] * s, p[2] * s);
  }
  pd->SetPoints(pts);
  pd->GetPointData()->Initialize();
  return pd;
}

/// The Stanford bunny, bunny.ply from $VTKRT_DATA_DIR or the project's
/// data/ (vtkrtDataFile.h); a failed check and nullptr when neither has it.
inline vtkSmartPointer<vtkPolyData> LoadBunny()
{
  const std::string path = vtkrtDataFile::Find("bunny.ply");
  LT_CHECK_MSG(!path.empty(), vtkrtDataFile::NotFound("bunny.ply"));
  if (path.empty())
  {
    return nullptr;
  }
  std::cout << "bunny: " << path << std::endl;
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->DeepCopy(reader->GetOutput());
  LT_CHECK_MSG(pd->GetNumberOfCells() > 0, path << " holds no cells");
  return pd->GetNumberOfCells() > 0 ? pd : nullptr;
}

inline double Diagonal(vtkDataSet* ds)
{
  double b[6];
  ds->GetBounds(b);
  return std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
}

struct Segment
{
  double P1[3];
  double P2[3];
  bool Aimed = false; ///< aimed exactly at a vertex or an edge point
};

/// Random segments crossing the (grown) bounds.
inline std::vector<Segment> RandomSegments(vtkDataSet* ds, int count, Random& rng)
{
  double b[6];
  ds->GetBounds(b);
  std::vector<Segment> out;
  for (int i = 0; i < count; ++i)
  {
    Segment s;
    for (int k = 0; k < 3; ++k)
    {
      const double c = 0.5 * (b[2 * k] + b[2 * k + 1]);
      const double h = 0.75 * (b[2 * k + 1] - b[2 * k]) + 1e-12;
      s.P1[k] = rng.Next(c - h, c + h);
      s.P2[k] = rng.Next(c - h, c + h);
    }
    out.push_back(s);
  }
  return out;
}

/// Segments from a random outside point through `target` (ending well past it).
inline Segment SegmentThrough(vtkDataSet* ds, const double target[3], Random& rng)
{
  double b[6];
  ds->GetBounds(b);
  const double diag = Diagonal(ds);
  Segment s;
  double dir[3] = { rng.Next(-1, 1), rng.Next(-1, 1), rng.Next(-1, 1) };
  vtkMath::Normalize(dir);
  for (int k = 0; k < 3; ++k)
  {
    s.P1[k] = target[k] - 1.5 * diag * dir[k];
    s.P2[k] = target[k] + 0.5 * diag * dir[k];
  }
  s.Aimed = true;
  return s;
}

/// Interior edges (shared by exactly two triangles) and interior vertices of
/// a triangle mesh: aiming there must hit, whatever the mesh's open borders.
inline void InteriorEdgesAndVertices(vtkPolyData* pd, std::vector<std::pair<vtkIdType, vtkIdType>>& edges,
  std::vector<vtkIdType>& vertices)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> count;
  vtkCellArray* polys = pd->GetPolys();
  vtkNew<vtkIdList> ids;
  polys->InitTraversal();
  while (polys->GetNextCell(ids))
  {
    const vtkIdType n = ids->GetNumberOfIds();
    for (vtkIdType k = 0; k < n; ++k)
    {
      vtkIdType a = ids->GetId(k), b = ids->GetId((k + 1) % n);
      if (a > b)
      {
        std::swap(a, b);
      }
      ++count[{ a, b }];
    }
  }
  std::set<vtkIdType> boundary;
  for (const auto& e : count)
  {
    if (e.second == 2)
    {
      edges.push_back(e.first);
    }
    else
    {
      boundary.insert(e.first.first);
      boundary.insert(e.first.second);
    }
  }
  std::set<vtkIdType> used;
  for (const auto& e : edges)
  {
    used.insert(e.first);
    used.insert(e.second);
  }
  for (vtkIdType v : used)
  {
    if (!boundary.count(v))
    {
      vertices.push_back(v);
    }
  }
}

/// Nearest hit of the segment over every cell, by the cells' own
/// IntersectWithLine with tolerance tol (brute force, no locator).
struct RefHit
{
  bool Hit = false;
  double T = 0.0;
  vtkIdType CellId = -1;
  double X[3] = { 0, 0, 0 };
};

/// vtkTriangleStrip::IntersectWithLine returns its first triangle hit, not
/// the nearest: strips are tested triangle by triangle here.
inline int CellIntersect(vtkGenericCell* cell, const double p1[3], const double p2[3], double tol,
  double& t, double x[3], double pc[3], int& sub)
{
  if (cell->GetCellType() != VTK_TRIANGLE_STRIP)
  {
    return cell->IntersectWithLine(p1, p2, tol, t, x, pc, sub);
  }
  vtkNew<vtkTriangle> tri;
  int found = 0;
  for (vtkIdType k = 0; k + 2 < cell->GetNumberOfPoints(); ++k)
  {
    for (int i = 0; i < 3; ++i)
    {
      tri->GetPoints()->SetPoint(i, cell->GetPoints()->GetPoint(k + i));
    }
    double tt, xx[3], pp[3];
    int ss;
    if (tri->IntersectWithLine(p1, p2, tol, tt, xx, pp, ss) && (!found || tt < t))
    {
      found = 1;
      t = tt;
      std::copy(xx, xx + 3, x);
      std::copy(pp, pp + 3, pc);
      sub = static_cast<int>(k);
    }
  }
  return found;
}

inline RefHit BruteForceHit(vtkDataSet* ds, const double p1[3], const double p2[3], double tol)
{
  RefHit best;
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    ds->GetCell(c, cell);
    double t, x[3], pc[3];
    int sub;
    if (CellIntersect(cell, p1, p2, tol, t, x, pc, sub) && t >= 0.0 && t <= 1.0 &&
      (!best.Hit || t < best.T))
    {
      best.Hit = true;
      best.T = t;
      best.CellId = c;
      std::copy(x, x + 3, best.X);
    }
  }
  return best;
}

/// Every cell the segment meets within tol, with its nearest t.
inline std::map<vtkIdType, double> BruteForceAllHits(
  vtkDataSet* ds, const double p1[3], const double p2[3], double tol)
{
  std::map<vtkIdType, double> hits;
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    ds->GetCell(c, cell);
    double t, x[3], pc[3];
    int sub;
    if (CellIntersect(cell, p1, p2, tol, t, x, pc, sub) && t >= 0.0 && t <= 1.0)
    {
      hits[c] = t;
    }
  }
  return hits;
}

/// The cell holds cell cellId's point ids and exact coordinates.
inline bool SameCellPoints(vtkDataSet* ds, vtkIdType cellId, vtkGenericCell* cell)
{
  vtkNew<vtkIdList> ids;
  ds->GetCellPoints(cellId, ids);
  if (ids->GetNumberOfIds() != cell->GetNumberOfPoints())
  {
    return false;
  }
  for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
  {
    if (ids->GetId(i) != cell->GetPointId(i))
    {
      return false;
    }
    double p[3], q[3];
    ds->GetPoint(ids->GetId(i), p);
    cell->GetPoints()->GetPoint(i, q);
    if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
    {
      return false;
    }
  }
  return true;
}

/// Squared distance from x to cell c (its EvaluatePosition).
inline double DistanceToCell2(vtkDataSet* ds, vtkIdType c, const double x[3])
{
  vtkNew<vtkGenericCell> cell;
  ds->GetCell(c, cell);
  double cp[3], pc[3], d2;
  int sub;
  std::vector<double> w(static_cast<size_t>(cell->GetNumberOfPoints()) + 1);
  double xx[3] = { x[0], x[1], x[2] };
  if (cell->EvaluatePosition(xx, cp, sub, pc, d2, w.data()) < 0)
  {
    return VTK_DOUBLE_MAX;
  }
  return d2;
}

/// Closest cell by brute force (min over cells of EvaluatePosition distance).
inline double BruteForceClosest(vtkDataSet* ds, const double x[3], vtkIdType& cellId)
{
  double best = VTK_DOUBLE_MAX;
  cellId = -1;
  vtkNew<vtkGenericCell> cell;
  std::vector<double> w(static_cast<size_t>(ds->GetMaxCellSize()) + 1);
  double xx[3] = { x[0], x[1], x[2] };
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    ds->GetCell(c, cell);
    double cp[3], pc[3], d2;
    int sub;
    if (cell->EvaluatePosition(xx, cp, sub, pc, d2, w.data()) >= 0 && d2 < best)
    {
      best = d2;
      cellId = c;
    }
  }
  return best;
}

/// Cells whose bounds overlap bbox (closed intervals).
inline std::vector<vtkIdType> BruteForceCellsInBox(vtkDataSet* ds, const double bbox[6])
{
  std::vector<vtkIdType> out;
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    double b[6];
    ds->GetCellBounds(c, b);
    if (b[0] <= bbox[1] && bbox[0] <= b[1] && b[2] <= bbox[3] && bbox[2] <= b[3] &&
      b[4] <= bbox[5] && bbox[4] <= b[5])
    {
      out.push_back(c);
    }
  }
  return out;
}

/// Whether segment p1->p2 meets box b (slab clipping in double).
inline bool SegmentMeetsBox(const double p1[3], const double p2[3], const double b[6])
{
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k)
  {
    const double d = p2[k] - p1[k];
    if (d == 0.0)
    {
      if (p1[k] < b[2 * k] || p1[k] > b[2 * k + 1])
      {
        return false;
      }
      continue;
    }
    double a = (b[2 * k] - p1[k]) / d, c = (b[2 * k + 1] - p1[k]) / d;
    if (a > c)
    {
      std::swap(a, c);
    }
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
    if (t0 > t1)
    {
      return false;
    }
  }
  return true;
}

/// Cells whose bounds, grown by tol, segment p1->p2 meets.
inline std::vector<vtkIdType> BruteForceCellsAlongLine(
  vtkDataSet* ds, const double p1[3], const double p2[3], double tol)
{
  std::vector<vtkIdType> out;
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    double cb[6];
    ds->GetCellBounds(c, cb);
    for (int k = 0; k < 3; ++k)
    {
      cb[2 * k] -= tol;
      cb[2 * k + 1] += tol;
    }
    if (SegmentMeetsBox(p1, p2, cb))
    {
      out.push_back(c);
    }
  }
  return out;
}

/// As VTK 9.1's locators answer FindCell: the lowest-id cell whose bounds
/// hold x and whose EvaluatePosition says inside (-1 if none); `cell` and
/// `w` are scratch.
inline vtkIdType BruteForceFindCell(vtkDataSet* ds, const double x[3], vtkGenericCell* cell, double* w)
{
  double xx[3] = { x[0], x[1], x[2] };
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
  {
    ds->GetCell(c, cell);
    const double* b = cell->GetBounds();
    double cp[3], pc[3], d2;
    int sub;
    if (xx[0] >= b[0] && xx[0] <= b[1] && xx[1] >= b[2] && xx[1] <= b[3] && xx[2] >= b[4] &&
      xx[2] <= b[5] && cell->EvaluatePosition(xx, cp, sub, pc, d2, w) == 1)
    {
      return c;
    }
  }
  return -1;
}

inline std::vector<vtkIdType> ToVector(vtkIdList* ids)
{
  std::vector<vtkIdType> v(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
  return v;
}

inline bool IsSubset(std::vector<vtkIdType> a, std::vector<vtkIdType> b)
{
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return std::includes(b.begin(), b.end(), a.begin(), a.end());
}

/// Nearest-hit queries: ours must agree with the brute-force reference on
/// every segment (including segments aimed exactly at shared vertices and
/// edges); VTK's locators are counted, not asserted.
void CheckIntersectWithLine(vtkDataSet* ds, vtkBVHCellLocator* bvh,
  std::vector<vtkAbstractCellLocator*> peers, const std::vector<Segment>& segments,
  double refTol, const char* name);

/// Closest point (all overloads) against brute force (or, on big meshes,
/// vtkStaticCellLocator) and vtkCellLocator.
void CheckClosestPoint(vtkDataSet* ds, vtkBVHCellLocator* bvh, vtkStaticCellLocator* st,
  vtkCellLocator* cl, int count, bool bruteForce, const char* name);

/// Cells within random boxes and along random segments: equal to brute force
/// when cell boxes are the primitives' boxes (else a subset), and a subset of
/// vtkStaticCellLocator's lists.
void CheckBoxAndLineLists(vtkDataSet* ds, vtkBVHCellLocator* bvh, vtkStaticCellLocator* st,
  bool cellBoxesArePrimitiveBoxes, const char* name);

/// All hits along a segment: same cells as brute force, sorted along it.
void CheckAllHits(vtkDataSet* ds, vtkBVHCellLocator* bvh, vtkModifiedBSPTree* bsp, double refTol,
  const char* name);

/// Copy of pd with double points mapped by p -> p * scale + offset.
vtkSmartPointer<vtkPolyData> Transformed(vtkPolyData* pd, double scale, const double offset[3]);

inline int Finish(const char* name)
{
  if (Failures() == 0)
  {
    std::cout << name << ": passed" << std::endl;
    return EXIT_SUCCESS;
  }
  std::cout << name << ": " << Failures() << " check(s) failed" << std::endl;
  return EXIT_FAILURE;
}

} // namespace locatortest

#endif
