// vtkrtBenchScenes: the scenes and the warm-up that vtkrtBenchPass and
// vtkrtBenchFirstFrame share, so that both measure the same meshes.
#ifndef vtkrtBenchScenes_h
#define vtkrtBenchScenes_h

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <cmath>

namespace vtkrtBench
{
/// A UV sphere with about `triangles` triangles.
inline vtkSmartPointer<vtkPolyData> MeshOf(long triangles)
{
  const int res = static_cast<int>(std::sqrt(triangles / 2.0)) + 2;
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(res);
  source->SetPhiResolution(res);
  source->Update();
  return source->GetOutput();
}

/// Renders one raster point, shaded by neither side's scene shaders: the
/// process's one-time GL start (its first shader compile and link) and the
/// window's buffers at its size are then paid before any measured frame,
/// not by whichever side happens to draw first.
inline void WarmUp(vtkRenderWindow* win)
{
  vtkNew<vtkPolyData> point;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0.0, 0.0, 0.0);
  vtkNew<vtkCellArray> verts;
  const vtkIdType id = 0;
  verts->InsertNextCell(1, &id);
  point->SetPoints(points);
  point->SetVerts(verts);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(point);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  win->AddRenderer(ren);
  win->Render();
  win->WaitForCompletion();
  win->RemoveRenderer(ren);
  ren->ReleaseGraphicsResources(win);
}
}

#endif
