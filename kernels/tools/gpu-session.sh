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
# STEPS: any of "build test sanitize bench partitions scale multi" (default: all but multi).
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
stamp done
