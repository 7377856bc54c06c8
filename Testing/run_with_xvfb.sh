#!/usr/bin/env bash
# Runs a command under an X server of its own (ParaView needs one, even pvbatch).
#
# - -noreset: by default an X server resets when its last client disconnects and drops
#   connections that arrive meanwhile; ParaView closes a probing connection and reconnects
#   at once, and under load loses that race ("bad X server connection").
# - Two X servers that start on one display at once break each other, and `xvfb-run -a`
#   picks its display by lock files before starting, so parallel tests can collide. Here
#   the choice and the start happen under a file lock, on displays from 200 up (away from
#   xvfb-run's 99 and up), and the command runs once the server reports (-displayfd) that
#   it accepts connections.
# Usage: run_with_xvfb.sh <command> [arguments...]
set -euo pipefail
dir=$(mktemp -d)
server=
trap '[ -n "$server" ] && kill $server 2>/dev/null; [ -n "$server" ] && wait $server 2>/dev/null; rm -rf "$dir"' EXIT

exec 9>"${TMPDIR:-/tmp}/linkgi-xvfb.lock"
flock 9
display=200
while [ -e "/tmp/.X$display-lock" ] || [ -e "/tmp/.X11-unix/X$display" ]; do
  display=$((display + 1))
done
Xvfb ":$display" -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$dir/display" 2>"$dir/log" &
server=$!
for _ in $(seq 1 300); do
  [ -s "$dir/display" ] && break
  kill -0 "$server" 2>/dev/null || break
  sleep 0.1
done
flock -u 9
exec 9>&-
if [ ! -s "$dir/display" ]; then
  echo "FAILED: Xvfb :$display did not start:"
  cat "$dir/log"
  exit 1
fi
export DISPLAY=":$display"
"$@"
