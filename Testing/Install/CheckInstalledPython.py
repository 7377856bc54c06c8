"""`import linkgi` from an installed LinkGI with nothing but its Python directory added to the
system Python's path, as Python finds it under the default prefix (no PYTHONPATH there).

Checks that the package, its wrapped modules and the LinkGI libraries they load (found by
relative RPATHs) all come from the prefix, then runs the installed example
sphere_on_plane.py, checks the light it computed and exports it as a web page and glTF (the
exporters find the vtk.js viewer where it was installed).

Usage: /usr/bin/python3 CheckInstalledPython.py <prefix> <python directory, relative to it>
       <examples directory> <output .vtp>
"""
import os
import runpy
import sys

from linkgi_install_checks import check, check_inside, check_sphere_on_plane

prefix, site, examples, output = sys.argv[1:5]
site_dir = os.path.join(os.path.realpath(prefix), site)
check(os.path.isdir(os.path.join(site_dir, "linkgi")), "a linkgi package in %s" % site_dir)
sys.path.insert(0, site_dir)

import linkgi  # noqa: E402

check_inside(site_dir, [linkgi.__file__], "linkgi")
check(hasattr(linkgi, "vtkGlobalIlluminationFilter")
      and hasattr(linkgi, "vtkGlobalIlluminationMapper"),
      "both modules wrapped: vtkGlobalIlluminationFilter, vtkGlobalIlluminationMapper")
# The LinkGI libraries in this process, from its memory map.
with open("/proc/self/maps") as maps:
    loaded = {line.split()[-1] for line in maps if "LinkGI" in line and ".so" in line}
check(any("libLinkGIRenderingGlobalIllumination" in path for path in loaded),
      "the wrapped modules loaded the LinkGI libraries")
check_inside(prefix, loaded, "the wrapped modules and the libraries they loaded")

sys.argv = ["sphere_on_plane.py", output]
try:
    runpy.run_path(os.path.join(examples, "sphere_on_plane.py"), run_name="__main__")
except SystemExit as exit_:  # the example ends with sys.exit(<whether it wrote the file>)
    check(exit_.code in (0, None), "the example sphere_on_plane.py ran")
check_sphere_on_plane(output)

# The exporters find their installed vtk.js viewer: the lit example as a web page and glTF.
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader  # noqa: E402

reader = vtkXMLPolyDataReader()
reader.SetFileName(output)
reader.Update()
page = linkgi.export_html(reader.GetOutput(), output + ".html")
with open(page["file"], encoding="utf-8") as f:
    text = f.read()
check("OfflineLocalView" in text and page["triangles"] > 0,
      "linkgi.export_html inlined the installed viewer (%d bytes)" % page["bytes"])
check(linkgi.export_glb(reader.GetOutput(), output + ".glb")["bytes"] > 0,
      "linkgi.export_glb wrote the lit example")
