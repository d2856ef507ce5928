#!/bin/sh
# Interleaved start-to-PNG runs of the level-8 sphereflake: the binary of main before (base) and after (new).
cd /work/wt/speed
for i in 1 2 3; do
  for v in base new; do
    if [ $v = base ]; then b=/tmp/speed-base/rt-render; else b=/tmp/speed-runs/rt-render-new; fi
    f=/tmp/speed-runs/flake-$v-$i.txt
    echo "before: $(date -u) $(uptime)" > $f
    /usr/bin/time -v $b tools/bench/scenes/spd-balls-8.json --out /tmp/speed-runs/flake-$v.png >> $f 2>&1
    echo "after: $(date -u) $(uptime)" >> $f
  done
done
