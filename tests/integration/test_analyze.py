#!/usr/bin/python3
"""Trajectory sampling and `grainflow analyze` end to end (Lan 1994 sections 3.2-3.3): a short run
of a small bed with a [trajectory] table writes trajectory.h5 (readable with h5py: ids, times,
windowed velocities and unwrapped positions, attributes); `grainflow analyze` writes
analysis/vacf.csv, msd.csv and diffusion.json. The first lags of the VACF and the MSD are
recomputed here with numpy, straight from the definitions (eqs. 3-2-6 and 3-3-7, unbiased: every
product of a lag averaged over all particles and time origins), and must agree to round-off; the
diffusion coefficients are the running integral at the last lag (VACF) and half the least-squares
slope over the second half of the lags (MSD), recomputed the same way. A folder without
trajectory.h5 is refused with exit status 2.

Zone series (Lan section 4.3): a longer run of the same bed with a [zone_series] table writes
zone_series.h5; analyze writes zone_spectra.csv, whose floor spectrum (the floor moves as a pure
sinusoid) peaks at the drive frequency, within one frequency bin, as a line standing far above the
rest of the spectrum (the estimator's normalisation is unit-tested in test_analysis_spectrum), and
floor_correlation.csv, whose delays are recomputed with numpy as the first cross-correlation peak
within one drive period (to one sample).

Usage: /usr/bin/python3 tests/integration/test_analyze.py PATH_TO_grainflow  (from the repo root)
"""
import json
import os
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

SAMPLES, MAX_LAG = 120, 40
CASE = f"""[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.015, 0.05, 0.015]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "periodic" }}

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 40

[particles]
init = "random"
expansion_time = 0.005
initial_temperature = 0.05
seed = 9

[contact]
k1 = 1.0e6
restitution = 0.9

[drive]
face = "ylo"
amplitude = [0.0, 0.0015, 0.0]
frequency = [0.0, 30.0, 0.0]

[run]
duration = 0.03

[output]
interval = 0.005

[trajectory]
start = 0.01
samples = {SAMPLES}
max_lag = {MAX_LAG}
"""


