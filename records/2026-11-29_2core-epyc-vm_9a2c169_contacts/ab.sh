#!/usr/bin/env bash
# Photon mapping before (42220e7) and after (143bb4f) the surface pieces, interleaved, CPU.
old=${1:?old bench}; new=${2:?new bench}; out=${3:?out.jsonl}
for round in 1 2 3; do
  for label in old new; do
    bin=$old; [ $label = new ] && bin=$new
    "$bin" --backend cpu --scenes cornell,conference --method photon-mapping --repeat 3 2>/dev/null |
      grep '^{' | sed "s/^{/{\"build\":\"$label\",\"round\":$round,/" >> "$out"
  done
done
