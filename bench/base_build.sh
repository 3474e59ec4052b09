#!/bin/bash
# Prints the path of a release grainflow built from commit BASE, building it first in build/ab/<sha>
# (a git archive of BASE, no tests or benchmarks) unless it is there: the baseline of the A/B scripts.
# Usage: bench/base_build.sh BASE   (from the repository root)
set -euo pipefail
BASE=${1:?usage: bench/base_build.sh BASE}
sha=$(git rev-parse --verify "$BASE^{commit}")
dir=build/ab/$sha
if [ ! -x "$dir/build/grainflow" ]; then
  echo "base_build: building $BASE ($sha) in $dir" >&2
  rm -rf "$dir"
  mkdir -p "$dir/src"
  git archive "$sha" | tar -x -C "$dir/src"
  cmake -S "$dir/src" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGRAINFLOW_TESTS=OFF -DGRAINFLOW_BENCHMARKS=OFF >/dev/null
  cmake --build "$dir/build" -j "$(nproc)" --target grainflow >/dev/null
fi
echo "$dir/build/grainflow"
