"""The web page of linkgi.export_html: the baked colours drawn unlit by vtk.js.

The page is vtk.js's offline viewer (static_viewer.html, from the trame-vtk wheel) with the
scene inlined as a zip (index.json: vtk.js's synchronizable render window state, and the
arrays base64-encoded), plus a toggle among the light terms and the colour-map legend.
Nothing is fetched: the page opens from disk without a network.
"""
import base64
import hashlib
import io
import json
import os
import zipfile

import numpy as np

from .export import MODES

# The vtk.js viewer: installed beside this module (from the trame-vtk wheel at build
# time), or the trame-vtk package where it is installed.
VIEWER_NAME = "vtkjs_viewer.html"

# The page parses the scene's JSON as one string; Chromium's V8 holds at most 2^29 - 24
# characters in a string (Firefox more): about 14 million triangles.
BROWSER_STRING_LIMIT = (1 << 29) - 24


def viewer_path():
    here = os.path.join(os.path.dirname(__file__), VIEWER_NAME)
    if os.path.exists(here):
        return here
    try:
        import trame_vtk.tools
        path = os.path.join(os.path.dirname(trame_vtk.tools.__file__), "static_viewer.html")
        if os.path.exists(path):
            return path
    except ImportError:
        pass
    raise FileNotFoundError(
        f"linkgi.export_html needs vtk.js's offline viewer: {here} is missing (LinkGI "
        "builds it from the trame-vtk wheel that scripts/setup.sh downloads) and trame-vtk "
        "is not installed (pip install trame-vtk)")


class _Arrays:
    """The arrays of the scene by content hash, as vtk.js's synchronizer fetches them."""

    JS_TYPES = {np.dtype(np.float32): "Float32Array", np.dtype(np.int32): "Int32Array",
                np.dtype(np.uint8): "Uint8Array", np.dtype(np.uint32): "Uint32Array"}

    def __init__(self):
        self.hashes = {}

    def add(self, values, vtk_class, name, components):
        values = np.ascontiguousarray(values)
        raw = values.tobytes()
        key = hashlib.sha1(raw).hexdigest() + f"_{values.size}"
        js_type = self.JS_TYPES[values.dtype]
        self.hashes[key] = {"hash": key, "type": js_type, "vtk": vtk_class,
                            "content": base64.b64encode(raw).decode("ascii")}
        flat = values.reshape(-1, components) if components > 1 else values.reshape(-1, 1)
        ranges = [{"min": float(flat[:, c].min()), "max": float(flat[:, c].max()),
                   "component": None} for c in range(components)] if values.size else []
        return {"hash": key, "vtkClass": vtk_class, "name": name, "dataType": js_type,
                "numberOfComponents": components, "size": int(values.size),
                "ranges": ranges}


def _state(scene, origin):
    """vtk.js's state of a render window holding the scene, points relative to `origin`."""
    arrays = _Arrays()
    camera = scene.camera
    props = []
    for index, part in enumerate(scene.parts):
        points = (part.points - origin).astype(np.float32)
        cells = np.empty((len(part.triangles), 4), dtype=np.int32)
        cells[:, 0] = 3
        cells[:, 1:] = part.triangles
        fields = []
        for mode in MODES:
            field = arrays.add(part.colors[mode], "vtkDataArray", mode, 3)
            field.update({"location": "pointData", "registration": "addArray"})
            fields.append(field)
        pid = f"part{index}"
        polydata = {
            "parent": f"{pid}-mapper", "id": f"{pid}-data", "type": "vtkPolyData",
            "properties": {
                "points": dict(arrays.add(points, "vtkPoints", "Points", 3)),
                "polys": arrays.add(cells.ravel(), "vtkCellArray", None, 1),
                "fields": fields}}
        mapper = {
            "parent": pid, "id": f"{pid}-mapper", "type": "vtkMapper",
            "properties": {"scalarVisibility": 1, "colorMode": 2, "scalarMode": 3,
                           "colorByArrayName": scene.mode,
                           "interpolateScalarsBeforeMapping": 0},
            "calls": [["setInputData", [f"instance:${{{pid}-data}}"]]],
            "dependencies": [polydata]}
        # Unlit: the colour is the ambient term alone, exactly the baked value.
        prop = {
            "parent": pid, "id": f"{pid}-property", "type": "vtkOpenGLProperty",
            "properties": {"representation": 2, "ambient": 1.0, "diffuse": 0.0,
                           "specular": 0.0, "lighting": 0, "interpolation": 1,
                           "opacity": part.opacity, "backfaceCulling": int(part.culled)}}
        props.append({
            "parent": "renderer", "id": pid, "type": "vtkOpenGLActor",
            "properties": {"visibility": 1, "pickable": 1},
            "calls": [["setMapper", [f"instance:${{{pid}-mapper}}"]],
                      ["setProperty", [f"instance:${{{pid}-property}}"]]],
            "dependencies": [mapper, prop]})
    cam = {
        "parent": "renderer", "id": "camera", "type": "vtkOpenGLCamera",
        "properties": {
            "position": list(np.subtract(camera["position"], origin)),
            "focalPoint": list(np.subtract(camera["focal_point"], origin)),
            "viewUp": camera["view_up"], "viewAngle": camera["view_angle"],
            "parallelProjection": int(camera["parallel"]),
            "parallelScale": camera["parallel_scale"],
            "clippingRange": camera["clipping_range"]}}
    renderer = {
        "parent": "window", "id": "renderer", "type": "vtkOpenGLRenderer",
        "properties": {"background": list(scene.background), "viewport": [0, 0, 1, 1],
                       "layer": 0, "interactive": 1},
        "dependencies": [cam] + props,
        "calls": [["setActiveCamera", ["instance:${camera}"]]] +
                 [["addViewProp", [f"instance:${{{p['id']}}}"]] for p in props]}
    window = {"parent": "0x0", "id": "window", "type": "vtkXOpenGLRenderWindow",
              "properties": {"numberOfLayers": 1}, "dependencies": [renderer],
              "calls": [["addRenderer", ["instance:${renderer}"]]]}
    return {"hashes": arrays.hashes, "scene": window}


