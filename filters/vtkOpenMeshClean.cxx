#include "vtkOpenMeshClean.h"

#include "vtkOpenMeshInternals.h"

#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkIdList.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"
#include "vtkUnsignedCharArray.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"

#include <algorithm>
#include <deque>
#include <tuple>

vtkStandardNewMacro(vtkOpenMeshClean);

namespace
{
using vtkrt_filters::Triangle;

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

// Relative to the longest edge squared: below this a triangle's height is
// floating-point noise of its edge length.
constexpr double DegenerateRatio = 1e-12;

// Whether `p` is inside the closed surface made of `faces` (kept-face ids):
// the parity of the crossings of a ray. A ray that grazes an edge or a
// vertex is retried in another direction.
bool InsideClosedSurface(const double p[3], vtkPoints* pts, const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, const vtkIdType* faces, size_t count)
{
  static const double directions[3][3] = { { 0.5773502691896258, 0.5773502691896258,
                                             0.5773502691896257 },
    { -0.2672612419124244, 0.5345224838248488, 0.8017837257372732 },
    { 0.7071067811865476, -0.4082482904638631, 0.5773502691896258 } };
  constexpr double eps = 1e-9;
  bool inside = false;
  for (const auto& d : directions)
  {
    bool ambiguous = false;
    size_t crossings = 0;
    for (size_t i = 0; i < count && !ambiguous; ++i)
    {
      const Triangle& tri = triangles[kept[faces[i]]];
      double a[3], b[3], c[3], e1[3], e2[3], h[3], sv[3], q[3];
      pts->GetPoint(tri[0], a);
      pts->GetPoint(tri[1], b);
      pts->GetPoint(tri[2], c);
      vtkMath::Subtract(b, a, e1);
      vtkMath::Subtract(c, a, e2);
      vtkMath::Cross(d, e2, h);
      const double det = vtkMath::Dot(e1, h);
      const double scale = vtkMath::Norm(e1) * vtkMath::Norm(e2);
      if (std::abs(det) <= eps * scale)
      {
        continue; // the ray runs parallel to the face
      }
      vtkMath::Subtract(p, a, sv);
      const double u = vtkMath::Dot(sv, h) / det;
      vtkMath::Cross(sv, e1, q);
      const double v = vtkMath::Dot(d, q) / det;
      const double t = vtkMath::Dot(e2, q) / det;
      if (u < -eps || v < -eps || u + v > 1 + eps || t < -eps * scale)
      {
        continue;
      }
      if (u < eps || v < eps || u + v > 1 - eps || t < eps * scale)
      {
        ambiguous = true; // through an edge or vertex, or p on the face
        break;
      }
      ++crossings;
    }
    inside = crossings % 2 == 1;
    if (!ambiguous)
    {
      break;
    }
  }
  return inside;
}

// Turns each closed patch to face away from the solid it bounds: outward
// (positive enclosed volume) for an outer shell, inward for a cavity's wall,
// that is a patch inside an odd number of other closed patches. Candidates
// for "contains" come from a BVH over the patches' bounds (the core's).
void OrientClosedPatches(vtkPoints* pts, const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, const std::vector<vtkIdType>& patchFaces,
  const std::vector<size_t>& patchStart, const std::vector<unsigned char>& patchClosed,
  std::vector<unsigned char>& flip)
{
  namespace core = vtkrt::core;
  const size_t numPatches = patchClosed.size();
  std::vector<core::AABB<double>> bounds(numPatches); // empty for open patches
  std::vector<double> volume(numPatches, 0.0);
  for (size_t patch = 0; patch < numPatches; ++patch)
  {
    if (!patchClosed[patch])
    {
      continue;
    }
    double origin[3];
    pts->GetPoint(triangles[kept[patchFaces[patchStart[patch]]]][0], origin);
    for (size_t i = patchStart[patch]; i < patchStart[patch + 1]; ++i)
    {
      const vtkIdType f = patchFaces[i];
      const Triangle& tri = triangles[kept[f]];
      double p[3][3];
      for (int k = 0; k < 3; ++k)
      {
        pts->GetPoint(tri[k], p[k]);
        bounds[patch].extend(core::Vec3<double>(p[k][0], p[k][1], p[k][2]));
        for (int c = 0; c < 3; ++c)
        {
          p[k][c] -= origin[c];
        }
      }
      const double det = vtkMath::Determinant3x3(p[0], p[1], p[2]);
      volume[patch] += flip[f] ? -det : det;
    }
  }
  core::BuildOptions options;
  options.numThreads = 1;
  const core::BVH bvh = core::buildBVH(bounds, options); // open patches skipped (empty bounds)
  for (size_t patch = 0; patch < numPatches; ++patch)
  {
    if (!patchClosed[patch])
    {
      continue;
    }
    // A point of this patch: the centroid of its first face.
    const Triangle& tri = triangles[kept[patchFaces[patchStart[patch]]]];
    double probe[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      double q[3];
      pts->GetPoint(tri[k], q);
      for (int c = 0; c < 3; ++c)
      {
        probe[c] += q[c] / 3.0;
      }
    }
    const core::AABB<double>& box = bounds[patch];
    size_t depth = 0;
    core::queryBox(bvh, box,
      [&](std::uint32_t other)
      {
        const core::AABB<double>& outer = bounds[other];
        if (other == patch ||
          !(outer.min.x <= box.min.x && outer.min.y <= box.min.y && outer.min.z <= box.min.z &&
            box.max.x <= outer.max.x && box.max.y <= outer.max.y && box.max.z <= outer.max.z))
        {
          return;
        }
        depth += InsideClosedSurface(probe, pts, triangles, kept,
                   patchFaces.data() + patchStart[other], patchStart[other + 1] - patchStart[other])
          ? 1
          : 0;
      });
    const bool cavity = depth % 2 == 1;
    if ((volume[patch] < 0.0) != cavity)
    {
      for (size_t i = patchStart[patch]; i < patchStart[patch + 1]; ++i)
      {
        flip[patchFaces[i]] ^= 1;
      }
    }
  }
}

} // namespace

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
/// Merges every point into the first point (lowest id) within `tol` of it
/// that is not itself merged, whatever the SMP backend and thread count:
/// VTK 9.1's vtkStaticPointLocator::MergePoints with a tolerance is not
/// deterministic under TBB. The neighbour queries run in parallel, the
/// assignment in id order.
void MergePointsInOrder(
  vtkStaticPointLocator* locator, vtkPoints* pts, double tol, std::vector<vtkIdType>& mergeMap)
{
  const vtkIdType n = static_cast<vtkIdType>(mergeMap.size());
  std::vector<std::vector<vtkIdType>> later(static_cast<std::size_t>(n));
  vtkSMPThreadLocalObject<vtkIdList> found;
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdList* ids = found.Local();
      double p[3];
      for (vtkIdType i = begin; i < end; ++i)
      {
        pts->GetPoint(i, p);
        locator->FindPointsWithinRadius(tol, p, ids);
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
        {
          if (ids->GetId(k) > i)
          {
            later[static_cast<std::size_t>(i)].push_back(ids->GetId(k));
          }
        }
      }
    });
  std::fill(mergeMap.begin(), mergeMap.end(), -1);
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (mergeMap[static_cast<std::size_t>(i)] >= 0)
    {
      continue;
    }
    mergeMap[static_cast<std::size_t>(i)] = i;
    for (vtkIdType j : later[static_cast<std::size_t>(i)])
    {
      if (mergeMap[static_cast<std::size_t>(j)] < 0)
      {
        mergeMap[static_cast<std::size_t>(j)] = i;
      }
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
int vtkOpenMeshClean::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
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
  std::vector<vtkIdType> finiteIds;
  {
    std::vector<unsigned char> finite(numInPoints);
    vtkSMPTools::For(0, numInPoints,
      [&](vtkIdType begin, vtkIdType end)
      {
        double p[3];
        for (vtkIdType i = begin; i < end; ++i)
        {
          inPts->GetPoint(i, p);
          finite[i] = vtkrt_filters::IsFinite(p) ? 1 : 0;
        }
      });
    finiteIds.reserve(numInPoints);
    for (vtkIdType i = 0; i < numInPoints; ++i)
    {
      if (finite[i])
      {
        finiteIds.push_back(i);
      }
    }
  }
  this->NumberOfNonFinitePoints = numInPoints - static_cast<vtkIdType>(finiteIds.size());
  std::vector<vtkIdType> weld(numInPoints, -1); // input id -> representative input id
  if (!finiteIds.empty())
  {
    const vtkIdType nFinite = static_cast<vtkIdType>(finiteIds.size());
    vtkNew<vtkPoints> finitePts;
    finitePts->SetDataTypeToDouble();
    finitePts->SetNumberOfPoints(nFinite);
    vtkSMPTools::For(0, nFinite,
      [&](vtkIdType begin, vtkIdType end)
      {
        double p[3];
        for (vtkIdType i = begin; i < end; ++i)
        {
          inPts->GetPoint(finiteIds[i], p);
          finitePts->SetPoint(i, p);
        }
      });
    double bounds[6];
    finitePts->GetBounds(bounds);
    const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    const double tol =
      this->ToleranceIsAbsolute ? this->AbsoluteTolerance : this->Tolerance * diagonal;

    vtkNew<vtkPolyData> cloud;
    cloud->SetPoints(finitePts);
    vtkNew<vtkStaticPointLocator> locator;
    locator->SetDataSet(cloud);
    locator->BuildLocator();
    std::vector<vtkIdType> mergeMap(nFinite);
    MergePointsInOrder(locator, finitePts, tol, mergeMap);
    for (vtkIdType i = 0; i < nFinite; ++i)
    {
      weld[finiteIds[i]] = finiteIds[mergeMap[i]];
    }
  }

  // 3. Classify faces: non-finite, degenerate (after the weld), kept.
  std::vector<unsigned char> status(numTris, FaceKept);
  vtkSMPTools::For(0, numTris,
    [&](vtkIdType begin, vtkIdType end)
    {
      double p[3][3];
      for (vtkIdType t = begin; t < end; ++t)
      {
        Triangle& tri = soup.Triangles[t];
        bool nonFinite = false;
        for (int k = 0; k < 3; ++k)
        {
          const vtkIdType id = tri[k];
          if (id < 0 || id >= numInPoints || weld[id] < 0)
          {
            nonFinite = true;
            break;
          }
          tri[k] = weld[id];
        }
        if (nonFinite)
        {
          status[t] = FaceNonFinite;
          continue;
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
        {
          status[t] = FaceDegenerate;
          continue;
        }
        for (int k = 0; k < 3; ++k)
        {
          inPts->GetPoint(tri[k], p[k]);
        }
        double n[3];
        vtkrt_filters::TriangleNormal(p[0], p[1], p[2], n);
        const double longest2 = std::max({ vtkMath::Distance2BetweenPoints(p[0], p[1]),
          vtkMath::Distance2BetweenPoints(p[1], p[2]),
          vtkMath::Distance2BetweenPoints(p[2], p[0]) });
        const double cross2 = vtkMath::Dot(n, n);
        const double limit = DegenerateRatio * longest2;
        if (!(cross2 > limit * limit))
        {
          status[t] = FaceDegenerate;
        }
      }
    });

  // 4. Duplicated faces: same point set, whatever the order.
  if (this->RemoveDuplicateFaces)
  {
    std::vector<std::pair<Triangle, vtkIdType>> keys;
    keys.reserve(numTris);
    for (vtkIdType t = 0; t < numTris; ++t)
    {
      if (status[t] == FaceKept)
      {
        Triangle s = soup.Triangles[t];
        std::sort(s.begin(), s.end());
        keys.emplace_back(s, t);
      }
    }
    vtkSMPTools::Sort(keys.begin(), keys.end());
    for (size_t i = 1; i < keys.size(); ++i)
    {
      if (keys[i].first == keys[i - 1].first)
      {
        status[keys[i].second] = FaceDuplicate;
      }
    }
  }

  std::vector<vtkIdType> kept; // kept triangle -> soup index
  kept.reserve(numTris);
  for (vtkIdType t = 0; t < numTris; ++t)
  {
    switch (status[t])
    {
      case FaceKept:
        kept.push_back(t);
        break;
      case FaceNonFinite:
        ++this->NumberOfNonFiniteFaces;
        break;
      case FaceDegenerate:
        ++this->NumberOfDegenerateFaces;
        break;
      default:
        ++this->NumberOfDuplicateFaces;
        break;
    }
  }
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
  if (numFaces == 0)
  {
    vtkErrorMacro("No valid face left: of "
      << numTris << " triangles, " << this->NumberOfNonFiniteFaces << " touch non-finite points, "
      << this->NumberOfDegenerateFaces << " are degenerate and " << this->NumberOfDuplicateFaces
      << " are duplicates.");
    return 1;
  }
  auto face = [&](vtkIdType f) -> const Triangle& { return soup.Triangles[kept[f]]; };

  // 5. Edge table: sorting the 3 uses of every face groups each edge's faces.
  std::vector<EdgeUse> uses(3 * numFaces);
  vtkSMPTools::For(0, numFaces,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType f = begin; f < end; ++f)
      {
        const Triangle& tri = face(f);
        for (int k = 0; k < 3; ++k)
        {
          const vtkIdType a = tri[k];
          const vtkIdType b = tri[(k + 1) % 3];
          uses[3 * f + k] = EdgeUse{ std::min(a, b), std::max(a, b), f, k, a < b };
        }
      }
    });
  vtkSMPTools::Sort(uses.begin(), uses.end(),
    [](const EdgeUse& x, const EdgeUse& y)
    { return std::tie(x.Low, x.High, x.Face) < std::tie(y.Low, y.High, y.Face); });

  std::vector<std::array<Neighbor, 3>> neighbors(numFaces);
  struct EdgeGroup
  {
    size_t Begin;
    size_t End;
  };
  std::vector<EdgeGroup> groups;
  groups.reserve(uses.size() / 2 + 1);
  for (size_t i = 0; i < uses.size();)
  {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].Low == uses[i].Low && uses[j].High == uses[i].High)
    {
      ++j;
    }
    groups.push_back({ i, j });
    if (j - i == 2)
    {
      const EdgeUse& u = uses[i];
      const EdgeUse& v = uses[i + 1];
      const bool same = u.Forward == v.Forward;
      neighbors[u.Face][u.Slot] = Neighbor{ v.Face, same };
      neighbors[v.Face][v.Slot] = Neighbor{ u.Face, same };
    }
    i = j;
  }

  // 6. Orientation: breadth-first over manifold edges, one patch at a time.
  std::vector<unsigned char> flip(numFaces, 0);
  std::vector<vtkIdType> patchOf(numFaces, -1);
  std::vector<vtkIdType> patchFaces; // faces grouped by patch
  std::vector<size_t> patchStart{ 0 };
  std::vector<unsigned char> patchClosed;
  patchFaces.reserve(numFaces);
  {
    std::deque<vtkIdType> queue;
    for (vtkIdType seed = 0; seed < numFaces; ++seed)
    {
      if (patchOf[seed] >= 0)
      {
        continue;
      }
      const vtkIdType patch = this->NumberOfComponents++;
      const size_t first = patchFaces.size();
      patchOf[seed] = patch;
      queue.push_back(seed);
      bool closed = true;
      while (!queue.empty())
      {
        const vtkIdType f = queue.front();
        queue.pop_front();
        patchFaces.push_back(f);
        for (const Neighbor& nb : neighbors[f])
        {
          if (nb.Face < 0)
          {
            closed = false;
            continue;
          }
          const unsigned char wanted = flip[f] ^ (nb.SameDirection ? 1 : 0);
          if (patchOf[nb.Face] < 0)
          {
            patchOf[nb.Face] = patch;
            flip[nb.Face] = this->ConsistentOrientation ? wanted : 0;
            queue.push_back(nb.Face);
          }
          else if (flip[nb.Face] != wanted)
          {
            closed = false; // non-orientable: counted per edge below
          }
        }
      }
      patchStart.push_back(patchFaces.size());
      patchClosed.push_back(closed ? 1 : 0);
      if (!this->ConsistentOrientation)
      {
        continue;
      }
      // Either orientation of a patch is consistent: keep the one that flips
      // fewer input faces (closed patches are settled below).
      size_t flipped = 0;
      for (size_t i = first; i < patchFaces.size(); ++i)
      {
        flipped += flip[patchFaces[i]];
      }
      if (2 * flipped > patchFaces.size() - first)
      {
        for (size_t i = first; i < patchFaces.size(); ++i)
        {
          flip[patchFaces[i]] ^= 1;
        }
      }
    }
  }
  if (this->ConsistentOrientation && this->OrientClosedSurfacesOutward)
  {
    OrientClosedPatches(inPts, soup.Triangles, kept, patchFaces, patchStart, patchClosed, flip);
  }
  for (vtkIdType f = 0; f < numFaces; ++f)
  {
    this->NumberOfFlippedFaces += flip[f];
  }

  // 7. Edge report on the oriented faces.
  std::vector<std::pair<std::array<vtkIdType, 2>, unsigned char>> problemEdges;
  for (const EdgeGroup& g : groups)
  {
    const size_t n = g.End - g.Begin;
    const EdgeUse& u = uses[g.Begin];
    unsigned char type = 0;
    if (n == 1)
    {
      type = BoundaryEdge;
      ++this->NumberOfBoundaryEdges;
    }
    else if (n > 2)
    {
      type = NonManifoldEdge;
      ++this->NumberOfNonManifoldEdges;
    }
    else
    {
      const EdgeUse& v = uses[g.Begin + 1];
      const bool uForward = u.Forward != (flip[u.Face] != 0);
      const bool vForward = v.Forward != (flip[v.Face] != 0);
      if (uForward == vForward)
      {
        type = InconsistentEdge;
        ++this->NumberOfInconsistentEdges;
      }
    }
    if (type && this->GenerateProblemEdges)
    {
      problemEdges.push_back({ { u.Low, u.High }, type });
    }
  }

  // Non-manifold vertices: the faces around a vertex must form one fan
  // (faces chained through shared manifold edges). Corners (face, vertex)
  // joined across manifold edges; a vertex whose corners end in more than
  // one set, or that lies on a non-manifold edge, is non-manifold.
  {
    std::vector<vtkIdType> parent(3 * numFaces);
    for (vtkIdType c = 0; c < 3 * numFaces; ++c)
    {
      parent[c] = c;
    }
    auto find = [&parent](vtkIdType c)
    {
      while (parent[c] != c)
      {
        parent[c] = parent[parent[c]];
        c = parent[c];
      }
      return c;
    };
    auto corner = [&](vtkIdType f, vtkIdType vertex)
    {
      const Triangle& tri = face(f);
      return 3 * f + (tri[0] == vertex ? 0 : tri[1] == vertex ? 1 : 2);
    };
    std::vector<unsigned char> onNonManifoldEdge(numInPoints, 0);
    for (const EdgeGroup& g : groups)
    {
      const EdgeUse& u = uses[g.Begin];
      if (g.End - g.Begin == 2)
      {
        const EdgeUse& v = uses[g.Begin + 1];
        for (vtkIdType end : { u.Low, u.High })
        {
          parent[find(corner(u.Face, end))] = find(corner(v.Face, end));
        }
      }
      else if (g.End - g.Begin > 2)
      {
        onNonManifoldEdge[u.Low] = onNonManifoldEdge[u.High] = 1;
      }
    }
    std::vector<vtkIdType> fan(numInPoints, -1);
    std::vector<unsigned char> nonManifold(onNonManifoldEdge);
    for (vtkIdType c = 0; c < 3 * numFaces; ++c)
    {
      const vtkIdType vertex = face(c / 3)[c % 3];
      const vtkIdType root = find(c);
      if (fan[vertex] < 0)
      {
        fan[vertex] = root;
      }
      else if (fan[vertex] != root)
      {
        nonManifold[vertex] = 1;
      }
    }
    this->NumberOfNonManifoldVertices =
      static_cast<vtkIdType>(std::count(nonManifold.begin(), nonManifold.end(), 1));
  }

  // 8. Output points: the representatives the kept faces use, in input order.
  std::vector<vtkIdType> newId(numInPoints, -1);
  for (vtkIdType f = 0; f < numFaces; ++f)
  {
    for (vtkIdType id : face(f))
    {
      newId[id] = 0;
    }
  }
  vtkIdType numOutPoints = 0;
  for (vtkIdType i = 0; i < numInPoints; ++i)
  {
    if (newId[i] == 0)
    {
      newId[i] = numOutPoints++;
    }
  }
  // A finite point is merged when the weld maps it onto another point.
  for (vtkIdType i = 0; i < numInPoints; ++i)
  {
    if (weld[i] >= 0 && weld[i] != i)
    {
      ++this->NumberOfMergedPoints;
    }
  }

  vtkNew<vtkPoints> outPts;
  if (this->OutputPointsPrecision == SINGLE_PRECISION)
  {
    outPts->SetDataTypeToFloat();
  }
  else if (this->OutputPointsPrecision == DOUBLE_PRECISION)
  {
    outPts->SetDataTypeToDouble();
  }
  else
  {
    outPts->SetDataType(inPts->GetDataType());
  }
  outPts->SetNumberOfPoints(numOutPoints);
  std::vector<vtkIdType> outToIn(numOutPoints);
  for (vtkIdType i = 0; i < numInPoints; ++i)
  {
    if (newId[i] >= 0)
    {
      outToIn[newId[i]] = i;
    }
  }
  std::vector<std::string> dropped;
  vtkrt_filters::GatherPoints(input, outToIn, outPts, output, dropped);

  // 9. Output triangles, oriented, with their cells' data.
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(numFaces + 1);
  connectivity->SetNumberOfValues(3 * numFaces);
  vtkSMPTools::For(0, numFaces + 1,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType f = begin; f < end; ++f)
      {
        offsets->SetValue(f, 3 * f);
        if (f == numFaces)
        {
          continue;
        }
        const Triangle& tri = face(f);
        const vtkIdType a = newId[tri[0]];
        const vtkIdType b = newId[tri[1]];
        const vtkIdType c = newId[tri[2]];
        connectivity->SetValue(3 * f, a);
        connectivity->SetValue(3 * f + 1, flip[f] ? c : b);
        connectivity->SetValue(3 * f + 2, flip[f] ? b : c);
      }
    });
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  output->SetPolys(polys);

  auto inCD = vtkrt_filters::ArraysWithTuples(
    input->GetCellData(), input->GetNumberOfCells(), "cell:", dropped);
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyAllocate(inCD.Get(), numFaces);
  for (vtkIdType f = 0; f < numFaces; ++f)
  {
    outCD->CopyData(inCD.Get(), soup.SourceCells[kept[f]], f);
  }
  if (vtkDataArray* cellNormals = outCD->GetNormals())
  {
    const int nc = cellNormals->GetNumberOfComponents();
    for (vtkIdType f = 0; f < numFaces; ++f)
    {
      if (flip[f])
      {
        for (int c = 0; c < nc; ++c)
        {
          cellNormals->SetComponent(f, c, -cellNormals->GetComponent(f, c));
        }
      }
    }
  }
  if (this->GenerateOriginalCellIds)
  {
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName("vtkOriginalCellIds");
    ids->SetNumberOfValues(numFaces);
    for (vtkIdType f = 0; f < numFaces; ++f)
    {
      ids->SetValue(f, soup.SourceCells[kept[f]]);
    }
    outCD->AddArray(ids);
  }

  // 10. OpenMesh's view of the result: faces its halfedge structure rejects
  // (they sit on non-manifold edges or vertices) and boundary loops.
  {
    vtkrt_filters::OpenMeshErrorMute mute;
    vtkrt_filters::OpenMeshTriMesh mesh;
    mesh.reserve(numOutPoints, 3 * numFaces / 2 + 3, numFaces);
    std::vector<vtkrt_filters::OpenMeshTriMesh::VertexHandle> vh(numOutPoints);
    double p[3];
    for (vtkIdType i = 0; i < numOutPoints; ++i)
    {
      outPts->GetPoint(i, p);
      vh[i] = mesh.add_vertex(vtkrt_filters::OpenMeshTriMesh::Point(p[0], p[1], p[2]));
    }
    const vtkIdType* conn = connectivity->GetPointer(0);
    for (vtkIdType f = 0; f < numFaces; ++f)
    {
      const auto fh = mesh.add_face(vh[conn[3 * f]], vh[conn[3 * f + 1]], vh[conn[3 * f + 2]]);
      if (!fh.is_valid())
      {
        ++this->NumberOfRejectedFaces;
      }
    }
    std::vector<unsigned char> seen(mesh.n_halfedges(), 0);
    for (const auto h : mesh.halfedges())
    {
      if (!mesh.is_boundary(h) || seen[h.idx()])
      {
        continue;
      }
      ++this->NumberOfBoundaryLoops;
      auto walk = h;
      do
      {
        seen[walk.idx()] = 1;
        walk = mesh.next_halfedge_handle(walk);
      } while (walk != h && !seen[walk.idx()]);
    }
  }

  // 11. Report.
  vtkFieldData* fd = output->GetFieldData();
  fd->PassData(input->GetFieldData());
  vtkrt_filters::AddFieldCount(fd, "NumberOfDroppedVerts", this->NumberOfDroppedVerts);
  vtkrt_filters::AddFieldCount(fd, "NumberOfDroppedLines", this->NumberOfDroppedLines);
  vtkrt_filters::AddFieldCount(fd, "NumberOfInvalidCells", this->NumberOfInvalidCells);
  vtkrt_filters::AddFieldCount(fd, "NumberOfMergedPoints", this->NumberOfMergedPoints);
  vtkrt_filters::AddFieldCount(fd, "NumberOfNonFinitePoints", this->NumberOfNonFinitePoints);
  vtkrt_filters::AddFieldCount(fd, "NumberOfNonFiniteFaces", this->NumberOfNonFiniteFaces);
  vtkrt_filters::AddFieldCount(fd, "NumberOfDegenerateFaces", this->NumberOfDegenerateFaces);
  vtkrt_filters::AddFieldCount(fd, "NumberOfDuplicateFaces", this->NumberOfDuplicateFaces);
  vtkrt_filters::AddFieldCount(fd, "NumberOfFlippedFaces", this->NumberOfFlippedFaces);
  vtkrt_filters::AddFieldCount(fd, "NumberOfComponents", this->NumberOfComponents);
  vtkrt_filters::AddFieldCount(fd, "NumberOfBoundaryEdges", this->NumberOfBoundaryEdges);
  vtkrt_filters::AddFieldCount(fd, "NumberOfNonManifoldEdges", this->NumberOfNonManifoldEdges);
  vtkrt_filters::AddFieldCount(fd, "NumberOfInconsistentEdges", this->NumberOfInconsistentEdges);
  vtkrt_filters::AddFieldCount(
    fd, "NumberOfNonManifoldVertices", this->NumberOfNonManifoldVertices);
  vtkrt_filters::AddFieldCount(fd, "NumberOfBoundaryLoops", this->NumberOfBoundaryLoops);
  vtkrt_filters::AddFieldCount(fd, "NumberOfRejectedFaces", this->NumberOfRejectedFaces);
  vtkrt_filters::AddFieldCount(fd, "IsClosedManifold", this->IsClosedManifold() ? 1 : 0);
  vtkrt_filters::AddFieldStrings(fd, "DroppedArrays", dropped);

  if (this->GenerateProblemEdges && !problemEdges.empty())
  {
    edgesOut->SetPoints(outPts);
    vtkNew<vtkCellArray> lines;
    vtkNew<vtkUnsignedCharArray> types;
    types->SetName("EdgeType");
    types->SetNumberOfValues(static_cast<vtkIdType>(problemEdges.size()));
    lines->AllocateExact(
      static_cast<vtkIdType>(problemEdges.size()), 2 * static_cast<vtkIdType>(problemEdges.size()));
    vtkIdType e = 0;
    for (const auto& pe : problemEdges)
    {
      const vtkIdType ids[2] = { newId[pe.first[0]], newId[pe.first[1]] };
      lines->InsertNextCell(2, ids);
      types->SetValue(e++, pe.second);
    }
    edgesOut->SetLines(lines);
    edgesOut->GetCellData()->AddArray(types);
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
