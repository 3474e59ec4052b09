#!/bin/bash
# What a triangle mesh costs against analytic walls: the walled cube of 10^5 spheres with its six
# walls as [[geometry]] planes (cases/bench/cube_geometry_100k.toml) and as one closed mesh of
# 99 372 triangles (bench/cube_mesh_100k.toml), 300 steps, one thread, ROUNDS interleaved rounds; prints
# each variant's median particle-steps per second, peak memory and the per-round ratio.
# Usage: bench/mesh_walls.sh [ROUNDS]   (from the repository root, after make release)
set -euo pipefail
ROUNDS=${1:-5}
A=build/release/grainflow
[ -x "$A" ] || { echo "mesh_walls: $A is missing: build the working tree first (make release)" >&2; exit 2; }
mkdir -p build/bench
/usr/bin/python3 tools/stl_shapes.py box build/bench/cube_box_100k.stl --lo 0 0 0 --hi 0.1435 0.1435 0.1435 --cells 91
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for round in $(seq "$ROUNDS"); do
  "$A" run cases/bench/cube_geometry_100k.toml --threads 1 --quiet -o "$out/planes_$round"
  "$A" run bench/cube_mesh_100k.toml --threads 1 --quiet -o "$out/mesh_$round"
done
/usr/bin/python3 - "$out" "$ROUNDS" <<'PY'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
def figures(name):
    s = [json.load(open(f"{out}/{name}_{r}/summary.json")) for r in range(1, rounds + 1)]
    return [x["particle_steps_per_second"] for x in s], [x["peak_memory_bytes"] for x in s]
planes, mesh = figures("planes"), figures("mesh")
for name, (speed, memory) in (("six [[geometry]] planes", planes), ("one mesh, 99 372 triangles", mesh)):
    print(f"{name:28s} {statistics.median(speed) / 1e6:7.3f} M particle-steps/s  (min {min(speed) / 1e6:.3f}, max {max(speed) / 1e6:.3f})"
          f"  peak memory {statistics.median(memory) / 2**20:7.1f} MiB")
ratios = [m / p for m, p in zip(mesh[0], planes[0])]
print(f"mesh / planes, per round: median {statistics.median(ratios):.3f} (min {min(ratios):.3f}, max {max(ratios):.3f})")
PY
