#!/usr/bin/env bash
# Strong and weak scaling of the soft-sphere engine over MPI ranks: Lan's vibrated bed (as in
# bench/dem_sweep.sh: 3 mm glass spheres ~10 layers deep on a square periodic base, started touching
# on a lattice), 300 steps, on 1, 2 and 4 ranks of one thread each (4 oversubscribes a 2-core machine).
# Prints ranks, N, particle-steps per second (all ranks together), the ghosts held (summed over
# ranks) and the particles that changed rank.
# Usage: bench/mpi_scaling.sh strong N    |   bench/mpi_scaling.sh weak N_PER_RANK
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${GRAINFLOW:-build/release/grainflow}
MODE=${1:-strong}
SIZE=${2:-100000}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-6s %-9s %16s %10s %12s\n' ranks N particle-steps/s ghosts migrations
for ranks in 1 2 4; do
  n=$SIZE
  if [ "$MODE" = weak ]; then n=$((SIZE * ranks)); fi
  m=$(/usr/bin/python3 -c "import math; print(math.ceil(math.sqrt(${n} / 10)))")
  side=$(/usr/bin/python3 -c "print(${m} * 1.05 * 0.003)")
  launch=()
  if [ "$ranks" -gt 1 ]; then launch=(mpirun --oversubscribe -np "$ranks"); fi
  "${launch[@]}" "$BIN" run cases/demo/vibrated_bed.toml -o "$out/run" --quiet --threads 1 \
    --set "species.0.count=$n" --set "domain.hi=[$side,0.08,$side]" \
    --set particles.init=lattice --set particles.lattice_spacing=1.0 --set particles.initial_temperature=0.01 \
    --set "particles.region_hi=[$side,0.05,$side]" --set particles.expansion_time=0 --set drive.start=0 --set drive.ramp=0 \
    --set run.duration=0.000237 --set output.interval=0.000237 --set output.snapshot_interval=0 \
    --set output.average_start=1 >/dev/null  # no profile samples: the engine alone
  /usr/bin/python3 -c "
import json; s = json.load(open('$out/run/summary.json'))
print(f\"{$ranks:<6} {$n:<9} {s['particle_steps_per_second']:16.4g} {s.get('mpi_ghosts', 0):10d} {s.get('mpi_migrations', 0):12d}\")"
done
