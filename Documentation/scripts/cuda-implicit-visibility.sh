#!/usr/bin/env bash
# Implicit visibility on one GPU: build, its tests (and the whole suite), sanitizers, benchmarks.
# From the repository root of a GPU machine, GoogleTest's sources in .gtest/googletest:
#   OUT=out TAG=m1 bash Documentation/scripts/cuda-implicit-visibility.sh   (SUITE=1 SAN=1: also the
#   whole kernel suite and compute-sanitizer)
set -uo pipefail
export LINKGI_GPU_BUILD=/tmp/b
O=$OUT/${TAG:-iv}; mkdir -p $O
kernels/tools/gpu-session.sh $O $PWD/.gtest/googletest "" "build" 2>&1 | tail -5
B=/tmp/b/bin/linkgi-bench; T=/tmp/b/bin/linkgi_kernel_tests
$T --gtest_filter='TestImplicitVisibility.*' 2>&1 | grep -E "CPU/GPU|OK|FAILED|Failure|Expected|Which|error|  Actual|SKIPPED" | head -60
if [ -n "${SUITE:-}" ]; then $T > $O/tests.log 2>&1; grep -E "^\[  (PASSED|FAILED|SKIPPED) " $O/tests.log | head -12; fi
summ() { python3 -c "
import json,sys
for l in sys.stdin:
    if not l.startswith('{'): continue
    d=json.loads(l); m=d.get('median_ms',{})
    print(d['scene'],d['backend'],d.get('bins'),d['vertices'],'full %.2f (med %.2f) light %.2f deform %s'%(d['ms_full_update'],m.get('full_update',0),d['ms_light_update'],d.get('ms_deform_update')),'links',d['links_raw'],d['links_compressed'],{k:round(v,2) for k,v in d['stages_ms'].items()}, d['note'][:60])
"; }
for n in 8 12 16; do
  $B --backend cuda --method implicit-visibility --bins $n --scenes torso,cornell --repeat 5 --no-bare --no-gather 2>>$O/steps.log | sed "s/^{/{\"bins\":$n,/" ; done > $O/iv-cuda.jsonl
summ < $O/iv-cuda.jsonl
$B --backend cuda --method implicit-visibility --bins 8 --scenes colorlamp,tearoom,iphi,conference --repeat 3 --no-bare --no-gather 2>>$O/steps.log | sed 's/^{/{"bins":8,/' > $O/iv-cuda-growth.jsonl
summ < $O/iv-cuda-growth.jsonl
$B --backend cpu --method implicit-visibility --bins 8 --scenes torso --repeat 3 --no-bare --no-gather 2>>$O/steps.log | sed 's/^{/{"bins":8,/' > $O/iv-cpu16.jsonl
summ < $O/iv-cpu16.jsonl
tail -3 $O/steps.log
if [ -n "${SAN:-}" ]; then
timeout 150 compute-sanitizer --tool memcheck --leak-check full --error-exitcode 3 $T --gtest_filter='TestImplicitVisibility.Cuda*:TestImplicitVisibility.MoreBins*' > $O/memcheck.log 2>&1; echo "memcheck exit $?"
timeout 150 compute-sanitizer --tool racecheck --error-exitcode 3 $T --gtest_filter='TestImplicitVisibility.CudaRefits*' > $O/racecheck.log 2>&1; echo "racecheck exit $?"
grep -h -E "ERROR SUMMARY|LEAK SUMMARY|RACECHECK SUMMARY" $O/memcheck.log $O/racecheck.log
fi
