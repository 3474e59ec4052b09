#!/usr/bin/env bash
# Soft-sphere cost per particle-step and memory per particle against N: Lan's vibrated bed
# (cases/demo/vibrated_bed.toml: 3 mm glass spheres, Walton-Braun, shaken floor at Gamma = 3),
# widened to N = 10^3 .. 10^MAX_EXPONENT spheres about 10 layers deep on a square periodic base,
# started touching on a cubic lattice with random velocities (T = 0.01 m^2/s^2: every neighbour pair
# collides at once, about 3 contacts per sphere), 300 steps each. Prints N, particle-steps per second,
# nanoseconds per particle-step, and the peak resident memory in bytes per particle (summary.json's
# peak_memory_bytes / N: the engine's arrays plus a fixed ~20 MB for the program, so it falls
# towards the per-particle cost as N grows; the last column differences consecutive rows to
# remove the fixed part).
# Usage: [GRAINFLOW=BINARY] [THREADS=1] bench/dem_sweep.sh [MAX_EXPONENT]   (default 6)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${GRAINFLOW:-build/release/grainflow}
THREADS=${THREADS:-1}
MAX=${1:-6}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-9s %14s %12s %14s %16s\n' N particle-steps/s ns/step/p bytes/particle marginal_bytes/p
prev_n=0
prev_mem=0
for ((e = 3; e <= MAX; ++e)); do
  n=$((10 ** e))
  # m x m columns of 10 layers (m^2 >= N / 10, spacing 1.05 d across); the lattice fills the lowest layers first.
  m=$(/usr/bin/python3 -c "import math; print(math.ceil(math.sqrt(${n} / 10)))")
  side=$(/usr/bin/python3 -c "print(${m} * 1.05 * 0.003)")
  "$BIN" run cases/demo/vibrated_bed.toml -o "$out/run" --quiet --threads "$THREADS" \
    --set "species.0.count=$n" --set "domain.hi=[$side,0.08,$side]" \
    --set particles.init=lattice --set particles.lattice_spacing=1.0 --set particles.initial_temperature=0.01 --set "particles.region_hi=[$side,0.05,$side]" \
    --set particles.expansion_time=0 --set drive.start=0 --set drive.ramp=0 \
    --set run.duration=0.000237 --set output.interval=0.000237 --set output.snapshot_interval=0 >/dev/null
  read -r rate mem <<<"$(/usr/bin/python3 -c "import json; s = json.load(open('$out/run/summary.json')); print(s['particle_steps_per_second'], s['peak_memory_bytes'])")"
  marginal="-"
  if [ "$prev_n" -gt 0 ]; then marginal=$(/usr/bin/python3 -c "print(round(($mem - $prev_mem) / ($n - $prev_n)))"); fi
  /usr/bin/python3 -c "print(f'{$n:<9} {$rate:14.4g} {1e9 / $rate:12.1f} {$mem / $n:14.0f} {\"$marginal\":>16}')"
  prev_n=$n
  prev_mem=$mem
done
