// Depth images of the pass's tests: a traced depth buffer against a
// reference (raster's, or the exact depth of the triangles computed in
// double), over the pixels both cover.
#ifndef vtkrtDepthComparison_h
#define vtkrtDepthComparison_h

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStaticCellLocator.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace vtkrtPassTest
{

/// Compares a traced depth image with a reference (exact or raster's) over
/// the pixels whose 3x3 neighbourhood both cover (silhouettes left out): how
/// many pixels, how many traced in front of the reference, the largest
/// difference and where the traced depth is most in front.
struct DepthComparison
{
  long Pixels = 0;
  long InFront = 0;
  double Largest = 0.0;
  double LargestInFront = 0.0; ///< the most a traced depth is in front of the reference
  int InFrontPixel[2] = { 0, 0 }; ///< where it is
  double InFrontDepths[2] = { 0.0, 0.0 }; ///< the reference and the traced depth there
};

template <class Reference>
inline DepthComparison CompareDepth(const std::vector<Reference>& reference, const std::vector<float>& traced,
  int w, int h)
{
  DepthComparison out;
  for (int j = 1; j + 1 < h; ++j)
  {
    for (int i = 1; i + 1 < w; ++i)
    {
      bool covered = true;
      for (int k = -1; k <= 1 && covered; ++k)
      {
        for (int l = -1; l <= 1 && covered; ++l)
        {
          const int n = (j + k) * w + i + l;
          covered = reference[n] < 1.0 && traced[n] < 1.0f;
        }
      }
      if (covered)
      {
        const int n = j * w + i;
        const double ahead = double(reference[n]) - double(traced[n]);
        ++out.Pixels;
        out.InFront += ahead > 0.0;
        out.Largest = std::max(out.Largest, std::abs(ahead));
        if (ahead > out.LargestInFront)
        {
          out.LargestInFront = ahead;
          out.InFrontPixel[0] = i;
          out.InFrontPixel[1] = j;
          out.InFrontDepths[0] = reference[n];
          out.InFrontDepths[1] = traced[n];
        }
      }
    }
  }
  return out;
}

/// What a comparison found, for a check's message.
inline std::string DescribeDepth(const DepthComparison& depth)
{
  std::ostringstream what;
  what << depth.Pixels << " pixels, " << depth.InFront << " in front, largest difference " << depth.Largest;
  if (depth.InFront > 0)
  {
    what << "; most in front by " << depth.LargestInFront << " at pixel (" << depth.InFrontPixel[0] << ", "
         << depth.InFrontPixel[1] << "): reference " << std::setprecision(9) << depth.InFrontDepths[0]
         << ", traced " << depth.InFrontDepths[1];
  }
  return what.str();
}

/// The exact window depth at the center of each pixel of the renderer's
/// w x h viewport: the nearest hit of the pixel's ray with the cells of the
/// actors (no actor transforms), through the camera's composite projection,
/// in double; 1 where the ray misses.
inline std::vector<double> ExactWindowDepths(vtkRenderer* ren, int w, int h, const std::vector<vtkActor*>& actors)
{
  vtkMatrix4x4* project =
    ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(double(w) / h, -1.0, 1.0);
  vtkNew<vtkMatrix4x4> unproject;
  vtkMatrix4x4::Invert(project, unproject);
  std::vector<vtkSmartPointer<vtkStaticCellLocator>> locators;
  for (vtkActor* actor : actors)
  {
    locators.push_back(vtkSmartPointer<vtkStaticCellLocator>::New());
    locators.back()->SetDataSet(actor->GetMapper()->GetInput());
    locators.back()->BuildLocator();
  }
  std::vector<double> depth(static_cast<std::size_t>(w) * h, 1.0);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double ends[2][3];
      for (int k = 0; k < 2; ++k)
      {
        double c[4] = { 2.0 * (i + 0.5) / w - 1.0, 2.0 * (j + 0.5) / h - 1.0, k == 0 ? -1.0 : 1.0, 1.0 };
        unproject->MultiplyPoint(c, c);
        for (int d = 0; d < 3; ++d)
        {
          ends[k][d] = c[d] / c[3];
        }
      }
      double nearest = 2.0;
      double hit[4] = { 0.0, 0.0, 0.0, 1.0 };
      for (vtkStaticCellLocator* locator : locators)
      {
        double t, x[3], pcoords[3];
        int subId;
        if (locator->IntersectWithLine(ends[0], ends[1], 0.0, t, x, pcoords, subId) && t < nearest)
        {
          nearest = t;
          std::copy(x, x + 3, hit);
        }
      }
      if (nearest <= 1.0)
      {
        project->MultiplyPoint(hit, hit);
        depth[j * w + i] = 0.5 * hit[2] / hit[3] + 0.5;
      }
    }
  }
  return depth;
}

} // namespace vtkrtPassTest

#endif
