"""linkgi.export_glb writes glTF 2.0 that Blender shows with the displayed colours.

The file is read back as glTF: one node per block, named as the block (a two-sided
solution's back faces a node of their own, wound the other way, both with back faces culled), unlit materials
(KHR_materials_unlit), normals of unit length, and COLOR_0 the baked display colours
decoded to linear light. Debian's Blender imports it (blender_import_check.py) and its
vertex colours, read back as display values, equal the baked ones within one 8-bit step
(two at the darkest values, which Blender re-encodes to 8 bits itself).

Usage: TestExportGlb.py [output directory]
"""
import json
import os
import shutil
import struct
import subprocess
import sys

import numpy as np

import linkgi
import linkgi_export_testing as testing
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkRenderingCore import vtkLight

BLENDER = shutil.which("blender")


def read_glb(path):
    with open(path, "rb") as f:
        magic, version, length = struct.unpack("<III", f.read(12))
        assert (magic, version) == (0x46546C67, 2) and length == os.path.getsize(path)
        size, kind = struct.unpack("<II", f.read(8))
        assert kind == 0x4E4F534A
        document = json.loads(f.read(size))
        size, kind = struct.unpack("<II", f.read(8))
        assert kind == 0x004E4942
        binary = f.read(size)

    def accessor(index):
        a = document["accessors"][index]
        view = document["bufferViews"][a["bufferView"]]
        dtype = {5126: np.float32, 5125: np.uint32}[a["componentType"]]
        width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
        values = np.frombuffer(binary, dtype=dtype, count=a["count"] * width,
                               offset=view["byteOffset"])
        return values.reshape(a["count"], width)

    return document, accessor


def check_file(scene, path):
    document, accessor = read_glb(path)
    assert "KHR_materials_unlit" in document["extensionsUsed"]
    meshes = [n for n in document["nodes"] if "mesh" in n]
    assert len(meshes) == len(scene.parts), (len(meshes), len(scene.parts))
    assert document["cameras"] and any("camera" in n for n in document["nodes"])
    for node, part in zip(meshes, scene.parts):
        primitive = document["meshes"][node["mesh"]]["primitives"][0]
        material = document["materials"][primitive["material"]]
        assert "KHR_materials_unlit" in material["extensions"]
        assert material["doubleSided"] == (not part.culled)
        positions = accessor(primitive["attributes"]["POSITION"]) + np.array(node["translation"])
        assert np.allclose(positions, part.points, atol=1e-5 * np.abs(part.points).max())
        normals = accessor(primitive["attributes"]["NORMAL"])
        assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-4)
        display = 255.0 * linear_to_srgb(accessor(primitive["attributes"]["COLOR_0"]))
        assert np.abs(display - part.colors[scene.mode]).max() <= 0.51
        triangles = accessor(primitive["indices"]).reshape(-1, 3)
        assert (triangles == part.triangles).all()
    return document


def linear_to_srgb(c):
    c = np.clip(c, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def check_blender(scene, path, out):
    assert BLENDER, "Blender is missing (scripts/setup.sh installs it)"
    expected = os.path.join(out, os.path.basename(path) + ".npz")
    arrays = {}
    for i, part in enumerate(scene.parts):
        arrays[f"points{i}"] = part.points
        arrays[f"colors{i}"] = part.colors[scene.mode]
    np.savez(expected, **arrays)
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "blender_import_check.py")
    result = subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1",
                             "--python", script, "--", path, expected],
                            capture_output=True, text=True, timeout=300)
    print(result.stdout[-1500:])
    assert result.returncode == 0, result.stderr[-3000:]
    assert "blender check: ok" in result.stdout


out = testing.output_dir(sys.argv)

# A lit scene from a render window: one block.
window = testing.lamp_scene()
scene = linkgi.bake(window)
path = os.path.join(out, "lamp.glb")
report = linkgi.export_glb(window, path)
print(report)
assert report["bytes"] == os.path.getsize(path)
check_file(scene, path)
check_blender(scene, path, out)

# Normals against the winding: the file's triangles are wound as the normals point (the
# side LinkGI lit is the side viewers take as the front).
window = testing.lamp_scene(against_winding=True)
scene = linkgi.bake(window)
path = os.path.join(out, "against-winding.glb")
linkgi.export_glb(window, path)
check_file(scene, path)
for part in scene.parts:
    corners = part.points[part.triangles]
    face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    agree = np.einsum("ij,ij->i", face, part.normals[part.triangles].sum(axis=1)) > 0
    assert agree.all(), f"{(~agree).sum()} triangles wound against their normals"

# A lit dataset, two-sided: its back faces are a node of their own with their own colours.
plane = vtkPlaneSource()
plane.SetResolution(8, 8)
lamp = vtkLight()
lamp.SetPositional(True)
lamp.SetConeAngle(180)
lamp.SetPosition(0.2, 0.1, 1.0)
lamp.SetAttenuationValues(0, 0, 1)
gi = linkgi.vtkGlobalIlluminationFilter()
gi.SetInputConnection(plane.GetOutputPort())
gi.AddLight(lamp)
gi.TwoSidedOn()
gi.Update()
two_sided = linkgi.bake(gi.GetOutput(), lights=[lamp])
assert len(two_sided.parts) == 2 and all(p.culled for p in two_sided.parts)
front, back = two_sided.parts
assert front.colors["combined"].sum() > 0 and back.colors["combined"].max() == 0, \
    "the lamp lights the front only"
# Without the lights, the filter's record of them (LinkGI.Lamps) picks the same look.
recorded = linkgi.bake(gi.GetOutput())
assert all((a.colors["combined"] == b.colors["combined"]).all()
           for a, b in zip(recorded.parts, two_sided.parts)), "the lamp look is lost"
path = os.path.join(out, "two-sided.glb")
linkgi.export_glb(gi.GetOutput(), path)
check_file(two_sided, path)
# Several blocks are several nodes, named as the blocks.
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkMultiBlockDataSet  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402

blocks = vtkMultiBlockDataSet()
for index, (name, source) in enumerate((("floor", vtkPlaneSource()), ("ball", vtkSphereSource()))):
    source.Update()
    blocks.SetBlock(index, source.GetOutput())
    blocks.GetMetaData(index).Set(vtkCompositeDataSet.NAME(), name)
gi = linkgi.vtkGlobalIlluminationFilter()
gi.SetInputData(blocks)
gi.AddLight(lamp)
gi.Update()
path = os.path.join(out, "blocks.glb")
linkgi.export_glb(gi.GetOutputDataObject(0), path)
document = check_file(linkgi.bake(gi.GetOutputDataObject(0)), path)
names = [n["name"] for n in document["nodes"] if "mesh" in n]
assert names == ["floor", "ball"], names
print("ok")
