#include "vtkOpenMeshDecimationModules.h"

#include "vtkGenericCell.h"
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
#include <vector>

namespace vtkrt_filters
{
namespace decimation
{
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


// OpenMesh's binary decimation modules (normal flips, and when asked normal
// deviation and aspect ratio), each able to veto a collapse.
class BinaryModules
{
public:
  BinaryModules(Mesh& mesh, const DecimationLimits& limits)
    : Flipping(mesh)
  {
    namespace D = OpenMesh::Decimater;
    this->All.push_back(&this->Flipping);
    if (limits.MaximumNormalDeviation < 180.0)
    {
      this->Deviation.reset(
        new D::ModNormalDeviationT<Mesh>(mesh, static_cast<float>(limits.MaximumNormalDeviation)));
      this->All.push_back(this->Deviation.get());
    }
    if (limits.MaximumAspectRatio > 0.0)
    {
      this->Aspect.reset(
        new D::ModAspectRatioT<Mesh>(mesh, static_cast<float>(limits.MaximumAspectRatio)));
      this->All.push_back(this->Aspect.get());
    }
    for (auto* m : this->All)
    {
      m->initialize();
    }
  }

  bool Allow(const CollapseInfo& ci)
  {
    for (auto* m : this->All)
    {
      if (m->collapse_priority(ci) < 0.0f)
      {
        return false;
      }
    }
    return true;
  }

  void Preprocess(const CollapseInfo& ci)
  {
    for (auto* m : this->All)
    {
      m->preprocess_collapse(ci);
    }
  }

  void Postprocess(const CollapseInfo& ci)
  {
    for (auto* m : this->All)
    {
      m->postprocess_collapse(ci);
    }
  }

private:
  OpenMesh::Decimater::ModNormalFlippingT<Mesh> Flipping;
  std::unique_ptr<OpenMesh::Decimater::ModNormalDeviationT<Mesh>> Deviation;
  std::unique_ptr<OpenMesh::Decimater::ModAspectRatioT<Mesh>> Aspect;
  std::vector<OpenMesh::Decimater::ModBaseT<Mesh>*> All;
};

// Each vertex's best collapse, in a min-heap by quadric cost; an entry goes
// stale when its vertex is heaped again. A halfedge the distance guard
// refused is skipped until its neighbourhood changes.
class CollapseQueue
{
public:
  CollapseQueue(Mesh& mesh, BoundaryQuadrics& quadric, BinaryModules& modules)
    : TheMesh(mesh)
    , Quadric(quadric)
    , Modules(modules)
    , Stamp(mesh.n_vertices(), 0)
    , Target(mesh.n_vertices())
    , Refused(mesh.n_halfedges(), 0)
  {
  }

  // A vertex's best collapse: the cheapest quadric among its outgoing
  // halfedges that passes the topology test and the binary modules. Those
  // tests cost far more than the quadric, so candidates are tried in
  // quadric order and the first legal one wins.
  void HeapVertex(Mesh::VertexHandle v)
  {
    Mesh& mesh = this->TheMesh;
    ++this->Stamp[v.idx()];
    this->Candidates.clear();
    for (const auto h : mesh.voh_range(v))
    {
      if (!this->Refused[h.idx()])
      {
        const float priority = this->Quadric.Priority(CollapseInfo(mesh, h));
        if (priority >= 0.0f)
        {
          this->Candidates.emplace_back(priority, h);
        }
      }
    }
    std::sort(this->Candidates.begin(), this->Candidates.end(),
      [](const std::pair<float, Mesh::HalfedgeHandle>& x,
        const std::pair<float, Mesh::HalfedgeHandle>& y) { return x.first < y.first; });
    for (const auto& candidate : this->Candidates)
    {
      CollapseInfo ci(mesh, candidate.second);
      if (!IsCollapseLegal(mesh, ci))
      {
        continue;
      }
      if (this->Modules.Allow(ci))
      {
        this->Target[v.idx()] = candidate.second;
        this->Heap.push(Entry{ candidate.first, v.idx(), this->Stamp[v.idx()] });
        return;
      }
    }
  }

