"""vtkOpenMeshClean from Python: a triangle soup (every triangle owns its three
points) of a closed sphere is welded back into one closed, manifold surface;
bad input gives a VTK error, not a crash."""
import vtkrt
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkrt_test_util import capture_vtk_output, check

out = capture_vtk_output()
sphere = vtkSphereSource()
sphere.SetThetaResolution(24)
sphere.SetPhiResolution(16)
sphere.Update()
mesh = sphere.GetOutput()

soup_points = vtkPoints()
soup_cells = vtkCellArray()
for c in range(mesh.GetNumberOfCells()):
    ids = mesh.GetCell(c).GetPointIds()
    soup_cells.InsertNextCell(ids.GetNumberOfIds())
    for k in range(ids.GetNumberOfIds()):
        soup_cells.InsertCellPoint(soup_points.InsertNextPoint(mesh.GetPoint(ids.GetId(k))))
soup = vtkPolyData()
soup.SetPoints(soup_points)
soup.SetPolys(soup_cells)

clean = vtkrt.vtkOpenMeshClean()
clean.SetInputData(soup)
clean.Update()
cleaned = clean.GetOutput()
check(soup.GetNumberOfPoints() == 3 * mesh.GetNumberOfCells(), "the soup has 3 points per triangle")
check(cleaned.GetNumberOfPoints() == mesh.GetNumberOfPoints(),
      "welded back to the sphere's %d points: %d" % (mesh.GetNumberOfPoints(), cleaned.GetNumberOfPoints()))
check(cleaned.GetNumberOfCells() == mesh.GetNumberOfCells(), "no triangle lost")
check(out.GetOutput() == "", "VTK printed nothing: %r" % out.GetOutput())

# Bad input: an empty polydata gives an error event, an empty output, no crash.
errors = []
def on_error(obj, event):
    errors.append(event)
bad = vtkrt.vtkOpenMeshClean()
bad.AddObserver(vtkCommand.ErrorEvent, on_error)
bad.SetInputData(vtkPolyData())
bad.Update()
check(len(errors) >= 1, "empty input reported as an error")
check(bad.GetOutput().GetNumberOfCells() == 0, "empty output for empty input")

# vtkOpenMeshDecimation: halve the welded sphere by count; then decimate by
# an error bound, and check every input vertex stays within that bound of the
# decimated surface (distance through vtkBVHCellLocator).
import math
from vtkmodules.vtkCommonCore import reference
decimate = vtkrt.vtkOpenMeshDecimation()
decimate.SetInputData(cleaned)
decimate.SetTargetModeToCount()
target = cleaned.GetNumberOfCells() // 2
decimate.SetTargetNumberOfTriangles(target)
decimate.Update()
check(abs(decimate.GetOutput().GetNumberOfCells() - target) <= 2,
      "decimated to %d triangles (target %d)" % (decimate.GetOutput().GetNumberOfCells(), target))

bound = 0.01
decimate.SetTargetModeToErrorBound()
decimate.SetMaximumError(bound)
decimate.Update()
decimated = decimate.GetOutput()
check(0 < decimated.GetNumberOfCells() < cleaned.GetNumberOfCells(),
      "error-bounded decimation removed triangles: %d -> %d" % (cleaned.GetNumberOfCells(), decimated.GetNumberOfCells()))
locator = vtkrt.vtkBVHCellLocator()
locator.SetDataSet(decimated)
locator.BuildLocator()
closest = [0.0, 0.0, 0.0]
cell_id, sub_id, dist2 = reference(0), reference(0), reference(0.0)
worst = 0.0
for i in range(cleaned.GetNumberOfPoints()):
    locator.FindClosestPoint(cleaned.GetPoint(i), closest, cell_id, sub_id, dist2)
    worst = max(worst, math.sqrt(float(dist2)))
check(0 < worst <= bound, "input vertices within the bound %g of the decimated surface (max %g)" % (bound, worst))

# vtkBVHBoxes: the root box (level 0) is the mesh's bounding box.
boxes = vtkrt.vtkBVHBoxes()
boxes.SetInputData(cleaned)
boxes.SetLevel(0)
boxes.Update()
b, m = boxes.GetOutput().GetBounds(), cleaned.GetBounds()
check(max(abs(b[k] - m[k]) for k in range(6)) < 1e-6, "BVH root box equals the mesh bounds: %s" % (b,))
boxes.SetLevel(3)
boxes.Update()
check(boxes.GetOutput().GetNumberOfCells() > 1, "level 3 has several boxes")
check(out.GetOutput() == "", "VTK printed nothing: %r" % out.GetOutput())
