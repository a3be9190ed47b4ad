#include "vtkOpenMeshDecimation.h"

#include "vtkOpenMeshInternals.h"

#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkGenericCell.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalDeviationT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <memory>
#include <queue>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkOpenMeshDecimation);

namespace
{
using Mesh = vtkrt_filters::OpenMeshTriMesh;
using Point = Mesh::Point;
using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;
using vtkrt_filters::Triangle;

// Squared distance from p to triangle abc (closest point by Voronoi region,
// after Ericson, Real-Time Collision Detection, 5.1.5).
double PointTriangleDistance2(const Point& p, const Point& a, const Point& b, const Point& c)
{
  const Point ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab | ap, d2 = ac | ap;
  if (d1 <= 0 && d2 <= 0)
  {
    return ap.sqrnorm();
  }
  const Point bp = p - b;
  const double d3 = ab | bp, d4 = ac | bp;
  if (d3 >= 0 && d4 <= d3)
  {
    return bp.sqrnorm();
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double v = d1 / (d1 - d3);
    return (p - (a + v * ab)).sqrnorm();
  }
  const Point cp = p - c;
  const double d5 = ab | cp, d6 = ac | cp;
  if (d6 >= 0 && d5 <= d6)
  {
    return cp.sqrnorm();
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double w = d2 / (d2 - d6);
    return (p - (a + w * ac)).sqrnorm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (p - (b + w * (c - b))).sqrnorm();
  }
  const double denom = 1.0 / (va + vb + vc);
  if (!std::isfinite(denom))
  {
    // Degenerate triangle: the nearest of its edges.
    auto segment = [&p](const Point& s, const Point& e)
    {
      const Point d = e - s;
      const double len2 = d.sqrnorm();
      const double t = len2 > 0 ? std::min(1.0, std::max(0.0, ((p - s) | d) / len2)) : 0.0;
      return (p - (s + t * d)).sqrnorm();
    };
    return std::min({ segment(a, b), segment(b, c), segment(c, a) });
  }
  const double v = vb * denom, w = vc * denom;
  return (p - (a + v * ab + w * ac)).sqrnorm();
}

void FacePoints(const Mesh& mesh, Mesh::FaceHandle f, Point& a, Point& b, Point& c)
{
  auto fv = mesh.cfv_iter(f);
  a = mesh.point(*fv);
  b = mesh.point(*(++fv));
  c = mesh.point(*(++fv));
}

// OpenMesh's topological collapse test (BaseDecimaterT::is_collapse_legal,
// protected there), without the feature-edge rule this filter does not use.
bool IsCollapseLegal(Mesh& mesh, const CollapseInfo& ci)
{
  if (mesh.status(ci.v0).locked() || !mesh.is_collapse_ok(ci.v0v1))
  {
    return false;
  }
  if (ci.vl.is_valid() && ci.vr.is_valid() && mesh.find_halfedge(ci.vl, ci.vr).is_valid() &&
    mesh.valence(ci.vl) == 3 && mesh.valence(ci.vr) == 3)
  {
    return false;
  }
  if (mesh.is_boundary(ci.v0))
  {
    // Never pull a boundary vertex inside, and only along the boundary.
    if (!mesh.is_boundary(ci.v1) || (ci.vl.is_valid() && ci.vr.is_valid()))
    {
      return false;
    }
  }
  // At least two faces at v0.
  return mesh.cw_rotated_halfedge_handle(mesh.cw_rotated_halfedge_handle(ci.v0v1)) != ci.v0v1;
}

// Keeps the decimated surface within MaximumError of the input, both ways,
// on samples: every input sample (face centroids, edge midpoints, removed
// vertices) stays within the bound of some face around it, and every new
// face's centroid and edge midpoints stay within the bound of the input
// surface. OpenMesh's ModHausdorffT only does the first, with removed
// vertices only, which let the output wander far past the bound at holes
// (docs/filters.md).
class SurfaceDistanceGuard
{
public:
  SurfaceDistanceGuard(Mesh& mesh, double tolerance, vtkStaticCellLocator* input)
    : TheMesh(mesh)
    , Tolerance2(tolerance * tolerance)
    , Tolerance(tolerance)
    , Input(input)
  {
    // The input triangles, by face index (faces are not yet garbage
    // collected, so face indices stay valid through the decimation).
    this->InputPoints.reserve(mesh.n_vertices());
    for (const auto v : mesh.vertices())
    {
      this->InputPoints.push_back(mesh.point(v));
    }
    this->InputFaces.resize(mesh.n_faces());
    this->FaceOfVertex.assign(mesh.n_vertices(), -1);
    mesh.add_property(this->Samples);
    for (const auto f : mesh.faces())
    {
      int k = 0;
      for (const auto v : mesh.fv_range(f))
      {
        this->InputFaces[f.idx()][k++] = v.idx();
        this->FaceOfVertex[v.idx()] = f.idx();
      }
      Point a, b, c;
      FacePoints(mesh, f, a, b, c);
      mesh.property(this->Samples, f).push_back(Sample{ (a + b + c) / 3.0, f.idx() });
    }
    for (const auto e : mesh.edges())
    {
      const auto h = mesh.halfedge_handle(e, 0);
      auto f = mesh.face_handle(h);
      if (!f.is_valid())
      {
        f = mesh.face_handle(mesh.opposite_halfedge_handle(h));
      }
      mesh.property(this->Samples, f)
        .push_back(Sample{
          0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))),
          f.idx() });
    }
    this->CandidateStamp.assign(mesh.n_faces(), 0);
  }
  ~SurfaceDistanceGuard() { this->TheMesh.remove_property(this->Samples); }
  SurfaceDistanceGuard(const SurfaceDistanceGuard&) = delete;
  SurfaceDistanceGuard& operator=(const SurfaceDistanceGuard&) = delete;

  bool Allows(const CollapseInfo& ci)
  {
    Mesh& mesh = this->TheMesh;
    // Faces after the collapse: those around v0 and v1, minus fl and fr.
    this->After.clear();
    this->Before.clear();
    for (const auto f : mesh.vf_range(ci.v0))
    {
      this->Before.push_back(f);
      if (f != ci.fl && f != ci.fr)
      {
        this->After.push_back(f);
      }
    }
    const size_t changed = this->After.size();
    for (const auto f : mesh.vf_range(ci.v1))
    {
      if (f != ci.fl && f != ci.fr)
      {
        this->After.push_back(f);
      }
    }
    // The input triangles this region stands for: the first place to look
    // for the input surface near a new face.
    ++this->Stamp;
    this->Candidates.clear();
    auto addCandidate = [this](int face)
    {
      if (face >= 0 && this->CandidateStamp[face] != this->Stamp)
      {
        this->CandidateStamp[face] = this->Stamp;
        this->Candidates.push_back(face);
      }
    };
    addCandidate(this->FaceOfVertex[ci.v0.idx()]);
    for (const auto f : this->Before)
    {
      for (const Sample& sample : mesh.property(this->Samples, f))
      {
        addCandidate(sample.Face);
      }
    }

    mesh.set_point(ci.v0, ci.p1); // simulate
    auto nearOutput = [&](const Point& p)
    {
      for (const auto f : this->After)
      {
        Point a, b, c;
        FacePoints(mesh, f, a, b, c);
        if (PointTriangleDistance2(p, a, b, c) <= this->Tolerance2)
        {
          return true;
        }
      }
      return false;
    };
    bool ok = nearOutput(ci.p0);
    for (size_t i = 0; ok && i < this->Before.size(); ++i)
    {
      for (const Sample& sample : mesh.property(this->Samples, this->Before[i]))
      {
        if (!nearOutput(sample.P))
        {
          ok = false;
          break;
        }
      }
    }
    // Output -> input, on the faces whose shape changes.
    for (size_t i = 0; ok && i < changed; ++i)
    {
      Point a, b, c;
      FacePoints(mesh, this->After[i], a, b, c);
      const Point samples[4] = { (a + b + c) / 3.0, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a) };
      for (const Point& p : samples)
      {
        if (!this->NearInput(p))
        {
          ok = false;
          break;
        }
      }
    }
    mesh.set_point(ci.v0, ci.p0); // undo
    return ok;
  }

  // After the collapse: hand the samples of the faces around v1 (and of the
  // two removed faces, and the removed vertex) to their nearest face.
  void Redistribute(const CollapseInfo& ci)
  {
    Mesh& mesh = this->TheMesh;
    this->Pending.clear();
    this->After.clear();
    auto take = [&](Mesh::FaceHandle f)
    {
      auto& s = mesh.property(this->Samples, f);
      this->Pending.insert(this->Pending.end(), s.begin(), s.end());
      s.clear();
    };
    for (const auto f : mesh.vf_range(ci.v1))
    {
      this->After.push_back(f);
      take(f);
    }
    if (this->After.empty())
    {
      return;
    }
    if (ci.fl.is_valid())
    {
      take(ci.fl);
    }
    if (ci.fr.is_valid())
    {
      take(ci.fr);
    }
    this->Pending.push_back(Sample{ ci.p0, this->FaceOfVertex[ci.v0.idx()] });
    for (const Sample& sample : this->Pending)
    {
      double best = VTK_DOUBLE_MAX;
      Mesh::FaceHandle bestFace = this->After[0];
      for (const auto f : this->After)
      {
        Point a, b, c;
        FacePoints(mesh, f, a, b, c);
        const double d2 = PointTriangleDistance2(sample.P, a, b, c);
        if (d2 < best)
        {
          best = d2;
          bestFace = f;
        }
      }
      mesh.property(this->Samples, bestFace).push_back(sample);
    }
  }

