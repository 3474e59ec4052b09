#!/usr/bin/env bash
# A/B guard for the soft-sphere hot loops: builds BASE (any git revision) beside the working tree
# in build/ab/<sha>, then runs the LAMMPS chute (cases/bench/chute_hooke.toml, 500 steps) on 1 and
# 2 threads and its Walton–Braun and Hertz–Mindlin variants on 1 thread with the working tree's
# build (A, build/release/grainflow) and BASE's (B), interleaved (A B, then B A, round after
# round, so that a drift of the machine's speed falls on both), and prints per variant the median
# and quartiles over the rounds of the per-round speed ratio A/B (> 1: the working tree is
# faster), from each run's particle_steps_per_second (the time loop only).
# Run it before any commit that touches the force loops, the neighbour list or the contact store
# (docs/BENCHMARKS.md).
# Usage: bench/ab_compare.sh BASE [ROUNDS]   (default 7 rounds; about 25 s a round on 2 cores)
#        VARIANTS="hooke1 hooke2 wb1 hm1" selects variants; STEPS_SET overrides the run length.
set -euo pipefail
shopt -s inherit_errexit  # a failed run inside $(...) stops the script
cd "$(dirname "$0")/.."
BASE=${1:?usage: bench/ab_compare.sh BASE [ROUNDS]}
ROUNDS=${2:-7}
VARIANTS=${VARIANTS-"hooke1 hooke2 wb1 hm1"}  # empty: only build BASE
STEPS_SET=${STEPS_SET:-run.duration=0.05}
A=build/release/grainflow
[ -x "$A" ] || { echo "ab_compare: $A is missing: build the working tree first (make release)" >&2; exit 2; }
[ -f ../shared/bench/chute_32k.csv ] || { echo "ab_compare: ../shared/bench/chute_32k.csv (LAMMPS bench/data.chute) is missing" >&2; exit 2; }

B=$(bench/base_build.sh "$BASE")
sha=$(git rev-parse --verify "$BASE^{commit}")

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
variant_args() {  # variant -> case file and thread count
  case $1 in
    hooke1) echo "cases/bench/chute_hooke.toml 1" ;;
    hooke2) echo "cases/bench/chute_hooke.toml 2" ;;
    wb1) echo "cases/bench/chute_walton_braun.toml 1" ;;
    hm1) echo "cases/bench/chute_hertz_mindlin.toml 1" ;;
    *) echo "ab_compare: unknown variant '$1' (hooke1 hooke2 wb1 hm1)" >&2; exit 2 ;;
  esac
}
speed() {  # binary, case, threads -> particle-steps per second
  rm -rf "$out/run"
  "$1" run "$2" -o "$out/run" --quiet --threads "$3" --set "$STEPS_SET" >/dev/null
  /usr/bin/python3 -c "import json; print(json.load(open('$out/run/summary.json'))['particle_steps_per_second'])"
}

echo "A: working tree ($(git rev-parse --short HEAD)$(git diff --quiet HEAD -- src || echo ' + changes'))  B: $BASE (${sha:0:7})"
echo "$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $ROUNDS rounds"
for v in $VARIANTS; do
  read -r case threads <<<"$(variant_args "$v")"
  if ! "$B" check "$case" >/dev/null 2>&1; then
    echo "$v: skipped: $BASE cannot run $case"
    continue
  fi
  ratios=()
  a_speeds=()
  b_speeds=()
  for ((r = 0; r < ROUNDS; ++r)); do
    if ((r % 2 == 0)); then
      a=$(speed "$A" "$case" "$threads"); b=$(speed "$B" "$case" "$threads")
    else
      b=$(speed "$B" "$case" "$threads"); a=$(speed "$A" "$case" "$threads")
    fi
    a_speeds+=("$a"); b_speeds+=("$b")
    ratios+=("$(/usr/bin/python3 -c "print($a / $b)")")
  done
  /usr/bin/python3 - "$v" "$case" "$threads" "${#ratios[@]}" "${ratios[@]}" "${a_speeds[@]}" "${b_speeds[@]}" <<'EOF'
import statistics, sys
label, case, threads, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
values = [float(x) for x in sys.argv[5:]]
ratios, a, b = values[:n], values[n:2 * n], values[2 * n:]
q = statistics.quantiles(ratios, n=4) if n > 1 else [ratios[0]] * 3
print(f"{label:7s} {case} {threads} thread(s): A/B {statistics.median(ratios):.3f} (IQR {q[0]:.3f}-{q[2]:.3f}); "
      f"A {statistics.median(a) / 1e6:.2f}, B {statistics.median(b) / 1e6:.2f} M particle-steps/s")
EOF
done
