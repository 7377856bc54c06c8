"""Share what you see: a lit scene as a self-contained web page or a glTF 2.0 file.

The light LinkGI computes is data on the mesh, so the colours the global illumination
mappers display can be baked per vertex (vtkGlobalIlluminationDisplayColors) and shown by
any viewer that draws vertex colours, with no renderer of ours:

    import linkgi
    linkgi.export_html(render_window, "scene.html")   # opens from disk, no network
    linkgi.export_glb(render_window, "scene.glb")     # Blender, any glTF viewer

Both take what the user looks at: a vtkRenderWindow or vtkRenderer (VTK Python), a
ParaView view (pvpython, pvbatch), or a lit dataset (the output of
vtkGlobalIlluminationFilter) with an optional camera and lights. A PyVista Plotter is taken
by its renderer (linkgi.pyvista). The shadows are the filter's per-vertex shadows: the
mappers' per-pixel shadow maps do not carry over.
"""
import numpy as np

from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals, vtkTriangleFilter
from vtkmodules.vtkRenderingCore import vtkLightCollection, vtkRenderer, vtkRenderWindow
from vtkmodules.util.numpy_support import vtk_to_numpy

from .LinkGIRenderingGlobalIllumination import (vtkGlobalIlluminationDisplayColors,
                                                vtkGlobalIlluminationShading)

MODES = ("combined", "direct", "indirect")


class Part:
    """One drawn surface, baked: world coordinates (float64), triangles, unit normals,
    and per mode the displayed colours (uint8 RGB, display values)."""

    def __init__(self, name, points, triangles, normals, colors, culled, opacity):
        self.name = name
        self.points = points
        self.triangles = triangles
        self.normals = normals
        self.colors = colors
        self.culled = culled  # back faces hidden (a two-sided solution's front, or its back)
        self.opacity = opacity


class LitScene:
    """What an exporter writes: the parts, the camera, the background, the legend."""

    def __init__(self):
        self.parts = []
        self.camera = None      # dict: position, focal_point, view_up, view_angle, parallel...
        self.background = (1.0, 1.0, 1.0)
        self.legend = None      # dict: title, range, colors (N x 3 uint8)
        self.mode = "combined"  # the display mode the mappers showed
        self.left_out = []      # what could not be baked, and why

    @property
    def triangles(self):
        return sum(len(p.triangles) for p in self.parts)

    @property
    def points(self):
        return sum(len(p.points) for p in self.parts)

    def bounds(self):
        lo = np.min([p.points.min(axis=0) for p in self.parts if len(p.points)], axis=0)
        hi = np.max([p.points.max(axis=0) for p in self.parts if len(p.points)], axis=0)
        return lo, hi


def _camera_dict(camera):
    return {
        "position": list(camera.GetPosition()),
        "focal_point": list(camera.GetFocalPoint()),
        "view_up": list(camera.GetViewUp()),
        "view_angle": camera.GetViewAngle(),
        "parallel": bool(camera.GetParallelProjection()),
        "parallel_scale": camera.GetParallelScale(),
        "clipping_range": list(camera.GetClippingRange()),
    }


def _leaves(data):
    """The polydata leaves of a dataset or composite dataset, with their names."""
    if isinstance(data, vtkPolyData):
        return [("", data)]
    if not isinstance(data, vtkCompositeDataSet):
        return []
    leaves = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        leaf = it.GetCurrentDataObject()
        if isinstance(leaf, vtkPolyData):
            name = ""
            meta = it.GetCurrentMetaData() if it.HasCurrentMetaData() else None
            if meta is not None and meta.Has(vtkCompositeDataSet.NAME()):
                name = meta.Get(vtkCompositeDataSet.NAME())
            leaves.append((name, leaf))
        it.GoToNextItem()
    return leaves


def _array(poly, name):
    array = poly.GetPointData().GetArray(name)
    return None if array is None else vtk_to_numpy(array)


