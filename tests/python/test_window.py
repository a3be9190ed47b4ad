"""The EGL window from Python: a sphere renders in the middle of the image,
the background stays the background, depth reads back, and VTK prints nothing."""
import vtkrt
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkWindowToImageFilter
from vtkrt_test_util import capture_vtk_output, check

out = capture_vtk_output()
window = vtkrt.vtkEGLHeadlessRenderWindow()
window.SetSize(120, 80)
window.SetMultiSamples(0)
renderer = vtkRenderer()
renderer.SetBackground(0.0, 0.0, 1.0)
window.AddRenderer(renderer)
sphere = vtkSphereSource()
sphere.SetThetaResolution(32)
sphere.SetPhiResolution(32)
mapper = vtkPolyDataMapper()
mapper.SetInputConnection(sphere.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
actor.GetProperty().SetColor(1.0, 0.0, 0.0)
renderer.AddActor(actor)
renderer.ResetCamera()
window.Render()

grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.Update()
image = grab.GetOutput()
check(image.GetDimensions()[:2] == (120, 80), "image has the window's size")
rgb = image.GetPointData().GetScalars()
center = rgb.GetTuple(40 * 120 + 60)
corner = rgb.GetTuple(0)
check(center[0] > 100 and center[2] < 50, "sphere (red) at the center: %s" % (center,))
check(corner == (0.0, 0.0, 255.0), "background (blue) at the corner: %s" % (corner,))

z_center = window.GetZbufferDataAtPoint(60, 40)
z_corner = window.GetZbufferDataAtPoint(0, 0)
check(0.0 < z_center < 1.0, "depth at the sphere in (0,1): %g" % z_center)
check(z_corner == 1.0, "depth at the background is 1: %g" % z_corner)
check(out.GetOutput() == "", "VTK printed nothing: %r" % out.GetOutput())
