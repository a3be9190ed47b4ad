/**
 * @class   vtkBVHBoxes
 * @brief   the boxes of the ray tracer's BVH over a mesh, one level at a time
 *
 * vtkBVHBoxes builds a bounding volume hierarchy with the builder the vtkrt
 * tracer and locator use (vtkrt::core::buildTriangleBVH, same options) over
 * the input's triangles (polygons and strips are triangulated;
 * vertices and lines are ignored) and outputs the boxes of the nodes at
 * depth Level (the root has depth 0), together with the leaves above that
 * depth, so that the boxes always hold every triangle between them. With
 * LeavesOnly, the output is every leaf instead.
 *
 * Each box is 8 points and either 12 line cells (OUTLINE, the default) or 6
 * outward-facing quads (FACES). Cell data, the same on every cell of a box:
 * "BVHNodeId" (index in the flattened node array), "BVHDepth",
 * "BVHPrimitiveCount" (triangles under the node) and "BVHIsLeaf" (0/1).
 * Field data: "BVHNodeCount", "BVHLeafCount", "BVHMaxDepth",
 * "BVHSkippedTriangles" (degenerate or non-finite, in no leaf) and
 * "BVHSAHCost".
 *
 * Input without points or without polygons/strips gives an error and an
 * empty output.
 *
 * @sa vtkOutlineFilter vtkOBBTree::GenerateRepresentation
 */
#ifndef vtkBVHBoxes_h
#define vtkBVHBoxes_h

#include "vtkPolyDataAlgorithm.h"
#include "vtkrtFiltersModule.h" // for export macro

class VTKRTFILTERS_EXPORT vtkBVHBoxes : public vtkPolyDataAlgorithm
{
public:
  static vtkBVHBoxes* New();
  vtkTypeMacro(vtkBVHBoxes, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Depth of the nodes to show (default 0: the root box). Leaves above this
   * depth are shown too.
   */
  vtkSetClampMacro(Level, int, 0, 64);
  vtkGetMacro(Level, int);
  ///@}

  ///@{
  /**
   * Show every leaf, whatever its depth (default off).
   */
  vtkSetMacro(LeavesOnly, bool);
  vtkGetMacro(LeavesOnly, bool);
  vtkBooleanMacro(LeavesOnly, bool);
  ///@}

  enum OutputStyles
  {
    OUTLINE = 0,
    FACES = 1
  };

  ///@{
  /**
   * Box edges as lines (OUTLINE, default) or box sides as quads (FACES).
   */
  vtkSetClampMacro(OutputStyle, int, OUTLINE, FACES);
  vtkGetMacro(OutputStyle, int);
  void SetOutputStyleToOutline() { this->SetOutputStyle(OUTLINE); }
  void SetOutputStyleToFaces() { this->SetOutputStyle(FACES); }
  ///@}

  enum BuildQualities
  {
    FAST = 0,
    MEDIUM = 1,
    HIGH = 2
  };

  ///@{
  /**
   * The core's builder: FAST (object median), MEDIUM (binned SAH, default,
   * what the tracer uses), HIGH (full-sweep SAH).
   */
  vtkSetClampMacro(BuildQuality, int, FAST, HIGH);
  vtkGetMacro(BuildQuality, int);
  ///@}

  ///@{
  /**
   * Most triangles per leaf (default 8, as vtkRayTracePass).
   */
  vtkSetClampMacro(MaximumLeafSize, int, 1, 1024);
  vtkGetMacro(MaximumLeafSize, int);
  ///@}

  ///@{
  /**
   * The tree of the last execution.
   */
  vtkGetMacro(NumberOfNodes, vtkIdType);
  vtkGetMacro(NumberOfLeaves, vtkIdType);
  vtkGetMacro(MaximumDepth, int);
  vtkGetMacro(NumberOfSkippedTriangles, vtkIdType);
  ///@}

protected:
  vtkBVHBoxes() = default;
  ~vtkBVHBoxes() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Level = 0;
  bool LeavesOnly = false;
  int OutputStyle = OUTLINE;
  int BuildQuality = MEDIUM;
  int MaximumLeafSize = 8;

  vtkIdType NumberOfNodes = 0;
  vtkIdType NumberOfLeaves = 0;
  int MaximumDepth = 0;
  vtkIdType NumberOfSkippedTriangles = 0;

private:
  vtkBVHBoxes(const vtkBVHBoxes&) = delete;
  void operator=(const vtkBVHBoxes&) = delete;
};

#endif
