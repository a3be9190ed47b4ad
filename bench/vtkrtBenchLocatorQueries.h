// vtkrtBenchLocatorQueries: every query of vtkAbstractCellLocator, timed for
// vtkBVHCellLocator and VTK's cell locators side by side (the query part of
// vtkrtBenchLocator; its ray part is vtkrtBenchLocator.cxx).
#ifndef vtkrtBenchLocatorQueries_h
#define vtkrtBenchLocatorQueries_h

#include <string>

class vtkPolyData;

namespace vtkrtBench
{
/// One mesh's tables: steady microseconds a query for each query kind and
/// locator (`rounds` interleaved rounds), then BuildLocator() and the first
/// query of each kind after it. `quick`: fewer probes.
void RunLocatorQueries(const std::string& name, vtkPolyData* pd, int rounds, bool quick);
}

#endif
