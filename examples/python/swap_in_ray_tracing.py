"""An ordinary VTK application, ray traced by adding two lines:

    pass_ = vtkrt.vtkRayTracePass(); renderer.SetPass(pass_)

Given an output file it renders, writes the PNG and exits: in a desktop window
when there is a display, headless through EGL without one or with --offscreen.
Without an output file and with a display it opens the window to look around
in (close it to quit).
"""
import os
import sys

import vtkrt
from vtkmodules.vtkFiltersSources import vtkPointSource, vtkSphereSource, vtkSuperquadricSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkGlyph3DMapper, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkRenderWindowInteractor,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkInteractionStyle  # noqa: F401  (default interactor style)

args = [a for a in sys.argv[1:] if a != "--offscreen"]
offscreen = "--offscreen" in sys.argv or "DISPLAY" not in os.environ
interactive = not offscreen and not args
output = args[0] if args else "swap_in_ray_tracing.png"

shape = vtkSuperquadricSource()
shape.SetThetaResolution(64)
shape.SetPhiResolution(64)
shape.ToroidalOn()
shape_mapper = vtkPolyDataMapper()
shape_mapper.SetInputConnection(shape.GetOutputPort())
shape_actor = vtkActor()
shape_actor.SetMapper(shape_mapper)
shape_actor.GetProperty().SetColor(0.9, 0.6, 0.3)

centers = vtkPointSource()
centers.SetNumberOfPoints(200)
centers.SetRadius(0.9)
glyph = vtkSphereSource()
glyph_mapper = vtkGlyph3DMapper()
glyph_mapper.SetInputConnection(centers.GetOutputPort())
glyph_mapper.SetSourceConnection(glyph.GetOutputPort())
glyph_mapper.SetScaleFactor(0.08)
glyph_mapper.ScalarVisibilityOff()
glyph_actor = vtkActor()
glyph_actor.SetMapper(glyph_mapper)
glyph_actor.GetProperty().SetColor(0.3, 0.6, 0.9)

renderer = vtkRenderer()
renderer.AddActor(shape_actor)
renderer.AddActor(glyph_actor)
renderer.SetBackground(0.1, 0.1, 0.15)
renderer.GetActiveCamera().Elevation(35)
renderer.ResetCamera()

# The two lines that make it ray traced.
ray_trace = vtkrt.vtkRayTracePass()
renderer.SetPass(ray_trace)

window = vtkrt.vtkEGLHeadlessRenderWindow() if offscreen else vtkRenderWindow()
window.SetSize(480, 360)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
window.Render()

if interactive:
    interactor = vtkRenderWindowInteractor()
    interactor.SetRenderWindow(window)
    interactor.Start()
    sys.exit(0)

grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(output)
writer.Write()
print("wrote %s (%d props ray traced)" % (output, ray_trace.GetNumberOfTracedProps()))
sys.exit(0 if ray_trace.GetNumberOfTracedProps() == 2 else 1)
