"""The demo scene of vtkrt-render (data/bunny.vtp + sphere glyphs from
data/demo-spheres.vtp), built the way a Python VTK user would."""
import os

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkGlyph3DMapper, vtkPolyDataMapper, vtkRenderer


def read(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def build(data_dir, background=(0.1, 0.1, 0.12)):
    """Returns (renderer, bunny polydata, keep-alive list)."""
    renderer = vtkRenderer()
    renderer.SetBackground(*background)
    bunny = read(os.path.join(data_dir, "bunny.vtp"))
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(bunny)
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.86, 0.82, 0.74)
    renderer.AddActor(actor)

    centres = read(os.path.join(data_dir, "demo-spheres.vtp"))
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(24)
    sphere.SetPhiResolution(24)
    lut = vtkLookupTable()
    lut.SetHueRange(0.66, 0.0)
    lut.SetTableRange(0.0, 1.0)
    lut.Build()
    glyphs = vtkGlyph3DMapper()
    glyphs.SetInputData(centres)
    glyphs.SetSourceConnection(sphere.GetOutputPort())
    glyphs.SetScaleArray("radius")
    glyphs.SetScaleModeToScaleByMagnitude()
    glyphs.SetScaleFactor(1.0)
    glyphs.OrientOff()
    glyphs.SetLookupTable(lut)
    glyphs.SetScalarModeToUsePointFieldData()
    glyphs.SelectColorArray("scalar")
    glyphs.SetScalarRange(0.0, 1.0)
    glyph_actor = vtkActor()
    glyph_actor.SetMapper(glyphs)
    renderer.AddActor(glyph_actor)
    renderer.ResetCamera()
    return renderer, bunny, [sphere, lut, glyphs, mapper]
