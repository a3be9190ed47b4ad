"""vtkRayTracePass's quality presets from Python: the enum constants, the
SetQualityPresetTo...() calls, the knobs each preset sets, a knob set after
a preset winning (the pass then reads Custom), and a preset rendering."""
import vtkrt
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkrt_test_util import capture_vtk_output, check

out = capture_vtk_output()
Pass = vtkrt.vtkRayTracePass

check((Pass.CUSTOM, Pass.INTERACTIVE, Pass.BALANCED, Pass.EXACT) == (0, 1, 2, 3),
      "the preset constants are class attributes")
ray_pass = Pass()
check(ray_pass.GetQualityPreset() == Pass.CUSTOM, "a new pass is CUSTOM")


def knobs(p):
    return (p.GetBuildQuality(), p.GetLeafSize(), p.GetSamplesPerPixel(),
            bool(p.GetProgressiveAccumulation()), bool(p.GetShadows()),
            p.GetAmbientOcclusionSamples(), p.GetMaximumTraversalSteps(), p.GetPrecisionMode())


expected = {
    "Interactive": (Pass.INTERACTIVE, (0, 8, 1, True, False, 0, 0, Pass.CAMERA_RELATIVE)),
    "Balanced": (Pass.BALANCED, (1, 8, 1, True, True, 2, 0, Pass.CAMERA_RELATIVE)),
    "Exact": (Pass.EXACT, (1, 8, 4, True, True, 4, 0, Pass.CAMERA_RELATIVE)),
}
for name, (preset, values) in expected.items():
    ray_pass.SetPrecisionModeToWorld()
    getattr(ray_pass, "SetQualityPresetTo" + name)()
    check(knobs(ray_pass) == values, name + " sets " + str(values) + ", got " + str(knobs(ray_pass)))
    check(ray_pass.GetQualityPreset() == preset and ray_pass.GetQualityPresetAsString() == name,
          "GetQualityPreset reads " + name)

ray_pass.SetQualityPreset(Pass.INTERACTIVE)
ray_pass.SetShadows(True)
check(ray_pass.GetShadows() and ray_pass.GetBuildQuality() == 0,
      "Shadows set after INTERACTIVE wins, the preset's other knobs stay")
check(ray_pass.GetQualityPresetAsString() == "Custom", "INTERACTIVE with shadows reads Custom")

# A preset renders: progressive accumulation counts still frames.
renderer = vtkRenderer()
sphere = vtkSphereSource()
mapper = vtkPolyDataMapper()
mapper.SetInputConnection(sphere.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
renderer.AddActor(actor)
window = vtkrt.vtkEGLHeadlessRenderWindow()
window.SetSize(96, 96)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
ray_pass.SetQualityPresetToInteractive()
renderer.SetPass(ray_pass)
for _ in range(3):
    window.Render()
check(ray_pass.GetAccumulatedFrames() == 3, "INTERACTIVE accumulates 3 still frames")
check("QualityPreset: Interactive" in str(ray_pass), "PrintSelf names the preset")
renderer.SetPass(None)
check(out.GetOutput() == "", "no VTK output: " + out.GetOutput())
