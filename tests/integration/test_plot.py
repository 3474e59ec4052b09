#!/usr/bin/python3
"""`grainflow plot DIR` / tools/plot_run.py (docs/OUTPUTS.md "Figures") on synthetic folders, so no
simulation is needed:

- a run folder holding every input (profiles with error columns and a kinetic-theory file, a time
  series with the new columns, VACF/MSD/diffusion, zone spectra and floor correlations, and
  zone_series.h5 when h5py is there, convection fields, tracers, a VTU snapshot series written in
  vtu_writer.cpp's format): exit 0 and every expected PNG, each a valid PNG, no temporary file left;
- an event-driven Couette cell's files (strip profiles, stresses, walls, collision angles, velocity
  and pair distributions) with the writers' column names: exit 0 and exactly the Campbell PNGs
  (strip profiles are not Lan's zone profiles); a strip profile without plug_flow: exit 1 naming
  the file and column, the other figures still drawn;
- an empty folder and a missing folder: exit 1 with a message;
- a malformed convection.csv (a field that is not a number), a tracers.csv without a column and a
  truncated VTU: exit 1, the message names the file, and the other figures are still written;
- a sweep folder (sweep.csv, sweep.json, member runs with profiles and diffusion.json): exit 0 and
  the sweep_*.png figures.
With the grainflow executable as the argument (as ctest passes it), `grainflow plot DIR` is run on
the full folder too, and on two real short runs so the fixtures cannot drift from the writers: a
Chapter 5 run (convection, tracers) and Campbell's Couette cell with snapshots, analysed (every
Campbell figure, and the film: animation.mp4 with ffmpeg, else animation.gif with one frame per
snapshot when pillow is there), and a real sweep of two Couette cells (sweep_strip_profiles.png).

Usage: /usr/bin/python3 tests/integration/test_plot.py [PATH_TO_grainflow]  (from the repo root)
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, finish  # noqa: E402

try:
    import h5py
except ImportError:  # the zone-history panels are then skipped; the PNGs are still written
    h5py = None

SCRIPT = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                      "tools", "plot_run.py")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

D = 0.003            # m, sphere diameter
G = 9.81             # m/s^2
F = 12.19            # Hz, drive frequency along y
A = 0.005            # m, drive amplitude
OMEGA = 2.0 * math.pi * F
ZONES = 20

RUN_PNGS = ["profiles.png", "mass_below.png", "timeseries.png", "vacf.png", "msd.png", "zone_spectra.png",
            "floor_correlation.png", "convection.png", "convection_columns.png", "convection_phases.png",
            "tracer_height.png", "tracer_spectrum.png", "tracer_coordination.png", "snapshots_phases.png"]
SWEEP_PNGS = ["sweep_bed_height.png", "sweep_bulk_solids_fraction.png", "sweep_density_peak.png",
              "sweep_cell_temperature.png", "sweep_collisions.png", "sweep_convection_speed.png",
              "sweep_profiles.png", "sweep_mass_below.png", "sweep_diffusion.png"]


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def write_csv(path, header, rows, comments=("units: synthetic test data",)):
    lines = [f"# {c}" for c in comments] + [",".join(header)]
    lines += [",".join(f"{v:.10g}" if isinstance(v, float) else str(v) for v in row) for row in rows]
    write(path, "\n".join(lines) + "\n")


def floor(t):
    """Floor position and velocity along y: y_b = A sin(w t) (MODELS.md's drive, phase 0)."""
    return A * np.sin(OMEGA * t), A * OMEGA * np.cos(OMEGA * t)


def profile_rows(gamma):
    """A vibrated-bed-like profile: nu peaks a few layers up, higher for a larger Gamma."""
    rows = []
    for z in range(ZONES):
        lo, hi = (z - 2) * D, (z - 1) * D
        y = 0.5 * (lo + hi) / D
        nu = max(0.0, 0.5 * math.exp(-((y - 2.0 - gamma) / 3.0) ** 2) - 0.01) if y > 0 else 0.0
        t = 0.004 * gamma * math.exp(-y / 8.0) if nu > 0 else 0.0
        w = math.sqrt(t / (G * D))
        rows.append([z, lo, hi, 0.5 * (lo + hi), y, nu, 0.0, 0.001 * y, 0.0, t, 1.3 * t, t, t, 1.5 * t, w, 100.0 * t,
                     0.01 * nu, 0.05 * t, 0.05 * w])
    return rows


PROFILE_HEADER = ["zone", "position_lo", "position_hi", "position", "Y", "solids_fraction", "mean_velocity_x",
                  "mean_velocity_y", "mean_velocity_z", "temperature_x", "temperature_y", "temperature_z",
                  "temperature", "temperature_time_mean", "W", "kinetic_energy_density", "solids_fraction_error",
                  "temperature_error", "W_error"]


def write_profiles(folder, gamma=3.0):
    write_csv(os.path.join(folder, "profiles.csv"), PROFILE_HEADER, profile_rows(gamma),
              ("zone profiles along the gravity axis, long-term averages over 100 samples", "units: ..."))


def write_diffusion(folder, scale=1.0):
    values = {"particles": 239, "samples": 400, "sample_interval": 0.002, "max_lag": 100, "msd_fit_first_lag": 50,
              "msd_fit_last_lag": 100, "error_groups": 8}
    for a, d in zip("xyz", (2e-5, 5e-6, 2.2e-5)):
        for kind in ("vacf", "msd"):
            values[f"d_{kind}_{a}"] = scale * d
            values[f"d_{kind}_{a}_error"] = 0.1 * scale * d
    for kind in ("vacf", "msd"):
        values[f"d_{kind}_total"] = scale * 4.9e-5 / 3.0
        values[f"d_{kind}_total_error"] = scale * 1e-6
    write(os.path.join(folder, "analysis", "diffusion.json"), json.dumps(values, indent=2))


def vtu_text(position, radius, velocity):
    """One snapshot in src/grainflow/io/vtu_writer.cpp's layout (ASCII unstructured grid)."""
    n = len(radius)

    def block(name, kind, rows, components=""):
        body = "\n".join(rows)
        return (f'        <DataArray type="{kind}" Name="{name}"{components} format="ascii">\n{body}\n'
                "        </DataArray>\n")

    vectors = lambda values: [" ".join(repr(float(c)) for c in v) for v in values]  # noqa: E731
    three = ' NumberOfComponents="3"'
    return ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
            f'  <UnstructuredGrid>\n    <Piece NumberOfPoints="{n}" NumberOfCells="{n}">\n'
            '      <PointData Scalars="diameter" Vectors="velocity">\n'
            + block("diameter", "Float64", [repr(2 * r) for r in radius])
            + block("radius", "Float64", [repr(r) for r in radius])
            + block("velocity", "Float64", vectors(velocity), three)
            + block("angular_velocity", "Float64", vectors(np.zeros((n, 3))), three)
            + block("species", "Int32", [str(k % 2) for k in range(n)])
            + block("id", "Int64", [str(k) for k in range(n)])
            + "      </PointData>\n      <Points>\n" + block("position", "Float64", vectors(position), three)
            + "      </Points>\n      <Cells>\n" + block("connectivity", "Int64", [str(k) for k in range(n)])
            + block("offsets", "Int64", [str(k + 1) for k in range(n)])
            + block("types", "UInt8", ["1"] * n)
            + "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n")


