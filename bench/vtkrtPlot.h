// vtkrtPlot: headless line charts for benchmarks, drawn with VTK's own
// charts (vtkChartXY in a vtkContextView) on a vtkEGLHeadlessRenderWindow
// and written as PNG. No plotting dependency beyond VTK.
#ifndef vtkrtPlot_h
#define vtkrtPlot_h

#include <string>
#include <vector>

namespace vtkrtPlot
{
/// One curve: points joined in the order given, each drawn with a marker
/// (a single point is drawn as a marker only).
struct Series
{
  std::string Name;
  std::vector<double> X;
  std::vector<double> Y;
  // Line color (0-255); a palette color is used when Color[0] < 0.
  int Color[3] = { -1, 0, 0 };
  bool Dashed = false;
};

/// Where the legend goes inside the plot area (choose where no data is).
enum class LegendCorner
{
  TopRight,
  TopCenter,
  TopLeft,
  BottomLeft,
  BottomCenter,
  BottomRight,
  OutsideRight ///< right of the plot area, which shrinks to make room
};

struct Chart
{
  std::string Title;
  std::string XLabel;
  std::string YLabel;
  bool LogX = false;
  bool LogY = false;
  // On a log axis, values <= 0 cannot be drawn: they are raised to this
  // floor (say so in the axis label when it matters).
  double LogFloor = 1e-9;
  // A linear axis spans the data (padded a little), stretched to 0 when set.
  bool XFromZero = false;
  bool YFromZero = false;
  LegendCorner Legend = LegendCorner::OutsideRight;
  int Width = 880;
  int Height = 480;
  std::vector<Series> Curves;
};

/// Renders `chart` headless and writes it to `path` (PNG). Returns false,
/// with a message on stderr, when no EGL context could be made or the file
/// could not be written. Points with non-finite coordinates are left out.
bool WritePNG(const Chart& chart, const std::string& path);
}

#endif
