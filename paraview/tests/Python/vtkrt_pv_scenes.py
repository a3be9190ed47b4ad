"""Scenes of vtkrt's ParaView tests, the same in serial, MPI and
client/server runs (the camera comes from the global bounds)."""
from vtkrt_pv_testing import *  # noqa: F401,F403

VIEW_SIZE = [400, 300]


def ray_traced_view():
    return _view("RayTracedRenderView")


def raster_view():
    """ParaView's raster view with the same settings, to compare against."""
    return _view("RenderView")


def _view(kind):
    view = CreateView(kind)
    view.ViewSize = VIEW_SIZE
    view.OrientationAxesVisibility = 1  # drawn by the raster fallback
    view.Background = [0.32, 0.34, 0.43]
    view.UseColorPaletteForBackground = 0
    view.MultiSamples = 0
    return view


def sphere_glyphs_3d(points, view):
    """`points` shown as the "3D Glyphs" representation with finely
    tessellated sphere glyphs (48 x 48: raster silhouettes close to the
    traced analytic ones), solid colored."""
    display = Show(points, view)
    display.SetRepresentationType("3D Glyphs")
    display.GlyphType = "Sphere"
    display.GlyphType.ThetaResolution = 48
    display.GlyphType.PhiResolution = 48
    display.ScaleFactor = 0.25
    display.DiffuseColor = [0.55, 0.75, 0.85]
    ColorBy(display, ("POINTS", None))
    return display


def mesh(view):
    """An isosurface of ParaView's Wavelet source (a closed, curved mesh of
    a few ten thousand triangles), solid colored. Under MPI the Wavelet's
    extent is split over the ranks, so each rank contours its own piece;
    ProcessIdScalars records which rank holds each point."""
    wavelet = Wavelet(WholeExtent=[-20, 20, -20, 20, -20, 20])
    contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[160.0])
    contour.ComputeScalars = 0
    ids = ProcessIdScalars(Input=contour)
    display = Show(ids, view)
    ColorBy(display, ("POINTS", None))
    display.DiffuseColor = [0.85, 0.75, 0.55]
    display.Specular = 0.3
    return ids, display


def glyphs(view, center=(0.0, 0.0, 0.0), radius=1.0):
    """Sphere glyphs: the points of a coarse sphere rendered as ray-traced
    spheres (Render Points As Spheres), colored by elevation. Under MPI the
    sphere source makes one piece per rank."""
    points = Sphere(Center=list(center), Radius=radius, ThetaResolution=16, PhiResolution=9)
    colored = Elevation(Input=points, LowPoint=[center[0], center[1] - radius, center[2]],
                        HighPoint=[center[0], center[1] + radius, center[2]])
    display = Show(colored, view)
    display.SetRepresentationType("Points")
    display.RenderPointsAsSpheres = 1
    display.PointSize = 14
    ColorBy(display, ("POINTS", "Elevation"))
    # ParaView maps scalars through a texture by default; the tracer takes
    # mapped colors per point.
    display.InterpolateScalarsBeforeMapping = 0
    return colored, display


def place_camera(view, azimuth=30.0, elevation=15.0):
    view.CameraPosition = [0, 0, 1]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    ResetCamera(view)
    camera = GetActiveCamera()
    camera.Azimuth(azimuth)
    camera.Elevation(elevation)
    ResetCamera(view)
