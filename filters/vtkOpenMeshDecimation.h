/**
 * @class   vtkOpenMeshDecimation
 * @brief   reduce a triangle mesh with OpenMesh's decimater, within an error bound
 *
 * vtkOpenMeshDecimation collapses halfedges of an OpenMesh mesh in the order
 * of their quadric error (Garland-Heckbert, area-weighted, with boundary
 * planes on open edges) until a target is met:
 *
 * - TARGET_REDUCTION: remove TargetReduction of the triangles (default 0.9,
 *   like vtkQuadricDecimation);
 * - TARGET_COUNT: keep TargetNumberOfTriangles triangles;
 * - ERROR_BOUND: collapse as long as MaximumError allows.
 *
 * Each target is met exactly (give or take one triangle: a collapse removes
 * two, or one on a boundary) unless the limits stop the decimater first:
 *
 * - MaximumError (world units, default unbounded): a two-sided distance
 *   bound. No input vertex ends up farther than this from the decimated
 *   surface (exact), nor any input face centroid or edge midpoint; and no
 *   centroid or edge midpoint of a decimated face lies farther than this
 *   from the input surface. Between those samples the distance can exceed
 *   the bound slightly (docs/filters.md gives the measurements). OpenMesh's
 *   ModHausdorffT checks only the first, one-sided, which lets the output
 *   drift far past the bound. (Quadric errors are
 *   area-weighted, so they cannot serve as a distance bound.);
 * - MaximumNormalDeviation (degrees, default 180 = off): no face normal turns
 *   by more than this (ModNormalDeviationT); faces never flip in any case
 *   (ModNormalFlippingT) -- a ray tracer would see them from the back;
 * - MaximumAspectRatio (longest edge over its height, default 0 = off): no
 *   collapse may create a triangle worse than this (ModAspectRatioT);
 * - PreserveBoundaries: boundary vertices are never removed.
 *
 * Halfedge collapses keep surviving vertices where they are, so every output
 * point is an input point and all point data is carried unchanged. Cell data
 * is carried from the input face each output triangle descends from, except
 * cell normals, which no longer hold; the names of arrays not carried are
 * listed in the output's field data string array "DroppedArrays" (as
 * "cell:Name" or "point:Name"), along with any array shorter than its
 * points or cells (malformed input, never read past its end).
 *
 * Polygons and strips are triangulated first; vertices and lines are
 * dropped (counted in field data). Faces OpenMesh's halfedge structure
 * cannot hold (on non-manifold edges or vertices) are passed through
 * unchanged and their points are locked. Points are not welded: run
 * vtkOpenMeshClean first on meshes with duplicated points (texture seams),
 * or the seams decimate as boundaries.
 *
 * Field data of the output: "NumberOfInputTriangles", "NumberOfOutputTriangles",
 * "NumberOfPassedThroughFaces", "NumberOfLockedVertices",
 * "NumberOfDroppedVerts", "NumberOfDroppedLines", "NumberOfInvalidCells"
 * (polygons or strips with < 3 points or point ids out of range, skipped),
 * "DroppedArrays".
 *
 * Empty input, input without polygons, or faces using non-finite points give
 * an error and an empty output.
 *
 * @sa vtkQuadricDecimation vtkDecimatePro vtkOpenMeshClean
 */
#ifndef vtkOpenMeshDecimation_h
#define vtkOpenMeshDecimation_h

#include "vtkPolyDataAlgorithm.h"
#include "vtkrtFiltersModule.h" // for export macro

