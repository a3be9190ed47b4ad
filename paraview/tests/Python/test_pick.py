"""pvbatch test: selections in the Ray Traced Render View (cast through
vtkBVHCellLocator) return the cell / point a CPU brute-force ray cast finds.

The scene is a multiblock (an isosurface and a sphere, each cell tagged with
its block and its id), so picks go through vtkCompositePolyDataMapper2's
blocks; under mpiexec the isosurface is split over the ranks and the nearest
hit is resolved across them. The expected answer is computed here with
numpy from the camera's parameters alone: a pinhole ray through the pixel's
center, Moeller-Trumbore against every triangle of the whole data set.
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtkrt_pv_scenes import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy

# "quick": fewer picks (each distributed pick is a render, an MPI reduction
# and a fetch).
quick = len(sys.argv) > 1 and sys.argv[1] == "quick"
load_plugin()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("pick on %d rank(s)" % ranks)
view = ray_traced_view()
SetActiveView(view)


def tagged(source, block):
    ids = GenerateIds(Input=source)
    ids.PointIdsArrayName = "PointIndex"
    ids.CellIdsArrayName = "CellIndex"
    return Calculator(Input=ids, AttributeType="Cell Data", ResultArrayName="Block",
                      Function=str(block))


wavelet = Wavelet(WholeExtent=[-20, 20, -20, 20, -20, 20])
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
contour.ComputeScalars = 0
ball = Sphere(Center=[14.0, -6.0, 18.0], Radius=7.0, ThetaResolution=24, PhiResolution=16)
group = GroupDatasets(Input=[tagged(contour, 0), tagged(ball, 1)])
display = Show(group, view)
ColorBy(display, ("POINTS", None))
place_camera(view, azimuth=30.0, elevation=15.0)
Render(view)
SetActiveSource(group)

# The whole data set, on this (driver) process.
blocks = []
whole = servermanager.Fetch(group)
iterator = whole.NewIterator()
iterator.InitTraversal()
while not iterator.IsDoneWithTraversal():
    block = iterator.GetCurrentDataObject()
    if block.GetNumberOfCells() > 0:
        points = vtk_to_numpy(block.GetPoints().GetData()).astype(np.float64)
        cells = block.GetPolys() if hasattr(block, "GetPolys") else None
        conn = vtk_to_numpy(cells.GetConnectivityArray()).reshape(-1, 3)
        blocks.append({
            "points": points,
            "triangles": conn,
            "block": vtk_to_numpy(block.GetCellData().GetArray("Block")),
            "cell": vtk_to_numpy(block.GetCellData().GetArray("CellIndex")),
            "point": vtk_to_numpy(block.GetPointData().GetArray("PointIndex")),
        })
    iterator.GoToNextItem()
check(len(blocks) >= 2, "fetched %d non-empty blocks" % len(blocks))


def camera_ray(x, y):
    """Origin and direction of the ray through pixel (x, y)'s center."""
    camera = GetActiveCamera()
    eye = np.array(camera.GetPosition())
    forward = np.array(camera.GetFocalPoint()) - eye
    forward /= np.linalg.norm(forward)
    up = np.array(camera.GetViewUp())
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    width, height = VIEW_SIZE
    half = math.tan(math.radians(camera.GetViewAngle()) / 2.0)
    u = (2.0 * (x + 0.5) / width - 1.0) * half * width / height
    v = (2.0 * (y + 0.5) / height - 1.0) * half
    direction = forward + u * right + v * up
    return eye, direction / np.linalg.norm(direction)


def brute_force(x, y):
    """(t, block, cell centroid, nearest vertex, edge margin) of the nearest
    hit, or None. Cells are compared by block and geometry, since ids are
    local to the rank that holds a piece."""
    origin, direction = camera_ray(x, y)
    best = None
    for b in blocks:
        p = b["points"]
        t0, t1, t2 = p[b["triangles"][:, 0]], p[b["triangles"][:, 1]], p[b["triangles"][:, 2]]
        e1, e2 = t1 - t0, t2 - t0
        pvec = np.cross(direction, e2)
        det = np.einsum("ij,ij->i", e1, pvec)
        ok = np.abs(det) > 1e-14
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        tvec = origin - t0
        u = np.einsum("ij,ij->i", tvec, pvec) * inv
        qvec = np.cross(tvec, e1)
        v = (qvec @ direction) * inv
        t = np.einsum("ij,ij->i", e2, qvec) * inv
        hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        if not hit.any():
            continue
        k = np.where(hit)[0][np.argmin(t[hit])]
        if best is None or t[k] < best[0]:
            point = origin + t[k] * direction
            corners = b["triangles"][k]
            nearest = corners[np.argmin(np.linalg.norm(p[corners] - point, axis=1))]
            # How far the hit is from the triangle's edges (in barycentric
            # units): pixels that graze an edge are ambiguous in any tracer.
            margin = min(u[k], v[k], 1.0 - u[k] - v[k])
            centroid = p[corners].mean(axis=0)
            best = (t[k], int(b["block"][k]), centroid, p[nearest], margin)
    return best


