/**
 * @class   vtkOpenMeshClean
 * @brief   make a polygonal mesh fit for watertight ray tracing
 *
 * vtkOpenMeshClean turns any vtkPolyData surface into a clean triangle mesh:
 *
 * 1. polygons and strips are triangulated (quads along the diagonal that
 *    keeps both halves facing the quad's normal, larger polygons by ear
 *    cutting); vertices and lines are dropped and counted;
 * 2. coincident points are welded, exactly or within a tolerance (relative
 *    to the bounding box diagonal unless ToleranceIsAbsolute);
 * 3. faces touching non-finite (NaN/inf) points, faces with repeated
 *    vertices or no area, and duplicated faces (same three points in any
 *    order) are removed;
 * 4. faces are oriented consistently across every manifold edge, per
 *    edge-connected patch (flipping as few faces as possible), and closed
 *    patches are turned to face away from the solid they bound: outward, or
 *    inward for the wall of a cavity (a closed patch inside an odd number of
 *    other closed patches, by ray parity);
 * 5. the topology is reported: open (boundary) edges, non-manifold edges
 *    (more than two faces), edges whose two faces cannot agree on an
 *    orientation (Moebius-like patches), non-manifold vertices (whose faces
 *    form more than one fan), and, from OpenMesh's halfedge structure, the
 *    faces it cannot hold and the boundary loops (holes).
 *
 * The counts are stored both in the output's field data (one-tuple
 * vtkIdTypeArray named like the getters without "Get", e.g.
 * "NumberOfBoundaryEdges") and on the filter (GetNumberOfBoundaryEdges()
 * after Update()). Point data follows the weld (each output point takes the
 * attributes of the lowest-id input point merged into it); cell data follows
 * the face each triangle came from, with cell normals negated on flipped
 * faces. Unused points are not passed. Arrays with fewer tuples than points
 * (or cells) are malformed: they are dropped and named in the field data
 * string array "DroppedArrays" ("point:Name", "cell:Name").
 *
 * Output port 1 (when GenerateProblemEdges is on) holds the problem edges as
 * two-point lines sharing output 0's points, with a cell array "EdgeType":
 * 1 boundary, 2 non-manifold, 3 inconsistently oriented.
 *
 * Empty input, input without polygons or strips, or input whose every face
 * is invalid gives an error and empty outputs.
 *
 * @sa vtkCleanPolyData vtkTriangleFilter vtkPolyDataNormals vtkOpenMeshDecimation
 */
#ifndef vtkOpenMeshClean_h
#define vtkOpenMeshClean_h

#include "vtkPolyDataAlgorithm.h"
#include "vtkrtFiltersModule.h" // for export macro

