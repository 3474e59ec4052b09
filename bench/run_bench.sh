#!/usr/bin/env bash
# Whole-case throughput: the LAMMPS chute benchmark (cases/bench/chute_hooke.toml) on 1 and 2
# threads, a Walton–Braun variant of the same work, the event-driven cases run side by side with
# DynamO and Smallenburg's EDMD, and the micro benchmarks of the hot kernels.
# Prints particle-steps per second (median of RUNS runs). Usage: bench/run_bench.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-5}
BIN=build/release/grainflow
STEPS_SET="run.duration=0.05"   # 500 steps: long enough to time, short enough to repeat
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
rate() {  # label, case, extra args...
  local label=$1 CASE=$2; shift 2
  local rates=()
  for ((r = 0; r < RUNS; ++r)); do
    "$BIN" run "$CASE" -o "$out/run" --quiet --set "$STEPS_SET" "$@" >/dev/null
    rates+=("$(/usr/bin/python3 -c "import json,sys; print(json.load(open('$out/run/summary.json'))['particle_steps_per_second'])")")
  done
  printf '%s\n' "${rates[@]}" | median | awk -v l="$label" '{printf "%-52s %8.2f M particle-steps/s\n", l, $1/1e6}'
}

if [ ! -f ../shared/bench/chute_32k.csv ]; then
  echo "bench: ../shared/bench/chute_32k.csv (LAMMPS bench/data.chute) is missing; whole-case runs skipped" >&2
else
  echo "== whole-case throughput, median of $RUNS runs ($(nproc) cores, $(uname -m)) =="
  rate "chute_hooke (gran/hooke/history), 1 thread" cases/bench/chute_hooke.toml --threads 1
  rate "chute_hooke (gran/hooke/history), 2 threads" cases/bench/chute_hooke.toml --threads 2
  rate "chute_walton_braun (friction 0.5), 1 thread" cases/bench/chute_walton_braun.toml --threads 1
fi
echo "== event-driven, 32,000 spheres (cases/bench/*spheres*.toml), real collisions per second =="
collision_rate() {  # case name
  local rates=()
  for ((r = 0; r < RUNS; ++r)); do
    "$BIN" run "cases/bench/$1.toml" -o "$out/edmd" --quiet >/dev/null
    rates+=("$(/usr/bin/python3 -c "import json; print(json.load(open('$out/edmd/summary.json'))['collisions_per_second'])")")
  done
  printf '%s\n' "${rates[@]}" | median | awk -v l="$1" '{printf "%-52s %8.3f M collisions/s\n", l, $1/1e6}'
}
for name in hard_spheres hard_spheres_n0.5 hard_spheres_n0.9 inelastic_spheres_n0.5 rough_spheres_n0.5 sheared_spheres_n0.5; do
  collision_rate "$name"
done
echo "== micro benchmarks =="
build/release/bench/micro_kernels --benchmark_min_time=0.2
