"""vtkCellPicker with vtkBVHCellLocator from Python picks what vtkCellPicker
picks alone, over a grid of pixels on the demo scene's bunny."""
import math

import vtkrt
from vtkmodules.vtkRenderingCore import vtkCellPicker
import demo_scene
from vtkrt_test_util import capture_vtk_output, check, data_dir

out = capture_vtk_output()
renderer, bunny, keep = demo_scene.build(data_dir())
renderer.RemoveActor(renderer.GetActors().GetLastActor())  # the bunny alone
renderer.ResetCamera()
window = vtkrt.vtkEGLHeadlessRenderWindow()
window.SetSize(200, 200)
window.AddRenderer(renderer)
window.Render()

locator = vtkrt.vtkBVHCellLocator()
locator.SetDataSet(bunny)
locator.BuildLocator()
with_locator = vtkCellPicker()
with_locator.AddLocator(locator)
with_locator.SetTolerance(0.0)
alone = vtkCellPicker()
alone.SetTolerance(0.0)

diag = math.sqrt(bunny.GetLength() ** 2)
picks = same_cell = same_point = hit_mismatch = 0
for y in range(10, 200, 12):
    for x in range(10, 200, 12):
        a = with_locator.Pick(x, y, 0, renderer)
        b = alone.Pick(x, y, 0, renderer)
        if a != b:
            hit_mismatch += 1
            continue
        if not a:
            continue
        picks += 1
        pa, pb = with_locator.GetPickPosition(), alone.GetPickPosition()
        same_point += math.dist(pa, pb) <= 1e-6 * diag
        same_cell += with_locator.GetCellId() == alone.GetCellId()
check(picks > 50, "%d pixels of the grid hit the bunny" % picks)
check(hit_mismatch <= 2, "hit/miss agrees (%d mismatches, bound 2: silhouette grazes)" % hit_mismatch)
check(same_point == picks, "picked points agree within 1e-6 of the diagonal: %d of %d" % (same_point, picks))
check(same_cell >= picks - 1, "picked cells agree: %d of %d (bound: 1 shared edge)" % (same_cell, picks))
check(out.GetOutput() == "", "VTK printed nothing: %r" % out.GetOutput())
