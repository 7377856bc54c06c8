#!/usr/bin/env bash
# Builds the Debian packages of LinkGI with CPack:
#   linkgi_<version>_<arch>.deb           VTK modules, `import linkgi`, headers, CMake package
#   linkgi-paraview_<version>_<arch>.deb  the ParaView 5.11 plugin
# into build/package/packages/. A build of its own, configured for /usr: Debian's Python
# reads /usr/lib/python3/dist-packages there (and /usr/local/lib/python3.X/dist-packages under
# /usr/local, the layout of build/), and ParaView finds plugins by name in its own directory.
# Install with: apt install ./build/package/packages/*.deb
# Usage: scripts/package.sh [--no-setup] [extra configure arguments]
#   --no-setup  skip scripts/setup.sh (the packages it installs are already there)
#   LINKGI_PACKAGE_BUILD=<dir> builds elsewhere.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = "--no-setup" ]; then
  shift
else
  "$top/scripts/setup.sh"
fi
build=${LINKGI_PACKAGE_BUILD:-$top/build/package}
cmake -S "$top" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DBUILD_TESTING=OFF -DLINKGI_BUILD_EXAMPLES=OFF "$@"
cmake --build "$build" -j "$(nproc)"
rm -f "$build"/packages/*.deb
(cd "$build" && cpack -G DEB)
ls -1 "$build"/packages/*.deb
