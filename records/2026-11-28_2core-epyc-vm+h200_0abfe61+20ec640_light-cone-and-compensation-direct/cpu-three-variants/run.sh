#!/bin/bash
cd /tmp/bench-comp2
for round in 1 2; do
  for build in base cond full; do
    case $build in base) b=/tmp/kb-base/bin/linkgi-bench;; cond) b=/tmp/kb-after/bin/linkgi-bench;; full) b=/tmp/bench-full-exact;; esac
    $b --scenes cornell,tearoom,conference --method instant-radiosity --repeat 3 --no-bare --no-gather 2>/dev/null | grep '^{' > $build-$round.jsonl
  done
done
echo done > finished
