/**
 * @class   vtkSurfaceTriangulation
 * @brief   the triangles of a vtkPolyData's polygons and strips, made once
 *          for whoever draws or picks it
 *
 * vtkRayTracePass (to draw a mesh) and vtkBVHCellLocator (to pick it) both
 * need the same triangles: polygons as fans from their first point (as
 * VTK's raster mapper draws them), strips as VTK draws them, each triangle
 * with its point ids and original cell id. Get() gives the triangulation of
 * a polydata's current geometry, made at most once while the polydata, its
 * points and its cell arrays are unmodified: the triangulation is kept in
 * the polydata's vtkInformation (key TRIANGULATION()), so it is released
 * with the polydata, as VTK keeps a data array's cached ranges in the
 * array's information. A modified attribute array (scalars, normals)
 * keeps it.
 *
 * It also holds the bounds of the finite points and how many points are not
 * finite, which both users need to place the mesh in a local frame.
 *
 * The triangulation itself (point ids, cell ids, subIds, what each triangle
 * is of its cell) is vtkrt::core::SurfaceTriangles
 * (plugin/core/vtkrt/core/SurfaceTriangulation.h); see docs/locator.md.
 *
 * Memory: a kept triangulation holds 12 bytes a triangle for a mesh of
 * triangles only, 25 otherwise, as long as the polydata lives or until
 * Release(); SetCaching(false) keeps none (each user then triangulates
 * for itself).
 *
 * Thread safety: Get() and Release() may be called from several threads at
 * once (one process-wide mutex: one thread looks up or triangulates at a
 * time, the others wait); a triangulation is never changed once made (a
 * modified polydata gets a new one at the next Get(), which replaces the
 * kept one), so it is read without locks.
 */
#ifndef vtkSurfaceTriangulation_h
#define vtkSurfaceTriangulation_h

#include "vtkObject.h"
#include "vtkSmartPointer.h"   // For the Get() result
#include "vtkrtPluginModule.h" // For export macro

#include <memory> // For std::unique_ptr

class vtkInformationObjectBaseKey;
class vtkPolyData;

namespace vtkrt
{
namespace core
{
struct SurfaceTriangles;
}
}

class VTKRTPLUGIN_EXPORT vtkSurfaceTriangulation : public vtkObject
{
public:
  static vtkSurfaceTriangulation* New();
  vtkTypeMacro(vtkSurfaceTriangulation, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The triangulation of pd's current polygons and strips: the one kept
   * with pd while it is current, else a new one (kept in its place when
   * caching is on). Never null.
   */
  static vtkSmartPointer<vtkSurfaceTriangulation> Get(vtkPolyData* pd);

  /**
   * Drops the triangulation kept with pd, if any.
   */
  static void Release(vtkPolyData* pd);

  /**
   * Whether Get() keeps triangulations with their polydata (default on).
   * Off, every Get() triangulates and keeps nothing, and
   * vtkBVHCellLocator extracts its triangles itself.
   */
  static void SetCaching(bool caching);
  static bool GetCaching();

  /**
   * Triangulations made in this process so far (every Get() that did not
   * find a current one).
   */
  static vtkIdType GetNumberOfTriangulations();

  /**
   * The key under which a polydata's information keeps its triangulation.
   */
  static vtkInformationObjectBaseKey* TRIANGULATION();

  /**
   * What the triangulation depends on: the polydata itself, its points and
   * its cell arrays (not its point, cell or field data).
   */
  static vtkMTimeType GetGeometryMTime(vtkPolyData* pd);

  /**
   * Whether this is the triangulation of pd's current geometry.
   */
  bool IsCurrent(vtkPolyData* pd) const;

  ///@{
  /**
   * Triangles; cells of fewer than three points (no triangle) and cells
   * naming a point id outside the points.
   */
  vtkIdType GetNumberOfTriangles() const;
  vtkIdType GetNumberOfDegenerateCells() const;
  vtkIdType GetNumberOfInvalidPointIdCells() const;
  ///@}

  /**
   * Bounds (xmin, xmax, ...) of the finite points; uninitialized (min >
   * max) when there is none.
   */
  void GetFinitePointBounds(double bounds[6]) const;

  /**
   * Points with a NaN or infinite coordinate.
   */
  vtkIdType GetNumberOfNonFinitePoints() const { return this->NonFinitePoints; }

  /**
   * Bytes held by the triangles.
   */
  size_t GetMemorySize() const;

#ifndef __VTK_WRAP__
  /**
   * The triangles, in vtkrt's core form.
   */
  const vtkrt::core::SurfaceTriangles& GetTriangles() const { return *this->Triangles; }
#endif

protected:
  vtkSurfaceTriangulation();
  ~vtkSurfaceTriangulation() override;

  /// Triangulates pd's geometry as it is now.
  void Triangulate(vtkPolyData* pd);
  void ComputeFinitePointBounds(vtkPolyData* pd);

  std::unique_ptr<vtkrt::core::SurfaceTriangles> Triangles;
  double FinitePointBounds[6];
  vtkIdType NonFinitePoints = 0;
  /// What it was made from: the geometry's MTime then, and which objects
  /// held the geometry (a replaced one is another geometry).
  vtkMTimeType SourceMTime = 0;
  const void* SourceParts[5] = { nullptr, nullptr, nullptr, nullptr, nullptr };

private:
  vtkSurfaceTriangulation(const vtkSurfaceTriangulation&) = delete;
  void operator=(const vtkSurfaceTriangulation&) = delete;
};

#endif