def build_run(folder):
    """Every input of a run folder, small and synthetic."""
    rng = np.random.default_rng(7)
    os.makedirs(folder, exist_ok=True)
    write(os.path.join(folder, "summary.json"), json.dumps({
        "engine": "dem", "dimension": 3, "particles": 239, "case": "synthetic/bed.toml",
        "shaking_acceleration": A * OMEGA ** 2 / G, "boundary_fluctuation_velocity": 0.91, "mass_holdup": 5.0,
        "profile_samples": 100, "errors": [], "warnings": []}, indent=2))
    write_profiles(folder)
    theory = []
    for y in np.linspace(0.0, 17.0, 60):
        nu = 0.5 * math.exp(-((y - 5.0) / 3.2) ** 2)
        t = 0.012 * math.exp(-y / 8.0)
        theory.append([float(y), nu, math.sqrt(t / (G * D)), t, 10.0 * nu * t, 0.0])
    write_csv(os.path.join(folder, "analysis", "kinetic_theory.csv"),
              ["Y", "solids_fraction", "W", "temperature", "pressure", "heat_flux"], theory,
              ("kinetic theory (synthetic)",))

    # Time series every 2 ms for 2 s: the drive starts at 0.3 s.
    time = np.arange(0.0, 2.0 + 1e-9, 0.002)
    position, velocity = floor(time)
    on = time >= 0.3
    position, velocity = np.where(on, position, 0.0), np.where(on, velocity, 0.0)
    rows = []
    for k, t in enumerate(time):
        rows.append([float(t), 1e-3 * (1 - math.exp(-t)), 0.0, 0.02 * (1 - math.exp(-t)), 0.02 + 0.002 * t,
                     float(position[k]), float(velocity[k]), 0.003 * rng.random(), 30, 5, k // 10,
                     0.05 + 0.005 * t, 0.3 - 0.02 * t, 0.018 * (1 - math.exp(-t)), 50 * k])
    write_csv(os.path.join(folder, "timeseries.csv"),
              ["time", "kinetic_energy", "rotational_energy", "granular_temperature", "mass_center_height",
               "floor_position", "floor_velocity", "max_overlap_over_diameter", "contacts", "wall_contacts",
               "neighbor_rebuilds", "bed_height", "bulk_solids_fraction", "cell_temperature", "collisions"], rows)

    # VACF and MSD (analyze_command.cpp's columns), diffusion.json.
    lag = np.arange(101)
    tau = 0.002 * lag
    c = {"x": 0.01 * np.exp(-tau / 0.004), "y": 0.02 * np.exp(-tau / 0.01) * np.cos(OMEGA * tau),
         "z": 0.011 * np.exp(-tau / 0.004)}
    running = {a: np.concatenate([[0.0], np.cumsum(0.5 * (c[a][1:] + c[a][:-1]) * 0.002)]) for a in "xyz"}
    write_csv(os.path.join(folder, "analysis", "vacf.csv"),
              ["lag", "time", "vacf_x", "vacf_y", "vacf_z", "vacf", "running_d_x", "running_d_y", "running_d_z",
               "running_d"],
              [[int(k), float(tau[k])] + [float(c[a][k]) for a in "xyz"] + [float(sum(c[a][k] for a in "xyz"))]
               + [float(running[a][k]) for a in "xyz"] + [float(sum(running[a][k] for a in "xyz") / 3)]
               for k in lag])
    msd = {"x": 4e-5 * tau, "y": 1e-6 * (1 - np.cos(OMEGA * tau)), "z": 4.4e-5 * tau}
    write_csv(os.path.join(folder, "analysis", "msd.csv"), ["lag", "time", "msd_x", "msd_y", "msd_z", "msd"],
              [[int(k), float(tau[k])] + [float(msd[a][k]) for a in "xyz"] + [float(sum(msd[a][k] for a in "xyz"))]
               for k in lag])
    write_diffusion(folder)

    # Zone velocities along y: the floor's wave, delayed and damped with height.
    interval = 1.0 / (20.0 * F)
    t = np.arange(512) * interval
    floor_x, floor_v = floor(t)
    centres = (np.arange(ZONES) - 1.5) * D
    zones = np.array([0.5 * math.exp(-max(h, 0.0) / (8 * D)) * A * OMEGA * np.cos(OMEGA * (t - max(h, 0.0) / 0.5))
                      for h in centres]).T + 0.01 * rng.standard_normal((t.size, ZONES))
    if h5py is not None:
        with h5py.File(os.path.join(folder, "zone_series.h5"), "w") as f:
            f["time"], f["floor_position"], f["floor_velocity"], f["zone_centre"] = t, floor_x, floor_v, centres
            velocity3 = np.zeros((t.size, ZONES, 3))
            velocity3[:, :, 1] = zones
            f["zone_velocity"] = velocity3
            for key, value in (("interval", interval), ("gravity_axis", 1), ("drive_frequency", F), ("diameter", D)):
                f.attrs[key] = value
    frequency = np.fft.rfftfreq(64, interval)
    spectra = [np.abs(np.fft.rfft(series[:64])) ** 2 * interval / 64 + 1e-12 for series in [floor_v] + list(zones.T)]
    write_csv(os.path.join(folder, "analysis", "zone_spectra.csv"),
              ["frequency", "floor"] + [f"zone_{z}" for z in range(ZONES)],
              [[float(frequency[k])] + [float(s[k]) for s in spectra] for k in range(frequency.size)])
    write_csv(os.path.join(folder, "analysis", "floor_correlation.csv"),
              ["zone", "height", "delay", "speed", "peak_frequency", "peak_psd"],
              [[z, float(h), float(max(h, 0.0) / 0.5), float(0.5) if h > 0 else "nan", F, 1e-3]
               for z, h in enumerate(centres)])

    # Convection: two counter-rotating rolls in the z-y plane, the top row empty.
    header = ["column", "row", "horizontal", "vertical", "visits", "velocity_horizontal", "velocity_vertical", "speed"]
    cell = 0.1

    def cells(phase_scale=1.0):
        out = []
        for col in range(12):
            for row in range(6):
                h, v = (col + 0.5) * cell, (row + 0.5) * cell
                samples = 0 if row == 5 else 100
                speed = phase_scale * 0.02 if samples else 0.0
                u = speed * math.sin(2 * math.pi * h / 0.6) * math.cos(math.pi * v / 0.5)
                w = -speed * math.cos(2 * math.pi * h / 0.6) * math.sin(math.pi * v / 0.5)
                out.append([col, row, h, v, samples, u, w, math.hypot(u, w)])
        return out
    comment = ("convection field: horizontal axis z, vertical axis y, cell 0.1 m", "units: m, m/s")
    write_csv(os.path.join(folder, "convection.csv"), header, cells(), comment)
    write_csv(os.path.join(folder, "convection_phases.csv"), ["phase_bin"] + header,
              [[b] + row for b in range(8) for row in cells(1.0 + math.sin(2 * math.pi * b / 8))], comment)

    # Two tracers sampled every 2 ms for 3 s: a rising large sphere and a bed sphere.
    time = np.arange(0.0, 3.0, 0.002)
    fx, fv = floor(time)
    rows = []
    for k, t in enumerate(time):
        for i, base, rise in ((500, 0.01, 0.004), (17, 0.005, 0.0)):
            y = base + rise * t + 0.3 * A * math.sin(OMEGA * t - 0.5)
            vy = rise + 0.3 * A * OMEGA * math.cos(OMEGA * t - 0.5)
            coordination = 2 + int(3 * max(0.0, math.sin(OMEGA * t)))
            rows.append([float(t), i, 0.005, y, 0.007, 0.0, vy, 0.0, coordination, int(fx[k] > 0.004),
                         float(fx[k]), float(fv[k])])
    write_csv(os.path.join(folder, "tracers.csv"), ["time", "id", "x", "y", "z", "vx", "vy", "vz", "coordination",
                                                    "wall_contacts", "floor_position", "floor_velocity"], rows)

    # Snapshots every 0.01 s from 1.8 s (the time series has rows there): 30 spheres above the floor.
    entries = []
    for k, t in enumerate(np.arange(1.8, 2.0 + 1e-9, 0.01)):
        base = floor(t)[0]
        position = np.column_stack([rng.random(30) * 5 * D, base + D + rng.random(30) * 10 * D, rng.random(30) * 5 * D])
        name = f"particles_{k:06d}.vtu"
        write(os.path.join(folder, "snapshots", name), vtu_text(position, np.full(30, D / 2), np.zeros((30, 3))))
        entries.append(f'    <DataSet timestep="{t:.10g}" group="" part="0" file="{name}"/>')
    write(os.path.join(folder, "snapshots", "particles.pvd"),
          '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
          + "\n".join(entries) + "\n  </Collection>\n</VTKFile>\n")


