#!/bin/sh
# run-all.sh — the whole benchmark in one command, as recorded in
# tools/bench/README.md: builds rt-bench and rt-render (release preset),
# then writes to bench-results/ (or $1):
#   machine.txt   CPU, memory, compiler, and `uptime` before and after
#   bench.txt     rt-bench --runs 3 (sections 1-6, Embree beside ours)
#   flake.txt     rt-render on the 48-million-sphere sphereflake, start to
#                 PNG, under /usr/bin/time -v (peak memory), and its PNG
#   tetra.txt     the same for the 1M-triangle Sierpinski tetrahedron
#   flake10.txt   the same for the level-10 sphereflake by instancing
#                 (3,922,632,451 spheres; targets: under 60 s, under 1 GB)
#   scaling.svg   time per ray against N (tools/bench/plot_scaling.py)
# Usage: tools/bench/run-all.sh [OUT_DIR]
set -eu
here=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-bench-results}
mkdir -p "$out"
cd "$here"
cmake --preset release >/dev/null
cmake --build --preset release --target rt-bench rt-render >/dev/null
bin=build/release/bin
{
  echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2) x $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB"
  echo "compiler: $(c++ --version | head -1)"
  echo "before: $(uptime)"
} > "$out/machine.txt"
"$bin/rt-bench" --runs 3 > "$out/bench.txt"
/usr/bin/time -v "$bin/rt-render" tools/bench/scenes/spd-balls-8.json --out "$out/sphereflake-8.png" \
  > "$out/flake.txt" 2>&1
/usr/bin/time -v "$bin/rt-render" tools/bench/scenes/spd-tetra-10.json --out "$out/tetra-10.png" \
  > "$out/tetra.txt" 2>&1
/usr/bin/time -v "$bin/rt-render" tools/bench/scenes/spd-balls-10-instanced.json --out "$out/flake-10.png" \
  > "$out/flake10.txt" 2>&1
echo "after: $(uptime)" >> "$out/machine.txt"
python3 tools/bench/plot_scaling.py "$out/bench.txt" "$out/scaling.svg"
cat "$out/machine.txt"
grep -E "rendered|tree:|Maximum resident|Elapsed|User time|System time" "$out/flake.txt" "$out/tetra.txt" "$out/flake10.txt"
