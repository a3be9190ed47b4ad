// Private helpers shared by the filters of vtkrt::Filters: the checks on a
// request's input and output, turning a vtkPolyData's polygons and strips into
// a triangle list, and OpenMesh's mesh type.
#ifndef vtkOpenMeshInternals_h
#define vtkOpenMeshInternals_h

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace vtkrt_filters
{

// Double-precision points: the filters judge geometry in double whatever the
// input's point type.
struct OpenMeshTraits : public OpenMesh::DefaultTraits
{
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using OpenMeshTriMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

// OpenMesh reports rejected faces ("complex edge") on its global error
// stream. The filters count those rejections themselves, so the stream is
// muted for the lifetime of this guard. The stream is process-wide: filters
// running concurrently in several threads may restore it early or late
// (only OpenMesh's messages are affected).
class OpenMeshErrorMute
{
public:
  OpenMeshErrorMute()
    : WasEnabled(omerr().is_enabled())
  {
    omerr().disable();
  }
  ~OpenMeshErrorMute()
  {
    if (this->WasEnabled)
    {
      omerr().enable();
    }
  }
  OpenMeshErrorMute(const OpenMeshErrorMute&) = delete;
  OpenMeshErrorMute& operator=(const OpenMeshErrorMute&) = delete;

private:
  bool WasEnabled;
};

using Triangle = std::array<vtkIdType, 3>;

// The triangles of a polydata's polygons and strips, each with the id of the
// input cell it came from (VTK's cell order: verts, lines, polys, strips).
struct TriangleSoup
{
  std::vector<Triangle> Triangles;
  std::vector<vtkIdType> SourceCells;
  vtkIdType NumberOfDroppedVerts = 0;
  vtkIdType NumberOfDroppedLines = 0;
  vtkIdType NumberOfInvalidCells = 0; // polygons/strips with < 3 points or bad point ids
};

inline bool IsFinite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Newell normal of a polygon (not normalised): robust for non-planar input.
inline void NewellNormal(vtkPoints* pts, const vtkIdType* ids, vtkIdType n, double normal[3])
{
  normal[0] = normal[1] = normal[2] = 0.0;
  double a[3], b[3];
  for (vtkIdType i = 0; i < n; ++i)
  {
    pts->GetPoint(ids[i], a);
    pts->GetPoint(ids[(i + 1) % n], b);
    normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
}

inline void TriangleNormal(const double a[3], const double b[3], const double c[3], double n[3])
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  vtkMath::Cross(u, v, n);
}

// Splits a quad along the diagonal that keeps both triangles facing the
// quad's normal (the only valid one for a non-convex quad); otherwise along
// the shorter diagonal, which gives better-shaped triangles.
inline void TriangulateQuad(
  vtkPoints* pts, const vtkIdType* q, TriangleSoup& soup, vtkIdType cellId)
{
  double p[4][3];
  for (int i = 0; i < 4; ++i)
  {
    pts->GetPoint(q[i], p[i]);
  }
  double nq[3];
  NewellNormal(pts, q, 4, nq);
  auto facesQuad = [&](int i, int j, int k)
  {
    double n[3];
    TriangleNormal(p[i], p[j], p[k], n);
    return vtkMath::Dot(n, nq) > 0.0;
  };
  const bool split02Valid = facesQuad(0, 1, 2) && facesQuad(0, 2, 3);
  const bool split13Valid = facesQuad(0, 1, 3) && facesQuad(1, 2, 3);
  bool use02;
  if (split02Valid != split13Valid)
  {
    use02 = split02Valid;
  }
  else
  {
    use02 =
      vtkMath::Distance2BetweenPoints(p[0], p[2]) <= vtkMath::Distance2BetweenPoints(p[1], p[3]);
  }
  if (use02)
  {
    soup.Triangles.push_back({ q[0], q[1], q[2] });
    soup.Triangles.push_back({ q[0], q[2], q[3] });
  }
  else
  {
    soup.Triangles.push_back({ q[0], q[1], q[3] });
    soup.Triangles.push_back({ q[1], q[2], q[3] });
  }
  soup.SourceCells.push_back(cellId);
  soup.SourceCells.push_back(cellId);
}

inline bool IdsInRange(const vtkIdType* ids, vtkIdType n, vtkIdType numPoints)
{
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (ids[i] < 0 || ids[i] >= numPoints)
    {
      return false;
    }
  }
  return true;
}

// Calls triangulate(ids, n, cellId) on each cell of `cells` that has at least
// 3 points, all below numPoints; the others are counted as invalid in `soup`.
// Cells are numbered on from `cellId`, which is left past the last one, so
// that polygons and strips keep VTK's cell order.
template <class Triangulate>
void ForEachValidCell(vtkCellArray* cells, vtkIdType numPoints, vtkIdType& cellId,
  TriangleSoup& soup, Triangulate&& triangulate)
{
  auto iter = vtk::TakeSmartPointer(cells->NewIterator());
  vtkIdType n;
  const vtkIdType* ids;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell(), ++cellId)
  {
    iter->GetCurrentCell(n, ids);
    if (n < 3 || !IdsInRange(ids, n, numPoints))
    {
      ++soup.NumberOfInvalidCells;
    }
    else
    {
      triangulate(ids, n, cellId);
    }
  }
}

