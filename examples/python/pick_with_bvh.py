"""Ray picking with vtkCellPicker + vtkBVHCellLocator: the picker asks the
locator (exact, double precision) instead of testing every cell."""
import sys

import vtkrt
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkCellPicker, vtkPolyDataMapper, vtkRenderer

sphere = vtkSphereSource()
sphere.SetThetaResolution(128)
sphere.SetPhiResolution(64)
sphere.Update()
mesh = sphere.GetOutput()

mapper = vtkPolyDataMapper()
mapper.SetInputData(mesh)
actor = vtkActor()
actor.SetMapper(mapper)
renderer = vtkRenderer()
renderer.AddActor(actor)
window = vtkrt.vtkEGLHeadlessRenderWindow()  # any vtkRenderWindow works
window.SetSize(400, 400)
window.AddRenderer(renderer)
renderer.ResetCamera()
window.Render()

# Build once; vtkCellPicker never builds the locators it is given.
locator = vtkrt.vtkBVHCellLocator()
locator.SetDataSet(mesh)
locator.BuildLocator()

picker = vtkCellPicker()
picker.AddLocator(locator)
picker.SetTolerance(0.0)
if not picker.Pick(230, 215, 0, renderer):
    sys.exit("nothing picked at pixel (230, 215)")
print("picked cell %d at %s" % (picker.GetCellId(), picker.GetPickPosition()))

plain = vtkCellPicker()
plain.SetTolerance(0.0)
plain.Pick(230, 215, 0, renderer)
print("without the locator: cell %d" % plain.GetCellId())
sys.exit(0 if plain.GetCellId() == picker.GetCellId() else 1)
