#!/usr/bin/env bash
# Build, whole suite, memcheck on instant radiosity's GPU tests and the small CUDA tests, IR + links
# benches on conference.
# From the repository root of a GPU machine, GoogleTest's sources in .gtest/googletest:
#   OUT=out bash Documentation/scripts/cuda-instant-radiosity-runs.sh
set -u
top=$PWD
export LINKGI_GPU_BUILD=/tmp/b
B=/tmp/b/bin
kernels/tools/gpu-session.sh $OUT/s $top/.gtest/googletest "" "build" 2>&1 | tail -20
cat $OUT/s/machine.txt
echo "== tests $(date +%T)"
timeout 240 $B/linkgi_kernel_tests > $OUT/tests.log 2>&1; echo "suite exit $?"
grep -E "^\[  (FAILED|PASSED|SKIPPED) |tests ran" $OUT/tests.log | head -30
grep -E "Failure|Expected|Which is|error" $OUT/tests.log | head -20
grep -E "IrCuda|TestInstantRadiosity.CpuAndCuda" $OUT/tests.log | grep -E "OK|FAILED" 
echo "== memcheck $(date +%T)"
small='IrCuda.*:TestInstantRadiosity.CpuAndCuda*:Cuda.BackendsAgreeOnARoom:CudaOffsets.*'
timeout 200 compute-sanitizer --tool memcheck --leak-check full --error-exitcode 3 $B/linkgi_kernel_tests --gtest_filter="$small" > $OUT/sanitizer.log 2>&1; echo "memcheck exit $?"
grep -E "ERROR SUMMARY|LEAK SUMMARY|PASSED|FAILED" $OUT/sanitizer.log | head
echo "== bench $(date +%T)"
IR="--backend cuda --method instant-radiosity --scenes conference --vpls 4096 --no-gather --no-bare"
for i in 1 2 3; do
  timeout 60 $B/linkgi-bench $IR --interleave 64 --proxy 16 --repeat 5 >> $OUT/bench-ir64.jsonl 2>>$OUT/bench.err
done
for i in 1 2; do
  timeout 60 $B/linkgi-bench $IR --interleave 16 --proxy 32 --repeat 5 >> $OUT/bench-ir16.jsonl 2>>$OUT/bench.err
done
timeout 60 $B/linkgi-bench ${IR/conference/torso} --interleave 64 --proxy 16 --repeat 5 >> $OUT/bench-torso.jsonl 2>>$OUT/bench.err
timeout 60 $B/linkgi-bench $IR --interleave 16 --repeat 5 >> $OUT/bench-ir16np.jsonl 2>>$OUT/bench.err
timeout 90 $B/linkgi-bench $IR --repeat 5 >> $OUT/bench-ir1.jsonl 2>>$OUT/bench.err
timeout 60 $B/linkgi-bench --backend cuda --scenes conference --repeat 7 --no-gather > $OUT/bench-links.jsonl 2>>$OUT/bench.err
timeout 60 $B/linkgi-bench --backend cuda --scenes conference --repeat 7 --no-gather >> $OUT/bench-links.jsonl 2>>$OUT/bench.err
tail -5 $OUT/bench.err
python3 - <<'PY'
import json,os,statistics as st
o=os.environ["OUT"]
for f in ("bench-ir64.jsonl","bench-ir16.jsonl","bench-torso.jsonl","bench-ir16np.jsonl","bench-ir1.jsonl","bench-links.jsonl"):
    rows=[]
    for line in open(os.path.join(o,f)):
        try: rows.append(json.loads(line))
        except Exception: pass
    for r in rows:
        m=r.get("median_ms",{})
        print(f, "full %.2f (med %.2f) light %.2f (med %.2f) deform %s vpls %s" % (r.get("ms_full_update",0), m.get("full_update",0), r.get("ms_light_update",0), m.get("light_update",0), r.get("ms_deform_update"), r.get("vpls")))
        print("   prepare %.2f stages" % r["ms_prepare"], {k:round(v,2) for k,v in r.get("stages_ms").items()}, "light", r.get("light_update_ms"))
        print("   deform first %.2f runs %s prepare %.2f" % (r["ms_deform_first"], [round(x,2) for x in r["ms_deform_update_runs"]], r["deform_ms_prepare"]), {k:round(v,2) for k,v in r["deform_stages_ms"].items()})
PY
echo "== done $(date +%T)"
