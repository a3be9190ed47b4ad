"""Small helpers shared by vtkrt's Python tests (run with Debian's python3)."""
import os
import sys

from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

def capture_vtk_output():
    """Route VTK's global output window into a string so a test can assert
    that nothing (no error, no warning) was printed."""
    window = vtkStringOutputWindow()
    vtkOutputWindow.SetInstance(window)
    return window

def data_dir():
    return os.environ.get("VTKRT_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "data"))

def check(condition, message):
    if not condition:
        print("FAILED:", message)
        sys.exit(1)
    print("ok:", message)
