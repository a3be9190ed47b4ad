"""vtkrt: ray tracing for VTK.

    import vtkrt
    window = vtkrt.vtkEGLHeadlessRenderWindow()   # headless OpenGL via EGL
    renderer.SetPass(vtkrt.vtkRayTracePass())       # GLSL ray tracer
    picker.AddLocator(vtkrt.vtkBVHCellLocator())    # picking with the same rays

Every class of the wrapped modules (vtkrt.vtkrtPlugin, vtkrt.vtkrtFilters) is
re-exported at package level.
"""

# VTK's own modules first: the wrapped classes derive from them.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from .vtkrtPlugin import *  # noqa: F401,F403

try:
    from .vtkrtFilters import *  # noqa: F401,F403
except ImportError:  # built without the OpenMesh filters (VTKRT_BUILD_FILTERS=OFF)
    pass

__version__ = "0.1.0"
