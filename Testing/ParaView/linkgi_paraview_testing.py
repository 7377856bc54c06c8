"""Shared helpers of the LinkGI pvbatch tests: arguments, plugin loading, checks, images.

Each test is run as `pvbatch <test>.py --plugin <LinkGI.so> --baseline-dir <dir>
--output-dir <dir>` by Testing/ParaView/CMakeLists.txt.
"""
import argparse
import os
import sys

from paraview import servermanager
from paraview import simple


def parse_arguments():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True, help="the LinkGI plugin library")
    parser.add_argument("--baseline-dir", required=True)
    parser.add_argument("--output-dir", required=True)
    return parser.parse_args(sys.argv[1:])


def load_plugin(path, namespace):
    """Loads the plugin like the GUI's Plugin Manager does; its proxies join `namespace`."""
    if not os.path.exists(path):
        fail("the plugin %s was not built" % path)
    simple.LoadPlugin(path, remote=False, ns=namespace)


def fail(message):
    print("FAILED: " + message)
    sys.stdout.flush()
    # Skip the interpreter's teardown: pvbatch would destroy live proxies after the C++
    # runtime's own globals and bury this message under a crash report.
    os._exit(1)


def check(condition, message):
    if not condition:
        fail(message)
    print("ok: " + message)


def fetch(proxy):
    """The output of `proxy` as a local VTK object (builtin session)."""
    return servermanager.Fetch(proxy)


def field_value(data, name):
    array = data.GetFieldData().GetAbstractArray(name)
    if array is None:
        fail("field data %s is missing" % name)
    return array.GetVariantValue(0).ToDouble()


def nearest_point(data, position):
    return data.FindPoint(position)


def point_rgb(data, array_name, point_id):
    array = data.GetPointData().GetArray(array_name)
    if array is None:
        fail("point array %s is missing" % array_name)
    return array.GetTuple3(point_id)


def compare_with_baseline(view, name, arguments, threshold=10.0):
    """Saves a screenshot of `view` and compares it with <baseline-dir>/<name>.png.

    The comparison is vtkImageDifference's (what VTK's regression tests use), which
    tolerates a pixel shift and small colour differences between OpenGL implementations.
    Without a baseline the screenshot is kept and the test fails, naming the file to review
    and copy.
    """
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.vtkImagingCore import vtkImageDifference

    os.makedirs(arguments.output_dir, exist_ok=True)
    image = os.path.join(arguments.output_dir, name + ".png")
    simple.SaveScreenshot(image, view, ImageResolution=list(view.ViewSize),
                          TransparentBackground=0)
    baseline = os.path.join(arguments.baseline_dir, name + ".png")
    if not os.path.exists(baseline):
        fail("no baseline %s: review %s and copy it there" % (baseline, image))
    readers = []
    for path in (image, baseline):
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        readers.append(reader)
    difference = vtkImageDifference()
    difference.SetInputConnection(readers[0].GetOutputPort())
    difference.SetImageConnection(readers[1].GetOutputPort())
    difference.Update()
    error = difference.GetThresholdedError()
    check(error <= threshold,
          "%s matches %s (thresholded error %.2f, limit %.2f)" % (image, baseline, error, threshold))
