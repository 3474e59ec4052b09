#!/usr/bin/python3
"""A vibrated bed like Lan (1994) Table 4.2 run through the command line for 10 s of simulated time:
the run succeeds, particles stay where they can be, the output folder follows INTERFACE.md, the
depth profiles conserve the mass hold-up, and their shape is Lan's (section 4.1: temperature
highest at the floor, solids fraction peaking at an intermediate depth).

The case: N = 119 smooth spheres, d = 0.01 m, rho = 2490 kg/m^3, e = 0.9, in a 5 d x 5 d cell with
periodic sides (m_t = N pi d^2 / (6 A) = 2.49, Table 4.2's 2.5), a flat floor and an open top;
50 Hz vertical shaking at V_b = 2. Lan drives Table 4.2 with the rotary floor of eq. (4-1-1), but
for smooth spheres on a flat floor "the x and z components do not transfer any momentum to the bed"
(section 4.1), so only the vertical component matters: its amplitude follows from eq. (4-1-3),
a = V_b sqrt(2 d g) / (2 pi f) = 2.82 mm (Gamma = 28.4, peak floor speed 0.886 m/s). K1 is Table 4.2's
3.64e6 N/m, the value Lan found by keeping the overlap below 1% of d; the smallest value of the
table, 1.2e5 N/m, lets overlaps reach 3.4% of d at this drive (measured), against the 1% limit.
Pouring until 0.5 s, amplitude ramp over 1 s, averages from 3 s. About 15 s of wall time.

Usage: /usr/bin/python3 tests/integration/test_vibrated_bed.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

D = 0.01          # m
N = 119
RHO = 2490.0      # kg/m^3
WIDTH = 0.05      # m, x and z
TOP = 0.5         # m, domain top (open)
G = 9.81
F = 50.0          # Hz
V_B = 2.0
AMPLITUDE = V_B * math.sqrt(2.0 * D * G) / (2.0 * math.pi * F)  # eq. (4-1-3): 2.8199 mm
K1 = 3.64e6
E = 0.9
N_STEPS = 15
AVERAGE_START = 3.0

CASE = f"""# Lan 1994 Table 4.2 (m_t = 2.5, V_b = 2, 50 Hz), vertical drive: integration test.
[engine]
kind = "dem"
dimension = 3

[domain]
lo = [0.0, 0.0, 0.0]
hi = [{WIDTH}, {TOP}, {WIDTH}]
boundary = {{ x = "periodic", y = ["wall", "open"], z = "periodic" }}

[gravity]
vector = [0.0, -{G}, 0.0]

[[species]]
name = "glass"
diameter = {D}
density = {RHO}
count = {N}

[particles]
init = "random"
region_lo = [0.0, 0.0, 0.0]
region_hi = [{WIDTH}, 0.15, {WIDTH}]
seed = 7

[contact]
model = "walton_braun"
k1 = {K1}
restitution = {E}
friction = 0.0

[drive]
face = "ylo"
amplitude = [0.0, {AMPLITUDE!r}, 0.0]
frequency = [0.0, {F}, 0.0]
start = 0.5
ramp = 1.0

[run]
duration = 10.0
collision_steps = {N_STEPS}
halt_overlap = 0.01