def build_sweep(folder):
    """A sweep of drive.frequency over three runs, each with a profile and diffusion.json."""
    header = ["drive.frequency", "run", "status", "engine", "particles", "shaking_acceleration", "bed_height",
              "bed_height_error", "bulk_solids_fraction", "bulk_solids_fraction_error", "cell_temperature",
              "cell_temperature_error", "collision_rate_per_particle", "density_peak_Y", "convection_speed",
              "granular_temperature"]
    rows = []
    for k, frequency in enumerate(("[0, 8, 0]", "[0, 12.19, 0]", "[0, 16, 0]")):
        gamma = [1.3, 3.0, 5.2][k]
        run = f"drive.frequency=0_{frequency[4:-4]}_0"
        member = os.path.join(folder, run)
        write(os.path.join(member, "summary.json"), json.dumps({"engine": "dem", "particles": 239,
                                                                 "case": "synthetic/bed.toml"}))
        write_profiles(member, gamma)
        write_diffusion(member, 1.0 + k)
        rows.append([f'"{frequency}"', run, 0, "dem", 239, gamma, 0.03 + 0.002 * k, 0.0005, 0.45 - 0.05 * k, 0.01,
                     0.01 * gamma, 0.001, 400.0 / gamma, 2.0 + gamma, 0.001 * k, 0.01 * gamma])
    rows.append(['"[0, 20, 0]"', "drive.frequency=0_20_0", 1, "", "", "", "", "", "", "", "", "", "", "", "", ""])
    write_csv(os.path.join(folder, "sweep.csv"), header, rows,
              ("grainflow sweep of synthetic/bed.toml: 4 runs; values as given to --vary, then ...",))
    write(os.path.join(folder, "sweep.json"), json.dumps({"case": "synthetic/bed.toml", "mode": "product"}))