class VTKRTFILTERS_EXPORT vtkOpenMeshDecimation : public vtkPolyDataAlgorithm
{
public:
  static vtkOpenMeshDecimation* New();
  vtkTypeMacro(vtkOpenMeshDecimation, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum TargetModes
  {
    TARGET_REDUCTION = 0,
    TARGET_COUNT = 1,
    ERROR_BOUND = 2
  };

  ///@{
  /**
   * What ends the decimation (default TARGET_REDUCTION).
   */
  vtkSetClampMacro(TargetMode, int, TARGET_REDUCTION, ERROR_BOUND);
  vtkGetMacro(TargetMode, int);
  void SetTargetModeToReduction() { this->SetTargetMode(TARGET_REDUCTION); }
  void SetTargetModeToCount() { this->SetTargetMode(TARGET_COUNT); }
  void SetTargetModeToErrorBound() { this->SetTargetMode(ERROR_BOUND); }
  ///@}

  ///@{
  /**
   * Fraction of the input triangles to remove in TARGET_REDUCTION mode
   * (default 0.9).
   */
  vtkSetClampMacro(TargetReduction, double, 0.0, 1.0);
  vtkGetMacro(TargetReduction, double);
  ///@}

  ///@{
  /**
   * Number of triangles to keep in TARGET_COUNT mode (default 1000).
   */
  vtkSetClampMacro(TargetNumberOfTriangles, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(TargetNumberOfTriangles, vtkIdType);
  ///@}

  ///@{
  /**
   * Two-sided distance bound, in world units, between input and output
   * surfaces (see the class description; default VTK_DOUBLE_MAX: unbounded).
   * Required by ERROR_BOUND mode.
   */
  vtkSetClampMacro(MaximumError, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumError, double);
  ///@}

  ///@{
  /**
   * Largest change of a face normal, in degrees (default 180: off).
   */
  vtkSetClampMacro(MaximumNormalDeviation, double, 0.0, 180.0);
  vtkGetMacro(MaximumNormalDeviation, double);
  ///@}

  ///@{
  /**
   * Worst triangle shape a collapse may create: longest edge over its
   * height (default 0: off; a right isosceles triangle has 2).
   */
  vtkSetClampMacro(MaximumAspectRatio, double, 0.0, VTK_FLOAT_MAX);
  vtkGetMacro(MaximumAspectRatio, double);
  ///@}

  ///@{
  /**
   * Never remove boundary vertices (default off).
   */
  vtkSetMacro(PreserveBoundaries, bool);
  vtkGetMacro(PreserveBoundaries, bool);
  vtkBooleanMacro(PreserveBoundaries, bool);
  ///@}

  ///@{
  /**
   * Weight of the boundary planes in the quadrics: each open edge adds the
   * plane through it perpendicular to its face, weighted by the squared edge
   * length times this (default 1; 0 drops them, as OpenMesh's ModQuadricT
   * does). They keep open rims from drifting.
   */
  vtkSetClampMacro(BoundaryConstraintWeight, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(BoundaryConstraintWeight, double);
  ///@}

  ///@{
  /**
   * What the last execution did.
   */
  vtkGetMacro(NumberOfInputTriangles, vtkIdType);
  vtkGetMacro(NumberOfOutputTriangles, vtkIdType);
  vtkGetMacro(NumberOfPassedThroughFaces, vtkIdType);
  vtkGetMacro(NumberOfLockedVertices, vtkIdType);
  ///@}

protected:
  vtkOpenMeshDecimation() = default;
  ~vtkOpenMeshDecimation() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int TargetMode = TARGET_REDUCTION;
  double TargetReduction = 0.9;
  vtkIdType TargetNumberOfTriangles = 1000;
  double MaximumError = VTK_DOUBLE_MAX;
  double MaximumNormalDeviation = 180.0;
  double MaximumAspectRatio = 0.0;
  bool PreserveBoundaries = false;
  double BoundaryConstraintWeight = 1.0;

  vtkIdType NumberOfInputTriangles = 0;
  vtkIdType NumberOfOutputTriangles = 0;
  vtkIdType NumberOfPassedThroughFaces = 0;
  vtkIdType NumberOfLockedVertices = 0;

private:
  // The target, in triangles of the whole output, of TargetMode.
  vtkIdType TargetTriangles() const;

  vtkOpenMeshDecimation(const vtkOpenMeshDecimation&) = delete;
  void operator=(const vtkOpenMeshDecimation&) = delete;
};

#endif