private:
  // Within the bound of the input surface: the region's own input triangles
  // first, the whole input (locator) only when none of them is near.
  bool NearInput(const Point& p)
  {
    for (const int face : this->Candidates)
    {
      const auto& t = this->InputFaces[face];
      if (PointTriangleDistance2(p, this->InputPoints[t[0]], this->InputPoints[t[1]],
            this->InputPoints[t[2]]) <= this->Tolerance2)
      {
        return true;
      }
    }
    double x[3] = { p[0], p[1], p[2] }, closest[3], dist2;
    vtkIdType cellId;
    int subId, inside;
    return this->Input->FindClosestPointWithinRadius(
             x, this->Tolerance, closest, this->Cell, cellId, subId, dist2, inside) != 0;
  }

  struct Sample
  {
    Point P;
    int Face; // the input face it samples (for a removed vertex: one of its faces)
  };

  Mesh& TheMesh;
  double Tolerance2;
  double Tolerance;
  vtkStaticCellLocator* Input;
  vtkNew<vtkGenericCell> Cell;
  OpenMesh::FPropHandleT<std::vector<Sample>> Samples;
  std::vector<Point> InputPoints;
  std::vector<std::array<int, 3>> InputFaces;
  std::vector<int> FaceOfVertex;
  std::vector<unsigned> CandidateStamp;
  unsigned Stamp = 0;
  std::vector<int> Candidates;
  std::vector<Mesh::FaceHandle> Before, After;
  std::vector<Sample> Pending;
};

