// vtkCellPicker with a vtkBVHCellLocator added picks what vtkCellPicker
// picks without it (its brute-force path over every cell), over a grid of
// screen positions of a rendered headless scene: same cell, point, pcoords,
// normal and position; where VTK misses a shared edge, ours hits the surface.
#include "LocatorTestUtils.h"
#include "vtkBVHCellLocator.h"
#include "vtkEGLHeadlessRenderWindow.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellPicker.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

using namespace locatortest;

namespace
{
void CheckPicking(vtkPolyData* pd, const char* name, int step)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(pd);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  vtkNew<vtkEGLHeadlessRenderWindow> win;
  win->SetSize(200, 160);
  win->SetMultiSamples(0);
  win->AddRenderer(ren);
  ren->GetActiveCamera()->Azimuth(25);
  ren->GetActiveCamera()->Elevation(15);
  ren->ResetCamera();
  win->Render();

  vtkNew<vtkBVHCellLocator> bvh;
  bvh->SetDataSet(pd);
  bvh->BuildLocator();
  vtkNew<vtkCellPicker> plain, fast;
  fast->AddLocator(bvh);
  const double diag = Diagonal(pd);
  int same = 0, ties = 0, vtkMisses = 0, picks = 0;
  for (int y = 2; y < 160; y += step)
  {
    for (int x = 2; x < 200; x += step)
    {
      const int a = plain->Pick(x, y, 0, ren);
      const int b = fast->Pick(x, y, 0, ren);
      if (!a && !b)
      {
        continue;
      }
      ++picks;
      double pa[3], pb[3];
      plain->GetPickPosition(pa);
      fast->GetPickPosition(pb);
      if (!a && b)
      {
        // VTK slipped between cells: our point must lie on our cell.
        ++vtkMisses;
        LT_CHECK(DistanceToCell2(pd, fast->GetCellId(), pb) <= 1e-14 * diag * diag);
        continue;
      }
      LT_CHECK_MSG(b, name << " no pick at " << x << "," << y << " where VTK picks cell " << plain->GetCellId());
      if (!b)
      {
        continue;
      }
      LT_CHECK_MSG(std::sqrt(vtkMath::Distance2BetweenPoints(pa, pb)) <= 1e-9 * diag,
        name << " positions differ by " << std::sqrt(vtkMath::Distance2BetweenPoints(pa, pb)) / diag
             << " diag, cells " << plain->GetCellId() << " " << fast->GetCellId());
      if (plain->GetCellId() == fast->GetCellId())
      {
        ++same;
        LT_CHECK(plain->GetPointId() == fast->GetPointId());
        LT_CHECK(plain->GetSubId() == fast->GetSubId());
        const double* ca = plain->GetPCoords();
        const double* cb = fast->GetPCoords();
        for (int k = 0; k < 3; ++k)
        {
          LT_CHECK(std::abs(ca[k] - cb[k]) <= 1e-6);
        }
        double na[3], nb[3];
        plain->GetPickNormal(na);
        fast->GetPickNormal(nb);
        LT_CHECK(vtkMath::Dot(na, nb) > 1.0 - 1e-9);
      }
      else
      {
        // Two cells at the same point (an edge): both contain it.
        ++ties;
        LT_CHECK(DistanceToCell2(pd, plain->GetCellId(), pb) <= 1e-14 * diag * diag);
        LT_CHECK(DistanceToCell2(pd, fast->GetCellId(), pb) <= 1e-14 * diag * diag);
      }
    }
  }
  std::cout << name << ": " << picks << " picks, " << same << " same cell, " << ties
            << " edge ties, " << vtkMisses << " where plain vtkCellPicker misses" << std::endl;
  LT_CHECK(picks > 100);
  LT_CHECK(same >= (picks * 9) / 10);
}
} // namespace

int TestPickerTriangles()
{
  auto pd = LoadBunny();
  if (!pd)
  {
    return 1;
  }
  CheckPicking(pd, "bunny", 6);
  CheckPicking(MakeBumpySphere(30), "generated mesh", 4);
  return 0;
}

int TestPickerQuads()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  plane->SetResolution(15, 11);
  vtkNew<vtkTransform> xf;
  xf->RotateX(35);
  xf->RotateZ(10);
  vtkNew<vtkTransformPolyDataFilter> tf;
  tf->SetInputConnection(plane->GetOutputPort());
  tf->SetTransform(xf);
  tf->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  tf->Update();
  vtkNew<vtkPolyData> pd;
  pd->DeepCopy(tf->GetOutput());
  CheckPicking(pd, "quads", 4);
  return 0;
}
