#!/usr/bin/env bash
# Durations of the link method's light-update kernels on conference (ncu, caches and clocks as they are).
# From the repository root of a GPU machine, GoogleTest's sources in .gtest/googletest:
#   OUT=out bash Documentation/scripts/cuda-light-kernels-ncu.sh
set -u
export LINKGI_GPU_BUILD=/tmp/b
B=/tmp/b/bin
[ -x $B/linkgi-bench ] || kernels/tools/gpu-session.sh $OUT/s $PWD/.gtest/googletest "" "build" 2>&1 | tail -3
timeout 400 ncu --cache-control none --clock-control none --kernel-name regex:'shadowSamplesKernel|combineKernel|startKernel|bounceKernel|finishKernel' \
  --launch-count 60 --section SpeedOfLight $B/linkgi-bench --backend cuda --scenes conference --repeat 1 --no-gather > $OUT/ncu.log 2>&1
echo "ncu exit $?"
python3 - <<'PY'
import os,re
name=None; rows=[]
for line in open(os.path.join(os.environ["OUT"],"ncu.log")):
    m=re.match(r"\s+(?:void )?\S*?(\w+Kernel)\b.*\((\d+), 1, 1\)x\((\d+)", line)
    if m: name=m.group(1); continue
    m=re.match(r"\s+Duration\s+(\w+)\s+([\d.]+)", line)
    if m and name:
        v=float(m.group(2)); v = v/1000 if m.group(1)=="us" else (v if m.group(1)=="ms" else v/1e6)
        rows.append((name,v)); name=None
print(len(rows), "launches")
print(" ".join("%s:%.3f" % (n[:-6],v) for n,v in rows))
PY
