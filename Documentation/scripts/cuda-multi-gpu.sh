#!/usr/bin/env bash
# One call on a multi-GPU machine: build, whole suite, conference/iphi on 1, 2 and all GPUs
# interleaved, isosurfaces (1M and 8M on one GPU, 16M on all), sanitizers on two GPUs.
# From the repository root, GoogleTest's sources in .gtest/googletest, e.g.
#   OUT=out TAG=m SCALE=16000000 SAN=1 bash Documentation/scripts/cuda-multi-gpu.sh
set -uo pipefail
export LINKGI_GPU_BUILD=/tmp/b
O=$OUT/${TAG:-m}; mkdir -p $O
nvidia-smi topo -m > $O/topo.txt 2>&1; nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv >> $O/topo.txt
kernels/tools/gpu-session.sh $O $PWD/.gtest/googletest "" "build test" 2>&1 | tail -12
B=/tmp/b/bin/linkgi-bench; T=/tmp/b/bin/linkgi_kernel_tests
n=$(nvidia-smi -L | wc -l)
for round in 1 2 3; do
  for d in $(printf "%s\n" 1 2 $n | uniq); do
    $B --backend cuda --devices $d --scenes conference,iphi --repeat 5 --no-gather 2>>$O/steps.log | sed "s/^{/{\"round\":$round,/"
  done
done > $O/multi.jsonl
python3 - $O/multi.jsonl <<'PY'
import json,sys
for l in open(sys.argv[1]):
    if not l.startswith('{'): continue
    d=json.loads(l); m=d['median_ms']; st=d['stages_ms']
    print(d['round'],d['scene'][:4],d['devices'],'geo %.2f topo %.2f links %.2f comp %.2f bounces %.2f smooth %.2f full %.2f light %.2f'%(st['Geometry'],st['Topology'],d['ms_links'],d['ms_compress'],d['ms_bounces'],d['ms_smoothing'],d['ms_full_update'],d['ms_light_update']), 'med full %.2f gen %.2f light %.2f'%(m['full_update'],m['link_generation'],m['light_update']), d['mean_indirect_irradiance'])
PY
if [ -n "${SCALE:-}" ]; then
( $B --backend cuda --devices 1 --scenes isosurface:1000000,isosurface:8000000 --repeat 2 --no-gather
  $B --backend cuda --devices $n --scenes isosurface:$SCALE --repeat 2 --no-gather ) > $O/scale.jsonl 2>>$O/steps.log
python3 - $O/scale.jsonl <<'PY'
import json,sys
for l in open(sys.argv[1]):
    if not l.startswith('{'): continue
    d=json.loads(l)
    print(d['scene'],d['devices'],d['vertices'],'links',d['links_compressed'],'gen %.1f full %.1f light %.1f'%(d['ms_link_generation'],d['ms_full_update'],d['ms_light_update']),'gpuGB %.1f'%(d['gpu_bytes_allocated']/1e9),'mean',d['mean_indirect_irradiance'],d.get('linked_per_device'),d['note'])
PY
tail -3 $O/steps.log
fi
if [ -n "${SAN:-}" ]; then
export CUDA_VISIBLE_DEVICES=0,1
[ -n "${MEMCHECK:-}" ] && { timeout ${MEM_S:-200} compute-sanitizer --tool memcheck --leak-check full --error-exitcode 3 $T --gtest_filter="${MEMCHECK}" > $O/memcheck2.log 2>&1; echo "memcheck exit $?"; }
[ -n "${RACE_S:-}" ] && timeout ${RACE_S} compute-sanitizer --tool racecheck --error-exitcode 3 $T --gtest_filter='Cuda.BackendsAgreeOnARoom' > $O/racecheck2.log 2>&1; echo "racecheck exit $?"
grep -h -E "ERROR SUMMARY|LEAK SUMMARY|RACECHECK SUMMARY|PASSED|FAILED|SKIPPED" $O/memcheck2.log $O/racecheck2.log
fi
