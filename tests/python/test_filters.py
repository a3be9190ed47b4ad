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