EDMD_PNGS = ["timeseries.png", "strip_profiles.png", "temperature_components.png", "stresses.png",
             "collision_angles.png", "velocity_distributions.png", "pair_distributions.png"]
REAL_EDMD_PNGS = EDMD_PNGS + ["velocity_distributions.png", "pair_distributions.png"]
STRIP_HEADER = ("strip,y,y_over_gap,solids_fraction,solids_fraction_error,particles,particles_error,u,u_error,v,"
                "v_error,omega,omega_error,u_variance,u_variance_error,v_variance,v_variance_error,uv_covariance,"
                "uv_covariance_error,rotational_temperature,rotational_temperature_error,granular_temperature,"
                "granular_temperature_error,temperature,temperature_error,translational_temperature,"
                "translational_temperature_error,temperature_lan,temperature_lan_error,u_variance_scaled,"
                "u_variance_scaled_error,v_variance_scaled,v_variance_scaled_error,rotational_temperature_scaled,"
                "rotational_temperature_scaled_error,granular_temperature_scaled,granular_temperature_scaled_error,"
                "du_dy,du_dy_error,S_prose,S_listing,plug_flow").split(",")


def build_edmd(folder):
    """An event-driven Couette cell's outputs (app/edmd_run.cpp's files and columns), synthetic:
    12 strips, a linear velocity profile, a denser plug in the middle."""
    gap, u_t, strips = 24.0, 1.0, 12
    write(os.path.join(folder, "summary.json"), json.dumps({
        "engine": "edmd", "dimension": 2, "particles": 40, "case": "synthetic/couette.toml",
        "savage_jeffrey_S": 1.5, "mean_gap": gap, "shear_speed": u_t, "profile_samples": 100, "errors": [],
        "warnings": []}))
    write_csv(os.path.join(folder, "timeseries.csv"),
              ["time", "kinetic_energy", "rotational_energy", "granular_temperature", "collisions",
               "wall_collisions", "events", "pressure", "dissipated"],
              [[10.0 * k, 1.0, 0.01, 0.05, 100 * k, 10 * k, 300 * k, 0.002, 0.01 * k] for k in range(20)])
    rows = []
    for k in range(strips):
        fraction = (k + 0.5) / strips
        value = {name: 0.01 for name in STRIP_HEADER}
        value.update(strip=k, y=fraction * gap, y_over_gap=fraction, solids_fraction=0.5 + 0.3 * (k in (5, 6)),
                     u=u_t * fraction, plug_flow=int(k in (5, 6)), granular_temperature=0.003, u_variance=0.004,
                     v_variance=0.002, rotational_temperature=0.001)
        for name in ("granular_temperature", "u_variance", "v_variance", "rotational_temperature"):
            value[name + "_scaled"] = value[name] * (gap / u_t) ** 2
        rows.append([value[name] for name in STRIP_HEADER])
    write_csv(os.path.join(folder, "profiles.csv"), STRIP_HEADER, rows,
              ("strip profiles (Campbell 1982 sections 3.1-3.2): 100 samples (synthetic)",
               f"couette: mean gap H = {gap} m, U_T = {u_t} m/s", "units: ..."))
    parts = [f"{p}_{c}{e}" for p in ("collisional", "kinetic", "total") for c in ("xx", "xy", "yx", "yy")
             for e in ("", "_error")]
    header = ["y", "y_over_H"] + parts + ["number", "mass_density", "collision_rate", "collision_rate_per_particle",
                                          "dissipation_rate", "momentum_rate_x", "momentum_rate_y", "weight_yx",
                                          "weight_yy"]
    rows = []
    for k in range(strips):
        row = [(k + 0.5) * gap / strips, (k + 0.5) / strips]
        for name in parts:
            share = {"collisional": 0.8, "kinetic": 0.2, "total": 1.0}[name.split("_")[0]]
            row.append(0.05 * share * 1e-3 if name.endswith("_error") else
                       share * (-8e-4 if "_yx" in name or "_xy" in name else 1e-3))
        rows.append(row + [3.5, 0.16, 0.01, 0.2, 3e-5, 0.0, 0.0, -8e-4, 1e-3])
    write_csv(os.path.join(folder, "stresses.csv"), header, rows)
    write_csv(os.path.join(folder, "walls.csv"),
              ["wall", "axis", "position", "area", "collisions", "normal_stress", "normal_stress_error",
               "shear_stress", "shear_stress_error", "friction", "impulse_angle_deg", "rolling_normal_stress",
               "rolling_shear_stress", "collision_rate", "dissipation_rate"],
              [["ylo", "y", 0.0, 9.6, 300, 1e-3, 5e-5, -8e-4, 4e-5, -0.8, -38.7, 0.0, 0.0, 0.015, 3e-5],
               ["yhi", "y", gap, 9.6, 200, 1e-3, 5e-5, -8e-4, 4e-5, -0.8, -38.7, 0.0, 0.0, 0.01, -9e-4]])
    theta = (np.arange(50) + 0.5) * 3.6
    law = [math.erfc(1.5 * math.cos(t) * math.sin(t) / math.sqrt(2)) / math.pi for t in np.radians(theta)]
    write_csv(os.path.join(folder, "collision_angles.csv"), ["theta_deg", "density", "count", "savage_jeffrey"],
              [[float(t), float(p), int(1000 * p), float(p)] for t, p in zip(theta, law)],
              ("units: ... savage_jeffrey 1/rad at S = 1.5",))

    # `grainflow analyze`'s distributions: half-normal P1-P3, chi densities P4 (k = 2), P5 (k = 3).
    x = (np.arange(50) + 0.5) * 0.1
    half_normal = np.sqrt(2 / math.pi) * np.exp(-x ** 2 / 2)
    chi2, chi3 = 2 * x * np.exp(-x ** 2), np.sqrt(27 / (2 * math.pi)) * 2 * x ** 2 * np.exp(-1.5 * x ** 2)
    columns = [half_normal, half_normal, half_normal, chi2, chi3]
    write_csv(os.path.join(folder, "analysis", "velocity_distributions.csv"),
              ["x"] + [f"p{k}{s}" for k in range(1, 6) for s in ("", "_fit", "_maxwell")],
              [[float(x[i])] + [float(c[i]) for c in columns for _ in range(3)] for i in range(50)])
    meta = {"dimension": 2, "diameter": 2.0, "particle_samples": 8000, "solids_fraction": 0.47, "pair_range": 8.0}
    for k, (components, maxwell) in enumerate((("u", 0.5), ("v", 0.5), ("omega", 0.5), ("u,v", 1.0),
                                               ("u,v,omega", 1.5)), start=1):
        meta.update({f"a{k}_components": components, f"a{k}": maxwell, f"a{k}_error": 0.01,
                     f"a{k}_maxwell": maxwell, f"a{k}_ratio": 1.0, f"a{k}_ratio_error": 0.02})
    write(os.path.join(folder, "analysis", "distributions.json"), json.dumps(meta))
    r = (np.arange(50) + 0.5) * 0.16
    g = 0.15 * (1 + 0.6 * np.exp(-((r - 2.0) / 0.3) ** 2)) * (r > 1.6)
    write_csv(os.path.join(folder, "analysis", "pair_distributions.csv"),
              ["r", "normal", "normal_error", "parallel", "parallel_error", "parallel_two_sided",
               "parallel_two_sided_error", "number_density"],
              [[float(r[i]), float(g[i]), 0.005, float(g[i]), 0.005, float(g[i]) if r[i] < 4.8 else "nan",
                0.005 if r[i] < 4.8 else "nan", 0.15] for i in range(50)])


