// Helpers shared by the filters tests: checks, an error catcher, a walk over
// a triangle mesh's faces, test inputs (a surface-less polydata, the real
// meshes of data/), OpenMesh's verdict on a mesh, and sampled surface distances.
#ifndef vtkrtFiltersTestUtilities_h
#define vtkrtFiltersTestUtilities_h

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkGenericCell.h"
#include "vtkIdTypeArray.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"
#include "vtkStaticCellLocator.h"
#include "vtkTriangle.h"
#include "vtksys/SystemTools.hxx"

#include "vtkrtDataFile.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace vtkrt_test
{

inline int& Failures()
{
  static int failures = 0;
  return failures;
}

#define VTKRT_CHECK(cond, what)                                                                    \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cout << "FAILED " << __FILE__ << ":" << __LINE__ << ": " << #cond << " -- " << what     \
                << std::endl;                                                                      \
      ++vtkrt_test::Failures();                                                                    \
    }                                                                                              \
  } while (0)

// Collects VTK errors and warnings from an algorithm and its executive so
// that tests provoking them on purpose print nothing.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings) +=
      data ? static_cast<const char*>(data) : "";
  }
  void Watch(vtkAlgorithm* algorithm)
  {
    algorithm->AddObserver(vtkCommand::ErrorEvent, this);
    algorithm->AddObserver(vtkCommand::WarningEvent, this);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this);
    algorithm->GetExecutive()->AddObserver(vtkCommand::WarningEvent, this);
  }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }
  std::string Errors;
  std::string Warnings;
};

inline vtkIdType FieldCount(vtkPolyData* pd, const char* name)
{
  auto* a = vtkIdTypeArray::SafeDownCast(pd->GetFieldData()->GetAbstractArray(name));
  return a && a->GetNumberOfValues() == 1 ? a->GetValue(0) : -1;
}

// Calls visit(p, normal) for each face of a triangle mesh: its corners and
// its (not normalised) normal.
template <class Visit>
void ForEachTriangle(vtkPolyData* pd, Visit&& visit)
{
  auto iter = vtk::TakeSmartPointer(pd->GetPolys()->NewIterator());
  vtkIdType n;
  const vtkIdType* ids;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    iter->GetCurrentCell(n, ids);
    double p[3][3], normal[3];
    for (int k = 0; k < 3; ++k)
    {
      pd->GetPoint(ids[k], p[k]);
    }
    vtkTriangle::ComputeNormalDirection(p[0], p[1], p[2], normal);
    visit(p, normal);
  }
}

// Two points joined by one line: points but no surface, which the filters refuse.
inline vtkSmartPointer<vtkPolyData> LinesOnly()
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, 0);
  pts->InsertNextPoint(1, 0, 0);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[] = { 0, 1 };
  lines->InsertNextCell(2, line);
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetLines(lines);
  return pd;
}

// A real mesh (.ply or .obj) by file name from $VTKRT_DATA_DIR or the
// project's data/ (vtkrtDataFile.h); a failed check and null when neither
// folder holds it.
inline vtkSmartPointer<vtkPolyData> ReadDataMesh(const std::string& file, const char* name)
{
  const std::string path = vtkrtDataFile::Find(file);
  if (path.empty())
  {
    VTKRT_CHECK(false, name << ": " << vtkrtDataFile::NotFound(file));
    return nullptr;
  }
  std::cout << name << ": " << path << std::endl;
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path));
  vtkSmartPointer<vtkPolyDataAlgorithm> reader;
  if (ext == ".ply")
  {
    auto ply = vtkSmartPointer<vtkPLYReader>::New();
    ply->SetFileName(path.c_str());
    reader = ply;
  }
  else if (ext == ".obj")
  {
    auto obj = vtkSmartPointer<vtkOBJReader>::New();
    obj->SetFileName(path.c_str());
    reader = obj;
  }
  else
  {
    VTKRT_CHECK(false, name << ": no reader for " << path);
    return nullptr;
  }
  reader->Update();
  return reader->GetOutput();
}

using CheckMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// OpenMesh's own verdict on a triangle mesh, built independently of the filters.
struct OpenMeshVerdict
{
  size_t RejectedFaces = 0;
  size_t BoundaryHalfedges = 0;
  size_t NonManifoldVertices = 0;
  size_t Vertices = 0, Edges = 0, Faces = 0;
  bool ClosedManifold() const
  {
    return RejectedFaces == 0 && BoundaryHalfedges == 0 && NonManifoldVertices == 0 && Faces > 0;
  }
  long EulerCharacteristic() const
  {
    return static_cast<long>(Vertices) - static_cast<long>(Edges) + static_cast<long>(Faces);
  }
};

