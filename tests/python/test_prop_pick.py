"""Click picking as vedo does it, in plain VTK: a left click runs
vtkPropPicker.PickProp at the event position. With vtkRayTracePass on, each
click picks the actor raster picks there (and nothing on the background)."""
import vtkrt
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkPropPicker, vtkRenderer
from vtkmodules.vtkRenderingUI import vtkGenericRenderWindowInteractor
import vtkmodules.vtkInteractionStyle  # noqa: F401  (the default style, made then dropped)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkrt_test_util import capture_vtk_output, check

out = capture_vtk_output()


def clicks(traced):
    """Builds the scene, clicks at fixed pixels, returns the picked actor's
    index (or None) per click."""
    keep = []
    renderer = vtkRenderer()
    actors = []
    for center, source in (((0, 0, 0), vtkSphereSource()), ((2.5, 0, 0), vtkCubeSource())):
        source.SetCenter(*center)
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(source.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer.AddActor(actor)
        actors.append(actor)
        keep += [source, mapper]
    renderer.ResetCamera()
    window = vtkrt.vtkEGLHeadlessRenderWindow()
    window.SetSize(300, 200)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    if traced:
        ray_pass = vtkrt.vtkRayTracePass()
        renderer.SetPass(ray_pass)
        keep.append(ray_pass)
    window.Render()
    if traced:
        check(ray_pass.GetNumberOfTracedProps() == 2, "both actors are traced")

    interactor = vtkGenericRenderWindowInteractor()
    interactor.SetRenderWindow(window)
    interactor.SetInteractorStyle(None)  # only the click observer, as vedo's
    picked = []

    def on_click(caller, event):
        x, y = caller.GetEventPosition()
        picker = vtkPropPicker()
        picker.PickProp(x, y, renderer)
        actor = picker.GetActor()
        picked.append(actors.index(actor) if actor in actors else None)

    interactor.AddObserver("LeftButtonPressEvent", on_click)
    # The actors' centers, a point near the sphere's rim, two background corners.
    for world in ((0, 0, 0), (2.5, 0, 0), (0.0, 0.45, 0.2)):
        renderer.SetWorldPoint(*world, 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        interactor.SetEventInformation(int(x), int(y))
        interactor.InvokeEvent("LeftButtonPressEvent")
    for x, y in ((2, 2), (297, 197)):
        interactor.SetEventInformation(x, y)
        interactor.InvokeEvent("LeftButtonPressEvent")
    return picked


raster = clicks(False)
traced = clicks(True)
print("raster", raster, "traced", traced)
check(raster == [0, 1, 0, None, None], "raster picks the sphere, the cube, the sphere, nothing twice")
check(traced == raster, "every click picks what raster picks")
check(out.GetOutput() == "", "no VTK error or warning: " + out.GetOutput())
