"""vtkRayTracePass from Python on the demo scene, headless: the ray-traced
image covers the same pixels as VTK's raster of the same scene, its colours are
close, and its depth agrees with raster depth where both see the bunny."""
import vtkrt
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
import demo_scene
from vtkrt_test_util import capture_vtk_output, check, data_dir

W, H = 240, 180
BACKGROUND = (0.1, 0.1, 0.12)
out = capture_vtk_output()
renderer, bunny, keep = demo_scene.build(data_dir(), BACKGROUND)
window = vtkrt.vtkEGLHeadlessRenderWindow()
window.SetSize(W, H)
window.SetMultiSamples(0)
window.AddRenderer(renderer)


def grab():
    window.Render()
    f = vtkWindowToImageFilter()
    f.SetInput(window)
    f.Update()
    rgb = f.GetOutput().GetPointData().GetScalars()
    pixels = [rgb.GetTuple3(i) for i in range(W * H)]
    depth = [window.GetZbufferDataAtPoint(x, y) for y in range(0, H, 6) for x in range(0, W, 6)]
    return pixels, depth


raster, raster_depth = grab()
ray_trace = vtkrt.vtkRayTracePass()
renderer.SetPass(ray_trace)
traced, traced_depth = grab()
check(ray_trace.GetNumberOfTracedProps() == 2, "both props (bunny, glyphs) ray traced")

bg = tuple(round(255 * c) for c in BACKGROUND)
def covered(p):
    return max(abs(p[k] - bg[k]) for k in range(3)) > 3

cov_raster = [covered(p) for p in raster]
cov_traced = [covered(p) for p in traced]
n_covered = sum(cov_raster)
n_disagree = sum(a != b for a, b in zip(cov_raster, cov_traced))
check(n_covered > 0.04 * W * H, "the scene covers a good part of the image (%d px)" % n_covered)
check(not cov_traced[0] and not cov_traced[W - 1], "background in the corners")
check(n_disagree <= 0.03 * n_covered,
      "coverage agrees with raster: %d of %d pixels differ (bound 3%%, silhouettes)" % (n_disagree, n_covered))

both = [i for i in range(W * H) if cov_raster[i] and cov_traced[i]]
mean_diff = sum(sum(abs(traced[i][k] - raster[i][k]) for k in range(3)) / 3 for i in both) / len(both)
check(mean_diff < 8, "mean colour difference to raster on covered pixels: %.2f / 255 (bound 8)" % mean_diff)

hits = [(r, t) for r, t in zip(raster_depth, traced_depth) if r < 1.0 and t < 1.0]
close = sum(abs(r - t) < 1e-3 for r, t in hits)
check(len(hits) > 50 and close >= 0.9 * len(hits),
      "depth agrees with raster within 1e-3 at %d of %d sampled hits" % (close, len(hits)))
check(out.GetOutput() == "", "VTK printed nothing: %r" % out.GetOutput())