def plot(folder, exe=None):
    command = [exe, "plot", folder] if exe else ["/usr/bin/python3", SCRIPT, folder]
    result = subprocess.run(command, capture_output=True, text=True)
    return result.returncode, result.stdout, result.stderr


def check_pngs(folder, names, context):
    for name in names:
        path = os.path.join(folder, name)
        if not check(os.path.isfile(path), f"{context}: {name} was not written"):
            continue
        with open(path, "rb") as f:
            head = f.read(8)
        if not check(head == PNG_SIGNATURE, f"{context}: {name} is not a PNG"):
            continue
        # A figure, not a blank or a stub: a readable size, and ink (axes, labels, curves) covering
        # between 1 % and 90 % of a white page.
        from PIL import Image
        with Image.open(path) as image:
            width, height = image.size
            gray = np.asarray(image.convert("L"), dtype=float)
        ink = float((gray < 250).mean())
        check(width >= 400 and height >= 250, f"{context}: {name} is only {width} x {height} pixels")
        check(0.01 < ink < 0.9, f"{context}: {name} has ink on {100 * ink:.2f} % of its pixels (blank or a solid block?)")
    leftovers = [n for n in os.listdir(folder) if ".tmp-" in n]
    check(not leftovers, f"{context}: temporary files left behind: {leftovers}")


