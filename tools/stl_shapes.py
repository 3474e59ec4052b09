#!/usr/bin/python3
"""Writes STL files of simple shapes, so that tests and cases need no outside files.

Usage: stl_shapes.py SHAPE OUTPUT.stl [options] [--ascii]     (binary STL unless --ascii)

Lengths are in whatever unit the case uses. Every shape's front (the side its triangles' corners
run counter-clockwise about, the side (b - a) x (c - a) points to) faces the particles:

  plane     a rectangle in z = center z, tessellated into cells of two triangles; faces +z.
  cylinder  a faceted cylinder about the z axis from z = 0 to z = length, its vertices at the angles
            2 pi k / facets exactly (the facets are chords of the circle); faces inwards (a
            container). With --caps both ends are closed, facing inwards too: a closed container
            facing inwards has a negative enclosed volume (grainflow turns a closed mesh to face
            outwards; its mesh contact is two-sided, so that changes no contact).
  vgroove   two planes meeting along the y axis at z = 0, each inclined at --angle degrees from the
            horizontal (opening upwards), x from -width to width, y from 0 to length; faces up
            into the groove.
  drum      a cylinder as above with open ends (the case closes them) and --lifters bars along
            its inner wall, equally spaced from angle 0: each bar is a separate closed box merged
            into the file (simpler than cutting it into the wall), its outer face at the radius so
            that it reaches through the facets, facing outwards, at the particles.
  box       a closed axis-aligned box from --lo to --hi, each face cells x cells squares of two
            triangles; faces inwards (a container).

Every triangle is checked for a positive area before the file is written.
"""
import argparse
import math
import sys

import numpy as np


def grid(points, diagonals="same"):
    """Triangles of a grid of points (nu + 1, nv + 1, 3): two per cell, counter-clockwise about the
    u x v direction. 'alternate' switches the diagonal from cell to cell."""
    a, b = points[:-1, :-1], points[1:, :-1]
    c, d = points[1:, 1:], points[:-1, 1:]
    first = np.stack([a, b, c], axis=2), np.stack([a, c, d], axis=2)
    if diagonals == "same":
        return np.concatenate([t.reshape(-1, 3, 3) for t in first])
    other = np.stack([a, b, d], axis=2), np.stack([b, c, d], axis=2)
    i, j = np.meshgrid(range(a.shape[0]), range(a.shape[1]), indexing="ij")
    even = ((i + j) % 2 == 0)[..., None, None]
    return np.concatenate([np.where(even, f, o).reshape(-1, 3, 3) for f, o in zip(first, other)])


def turned(triangles):
    """The same triangles facing the other way."""
    return triangles[:, ::-1]


def plane(size, cells, center, jitter=0.0, seed=1, diagonals="alternate"):
    if not 0.0 <= jitter < 0.25:
        sys.exit("stl_shapes.py: --jitter must be in [0, 0.25): further can turn a triangle over")
    (lx, ly), (nx, ny) = size, cells
    x, y = np.meshgrid(np.linspace(-0.5, 0.5, nx + 1) * lx, np.linspace(-0.5, 0.5, ny + 1) * ly, indexing="ij")
    # Interior vertices move in the plane; the edges stay straight, so the area stays lx * ly.
    moves = np.random.default_rng(seed).uniform(-jitter, jitter, (2, nx - 1, ny - 1))
    x[1:-1, 1:-1] += moves[0] * lx / nx
    y[1:-1, 1:-1] += moves[1] * ly / ny
    points = np.stack([x + center[0], y + center[1], np.full_like(x, center[2])], axis=-1)
    return grid(points, diagonals)  # u = x, v = y: faces +z


def ring(radius, facets):
    """The facets' corners: angles 2 pi k / facets, k taken modulo facets so that the seam closes on
    the same numbers."""
    angle = 2.0 * math.pi * (np.arange(facets + 1) % facets) / facets
    return radius * np.cos(angle), radius * np.sin(angle)


