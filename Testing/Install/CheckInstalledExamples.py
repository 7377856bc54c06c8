"""The C++ examples built against an installed LinkGI (a project of their own that found it
with find_package(LinkGI)): they load the installed libraries, GlobalIlluminationSphereOnPlane
computes the expected light, and linkgi-demo renders through the Rendering module.

Usage: /usr/bin/python3 CheckInstalledExamples.py <prefix> <examples' build directory>
"""
import os
import subprocess
import sys

from linkgi_install_checks import check, check_inside, check_sphere_on_plane

prefix, build = sys.argv[1:3]
for program in ("GlobalIlluminationSphereOnPlane", "linkgi-demo"):
    ldd = subprocess.run(["ldd", os.path.join(build, program)], check=True,
                         capture_output=True, text=True).stdout
    libraries = [line.split("=>")[1].split("(")[0].strip()
                 for line in ldd.splitlines() if "libLinkGI" in line and "=>" in line]
    check_inside(prefix, libraries, "%s's LinkGI libraries" % program)

output = os.path.join(build, "sphere_on_plane.vtp")
subprocess.run([os.path.join(build, "GlobalIlluminationSphereOnPlane"), output], check=True)
check_sphere_on_plane(output)

image = os.path.join(build, "linkgi-demo.png")
if os.path.exists(image):
    os.remove(image)
subprocess.run([os.path.join(build, "linkgi-demo"), image], check=True,
               stdout=subprocess.DEVNULL)
check(os.path.getsize(image) > 10000, "linkgi-demo rendered %s" % image)