def _parts(baked, name, matrix, opacity, scene):
    """The triangles of one baked polydata as Parts (two where the solution is two-sided)."""
    triangles = vtkTriangleFilter()
    triangles.PassVertsOff()
    triangles.PassLinesOff()
    triangles.SetInputData(baked)
    triangles.Update()
    tri = triangles.GetOutput()
    skipped = baked.GetNumberOfVerts() + baked.GetNumberOfLines()
    if skipped:
        scene.left_out.append(f"{name or 'a block'}: {skipped} vertices and lines (unlit)")
    if tri.GetNumberOfPolys() == 0:
        return []
    if tri.GetPointData().GetNormals() is None:
        normals = vtkPolyDataNormals()
        normals.SetInputData(tri)
        normals.SplittingOff()
        normals.ConsistencyOff()
        normals.Update()
        tri = normals.GetOutput()
    points = vtk_to_numpy(tri.GetPoints().GetData()).astype(np.float64)
    cells = vtk_to_numpy(tri.GetPolys().GetConnectivityArray()).astype(np.int64).reshape(-1, 3)
    normals = vtk_to_numpy(tri.GetPointData().GetNormals()).astype(np.float64)
    if matrix is not None:
        m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
        points = points @ m[:3, :3].T + m[:3, 3]
        normals = normals @ np.linalg.inv(m[:3, :3])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = (normals / np.where(lengths > 0, lengths, 1.0)).astype(np.float32)
    # Viewers cull and choose a side by winding; LinkGI's front is where the normals point
    # (also after a mirroring transform): wind every triangle that way.
    corners = points[cells]
    face = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    against = np.einsum("ij,ij->i", face, normals[cells].sum(axis=1)) < 0
    cells[against] = cells[against][:, ::-1]

    def colors(back):
        return {mode: _array(tri, vtkGlobalIlluminationDisplayColors.GetColorsArrayName(k, back))
                for k, mode in enumerate(MODES)}

    front = colors(False)
    back = colors(True)
    if back["combined"] is None:
        return [Part(name, points, cells, normals, front, False, opacity)]
    # Two-sided: the back faces are a surface of their own, wound the other way.
    return [Part(name, points, cells, normals, front, True, opacity),
            Part(name + " (back)" if name else "back", points, cells[:, ::-1].copy(), -normals,
                 back, True, opacity)]


def _legend(mapper):
    """The colour map of a mapper that colours by scalars, as a legend."""
    if mapper is None or not mapper.GetScalarVisibility() or mapper.GetLookupTable() is None:
        return None
    name = mapper.GetArrayName()
    if not name:
        return None
    table = mapper.GetLookupTable()
    lo, hi = table.GetRange() if mapper.GetUseLookupTableScalarRange() else mapper.GetScalarRange()
    rgb = [0.0, 0.0, 0.0]
    colors = []
    for value in np.linspace(lo, hi, 256):
        table.GetColor(value, rgb)
        colors.append([int(round(255 * c)) for c in rgb])
    colors = np.array(colors, dtype=np.uint8)
    return {"title": name, "range": [lo, hi], "colors": colors}


def _bake_actor(actor, renderer, scene):
    mapper = actor.GetMapper()
    data = mapper.GetInputDataObject(0, 0)
    if data is None or data.GetNumberOfPoints() == 0:
        return  # draws nothing (ParaView keeps empty actors of other representations)
    if not hasattr(mapper, "GetShading"):
        scene.left_out.append(f"an actor drawn by {mapper.GetClassName()}, not by a global "
                              "illumination mapper")
        return
    colors = vtkGlobalIlluminationDisplayColors()
    colors.SetInputData(data)
    colors.SetMapper(mapper)
    colors.SetProperty(actor.GetProperty())
    colors.SetShading(mapper.GetShading())
    colors.SetLights(renderer.GetLights())
    colors.Update()
    matrix = actor.GetMatrix()
    identity = all(matrix.GetElement(i, j) == (1.0 if i == j else 0.0)
                   for i in range(4) for j in range(4))
    for name, leaf in _leaves(colors.GetOutputDataObject(0)):
        scene.parts += _parts(leaf, name, None if identity else matrix,
                              actor.GetProperty().GetOpacity(), scene)
    scene.mode = MODES[mapper.GetShading().GetDisplayMode()]
    if scene.legend is None:
        scene.legend = _legend(mapper)