_POLICY = ('<meta http-equiv="Content-Security-Policy" content="default-src \'none\'; '
           "script-src 'unsafe-inline' 'unsafe-eval' blob:; style-src 'unsafe-inline'; "
           'img-src data: blob:; font-src data:; worker-src blob:; connect-src data: blob:">')

_PAGE_SCRIPT = """<style>
  #linkgi-view { position: absolute; inset: 0; }
  .linkgi-panel { position: absolute; z-index: 10; font: 13px sans-serif; color: #222;
    background: rgba(255, 255, 255, 0.85); border-radius: 4px; padding: 6px 8px; }
  #linkgi-modes { top: 8px; left: 8px; }
  #linkgi-modes button { font: inherit; margin-right: 2px; }
  #linkgi-modes button.active { font-weight: bold; }
  #linkgi-legend { bottom: 8px; right: 8px; width: 220px; }
  #linkgi-legend .bar { height: 12px; margin: 4px 0; }
  #linkgi-legend .ticks { display: flex; justify-content: space-between; }
</style>
<div id="linkgi-view"></div>
<div id="linkgi-modes" class="linkgi-panel">
  <button data-mode="combined">Combined</button><button data-mode="direct">Direct</button><button
    data-mode="indirect">Indirect</button>
</div>
%(legend)s
<script>
(function () {
  var scene = "%(scene)s";
  var parts = %(parts)d;
  var initial = "%(mode)s";
  function actors() {
    // The viewer's window has a renderer of its own besides the scene's.
    var w = window.global && window.global.renderWindow;
    var list = [];
    (w ? w.getRenderers() : []).forEach(function (r) { list = list.concat(r.getActors()); });
    return list;
  }
  function show(mode) {
    if (["combined", "direct", "indirect"].indexOf(mode) < 0) mode = initial;
    var list = actors();
    if (list.length < parts) { setTimeout(function () { show(mode); }, 20); return; }
    list.forEach(function (a) { a.getMapper().setColorByArrayName(mode); });
    window.global.renderWindow.render();
    document.querySelectorAll("#linkgi-modes button").forEach(function (b) {
      b.classList.toggle("active", b.dataset.mode === mode);
    });
    document.body.dataset.linkgiMode = mode;
  }
  document.querySelectorAll("#linkgi-modes button").forEach(function (b) {
    b.addEventListener("click", function () { location.hash = b.dataset.mode; });
  });
  window.addEventListener("hashchange", function () { show(location.hash.slice(1)); });
  // The viewer is a module script: it runs after this one. Load once it exists (its own
  // loadDataSet hook can run before the page is ready).
  var started = false;
  function start() {
    if (started) return;
    if (!window.OfflineLocalView) { setTimeout(start, 10); return; }
    started = true;
    OfflineLocalView.load(document.getElementById("linkgi-view"), { base64Str: scene });
    show(location.hash.slice(1));
  }
  window.loadDataSet = start;
  start();
})();
</script>
"""


def _legend_html(legend):
    if legend is None:
        return ""
    colors = legend["colors"][:: max(1, len(legend["colors"]) // 32)]
    stops = ", ".join(f"rgb({r},{g},{b})" for r, g, b in colors)
    lo, hi = legend["range"]
    title = (legend["title"] or "").replace("&", "&amp;").replace("<", "&lt;")
    return (f'<div id="linkgi-legend" class="linkgi-panel"><div>{title}</div>'
            f'<div class="bar" style="background: linear-gradient(to right, {stops})"></div>'
            f'<div class="ticks"><span>{lo:.4g}</span><span>{hi:.4g}</span></div></div>')


def write(scene, filename, title="LinkGI"):
    lo, hi = scene.bounds()
    origin = 0.5 * (lo + hi)  # float32 points relative to the centre keep their precision
    text = json.dumps(_state(scene, origin))
    if len(text) > BROWSER_STRING_LIMIT:
        raise ValueError(
            f"linkgi.export_html: the scene's {scene.triangles} triangles need "
            f"{len(text)} characters of JSON, more than a browser holds in one string "
            f"({BROWSER_STRING_LIMIT}): decimate the surface (vtkQuadricDecimation) or "
            "write glTF (linkgi.export_glb)")
    archive = io.BytesIO()
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("index.json", text)
    encoded = base64.b64encode(archive.getvalue()).decode("ascii")
    with open(viewer_path(), encoding="utf-8") as f:
        page = f.read()
    script = _PAGE_SCRIPT % {"scene": encoded, "parts": len(scene.parts), "mode": scene.mode,
                             "legend": _legend_html(scene.legend)}
    page = page.replace("</body>", script + "</body>", 1)
    # Nothing leaves the page: the viewer's favicon links (and anything else) stay local.
    page = page.replace('<meta charset="utf-8" />', '<meta charset="utf-8" />\n' + _POLICY, 1)
    page = page.replace("<title>VTK.js | Example - OfflineLocalView</title>",
                        f"<title>{title}</title>", 1)
    with open(filename, "w", encoding="utf-8") as f:
        f.write(page)
    return {"file": str(filename), "bytes": os.path.getsize(filename),
            "scene_bytes": len(encoded), "points": scene.points, "triangles": scene.triangles,
            "parts": len(scene.parts), "left_out": list(scene.left_out)}
