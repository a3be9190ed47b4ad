#!/usr/bin/env python3
"""Regenerates the demo scene of vtkrt-render (needs Debian's python3-vtk9):

    /usr/bin/python3 data/make_demo_data.py data/bunny.ply

- data/bunny.vtp: the Stanford bunny (points and triangles only, normals
  computed here), binary, zlib-compressed, 32-bit ids.
- data/demo-spheres.vtp: sphere glyph centres around the bunny with point
  arrays "radius" (world units) and "scalar" (0..1, coloured through a LUT).
Deterministic: the same input gives the same files.
"""
import math
import sys

from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkPolyDataNormals, vtkTriangleFilter
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def write(poly, path):
    w = vtkXMLPolyDataWriter()
    w.SetInputData(poly)
    w.SetFileName(path)
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()
    w.SetCompressorTypeToZLib()
    w.SetIdTypeToInt32()
    w.SetHeaderTypeToUInt32()
    if not w.Write():
        sys.exit("cannot write " + path)


def bunny(ply_path, out_path):
    reader = vtkPLYReader()
    reader.SetFileName(ply_path)
    tri = vtkTriangleFilter()
    tri.SetInputConnection(reader.GetOutputPort())
    clean = vtkCleanPolyData()  # drops unused points, keeps all triangles
    clean.SetInputConnection(tri.GetOutputPort())
    clean.PointMergingOff()
    normals = vtkPolyDataNormals()
    normals.SetInputConnection(clean.GetOutputPort())
    normals.SplittingOff()
    normals.ConsistencyOn()
    normals.AutoOrientNormalsOff()
    normals.Update()
    out = vtkPolyData()
    out.SetPoints(normals.GetOutput().GetPoints())
    out.SetPolys(normals.GetOutput().GetPolys())
    out.GetPointData().SetNormals(normals.GetOutput().GetPointData().GetNormals())
    write(out, out_path)
    return out


def spheres(mesh, out_path):
    b = mesh.GetBounds()
    cx, cy, cz = (b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2
    size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
    pts = vtkPoints()
    radius = vtkFloatArray()
    radius.SetName("radius")
    scalar = vtkFloatArray()
    scalar.SetName("scalar")
    # A rising helix of spheres around the bunny plus a ring at its feet.
    n_helix, n_ring = 96, 48
    for i in range(n_helix):
        t = i / (n_helix - 1)
        a = 5.0 * math.pi * t
        r = 0.62 * size
        pts.InsertNextPoint(cx + r * math.cos(a), b[2] + t * (b[3] - b[2]) * 1.1, cz + r * math.sin(a))
        radius.InsertNextValue(size * (0.025 + 0.02 * math.sin(7.0 * a) ** 2))
        scalar.InsertNextValue(t)
    for i in range(n_ring):
        a = 2.0 * math.pi * i / n_ring
        r = 0.85 * size
        pts.InsertNextPoint(cx + r * math.cos(a), b[2] + 0.03 * size, cz + r * math.sin(a))
        radius.InsertNextValue(size * 0.035)
        scalar.InsertNextValue(0.5 + 0.5 * math.cos(3.0 * a))
    out = vtkPolyData()
    out.SetPoints(pts)
    out.GetPointData().AddArray(radius)
    out.GetPointData().AddArray(scalar)
    out.GetPointData().SetActiveScalars("scalar")
    write(out, out_path)


if __name__ == "__main__":
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "bunny.ply")
    mesh = bunny(src, os.path.join(here, "bunny.vtp"))
    spheres(mesh, os.path.join(here, "demo-spheres.vtp"))
    print("bunny: %d points, %d triangles" % (mesh.GetNumberOfPoints(), mesh.GetNumberOfPolys()))
