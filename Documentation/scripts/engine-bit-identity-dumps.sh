#!/bin/bash
# Every standard scene under every method, one CPU update each, solutions dumped for cmp.
# usage: engine-bit-identity-dumps.sh BENCH OUTDIR
B=$1; O=$2
for m in links instant-radiosity implicit-visibility photon-mapping; do
  mkdir -p $O/$m
  $B --method $m --repeat 1 --backend cpu --dump $O/$m > $O/$m.json 2>&1 || echo "FAIL $m"
done
echo finished
