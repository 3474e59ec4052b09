#!/bin/bash
# Runs every study of Lan 1994 (cases/lan1994) at full length, then `grainflow analyze` where the
# run sampled trajectories or zone series, then `grainflow plot` on every run and sweep folder.
# Results land in runs/lan1994/<study>/; docs/validation/lan1994.md compares them with the thesis.
# Usage: tools/run_lan1994.sh [STUDY...]   (default: all, cheapest first; e.g. `tools/run_lan1994.sh table4_3`)
# Environment: GRAINFLOW (default build/release/grainflow), GRAINFLOW_JOBS (parallel sweep runs).
set -u
cd "$(dirname "$0")/.."
G=${GRAINFLOW:-build/release/grainflow}
OUT=runs/lan1994
mkdir -p "$OUT"

# The sweep commands written in a case's header, with their output folders.
sweeps_of() { grep -o 'grainflow sweep .*' "$1" | sed "s|^grainflow|$G|"; }

run_study() {
  local case=cases/lan1994/$1.toml
  echo "== $1"
  local commands
  commands=$(sweeps_of "$case")
  if [ -n "$commands" ]; then
    while IFS= read -r command; do
      eval "$command --quiet" || echo "   (sweep exited $?)"
    done <<< "$commands"
  else
    "$G" run "$case" -o "$OUT/$1" --quiet || echo "   (run exited $?)"
  fi
}

ALL="table4_5_diffusion_gamma90 table4_5_diffusion_gamma483 table4_6_diffusion_amplitude_half_d
table4_7_diffusion_amplitude_001d sec4_3_spectra table5_1_convection_amplitude table5_2_friction
sec5_1_3_cell_20dx3d sec5_1_3_cell_100dx1d sec5_2_large_sphere_6dx3d sec5_2_large_sphere_20dx3d
table4_1_mass_holdup sec4_1_4_gamma table4_2_stiffness sec5_2_large_sphere_100dx1d table4_3_hunt"
for study in ${@:-$ALL}; do run_study "$study"; done

# Analysis and figures for whatever exists.
for dir in $(find "$OUT" -name summary.json -printf '%h\n' | sort); do
  if [ -e "$dir/trajectory.h5" ] || [ -e "$dir/zone_series.h5" ]; then "$G" analyze "$dir" > /dev/null; fi
  "$G" theory "$dir" > /dev/null 2>&1 || true  # kinetic-theory overlay where the solver applies
  "$G" plot "$dir" > /dev/null || echo "   (plot of $dir failed)"
done
for dir in $(find "$OUT" -name sweep.csv -printf '%h\n' | sort); do "$G" plot "$dir" > /dev/null || true; done
echo "results in $OUT/"
