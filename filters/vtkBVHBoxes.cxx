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

namespace
{
namespace core = vtkrt::core;

// The core's BVH over the soup's triangles and the input's points.
core::BVH BuildTriangleBVH(
  vtkPolyData* input, const vtkrt_filters::TriangleSoup& soup, const core::BuildOptions& options)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
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
  return core::buildTriangleBVH(mesh, options);
}

// Depth and triangle count of every node.
struct NodeSummary
{
  std::vector<int> Depth;
  std::vector<std::uint32_t> Primitives;
};

NodeSummary SummarizeNodes(const core::BVH& bvh)
{
  // Children come after their parent, so one forward sweep sets depths and
  // one backward sweep sums triangles.
  const size_t numNodes = bvh.nodes.size();
  NodeSummary summary;
  summary.Primitives.assign(numNodes, 0);
  summary.Depth.assign(numNodes, 0);
  std::vector<int>& depth = summary.Depth;
  for (size_t i = 0; i < numNodes; ++i)
  {
    const core::BVHNode& n = bvh.nodes[i];
    if (!n.isLeaf())
    {
      depth[n.index] = depth[n.index + 1] = depth[i] + 1;
    }
  }
  std::vector<std::uint32_t>& primitives = summary.Primitives;
  for (size_t i = numNodes; i-- > 0;)
  {
    const core::BVHNode& n = bvh.nodes[i];
    primitives[i] = n.isLeaf() ? n.count : primitives[n.index] + primitives[n.index + 1];
  }
  return summary;
}

// The nodes shown: every leaf, or the nodes at `level` and the leaves above it.
std::vector<size_t> ShownNodes(
  const core::BVH& bvh, const std::vector<int>& depth, bool leavesOnly, int level)
{
  std::vector<size_t> shown;
  for (size_t i = 0; i < bvh.nodes.size(); ++i)
  {
    const bool leaf = bvh.nodes[i].isLeaf();
    if (leavesOnly ? leaf : (depth[i] == level || (leaf && depth[i] < level)))
    {
      shown.push_back(i);
    }
  }
  return shown;
}

// The cell data of the boxes: which node each cell shows, and that node's
// depth, triangle count and kind.
struct BoxCellData
{
  vtkNew<vtkIdTypeArray> NodeIds;
  vtkNew<vtkIntArray> Depths;
  vtkNew<vtkIdTypeArray> Counts;
  vtkNew<vtkUnsignedCharArray> IsLeaf;

  explicit BoxCellData(vtkIdType numCells)
  {
    this->NodeIds->SetName("BVHNodeId");
    this->Depths->SetName("BVHDepth");
    this->Counts->SetName("BVHPrimitiveCount");
    this->IsLeaf->SetName("BVHIsLeaf");
    for (auto* a : { static_cast<vtkDataArray*>(this->NodeIds),
           static_cast<vtkDataArray*>(this->Depths), static_cast<vtkDataArray*>(this->Counts),
           static_cast<vtkDataArray*>(this->IsLeaf) })
    {
      a->SetNumberOfTuples(numCells);
    }
  }

  void AddTo(vtkCellData* cd)
  {
    cd->AddArray(this->NodeIds);
    cd->AddArray(this->Depths);
    cd->AddArray(this->Counts);
    cd->AddArray(this->IsLeaf);
  }
};

// One box per shown node: 8 corners and 6 quads (`faces`) or 12 lines.
void BuildBoxes(const core::BVH& bvh, const NodeSummary& summary,
  const std::vector<size_t>& shown, bool faces, vtkPolyData* output)
{
  const vtkIdType numBoxes = static_cast<vtkIdType>(shown.size());
  const int cellsPerBox = faces ? 6 : 12;
  vtkNew<vtkPoints> boxPoints;
  boxPoints->SetDataTypeToDouble();
  boxPoints->SetNumberOfPoints(8 * numBoxes);
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(cellsPerBox * numBoxes, cellsPerBox * numBoxes * (faces ? 4 : 2));
  BoxCellData data(cellsPerBox * numBoxes);
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
      data.NodeIds->SetValue(cell, static_cast<vtkIdType>(node));
      data.Depths->SetValue(cell, summary.Depth[node]);
      data.Counts->SetValue(cell, summary.Primitives[node]);
      data.IsLeaf->SetValue(cell, n.isLeaf() ? 1 : 0);
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
  data.AddTo(output->GetCellData());
}
} // namespace

//------------------------------------------------------------------------------
int vtkBVHBoxes::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
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
  core::BuildOptions options;
  options.quality = this->BuildQuality == FAST ? core::BuildQuality::Fast
    : this->BuildQuality == HIGH               ? core::BuildQuality::High
                                               : core::BuildQuality::Medium;
  options.maxLeafSize = static_cast<std::uint32_t>(this->MaximumLeafSize);
  options.numThreads = static_cast<unsigned>(vtkSMPTools::GetEstimatedNumberOfThreads());
  const core::BVH bvh = BuildTriangleBVH(input, soup, options);
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

  const NodeSummary summary = SummarizeNodes(bvh);
  const std::vector<size_t> shown = ShownNodes(bvh, summary.Depth, this->LeavesOnly, this->Level);
  BuildBoxes(bvh, summary, shown, this->OutputStyle == FACES, output);
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