class VTKRTFILTERS_EXPORT vtkOpenMeshClean : public vtkPolyDataAlgorithm
{
public:
  static vtkOpenMeshClean* New();
  vtkTypeMacro(vtkOpenMeshClean, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Points closer than this are welded. Tolerance is a fraction of the
   * bounding box diagonal (default 0: only exactly coincident points);
   * AbsoluteTolerance is in world units and used when ToleranceIsAbsolute.
   */
  vtkSetClampMacro(Tolerance, double, 0.0, 1.0);
  vtkGetMacro(Tolerance, double);
  vtkSetClampMacro(AbsoluteTolerance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(AbsoluteTolerance, double);
  vtkSetMacro(ToleranceIsAbsolute, bool);
  vtkGetMacro(ToleranceIsAbsolute, bool);
  vtkBooleanMacro(ToleranceIsAbsolute, bool);
  ///@}

  ///@{
  /**
   * Remove faces made of the same three points as an earlier face, in either
   * orientation (default on): they double-hit rays and make edges non-manifold.
   */
  vtkSetMacro(RemoveDuplicateFaces, bool);
  vtkGetMacro(RemoveDuplicateFaces, bool);
  vtkBooleanMacro(RemoveDuplicateFaces, bool);
  ///@}

  ///@{
  /**
   * Orient faces consistently within each patch (default on), and turn
   * closed patches away from the solid they bound (default on): outward,
   * inward for cavity walls.
   */
  vtkSetMacro(ConsistentOrientation, bool);
  vtkGetMacro(ConsistentOrientation, bool);
  vtkBooleanMacro(ConsistentOrientation, bool);
  vtkSetMacro(OrientClosedSurfacesOutward, bool);
  vtkGetMacro(OrientClosedSurfacesOutward, bool);
  vtkBooleanMacro(OrientClosedSurfacesOutward, bool);
  ///@}

  ///@{
  /**
   * Fill output port 1 with the boundary, non-manifold and inconsistently
   * oriented edges (default on).
   */
  vtkSetMacro(GenerateProblemEdges, bool);
  vtkGetMacro(GenerateProblemEdges, bool);
  vtkBooleanMacro(GenerateProblemEdges, bool);
  ///@}

  ///@{
  /**
   * Add a cell array "vtkOriginalCellIds" holding each triangle's input cell
   * id (default off).
   */
  vtkSetMacro(GenerateOriginalCellIds, bool);
  vtkGetMacro(GenerateOriginalCellIds, bool);
  vtkBooleanMacro(GenerateOriginalCellIds, bool);
  ///@}

  ///@{
  /**
   * Output point precision: vtkAlgorithm::DEFAULT_PRECISION (the input's),
   * SINGLE_PRECISION or DOUBLE_PRECISION.
   */
  vtkSetClampMacro(OutputPointsPrecision, int, SINGLE_PRECISION, DEFAULT_PRECISION);
  vtkGetMacro(OutputPointsPrecision, int);
  ///@}

  /**
   * The problem edges (output port 1).
   */
  vtkPolyData* GetProblemEdges();

  ///@{
  /**
   * What the last execution found and did.
   */
  vtkGetMacro(NumberOfDroppedVerts, vtkIdType);
  vtkGetMacro(NumberOfDroppedLines, vtkIdType);
  vtkGetMacro(NumberOfInvalidCells, vtkIdType);
  vtkGetMacro(NumberOfMergedPoints, vtkIdType);
  vtkGetMacro(NumberOfNonFinitePoints, vtkIdType);
  vtkGetMacro(NumberOfNonFiniteFaces, vtkIdType);
  vtkGetMacro(NumberOfDegenerateFaces, vtkIdType);
  vtkGetMacro(NumberOfDuplicateFaces, vtkIdType);
  vtkGetMacro(NumberOfFlippedFaces, vtkIdType);
  vtkGetMacro(NumberOfComponents, vtkIdType);
  vtkGetMacro(NumberOfBoundaryEdges, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldEdges, vtkIdType);
  vtkGetMacro(NumberOfInconsistentEdges, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldVertices, vtkIdType);
  vtkGetMacro(NumberOfBoundaryLoops, vtkIdType);
  vtkGetMacro(NumberOfRejectedFaces, vtkIdType);
  ///@}

  /**
   * True when the last output is a closed, manifold, consistently oriented
   * surface (no boundary, non-manifold or inconsistent edges, no
   * non-manifold vertices): every ray that enters it also leaves it.
   */
  bool IsClosedManifold() const;

protected:
  vtkOpenMeshClean();
  ~vtkOpenMeshClean() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Tolerance = 0.0;
  double AbsoluteTolerance = 0.0;
  bool ToleranceIsAbsolute = false;
  bool RemoveDuplicateFaces = true;
  bool ConsistentOrientation = true;
  bool OrientClosedSurfacesOutward = true;
  bool GenerateProblemEdges = true;
  bool GenerateOriginalCellIds = false;
  int OutputPointsPrecision = DEFAULT_PRECISION;

  vtkIdType NumberOfDroppedVerts = 0;
  vtkIdType NumberOfDroppedLines = 0;
  vtkIdType NumberOfInvalidCells = 0;
  vtkIdType NumberOfMergedPoints = 0;
  vtkIdType NumberOfNonFinitePoints = 0;
  vtkIdType NumberOfNonFiniteFaces = 0;
  vtkIdType NumberOfDegenerateFaces = 0;
  vtkIdType NumberOfDuplicateFaces = 0;
  vtkIdType NumberOfFlippedFaces = 0;
  vtkIdType NumberOfComponents = 0;
  vtkIdType NumberOfBoundaryEdges = 0;
  vtkIdType NumberOfNonManifoldEdges = 0;
  vtkIdType NumberOfInconsistentEdges = 0;
  vtkIdType NumberOfNonManifoldVertices = 0;
  vtkIdType NumberOfBoundaryLoops = 0;
  vtkIdType NumberOfRejectedFaces = 0;

private:
  vtkOpenMeshClean(const vtkOpenMeshClean&) = delete;
  void operator=(const vtkOpenMeshClean&) = delete;

  void ResetCounts();
};

#endif