def extracted(kind, x0, y0, x1=None, y1=None):
    """What a selection of `kind` of the pixels (x0, y0)-(x1, y1) extracts:
    a list of (block, centroid) for cells, (None, coordinates) for points."""
    x1 = x0 if x1 is None else x1
    y1 = y0 if y1 is None else y1
    ClearSelection(group)
    if kind == "cells":
        SelectSurfaceCells(Rectangle=[x0, y0, x1, y1], View=view)
    else:
        SelectSurfacePoints(Rectangle=[x0, y0, x1, y1], View=view)
    selection = group.GetSelectionInput(0)
    if selection is None:
        return []
    extract = ExtractSelection(Input=group, Selection=selection)
    data = servermanager.Fetch(extract)
    Delete(extract)
    result = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        piece = it.GetCurrentDataObject()
        if kind == "cells":
            for c in range(piece.GetNumberOfCells()):
                ids = piece.GetCell(c).GetPointIds()
                corners = np.array([piece.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())])
                result.append((int(piece.GetCellData().GetArray("Block").GetValue(c)), corners.mean(axis=0)))
        else:
            for q in range(piece.GetNumberOfPoints()):
                result.append((None, np.array(piece.GetPoint(q))))
        it.GoToNextItem()
    return result


def same_cell(a, b):
    return a[0] == b[0] and np.allclose(a[1], b[1], rtol=0.0, atol=1e-6)


width, height = VIEW_SIZE
# Single-pixel picks over the whole view (hits and misses).
step = (100, 70) if quick else (50, 40)
pixels = [(x, y) for x in range(12, width, step[0]) for y in range(9, height, step[1])]
hits = misses = 0
for x, y in pixels:
    expected = brute_force(x, y)
    if expected is not None and expected[4] < 1e-3:
        continue  # grazes an edge: either neighbor is a right answer
    got = extracted("cells", x, y)
    if expected is None:
        misses += 1
        check(got == [], "pixel (%d, %d): no cell selected where the ray misses (got %d)" % (x, y, len(got)))
        continue
    hits += 1
    check(len(got) == 1 and same_cell(got[0], (expected[1], expected[2])),
          "pixel (%d, %d): the cell of block %d centred at %s is selected (got %s)"
          % (x, y, expected[1], expected[2], got))
check(hits >= (3 if quick else 8) and misses >= (3 if quick else 8), "%d hit and %d missed pixels tested" % (hits, misses))

# Rubber bands: every cell hit at a pixel of the rectangle, nothing else
# (a pixel grazing an edge may add its neighbor cell instead).
rectangles = [(150, 120, 165, 135), (238, 88, 250, 100), (185, 200, 196, 211)]
for x0, y0, x1, y1 in rectangles[:2] if quick else rectangles:
    must = []
    grazing = 0
    for x in range(x0, x1 + 1):
        for y in range(y0, y1 + 1):
            e = brute_force(x, y)
            if e is None:
                continue
            if e[4] < 1e-3:
                grazing += 1
            elif not any(same_cell(m, (e[1], e[2])) for m in must):
                must.append((e[1], e[2]))
    got = extracted("cells", x0, y0, x1, y1)
    missing = [m for m in must if not any(same_cell(g, m) for g in got)]
    extra = [g for g in got if not any(same_cell(g, m) for m in must)]
    check(len(must) > 5 and not missing and len(extra) <= grazing,
          "rectangle (%d, %d)-(%d, %d): all %d cells hit are selected (missing %d, extra %d, grazing pixels %d)"
          % (x0, y0, x1, y1, len(must), len(missing), len(extra), grazing))

# A polygon selection (ParaView's hardware selector, with the tracer taken
# out for its renders) selects about the cells the locator's rubber band
# over the same square does.
x0, y0, x1, y1 = rectangles[0]
band = extracted("cells", x0, y0, x1, y1)
ClearSelection(group)
SelectSurfaceCells(Polygon=[x0, y0, x1, y0, x1, y1, x0, y1], View=view)
polygon = group.GetSelectionInput(0)
count = 0
if polygon is not None:
    extract = ExtractSelection(Input=group, Selection=polygon)
    extract.UpdatePipeline()
    count = extract.GetDataInformation().GetNumberOfCells()
    Delete(extract)
check(len(band) > 5 and abs(count - len(band)) <= 0.25 * len(band),
      "polygon selection: %d cells, rubber band over the same square: %d" % (count, len(band)))

# Points: the hit cell's vertex nearest the hit.
for x, y in pixels[:: 8 if quick else 4]:
    expected = brute_force(x, y)
    if expected is None or expected[4] < 1e-3:
        continue
    got = extracted("points", x, y)
    check(len(got) == 1 and np.allclose(got[0][1], expected[3], atol=1e-9),
          "pixel (%d, %d): point selection is the hit cell's vertex nearest the hit %s (got %s)"
          % (x, y, expected[3], [g[1] for g in got]))
finish()
