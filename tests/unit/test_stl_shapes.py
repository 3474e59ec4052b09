#!/usr/bin/python3
"""tools/stl_shapes.py against the geometry of its shapes, each written binary and ASCII and read
back with the small STL parser below (not grainflow's: the two should not share their mistakes).

- plane: total area LX * LY (with jittered interior vertices too), (NX+1)(NY+1) vertices, every
  triangle facing +z in the plane z = center z;
- cylinder: lateral area N * 2R sin(pi/N) * L, every vertex at R from the axis, facing the axis;
  with caps, the cap areas N/2 R^2 sin(2pi/N) added, 2 more vertices, and the signed volume minus
  the prism's (closed and facing inwards);
- box: area 2(ab + bc + ca), signed volume -abc (facing inwards), 6 N^2 + 2 vertices;
- vgroove: every normal at `angle` from +z, leaning towards the groove's axis, area 2 W L / cos;
- drum: N (M+1) + 8K vertices, 2NM + 12K triangles, the lateral area plus K bars of area
  2(HB + BL + LH), each bar closed and facing outwards (signed volume K H B L in all).

Binary STL holds float32: the binary files are compared to a relative 1e-6 (float32 round-off), the
ASCII files to 1e-12 (they hold the doubles exactly, up to the geometry's own round-off).

Usage: /usr/bin/python3 tests/unit/test_stl_shapes.py   (from anywhere)
"""
import math
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOOL = os.path.join(ROOT, "tools", "stl_shapes.py")
FAILURES = []


def read_stl(path):
    """Triangles (n, 3, 3) of a binary or ASCII STL file, and whether it was binary."""
    data = open(path, "rb").read()
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]:
        records = np.frombuffer(data, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")], offset=84)
        return records["v"].astype(float), True
    words = data.decode().split()
    corners = [[float(w) for w in words[i + 1:i + 4]] for i, w in enumerate(words) if w == "vertex"]
    return np.array(corners).reshape(-1, 3, 3), False


def check(name, value, expected, rel):
    if not abs(value - expected) <= rel * max(abs(expected), 1.0):
        FAILURES.append(f"{name}: {value!r}, expected {expected!r} (relative {rel})")


def check_true(name, condition):
    if not condition:
        FAILURES.append(name)


def shape(tmp, args, ascii):
    path = os.path.join(tmp, "shape.stl")
    subprocess.run([sys.executable, TOOL] + args.split()[:1] + [path] + args.split()[1:] + (["--ascii"] if ascii else []),
                   check=True)
    t, binary = read_stl(path)
    check_true(f"{args}: {'ASCII' if ascii else 'binary'} read as such", binary != ascii)
    return t


def cross(t):
    return np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])


def area(t):
    return 0.5 * np.linalg.norm(cross(t), axis=1).sum()


def signed_volume(t):
    return np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0


def vertex_count(t):
    return len({tuple(p) for p in t.reshape(-1, 3).tolist()})


