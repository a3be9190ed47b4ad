"""Frame times of the Ray Traced Render View, serial or under mpiexec (not
a test: timings never decide a test). Prints the median of still renders
after a warm-up, for a camera orbit (every frame re-traces; geometry and
BVHs are built once).

Usage: [mpiexec -np N] pvbatch --force-offscreen-rendering bench_scaling.py [EXTENT [WIDTH HEIGHT [raster]]]
("raster": ParaView's own rendering in the same view, for comparison.)
"""
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtkrt_pv_scenes import *  # noqa: F401,F403

extent = int(sys.argv[1]) if len(sys.argv) > 1 else 60
size = [int(sys.argv[2]), int(sys.argv[3])] if len(sys.argv) > 3 else [1024, 768]
raster = len(sys.argv) > 4 and sys.argv[4] == "raster"
load_plugin()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
view = ray_traced_view()
view.ViewSize = size
view.EnableRayTracing = 0 if raster else 1
SetActiveView(view)
wavelet = Wavelet(WholeExtent=[-extent, extent] * 3)
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
display = Show(contour, view)
ColorBy(display, ("POINTS", None))
place_camera(view)
start = time.perf_counter()
Render(view)
first = time.perf_counter() - start
triangles = contour.GetDataInformation().GetNumberOfCells()
camera = GetActiveCamera()
times = []
for i in range(12):
    camera.Azimuth(3.0)
    start = time.perf_counter()
    Render(view)
    times.append(time.perf_counter() - start)
print("%s, ranks %d, %d triangles, %dx%d: first frame %.2f s (data, BVH, upload), "
      "median frame %.3f s (min %.3f, max %.3f)"
      % ("raster" if raster else "ray traced", ranks, triangles, size[0], size[1], first, statistics.median(times), min(times), max(times)))
