// Private steps of vtkOpenMeshClean's RequestData, in the order it runs them:
// weld, classify faces, find duplicates, build the edge table, orient the
// patches, classify edges and vertices, and assemble the outputs.
#ifndef vtkOpenMeshCleanSteps_h
#define vtkOpenMeshCleanSteps_h

#include "vtkOpenMeshInternals.h"

#include <array>
#include <string>
#include <utility>
#include <vector>

class vtkIdTypeArray;
class vtkPoints;
class vtkPolyData;

namespace vtkrt_filters
{
namespace clean
{

// One side of an edge as seen from a face: the edge (Low < High), the face,
// which of its three edges it is, and whether the face walks it Low -> High.
struct EdgeUse
{
  vtkIdType Low;
  vtkIdType High;
  vtkIdType Face;
  int Slot;
  bool Forward;
};

struct Neighbor
{
  vtkIdType Face = -1;        // the face across a manifold edge, -1 if none
  bool SameDirection = false; // both faces walk the edge the same way
};

enum EdgeType : unsigned char
{
  BoundaryEdge = 1,
  NonManifoldEdge = 2,
  InconsistentEdge = 3
};

// Classifies each triangle once its points are welded: kept, touching a
// non-finite point, or degenerate (repeated point, no area).
enum FaceStatus : unsigned char
{
  FaceKept = 0,
  FaceNonFinite = 1,
  FaceDegenerate = 2,
  FaceDuplicate = 3
};

// The uses of one edge: a run of the sorted edge-use table.
struct EdgeGroup
{
  size_t Begin;
  size_t End;
};

// Every edge of the kept faces, its uses grouped, and each face's neighbour
// across each of its manifold edges.
struct EdgeTable
{
  std::vector<EdgeUse> Uses;
  std::vector<EdgeGroup> Groups;
  std::vector<std::array<Neighbor, 3>> Neighbors;
};

// The kept faces' connected patches (over manifold edges): their faces
// grouped by patch, whether each patch is closed, and which faces to flip.
struct Patches
{
  std::vector<unsigned char> Flip;
  std::vector<vtkIdType> Faces;
  std::vector<size_t> Start{ 0 };
  std::vector<unsigned char> Closed;
  vtkIdType Count = 0;
};

struct EdgeCounts
{
  vtkIdType Boundary = 0;
  vtkIdType NonManifold = 0;
  vtkIdType Inconsistent = 0;
};

using ProblemEdge = std::pair<std::array<vtkIdType, 2>, unsigned char>;

// Maps every input point to the representative it is welded to (an input
// id), or -1 for a non-finite point; returns the number of finite points.
vtkIdType WeldPoints(vtkPoints* inPts, bool toleranceIsAbsolute, double absoluteTolerance,
  double relativeTolerance, std::vector<vtkIdType>& weld);

// Renumbers the triangles onto the weld's representatives and classifies them
// as kept, non-finite or degenerate.
void ClassifyFaces(vtkPoints* inPts, const std::vector<vtkIdType>& weld,
  std::vector<Triangle>& triangles, std::vector<unsigned char>& status);

// Marks as duplicates the kept faces whose point set an earlier kept face has.
void MarkDuplicateFaces(const std::vector<Triangle>& triangles, std::vector<unsigned char>& status);

void BuildEdgeTable(
  const std::vector<Triangle>& triangles, const std::vector<vtkIdType>& kept, EdgeTable& table);

// Grows the patches breadth-first over manifold edges, each made consistent
// (when asked) with the orientation that flips fewer input faces.
void OrientPatches(const EdgeTable& table, vtkIdType numFaces, bool consistent, Patches& patches);

// Turns each closed patch to face away from the solid it bounds.
void OrientClosedPatches(vtkPoints* pts, const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, Patches& patches);

// Counts the boundary, non-manifold and inconsistent edges of the oriented
// faces, and lists them when `listEdges`.
EdgeCounts ClassifyEdges(const EdgeTable& table, const std::vector<unsigned char>& flip,
  bool listEdges, std::vector<ProblemEdge>& problemEdges);

vtkIdType CountNonManifoldVertices(const EdgeTable& table, const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, vtkIdType numInPoints);

// Numbers, in input order, the representatives the kept faces use (-1 for
// the others); returns how many there are.
vtkIdType NumberOutputPoints(const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, std::vector<vtkIdType>& newId);

vtkIdType CountMergedPoints(const std::vector<vtkIdType>& weld);

// The output points, in the precision asked, with the input's point data.
vtkSmartPointer<vtkPoints> GatherOutputPoints(vtkPolyData* input, int precision,
  const std::vector<vtkIdType>& newId, vtkIdType numOutPoints, vtkPolyData* output,
  std::vector<std::string>& dropped);

// The kept triangles, oriented, as a cell array's offsets and connectivity.
void BuildTriangles(const std::vector<Triangle>& triangles, const std::vector<vtkIdType>& kept,
  const std::vector<vtkIdType>& newId, const std::vector<unsigned char>& flip,
  vtkIdTypeArray* offsets, vtkIdTypeArray* connectivity);

// The kept faces' cell data, their normals turned with the faces.
void CopyCellData(vtkPolyData* input, const TriangleSoup& soup,
  const std::vector<vtkIdType>& kept, const std::vector<unsigned char>& flip,
  bool originalCellIds, vtkPolyData* output, std::vector<std::string>& dropped);

// OpenMesh's view of the result: faces its halfedge structure rejects (they
// sit on non-manifold edges or vertices) and boundary loops.
void CountOpenMeshRejects(vtkPoints* outPts, const vtkIdType* connectivity, vtkIdType numFaces,
  vtkIdType& rejectedFaces, vtkIdType& boundaryLoops);

void BuildProblemEdges(const std::vector<ProblemEdge>& problemEdges,
  const std::vector<vtkIdType>& newId, vtkPoints* outPts, vtkPolyData* edgesOut);

} // namespace clean
} // namespace vtkrt_filters

#endif
