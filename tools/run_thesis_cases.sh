#!/bin/bash
# Runs the bundled studies of one thesis (cases/THESIS/) at full length: a case whose header has
# `grainflow sweep` commands runs as those sweeps, any other as one run. Then `grainflow analyze`
# where a run sampled trajectories or zone series, `grainflow theory` where the kinetic theory of a
# shaken bed applies, and `grainflow plot` on every run and sweep folder; for event-driven runs the
# table of constitutive functions (`grainflow constitutive`) and its figures. Results: runs/THESIS/.
# Usage: tools/run_thesis_cases.sh THESIS "ALL STUDIES" [STUDY...]   (tools/run_lan1994.sh and
# tools/run_campbell1982.sh call it with their lists). Environment: GRAINFLOW (default
# build/release/grainflow), GRAINFLOW_JOBS (parallel sweep runs, default 2).
set -u
cd "$(dirname "$0")/.."
THESIS=$1
ALL=$2
shift 2
G=${GRAINFLOW:-build/release/grainflow}
JOBS=${GRAINFLOW_JOBS:-2}
OUT=runs/$THESIS
mkdir -p "$OUT"

# The sweep commands written in a case's header, with their output folders.
sweeps_of() { grep -o 'grainflow sweep .*' "$1" | sed "s|^grainflow|$G|"; }

run_study() {
  local case=cases/$THESIS/$1.toml
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

for study in ${@:-$ALL}; do run_study "$study"; done

# Analysis and figures for whatever exists.
for dir in $(find "$OUT" -name summary.json -printf '%h\n' | sort); do
  if [ -e "$dir/trajectory.h5" ] || [ -e "$dir/zone_series.h5" ]; then
    "$G" analyze "$dir" > /dev/null || echo "   (analyze of $dir failed)"
  fi
  "$G" theory "$dir" > /dev/null 2>&1 || true  # kinetic-theory overlay where the solver applies
  "$G" plot "$dir" > /dev/null || echo "   (plot of $dir failed)"
done
for dir in $(find "$OUT" -name sweep.csv -printf '%h\n' | sort); do "$G" plot "$dir" > /dev/null || true; done
# Event-driven runs: their constitutive functions over all strips and runs (Campbell's Figs. 3.5, 3.21-3.24).
if [ -n "$(find "$OUT" -name constitutive.csv -print -quit)" ]; then
  "$G" constitutive "$OUT" && "$G" plot "$OUT" > /dev/null || echo "   (constitutive table of $OUT failed)"
fi
echo "results in $OUT/"
