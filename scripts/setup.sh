#!/usr/bin/env bash
# Installs the Debian 12 packages LinkGI needs, only those that are missing, and unpacks
# python3-paraview into a build-local prefix (it conflicts with python3-vtk9 system-wide).
# Usage: scripts/setup.sh [--paraview-python]      (run as root, or with sudo available)
# The unpacking always happens now (--paraview-python is kept for old callers): the
# ParaView plugin's build needs the wrapping files in it, and a build configured without
# it would leave the plugin out.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libvtk9-dev python3-vtk9 python3-numpy
  paraview-dev
  libembree-dev libtbb-dev libopenmesh-dev
  libgtest-dev libgmock-dev
  xvfb xauth libgl1-mesa-dri
  dpkg-dev file
  clang libclang-rt-14-dev libfuzzer-14-dev
  python3-sphinx python3-myst-parser python3-pydata-sphinx-theme
  chromium blender python3-venv python3-matplotlib
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#packages[@]} packages present"
fi

# pvbatch needs ParaView's Python modules, and the plugin build ParaView's wrapping
# hierarchy files, both in python3-paraview, which cannot be installed next to
# python3-vtk9: unpack its .deb into build/python3-paraview instead.
top=$(cd "$(dirname "$0")/.." && pwd)
prefix="$top/build/python3-paraview"
if [ ! -d "$prefix/usr/lib/python3/dist-packages/paraview" ]; then
  mkdir -p "$prefix" && cd "$prefix"
  rm -f python3-paraview_*.deb
  apt-get download python3-paraview >/dev/null 2>&1 || { "${sudo_cmd[@]}" apt-get update -qq && apt-get download python3-paraview; }
  dpkg -x python3-paraview_*.deb "$prefix" && rm -f python3-paraview_*.deb
  echo "setup: unpacked python3-paraview into $prefix"
fi

# linkgi.export_html inlines vtk.js's offline viewer from the trame-vtk wheel (PyPI), which
# the build unpacks (cmake/LinkGIInstall.cmake); pinned by version and checksum.
wheel="$top/build/downloads/trame_vtk-2.11.17-py3-none-any.whl"
sha=8fe2adbe3b6888ad41cb4311421fbd850cece75a801bf8b5f7af5bdc6473bee4
if ! echo "$sha  $wheel" | sha256sum --check --status 2>/dev/null; then
  mkdir -p "$top/build/downloads"
  python3 -m pip download --quiet --no-deps --only-binary=:all: trame-vtk==2.11.17 \
    -d "$top/build/downloads"
  echo "$sha  $wheel" | sha256sum --check --quiet || { echo "setup: $wheel: wrong checksum" >&2; exit 1; }
  echo "setup: downloaded $(basename "$wheel")"
fi

# Python packages from PyPI for LinkGI's Python extras, in a virtual environment of
# Debian's Python that sees its VTK (--system-site-packages): trame for python -m linkgi.web,
# PyVista for linkgi.pyvista. PyVista 0.46.5 is the newest that runs on VTK 9.1; it goes in
# without its declared dependencies (they would pull PyPI's VTK over Debian's): the others
# come from the line before and Debian (numpy, matplotlib, Pillow).
venv="$top/build/venv"
if ! "$venv/bin/python" -c "import trame, trame_vtk, trame_vuetify, pyvista" 2>/dev/null; then
  /usr/bin/python3 -m venv --system-site-packages "$venv"
  "$venv/bin/pip" install --quiet trame==4.0.0 trame-vtk==2.11.17 trame-vuetify==3.3.0 \
    scooby==0.12.1 pooch==1.9.0 typing-extensions==4.16.0
  "$venv/bin/pip" install --quiet --no-deps pyvista==0.46.5
  echo "setup: made $venv with trame and PyVista"
fi
