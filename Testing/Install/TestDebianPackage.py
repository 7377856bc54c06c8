"""The Debian packages: built by scripts/package.sh, installed with `dpkg -i` into a scratch
root (a dpkg database of its own, so the machine's packages stay as they were), checked
there, and removed again.

- The Depends of each package are met by this machine's installed packages (what
  `apt install ./linkgi_*.deb` would need to find).
- The files are where Debian's programs look: the Python package in
  /usr/lib/python3/dist-packages, the plugin in ParaView's plugin directory.
- No file refers to the package's build tree.
- The system Python imports linkgi from the root and runs the installed example
  (CheckInstalledPython.py), loading the root's libraries through relative RPATHs.
- Removing the packages leaves no file behind.

Maintainer scripts run outside the root (dpkg --force-script-chrootless) with `ldconfig`
replaced by a stub that records its call: the real one would rebuild this machine's cache
and knows nothing of the root.

Usage: /usr/bin/python3 TestDebianPackage.py <source dir> <work dir> <LinkGI version>
"""
import fcntl
import glob
import os
import shutil
import subprocess
import sys

from linkgi_install_checks import check

source, work, version = sys.argv[1:4]
build = os.path.join(work, "package-build")
root = os.path.join(work, "root")
here = os.path.dirname(os.path.abspath(__file__))
# Two ctest runs in one build tree would configure, package and install into the same
# directories at once: the second waits.
os.makedirs(work, exist_ok=True)
lock = open(os.path.join(work, "lock"), "w")
fcntl.flock(lock, fcntl.LOCK_EX)


def run(*command, quiet=False, **kwargs):
    """Runs `command`; with `quiet`, shows its output only when it fails."""
    print("+ " + " ".join(command), flush=True)
    if not quiet:
        return subprocess.run(command, check=True, **kwargs)
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            **kwargs)
    if result.returncode != 0:
        print(result.stdout)
        check(False, "%s exited with %d" % (command[0], result.returncode))
    return result


def output(*command):
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout.strip()


# The packages, by the documented command (the packages it needs are installed already).
environment = dict(os.environ, LINKGI_PACKAGE_BUILD=build)
run(os.path.join(source, "scripts", "package.sh"), "--no-setup", env=environment, quiet=True)
arch = output("dpkg", "--print-architecture")
debs = {name: os.path.join(build, "packages", "%s_%s_%s.deb" % (name, version, arch))
        for name in ("linkgi", "linkgi-paraview")}
for name, deb in debs.items():
    check(os.path.exists(deb), "built %s" % os.path.basename(deb))


def satisfied(relation):
    """Whether an installed package satisfies `name[:arch] [(op version)]`."""
    name, _, constraint = relation.strip().partition(" ")
    name = name.split(":")[0]
    status = subprocess.run(["dpkg-query", "-W", "-f=${Status} ${Version}", name],
                            capture_output=True, text=True).stdout.split()
    if status[:3] != ["install", "ok", "installed"]:
        return False
    if not constraint:
        return True
    op, wanted = constraint.strip("()").split()
    return subprocess.run(["dpkg", "--compare-versions", status[3], op, wanted]).returncode == 0


for name, deb in debs.items():
    depends = output("dpkg-deb", "-f", deb, "Depends")
    unmet = [clause.strip() for clause in depends.split(",")
             if not any(satisfied(alternative) for alternative in clause.split("|"))]
    check(not unmet, "%s Depends: %s; met here (unmet: %s)" % (name, depends, unmet))
for needed in ("python3-vtk9", "libvtk9.1", "libembree3-3", "libtbb12"):
    check(needed in output("dpkg-deb", "-f", debs["linkgi"], "Depends"),
          "linkgi depends on %s" % needed)
check("paraview" in output("dpkg-deb", "-f", debs["linkgi-paraview"], "Depends"),
      "linkgi-paraview depends on paraview")

# A scratch root with an empty dpkg database.
shutil.rmtree(root, ignore_errors=True)
admin = os.path.join(root, "var", "lib", "dpkg")
for directory in ("updates", "info", "triggers"):
    os.makedirs(os.path.join(admin, directory))
open(os.path.join(admin, "status"), "w").close()
stubs = os.path.join(work, "stubs")
os.makedirs(stubs, exist_ok=True)
ldconfig_log = os.path.join(work, "ldconfig.log")
with open(os.path.join(stubs, "ldconfig"), "w") as stub:
    stub.write('#!/bin/sh\necho "ldconfig $*" >> "%s"\n' % ldconfig_log)
os.chmod(os.path.join(stubs, "ldconfig"), 0o755)
if os.path.exists(ldconfig_log):
    os.remove(ldconfig_log)
dpkg = ["dpkg", "--root=" + root, "--force-script-chrootless", "--force-depends",
        "--force-not-root", "--log=" + os.path.join(work, "dpkg.log")]
environment = dict(os.environ, PATH=stubs + os.pathsep + os.environ["PATH"])

# The root's empty database lacks every dependency: dpkg says so at length, and goes on.
run(*dpkg, "-i", *debs.values(), env=environment, quiet=True)
check(os.path.exists(ldconfig_log), "the maintainer scripts ran (ldconfig after the libraries)")
listed = [path for name in debs for path in output(*dpkg, "-L", name).splitlines()]
multiarch = output("dpkg-architecture", "-qDEB_HOST_MULTIARCH")
for path in ("/usr/lib/python3/dist-packages/linkgi/__init__.py",
             "/usr/lib/%s/cmake/LinkGI/LinkGIConfig.cmake" % multiarch,
             "/usr/lib/%s/libLinkGIFiltersGlobalIllumination.so" % multiarch,
             "/usr/include/linkgi/vtkGlobalIlluminationFilter.h",
             "/usr/share/doc/linkgi/examples/Python/sphere_on_plane.py",
             "/usr/lib/%s/paraview-5.11/plugins/LinkGI/LinkGI.so" % multiarch,
             "/usr/lib/%s/paraview-5.11/plugins/LinkGI.xml" % multiarch):
    check(path in listed and os.path.exists(root + path), "installed %s" % path)
referring = subprocess.run(["grep", "-rlF", build, os.path.join(root, "usr")],
                           capture_output=True, text=True).stdout.split()
check(not referring, "no installed file refers to the build tree (%s)" % referring)

# The system Python, with the root's dist-packages on its path.
run("/usr/bin/python3", os.path.join(here, "CheckInstalledPython.py"), os.path.join(root, "usr"),
    "lib/python3/dist-packages", os.path.join(root, "usr/share/doc/linkgi/examples/Python"),
    os.path.join(work, "sphere_on_plane.vtp"))

run(*dpkg, "--purge", "linkgi-paraview", "linkgi", env=environment, quiet=True)
left = [os.path.join(d, f) for d, _, files in os.walk(os.path.join(root, "usr")) for f in files]
check(not left and not glob.glob(os.path.join(admin, "info", "linkgi*")),
      "removed without a trace (left: %s)" % left[:5])
