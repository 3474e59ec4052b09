#!/usr/bin/env bash
# Instructions per particle-step of a soft-sphere case's time loop, for the working tree and BASE,
# counted by valgrind (cachegrind, no cache simulation): a count does not depend on what else the
# machine runs, where wall time on a shared machine does. Both are built without -march=native
# (valgrind cannot decode AVX-512), in build/portable and build/ab/<sha>-portable. Each binary runs
# the case for 50 and for 100 steps on one thread; the difference of the two counts over 50 steps
# and the moving particles is the time loop's cost (set-up and output cancel), neighbour rebuilds
# included. Also prints the hot functions' share of the 100-step run. Complements
# bench/ab_compare.sh: fewer instructions is not always less time, but an added per-pair test or a
# function that stopped inlining shows here plainly.
# Usage: bench/instruction_count.sh BASE [CASE]   (default cases/bench/chute_hooke.toml)
set -euo pipefail
shopt -s inherit_errexit
cd "$(dirname "$0")/.."
BASE=${1:?usage: bench/instruction_count.sh BASE [CASE]}
CASE=${2:-cases/bench/chute_hooke.toml}
command -v valgrind >/dev/null || { echo "instruction_count: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }

build_portable() {  # source dir, build dir
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGRAINFLOW_NATIVE=OFF -DGRAINFLOW_TESTS=OFF \
    -DGRAINFLOW_BENCHMARKS=OFF >/dev/null
  cmake --build "$2" -j "$(nproc)" --target grainflow >/dev/null
}
echo "instruction_count: building the working tree without -march=native in build/portable" >&2
build_portable . build/portable
sha=$(git rev-parse --verify "$BASE^{commit}")
dir=build/ab/$sha-portable
if [ ! -x "$dir/build/grainflow" ]; then
  echo "instruction_count: building $BASE ($sha) in $dir" >&2
  rm -rf "$dir"
  mkdir -p "$dir/src"
  git archive "$sha" | tar -x -C "$dir/src"
  build_portable "$dir/src" "$dir/build"
fi

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
time_step=$(build/portable/grainflow check "$CASE" 2>/dev/null | /usr/bin/python3 -c "
import re, sys
text = sys.stdin.read()
m = re.search(r'time step[^0-9]*([0-9.eE+-]+)', text)
print(m.group(1) if m else '')")
[ -n "$time_step" ] || { echo "instruction_count: could not read the time step from 'grainflow check $CASE'" >&2; exit 2; }
count() {  # label, binary, steps -> total instructions (and leaves $out/label-steps.cg)
  local file=$out/$1-$3.cg
  valgrind --tool=cachegrind --cache-sim=no --cachegrind-out-file="$file" \
    "$2" run "$CASE" -o "$out/run" --quiet --threads 1 --set "run.duration=$(/usr/bin/python3 -c "print($3 * $time_step)")" \
    >/dev/null 2>&1
  awk '/^summary:/ {print $2}' "$file"
}
moving=$(/usr/bin/python3 -c "import json; print(json.load(open('$out/run/summary.json'))['particles'])" 2>/dev/null || true)
echo "$CASE, 1 thread, time step $time_step"
for label in A B; do
  if [ "$label" = A ]; then bin=build/portable/grainflow; name="working tree"; else bin=$dir/build/grainflow; name="$BASE (${sha:0:7})"; fi
  short=$(count "$label" "$bin" 50)
  long=$(count "$label" "$bin" 100)
  [ -n "$moving" ] || moving=$(/usr/bin/python3 -c "import json; print(json.load(open('$out/run/summary.json'))['particles'])")
  /usr/bin/python3 -c "print(f'$label ($name): {($long - $short) / (50 * $moving):.1f} instructions per particle-step')"
  cg_annotate "$out/$label-100.cg" 2>/dev/null | awk '/^-+$/ {n++} n >= 3 && /[0-9,]+ +\(/ && shown++ < 8 {print "    " $0}' |
    sed -E 's/grainflow::(dem::)?//g' | cut -c1-150
done
