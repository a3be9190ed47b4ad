#include "vtkBVHBoxes.h"

#include "vtkOpenMeshInternals.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include "vtkrt/core/Mesh.h"

#include <cstdint>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkBVHBoxes);

//------------------------------------------------------------------------------
int vtkBVHBoxes::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  namespace core = vtkrt::core;
  this->NumberOfNodes = 0;
  this->NumberOfLeaves = 0;
  this->MaximumDepth = 0;
  this->NumberOfSkippedTriangles = 0;
  vtkPolyData* output = vtkrt_filters::EmptiedOutput(this, outputVector);
  if (!output)
  {
    return 0;
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  if (!vtkrt_filters::CheckSurfaceInput(
        this, input, "there is nothing to build a BVH over", "the BVH holds triangles only"))
  {
    return 1;
  }
  const vtkIdType numPoints = input->GetNumberOfPoints();
  if (static_cast<std::uint64_t>(numPoints) >= std::numeric_limits<std::uint32_t>::max())
  {
    vtkErrorMacro("Input has " << numPoints << " points: the core's indices are 32-bit.");
    return 1;
  }

  vtkrt_filters::TriangleSoup soup;
  vtkrt_filters::TriangulatePolyData(input, soup);
  if (!vtkrt_filters::CheckTriangulation(this, soup))
  {
    return 1;
  }
  std::vector<core::Vec3<double>> vertices(numPoints);
  vtkPoints* pts = input->GetPoints();
  vtkSMPTools::For(0, numPoints,
    [&](vtkIdType begin, vtkIdType end)
    {
      double p[3];
      for (vtkIdType i = begin; i < end; ++i)
      {
        pts->GetPoint(i, p);
        vertices[i] = core::Vec3<double>(p[0], p[1], p[2]);
      }
    });
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * soup.Triangles.size());
  for (const auto& tri : soup.Triangles)
  {
    for (vtkIdType id : tri)
    {
      indices.push_back(static_cast<std::uint32_t>(id)); // in range: checked by the triangulation
    }
  }
  core::TriangleMesh<double> mesh(vertices, indices);
  core::BuildOptions options;
  options.quality = this->BuildQuality == FAST ? core::BuildQuality::Fast
    : this->BuildQuality == HIGH               ? core::BuildQuality::High
                                               : core::BuildQuality::Medium;
  options.maxLeafSize = static_cast<std::uint32_t>(this->MaximumLeafSize);
  options.numThreads = static_cast<unsigned>(vtkSMPTools::GetEstimatedNumberOfThreads());
  const core::BVH bvh = core::buildTriangleBVH(mesh, options);
  this->NumberOfNodes = static_cast<vtkIdType>(bvh.nodes.size());
  this->NumberOfLeaves = static_cast<vtkIdType>(bvh.stats.leafCount);
  this->MaximumDepth = static_cast<int>(bvh.stats.maxDepth);
  this->NumberOfSkippedTriangles = static_cast<vtkIdType>(bvh.stats.skippedPrimitives);

  vtkFieldData* fd = output->GetFieldData();
  vtkrt_filters::AddFieldCount(fd, "BVHNodeCount", this->NumberOfNodes);
  vtkrt_filters::AddFieldCount(fd, "BVHLeafCount", this->NumberOfLeaves);
  vtkrt_filters::AddFieldCount(fd, "BVHMaxDepth", this->MaximumDepth);
  vtkrt_filters::AddFieldCount(fd, "BVHSkippedTriangles", this->NumberOfSkippedTriangles);
  vtkNew<vtkDoubleArray> sah;
  sah->SetName("BVHSAHCost");
  sah->InsertNextValue(bvh.stats.sahCost);
  fd->AddArray(sah);
  if (bvh.empty())
  {
    return 1; // every triangle degenerate or non-finite: no box to show
  }

  // Triangles under every node: children come after their parent, so one
  // backward sweep sums them.
  const size_t numNodes = bvh.nodes.size();
  std::vector<std::uint32_t> primitives(numNodes, 0);
  std::vector<int> depth(numNodes, 0);
  for (size_t i = 0; i < numNodes; ++i)
  {
    const core::BVHNode& n = bvh.nodes[i];
    if (!n.isLeaf())
    {
      depth[n.index] = depth[n.index + 1] = depth[i] + 1;
    }
  }
  for (size_t i = numNodes; i-- > 0;)
  {
    const core::BVHNode& n = bvh.nodes[i];
    primitives[i] = n.isLeaf() ? n.count : primitives[n.index] + primitives[n.index + 1];
  }
  std::vector<size_t> shown;
  for (size_t i = 0; i < numNodes; ++i)
  {
    const bool leaf = bvh.nodes[i].isLeaf();
    if (this->LeavesOnly ? leaf : (depth[i] == this->Level || (leaf && depth[i] < this->Level)))
    {
      shown.push_back(i);
    }
  }

  const vtkIdType numBoxes = static_cast<vtkIdType>(shown.size());
  const bool faces = this->OutputStyle == FACES;
  const int cellsPerBox = faces ? 6 : 12;
  vtkNew<vtkPoints> boxPoints;
  boxPoints->SetDataTypeToDouble();
  boxPoints->SetNumberOfPoints(8 * numBoxes);
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(cellsPerBox * numBoxes, cellsPerBox * numBoxes * (faces ? 4 : 2));
  vtkNew<vtkIdTypeArray> nodeIds;
  nodeIds->SetName("BVHNodeId");
  vtkNew<vtkIntArray> depths;
  depths->SetName("BVHDepth");
  vtkNew<vtkIdTypeArray> counts;
  counts->SetName("BVHPrimitiveCount");
  vtkNew<vtkUnsignedCharArray> isLeaf;
  isLeaf->SetName("BVHIsLeaf");
  for (auto* a : { static_cast<vtkDataArray*>(nodeIds), static_cast<vtkDataArray*>(depths),
         static_cast<vtkDataArray*>(counts), static_cast<vtkDataArray*>(isLeaf) })
  {
    a->SetNumberOfTuples(cellsPerBox * numBoxes);
  }
  // Corner k has x from bit 0, y from bit 1, z from bit 2.
  static const vtkIdType edges[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 },
    { 1, 3 }, { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
  // Counter-clockwise seen from outside.
  static const vtkIdType sides[6][4] = { { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 },
    { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 } };
  for (vtkIdType b = 0; b < numBoxes; ++b)
  {
    const size_t node = shown[b];
    const core::BVHNode& n = bvh.nodes[node];
    for (int k = 0; k < 8; ++k)
    {
      boxPoints->SetPoint(8 * b + k, (k & 1) ? n.max.x : n.min.x, (k & 2) ? n.max.y : n.min.y,
        (k & 4) ? n.max.z : n.min.z);
    }
    for (int c = 0; c < cellsPerBox; ++c)
    {
      const vtkIdType cell = cellsPerBox * b + c;
      if (faces)
      {
        const vtkIdType ids[4] = { 8 * b + sides[c][0], 8 * b + sides[c][1], 8 * b + sides[c][2],
          8 * b + sides[c][3] };
        cells->InsertNextCell(4, ids);
      }
      else
      {
        const vtkIdType ids[2] = { 8 * b + edges[c][0], 8 * b + edges[c][1] };
        cells->InsertNextCell(2, ids);
      }
      nodeIds->SetValue(cell, static_cast<vtkIdType>(node));
      depths->SetValue(cell, depth[node]);
      counts->SetValue(cell, primitives[node]);
      isLeaf->SetValue(cell, n.isLeaf() ? 1 : 0);
    }
  }
  output->SetPoints(boxPoints);
  if (faces)
  {
    output->SetPolys(cells);
  }
  else
  {
    output->SetLines(cells);
  }
  vtkCellData* cd = output->GetCellData();
  cd->AddArray(nodeIds);
  cd->AddArray(depths);
  cd->AddArray(counts);
  cd->AddArray(isLeaf);
  return 1;
}

//------------------------------------------------------------------------------
void vtkBVHBoxes::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Level: " << this->Level << "\n";
  os << indent << "LeavesOnly: " << this->LeavesOnly << "\n";
  os << indent << "OutputStyle: " << (this->OutputStyle == FACES ? "FACES" : "OUTLINE") << "\n";
  os << indent << "BuildQuality: " << this->BuildQuality << "\n";
  os << indent << "MaximumLeafSize: " << this->MaximumLeafSize << "\n";
  os << indent << "NumberOfNodes: " << this->NumberOfNodes << "\n";
  os << indent << "NumberOfLeaves: " << this->NumberOfLeaves << "\n";
  os << indent << "MaximumDepth: " << this->MaximumDepth << "\n";
  os << indent << "NumberOfSkippedTriangles: " << this->NumberOfSkippedTriangles << "\n";
}
