"""Run by Blender (blender -b --python blender_import_check.py -- FILE.glb EXPECTED.npz):
imports FILE.glb with Blender's glTF importer and checks that every imported mesh's vertex
colours, as display (sRGB) values, equal the expected ones (points{i}, colors{i} of the
exported parts) at the same positions within one 8-bit step (two at the darkest values,
on at most 1 % of the corners: Blender re-encodes them to 8 bits)."""
import sys

import bpy
import numpy as np

# Debian's Blender 3.4 importer still names np.bool, which NumPy 1.24 removed.
if "bool" not in np.__dict__:
    np.bool = bool

path, expected_path = sys.argv[sys.argv.index("--") + 1:][:2]
expected = np.load(expected_path)
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)

meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
parts = len([k for k in expected.files if k.startswith("points")])
assert len(meshes) == parts, f"{len(meshes)} meshes imported, {parts} exported"
# The exported colour of every position (glTF's +Y up is Blender's +Z up).
lookup = {}
for i in range(parts):
    for p, c in zip(expected[f"points{i}"], expected[f"colors{i}"]):
        lookup[tuple(np.round(p, 4))] = c
differences = []
for ob in meshes:
    mesh = ob.data
    assert len(mesh.color_attributes) == 1, [a.name for a in mesh.color_attributes]
    colors = mesh.color_attributes[0]
    world = ob.matrix_world
    for loop in mesh.loops:
        x, y, z = world @ mesh.vertices[loop.vertex_index].co
        key = tuple(np.round((x, z, -y), 4))
        assert key in lookup, f"no exported point at {key}"
        value = colors.data[loop.index if colors.domain == "CORNER" else loop.vertex_index]
        shown = 255.0 * np.array(value.color_srgb[:3])
        differences.append((float(np.abs(shown - lookup[key]).max()), tuple(lookup[key])))
worst = max(differences)
over = [d for d in differences if d[0] > 1.0]
print(f"blender check: {len(differences)} corners, largest difference {worst[0]:.2f} of 255 "
      f"(at {worst[1]}), {len(over)} over 1: {sorted(set(o[1] for o in over))[:10]}")
# Blender keeps imported vertex colours as 8-bit sRGB (BYTE_COLOR) converted from glTF's
# linear floats with a curve of its own: one step apart, two at the darkest values.
assert differences and worst[0] <= 2.0 and len(over) <= 0.01 * len(differences), worst
print("blender check: ok")