def _renderer_of(target):
    """The renderer of a render window, a PyVista plotter or a ParaView view."""
    if isinstance(target, vtkRenderer):
        return target
    if isinstance(target, vtkRenderWindow):
        return target.GetRenderers().GetFirstRenderer()
    if hasattr(target, "renderer") and isinstance(target.renderer, vtkRenderer):
        return target.renderer  # pyvista.Plotter
    if hasattr(target, "GetRenderer"):
        return target.GetRenderer()  # ParaView's render view proxy
    return None


def bake(target, camera=None, lights=None, shading=None):
    """The displayed colours of `target`, baked per vertex: a LitScene.

    `target` is a vtkRenderWindow, vtkRenderer, PyVista Plotter or ParaView view (every
    visible actor drawn by a global illumination mapper, with the renderer's lights and
    camera), or a lit dataset: vtkGlobalIlluminationFilter's output (vtkPolyData or a
    composite of them), drawn white (or in its Albedo array) with `shading` (a
    vtkGlobalIlluminationShading, default settings if None), the `lights` it was lit by
    (vtkLight objects, for the lamp look) and `camera` (a vtkCamera; None frames the data).
    """
    scene = LitScene()
    renderer = _renderer_of(target)
    if renderer is not None:
        actors = renderer.GetActors()
        actors.InitTraversal()
        for _ in range(actors.GetNumberOfItems()):
            actor = actors.GetNextActor()
            if actor.GetVisibility() and actor.GetMapper() is not None:
                _bake_actor(actor, renderer, scene)
        scene.camera = _camera_dict(renderer.GetActiveCamera())
        scene.background = tuple(renderer.GetBackground())
    elif isinstance(target, (vtkPolyData, vtkCompositeDataSet)):
        colors = vtkGlobalIlluminationDisplayColors()
        colors.SetInputData(target)
        colors.SetShading(shading or vtkGlobalIlluminationShading())
        if lights:
            collection = vtkLightCollection()
            for light in lights:
                collection.AddItem(light)
            colors.SetLights(collection)
        colors.Update()
        for name, leaf in _leaves(colors.GetOutputDataObject(0)):
            scene.parts += _parts(leaf, name, None, 1.0, scene)
        scene.mode = MODES[colors.GetShading().GetDisplayMode()]
        if camera is None:
            lo, hi = scene.bounds() if scene.parts else (np.zeros(3), np.ones(3))
            renderer = vtkRenderer()
            renderer.ResetCamera(*np.ravel(np.column_stack([lo, hi])))
            camera = renderer.GetActiveCamera()
        scene.camera = _camera_dict(camera)
    else:
        raise TypeError(
            f"linkgi: cannot export a {type(target).__name__}: give a vtkRenderWindow, a "
            "vtkRenderer, a PyVista Plotter, a ParaView view or vtkGlobalIlluminationFilter's "
            "output")
    if not scene.parts:
        raise ValueError("linkgi: nothing to export: no surface drawn by a global illumination "
                         "mapper (or no lit polydata)" +
                         (f"; left out: {'; '.join(scene.left_out)}" if scene.left_out else ""))
    return scene


def export_html(target, filename, camera=None, lights=None, shading=None, title="LinkGI"):
    """Writes `target` (see bake()) as one self-contained .html file: the baked colours in
    vtk.js, orbit and zoom, the colour-map legend, and a toggle among combined, direct and
    indirect light. Returns a size report (a dict)."""
    from . import _vtkjs
    return _vtkjs.write(bake(target, camera, lights, shading), filename, title)


def export_glb(target, filename, camera=None, lights=None, shading=None):
    """Writes `target` (see bake()) as binary glTF 2.0 (.glb): the displayed colours as
    COLOR_0 of unlit materials (KHR_materials_unlit), normals, one node per block and the
    camera. Returns a size report (a dict)."""
    from . import _gltf
    return _gltf.write(bake(target, camera, lights, shading), filename)
