"""Command 1's picture is the README's picture: runs linkgi-demo (what scripts/demo.sh runs)
and compares its output with the image the README shows, Documentation/cornell-demo.png, by
the rule of the image tests (RenderingTestUtilities.h: mean difference within 1 level, at
most 0.2 % of the pixels off by more than 16). Fails when the README stops showing that file
or the two pictures diverge; regenerate the README's with
    Testing/run_with_xvfb.sh build/bin/linkgi-demo Documentation/cornell-demo.png
Usage: TestDemoIsReadmePicture.py DEMO README OUTPUT_DIR
"""
import os
import re
import subprocess
import sys

from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

PICTURE = "Documentation/cornell-demo.png"


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    array = vtk_to_numpy(image.GetPointData().GetScalars())
    return array.reshape(height, width, -1)[:, :, :3].astype(float)


def main():
    demo, readme, output_dir = sys.argv[1:4]
    top = os.path.dirname(os.path.abspath(readme))
    shown = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", open(readme, encoding="utf-8").read())
    if PICTURE not in shown:
        print("FAILED: README.md does not show %s (it shows %s)" % (PICTURE, shown))
        return 1
    os.makedirs(output_dir, exist_ok=True)
    produced = os.path.join(output_dir, "linkgi-demo.png")
    subprocess.run([demo, produced], check=True)
    a, b = pixels(produced), pixels(os.path.join(top, PICTURE))
    if a.shape != b.shape:
        print("FAILED: linkgi-demo wrote a %s image, the README shows %s" % (a.shape, b.shape))
        return 1
    difference = abs(a - b)
    mean = difference.mean()
    differing = int((difference.max(axis=2) > 16).sum())
    n = a.shape[0] * a.shape[1]
    print("linkgi-demo vs %s: mean difference %.3f levels, %d of %d pixels differ by more "
          "than 16" % (PICTURE, mean, differing, n))
    if mean <= 1.0 and differing <= n // 500:
        return 0
    print("FAILED: command 1's picture (%s) is not the README's; regenerate the README's "
          "picture with linkgi-demo if the change is intended" % produced)
    return 1


if __name__ == "__main__":
    sys.exit(main())