def check_animation(folder, snapshots):
    """The film of an event-driven run: animation.mp4 with ffmpeg, else animation.gif with pillow
    (one frame per snapshot up to the cap of 100), else none."""
    try:
        from PIL import Image
    except ImportError:
        Image = None
    if os.path.exists("/usr/bin/ffmpeg"):
        path = os.path.join(folder, "animation.mp4")
        if check(os.path.isfile(path), "animation.mp4 was not written (ffmpeg is there)"):
            with open(path, "rb") as f:
                check(f.read(12)[4:8] == b"ftyp", "animation.mp4 is not an MP4 file")
    elif Image is not None:
        path = os.path.join(folder, "animation.gif")
        if check(os.path.isfile(path), "animation.gif was not written (pillow is there)"):
            with Image.open(path) as film:
                check(film.format == "GIF" and film.n_frames == min(snapshots, 100),
                      f"animation.gif: {film.format}, {film.n_frames} frames of {snapshots} snapshots")
    else:
        check(not any(n.startswith("animation.") for n in os.listdir(folder)), "a film without ffmpeg or pillow")


def pngs_in(folder):
    return sorted(n for n in os.listdir(folder) if n.endswith(".png"))


def main():
    exe = os.path.abspath(sys.argv[1]) if len(sys.argv) == 2 else None
    with tempfile.TemporaryDirectory(prefix="grainflow_plot_") as tmp:
        # Every input: every figure.
        full = os.path.join(tmp, "full")
        build_run(full)
        status, out, err = plot(full)
        check(status == 0, f"full run folder: exit {status}, stderr: {err.strip()}")
        check_pngs(full, RUN_PNGS, "full run folder")
        check(set(pngs_in(full)) == set(RUN_PNGS), f"full run folder: unexpected PNGs {pngs_in(full)}")
        check("wrote" in out and "convection.png" in out, f"full run folder: stdout does not list the PNGs: {out!r}")
        check(not any(n.startswith("animation.") for n in os.listdir(full)), "a DEM run got an event-driven film")

        # An event-driven run's files, synthetic with the writers' column names: the Campbell figures.
        edmd = os.path.join(tmp, "edmd")
        build_edmd(edmd)
        status, out, err = plot(edmd)
        check(status == 0 and not err.strip(), f"edmd folder: exit {status}, stderr: {err.strip()}")
        check(set(pngs_in(edmd)) == set(EDMD_PNGS), f"edmd folder: PNGs {pngs_in(edmd)}, expected {EDMD_PNGS}")
        check_pngs(edmd, EDMD_PNGS, "edmd folder")
        # A strip profile without a column the figures need: named, the other figures still drawn.
        edit_path = os.path.join(edmd, "profiles.csv")
        with open(edit_path) as f:
            text = f.read()
        with open(edit_path, "w") as f:
            f.write(text.replace(",plug_flow", ",plug", 1))
        for name in ("strip_profiles.png", "temperature_components.png"):
            os.remove(os.path.join(edmd, name))
        status, _, err = plot(edmd)
        check(status == 1 and "profiles.csv" in err and "plug_flow" in err,
              f"edmd folder without plug_flow: exit {status}, stderr: {err.strip()}")
        check("stresses.png" in pngs_in(edmd) and "strip_profiles.png" not in pngs_in(edmd),
              f"edmd folder without plug_flow: PNGs {pngs_in(edmd)}")

        # Nothing to plot, no folder.
        empty = os.path.join(tmp, "empty")
        os.makedirs(empty)
        status, _, err = plot(empty)
        check(status == 1 and "nothing to plot" in err, f"empty folder: exit {status}, stderr: {err.strip()}")
        status, _, err = plot(os.path.join(tmp, "missing"))
        check(status == 1 and "missing" in err, f"missing folder: exit {status}, stderr: {err.strip()}")

        # Malformed inputs: exit 1 naming the file; the other figures are still drawn.
        def edit(path, change):
            with open(path) as f:
                text = f.read()
            with open(path, "w") as f:
                f.write(change(text))

        def truncate_snapshots(folder):  # every VTU cut in half: whichever eight are chosen, all fail
            for name in os.listdir(os.path.join(folder, "snapshots")):
                if name.endswith(".vtu"):
                    edit(os.path.join(folder, "snapshots", name), lambda text: text[: len(text) // 2])

        cases = [
            ("convection.csv", lambda folder: edit(os.path.join(folder, "convection.csv"),
                                                   lambda text: text.replace("\n0,0,", "\n0,abc,", 1)),
             "'abc' is not a number", {"convection.png", "convection_columns.png"}),
            ("tracers.csv", lambda folder: edit(os.path.join(folder, "tracers.csv"),
                                                lambda text: text.replace("coordination,", "coordinations,", 1)),
             "missing column(s) coordination", {"tracer_height.png", "tracer_spectrum.png",
                                                "tracer_coordination.png"}),
            (".vtu", truncate_snapshots, "not a readable VTU file", {"snapshots_phases.png"}),
        ]
        for name, damage, words, lost in cases:
            broken = os.path.join(tmp, "broken" + name.replace(".", "_"))
            build_run(broken)
            damage(broken)
            status, _, err = plot(broken)
            check(status == 1, f"malformed {name}: exit {status}, expected 1")
            check(name in err and words in err, f"malformed {name}: message {err.strip()!r}")
            check(set(pngs_in(broken)) == set(RUN_PNGS) - lost,
                  f"malformed {name}: PNGs {pngs_in(broken)}, expected all but {sorted(lost)}")

        # A sweep folder.
        sweep = os.path.join(tmp, "sweep")
        build_sweep(sweep)
        status, out, err = plot(sweep)
        check(status == 0, f"sweep folder: exit {status}, stderr: {err.strip()}")
        check_pngs(sweep, SWEEP_PNGS, "sweep folder")

        # Through the command line, when the executable is given.
        if exe:
            again = os.path.join(tmp, "via_grainflow")
            shutil.copytree(full, again)
            for name in pngs_in(again):
                os.remove(os.path.join(again, name))
            status, _, err = plot(again, exe)
            check(status == 0, f"grainflow plot: exit {status}, stderr: {err.strip()}")
            check_pngs(again, RUN_PNGS, "grainflow plot")

            # The synthetic files above must match what the runs really write: plot a real (short)
            # Chapter 5 run with a convection field and a tracer.
            real = os.path.join(tmp, "real_field")
            status, _, err = subprocess_run([exe, "run", "cases/lan1994/sec5_2_large_sphere_6dx3d.toml", "-o", real,
                                             "--quiet", "--set", "run.duration=0.06", "--set", "drive.start=0",
                                             "--set", "output.average_start=0", "--set", "output.interval=0.01",
                                             "--set", "tracers.start=0"])
            if check(status == 0, f"short real run: exit {status}, stderr: {err.strip()}"):
                status, _, err = plot(real, exe)
                check(status == 0, f"grainflow plot of a real run: exit {status}, stderr: {err.strip()}")
                check_pngs(real, ["convection.png", "convection_columns.png", "convection_phases.png", "tracer_height.png",
                            "tracer_coordination.png"],
                           "real run")

            # And a real Campbell Couette cell (0.2 s of simulation time on this machine), analysed:
            # every Campbell figure from the files the event-driven run really writes.
            couette = os.path.join(tmp, "real_couette")
            status, _, err = subprocess_run([exe, "run", "cases/campbell1982/couette_noslip.toml", "-o", couette,
                                             "--quiet", "--set", "output.snapshot_interval=60"])
            if check(status == 0, f"real Couette run: exit {status}, stderr: {err.strip()}"):
                status, _, err = subprocess_run([exe, "analyze", couette])
                check(status == 0, f"grainflow analyze of the Couette run: exit {status}, stderr: {err.strip()}")
                status, _, err = plot(couette, exe)
                check(status == 0, f"grainflow plot of the real Couette run: exit {status}, stderr: {err.strip()}")
                check_pngs(couette, REAL_EDMD_PNGS, "real Couette run")
                check_animation(couette, len([n for n in os.listdir(os.path.join(couette, "snapshots"))
                                              if n.endswith(".vtu")]))

            # A real sweep of Couette cells: the members' strip profiles overlaid.
            couettes = os.path.join(tmp, "real_couette_sweep")
            status, _, err = subprocess_run([exe, "sweep", "cases/campbell1982/couette_noslip.toml", "--vary",
                                             "collision.restitution=0.6,0.8", "-o", couettes, "--quiet", "--set",
                                             "run.duration=1500", "--set", "output.average_start=500"])
            if check(status == 0, f"real Couette sweep: exit {status}, stderr: {err.strip()}"):
                status, _, err = plot(couettes, exe)
                check(status == 0, f"grainflow plot of the Couette sweep: exit {status}, stderr: {err.strip()}")
                check_pngs(couettes, ["sweep_strip_profiles.png"], "real Couette sweep")
    return finish("test_plot")


def subprocess_run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr


if __name__ == "__main__":
    sys.exit(main())
