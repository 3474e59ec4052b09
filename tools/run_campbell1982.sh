#!/bin/bash
# Runs every study of Campbell 1982 Chapter 3 (cases/campbell1982) at full length: a case whose header has
# `grainflow sweep` commands runs as those sweeps, any other as one run. Then `grainflow analyze` where a run
# sampled trajectories, and `grainflow plot` on every run and sweep folder. Results land in runs/campbell1982/.
# Full length is about 5 minutes on 2 cores (the 3D chute, 30 s, is the longest single run).
# Usage: tools/run_campbell1982.sh [STUDY...]   (default: all; e.g. `tools/run_campbell1982.sh couette_rough`)
# Environment: GRAINFLOW (default build/release/grainflow), GRAINFLOW_JOBS (parallel sweep runs, default 2).
set -u
cd "$(dirname "$0")/.."
G=${GRAINFLOW:-build/release/grainflow}
JOBS=${GRAINFLOW_JOBS:-2}
OUT=runs/campbell1982
mkdir -p "$OUT"

# The sweep commands written in a case's header, with their output folders.
sweeps_of() { grep -o 'grainflow sweep .*' "$1" | sed "s|^grainflow|$G|"; }

run_study() {
  local case=cases/campbell1982/$1.toml
  echo "== $1"
  local commands
  commands=$(sweeps_of "$case")
  if [ -n "$commands" ]; then
    while IFS= read -r command; do
      eval "$command --quiet --jobs $JOBS" || echo "   (sweep exited $?)"
    done <<< "$commands"
  else
    "$G" run "$case" -o "$OUT/$1" --quiet || echo "   (run exited $?)"
  fi
}

ALL="couette_noslip couette_shear_rate couette_noslip_normal_force couette_noslip_density couette_low_density_S
couette_rough couette_3d_spheres chute_40deg_5x4 chute_40deg_4x4 chute_40deg chute_30deg chute_30deg_wide
chute_20deg chute_depth_30deg chute_restitution_30deg chute_3d_spheres"
for study in ${@:-$ALL}; do run_study "$study"; done

# Analysis and figures for whatever exists.
for dir in $(find "$OUT" -name summary.json -printf '%h\n' | sort); do
  if [ -e "$dir/trajectory.h5" ]; then "$G" analyze "$dir" > /dev/null || echo "   (analyze of $dir failed)"; fi
  "$G" plot "$dir" > /dev/null || echo "   (plot of $dir failed)"
done
for dir in $(find "$OUT" -name sweep.csv -printf '%h\n' | sort); do "$G" plot "$dir" > /dev/null || true; done
echo "results in $OUT/"
