#!/usr/bin/python3
"""Campbell's distributions end to end (Campbell 1982 section 3.4): the bundled no-slip Couette case
(cases/campbell1982/couette_noslip.toml, 40 rough inelastic discs, its [trajectory] table) writes
trajectory.h5 with instantaneous states on the grid t_k = start + k interval; `grainflow analyze`
writes analysis/velocity_distributions.csv, pair_distributions.csv and distributions.json.

Checked here, independently of the C++ code: the file's layout and sampling grid; the X1 (u) and X4
(u, v) histograms and the normal and parallel pair distributions recomputed with numpy straight from
the definitions (strip of each centre, strip means and mean squares over all samples; test
particles within a diameter of the midplane, counts over slice regions), to round-off; the
Maxwellian columns; a_4 in a broad physical range (Campbell's generalized Maxwellians have
a_i / a_mi within about 0.7-1.5); the pair distributions' plateau at large distance near the cell's
number density; --strips restricting the count; and the case errors for the engine-specific keys.

Usage: /usr/bin/python3 tests/integration/test_edmd_distributions.py PATH_TO_grainflow  (from the repo root)
"""
import json
import os
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

CASE = os.path.join("cases", "campbell1982", "couette_noslip.toml")


def strips_of(f):
    """Strip index of every particle sample (-1 outside), as Campbell: the strip holding the centre."""
    y = f["position"][:, :, 1]
    lo, hi = f["strip_lo"][:], f["strip_hi"][:]
    count = int(f.attrs["strip_count"])
    k = np.floor((y - lo[:, None]) / ((hi - lo)[:, None] / count)).astype(int)
    k[(y < lo[:, None]) | (y >= hi[:, None])] = -1
    return np.minimum(k, count - 1), count


def x_histograms(f):
    """X1 and X4 densities on [0, 5) in 50 bins, normalised by the total count and the bin width."""
    k, count = strips_of(f)
    v = f["velocity"][:]
    inside = k >= 0
    u, w = v[:, :, 0][inside], v[:, :, 1][inside]
    ks = k[inside]
    mean_u = np.array([u[ks == j].mean() for j in range(count)])
    mean_v = np.array([w[ks == j].mean() for j in range(count)])
    du, dv = u - mean_u[ks], w - mean_v[ks]
    var_u = np.array([np.mean(du[ks == j] ** 2) for j in range(count)])
    var_v = np.array([np.mean(dv[ks == j] ** 2) for j in range(count)])
    x1 = np.abs(du) / np.sqrt(var_u[ks])
    x4 = np.sqrt((du ** 2 + dv ** 2) / (var_u[ks] + var_v[ks]))
    edges = np.linspace(0.0, 5.0, 51)
    return [np.histogram(x, bins=edges)[0] / (len(x) * 0.1) for x in (x1, x4)]


def overlap(a, b, lo, hi):
    return np.clip(np.minimum(b, hi) - np.maximum(a, lo), 0.0, None)


