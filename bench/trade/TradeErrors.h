// vtkrtBenchTrade's error measures: image, depth, pick and surface errors of
// a candidate against a reference.
#ifndef vtkrtTradeErrors_h
#define vtkrtTradeErrors_h

#include "TradeStage.h"

#include "vtkBVHCellLocator.h"
#include "vtkImageData.h"
#include "vtkPolyData.h"

#include <array>
#include <vector>

class vtkAbstractCellLocator;

namespace vtkrtTrade
{
/// Root mean square difference of two RGB images (0-255); NaN when their
/// sizes differ.
double ImageRMSE(vtkImageData* a, vtkImageData* b);

/// vtkImageDifference's thresholded error (the image-test harness settings).
double ImageDifference(vtkImageData* a, vtkImageData* b);

struct DepthError
{
  double Mean = 0.0;     // world distance between the points under a pixel
  double Coverage = 0.0; // pixels hit by one side only / pixels hit by either
};

DepthError CompareDepth(const Stage& ref, const Stage& cand);

/// Display positions (pixel centres).
using Pixels = std::vector<std::array<double, 2>>;

/// Display positions on a grid over the object's footprint in `ref`.
Pixels PickPixels(const Stage& ref, int grid);

struct Picks
{
  std::vector<char> Hit;
  std::vector<Point> X;
  std::vector<vtkIdType> CellId;
  double SecondsPerPick = kNaN;
};

/// vtkCellPicker at each display position (with `locator` when given).
Picks PickWithPicker(const Stage& st, const Pixels& pixels, vtkAbstractCellLocator* locator);

/// The point under each display position from the stage's depth buffer.
Picks PickFromDepth(const Stage& st, const Pixels& pixels);

struct PickError
{
  double Mean = kNaN, Max = kNaN;
  double Miss = 0.0; // picks hit by one side only / picks hit by either
};

PickError ComparePicks(const Picks& ref, const Picks& cand);

/// Area-uniform random points on the surface (fixed seed).
std::vector<Point> SampleSurface(vtkPolyData* mesh, int count, unsigned seed);

struct GeomError
{
  double Mean = kNaN, Max = kNaN;
};

/// Symmetric sampled surface distance: samples of A to B and of B to A.
GeomError SurfaceDistance(vtkBVHCellLocator* a, const std::vector<Point>& samplesA,
  vtkBVHCellLocator* b, const std::vector<Point>& samplesB);
}

#endif
