"""The binary glTF 2.0 (.glb) of linkgi.export_glb: the baked colours on unlit materials.

glTF's vertex colours (COLOR_0) are linear and multiply the base colour; an unlit material
(KHR_materials_unlit) shows that product, encoded for display by the viewer. So COLOR_0
holds the displayed (sRGB) colours decoded to linear light, as float RGB: a viewer that
follows the specification, Blender among them, shows exactly the colours LinkGI displayed.
"""
import json
import os
import struct

import numpy as np

GLB_MAGIC = 0x46546C67  # "glTF"
CHUNK_JSON = 0x4E4F534A
CHUNK_BIN = 0x004E4942
FLOAT, UNSIGNED_INT = 5126, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


def srgb_to_linear(display):
    """Display values in [0, 1] decoded to linear light (the sRGB curve)."""
    c = np.clip(display, 0.0, 1.0)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _camera_node(camera):
    """A glTF camera node (looking down its -Z, +Y up) at the VTK camera."""
    position = np.array(camera["position"], dtype=np.float64)
    z = position - np.array(camera["focal_point"], dtype=np.float64)
    distance = np.linalg.norm(z)
    z /= distance
    y = np.array(camera["view_up"], dtype=np.float64)
    y -= np.dot(y, z) * z
    y /= np.linalg.norm(y)
    x = np.cross(y, z)
    m = np.column_stack([x, y, z])
    # Rotation matrix to quaternion (x, y, z, w).
    w = np.sqrt(max(0.0, 1.0 + np.trace(m))) / 2.0
    if w > 1e-6:
        q = [(m[2, 1] - m[1, 2]) / (4 * w), (m[0, 2] - m[2, 0]) / (4 * w),
             (m[1, 0] - m[0, 1]) / (4 * w), w]
    else:
        i = int(np.argmax(np.diag(m)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = np.sqrt(max(0.0, 1.0 + m[i, i] - m[j, j] - m[k, k])) * 2.0
        q = [0.0, 0.0, 0.0, (m[k, j] - m[j, k]) / s]
        q[i] = s / 4.0
        q[j] = (m[j, i] + m[i, j]) / s
        q[k] = (m[k, i] + m[i, k]) / s
    near, far = camera["clipping_range"]
    if camera["parallel"]:
        scale = camera["parallel_scale"]
        gltf_camera = {"type": "orthographic",
                       "orthographic": {"xmag": scale, "ymag": scale, "znear": near, "zfar": far}}
    else:
        gltf_camera = {"type": "perspective",
                       "perspective": {"yfov": np.radians(camera["view_angle"]),
                                       "znear": near, "zfar": far}}
    return gltf_camera, {"name": "camera", "camera": 0, "translation": position.tolist(),
                         "rotation": [float(v) for v in q]}


class _Buffer:
    def __init__(self):
        self.chunks = []
        self.size = 0
        self.views = []
        self.accessors = []

    def accessor(self, values, component, kind, target, bounds=False):
        data = np.ascontiguousarray(values).tobytes()
        self.views.append({"buffer": 0, "byteOffset": self.size, "byteLength": len(data),
                           "target": target})
        padding = (-len(data)) % 4
        self.chunks.append(data + b"\0" * padding)
        self.size += len(data) + padding
        rows = values.reshape(len(values), -1)
        accessor = {"bufferView": len(self.views) - 1, "componentType": component,
                    "count": int(len(values)), "type": kind}
        if bounds:
            accessor["min"] = [float(v) for v in rows.min(axis=0)]
            accessor["max"] = [float(v) for v in rows.max(axis=0)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def write(scene, filename):
    lo, hi = scene.bounds()
    origin = 0.5 * (lo + hi)  # float32 positions relative to the centre keep their precision
    buffer = _Buffer()
    materials, material_index = [], {}
    meshes, nodes = [], []
    for part in scene.parts:
        key = (part.culled, round(float(part.opacity), 6))
        if key not in material_index:
            material = {"name": "LinkGI unlit", "doubleSided": not part.culled,
                        "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, key[1]],
                                                 "metallicFactor": 0.0, "roughnessFactor": 1.0},
                        "extensions": {"KHR_materials_unlit": {}}}
            if key[1] < 1.0:
                material["alphaMode"] = "BLEND"
            material_index[key] = len(materials)
            materials.append(material)
        colors = srgb_to_linear(part.colors[scene.mode].astype(np.float64) / 255.0)
        attributes = {
            "POSITION": buffer.accessor((part.points - origin).astype(np.float32), FLOAT,
                                        "VEC3", ARRAY_BUFFER, bounds=True),
            "NORMAL": buffer.accessor(part.normals.astype(np.float32), FLOAT, "VEC3",
                                      ARRAY_BUFFER),
            "COLOR_0": buffer.accessor(colors.astype(np.float32), FLOAT, "VEC3", ARRAY_BUFFER)}
        indices = buffer.accessor(part.triangles.astype(np.uint32).ravel(), UNSIGNED_INT,
                                  "SCALAR", ELEMENT_ARRAY_BUFFER)
        meshes.append({"name": part.name or f"part {len(meshes)}",
                       "primitives": [{"attributes": attributes, "indices": indices,
                                       "material": material_index[key], "mode": 4}]})
        nodes.append({"name": part.name or f"part {len(nodes)}", "mesh": len(meshes) - 1,
                      "translation": [float(v) for v in origin]})
    gltf_camera, camera_node = _camera_node(scene.camera)
    nodes.append(camera_node)
    document = {
        "asset": {"version": "2.0", "generator": "LinkGI (linkgi.export_glb)"},
        "extensionsUsed": ["KHR_materials_unlit"],
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "materials": materials, "cameras": [gltf_camera],
        "accessors": buffer.accessors, "bufferViews": buffer.views,
        "buffers": [{"byteLength": buffer.size}]}
    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * ((-len(text)) % 4)
    total = 12 + 8 + len(text) + 8 + buffer.size
    if total >= 2 ** 32:
        raise ValueError(f"linkgi: the scene needs {total} bytes, beyond glTF's 4 GiB limit")
    with open(filename, "wb") as f:
        f.write(struct.pack("<III", GLB_MAGIC, 2, total))
        f.write(struct.pack("<II", len(text), CHUNK_JSON))
        f.write(text)
        f.write(struct.pack("<II", buffer.size, CHUNK_BIN))
        for chunk in buffer.chunks:
            f.write(chunk)
    return {"file": str(filename), "bytes": os.path.getsize(filename), "points": scene.points,
            "triangles": scene.triangles, "parts": len(scene.parts),
            "left_out": list(scene.left_out)}
