"""What the agreement scripts share: luminance, vertex areas and the area-weighted relative
RMSE, as the engine's tests take them (linkgi::vertexAreas, linkgi::relativeRmse)."""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec. 709


def vertex_areas(surface):
    """A third of each triangle's area to each of its corners (linkgi::vertexAreas)."""
    p = vtk_to_numpy(surface.GetPoints().GetData()).astype(float)
    t = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    third = np.linalg.norm(np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]), axis=1) / 6
    areas = np.zeros(len(p))
    for k in range(3):
        np.add.at(areas, t[:, k], third)
    return areas


def rel_rmse(a, r, w):
    """Area-weighted relative RMSE of a against r, weights w."""
    return float(np.sqrt(np.sum(w * (a - r) ** 2) / np.sum(w * r ** 2)))
