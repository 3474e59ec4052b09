#!/bin/bash
# A silo's discharge as a user pays for it: bench/silo_100k.toml (10^5 spheres, orifice 10 d, kept
# full) for 4 time units on 1 and 2 threads, ROUNDS interleaved rounds; prints each thread count's
# median particles discharged per wall-clock second, particle-steps per second and simulated time
# per wall-clock second.
# Usage: bench/silo_discharge.sh [ROUNDS]   (from the repository root, after make release)
set -euo pipefail
ROUNDS=${1:-3}
A=build/release/grainflow
[ -x "$A" ] || { echo "silo_discharge: $A is missing: build the working tree first (make release)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for round in $(seq "$ROUNDS"); do
  for threads in 1 2; do
    "$A" run bench/silo_100k.toml --threads "$threads" --quiet -o "$out/t${threads}_$round"
  done
done
/usr/bin/python3 - "$out" "$ROUNDS" <<'PY'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
for threads in (1, 2):
    s = [json.load(open(f"{out}/t{threads}_{r}/summary.json")) for r in range(1, rounds + 1)]
    per_second = [x["discharged"] / x["wall_seconds"] for x in s]
    speed = [x["particle_steps_per_second"] for x in s]
    pace = [x["simulated_time"] / x["wall_seconds"] for x in s]
    print(f"{threads} thread(s): {statistics.median(per_second):6.2f} particles discharged per second "
          f"({statistics.median([x['discharged'] for x in s]):.0f} in {s[0]['simulated_time']:g} time units), "
          f"{statistics.median(speed) / 1e6:6.3f} M particle-steps/s, "
          f"{statistics.median(pace):.4f} time units per second (min-max over {rounds} rounds: "
          f"{min(per_second):.2f}-{max(per_second):.2f} discharged/s)")
PY
