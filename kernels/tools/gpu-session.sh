#!/usr/bin/env bash
# The CUDA backend's checks and measurements in one go on a GPU machine that has CUDA, CMake
# and ninja but no VTK, Embree, TBB or GoogleTest package: configures the engine on its own,
# builds it, runs the GPU tests, compute-sanitizer on small scenes, and linkgi-bench.
#
#   kernels/tools/gpu-session.sh OUT [GTEST_SRC] [REFERENCE_DIR] [STEPS]
#
# OUT: folder for the logs. GTEST_SRC: GoogleTest sources (e.g. a copy of /usr/src/googletest)
# where no package exists. REFERENCE_DIR: CPU (Embree) solutions written by
# `linkgi-bench --backend cpu --scenes cornell,tearoom --dump DIR`, to compare against.
# STEPS: any of "build test sanitize bench photons partitions scale multi ab profile"
# (default: build test sanitize bench partitions scale). photons: photon mapping's H200
# benchmark (Methods.md), three rounds, and its CPU/CUDA test under racecheck. ab: conference with the shipped defaults against the
# testing knobs' variants (the linear BVH, PLOC radii), interleaved, in one run. profile:
# Nsight Compute's summary of the link, compression and bounce kernels (where ncu exists).
set -uo pipefail
out=${1:?output folder}
gtest=${2:-}
ref=${3:-}
steps=${4:-build test sanitize bench partitions scale}
top=$(cd "$(dirname "$0")/../.." && pwd)
build=${LINKGI_GPU_BUILD:-/tmp/linkgi-gpu-build}
mkdir -p "$out"
has() { [[ " $steps " == *" $1 "* ]]; }
stamp() { echo "== $1 $(date +%T)" | tee -a "$out/steps.log"; }

if has build; then
  stamp build
  { nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv
    nvcc --version | tail -2; cmake --version | head -1; nproc; } > "$out/machine.txt" 2>&1
  cmake -S "$top/kernels" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_POLICY_VERSION_MINIMUM=3.5 \
    ${gtest:+-DLINKGI_GTEST_SOURCE_DIR=$gtest} > "$out/build.log" 2>&1 &&
    cmake --build "$build" -j "$(nproc)" >> "$out/build.log" 2>&1 || { tail -40 "$out/build.log"; exit 1; }
  grep -E "warning|error" "$out/build.log" | sort -u | head -20
fi
tests=$build/bin/linkgi_kernel_tests
if has test; then
  stamp test
  # The whole suite: GPU tests, and CPU tests whose default (Auto) backend is now the GPU.
  "$tests" > "$out/tests.log" 2>&1
  grep -E "^\[  (FAILED|PASSED|SKIPPED) |Failure|Expected|Which is|error" "$out/tests.log" | head -40
fi
if has sanitize; then
  stamp sanitize
  small='Cuda.BackendsAgreeOnARoom:Cuda.ManyRaysPerVertexUseTheWideMerge:Cuda.BackendsAgreeTwoSidedWithAnEnvironmentMap'
  small+=':Cuda.PartitionsOnOneGpuGiveTheOneGpuSolution:CudaOffsets.*'
  compute-sanitizer --tool memcheck --leak-check full --error-exitcode 3 "$tests" --gtest_filter="$small" \
    > "$out/sanitizer.log" 2>&1
  echo "memcheck exit $?" | tee -a "$out/sanitizer.log"
  # Racecheck looks for shared-memory hazards in kernels, which the partition test shares
  # with this one; on tearoom it ran past 10 minutes.
  compute-sanitizer --tool racecheck --error-exitcode 3 "$tests" --gtest_filter='Cuda.BackendsAgreeOnARoom' \
    >> "$out/sanitizer.log" 2>&1
  echo "racecheck exit $?" | tee -a "$out/sanitizer.log"
  grep -E "ERROR SUMMARY|LEAK SUMMARY|RACECHECK SUMMARY" "$out/sanitizer.log"
fi
if has bench; then
  stamp bench
  "$build/bin/linkgi-bench" --backend cuda --scenes conference --repeat 7 --no-gather \
    > "$out/bench.jsonl" 2>> "$out/steps.log"
  "$build/bin/linkgi-bench" --backend cuda --scenes cornell,tearoom,torso,colorlamp,iphi,conference \
    --repeat 5 ${ref:+--compare $ref} >> "$out/bench.jsonl" 2>> "$out/steps.log"
  # BVH choices for deforming meshes: always rebuild the linear BVH (default: refit until its
  # boxes swell), and a CPU-built SAH tree (refit on the GPU after deformation).
  "$build/bin/linkgi-bench" --backend cuda --scenes torso,conference --bvh-update rebuild \
    --repeat 3 --no-gather >> "$out/bench.jsonl" 2>> "$out/steps.log"
  "$build/bin/linkgi-bench" --backend cuda --scenes torso,iphi,conference --bvh-build sah \
    --repeat 3 --no-gather >> "$out/bench.jsonl" 2>> "$out/steps.log"
  cat "$out/bench.jsonl"
