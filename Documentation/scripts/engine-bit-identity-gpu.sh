#!/usr/bin/env bash
# On the GPU machine: are the engine's CUDA solutions bit for bit those of an older tree?
# Needs base-tree.tar.gz (git archive <base> kernels cmake Testing/Kernels | gzip) in the
# repository root and GoogleTest sources in .gpu-gtest; OUT gets the logs and compare.txt.
set -uo pipefail
out=$1; top=$PWD
mkdir -p /tmp/base && tar xzf base-tree.tar.gz -C /tmp/base
( cmake -S /tmp/base/kernels -B /tmp/base-build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
    -DBUILD_TESTING=OFF -DCMAKE_POLICY_VERSION_MINIMUM=3.5 > $out/base-build.log 2>&1 &&
  cmake --build /tmp/base-build -j 8 --target linkgi-bench >> $out/base-build.log 2>&1; echo "base build $?" ) &
export LINKGI_GPU_BUILD=$top/build-gpu
bash kernels/tools/gpu-session.sh $out $top/.gpu-gtest "" "build test"
wait
for m in links instant-radiosity implicit-visibility photon-mapping; do
  for which in base new; do
    b=/tmp/base-build/bin/linkgi-bench; [ $which = new ] && b=$LINKGI_GPU_BUILD/bin/linkgi-bench
    mkdir -p /tmp/d/$which/$m /tmp/d/${which}2/$m
    $b --method $m --backend cuda --repeat 1 --no-bare --no-gather --dump /tmp/d/$which/$m > $out/$which-$m.jsonl 2>&1
  done
  $b --method $m --backend cuda --repeat 1 --no-bare --no-gather --dump /tmp/d/new2/$m > /dev/null 2>&1
  for f in /tmp/d/base/$m/*.bin; do
    n=$(basename $f)
    cmp -s $f /tmp/d/new/$m/$n && r=identical || r=DIFFERENT
    cmp -s /tmp/d/new/$m/$n /tmp/d/new2/$m/$n && r2=identical || r2=DIFFERENT
    echo "$m $n base-vs-new $r new-vs-new-rerun $r2" | tee -a $out/compare.txt
  done
done
