"""Shared helpers of vtkrt's ParaView tests (run by pvbatch / pvpython).

Image comparison mirrors tests/common/vtkrtImageRegression.h: the image is
compared with data/baselines/<name>.png through vtkImageDifference
(averaging on, per-pixel threshold 16, no shift) as RGB; it passes when the
thresholded error (about "this many wholly wrong pixels") is <= threshold.
On failure the image and the difference image are written to
VTKRT_TEMP_DIR as <name>.png and <name>.diff.png. A missing baseline fails,
unless VTKRT_UPDATE_BASELINES=1, which records it.
"""
import os
import shutil
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (scripts share this namespace)
from vtkmodules.vtkImagingCore import vtkImageExtractComponents
from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

DATA_DIR = os.environ.get("VTKRT_DATA_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "..", "data"))
TEMP_DIR = os.environ.get("VTKRT_TEMP_DIR", ".")
PLUGIN = os.environ.get("VTKRT_PARAVIEW_PLUGIN", "")

failures = []


def check(condition, what):
    """Records a failed assertion (the script fails at the end)."""
    if condition:
        print("ok   " + what)
    else:
        print("FAIL " + what)
        failures.append(what)
    return condition


def finish():
    if failures:
        print("FAILED: %d check(s): %s" % (len(failures), "; ".join(failures)))
        sys.exit(1)
    print("all checks passed")


def load_plugin(remote=True):
    """Loads the plugin on the client and, in client/server, the server;
    its filters become functions of the running script."""
    if not PLUGIN:
        raise RuntimeError("VTKRT_PARAVIEW_PLUGIN is not set")
    LoadPlugin(PLUGIN, remote=False, ns=sys.modules["__main__"].__dict__)
    if remote and servermanager.ActiveConnection.IsRemote():
        LoadPlugin(PLUGIN, remote=True, ns=sys.modules["__main__"].__dict__)


def _rgb(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    extract = vtkImageExtractComponents()
    extract.SetInputConnection(reader.GetOutputPort())
    extract.SetComponents(0, 1, 2)
    extract.Update()
    image = extract.GetOutput()
    if image.GetNumberOfScalarComponents() != 3:
        # Gray or RGB already.
        image = reader.GetOutput()
    return image


def mean_red(png):
    """Mean red value (0..255) of a PNG's pixels."""
    scalars = _rgb(png).GetPointData().GetScalars()
    n = scalars.GetNumberOfTuples()
    return sum(scalars.GetComponent(i, 0) for i in range(n)) / max(n, 1)


def image_error(png, other_png):
    """Thresholded error between two PNGs of the same size (as above)."""
    diff = vtkImageDifference()
    diff.SetInputData(_rgb(png))
    diff.SetImageData(_rgb(other_png))
    diff.SetThreshold(16)
    diff.SetAveraging(True)
    diff.SetAllowShift(False)
    diff.Update()
    return diff.GetThresholdedError()


def image_rmse(png, other_png):
    """RGB root mean square error (0..255) between two PNGs of the same size."""
    a = _rgb(png).GetPointData().GetScalars()
    b = _rgb(other_png).GetPointData().GetScalars()
    n = a.GetNumberOfTuples()
    if n == 0 or n != b.GetNumberOfTuples():
        return float("inf")
    total = 0.0
    for i in range(n):
        for c in range(3):
            d = a.GetComponent(i, c) - b.GetComponent(i, c)
            total += d * d
    return (total / (3.0 * n)) ** 0.5


def compare_with_baseline(png, name, threshold=10.0):
    """Compares the PNG `png` with data/baselines/<name>.png; returns the
    thresholded error (or None when no comparison could be made)."""
    baseline = os.path.join(DATA_DIR, "baselines", name + ".png")
    if not os.path.exists(baseline):
        if os.environ.get("VTKRT_UPDATE_BASELINES") == "1":
            shutil.copyfile(png, baseline)
            print("recorded baseline " + baseline)
            return 0.0
        check(False, "baseline %s exists (VTKRT_UPDATE_BASELINES=1 records it)" % baseline)
        return None
    image = _rgb(png)
    reference = _rgb(baseline)
    if image.GetDimensions() != reference.GetDimensions():
        check(False, "%s: image size %s matches the baseline's %s"
              % (name, image.GetDimensions(), reference.GetDimensions()))
        return None
    diff = vtkImageDifference()
    diff.SetInputData(image)
    diff.SetImageData(reference)
    diff.SetThreshold(16)
    diff.SetAveraging(True)
    diff.SetAllowShift(False)
    diff.Update()
    error = diff.GetThresholdedError()
    if not check(error <= threshold, "%s: image error %.2f <= %.2f against %s"
                 % (name, error, threshold, baseline)):
        os.makedirs(TEMP_DIR, exist_ok=True)
        failed = os.path.join(TEMP_DIR, name + ".png")
        shutil.copyfile(png, failed)
        writer = vtkPNGWriter()
        writer.SetFileName(os.path.join(TEMP_DIR, name + ".diff.png"))
        writer.SetInputConnection(diff.GetOutputPort())
        writer.Write()
        print("failed image: %s, difference: %s" % (failed, os.path.join(TEMP_DIR, name + ".diff.png")))
    return error


def traced_primitives(view):
    """Primitives the ray tracer traced in the view's last frame."""
    view.UpdatePropertyInformation()
    return int(view.GetPropertyValue("LastTracedPrimitives"))


def bunny():
    """The demo bunny (69,451 triangles)."""
    return XMLPolyDataReader(FileName=[os.path.join(DATA_DIR, "bunny.vtp")])
