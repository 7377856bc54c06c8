#!/bin/bash
cd /tmp/bench-comp3
for round in 1 2; do
  for build in base reach; do
    case $build in base) b=/tmp/kb-base/bin/linkgi-bench;; reach) b=/tmp/kb-after/bin/linkgi-bench;; esac
    $b --scenes cornell,tearoom,conference --method instant-radiosity --repeat 3 --no-bare --no-gather 2>/dev/null | grep '^{' > $build-$round.jsonl
  done
done
echo done > finished
