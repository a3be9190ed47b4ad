"""An offscreen regression test of your own scene: render it ray traced
headless and compare with a baseline PNG (written on the first run, or with
--update).   Usage: regression_test.py BASELINE.png [--update]"""
import os
import sys

import vtkrt
from vtkmodules.vtkFiltersSources import vtkConeSource
from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkWindowToImageFilter

if len(sys.argv) < 2:
    sys.exit(__doc__)
baseline = sys.argv[1]
update = "--update" in sys.argv[2:]

# Your scene here.
cone = vtkConeSource()
cone.SetResolution(48)
mapper = vtkPolyDataMapper()
mapper.SetInputConnection(cone.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
actor.GetProperty().SetColor(0.8, 0.3, 0.3)
renderer = vtkRenderer()
renderer.AddActor(actor)
renderer.SetBackground(1, 1, 1)
renderer.ResetCamera()
renderer.SetPass(vtkrt.vtkRayTracePass())

window = vtkrt.vtkEGLHeadlessRenderWindow()
window.SetSize(300, 300)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.Update()

if update or not os.path.exists(baseline):
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(baseline)
    writer.Write()
    print("wrote baseline", baseline)
    sys.exit(0)

reader = vtkPNGReader()
reader.SetFileName(baseline)
difference = vtkImageDifference()
difference.SetInputConnection(grab.GetOutputPort())
difference.SetImageConnection(reader.GetOutputPort())
difference.Update()
error = difference.GetThresholdedError()
print("image error against %s: %g" % (baseline, error))
sys.exit(0 if error <= 10.0 else 1)