fi
if has photons; then
  # Photon mapping: three rounds of the H200 benchmark at 262,144 and 1M photons
  # asked, then the machine's CPU on the 1M case, and the CPU/CUDA tests under racecheck.
  stamp photons
  for round in 1 2 3; do
    for p in 262144 1048576; do
      "$build/bin/linkgi-bench" --backend cuda --method photon-mapping --scenes cornell,conference,caustics \
        --photons $p --clusters 4096 --repeat 5 --no-bare --no-gather >> "$out/bench-pm-h200-$p.jsonl" 2>> "$out/steps.log"
    done
  done
  "$build/bin/linkgi-bench" --backend cpu --method photon-mapping --scenes cornell,conference --photons 1048576 \
    --clusters 4096 --repeat 3 --no-bare --no-gather > "$out/bench-pm-cpu-1048576.jsonl" 2>> "$out/steps.log"
  compute-sanitizer --tool racecheck --error-exitcode 3 "$tests" --gtest_filter='TestPhotonMapping.CpuAndCuda*' \
    > "$out/racecheck-pm.log" 2>&1
  echo "racecheck exit $?" | tee -a "$out/racecheck-pm.log"
fi
if has partitions; then
  stamp partitions
  # The multi-GPU path on one GPU: P partitions must give the one-partition solution.
  p1=$(mktemp -d)
  "$build/bin/linkgi-bench" --backend cuda --scenes conference,iphi --repeat 5 --no-gather --dump "$p1" \
    > "$out/partitions.jsonl" 2>> "$out/steps.log"
  for p in 2 3; do
    LINKGI_CUDA_PARTITIONS=$p "$build/bin/linkgi-bench" --backend cuda --scenes conference,iphi --repeat 5 \
      --no-gather --compare "$p1" >> "$out/partitions.jsonl" 2>> "$out/steps.log"
  done
  cat "$out/partitions.jsonl"
fi
if has scale; then
  stamp scale
  # More than 2^32 links from 6.5M vertices on: the mean indirect irradiance must not move.
  "$build/bin/linkgi-bench" --backend cuda --scenes isosurface:1000000,isosurface:8000000 --repeat 2 \
    --no-gather > "$out/scale.jsonl" 2>> "$out/steps.log"
  cat "$out/scale.jsonl"
fi
if has multi; then
  stamp multi
  for d in 1 0; do
    "$build/bin/linkgi-bench" --backend cuda --devices $d --scenes conference,iphi --repeat 5 --no-gather
  done > "$out/multi.jsonl" 2>> "$out/steps.log"
  cat "$out/multi.jsonl"
  "$tests" --gtest_filter='Cuda.AllGpus*' 2>&1 | tail -3
fi
if has ab; then
  stamp ab
  # Variants side by side, twice and interleaved (a drift of the machine shows as a
  # difference between the rounds): words with '=' are environment knobs, the rest bench
  # options; "default" is the shipped configuration. AB_VARIANTS overrides the list.
  variants=${AB_VARIANTS:-"default LINKGI_CUDA_BVH=linear LINKGI_CUDA_BVH_ORDER=build --bvh-build,sah"}
  for round in 1 2; do
    for v in $variants; do
      vars=() args=()
      for w in ${v//,/ }; do
        if [[ $w == *=* ]]; then vars+=("$w"); elif [[ $w != default ]]; then args+=("$w"); fi
      done
      echo "== variant $v round $round" >> "$out/steps.log"
      env LINKGI_CUDA_BVH_COST=1 "${vars[@]}" "$build/bin/linkgi-bench" --backend cuda --scenes conference \
        --repeat 7 --no-gather "${args[@]}" 2>> "$out/steps.log" | sed "s/^{/{\"variant\":\"$v\",\"round\":$round,/"
    done
  done > "$out/ab.jsonl"
  grep -E "^== variant|linkgi bvh" "$out/steps.log" | uniq -c | head -40
  python3 - "$out/ab.jsonl" <<'PY' || true
import json, sys
for line in open(sys.argv[1]):
    if line.startswith("{"):
        d = json.loads(line)
        m = d["median_ms"]
        print(f'{d["variant"]:40s} r{d["round"]} rays {d["rays_per_s"]/1e9:.2f} G/s  bvh {d["ms_bvh"]:.2f}  links {d["ms_links"]:.2f}'
              f'  compress {d["ms_compress"]:.2f}  full {d["ms_full_update"]:.2f} (med {m["full_update"]:.2f})'
              f'  light {d["ms_light_update"]:.2f} (med {m["light_update"]:.2f})')
PY
fi
if has profile && command -v ncu > /dev/null; then
  stamp profile
  ncu --kernel-name regex:'traceLinksKernel|compressKernel|shadowSamplesKernel|bounceKernel' \
    --launch-skip 0 --launch-count 6 --section SpeedOfLight --section Occupancy --section LaunchStats \
    "$build/bin/linkgi-bench" --backend cuda --scenes conference --repeat 1 --no-gather \
    > "$out/ncu.log" 2>&1
  grep -E "^  [a-zA-Z].*\(|Duration|Throughput|Achieved Occupancy|Registers Per|Block Limit" "$out/ncu.log" | head -120
fi
stamp done