def pair_densities(f):
    """Normal (by |dy|) and parallel (|dy| < d, by the forward periodic dx) densities on [0, 4d)."""
    x = f["position"][:]
    lo, hi, width = f["wall_lo"][:], f["wall_hi"][:], f["box_width"][:]
    d = 2.0 * f["radius"][:].mean()
    h = 4.0 * d / 50
    a = np.arange(50) * h
    counts = np.zeros((2, 50))
    measures = np.zeros((2, 50))
    for t in range(x.shape[0]):
        mid = 0.5 * (lo[t] + hi[t])
        for i in np.nonzero(np.abs(x[t, :, 1] - mid) < d)[0]:
            yi = x[t, i, 1]
            others = np.delete(np.arange(x.shape[1]), i)
            dy = np.abs(x[t, others, 1] - yi)
            counts[0] += np.histogram(dy, bins=np.append(a, 4.0 * d))[0]
            forward = np.mod(x[t, others, 0] - x[t, i, 0], width[t])
            counts[1] += np.histogram(forward[dy < d], bins=np.append(a, 4.0 * d))[0]
            measures[0] += (overlap(yi + a, yi + a + h, lo[t], hi[t]) + overlap(yi - a - h, yi - a, lo[t], hi[t])) * width[t]
            measures[1] += overlap(a, a + h, 0.0, width[t]) * overlap(yi - d, yi + d, lo[t], hi[t])
    return counts / measures


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_distributions_") as tmp:
        out = os.path.join(tmp, "couette")
        status, _, err = run(exe, "run", CASE, "-o", out, "--quiet")
        if not check(status == 0, f"run exited {status}: {err.strip()}"):
            return finish("test_edmd_distributions")
        summary = json.load(open(os.path.join(out, "summary.json")))
        check(summary["warnings"] == [], f"warnings: {summary['warnings']}")
        with h5py.File(os.path.join(out, "trajectory.h5"), "r") as f:
            samples, start, interval = int(f.attrs["samples"]), f.attrs["start"], f.attrs["interval"]
            check(f.attrs["engine"] in (b"edmd", "edmd") and f.attrs["dimension"] == 2, "engine / dimension attributes")
            check(f.attrs["inertia_factor"] == 0.5 and f.attrs["flow_axis"] == 0 and f.attrs["gradient_axis"] == 1,
                  "inertia_factor / axes attributes")
            check(samples == 2000 and start == 1000.0 and abs(interval - 1.0) < 1e-12,
                  f"samples {samples}, start {start}, interval {interval} (default: 2000 s / 2000)")
            time = f["time"][:]
            check(np.allclose(time, start + interval * np.arange(samples), rtol=0, atol=1e-9), "sample times")
            for name in ("position", "velocity", "angular_velocity"):
                check(f[name].shape == (samples, 40, 3), f"{name} shape {f[name].shape}")
            check(list(f["id"][:]) == list(range(40)) and np.all(f["radius"][:] == 1.0), "ids and radii")
            gap = f["wall_hi"][:] - f["wall_lo"][:]
            check(np.all((gap > 15.0) & (gap < 40.0)), f"wall gap from {gap.min()} to {gap.max()}")
            check(np.allclose(f["box_width"][:] / gap, 9.6 / 24.0, rtol=1e-9), "the width follows the gap (scale_width)")
            check(np.all(f["velocity"][:, :, 2] == 0.0) and np.all(f["angular_velocity"][:, :, :2] == 0.0),
                  "2D: w and the in-plane spins are zero")
            x1, x4 = x_histograms(f)
            normal, parallel = pair_densities(f)

        status, stdout, err = run(exe, "analyze", out)
        if not check(status == 0, f"analyze exited {status}: {err.strip()}"):
            return finish("test_edmd_distributions")
        rows = read_csv(os.path.join(out, "analysis", "velocity_distributions.csv"))
        check(len(rows) == 50, f"{len(rows)} velocity bins")
        p1 = np.array([float(r["p1"]) for r in rows])
        p4 = np.array([float(r["p4"]) for r in rows])
        check(np.allclose(p1, x1, rtol=1e-9, atol=1e-12), f"p1 differs from numpy's by {np.abs(p1 - x1).max()}")
        check(np.allclose(p4, x4, rtol=1e-9, atol=1e-12), f"p4 differs from numpy's by {np.abs(p4 - x4).max()}")
        xs = np.array([float(r["x"]) for r in rows])
        check(np.allclose([float(r["p4_maxwell"]) for r in rows], 2 * xs * np.exp(-xs ** 2), rtol=1e-9),
              "p4_maxwell is 2 X exp(-X^2)")
        check(np.allclose([float(r["p1_maxwell"]) for r in rows], np.sqrt(2 / np.pi) * np.exp(-xs ** 2 / 2), rtol=1e-9),
              "p1_maxwell is the folded Gaussian 2 sqrt(1/(2 pi)) exp(-X^2 / 2)")
        d = json.load(open(os.path.join(out, "analysis", "distributions.json")))
        check(d["samples"] == samples and d["particle_samples"] == 40 * samples,
              f"samples {d['samples']}, particle samples {d['particle_samples']}")
        check(0.7 < d["a4"] < 1.6, f"a4 = {d['a4']} outside the physical range")
        for i, am in enumerate((0.5, 0.5, 0.5, 1.0, 1.5), start=1):
            check(d[f"a{i}_maxwell"] == am and abs(d[f"a{i}_ratio"] / (d[f"a{i}"] / am) - 1) < 1e-9, f"a{i} ratio")
            check(0.0 < d[f"a{i}_error"] < 0.2 * d[f"a{i}"], f"a{i} error {d[f'a{i}_error']}")
        check(d["s"] > 0.0 and abs(d["s_uv"] / d["s"] - np.sqrt(d["u_fluctuation_square"] / (
            d["u_fluctuation_square"] + d["v_fluctuation_square"]))) < 1e-9, "S forms")

        pairs = read_csv(os.path.join(out, "analysis", "pair_distributions.csv"))
        n = float(pairs[0]["number_density"])
        check(abs(n - d["number_density"]) < 1e-9 * n and abs(d["solids_fraction"] - n * np.pi) < 1e-9,
              "number density and nu")
        got_normal = np.array([float(r["normal"]) for r in pairs])
        got_parallel = np.array([float(r["parallel"]) for r in pairs])
        check(np.allclose(got_normal, normal, rtol=1e-9), f"normal differs from numpy's by {np.abs(got_normal - normal).max()}")
        check(np.allclose(got_parallel, parallel, rtol=1e-9),
              f"parallel differs from numpy's by {np.abs(got_parallel - parallel).max()}")
        r = np.array([float(row["r"]) for row in pairs])
        far = (r > 6.0) & (r < 8.0)
        # The plateau: 12 slices of normal distribution, each with a few % error (block averages).
        check(abs(got_normal[far].mean() / n - 1.0) < 0.1, f"normal plateau {got_normal[far].mean()} vs n = {n}")
        # Inside the core a layer partner within R along the flow needs |dy| > sqrt(4R^2 - dx^2): at
        # most 13 % of the layer, so even at a dense contact density (g ~ 2.8 at nu ~ 0.47) the mean
        # over dx < R stays well under n.
        check(got_parallel[r < 1.0].mean() < 0.3 * n, "parallel distribution inside the excluded core")
        check(2.0 - 0.25 < r[np.argmax(got_parallel[r < 4.0])] < 2.0 + 0.25, "parallel contact peak at 2R")

        status, _, _ = run(exe, "analyze", out, "--strips", "3", "8")
        d38 = json.load(open(os.path.join(out, "analysis", "distributions.json")))
        check(status == 0 and d38["first_strip"] == 3 and d38["last_strip"] == 8 and
              0 < d38["particle_samples"] < d["particle_samples"], f"--strips 3 8: {d38['particle_samples']}")
        status, _, err = run(exe, "analyze", out, "--strips", "3", "99")
        check(status == 2 and "--strips" in err, f"--strips 3 99: status {status}, {err.strip()}")

        text = open(CASE).read()
        bad = write_text(os.path.join(tmp, "bad.toml"), text.replace("samples = 2000", "samples = 2000\nwindow = 1.0"))
        status, _, err = run(exe, "check", bad)
        check(status == 2 and "trajectory.window" in err, f"edmd with trajectory.window: {status} {err.strip()}")
        late = write_text(os.path.join(tmp, "late.toml"), text.replace("samples = 2000", "samples = 2000\nstart = 3000.0"))
        status, _, err = run(exe, "check", late)
        check(status == 2 and "trajectory.start" in err, f"samples starting at the end: {status} {err.strip()}")
    return finish("test_edmd_distributions")


if __name__ == "__main__":
    sys.exit(main())
