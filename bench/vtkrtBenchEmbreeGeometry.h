// vtkrtBenchEmbreeGeometry: a vtkPolyData's polygons as an Embree 3
// triangle geometry, for the benchmarks whose peer is Embree.
#ifndef vtkrtBenchEmbreeGeometry_h
#define vtkrtBenchEmbreeGeometry_h

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <vector>

namespace vtkrtBench
{
/// Attaches `mesh`'s polygons (fan triangulated) to `scene` as one
/// committed triangle geometry, in float relative to `origin` (the mesh's
/// centre gives Embree its best precision).
inline void AttachEmbreeTriangles(
  RTCDevice device, RTCScene scene, vtkPolyData* mesh, const double origin[3])
{
  std::vector<unsigned> indices;
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    for (vtkIdType k = 2; k < n; ++k)
    {
      indices.insert(indices.end(), { unsigned(ids[0]), unsigned(ids[k - 1]), unsigned(ids[k]) });
    }
  }
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const vtkIdType points = mesh->GetNumberOfPoints();
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
    geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), points));
  for (vtkIdType i = 0; i < points; ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      v[3 * i + k] = static_cast<float>(p[k] - origin[k]);
    }
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
    geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), indices.size() / 3));
  std::copy(indices.begin(), indices.end(), idx);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
}
}

#endif
