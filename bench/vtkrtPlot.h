// vtkrtPlot: headless line charts for benchmarks, drawn with VTK's own
// charts (vtkChartXY in a vtkContextView) on a vtkEGLHeadlessRenderWindow
// and written as PNG. No plotting dependency beyond VTK.
//
// A chart is one call: WritePNG(path, title, x axis, y axis, curves), each
// curve picked from a table's rows with SeriesOf.
#ifndef vtkrtPlot_h
#define vtkrtPlot_h

#include <string>
#include <utility>
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

/// The curve `name` through (x(row), y(row)) for every row of `rows` that
/// `keep(row)` accepts, in the rows' order.
template <class Rows, class Keep, class X, class Y>
Series SeriesOf(std::string name, const Rows& rows, Keep keep, X x, Y y)
{
  Series s;
  s.Name = std::move(name);
  for (const auto& row : rows)
  {
    if (keep(row))
    {
      s.X.push_back(x(row));
      s.Y.push_back(y(row));
    }
  }
  return s;
}

/// One axis: its title and its scale.
struct Axis
{
  std::string Label;
  bool Log = false;
  // On a log axis, values <= 0 cannot be drawn: they are raised to this
  // floor (say so in the label when it matters).
  double LogFloor = 1e-9;
  // A linear axis spans the data (padded a little), stretched to 0 when set.
  bool FromZero = false;
};

/// A linear axis spanning the data.
inline Axis Linear(std::string label)
{
  return { std::move(label), false, 1e-9, false };
}

/// A linear axis spanning the data and 0.
inline Axis LinearFromZero(std::string label)
{
  return { std::move(label), false, 1e-9, true };
}

/// A log axis; values below `floor` are drawn at it.
inline Axis Log(std::string label, double floor = 1e-9)
{
  return { std::move(label), true, floor, false };
}

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

/// Draws `curves` under `title` on the axes `x` and `y`, headless, and
/// writes the chart to `path` (PNG). Returns false, with a message on
/// stderr, when no EGL context could be made or the file could not be
/// written. Points with non-finite coordinates are left out.
bool WritePNG(const std::string& path, const std::string& title, const Axis& x, const Axis& y,
  const std::vector<Series>& curves, LegendCorner legend = LegendCorner::OutsideRight);
}

#endif
