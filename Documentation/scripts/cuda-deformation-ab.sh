#!/usr/bin/env bash
# Conference's deformation steps on one GPU: the engine of commit BASE against the working
# tree, both built on the machine, the benches interleaved (odd rounds BASE first), then
# the preparation drivers and the working tree's kernel suite. From the repository root:
#
#   mkdir -p /tmp/base && git archive 56b462b kernels cmake | tar -x -C /tmp/base
#   BASE_SRC=/tmp/base OUT=out GTEST=$PWD/.gtest/googletest ROUNDS=4 \
#     bash Documentation/scripts/cuda-deformation-ab.sh
set -u
top=$PWD
here=$top/Documentation/scripts
ROUNDS=${ROUNDS:-3}
mkdir -p "$OUT"
{ nvidia-smi --query-gpu=name,uuid,memory.total,driver_version,clocks.max.sm --format=csv; nproc
  grep -m1 "model name" /proc/cpuinfo; nvcc --version | tail -1; date -u; } > "$OUT/machine.txt" 2>&1
B0=/tmp/b-base B1=/tmp/b-new
opts="-G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 -DCMAKE_POLICY_VERSION_MINIMUM=3.5"
( cmake -S "$BASE_SRC/kernels" -B $B0 $opts -DBUILD_TESTING=OFF > "$OUT/build0.log" 2>&1 &&
  cmake --build $B0 -j 8 --target linkgi-bench >> "$OUT/build0.log" 2>&1; echo "base build $?" ) &
( cmake -S "$top/kernels" -B $B1 $opts -DLINKGI_GTEST_SOURCE_DIR="$GTEST" > "$OUT/build1.log" 2>&1 &&
  cmake --build $B1 -j 8 --target linkgi-bench linkgi_kernel_tests >> "$OUT/build1.log" 2>&1; echo "new build $?" ) &
wait
L="--backend cuda --scenes conference --repeat 7 --no-gather"
IR="--backend cuda --method instant-radiosity --scenes conference --vpls 4096 --no-gather --no-bare --interleave 64 --proxy 16 --repeat 5"
for r in $(seq 1 "$ROUNDS"); do
  order="base new"; [ $((r % 2)) = 0 ] && order="new base"
  for v in $order; do
    B=$B0; [ $v = new ] && B=$B1
    for args in "$L" "$IR"; do
      timeout 90 $B/bin/linkgi-bench $args 2>> "$OUT/bench.err" |
        sed "s/^{/{\"variant\":\"$v\",\"round\":$r,/" >> "$OUT/deformation-ab.jsonl"
    done
  done
done
# The preparation of a deformation alone (deformation-preparation.cpp, both builds), and its pieces.
LIBS="-L/usr/local/cuda/lib64 -lcudart_static -lcudadevrt -ldl -lrt -lpthread"
g++ -O2 -std=c++17 -I"$BASE_SRC/kernels/include" "$here/deformation-preparation.cpp" $B0/liblinkgi_kernels.a $LIBS -o /tmp/prep-base
g++ -O2 -std=c++17 -I"$top/kernels/include" "$here/deformation-preparation.cpp" $B1/liblinkgi_kernels.a $LIBS -o /tmp/prep-new
g++ -O2 -std=c++17 -I"$top/kernels/include" "$here/deformation-preparation-pieces.cpp" $B1/liblinkgi_kernels.a $LIBS -o /tmp/prep-pieces
{ for i in 1 2; do /tmp/prep-base 60 cuda; /tmp/prep-new 60 cuda; done; /tmp/prep-pieces; } > "$OUT/preparation.txt"
timeout 240 $B1/bin/linkgi_kernel_tests > "$OUT/tests.log" 2>&1; echo "suite exit $?"
