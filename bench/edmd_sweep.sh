#!/usr/bin/env bash
# Event-driven cost per event against N: elastic hard spheres (3D, packing fraction 0.45) and hard
# discs (2D, area fraction 0.45), N = 10^3 .. 10^6, about 8 collisions per particle each run.
# Prints N, events/s, collisions/s, nanoseconds per event and the peak resident memory per particle
# (summary.json; whole process, so a fixed ~20 MB weighs on small N: compare the large ones).
# Usage: [GRAINFLOW=BINARY] bench/edmd_sweep.sh [MAX_EXPONENT]   (default 6)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${GRAINFLOW:-build/release/grainflow}  # GRAINFLOW=path/to/another/build compares builds
MAX=${1:-6}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-4s %-9s %12s %14s %12s %14s\n' dim N events/s collisions/s ns/event bytes/particle
for dim in 3 2; do
  for ((e = 3; e <= MAX; ++e)); do
    n=$((10 ** e))
    if [ "$dim" = 3 ]; then
      side=$(/usr/bin/python3 -c "import math; print((${n} * math.pi / 6 / 0.45) ** (1 / 3))")
      set_args=(--set "species.0.count=$n" --set "domain.hi=[$side,$side,$side]")
      case_file=cases/bench/hard_spheres.toml
      spacing=$(/usr/bin/python3 -c "import math; print(0.999 * $side / math.ceil(${n} ** (1 / 3) - 1e-9))")
      lattice=(--set particles.lattice=cubic --set "particles.lattice_spacing=$spacing")
    else
      side=$(/usr/bin/python3 -c "import math; print((${n} * math.pi / 4 / 0.45) ** 0.5)")
      set_args=(--set "species.0.count=$n" --set "domain.hi=[$side,$side,1.0]" --set engine.dimension=2
                --set species.0.density=1.2732395447351628 --set "gravity.vector=[0,0,0]")
      case_file=cases/bench/hard_spheres.toml
      spacing=$(/usr/bin/python3 -c "import math; print(0.999 * $side / math.ceil(${n} ** 0.5 - 1e-9))")
      lattice=(--set particles.lattice=cubic --set "particles.lattice_spacing=$spacing")
    fi
    "$BIN" run "$case_file" -o "$out/run" --quiet "${set_args[@]}" "${lattice[@]}" --set run.duration=0.5 \
      --set output.interval=0.5 >/dev/null
    /usr/bin/python3 - "$out/run/summary.json" "$dim" "$n" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
eps = s["events_per_second"]
print(f"{sys.argv[2]:<4} {sys.argv[3]:<9} {eps:12.4g} {s['collisions_per_second']:14.4g} {1e9 / eps:12.1f} "
      f"{s['peak_memory_bytes'] / int(sys.argv[3]):14.0f}")
PY
  done
done