  // The next live entry's vertex and halfedge; false when the heap is empty.
  bool Pop(Mesh::VertexHandle& v, Mesh::HalfedgeHandle& h)
  {
    while (!this->Heap.empty())
    {
      const Entry top = this->Heap.top();
      this->Heap.pop();
      v = Mesh::VertexHandle(top.Vertex);
      if (top.Stamp != this->Stamp[top.Vertex] || this->TheMesh.status(v).deleted())
      {
        continue; // stale entry
      }
      h = this->Target[top.Vertex];
      return true;
    }
    return false;
  }

  void Refuse(Mesh::HalfedgeHandle h) { this->Refused[h.idx()] = 1; }

  // The neighbourhood of `w` changed: its halfedges may be tried again.
  void Reconsider(Mesh::VertexHandle w)
  {
    for (const auto wh : this->TheMesh.voh_range(w))
    {
      this->Refused[wh.idx()] = 0;
    }
    this->HeapVertex(w);
  }

private:
  struct Entry
  {
    float Priority;
    int Vertex;
    unsigned Stamp;
    bool operator<(const Entry& o) const { return this->Priority > o.Priority; } // min-heap
  };

  Mesh& TheMesh;
  BoundaryQuadrics& Quadric;
  BinaryModules& Modules;
  std::priority_queue<Entry> Heap;
  std::vector<unsigned> Stamp;
  std::vector<Mesh::HalfedgeHandle> Target;
  std::vector<unsigned char> Refused;
  std::vector<std::pair<float, Mesh::HalfedgeHandle>> Candidates;
};

} // namespace

// Greedy halfedge collapses in quadric order: OpenMesh's DecimaterT loop,
// rewritten so that the distance guard, which is costly, runs only on the
// collapse about to happen rather than on every candidate the heap weighs.
// OpenMesh's modules still judge normals and shapes.
void Decimate(
  Mesh& mesh, size_t targetFaces, const DecimationLimits& limits, vtkStaticCellLocator* input)
{
  BoundaryQuadrics quadric(mesh, limits.BoundaryWeight);
  BinaryModules modules(mesh, limits);
  std::unique_ptr<SurfaceDistanceGuard> guard;
  if (limits.MaximumError >= 0.0 && input)
  {
    guard.reset(new SurfaceDistanceGuard(mesh, limits.MaximumError, input));
  }
  CollapseQueue queue(mesh, quadric, modules);
  for (const auto v : mesh.vertices())
  {
    queue.HeapVertex(v);
  }
  size_t nf = mesh.n_faces();
  std::vector<Mesh::VertexHandle> support;
  Mesh::VertexHandle v;
  Mesh::HalfedgeHandle h;
  while (nf > targetFaces && queue.Pop(v, h))
  {
    CollapseInfo ci(mesh, h);
    if (!IsCollapseLegal(mesh, ci))
    {
      continue;
    }
    if (guard && !guard->Allows(ci))
    {
      queue.Refuse(h);
      queue.HeapVertex(v);
      continue;
    }
    support.clear();
    for (const auto w : mesh.vv_range(ci.v0))
    {
      support.push_back(w);
    }
    nf -= (mesh.is_boundary(ci.v0v1) || mesh.is_boundary(ci.v1v0)) ? 1 : 2;
    modules.Preprocess(ci);
    mesh.collapse(h);
    for (const auto f : mesh.vf_range(ci.v1))
    {
      mesh.set_normal(f, mesh.calc_face_normal(f));
    }
    quadric.Collapsed(ci);
    modules.Postprocess(ci);
    if (guard)
    {
      guard->Redistribute(ci);
    }
    for (const auto w : support)
    {
      queue.Reconsider(w);
    }
  }
}

} // namespace decimation
} // namespace vtkrt_filters