// Triangulates every polygon and strip of `input`. Vertices and lines are
// counted and dropped: a ray tracer hits surfaces only. Cells with fewer
// than 3 points or with point ids out of range are counted as invalid.
inline void TriangulatePolyData(vtkPolyData* input, TriangleSoup& soup)
{
  vtkPoints* pts = input->GetPoints();
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType nVerts = input->GetNumberOfVerts();
  const vtkIdType nLines = input->GetNumberOfLines();
  const vtkIdType nPolys = input->GetNumberOfPolys();
  soup.NumberOfDroppedVerts = nVerts;
  soup.NumberOfDroppedLines = nLines;
  soup.Triangles.reserve(
    static_cast<size_t>(nPolys + input->GetStrips()->GetNumberOfConnectivityIds()));
  soup.SourceCells.reserve(soup.Triangles.capacity());

  vtkNew<vtkPolygon> polygon;
  vtkNew<vtkIdList> localTris;
  vtkIdType cellId = nVerts + nLines;
  ForEachValidCell(input->GetPolys(), numPoints, cellId, soup,
    [&](const vtkIdType* ids, vtkIdType n, vtkIdType polyId)
    {
      if (n == 3)
      {
        soup.Triangles.push_back({ ids[0], ids[1], ids[2] });
        soup.SourceCells.push_back(polyId);
      }
      else if (n == 4)
      {
        TriangulateQuad(pts, ids, soup, polyId);
      }
      else
      {
        // Ear cutting handles non-convex polygons; a fan is the fallback when
        // it gives up (non-planar or self-touching polygons).
        polygon->PointIds->SetNumberOfIds(n);
        polygon->Points->SetNumberOfPoints(n);
        for (vtkIdType i = 0; i < n; ++i)
        {
          polygon->PointIds->SetId(i, ids[i]);
          polygon->Points->SetPoint(i, pts->GetPoint(ids[i]));
        }
        localTris->Reset();
        if (polygon->Triangulate(localTris) && localTris->GetNumberOfIds() == 3 * (n - 2))
        {
          for (vtkIdType t = 0; t < n - 2; ++t)
          {
            soup.Triangles.push_back({ ids[localTris->GetId(3 * t)],
              ids[localTris->GetId(3 * t + 1)], ids[localTris->GetId(3 * t + 2)] });
            soup.SourceCells.push_back(polyId);
          }
        }
        else
        {
          for (vtkIdType t = 1; t + 1 < n; ++t)
          {
            soup.Triangles.push_back({ ids[0], ids[t], ids[t + 1] });
            soup.SourceCells.push_back(polyId);
          }
        }
      }
    });
  ForEachValidCell(input->GetStrips(), numPoints, cellId, soup,
    [&](const vtkIdType* ids, vtkIdType n, vtkIdType stripId)
    {
      // Every other triangle of a strip is wound the other way.
      for (vtkIdType i = 0; i + 2 < n; ++i)
      {
        if (i % 2 == 0)
        {
          soup.Triangles.push_back({ ids[i], ids[i + 1], ids[i + 2] });
        }
        else
        {
          soup.Triangles.push_back({ ids[i + 1], ids[i], ids[i + 2] });
        }
        soup.SourceCells.push_back(stripId);
      }
    });
}

// The request's output polydata on `port`, emptied for a fresh result; null,
// reported on `filter`, when the executive gave none.
inline vtkPolyData* EmptiedOutput(
  vtkObject* filter, vtkInformationVector* outputVector, int port = 0)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, port);
  if (!output)
  {
    vtkErrorWithObjectMacro(filter, "Missing output polydata.");
    return nullptr;
  }
  output->Initialize();
  return output;
}