// Garland-Heckbert quadrics: per vertex, the area-weighted planes of its
// faces, plus, on open boundaries, the plane through each boundary edge
// perpendicular to its face (weighted by the edge's squared length), which
// holds boundaries in place the way the faces hold the surface. OpenMesh's
// ModQuadricT has no boundary term, so the rims of holes drift.
class BoundaryQuadrics
{
public:
  using Quadric = OpenMesh::Geometry::Quadricd;

  BoundaryQuadrics(Mesh& mesh, double boundaryWeight)
    : Quadrics(mesh.n_vertices())
  {
    for (const auto f : mesh.faces())
    {
      Point a, b, c;
      FacePoints(mesh, f, a, b, c);
      Point n = (b - a) % (c - a);
      const double twiceArea = n.norm();
      if (!(twiceArea > 0.0) || !std::isfinite(twiceArea))
      {
        continue;
      }
      n /= twiceArea;
      Quadric q(n[0], n[1], n[2], -(n | a));
      q *= 0.5 * twiceArea;
      for (const auto v : mesh.fv_range(f))
      {
        this->Quadrics[v.idx()] += q;
      }
    }
    if (boundaryWeight <= 0.0)
    {
      return;
    }
    for (const auto h : mesh.halfedges())
    {
      if (!mesh.is_boundary(h))
      {
        continue;
      }
      const auto inner = mesh.opposite_halfedge_handle(h);
      const auto f = mesh.face_handle(inner);
      if (!f.is_valid())
      {
        continue;
      }
      const Point a = mesh.point(mesh.from_vertex_handle(h));
      const Point b = mesh.point(mesh.to_vertex_handle(h));
      Point fa, fb, fc;
      FacePoints(mesh, f, fa, fb, fc);
      const Point faceNormal = (fb - fa) % (fc - fa);
      Point m = (b - a) % faceNormal;
      const double length = m.norm();
      if (!(length > 0.0) || !std::isfinite(length))
      {
        continue;
      }
      m /= length;
      Quadric q(m[0], m[1], m[2], -(m | a));
      q *= boundaryWeight * (b - a).sqrnorm();
      this->Quadrics[mesh.from_vertex_handle(h).idx()] += q;
      this->Quadrics[mesh.to_vertex_handle(h).idx()] += q;
    }
  }

