#!/usr/bin/env bash
# A 10^6-sphere vibrated bed (bench/dem_sweep.sh's bed, shaken from the start at Gamma = 3) on one
# rank and on RANKS ranks (default 2), STEPS steps each (default 6000), profiles sampled every 60
# steps; prints each run's speed and how far apart the two runs' zone profiles are, in combined
# standard errors (block averages), zone by zone.
# Usage: [RANKS=2] [STEPS=6000] bench/mpi_million_bed.sh [OUTDIR]
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${GRAINFLOW:-build/release/grainflow}
RANKS=${RANKS:-2}
STEPS=${STEPS:-6000}
out=${1:-$(mktemp -d)}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
n=1000000
m=$(/usr/bin/python3 -c "import math; print(math.ceil(math.sqrt(${n} / 10)))")
side=$(/usr/bin/python3 -c "print(${m} * 1.05 * 0.003)")
dt=7.908014e-07  # the case's time step (grainflow check)
duration=$(/usr/bin/python3 -c "print(${STEPS} * ${dt})")
args=(run cases/demo/vibrated_bed.toml --quiet --threads 1 --set "species.0.count=$n" --set "domain.hi=[$side,0.08,$side]"
      --set particles.init=lattice --set particles.lattice_spacing=1.0 --set particles.initial_temperature=0.01
      --set "particles.region_hi=[$side,0.05,$side]" --set particles.expansion_time=0 --set drive.start=0 --set drive.ramp=0
      --set "run.duration=$duration" --set "output.interval=$(/usr/bin/python3 -c "print(600 * ${dt})")"
      --set "output.profile_interval=$(/usr/bin/python3 -c "print(60 * ${dt})")" --set output.average_start=0
      --set output.snapshot_interval=0)
"$BIN" "${args[@]}" -o "$out/ranks_1" >/dev/null
mpirun --oversubscribe -np "$RANKS" "$BIN" "${args[@]}" -o "$out/ranks_$RANKS" >/dev/null
/usr/bin/python3 - "$out/ranks_1" "$out/ranks_$RANKS" <<'PY'
import csv, json, math, sys
def rows(d):
    return list(csv.DictReader(l for l in open(d + "/profiles.csv") if not l.startswith("#")))
for d in sys.argv[1:]:
    s = json.load(open(d + "/summary.json"))
    print(f"{d}: {s.get('mpi_ranks', 1)} rank(s), {s['particle_steps_per_second']:.4g} particle-steps/s, "
          f"{s['profile_samples']} profile samples, peak {s['peak_memory_bytes'] / 1e6:.0f} MB (rank 0)")
worst, compared = 0.0, 0
for a, b in zip(rows(sys.argv[1]), rows(sys.argv[2])):
    for value, error in (("solids_fraction", "solids_fraction_error"), ("temperature", "temperature_error")):
        ea, eb = float(a[error]), float(b[error])
        if not (math.isfinite(ea) and math.isfinite(eb)) or float(a["solids_fraction"]) < 0.05 or ea + eb == 0:
            continue
        z = abs(float(a[value]) - float(b[value])) / math.hypot(ea, eb)
        worst, compared = max(worst, z), compared + 1
print(f"{compared} zone values compared; largest difference {worst:.2f} combined standard errors")
PY
