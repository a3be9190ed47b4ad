#include "vtkOpenMeshClean.h"

#include "vtkOpenMeshCleanSteps.h"
#include "vtkOpenMeshInternals.h"

#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkOpenMeshClean);

//------------------------------------------------------------------------------
vtkOpenMeshClean::vtkOpenMeshClean()
{
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkPolyData* vtkOpenMeshClean::GetProblemEdges()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
bool vtkOpenMeshClean::IsClosedManifold() const
{
  return this->NumberOfComponents > 0 && this->NumberOfBoundaryEdges == 0 &&
    this->NumberOfNonManifoldEdges == 0 && this->NumberOfInconsistentEdges == 0 &&
    this->NumberOfNonManifoldVertices == 0 && this->NumberOfRejectedFaces == 0;
}

//------------------------------------------------------------------------------
void vtkOpenMeshClean::ResetCounts()
{
  this->NumberOfDroppedVerts = 0;
  this->NumberOfDroppedLines = 0;
  this->NumberOfInvalidCells = 0;
  this->NumberOfMergedPoints = 0;
  this->NumberOfNonFinitePoints = 0;
  this->NumberOfNonFiniteFaces = 0;
  this->NumberOfDegenerateFaces = 0;
  this->NumberOfDuplicateFaces = 0;
  this->NumberOfFlippedFaces = 0;
  this->NumberOfComponents = 0;
  this->NumberOfBoundaryEdges = 0;
  this->NumberOfNonManifoldEdges = 0;
  this->NumberOfInconsistentEdges = 0;
  this->NumberOfNonManifoldVertices = 0;
  this->NumberOfBoundaryLoops = 0;
  this->NumberOfRejectedFaces = 0;
}

namespace
{
// The counts as field data, with the input's field data, for pipelines that
// read them downstream.
void AddCountsToFieldData(vtkOpenMeshClean* self, vtkFieldData* fd, vtkFieldData* inputFieldData,
  const std::vector<std::string>& dropped)
{
  fd->PassData(inputFieldData);
  vtkrt_filters::AddFieldCount(fd, "NumberOfDroppedVerts", self->GetNumberOfDroppedVerts());
  vtkrt_filters::AddFieldCount(fd, "NumberOfDroppedLines", self->GetNumberOfDroppedLines());
  vtkrt_filters::AddFieldCount(fd, "NumberOfInvalidCells", self->GetNumberOfInvalidCells());
  vtkrt_filters::AddFieldCount(fd, "NumberOfMergedPoints", self->GetNumberOfMergedPoints());
  vtkrt_filters::AddFieldCount(fd, "NumberOfNonFinitePoints", self->GetNumberOfNonFinitePoints());
  vtkrt_filters::AddFieldCount(fd, "NumberOfNonFiniteFaces", self->GetNumberOfNonFiniteFaces());
  vtkrt_filters::AddFieldCount(fd, "NumberOfDegenerateFaces", self->GetNumberOfDegenerateFaces());
  vtkrt_filters::AddFieldCount(fd, "NumberOfDuplicateFaces", self->GetNumberOfDuplicateFaces());
  vtkrt_filters::AddFieldCount(fd, "NumberOfFlippedFaces", self->GetNumberOfFlippedFaces());
  vtkrt_filters::AddFieldCount(fd, "NumberOfComponents", self->GetNumberOfComponents());
  vtkrt_filters::AddFieldCount(fd, "NumberOfBoundaryEdges", self->GetNumberOfBoundaryEdges());
  vtkrt_filters::AddFieldCount(fd, "NumberOfNonManifoldEdges", self->GetNumberOfNonManifoldEdges());
  vtkrt_filters::AddFieldCount(
    fd, "NumberOfInconsistentEdges", self->GetNumberOfInconsistentEdges());
  vtkrt_filters::AddFieldCount(
    fd, "NumberOfNonManifoldVertices", self->GetNumberOfNonManifoldVertices());
  vtkrt_filters::AddFieldCount(fd, "NumberOfBoundaryLoops", self->GetNumberOfBoundaryLoops());
  vtkrt_filters::AddFieldCount(fd, "NumberOfRejectedFaces", self->GetNumberOfRejectedFaces());
  vtkrt_filters::AddFieldCount(fd, "IsClosedManifold", self->IsClosedManifold() ? 1 : 0);
  vtkrt_filters::AddFieldStrings(fd, "DroppedArrays", dropped);
}

// How many faces each classification drops.
struct DroppedFaces
{
  vtkIdType NonFinite = 0;
  vtkIdType Degenerate = 0;
  vtkIdType Duplicate = 0;
};

// Classifies the welded triangles (non-finite, degenerate, and duplicated when
// `removeDuplicates`: same point set, whatever the order) and returns the soup
// indices of the kept ones, in order; the others are counted.
std::vector<vtkIdType> KeptFaces(vtkPoints* inPts, const std::vector<vtkIdType>& weld,
  bool removeDuplicates, std::vector<vtkrt_filters::Triangle>& triangles, DroppedFaces& dropped)
{
  namespace clean = vtkrt_filters::clean;
  std::vector<unsigned char> status;
  clean::ClassifyFaces(inPts, weld, triangles, status);
  if (removeDuplicates)
  {
    clean::MarkDuplicateFaces(triangles, status);
  }
  const vtkIdType numTris = static_cast<vtkIdType>(status.size());
  std::vector<vtkIdType> kept;
  kept.reserve(numTris);
  for (vtkIdType t = 0; t < numTris; ++t)
  {
    switch (status[t])
    {
      case clean::FaceKept:
        kept.push_back(t);
        break;
      case clean::FaceNonFinite:
        ++dropped.NonFinite;
        break;
      case clean::FaceDegenerate:
        ++dropped.Degenerate;
        break;
      default:
        ++dropped.Duplicate;
        break;
    }
  }
  return kept;
}

// Orients the kept faces breadth-first over manifold edges, one patch at a
// time (consistently when `consistent`), then turns closed patches outward
// when `outward` too.
vtkrt_filters::clean::Patches OrientFaces(const vtkrt_filters::clean::EdgeTable& edges,
  vtkPoints* inPts, const std::vector<vtkrt_filters::Triangle>& triangles,
  const std::vector<vtkIdType>& kept, bool consistent, bool outward)
{
  namespace clean = vtkrt_filters::clean;
  clean::Patches patches;
  clean::OrientPatches(edges, static_cast<vtkIdType>(kept.size()), consistent, patches);
  if (consistent && outward)
  {
    clean::OrientClosedPatches(inPts, triangles, kept, patches);
  }
  return patches;
}

// The kept triangles, oriented, as the output's polys; returns their
// connectivity.
vtkSmartPointer<vtkIdTypeArray> SetOutputTriangles(const vtkrt_filters::TriangleSoup& soup,
  const std::vector<vtkIdType>& kept, const std::vector<vtkIdType>& newId,
  const std::vector<unsigned char>& flip, vtkPolyData* output)
{
  vtkNew<vtkIdTypeArray> offsets;
  auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
  vtkrt_filters::clean::BuildTriangles(soup.Triangles, kept, newId, flip, offsets, connectivity);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  output->SetPolys(polys);
  return connectivity;
}
} // namespace

//------------------------------------------------------------------------------
int vtkOpenMeshClean::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  namespace clean = vtkrt_filters::clean;
  this->ResetCounts();
  vtkPolyData* output = vtkrt_filters::EmptiedOutput(this, outputVector, 0);
  vtkPolyData* edgesOut = output ? vtkrt_filters::EmptiedOutput(this, outputVector, 1) : nullptr;
  if (!edgesOut)
  {
    return 0;
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  if (!input)
  {
    vtkErrorMacro("No input polydata: connect a vtkPolyData to port 0.");
    return 0;
  }
  if (!vtkrt_filters::CheckSurfaceInput(
        this, input, "nothing to clean", "there is no surface to clean"))
  {
    return 1;
  }
  const vtkIdType numInPoints = input->GetNumberOfPoints();

  // 1. Triangulate.
  vtkrt_filters::TriangleSoup soup;
  vtkrt_filters::TriangulatePolyData(input, soup);
  this->NumberOfDroppedVerts = soup.NumberOfDroppedVerts;
  this->NumberOfDroppedLines = soup.NumberOfDroppedLines;
  this->NumberOfInvalidCells = soup.NumberOfInvalidCells;
  const vtkIdType numTris = static_cast<vtkIdType>(soup.Triangles.size());

  // 2. Weld the finite points; non-finite ones map to -1.
  vtkPoints* inPts = input->GetPoints();
  std::vector<vtkIdType> weld; // input id -> representative input id
  this->NumberOfNonFinitePoints = numInPoints -
    clean::WeldPoints(
      inPts, this->ToleranceIsAbsolute, this->AbsoluteTolerance, this->Tolerance, weld);

  // 3. Classify faces: non-finite, degenerate (after the weld), duplicated, kept.
  DroppedFaces droppedFaces;
  const std::vector<vtkIdType> kept = // kept triangle -> soup index
    KeptFaces(inPts, weld, this->RemoveDuplicateFaces, soup.Triangles, droppedFaces);
  this->NumberOfNonFiniteFaces = droppedFaces.NonFinite;
  this->NumberOfDegenerateFaces = droppedFaces.Degenerate;
  this->NumberOfDuplicateFaces = droppedFaces.Duplicate;
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
  if (numFaces == 0)
  {
    vtkErrorMacro("No valid face left: of "
      << numTris << " triangles, " << this->NumberOfNonFiniteFaces << " touch non-finite points, "
      << this->NumberOfDegenerateFaces << " are degenerate and " << this->NumberOfDuplicateFaces
      << " are duplicates.");
    return 1;
  }

  // 4. Edge table: sorting the 3 uses of every face groups each edge's faces.
  clean::EdgeTable edges;
  clean::BuildEdgeTable(soup.Triangles, kept, edges);

  // 5. Orientation, patch by patch.
  const clean::Patches patches = OrientFaces(edges, inPts, soup.Triangles, kept,
    this->ConsistentOrientation, this->OrientClosedSurfacesOutward);
  this->NumberOfComponents = patches.Count;
  const std::vector<unsigned char>& flip = patches.Flip;
  for (vtkIdType f = 0; f < numFaces; ++f)
  {
    this->NumberOfFlippedFaces += flip[f];
  }

  // 6. Edge and vertex report on the oriented faces.
  std::vector<clean::ProblemEdge> problemEdges;
  const clean::EdgeCounts edgeCounts =
    clean::ClassifyEdges(edges, flip, this->GenerateProblemEdges, problemEdges);
  this->NumberOfBoundaryEdges = edgeCounts.Boundary;
  this->NumberOfNonManifoldEdges = edgeCounts.NonManifold;
  this->NumberOfInconsistentEdges = edgeCounts.Inconsistent;
  this->NumberOfNonManifoldVertices =
    clean::CountNonManifoldVertices(edges, soup.Triangles, kept, numInPoints);

  // 7. Output points: the representatives the kept faces use, in input order.
  std::vector<vtkIdType> newId(numInPoints, -1);
  const vtkIdType numOutPoints = clean::NumberOutputPoints(soup.Triangles, kept, newId);
  this->NumberOfMergedPoints = clean::CountMergedPoints(weld);
  std::vector<std::string> dropped;
  vtkSmartPointer<vtkPoints> outPts = clean::GatherOutputPoints(
    input, this->OutputPointsPrecision, newId, numOutPoints, output, dropped);

  // 8. Output triangles, oriented, with their cells' data.
  vtkSmartPointer<vtkIdTypeArray> connectivity =
    SetOutputTriangles(soup, kept, newId, flip, output);
  clean::CopyCellData(input, soup, kept, flip, this->GenerateOriginalCellIds, output, dropped);

  // 9. OpenMesh's view of the result.
  clean::CountOpenMeshRejects(outPts, connectivity->GetPointer(0), numFaces,
    this->NumberOfRejectedFaces, this->NumberOfBoundaryLoops);

  // 10. Report.
  AddCountsToFieldData(this, output->GetFieldData(), input->GetFieldData(), dropped);
  if (this->GenerateProblemEdges && !problemEdges.empty())
  {
    clean::BuildProblemEdges(problemEdges, newId, outPts, edgesOut);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkOpenMeshClean::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "AbsoluteTolerance: " << this->AbsoluteTolerance << "\n";
  os << indent << "ToleranceIsAbsolute: " << this->ToleranceIsAbsolute << "\n";
  os << indent << "RemoveDuplicateFaces: " << this->RemoveDuplicateFaces << "\n";
  os << indent << "ConsistentOrientation: " << this->ConsistentOrientation << "\n";
  os << indent << "OrientClosedSurfacesOutward: " << this->OrientClosedSurfacesOutward << "\n";
  os << indent << "GenerateProblemEdges: " << this->GenerateProblemEdges << "\n";
  os << indent << "GenerateOriginalCellIds: " << this->GenerateOriginalCellIds << "\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
  os << indent << "NumberOfMergedPoints: " << this->NumberOfMergedPoints << "\n";
  os << indent << "NumberOfNonFiniteFaces: " << this->NumberOfNonFiniteFaces << "\n";
  os << indent << "NumberOfDegenerateFaces: " << this->NumberOfDegenerateFaces << "\n";
  os << indent << "NumberOfDuplicateFaces: " << this->NumberOfDuplicateFaces << "\n";
  os << indent << "NumberOfFlippedFaces: " << this->NumberOfFlippedFaces << "\n";
  os << indent << "NumberOfComponents: " << this->NumberOfComponents << "\n";
  os << indent << "NumberOfBoundaryEdges: " << this->NumberOfBoundaryEdges << "\n";
  os << indent << "NumberOfNonManifoldEdges: " << this->NumberOfNonManifoldEdges << "\n";
  os << indent << "NumberOfInconsistentEdges: " << this->NumberOfInconsistentEdges << "\n";
  os << indent << "NumberOfNonManifoldVertices: " << this->NumberOfNonManifoldVertices << "\n";
  os << indent << "NumberOfBoundaryLoops: " << this->NumberOfBoundaryLoops << "\n";
  os << indent << "NumberOfRejectedFaces: " << this->NumberOfRejectedFaces << "\n";
}
