"""pvpython test: vtkrt's filters, loaded from the plugin, run in ParaView."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtkrt_pv_testing import *  # noqa: F401,F403

load_plugin()
for name in ["OpenMeshClean", "OpenMeshDecimation", "BVHBoxes"]:
    check(servermanager.ProxyManager().GetPrototypeProxy("filters", name) is not None,
          "filter %s is registered" % name)


# A closed sphere: one component, no boundary, every triangle kept.
ball = Sphere(ThetaResolution=48, PhiResolution=32)
ball.UpdatePipeline()
triangles = ball.GetDataInformation().GetNumberOfCells()
clean = OpenMeshClean(Input=ball)
clean.UpdatePipeline()
check(clean.GetDataInformation().GetNumberOfCells() == triangles,
      "clean keeps the sphere's %d triangles (got %d)" % (triangles, clean.GetDataInformation().GetNumberOfCells()))
out = servermanager.Fetch(clean)
check(out.GetFieldData().GetArray("NumberOfBoundaryEdges").GetTuple1(0) == 0,
      "a closed sphere has no boundary edges")
check(out.GetFieldData().GetArray("NumberOfComponents").GetTuple1(0) == 1,
      "a sphere is one component")

# An isosurface cut by the domain: its boundary edges are the second
# output's lines of EdgeType 1.
wavelet = Wavelet(WholeExtent=[-10, 10, -10, 10, -10, 10])
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
clean_open = OpenMeshClean(Input=contour)
clean_open.UpdatePipeline()
mesh_out = servermanager.Fetch(clean_open, idx=0)
edges_out = servermanager.Fetch(clean_open, idx=1)
boundary = int(mesh_out.GetFieldData().GetArray("NumberOfBoundaryEdges").GetTuple1(0))
edge_types = edges_out.GetCellData().GetArray("EdgeType")
type1 = sum(1 for i in range(edges_out.GetNumberOfCells()) if edge_types.GetValue(i) == 1)
check(boundary > 0 and type1 == boundary,
      "the cut isosurface's %d boundary edges are the problem-edge lines of type 1 (%d)" % (boundary, type1))

# Decimation to a triangle count.
fine = Sphere(ThetaResolution=64, PhiResolution=64)
decimate = OpenMeshDecimation(Input=fine, TargetMode="Target Triangle Count", TargetNumberOfTriangles=500)
decimate.UpdatePipeline()
kept = decimate.GetDataInformation().GetNumberOfCells()
check(499 <= kept <= 501, "decimation keeps 500 +- 1 triangles (got %d)" % kept)

# The BVH's root box is the mesh's bounding box, as 12 edges.
boxes = BVHBoxes(Input=fine, Level=0)
boxes.UpdatePipeline()
info = boxes.GetDataInformation()
bounds, expected = info.GetBounds(), fine.GetDataInformation().GetBounds()
check(info.GetNumberOfCells() == 12 and all(abs(a - b) < 1e-6 for a, b in zip(bounds, expected)),
      "BVH root box: 12 lines on the mesh bounds (%d cells, %s vs %s)" % (info.GetNumberOfCells(), bounds, expected))
finish()