  float Priority(const CollapseInfo& ci) const
  {
    Quadric q = this->Quadrics[ci.v0.idx()];
    q += this->Quadrics[ci.v1.idx()];
    return static_cast<float>(std::max(0.0, q(ci.p1)));
  }

  void Collapsed(const CollapseInfo& ci)
  {
    this->Quadrics[ci.v1.idx()] += this->Quadrics[ci.v0.idx()];
  }

private:
  std::vector<Quadric> Quadrics;
};

struct DecimationLimits
{
  double MaximumError = -1.0; // < 0: unbounded
  double MaximumNormalDeviation = 180.0;
  double MaximumAspectRatio = 0.0;
  double BoundaryWeight = 1.0;
};

// Greedy halfedge collapses in quadric order: OpenMesh's DecimaterT loop,
// rewritten so that the distance guard, which is costly, runs only on the
// collapse about to happen rather than on every candidate the heap weighs
// (a refused halfedge is skipped until its neighbourhood changes).
// OpenMesh's modules still judge normals and shapes.
void Decimate(
  Mesh& mesh, size_t targetFaces, const DecimationLimits& limits, vtkStaticCellLocator* input)
{
  namespace D = OpenMesh::Decimater;
  BoundaryQuadrics quadric(mesh, limits.BoundaryWeight);
  D::ModNormalFlippingT<Mesh> flipping(mesh);
  std::unique_ptr<D::ModNormalDeviationT<Mesh>> deviation;
  std::unique_ptr<D::ModAspectRatioT<Mesh>> aspect;
  std::vector<D::ModBaseT<Mesh>*> binary{ &flipping };
  if (limits.MaximumNormalDeviation < 180.0)
  {
    deviation.reset(
      new D::ModNormalDeviationT<Mesh>(mesh, static_cast<float>(limits.MaximumNormalDeviation)));
    binary.push_back(deviation.get());
  }
  if (limits.MaximumAspectRatio > 0.0)
  {
    aspect.reset(new D::ModAspectRatioT<Mesh>(mesh, static_cast<float>(limits.MaximumAspectRatio)));
    binary.push_back(aspect.get());
  }
  for (auto* m : binary)
  {
    m->initialize();
  }
  std::unique_ptr<SurfaceDistanceGuard> guard;
  if (limits.MaximumError >= 0.0 && input)
  {
    guard.reset(new SurfaceDistanceGuard(mesh, limits.MaximumError, input));
  }

  struct Entry
  {
    float Priority;
    int Vertex;
    unsigned Stamp;
    bool operator<(const Entry& o) const { return this->Priority > o.Priority; } // min-heap
  };
  std::priority_queue<Entry> heap;
  std::vector<unsigned> stamp(mesh.n_vertices(), 0);
  std::vector<Mesh::HalfedgeHandle> target(mesh.n_vertices());
  std::vector<unsigned char> refused(mesh.n_halfedges(), 0);

  // A vertex's best collapse: the cheapest quadric among its outgoing
  // halfedges that passes the topology test and the binary modules. Those
  // tests cost far more than the quadric (OpenMesh's is_collapse_ok
  // dominated profiles), so candidates are tried in quadric order and the
  // first legal one wins.
  std::vector<std::pair<float, Mesh::HalfedgeHandle>> candidates;
  auto heapVertex = [&](Mesh::VertexHandle v)
  {
    ++stamp[v.idx()];
    candidates.clear();
    for (const auto h : mesh.voh_range(v))
    {
      if (!refused[h.idx()])
      {
        const float priority = quadric.Priority(CollapseInfo(mesh, h));
        if (priority >= 0.0f)
        {
          candidates.emplace_back(priority, h);
        }
      }
    }
    std::sort(candidates.begin(), candidates.end(),
      [](const std::pair<float, Mesh::HalfedgeHandle>& x,
        const std::pair<float, Mesh::HalfedgeHandle>& y) { return x.first < y.first; });
    for (const auto& candidate : candidates)
    {
      CollapseInfo ci(mesh, candidate.second);
      if (!IsCollapseLegal(mesh, ci))
      {
        continue;
      }
      bool legal = true;
      for (auto* m : binary)
      {
        if (m->collapse_priority(ci) < 0.0f)
        {
          legal = false;
          break;
        }
      }
      if (legal)
      {
        target[v.idx()] = candidate.second;
        heap.push(Entry{ candidate.first, v.idx(), stamp[v.idx()] });
        return;
      }
    }
  };

  for (const auto v : mesh.vertices())
  {
    heapVertex(v);
  }
  size_t nf = mesh.n_faces();
  std::vector<Mesh::VertexHandle> support;
  while (!heap.empty() && nf > targetFaces)
  {
    const Entry top = heap.top();
    heap.pop();
    const Mesh::VertexHandle v(top.Vertex);
    if (top.Stamp != stamp[top.Vertex] || mesh.status(v).deleted())
    {
      continue; // stale entry
    }
    const Mesh::HalfedgeHandle h = target[top.Vertex];
    CollapseInfo ci(mesh, h);
    if (!IsCollapseLegal(mesh, ci))
    {
      continue;
    }
    if (guard && !guard->Allows(ci))
    {
      refused[h.idx()] = 1;
      heapVertex(v);
      continue;
    }
    support.clear();
    for (const auto w : mesh.vv_range(ci.v0))
    {
      support.push_back(w);
    }
    nf -= (mesh.is_boundary(ci.v0v1) || mesh.is_boundary(ci.v1v0)) ? 1 : 2;
    for (auto* m : binary)
    {
      m->preprocess_collapse(ci);
    }
    mesh.collapse(h);
    for (const auto f : mesh.vf_range(ci.v1))
    {
      mesh.set_normal(f, mesh.calc_face_normal(f));
    }
    quadric.Collapsed(ci);
    for (auto* m : binary)
    {
      m->postprocess_collapse(ci);
    }
    if (guard)
    {
      guard->Redistribute(ci);
    }
    for (const auto w : support)
    {
      for (const auto wh : mesh.voh_range(w))
      {
        refused[wh.idx()] = 0;
      }
      heapVertex(w);
    }
  }
}

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
    Decimate(mesh, static_cast<size_t>(meshTarget), limits, bounded ? locator.Get() : nullptr);
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
