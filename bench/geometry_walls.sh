#!/bin/bash
# What a [[geometry]] wall costs against a box face, and what the sparse wall contacts save: the
# walled cube of 10^5 spheres (cases/bench/cube_walls_100k.toml, 300 steps, one thread) with its six
# walls as box faces and as [[geometry]] planes (cube_geometry_100k.toml), and the box-face case on
# a base build (dense wall contacts: one state per particle per wall). ROUNDS interleaved rounds;
# prints each variant's median particle-steps per second and peak memory (summary.json).
# Usage: bench/geometry_walls.sh BASE_COMMIT [ROUNDS]   (from the repository root, after make release)
set -euo pipefail
BASE=${1:?usage: bench/geometry_walls.sh BASE_COMMIT [ROUNDS]}
ROUNDS=${2:-5}
A=build/release/grainflow
[ -x "$A" ] || { echo "geometry_walls: $A is missing: build the working tree first (make release)" >&2; exit 2; }
B=$(bench/base_build.sh "$BASE")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for round in $(seq "$ROUNDS"); do
  "$A" run cases/bench/cube_walls_100k.toml --threads 1 --quiet -o "$out/faces_$round"
  "$A" run cases/bench/cube_geometry_100k.toml --threads 1 --quiet -o "$out/geometry_$round"
  "$B" run cases/bench/cube_walls_100k.toml --threads 1 --quiet -o "$out/base_$round"
done
/usr/bin/python3 - "$out" "$ROUNDS" <<'PY'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
def figures(name):
    s = [json.load(open(f"{out}/{name}_{r}/summary.json")) for r in range(1, rounds + 1)]
    return [x["particle_steps_per_second"] for x in s], [x["peak_memory_bytes"] for x in s]
faces, geometry, base = figures("faces"), figures("geometry"), figures("base")
for name, (speed, memory) in (("box faces", faces), ("[[geometry]] planes", geometry), ("base, box faces", base)):
    print(f"{name:22s} {statistics.median(speed) / 1e6:7.3f} M particle-steps/s  (min {min(speed) / 1e6:.3f}, max {max(speed) / 1e6:.3f})"
          f"  peak memory {statistics.median(memory) / 2**20:7.1f} MiB")
ratios = [g / f for g, f in zip(geometry[0], faces[0])]
print(f"geometry / faces, per round: median {statistics.median(ratios):.3f} (min {min(ratios):.3f}, max {max(ratios):.3f})")
ratios = [f / b for f, b in zip(faces[0], base[0])]
print(f"faces / base, per round: median {statistics.median(ratios):.3f} (min {min(ratios):.3f}, max {max(ratios):.3f})")
PY
