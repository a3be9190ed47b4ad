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
using vtkrt_filters::decimation::DecimationLimits;
} // namespace

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
  const vtkIdType numInPoints = input->GetNumberOfPoints();
  if (this->TargetMode == ERROR_BOUND && !(this->MaximumError < VTK_DOUBLE_MAX))
  {
    vtkErrorMacro("TargetMode ERROR_BOUND needs a finite MaximumError: without one the mesh "
                  "would be decimated to nothing.");
    return 1;
  }

  vtkrt_filters::TriangleSoup soup;
  vtkrt_filters::TriangulatePolyData(input, soup);
  const vtkIdType numTris = static_cast<vtkIdType>(soup.Triangles.size());

  if (!vtkrt_filters::CheckTriangulation(this, soup))
  {
    return 1;
  }
  // Non-finite points poison the quadrics and distances: refuse them.
  std::vector<unsigned char> used(numInPoints, 0);
  for (const Triangle& tri : soup.Triangles)
  {
    for (vtkIdType id : tri)
    {
      used[id] = 1;
    }
  }
  std::vector<unsigned char> nonFinite(numInPoints, 0);
  vtkSMPTools::For(0, numInPoints,
    [&](vtkIdType begin, vtkIdType end)
    {
      double p[3];
      for (vtkIdType i = begin; i < end; ++i)
      {
        inPts->GetPoint(i, p);
        nonFinite[i] = used[i] && !vtkrt_filters::IsFinite(p);
      }
    });
  const vtkIdType numNonFinite =
    static_cast<vtkIdType>(std::count(nonFinite.begin(), nonFinite.end(), 1));
  if (numNonFinite)
  {
    vtkErrorMacro("Input faces use " << numNonFinite
                                     << " non-finite (NaN or infinite) points; remove them first "
                                        "(vtkOpenMeshClean drops the faces that use them).");
    return 1;
  }

  // Build the halfedge mesh. Faces OpenMesh cannot hold (non-manifold edges
  // or vertices) are passed through untouched, their points locked.
  vtkrt_filters::OpenMeshErrorMute mute;
  Mesh mesh;
  OpenMesh::VPropHandleT<vtkIdType> inputPointId;
  OpenMesh::FPropHandleT<vtkIdType> inputCellId;
  mesh.add_property(inputPointId);
  mesh.add_property(inputCellId);
  std::vector<Mesh::VertexHandle> vh(numInPoints);
  for (vtkIdType i = 0; i < numInPoints; ++i)
  {
    if (used[i])
    {
      double p[3];
      inPts->GetPoint(i, p);
      vh[i] = mesh.add_vertex(Mesh::Point(p[0], p[1], p[2]));
      mesh.property(inputPointId, vh[i]) = i;
    }
  }
  std::vector<vtkIdType> passedThrough; // soup indices
  vtkIdType numDegenerate = 0;
  for (vtkIdType t = 0; t < numTris; ++t)
  {
    const Triangle& tri = soup.Triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
    {
      ++numDegenerate;
      continue;
    }
    const Mesh::FaceHandle fh = mesh.add_face(vh[tri[0]], vh[tri[1]], vh[tri[2]]);
    if (fh.is_valid())
    {
      mesh.property(inputCellId, fh) = soup.SourceCells[t];
    }
    else
    {
      passedThrough.push_back(t);
    }
  }
  this->NumberOfInputTriangles = numTris - numDegenerate;
  this->NumberOfPassedThroughFaces = static_cast<vtkIdType>(passedThrough.size());
  for (vtkIdType t : passedThrough)
  {
    for (vtkIdType id : soup.Triangles[t])
    {
      mesh.status(vh[id]).set_locked(true);
    }
  }
  if (this->PreserveBoundaries)
  {
    for (const auto v : mesh.vertices())
    {
      if (mesh.is_boundary(v))
      {
        mesh.status(v).set_locked(true);
      }
    }
  }
  for (const auto v : mesh.vertices())
  {
    this->NumberOfLockedVertices += mesh.status(v).locked() ? 1 : 0;
  }
  mesh.update_face_normals();

  // Target, in triangles of the whole output.
  vtkIdType target = 0;
  switch (this->TargetMode)
  {
    case TARGET_REDUCTION:
      target = static_cast<vtkIdType>(
        std::llround((1.0 - this->TargetReduction) * this->NumberOfInputTriangles));
      break;
    case TARGET_COUNT:
      target = this->TargetNumberOfTriangles;
      break;
    default:
      target = 0;
      break;
  }
  const vtkIdType meshTarget = std::max<vtkIdType>(0, target - this->NumberOfPassedThroughFaces);

  if (meshTarget < static_cast<vtkIdType>(mesh.n_faces()))
  {
    // The input surface, for the distance guard's output -> input check.
    vtkNew<vtkPolyData> surface;
    vtkNew<vtkStaticCellLocator> locator;
    const bool bounded = this->MaximumError < VTK_DOUBLE_MAX;
    if (bounded)
    {
      vtkNew<vtkCellArray> tris;
      tris->AllocateExact(static_cast<vtkIdType>(mesh.n_faces()), 3 * mesh.n_faces());
      for (const auto f : mesh.faces())
      {
        vtkIdType ids[3];
        int k = 0;
        for (const auto v : mesh.fv_range(f))
        {
          ids[k++] = mesh.property(inputPointId, v);
        }
        tris->InsertNextCell(3, ids);
      }
      surface->SetPoints(inPts);
      surface->SetPolys(tris);
      locator->SetDataSet(surface);
      locator->BuildLocator();
    }
    DecimationLimits limits;
    limits.MaximumError = bounded ? this->MaximumError : -1.0;
    limits.MaximumNormalDeviation = this->MaximumNormalDeviation;
    limits.MaximumAspectRatio = this->MaximumAspectRatio;
    limits.BoundaryWeight = this->BoundaryConstraintWeight;
    vtkrt_filters::decimation::Decimate(
      mesh, static_cast<size_t>(meshTarget), limits, bounded ? locator.Get() : nullptr);
    mesh.garbage_collection();
  }

  // Output points: the surviving vertices in input order, with all their data.
  std::vector<vtkIdType> outToIn;
  outToIn.reserve(mesh.n_vertices() + 3 * passedThrough.size());
  std::vector<vtkIdType> newId(numInPoints, -1);
  for (const auto v : mesh.vertices())
  {
    if (!mesh.is_isolated(v) || mesh.status(v).locked())
    {
      newId[mesh.property(inputPointId, v)] = 0;
    }
  }
  for (vtkIdType t : passedThrough)
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
  const vtkIdType numOutPoints = static_cast<vtkIdType>(outToIn.size());
  vtkNew<vtkPoints> outPts;
  outPts->SetDataType(inPts->GetDataType());
  outPts->SetNumberOfPoints(numOutPoints);
  std::vector<std::string> dropped;
  vtkrt_filters::GatherPoints(input, outToIn, outPts, output, dropped);

  // Output triangles: the decimated faces, then the passed-through ones.
  const vtkIdType numOutFaces =
    static_cast<vtkIdType>(mesh.n_faces()) + this->NumberOfPassedThroughFaces;
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
      ids[k++] = newId[mesh.property(inputPointId, v)];
    }
    polys->InsertNextCell(3, ids);
    sourceCell.push_back(mesh.property(inputCellId, f));
  }
  for (vtkIdType t : passedThrough)
  {
    const Triangle& tri = soup.Triangles[t];
    const vtkIdType ids[3] = { newId[tri[0]], newId[tri[1]], newId[tri[2]] };
    polys->InsertNextCell(3, ids);
    sourceCell.push_back(soup.SourceCells[t]);
  }
  output->SetPolys(polys);
  this->NumberOfOutputTriangles = numOutFaces;

  // Cell data from the face each triangle descends from; cell normals no
  // longer describe the moved faces.
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