def cylinder(radius, length, facets, rings, caps=False):
    cx, cy = ring(radius, facets)
    z = np.linspace(0.0, length, rings + 1)
    points = np.stack(np.broadcast_arrays(cx[:, None], cy[:, None], z[None, :]), axis=-1)
    parts = [turned(grid(points))]  # u along the angle, v = +z: u x v is outwards; turned inwards
    if caps:
        for height, up in ((0.0, True), (length, False)):
            rim = np.stack([cx, cy, np.full_like(cx, height)], axis=-1)
            fan = np.stack([np.broadcast_to([0.0, 0.0, height], rim[:-1].shape), rim[:-1], rim[1:]], axis=1)
            parts.append(fan if up else turned(fan))  # counter-clockwise about +z: faces up
    return np.concatenate(parts)


def vgroove(angle, width, length, cells):
    if not 0.0 <= angle < 90.0:
        sys.exit("stl_shapes.py: --angle must be in [0, 90) degrees")
    slope = math.tan(math.radians(angle))
    x, y = np.meshgrid(np.linspace(-width, width, 2 * cells + 1), np.linspace(0.0, length, cells + 1), indexing="ij")
    x[cells] = 0.0  # the ridge exactly on the axis, shared by both faces
    # A surface z = f(x, y) walked counter-clockwise about +z in (x, y) faces up.
    return grid(np.stack([x, y, slope * np.abs(x)], axis=-1))


def box(lo, hi, cells, inwards=True):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    if not np.all(hi > lo):
        sys.exit("stl_shapes.py: --hi must exceed --lo on every axis")
    # One list of coordinates per axis, so the faces meeting at an edge share its vertices exactly.
    ticks = [np.linspace(lo[a], hi[a], cells + 1) for a in range(3)]
    parts = []
    for a in range(3):
        u, v = (a + 1) % 3, (a + 2) % 3  # u x v = +axis a
        for at, plus in ((lo[a], True), (hi[a], False)):
            points = np.empty((cells + 1, cells + 1, 3))
            points[..., a] = at
            points[..., u], points[..., v] = np.meshgrid(ticks[u], ticks[v], indexing="ij")
            faces_in = plus  # the face at lo faces +axis, into the box
            parts.append(grid(points) if faces_in == inwards else turned(grid(points)))
    return np.concatenate(parts)


def drum(radius, length, facets, rings, lifters, lifter_height, lifter_width):
    if lifters and not (0.0 < lifter_height < radius and lifters * lifter_width < 2.0 * math.pi * (radius - lifter_height)):
        sys.exit("stl_shapes.py: the lifters must fit inside the drum, side by side at most")
    parts = [cylinder(radius, length, facets, rings)]
    # A bar in (radial, tangential, z) coordinates, turned to its angle: a rotation about z keeps
    # the winding, so the box keeps facing outwards.
    bar = box([radius - lifter_height, -0.5 * lifter_width, 0.0], [radius, 0.5 * lifter_width, length], 1, inwards=False)
    for k in range(lifters):
        phi = 2.0 * math.pi * k / lifters
        c, s = math.cos(phi), math.sin(phi)
        parts.append(bar @ np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]))
    return np.concatenate(parts)


def normals(triangles):
    return np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])