[output]
interval = 0.01
average_start = {AVERAGE_START}
"""

def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_bed_") as tmp:
        case_path = write_text(os.path.join(tmp, "lan_table_4_2.toml"), CASE)
        out = os.path.join(tmp, "out")
        started = time.monotonic()
        status, _, err = run(exe, "run", case_path, "-o", out, "--quiet")
        wall = time.monotonic() - started
        print(f"grainflow run: {wall:.1f} s wall for 10 s simulated")
        if not check(status == 0, f"run exited {status}: {err.strip()}"):
            return 1

        mass = math.pi / 6.0 * D ** 3 * RHO
        dt = math.pi * E / N_STEPS * math.sqrt(mass / (2.0 * K1))  # eq. (2-5-4)
        m_t = N * math.pi * D ** 2 / (6.0 * WIDTH * WIDTH)        # eq. (4-1-3)

        # --- summary.json: the INTERFACE keys, with values that follow from the case.
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        for key in ("engine", "dimension", "particles", "case", "version", "simulated_time", "wall_seconds", "steps",
                    "time_step", "particle_steps_per_second", "max_overlap_over_diameter", "kinetic_energy",
                    "granular_temperature", "errors", "warnings"):
            check(key in summary, f"summary.json lacks '{key}'")
        version = run(exe, "--version")[1].split()[-1]
        check(summary.get("engine") == "dem", f"engine = {summary.get('engine')!r}")
        check(summary.get("dimension") == 3, f"dimension = {summary.get('dimension')!r}")
        check(summary.get("particles") == N, f"particles = {summary.get('particles')!r}, expected {N}")
        check(summary.get("case") == case_path, f"case = {summary.get('case')!r}, expected {case_path}")
        check(summary.get("version") == version, f"version = {summary.get('version')!r}, --version says {version}")
        check(summary.get("errors") == [], f"errors = {summary.get('errors')!r}")
        check(isinstance(summary.get("warnings"), list), "warnings is not a list")
        # The step of eq. (2-5-4), to the 10 digits summary.json prints; the run ends within one step of 10 s.
        check(abs(summary.get("time_step", 0) - dt) < 1e-9 * dt, f"time_step = {summary.get('time_step')}, eq. (2-5-4) gives {dt}")
        check(abs(summary.get("simulated_time", 0) - 10.0) <= dt, f"simulated_time = {summary.get('simulated_time')}")
        check(abs(summary.get("steps", 0) - round(10.0 / dt)) <= 1, f"steps = {summary.get('steps')}, 10 s / dt = {10.0 / dt:.1f}")
        check(summary.get("wall_seconds", 0) > 0, "wall_seconds not positive")
        rate = N * summary.get("steps", 0) / max(summary.get("wall_seconds", 1), 1e-12)
        check(abs(summary.get("particle_steps_per_second", 0) - rate) < 1e-6 * rate,
              f"particle_steps_per_second = {summary.get('particle_steps_per_second')}, particles * steps / wall_seconds = {rate}")
        # Lan's T_x, T_y, T_z (Table 4.6) are the components' shares of the cell-average temperature:
        # they add up to it (to the 10 digits printed), and the vertical drive makes T_y the largest.
        parts = [summary.get(f"cell_temperature_{a}", float("nan")) for a in "xyz"]
        total = summary.get("cell_temperature", float("nan"))
        check(abs(sum(parts) / total - 1.0) < 1e-8, f"cell_temperature_x/_y/_z {parts} add up to {sum(parts)}, not {total}")
        check(parts[1] > max(parts[0], parts[2]), f"cell temperature components {parts}: T_y is not the largest")
        # Lan's criterion (section 4.1.3): the overlap stays below 1% of d (halt_overlap also enforces it).
        overlap = summary.get("max_overlap_over_diameter", 1.0)
        check(0.0 < overlap < 0.01, f"max_overlap_over_diameter = {overlap}, must lie in (0, 0.01)")
        print(f"max overlap / d = {overlap:.4g}")

        # --- timeseries.csv
        rows = read_csv(os.path.join(out, "timeseries.csv"))
        for column in ("time", "kinetic_energy", "granular_temperature"):
            check(column in rows[0], f"timeseries.csv lacks the column '{column}'")
        times = [float(r["time"]) for r in rows]
        check(all(b > a for a, b in zip(times, times[1:])), "timeseries times do not increase")
        check(len(rows) == 1001, f"timeseries has {len(rows)} rows, expected 1001 (every 0.01 s over 10 s, and t = 0)")
        # Rows fall on the step nearest to k * interval: no drift over the run (printed to 10 digits).
        worst = max(abs(t - 0.01 * k) for k, t in enumerate(times))
        check(worst <= 0.5 * dt * 1.001 + 1e-9, f"timeseries times drift from k * 0.01 s by up to {worst} s (time step {dt} s)")
        check(all(float(r["kinetic_energy"]) >= 0.0 and float(r["granular_temperature"]) >= 0.0 for r in rows),
              "negative kinetic energy or temperature in timeseries.csv")
        # The summary's temperature is the long-term average of the rows from average_start on (the rows
        # carry 10 digits, so their mean is good to ~1e-9).
        late = [float(r["granular_temperature"]) for r in rows if float(r["time"]) >= AVERAGE_START]
        mean_t = sum(late) / len(late)
        check(abs(summary.get("granular_temperature", 0) - mean_t) <= 1e-8 * mean_t,
              f"summary granular_temperature {summary.get('granular_temperature')} is not the mean {mean_t} of the rows after {AVERAGE_START} s")
        if "floor_position" in rows[0]:
            # Still until the pour ends, never beyond the amplitude (plus the 10 printed digits).
            check(all(float(r["floor_position"]) == 0.0 for r in rows if float(r["time"]) <= 0.5),
                  "the floor moved before drive.start")
            check(max(abs(float(r["floor_position"])) for r in rows) <= AMPLITUDE * (1 + 1e-9),
                  "the floor moved beyond its amplitude")

        # --- final_state.csv: where the particles are.
        state = read_csv(os.path.join(out, "final_state.csv"))
        check(len(state) == N, f"final_state.csv has {len(state)} rows, expected {N}")
        check(sorted(int(r["id"]) for r in state) == list(range(N)), "final_state.csv ids are not 0..N-1")
        # Laterally in the periodic box: the engine wraps positions at each neighbor rebuild and a particle
        # moves less than half the skin (0.15 d / 2) between rebuilds.
        slack = 0.075 * D
        for r in state:
            x, y, z = float(r["x"]), float(r["y"]), float(r["z"])
            check(-slack <= x <= WIDTH + slack and -slack <= z <= WIDTH + slack, f"particle {r['id']} left the periodic cell: x={x}, z={z}")
            # Above the floor's lowest reach, -a, less the 1% overlap bound; below the open top (a particle
            # leaving the floor at three times its peak speed, 2.7 m/s, rises 0.36 m).
            check(y - 0.5 * D >= -AMPLITUDE - 0.01 * D, f"particle {r['id']} is below the floor: y = {y}")
            check(y < TOP, f"particle {r['id']} is above the domain: y = {y}")
        # Smooth spheres, frictionless floor, no initial velocities: horizontal momentum stays zero. Round-off
        # over 4e6 steps is ~1e-15 m/s per particle (measured); a momentum leak is mm/s.
        for axis in ("vx", "vz"):
            drift = sum(float(r[axis]) for r in state) / N
            check(abs(drift) < 1e-10, f"mean {axis} = {drift} m/s: horizontal momentum is not conserved")

        # --- profiles.csv
        zones = read_csv(os.path.join(out, "profiles.csv"))
        for column in ("position_lo", "position_hi", "solids_fraction", "temperature"):
            check(column in zones[0], f"profiles.csv lacks '{column}'")
        lo = [float(z["position_lo"]) for z in zones]
        hi = [float(z["position_hi"]) for z in zones]
        nu = [float(z["solids_fraction"]) for z in zones]
        check(all(0.0 <= v <= 0.74 for v in nu), f"solids fraction outside [0, 0.74]: {min(nu)} .. {max(nu)}")
        check(lo[0] <= -AMPLITUDE and hi[-1] >= TOP - 1e-12,
              f"zones span [{lo[0]}, {hi[-1]}]; they must reach from the floor's lowest position to the top")
        # Nothing came near the open top: the upper 20 zones stayed empty in every sample, so no particle was
        # above the domain during averaging (one crossing the 0.2 m band at <= 3 m/s would be sampled >= 60
        # times, one sample per ms). Then the profile holds every sphere's volume in every sample, and
        # sum(nu * thickness / d) = m_t (eq. 4-1-3) exactly; the 10 printed digits and the float sums leave
        # ~1e-9 relative, 1e-6 is allowed.
        check(all(v == 0.0 for v in nu[-20:]), "particles reached the top 20 zones: the mass balance below would not hold")
        integral = sum(v * (h - l) / D for v, l, h in zip(nu, lo, hi))
        check(abs(integral - m_t) < 1e-6 * m_t, f"sum(solids_fraction * thickness / d) = {integral}, m_t = {m_t}")
        print(f"profile integral {integral:.9f}, m_t {m_t:.9f}")

        # Lan section 4.1 (Figs. A4.1, A4.3, m_t = 2.5, V_b = 2): "a maximum [of W(Y)] at the vibrating
        # floor and a monotonic decrease with depth, while the solids fraction profile has a peak at some
        # intermediate depth and a lower value at the vibrating floor". Judged over the bed's body (zones
        # with nu > 0.05: W there is an average over thousands of particle samples; zone to zone it
        # falls by 1..20%, so the comparisons use the peak, not each neighbor).
        body = [i for i, v in enumerate(nu) if v > 0.05]
        check(len(body) >= 8, f"only {len(body)} zones with solids fraction > 0.05: the bed is not where expected")
        if body and "W" in zones[0]:
            w = [float(zones[i]["W"]) for i in body]
            check(w.index(max(w)) == 0, f"W(Y) in the bed peaks in its zone {w.index(max(w))}, not at the floor: {w}")
            check(w[-1] < 0.5 * w[0], f"W(Y) does not decrease through the bed: {w[0]} at the floor, {w[-1]} at the top")
            peak = max(body, key=lambda i: nu[i])
            check(body[0] < peak < body[-1], f"the solids fraction peaks at the edge of the bed (zone {peak})")
            check(nu[body[0]] < 0.6 * nu[peak], f"the solids fraction at the floor, {nu[body[0]]}, is not well below the peak {nu[peak]}")

    return finish("test_vibrated_bed")


if __name__ == "__main__":
    sys.exit(main())
