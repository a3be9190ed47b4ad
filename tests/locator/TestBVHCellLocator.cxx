// One executable for the locator tests; the first argument names the case
// (one CTest per case, see CMakeLists.txt).
#include "LocatorTestUtils.h"

#include <cstring>

int TestOracleGeneratedMesh();
int TestOracleBunny();
int TestOracleQuadsStripsPolygons();
int TestOracleUnstructuredGrid();
int TestOracleLinesAndVertices();
int TestRobustExtremeCoordinates();
int TestRobustExtremeScales();
int TestRobustDegenerateCells();
int TestRobustBadInput();
int TestRobustRebuild();
int TestRobustThreads();
int TestContractBadPointIdsPolyData();
int TestContractBadPointIdsUnstructuredGrid();
int TestContractFreshLocatorThreads();
int TestContractZeroLengthSegment();
int TestContractZeroAreaClosestPoint();
int TestContractMovedFloatPoints();
int TestContractReplacedPoints();
int TestContractFindCellOnSurfaces();
int TestContractCellsVTKCannotRead();
int TestRobustLargeMesh();
int TestPickerTriangles();
int TestPickerQuads();
int TestWarpedQuadsAndPolygons();
int TestQueriesClosestPointProbes();
int TestQueriesFirstQueryBuildsNothing();
int TestQueriesAxisParallelSegments();
int TestQueriesBlankedCells();
int TestQueriesCellsOfSeveralTriangles();
int TestQueriesSegmentsInPlane();

int main(int argc, char* argv[])
{
  struct Case
  {
    const char* Name;
    int (*Run)();
  } cases[] = { { "OracleGeneratedMesh", TestOracleGeneratedMesh },
    { "OracleBunny", TestOracleBunny }, { "OracleQuadsStripsPolygons", TestOracleQuadsStripsPolygons },
    { "OracleUnstructuredGrid", TestOracleUnstructuredGrid },
    { "OracleLinesAndVertices", TestOracleLinesAndVertices },
    { "ExtremeCoordinates", TestRobustExtremeCoordinates },
    { "ExtremeScales", TestRobustExtremeScales },
    { "DegenerateCells", TestRobustDegenerateCells }, { "BadInput", TestRobustBadInput },
    { "Rebuild", TestRobustRebuild }, { "Threads", TestRobustThreads },
    { "BadPointIdsPolyData", TestContractBadPointIdsPolyData },
    { "BadPointIdsUnstructuredGrid", TestContractBadPointIdsUnstructuredGrid },
    { "FreshLocatorThreads", TestContractFreshLocatorThreads },
    { "ZeroLengthSegment", TestContractZeroLengthSegment },
    { "ZeroAreaClosestPoint", TestContractZeroAreaClosestPoint },
    { "MovedFloatPoints", TestContractMovedFloatPoints },
    { "ReplacedPoints", TestContractReplacedPoints },
    { "FindCellOnSurfaces", TestContractFindCellOnSurfaces },
    { "CellsVTKCannotRead", TestContractCellsVTKCannotRead },
    { "LargeMesh", TestRobustLargeMesh },
    { "PickerTriangles", TestPickerTriangles }, { "PickerQuads", TestPickerQuads },
    { "WarpedQuadsAndPolygons", TestWarpedQuadsAndPolygons },
    { "QueriesClosestPointProbes", TestQueriesClosestPointProbes },
    { "QueriesFirstQueryBuildsNothing", TestQueriesFirstQueryBuildsNothing },
    { "QueriesAxisParallelSegments", TestQueriesAxisParallelSegments },
    { "QueriesBlankedCells", TestQueriesBlankedCells },
    { "QueriesCellsOfSeveralTriangles", TestQueriesCellsOfSeveralTriangles },
    { "QueriesSegmentsInPlane", TestQueriesSegmentsInPlane } };
  if (argc < 2)
  {
    std::cerr << "usage: " << argv[0] << " CASE" << std::endl;
    return EXIT_FAILURE;
  }
  auto* window = locatortest::InstallOutputWindow();
  for (const auto& c : cases)
  {
    if (std::strcmp(argv[1], c.Name) == 0)
    {
      c.Run();
      // Passing tests print no VTK error or warning.
      LT_CHECK(window->Errors == 0);
      LT_CHECK(window->Warnings == 0);
      return locatortest::Finish(c.Name);
    }
  }
  std::cerr << "unknown case " << argv[1] << std::endl;
  return EXIT_FAILURE;
}