// The input checks shared by the filters: a polydata with points and with
// polygons or strips to triangulate. Reports the first failure on `filter`,
// the messages ending with the filter's own consequence (`noPoints`,
// `noSurface`), and returns false.
inline bool CheckSurfaceInput(
  vtkObject* filter, vtkPolyData* input, const char* noPoints, const char* noSurface)
{
  if (!input)
  {
    vtkErrorWithObjectMacro(filter, "No input polydata: connect a vtkPolyData to port 0.");
    return false;
  }
  if (input->GetNumberOfPoints() == 0 || !input->GetPoints())
  {
    vtkErrorWithObjectMacro(filter, "Input polydata has no points: " << noPoints << ".");
    return false;
  }
  if (input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    vtkErrorWithObjectMacro(filter,
      "Input polydata has no polygons or triangle strips ("
        << input->GetNumberOfLines() << " lines, " << input->GetNumberOfVerts()
        << " vertex cells): " << noSurface << ".");
    return false;
  }
  return true;
}

// False, reported on `filter`, when triangulating left no triangle: every
// polygon and strip was invalid.
inline bool CheckTriangulation(vtkObject* filter, const TriangleSoup& soup)
{
  if (soup.Triangles.empty())
  {
    vtkErrorWithObjectMacro(filter,
      "Input has no valid polygon or strip (" << soup.NumberOfInvalidCells
                                              << " with < 3 points or bad point ids).");
    return false;
  }
  return true;
}

// A shallow copy of `in` without the arrays that have fewer than `count`
// tuples (malformed input: copying from them would read past their end);
// their names, prefixed, go to `dropped`.
template <class Attributes>
vtkSmartPointer<Attributes> ArraysWithTuples(
  Attributes* in, vtkIdType count, const char* prefix, std::vector<std::string>& dropped)
{
  auto out = vtkSmartPointer<Attributes>::New();
  out->ShallowCopy(in);
  for (int i = out->GetNumberOfArrays() - 1; i >= 0; --i)
  {
    vtkAbstractArray* a = out->GetAbstractArray(i);
    if (a && a->GetNumberOfTuples() < count)
    {
      dropped.push_back(std::string(prefix) + (a->GetName() ? a->GetName() : "(unnamed)"));
      out->RemoveArray(i);
    }
  }
  return out;
}

// Output point i is input point outToIn[i]: copies the coordinates (into
// outPts, already sized) and the point data (arrays too short to index are
// left out and named in `dropped`) onto `output`.
inline void GatherPoints(vtkPolyData* input, const std::vector<vtkIdType>& outToIn,
  vtkPoints* outPts, vtkPolyData* output, std::vector<std::string>& dropped)
{
  vtkPoints* inPts = input->GetPoints();
  const vtkIdType numOutPoints = static_cast<vtkIdType>(outToIn.size());
  vtkSMPTools::For(0, numOutPoints,
    [&](vtkIdType begin, vtkIdType end)
    {
      double p[3];
      for (vtkIdType i = begin; i < end; ++i)
      {
        inPts->GetPoint(outToIn[i], p);
        outPts->SetPoint(i, p);
      }
    });
  output->SetPoints(outPts);

  auto inPD = ArraysWithTuples(
    input->GetPointData(), input->GetNumberOfPoints(), "point:", dropped);
  vtkPointData* outPD = output->GetPointData();
  outPD->CopyAllocate(inPD.Get(), numOutPoints);
  for (vtkIdType i = 0; i < numOutPoints; ++i)
  {
    outPD->CopyData(inPD.Get(), outToIn[i], i);
  }
}

inline void AddFieldCount(vtkFieldData* fd, const char* name, vtkIdType value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->SetNumberOfTuples(1);
  a->SetValue(0, value);
  fd->AddArray(a);
}

inline void AddFieldStrings(
  vtkFieldData* fd, const char* name, const std::vector<std::string>& values)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  for (size_t i = 0; i < values.size(); ++i)
  {
    a->SetValue(static_cast<vtkIdType>(i), values[i]);
  }
  fd->AddArray(a);
}

} // namespace vtkrt_filters

#endif
// VTK-HeaderTest-Exclude: vtkOpenMeshInternals.h