def write_stl(path, triangles, ascii=False):
    triangles = np.asarray(triangles, float)
    n = normals(triangles)
    area = 0.5 * np.linalg.norm(n, axis=1)
    corners = triangles.reshape(-1, 3)
    diagonal2 = np.sum((corners.max(axis=0) - corners.min(axis=0)) ** 2)
    if np.any(area <= 1e-12 * diagonal2):  # the same test as grainflow's reader
        sys.exit(f"stl_shapes.py: triangle {np.argmax(area <= 1e-12 * diagonal2) + 1} has zero area")
    n /= 2.0 * area[:, None]
    if ascii:
        with open(path, "w") as f:
            f.write("solid stl_shapes\n")
            for normal, t in zip(n, triangles):
                # repr: the shortest text that reads back as the same double.
                f.write("  facet normal %s\n    outer loop\n" % " ".join(map(repr, normal.tolist())))
                for corner in t.tolist():
                    f.write("      vertex %s\n" % " ".join(map(repr, corner)))
                f.write("    endloop\n  endfacet\n")
            f.write("endsolid stl_shapes\n")
        return
    record = np.zeros(len(triangles), dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    record["normal"], record["corners"] = n, triangles
    with open(path, "wb") as f:
        f.write(b"stl_shapes.py binary STL".ljust(80, b"\0"))  # a header not starting with "solid"
        f.write(np.uint32(len(triangles)).astype("<u4").tobytes())
        f.write(record.tobytes())


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    shapes = parser.add_subparsers(dest="shape", required=True, metavar="SHAPE")

    def shape(name, summary):
        p = shapes.add_parser(name, help=summary, description=summary + " (lengths in the case's unit)")
        p.add_argument("output", metavar="OUTPUT.stl")
        p.add_argument("--ascii", action="store_true", help="write ASCII STL (default: binary)")
        return p

    def round_(p, facets):
        p.add_argument("--radius", type=float, default=1.0)
        p.add_argument("--length", type=float, default=1.0, help="along z, from z = 0")
        p.add_argument("--facets", type=int, default=facets, help="facets around the axis")
        p.add_argument("--rings", type=int, default=1, help="segments along the axis")

    p = shape("plane", "a tessellated rectangle in z = center z, facing +z")
    p.add_argument("--size", type=float, nargs=2, default=[1.0, 1.0], metavar=("LX", "LY"))
    p.add_argument("--cells", type=int, nargs=2, default=[4, 4], metavar=("NX", "NY"))
    p.add_argument("--center", type=float, nargs=3, default=[0.0, 0.0, 0.0], metavar=("X", "Y", "Z"))
    p.add_argument("--jitter", type=float, default=0.0, help="move interior vertices in the plane by up to this "
                   "fraction of a cell, at random (below 0.25)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--diagonals", choices=["alternate", "same"], default="alternate")
    p = shape("cylinder", "a faceted cylinder about z, facing inwards")
    round_(p, 32)
    p.add_argument("--caps", action="store_true", help="close both ends (facing inwards)")
    p = shape("vgroove", "two planes meeting along y at z = 0, opening upwards, facing up")
    p.add_argument("--angle", type=float, default=30.0, help="each face's inclination from the horizontal (degrees)")
    p.add_argument("--width", type=float, default=1.0, help="x extent of each face")
    p.add_argument("--length", type=float, default=1.0, help="along y, from y = 0")
    p.add_argument("--cells", type=int, default=4, help="cells per face along x and along y")
    p = shape("drum", "an open faceted cylinder about z with lifter bars on its inner wall")
    round_(p, 48)
    p.add_argument("--lifters", type=int, default=4)
    p.add_argument("--lifter-height", type=float, default=0.1, help="radial height of a bar")
    p.add_argument("--lifter-width", type=float, default=0.1, help="tangential width of a bar")
    p = shape("box", "a closed axis-aligned box, facing inwards")
    p.add_argument("--lo", type=float, nargs=3, default=[0.0, 0.0, 0.0], metavar=("X", "Y", "Z"))
    p.add_argument("--hi", type=float, nargs=3, default=[1.0, 1.0, 1.0], metavar=("X", "Y", "Z"))
    p.add_argument("--cells", type=int, default=1, help="squares along each edge of a face")

    a = parser.parse_args(argv)
    counts = [np.atleast_1d(getattr(a, k)) for k in ("cells", "facets", "rings") if hasattr(a, k)]
    if np.any(np.concatenate(counts) < 1) or (a.shape in ("cylinder", "drum") and a.facets < 3):
        sys.exit("stl_shapes.py: cells and rings must be at least 1, facets at least 3")
    if a.shape == "plane":
        triangles = plane(a.size, a.cells, a.center, a.jitter, a.seed, a.diagonals)
    elif a.shape == "cylinder":
        triangles = cylinder(a.radius, a.length, a.facets, a.rings, a.caps)
    elif a.shape == "vgroove":
        triangles = vgroove(a.angle, a.width, a.length, a.cells)
    elif a.shape == "drum":
        triangles = drum(a.radius, a.length, a.facets, a.rings, a.lifters, a.lifter_height, a.lifter_width)
    else:
        triangles = box(a.lo, a.hi, a.cells)
    write_stl(a.output, triangles, a.ascii)


if __name__ == "__main__":
    main()