def test_shapes(tmp, ascii):
    rel = 1e-12 if ascii else 1e-6
    kind = "ASCII" if ascii else "binary"

    for extra in ("", " --jitter 0.2 --seed 7", " --diagonals same"):
        t = shape(tmp, "plane --size 3 2 --cells 6 5 --center 1 -1 0.5" + extra, ascii)
        tag = f"plane{extra} ({kind})"
        check(f"{tag}: triangles", len(t), 60, 0)
        check(f"{tag}: vertices", vertex_count(t), 42, 0)
        check(f"{tag}: area", area(t), 6.0, rel)
        check_true(f"{tag}: every triangle faces +z", np.all(cross(t)[:, 2] > 0.0))
        check_true(f"{tag}: in z = 0.5", np.all(t[..., 2] == 0.5))

    n, m, r, length = 24, 3, 0.7, 2.0
    lateral = n * 2.0 * r * math.sin(math.pi / n) * length
    caps = n / 2.0 * r * r * math.sin(2.0 * math.pi / n)
    for capped in (False, True):
        t = shape(tmp, f"cylinder --radius {r} --length {length} --facets {n} --rings {m}" + (" --caps" if capped else ""),
                  ascii)
        tag = f"cylinder{' with caps' if capped else ''} ({kind})"
        check(f"{tag}: triangles", len(t), 2 * n * m + (2 * n if capped else 0), 0)
        check(f"{tag}: vertices", vertex_count(t), n * (m + 1) + (2 if capped else 0), 0)
        check(f"{tag}: area", area(t), lateral + (2.0 * caps if capped else 0.0), rel)
        side = t[np.abs(cross(t)[:, 2]) < 1e-9 * r * r]
        distance = np.hypot(side[..., 0], side[..., 1])
        check(f"{tag}: farthest vertex from the axis", distance.max(), r, rel)
        check(f"{tag}: nearest vertex to the axis", distance.min(), r, rel)
        centroid = side.mean(axis=1)
        check_true(f"{tag}: the side faces the axis", np.all(np.einsum("ij,ij->i", cross(side)[:, :2], centroid[:, :2]) < 0))
        if capped:
            check(f"{tag}: signed volume", signed_volume(t), -caps * length, rel)

    lo, hi = np.array([-1.0, 0.5, 2.0]), np.array([0.5, 1.25, 4.0])
    a, b, c = hi - lo
    t = shape(tmp, "box --lo {} {} {} --hi {} {} {} --cells 3".format(*lo, *hi), ascii)
    check(f"box ({kind}): triangles", len(t), 6 * 9 * 2, 0)
    check(f"box ({kind}): vertices", vertex_count(t), 6 * 9 + 2, 0)
    check(f"box ({kind}): area", area(t), 2.0 * (a * b + b * c + c * a), rel)
    check(f"box ({kind}): signed volume (facing inwards)", signed_volume(t), -a * b * c, rel)

    angle, width, length, cells = 35.0, 0.8, 1.5, 4
    t = shape(tmp, f"vgroove --angle {angle} --width {width} --length {length} --cells {cells}", ascii)
    normal = cross(t) / np.linalg.norm(cross(t), axis=1)[:, None]
    centroid = t.mean(axis=1)
    check(f"vgroove ({kind}): triangles", len(t), 2 * 2 * cells * cells, 0)
    check(f"vgroove ({kind}): area", area(t), 2.0 * width * length / math.cos(math.radians(angle)), rel)
    check(f"vgroove ({kind}): largest angle from +z", math.degrees(np.arccos(normal[:, 2].min())), angle, 1e-5)
    check(f"vgroove ({kind}): smallest angle from +z", math.degrees(np.arccos(normal[:, 2].max())), angle, 1e-5)
    check_true(f"vgroove ({kind}): each face leans towards the axis", np.all(normal[:, 0] * centroid[:, 0] < 0.0))

    n, m, r, length, k, h, w = 36, 2, 1.0, 0.5, 3, 0.15, 0.1
    t = shape(tmp, f"drum --radius {r} --length {length} --facets {n} --rings {m} --lifters {k} "
                   f"--lifter-height {h} --lifter-width {w}", ascii)
    on_wall = np.all(np.abs(np.hypot(t[..., 0], t[..., 1]) - r) <= rel * r, axis=1)
    check(f"drum ({kind}): triangles", len(t), 2 * n * m + 12 * k, 0)
    check(f"drum ({kind}): wall triangles", on_wall.sum(), 2 * n * m, 0)
    check(f"drum ({kind}): vertices", vertex_count(t), n * (m + 1) + 8 * k, 0)
    check(f"drum ({kind}): wall area", area(t[on_wall]), n * 2.0 * r * math.sin(math.pi / n) * length, rel)
    check(f"drum ({kind}): lifter area", area(t[~on_wall]), k * 2.0 * (h * w + w * length + length * h), rel)
    check(f"drum ({kind}): lifter volume (facing outwards)", signed_volume(t[~on_wall]), k * h * w * length, 10 * rel)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for ascii in (False, True):
            test_shapes(tmp, ascii)
    for f in FAILURES:
        print("FAIL", f)
    print(f"test_stl_shapes: {len(FAILURES)} failures")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
