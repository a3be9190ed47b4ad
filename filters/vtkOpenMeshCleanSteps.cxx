#include "vtkOpenMeshCleanSteps.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"
#include "vtkUnsignedCharArray.h"

#include "vtkrt/core/BVHBuild.h"
#include "vtkrt/core/BVHTraversal.h"

#include <algorithm>
#include <deque>
#include <tuple>

namespace vtkrt_filters
{
namespace clean
{
namespace
{
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
vtkIdType WeldPoints(vtkPoints* inPts, bool toleranceIsAbsolute, double absoluteTolerance,
  double relativeTolerance, std::vector<vtkIdType>& weld)
{
  const vtkIdType numInPoints = inPts->GetNumberOfPoints();
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
          finite[i] = IsFinite(p) ? 1 : 0;
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
  weld.assign(numInPoints, -1);
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
      toleranceIsAbsolute ? absoluteTolerance : relativeTolerance * diagonal;

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
  return static_cast<vtkIdType>(finiteIds.size());
}

//------------------------------------------------------------------------------
void ClassifyFaces(vtkPoints* inPts, const std::vector<vtkIdType>& weld,
  std::vector<Triangle>& triangles, std::vector<unsigned char>& status)
{
  const vtkIdType numInPoints = static_cast<vtkIdType>(weld.size());
  const vtkIdType numTris = static_cast<vtkIdType>(triangles.size());
  status.assign(numTris, FaceKept);
  vtkSMPTools::For(0, numTris,
    [&](vtkIdType begin, vtkIdType end)
    {
      double p[3][3];
      for (vtkIdType t = begin; t < end; ++t)
      {
        Triangle& tri = triangles[t];
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
        TriangleNormal(p[0], p[1], p[2], n);
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
}

//------------------------------------------------------------------------------
void MarkDuplicateFaces(const std::vector<Triangle>& triangles, std::vector<unsigned char>& status)
{
  const vtkIdType numTris = static_cast<vtkIdType>(triangles.size());
  std::vector<std::pair<Triangle, vtkIdType>> keys;
  keys.reserve(numTris);
  for (vtkIdType t = 0; t < numTris; ++t)
  {
    if (status[t] == FaceKept)
    {
      Triangle s = triangles[t];
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

//------------------------------------------------------------------------------
void BuildEdgeTable(
  const std::vector<Triangle>& triangles, const std::vector<vtkIdType>& kept, EdgeTable& table)
{
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
  std::vector<EdgeUse>& uses = table.Uses;
  uses.resize(3 * numFaces);
  vtkSMPTools::For(0, numFaces,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType f = begin; f < end; ++f)
      {
        const Triangle& tri = triangles[kept[f]];
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

  std::vector<std::array<Neighbor, 3>>& neighbors = table.Neighbors;
  neighbors.resize(numFaces);
  std::vector<EdgeGroup>& groups = table.Groups;
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
}

//------------------------------------------------------------------------------
void OrientPatches(const EdgeTable& table, vtkIdType numFaces, bool consistent, Patches& patches)
{
  const std::vector<std::array<Neighbor, 3>>& neighbors = table.Neighbors;
  std::vector<unsigned char>& flip = patches.Flip;
  std::vector<vtkIdType>& patchFaces = patches.Faces;
  flip.assign(numFaces, 0);
  std::vector<vtkIdType> patchOf(numFaces, -1);
  patchFaces.reserve(numFaces);
  std::deque<vtkIdType> queue;
  for (vtkIdType seed = 0; seed < numFaces; ++seed)
  {
    if (patchOf[seed] >= 0)
    {
      continue;
    }
    const vtkIdType patch = patches.Count++;
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
          flip[nb.Face] = consistent ? wanted : 0;
          queue.push_back(nb.Face);
        }
        else if (flip[nb.Face] != wanted)
        {
          closed = false; // non-orientable: counted per edge below
        }
      }
    }
    patches.Start.push_back(patchFaces.size());
    patches.Closed.push_back(closed ? 1 : 0);
    if (!consistent)
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

//------------------------------------------------------------------------------
// Turns each closed patch to face away from the solid it bounds: outward
// (positive enclosed volume) for an outer shell, inward for a cavity's wall,
// that is a patch inside an odd number of other closed patches. Candidates
// for "contains" come from a BVH over the patches' bounds (the core's).
void OrientClosedPatches(vtkPoints* pts, const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, Patches& patches)
{
  namespace core = vtkrt::core;
  const std::vector<vtkIdType>& patchFaces = patches.Faces;
  const std::vector<size_t>& patchStart = patches.Start;
  const std::vector<unsigned char>& patchClosed = patches.Closed;
  std::vector<unsigned char>& flip = patches.Flip;
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

//------------------------------------------------------------------------------
EdgeCounts ClassifyEdges(const EdgeTable& table, const std::vector<unsigned char>& flip,
  bool listEdges, std::vector<ProblemEdge>& problemEdges)
{
  const std::vector<EdgeUse>& uses = table.Uses;
  EdgeCounts counts;
  for (const EdgeGroup& g : table.Groups)
  {
    const size_t n = g.End - g.Begin;
    const EdgeUse& u = uses[g.Begin];
    unsigned char type = 0;
    if (n == 1)
    {
      type = BoundaryEdge;
      ++counts.Boundary;
    }
    else if (n > 2)
    {
      type = NonManifoldEdge;
      ++counts.NonManifold;
    }
    else
    {
      const EdgeUse& v = uses[g.Begin + 1];
      const bool uForward = u.Forward != (flip[u.Face] != 0);
      const bool vForward = v.Forward != (flip[v.Face] != 0);
      if (uForward == vForward)
      {
        type = InconsistentEdge;
        ++counts.Inconsistent;
      }
    }
    if (type && listEdges)
    {
      problemEdges.push_back({ { u.Low, u.High }, type });
    }
  }
  return counts;
}

//------------------------------------------------------------------------------
// Non-manifold vertices: the faces around a vertex must form one fan
// (faces chained through shared manifold edges). Corners (face, vertex)
// joined across manifold edges; a vertex whose corners end in more than
// one set, or that lies on a non-manifold edge, is non-manifold.
vtkIdType CountNonManifoldVertices(const EdgeTable& table, const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, vtkIdType numInPoints)
{
  const std::vector<EdgeUse>& uses = table.Uses;
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
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
    const Triangle& tri = triangles[kept[f]];
    return 3 * f + (tri[0] == vertex ? 0 : tri[1] == vertex ? 1 : 2);
  };
  std::vector<unsigned char> onNonManifoldEdge(numInPoints, 0);
  for (const EdgeGroup& g : table.Groups)
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
    const vtkIdType vertex = triangles[kept[c / 3]][c % 3];
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
  return
    static_cast<vtkIdType>(std::count(nonManifold.begin(), nonManifold.end(), 1));
}

//------------------------------------------------------------------------------
vtkIdType NumberOutputPoints(const std::vector<Triangle>& triangles,
  const std::vector<vtkIdType>& kept, std::vector<vtkIdType>& newId)
{
  const vtkIdType numInPoints = static_cast<vtkIdType>(newId.size());
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
  for (vtkIdType f = 0; f < numFaces; ++f)
  {
    for (vtkIdType id : triangles[kept[f]])
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
  return numOutPoints;
}

//------------------------------------------------------------------------------
vtkIdType CountMergedPoints(const std::vector<vtkIdType>& weld)
{
  const vtkIdType numInPoints = static_cast<vtkIdType>(weld.size());
  vtkIdType merged = 0;
  // A finite point is merged when the weld maps it onto another point.
  for (vtkIdType i = 0; i < numInPoints; ++i)
  {
    if (weld[i] >= 0 && weld[i] != i)
    {
      ++merged;
    }
  }
  return merged;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPoints> GatherOutputPoints(vtkPolyData* input, int precision,
  const std::vector<vtkIdType>& newId, vtkIdType numOutPoints, vtkPolyData* output,
  std::vector<std::string>& dropped)
{
  vtkPoints* inPts = input->GetPoints();
  const vtkIdType numInPoints = static_cast<vtkIdType>(newId.size());
  auto outPts = vtkSmartPointer<vtkPoints>::New();
  if (precision == vtkAlgorithm::SINGLE_PRECISION)
  {
    outPts->SetDataTypeToFloat();
  }
  else if (precision == vtkAlgorithm::DOUBLE_PRECISION)
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
  GatherPoints(input, outToIn, outPts, output, dropped);
  return outPts;
}

//------------------------------------------------------------------------------
void BuildTriangles(const std::vector<Triangle>& triangles, const std::vector<vtkIdType>& kept,
  const std::vector<vtkIdType>& newId, const std::vector<unsigned char>& flip,
  vtkIdTypeArray* offsets, vtkIdTypeArray* connectivity)
{
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
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
        const Triangle& tri = triangles[kept[f]];
        const vtkIdType a = newId[tri[0]];
        const vtkIdType b = newId[tri[1]];
        const vtkIdType c = newId[tri[2]];
        connectivity->SetValue(3 * f, a);
        connectivity->SetValue(3 * f + 1, flip[f] ? c : b);
        connectivity->SetValue(3 * f + 2, flip[f] ? b : c);
      }
    });
}

//------------------------------------------------------------------------------
void CopyCellData(vtkPolyData* input, const TriangleSoup& soup,
  const std::vector<vtkIdType>& kept, const std::vector<unsigned char>& flip,
  bool originalCellIds, vtkPolyData* output, std::vector<std::string>& dropped)
{
  const vtkIdType numFaces = static_cast<vtkIdType>(kept.size());
  auto inCD = ArraysWithTuples(
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
  if (originalCellIds)
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
}

//------------------------------------------------------------------------------
void CountOpenMeshRejects(vtkPoints* outPts, const vtkIdType* conn, vtkIdType numFaces,
  vtkIdType& rejectedFaces, vtkIdType& boundaryLoops)
{
  const vtkIdType numOutPoints = outPts->GetNumberOfPoints();
  OpenMeshErrorMute mute;
  OpenMeshTriMesh mesh;
  mesh.reserve(numOutPoints, 3 * numFaces / 2 + 3, numFaces);
  std::vector<OpenMeshTriMesh::VertexHandle> vh(numOutPoints);
  double p[3];
  for (vtkIdType i = 0; i < numOutPoints; ++i)
  {
    outPts->GetPoint(i, p);
    vh[i] = mesh.add_vertex(OpenMeshTriMesh::Point(p[0], p[1], p[2]));
  }
  for (vtkIdType f = 0; f < numFaces; ++f)
  {
    const auto fh = mesh.add_face(vh[conn[3 * f]], vh[conn[3 * f + 1]], vh[conn[3 * f + 2]]);
    if (!fh.is_valid())
    {
      ++rejectedFaces;
    }
  }
  std::vector<unsigned char> seen(mesh.n_halfedges(), 0);
  for (const auto h : mesh.halfedges())
  {
    if (!mesh.is_boundary(h) || seen[h.idx()])
    {
      continue;
    }
    ++boundaryLoops;
    auto walk = h;
    do
    {
      seen[walk.idx()] = 1;
      walk = mesh.next_halfedge_handle(walk);
    } while (walk != h && !seen[walk.idx()]);
  }
}

//------------------------------------------------------------------------------
void BuildProblemEdges(const std::vector<ProblemEdge>& problemEdges,
  const std::vector<vtkIdType>& newId, vtkPoints* outPts, vtkPolyData* edgesOut)
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

} // namespace clean
} // namespace vtkrt_filters
