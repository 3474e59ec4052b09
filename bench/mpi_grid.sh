#!/usr/bin/env bash
# The grid of sub-domains on a gravity-free walled cube of 10^5 spheres (cases/bench/cube_walls_100k.toml,
# 300 steps) on 1, 2 and 4 ranks of one thread each (4 oversubscribes a 2-core machine). Prints
# ranks, the grid's shape, the ghosts held (summed over ranks) and particle-steps per second.
# Usage: [GRAINFLOW=path/to/grainflow] bench/mpi_grid.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${GRAINFLOW:-build/release/grainflow}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-6s %-7s %10s %16s\n' ranks grid ghosts particle-steps/s
for ranks in 1 2 4; do
  launch=()
  if [ "$ranks" -gt 1 ]; then launch=(mpirun --oversubscribe -np "$ranks"); fi
  "${launch[@]}" "$BIN" run cases/bench/cube_walls_100k.toml -o "$out/run" --quiet --threads 1 >/dev/null
  /usr/bin/python3 -c "
import json; s = json.load(open('$out/run/summary.json'))
print(f\"{$ranks:<6} {s.get('mpi_grid', '-'):<7} {s.get('mpi_ghosts', 0):10d} {s['particle_steps_per_second']:16.4g}\")"
done
