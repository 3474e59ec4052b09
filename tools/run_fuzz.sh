#!/usr/bin/env bash
# Runs each libFuzzer target of build/fuzz for SECONDS (default 60), seeded with the bundled cases
# (case files) and particle files, under a 2 GB memory limit and 10 s per input. A crash, leak,
# timeout or out-of-memory input is written to build/fuzz/findings/<target>/ and the script exits 1.
# Usage: tools/run_fuzz.sh [SECONDS]     (make fuzz builds the targets first)
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:-60}
status=0
for target in fuzz_case_file fuzz_particle_csv; do
  corpus=build/fuzz/corpus/$target
  findings=build/fuzz/findings/$target
  mkdir -p "$corpus" "$findings"
  if [ "$target" = fuzz_case_file ]; then
    find cases -name '*.toml' -exec cp {} "$corpus/" \;
  else
    find cases tests -name '*.csv' -size -200k -exec cp {} "$corpus/" \; 2>/dev/null || true
    printf 'species,x,y,z,vx,vy,vz,diameter\nglass,0.001,0.002,0.003,0,0,0,0.002\n' > "$corpus/seed.csv"
  fi
  echo "== $target: $SECONDS_PER_TARGET s"
  if ! "build/fuzz/fuzz/$target" "$corpus" -max_total_time="$SECONDS_PER_TARGET" -rss_limit_mb=2048 -timeout=10 \
      -artifact_prefix="$findings/" -print_final_stats=1 2>&1 | tail -n 25; then
    status=1
  fi
  if [ -n "$(ls -A "$findings")" ]; then
    echo "$target: findings in $findings" >&2
    status=1
  fi
done
exit $status
