#include "vtkOpenMeshDecimation.h"

#include "vtkOpenMeshDecimationModules.h"
#include "vtkOpenMeshInternals.h"

#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkOpenMeshDecimation);

namespace
{
using Mesh = vtkrt_filters::OpenMeshTriMesh;
using vtkrt_filters::Triangle;
using vtkrt_filters::TriangleSoup;
using vtkrt_filters::decimation::DecimationLimits;

// The halfedge mesh of the input's faces, with the input ids of its vertices
// and faces, and the faces it could not hold.
struct HalfedgeMesh
{
  Mesh Halfedges;
  OpenMesh::VPropHandleT<vtkIdType> InputPointId;
  OpenMesh::FPropHandleT<vtkIdType> InputCellId;
  std::vector<Mesh::VertexHandle> Vertex; // input point id -> vertex, for used points
  std::vector<vtkIdType> PassedThrough;   // soup indices of faces OpenMesh cannot hold
  vtkIdType NumberOfDegenerateFaces = 0;
};

// 1 for each input point a triangle uses.
std::vector<unsigned char> UsedPoints(const TriangleSoup& soup, vtkIdType numPoints)
{
  std::vector<unsigned char> used(numPoints, 0);
  for (const Triangle& tri : soup.Triangles)
  {
    for (vtkIdType id : tri)
    {
      used[id] = 1;
    }
  }
  return used;
}

vtkIdType CountNonFinitePoints(vtkPoints* points, const std::vector<unsigned char>& used)
{
  const vtkIdType numPoints = static_cast<vtkIdType>(used.size());
  std::vector<unsigned char> nonFinite(numPoints, 0);
  vtkSMPTools::For(0, numPoints,
    [&](vtkIdType begin, vtkIdType end)
    {
      double p[3];
      for (vtkIdType i = begin; i < end; ++i)
      {
        points->GetPoint(i, p);
        nonFinite[i] = used[i] && !vtkrt_filters::IsFinite(p);
      }
    });
  return static_cast<vtkIdType>(std::count(nonFinite.begin(), nonFinite.end(), 1));
}

// The used points as vertices, in input order, then the triangles as faces;
// degenerate triangles are dropped, those OpenMesh refuses kept aside.
void BuildHalfedgeMesh(vtkPoints* points, const std::vector<unsigned char>& used,
  const TriangleSoup& soup, HalfedgeMesh& hm)
{
  Mesh& mesh = hm.Halfedges;
  mesh.add_property(hm.InputPointId);
  mesh.add_property(hm.InputCellId);
  const vtkIdType numPoints = static_cast<vtkIdType>(used.size());
  hm.Vertex.resize(numPoints);
  for (vtkIdType i = 0; i < numPoints; ++i)
  {
    if (used[i])
    {
      double p[3];
      points->GetPoint(i, p);
      hm.Vertex[i] = mesh.add_vertex(Mesh::Point(p[0], p[1], p[2]));
      mesh.property(hm.InputPointId, hm.Vertex[i]) = i;
    }
  }
  const vtkIdType numTris = static_cast<vtkIdType>(soup.Triangles.size());
  for (vtkIdType t = 0; t < numTris; ++t)
  {
    const Triangle& tri = soup.Triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
    {
      ++hm.NumberOfDegenerateFaces;
      continue;
    }
    const Mesh::FaceHandle fh =
      mesh.add_face(hm.Vertex[tri[0]], hm.Vertex[tri[1]], hm.Vertex[tri[2]]);
    if (fh.is_valid())
    {
      mesh.property(hm.InputCellId, fh) = soup.SourceCells[t];
    }
    else
    {
      hm.PassedThrough.push_back(t);
    }
  }
}

// Locks the points of the passed-through faces and, if asked, the boundary
// vertices; returns how many vertices are locked.
vtkIdType LockVertices(HalfedgeMesh& hm, const TriangleSoup& soup, bool preserveBoundaries)
{
  Mesh& mesh = hm.Halfedges;
  for (vtkIdType t : hm.PassedThrough)
  {
    for (vtkIdType id : soup.Triangles[t])
    {
      mesh.status(hm.Vertex[id]).set_locked(true);
    }
  }
  if (preserveBoundaries)
  {
    for (const auto v : mesh.vertices())
    {
      if (mesh.is_boundary(v))
      {
        mesh.status(v).set_locked(true);
      }
    }
  }
  vtkIdType numLocked = 0;
  for (const auto v : mesh.vertices())
  {
    numLocked += mesh.status(v).locked() ? 1 : 0;
  }
  return numLocked;
}

// The mesh's faces over the input points, located for the distance guard's
// output -> input check.
void LocateInputSurface(
  const HalfedgeMesh& hm, vtkPoints* points, vtkPolyData* surface, vtkStaticCellLocator* locator)
{
  const Mesh& mesh = hm.Halfedges;
  vtkNew<vtkCellArray> tris;
  tris->AllocateExact(static_cast<vtkIdType>(mesh.n_faces()), 3 * mesh.n_faces());
  for (const auto f : mesh.faces())
  {
    vtkIdType ids[3];
    int k = 0;
    for (const auto v : mesh.fv_range(f))
    {
      ids[k++] = mesh.property(hm.InputPointId, v);
    }
    tris->InsertNextCell(3, ids);
  }
  surface->SetPoints(points);
  surface->SetPolys(tris);
  locator->SetDataSet(surface);
  locator->BuildLocator();
}

// Collapses the mesh down to `targetFaces` within `limits` (a negative
// MaximumError: no distance guard), then drops the deleted elements.
void DecimateMesh(
  HalfedgeMesh& hm, vtkPoints* points, vtkIdType targetFaces, const DecimationLimits& limits)
{
  vtkNew<vtkPolyData> surface;
  vtkNew<vtkStaticCellLocator> locator;
  const bool bounded = limits.MaximumError >= 0.0;
  if (bounded)
  {
    LocateInputSurface(hm, points, surface, locator);
  }
  vtkrt_filters::decimation::Decimate(
    hm.Halfedges, static_cast<size_t>(targetFaces), limits, bounded ? locator.Get() : nullptr);
  hm.Halfedges.garbage_collection();
}

// Output points: the surviving vertices and the passed-through faces' points,
// in input order, with all their data. Returns input id -> output id (-1: gone).
std::vector<vtkIdType> GatherOutputPoints(vtkPolyData* input, const HalfedgeMesh& hm,
  const TriangleSoup& soup, vtkPolyData* output, std::vector<std::string>& dropped)
{
  const Mesh& mesh = hm.Halfedges;
  const vtkIdType numInPoints = input->GetNumberOfPoints();
  std::vector<vtkIdType> outToIn;
  outToIn.reserve(mesh.n_vertices() + 3 * hm.PassedThrough.size());
  std::vector<vtkIdType> newId(numInPoints, -1);
  for (const auto v : mesh.vertices())
  {
    if (!mesh.is_isolated(v) || mesh.status(v).locked())
    {
      newId[mesh.property(hm.InputPointId, v)] = 0;
    }
  }
  for (vtkIdType t : hm.PassedThrough)
  {
    for (vtkIdType id : soup.Triangles[t])
    {
      newId[id] = 0;
    }
  }
  for (vtkIdType i = 0; i < numInPoints; ++i)
  {
    if (newId[i] == 0)
    {
      newId[i] = static_cast<vtkIdType>(outToIn.size());
      outToIn.push_back(i);
    }
  }
  vtkNew<vtkPoints> outPts;
  outPts->SetDataType(input->GetPoints()->GetDataType());
  outPts->SetNumberOfPoints(static_cast<vtkIdType>(outToIn.size()));
  vtkrt_filters::GatherPoints(input, outToIn, outPts, output, dropped);
  return newId;
}

// Output triangles: the decimated faces, then the passed-through ones.
// Returns the input cell each descends from.
std::vector<vtkIdType> BuildOutputTriangles(const HalfedgeMesh& hm, const TriangleSoup& soup,
  const std::vector<vtkIdType>& newId, vtkPolyData* output)
{
  const Mesh& mesh = hm.Halfedges;
  const vtkIdType numOutFaces =
    static_cast<vtkIdType>(mesh.n_faces() + hm.PassedThrough.size());
  std::vector<vtkIdType> sourceCell;
  sourceCell.reserve(numOutFaces);
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(numOutFaces, 3 * numOutFaces);
  for (const auto f : mesh.faces())
  {
    vtkIdType ids[3];
    int k = 0;
    for (const auto v : mesh.fv_range(f))
    {
      ids[k++] = newId[mesh.property(hm.InputPointId, v)];
    }
    polys->InsertNextCell(3, ids);
    sourceCell.push_back(mesh.property(hm.InputCellId, f));
  }
  for (vtkIdType t : hm.PassedThrough)
  {
    const Triangle& tri = soup.Triangles[t];
    const vtkIdType ids[3] = { newId[tri[0]], newId[tri[1]], newId[tri[2]] };
    polys->InsertNextCell(3, ids);
    sourceCell.push_back(soup.SourceCells[t]);
  }
  output->SetPolys(polys);
  return sourceCell;
}

// Cell data from the face each triangle descends from; cell normals no
// longer describe the moved faces.
void CopyCellData(vtkPolyData* input, const std::vector<vtkIdType>& sourceCell,
  vtkPolyData* output, std::vector<std::string>& dropped)
{
  const vtkIdType numOutFaces = static_cast<vtkIdType>(sourceCell.size());
  auto inCD = vtkrt_filters::ArraysWithTuples(
    input->GetCellData(), input->GetNumberOfCells(), "cell:", dropped);
  vtkCellData* outCD = output->GetCellData();
  if (vtkDataArray* normals = inCD->GetNormals())
  {
    dropped.push_back(std::string("cell:") + (normals->GetName() ? normals->GetName() : "Normals"));
    outCD->CopyNormalsOff();
  }
  outCD->CopyAllocate(inCD.Get(), numOutFaces);
  for (vtkIdType f = 0; f < numOutFaces; ++f)
  {
    outCD->CopyData(inCD.Get(), sourceCell[f], f);
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkIdType vtkOpenMeshDecimation::TargetTriangles() const
{
  switch (this->TargetMode)
  {
    case TARGET_REDUCTION:
      return static_cast<vtkIdType>(
        std::llround((1.0 - this->TargetReduction) * this->NumberOfInputTriangles));
    case TARGET_COUNT:
      return this->TargetNumberOfTriangles;
    default:
      return 0;
  }
}

//------------------------------------------------------------------------------
int vtkOpenMeshDecimation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->NumberOfInputTriangles = 0;
  this->NumberOfOutputTriangles = 0;
  this->NumberOfPassedThroughFaces = 0;
  this->NumberOfLockedVertices = 0;
  vtkPolyData* output = vtkrt_filters::EmptiedOutput(this, outputVector);
  if (!output)
  {
    return 0;
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  if (!vtkrt_filters::CheckSurfaceInput(
        this, input, "nothing to decimate", "there is no surface to decimate"))
  {
    return 1;
  }
  vtkPoints* inPts = input->GetPoints();
  if (this->TargetMode == ERROR_BOUND && !(this->MaximumError < VTK_DOUBLE_MAX))
  {
    vtkErrorMacro("TargetMode ERROR_BOUND needs a finite MaximumError: without one the mesh "
                  "would be decimated to nothing.");
    return 1;
  }

  TriangleSoup soup;
  vtkrt_filters::TriangulatePolyData(input, soup);
  if (!vtkrt_filters::CheckTriangulation(this, soup))
  {
    return 1;
  }
  // Non-finite points poison the quadrics and distances: refuse them.
  const std::vector<unsigned char> used = UsedPoints(soup, input->GetNumberOfPoints());
  if (const vtkIdType numNonFinite = CountNonFinitePoints(inPts, used))
  {
    vtkErrorMacro("Input faces use " << numNonFinite
                                     << " non-finite (NaN or infinite) points; remove them first "
                                        "(vtkOpenMeshClean drops the faces that use them).");
    return 1;
  }

  // Build the halfedge mesh. Faces OpenMesh cannot hold (non-manifold edges
  // or vertices) are passed through untouched, their points locked.
  vtkrt_filters::OpenMeshErrorMute mute;
  HalfedgeMesh hm;
  BuildHalfedgeMesh(inPts, used, soup, hm);
  this->NumberOfInputTriangles =
    static_cast<vtkIdType>(soup.Triangles.size()) - hm.NumberOfDegenerateFaces;
  this->NumberOfPassedThroughFaces = static_cast<vtkIdType>(hm.PassedThrough.size());
  this->NumberOfLockedVertices = LockVertices(hm, soup, this->PreserveBoundaries);
  hm.Halfedges.update_face_normals();

  // Target, in triangles of the whole output.
  const vtkIdType meshTarget =
    std::max<vtkIdType>(0, this->TargetTriangles() - this->NumberOfPassedThroughFaces);
  if (meshTarget < static_cast<vtkIdType>(hm.Halfedges.n_faces()))
  {
    DecimationLimits limits;
    limits.MaximumError = this->MaximumError < VTK_DOUBLE_MAX ? this->MaximumError : -1.0;
    limits.MaximumNormalDeviation = this->MaximumNormalDeviation;
    limits.MaximumAspectRatio = this->MaximumAspectRatio;
    limits.BoundaryWeight = this->BoundaryConstraintWeight;
    DecimateMesh(hm, inPts, meshTarget, limits);
  }

  std::vector<std::string> dropped;
  const std::vector<vtkIdType> newId = GatherOutputPoints(input, hm, soup, output, dropped);
  const std::vector<vtkIdType> sourceCell = BuildOutputTriangles(hm, soup, newId, output);
  this->NumberOfOutputTriangles = static_cast<vtkIdType>(sourceCell.size());
  CopyCellData(input, sourceCell, output, dropped);

  vtkFieldData* fd = output->GetFieldData();
  fd->PassData(input->GetFieldData());
  vtkrt_filters::AddFieldCount(fd, "NumberOfInputTriangles", this->NumberOfInputTriangles);
  vtkrt_filters::AddFieldCount(fd, "NumberOfOutputTriangles", this->NumberOfOutputTriangles);
  vtkrt_filters::AddFieldCount(fd, "NumberOfPassedThroughFaces", this->NumberOfPassedThroughFaces);
  vtkrt_filters::AddFieldCount(fd, "NumberOfLockedVertices", this->NumberOfLockedVertices);
  vtkrt_filters::AddFieldCount(fd, "NumberOfDroppedVerts", soup.NumberOfDroppedVerts);
  vtkrt_filters::AddFieldCount(fd, "NumberOfDroppedLines", soup.NumberOfDroppedLines);
  vtkrt_filters::AddFieldCount(fd, "NumberOfInvalidCells", soup.NumberOfInvalidCells);
  vtkrt_filters::AddFieldStrings(fd, "DroppedArrays", dropped);
  return 1;
}

//------------------------------------------------------------------------------
void vtkOpenMeshDecimation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetMode: " << this->TargetMode << "\n";
  os << indent << "TargetReduction: " << this->TargetReduction << "\n";
  os << indent << "TargetNumberOfTriangles: " << this->TargetNumberOfTriangles << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
  os << indent << "MaximumNormalDeviation: " << this->MaximumNormalDeviation << "\n";
  os << indent << "MaximumAspectRatio: " << this->MaximumAspectRatio << "\n";
  os << indent << "PreserveBoundaries: " << this->PreserveBoundaries << "\n";
  os << indent << "BoundaryConstraintWeight: " << this->BoundaryConstraintWeight << "\n";
  os << indent << "NumberOfInputTriangles: " << this->NumberOfInputTriangles << "\n";
  os << indent << "NumberOfOutputTriangles: " << this->NumberOfOutputTriangles << "\n";
  os << indent << "NumberOfPassedThroughFaces: " << this->NumberOfPassedThroughFaces << "\n";
  os << indent << "NumberOfLockedVertices: " << this->NumberOfLockedVertices << "\n";
}