def check_zone_series(exe, tmp):
    case = write_text(os.path.join(tmp, "bed_series.toml"), CASE.replace("duration = 0.03", "duration = 0.4")
                      .replace('frequency = [0.0, 30.0, 0.0]', 'frequency = [0.0, 30.0, 0.0]\nramp = 0.0')
                      + "\n[zone_series]\nstart = 0.05\nsamples = 200\n")
    out = os.path.join(tmp, "bed_series")
    status, _, err = run(exe, "run", case, "-o", out, "--quiet")
    if not check(status == 0, f"zone series run exited {status}: {err.strip()}"):
        return
    status, _, err = run(exe, "analyze", out)
    if not check(status == 0, f"analyze (zone series) exited {status}: {err.strip()}"):
        return
    with h5py.File(os.path.join(out, "zone_series.h5"), "r") as f:
        u, floor_v = f["zone_velocity"][:], f["floor_velocity"][:]
        interval, drive = f.attrs["interval"], f.attrs["drive_frequency"]
    check(abs(interval - 1 / (20 * 30.0)) < 1e-15 and drive == 30.0, f"interval {interval}, drive {drive}")
    check(u.shape[0] == 200 and u.shape[2] == 3, f"zone_velocity shape {u.shape}")
    spectra = read_csv(os.path.join(out, "analysis", "zone_spectra.csv"))
    freq = np.array([float(r["frequency"]) for r in spectra])
    floor_psd = np.array([float(r["floor"]) for r in spectra])
    df = freq[1] - freq[0]
    peak = freq[1:][np.argmax(floor_psd[1:])]
    check(abs(peak - 30.0) <= df, f"floor spectrum peaks at {peak} Hz, not 30 Hz (bin {df} Hz)")
    # A Hann window leaks a line into its two neighbouring bins only; beyond them the spectrum of a
    # sinusoid is down by orders of magnitude, so the median bin is far below the peak.
    check(floor_psd.max() > 100 * np.median(floor_psd), f"floor spectrum: peak {floor_psd.max()}, median {np.median(floor_psd)}")
    rows = read_csv(os.path.join(out, "analysis", "floor_correlation.csv"))
    check(len(rows) == u.shape[1], f"{len(rows)} correlation rows for {u.shape[1]} zones")
    period = int(np.ceil(1 / (drive * interval)))
    f0 = floor_v - floor_v.mean()
    worst = 0
    for z in range(u.shape[1]):
        zone = u[:, z, 1] - u[:, z, 1].mean()
        if not zone.any():
            continue
        n = len(f0)
        c = [np.dot(f0[: n - k], zone[k:]) / (n - k) for k in range(period)]
        worst = max(worst, abs(float(rows[z]["delay"]) / interval - int(np.argmax(c))))
    check(worst <= 1.0, f"zone delays differ from numpy's first peak by up to {worst} samples")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_analyze_") as tmp:
        case = write_text(os.path.join(tmp, "bed.toml"), CASE)
        out = os.path.join(tmp, "bed")
        status, _, err = run(exe, "run", case, "-o", out, "--quiet")
        if not check(status == 0, f"run exited {status}: {err.strip()}"):
            return finish("test_analyze")
        with h5py.File(os.path.join(out, "trajectory.h5"), "r") as f:
            ids, time = f["id"][:], f["time"][:]
            v, x = f["velocity"][:], f["position"][:]
            window, lag_attr = f.attrs["window"], f.attrs["max_lag"]
            dt = f.attrs["time_step"]
        check(list(ids) == list(range(40)), f"trajectory.h5 ids: {list(ids)[:5]}...")
        check(v.shape == (SAMPLES, 40, 3) and x.shape == v.shape, f"trajectory shapes {v.shape} {x.shape}")
        check(lag_attr == MAX_LAG, f"max_lag attribute {lag_attr}")
        check(abs(window / (7.5 * dt) - 1) < 1e-12, f"default window {window} s is not 7.5 steps of {dt} s")
        check(np.allclose(np.diff(time), window, rtol=1e-9) and abs(time[0] - (0.01 + window / 2)) < 1e-12,
              f"sample times: first {time[0]}, spacing {np.diff(time)[:3]}")
        check(not os.path.exists(os.path.join(out, "trajectory.h5.tmp")), "trajectory.h5.tmp left behind")

        status, stdout, err = run(exe, "analyze", out)
        if not check(status == 0, f"analyze exited {status}: {err.strip()}"):
            return finish("test_analyze")
        vacf = read_csv(os.path.join(out, "analysis", "vacf.csv"))
        msd = read_csv(os.path.join(out, "analysis", "msd.csv"))
        with open(os.path.join(out, "analysis", "diffusion.json")) as f:
            diffusion = json.load(f)
        check(len(vacf) == MAX_LAG + 1 and len(msd) == MAX_LAG + 1, f"{len(vacf)} VACF rows, {len(msd)} MSD rows")
        worst = 0.0
        expected_vacf, expected_msd = np.zeros((MAX_LAG + 1, 3)), np.zeros((MAX_LAG + 1, 3))
        for k in range(MAX_LAG + 1):
            expected_vacf[k] = (v[: SAMPLES - k] * v[k:]).mean(axis=(0, 1))
            expected_msd[k] = ((x[k:] - x[: SAMPLES - k]) ** 2).mean(axis=(0, 1))
        for k in range(MAX_LAG + 1):
            for a, name in enumerate("xyz"):
                got_v, got_m = float(vacf[k]["vacf_" + name]), float(msd[k]["msd_" + name])
                scale_v = expected_vacf[0].max()
                scale_m = max(expected_msd[MAX_LAG].max(), 1e-300)
                worst = max(worst, abs(got_v - expected_vacf[k, a]) / scale_v, abs(got_m - expected_msd[k, a]) / scale_m)
        # The CSV prints 10 significant digits; the FFT estimators agree with the direct sums to ~1e-12.
        check(worst < 1e-8, f"VACF / MSD differ from the direct definitions by {worst:.3g} (relative)")
        lags = np.arange(MAX_LAG + 1) * window
        for a, name in enumerate("xyz"):
            c = expected_vacf[:, a]
            d_vacf = window * (c.sum() - 0.5 * (c[0] + c[-1]))  # trapezoid rule up to the last lag
            first = MAX_LAG // 2
            slope = np.polyfit(lags[first:], expected_msd[first:, a], 1)[0]
            check(abs(diffusion["d_vacf_" + name] / d_vacf - 1) < 1e-8,
                  f"D_{name} from the VACF: {diffusion['d_vacf_' + name]} vs {d_vacf}")
            check(abs(diffusion["d_msd_" + name] / (slope / 2) - 1) < 1e-8,
                  f"D_{name} from the MSD: {diffusion['d_msd_' + name]} vs {slope / 2}")
            check(diffusion["d_vacf_" + name + "_error"] > 0, f"D_{name}: no error bar")
        check("D_x" in stdout, f"analyze printed no summary: {stdout}")
        # Savage's D (eqs. 4-3-3, 4-3-4) from the summary's cell-average T and bulk nu, with d and e
        # from trajectory.h5, recomputed from the formula.
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        t, nu = summary["cell_temperature"], summary["bulk_solids_fraction"]
        g0 = (2 - nu) / (2 * (1 - nu) ** 3)
        expected = 0.003 * np.sqrt(np.pi * t) / (8 * (1 + 0.9) * nu * g0)
        check("d_savage_dai" in diffusion and abs(diffusion["d_savage_dai"] / expected - 1) < 1e-9,
              f"Savage-Dai D {diffusion.get('d_savage_dai')} vs {expected} from T = {t}, nu = {nu}")

        check_zone_series(exe, tmp)

        empty = os.path.join(tmp, "empty")
        os.makedirs(empty)
        status, _, err = run(exe, "analyze", empty)
        check(status == 2 and "trajectory.h5" in err and "[trajectory]" in err,
              f"analyze of a folder without trajectory.h5: exit {status}, {err.strip()}")
    return finish("test_analyze")


if __name__ == "__main__":
    sys.exit(main())