inline OpenMeshVerdict JudgeWithOpenMesh(vtkPolyData* pd)
{
  OpenMeshVerdict verdict;
  const bool wasEnabled = omerr().is_enabled();
  omerr().disable();
  CheckMesh mesh;
  std::vector<CheckMesh::VertexHandle> vh;
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    vh.push_back(mesh.add_vertex(CheckMesh::Point(
      static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]))));
  }
  auto iter = vtk::TakeSmartPointer(pd->GetPolys()->NewIterator());
  vtkIdType n;
  const vtkIdType* ids;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    iter->GetCurrentCell(n, ids);
    if (n != 3 || !mesh.add_face(vh[ids[0]], vh[ids[1]], vh[ids[2]]).is_valid())
    {
      ++verdict.RejectedFaces;
    }
  }
  for (auto h : mesh.halfedges())
  {
    verdict.BoundaryHalfedges += mesh.is_boundary(h) ? 1 : 0;
  }
  for (auto v : mesh.vertices())
  {
    verdict.NonManifoldVertices += mesh.is_manifold(v) ? 0 : 1;
  }
  // Isolated vertices are not part of the surface.
  for (auto v : mesh.vertices())
  {
    verdict.Vertices += mesh.is_isolated(v) ? 0 : 1;
  }
  verdict.Edges = mesh.n_edges();
  verdict.Faces = mesh.n_faces();
  if (wasEnabled)
  {
    omerr().enable();
  }
  return verdict;
}

// Area-weighted random points on a triangle mesh, plus its vertices.
inline vtkSmartPointer<vtkPoints> SampleSurface(vtkPolyData* pd, vtkIdType count, int seed)
{
  auto samples = vtkSmartPointer<vtkPoints>::New();
  samples->SetDataTypeToDouble();
  samples->DeepCopy(pd->GetPoints());
  std::vector<double> cumulative;
  std::vector<std::array<vtkIdType, 3>> tris;
  double total = 0.0;
  auto iter = vtk::TakeSmartPointer(pd->GetPolys()->NewIterator());
  vtkIdType n;
  const vtkIdType* ids;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    iter->GetCurrentCell(n, ids);
    if (n != 3)
    {
      continue;
    }
    double a[3], b[3], c[3], u[3], v[3], w[3];
    pd->GetPoint(ids[0], a);
    pd->GetPoint(ids[1], b);
    pd->GetPoint(ids[2], c);
    vtkMath::Subtract(b, a, u);
    vtkMath::Subtract(c, a, v);
    vtkMath::Cross(u, v, w);
    total += 0.5 * vtkMath::Norm(w);
    cumulative.push_back(total);
    tris.push_back({ ids[0], ids[1], ids[2] });
  }
  if (tris.empty())
  {
    return samples;
  }
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(seed);
  for (vtkIdType s = 0; s < count; ++s)
  {
    const double pick = random->GetNextRangeValue(0.0, total);
    size_t t = std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin();
    t = std::min(t, tris.size() - 1);
    double r1 = random->GetNextRangeValue(0.0, 1.0);
    double r2 = random->GetNextRangeValue(0.0, 1.0);
    if (r1 + r2 > 1.0)
    {
      r1 = 1.0 - r1;
      r2 = 1.0 - r2;
    }
    double a[3], b[3], c[3], p[3];
    pd->GetPoint(tris[t][0], a);
    pd->GetPoint(tris[t][1], b);
    pd->GetPoint(tris[t][2], c);
    for (int k = 0; k < 3; ++k)
    {
      p[k] = a[k] + r1 * (b[k] - a[k]) + r2 * (c[k] - a[k]);
    }
    samples->InsertNextPoint(p);
  }
  return samples;
}

struct Distances
{
  double Max = 0.0;
  double Mean = 0.0;
};

// Distances from samples of `from` (its vertices and `count` random surface
// points) to the surface `to`.
inline Distances SurfaceDistance(vtkPolyData* from, vtkPolyData* to, vtkIdType count, int seed)
{
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(to);
  locator->BuildLocator();
  auto samples = SampleSurface(from, count, seed);
  vtkNew<vtkGenericCell> cell;
  Distances d;
  for (vtkIdType i = 0; i < samples->GetNumberOfPoints(); ++i)
  {
    double p[3], closest[3], dist2;
    vtkIdType cellId;
    int subId;
    samples->GetPoint(i, p);
    locator->FindClosestPoint(p, closest, cell, cellId, subId, dist2);
    const double dist = std::sqrt(dist2);
    d.Max = std::max(d.Max, dist);
    d.Mean += dist;
  }
  d.Mean /= std::max<vtkIdType>(1, samples->GetNumberOfPoints());
  return d;
}

inline double BoundsDiagonal(vtkPolyData* pd)
{
  return pd->GetLength();
}

} // namespace vtkrt_test

#endif
