#!/usr/bin/python3
"""The event-driven engine from the command line (the output folder of OUTPUTS.md):

- `grainflow run cases/campbell1982/chute_30deg.toml` (shortened with --set) exits 0 and writes
  summary.json with engine "edmd" and the EDMD keys (events, collisions, events_per_second, pressure,
  packing_fraction, compressibility_factor), consistent with each other and with the case
  (packing fraction = 40 pi R^2 / box area; Z = P / (n m T)); timeseries.csv with its columns, one
  row per output interval, counters that never decrease and end at the summary's; final_state.csv
  with 40 discs, none overlapping another or the floor.
- `--set run.collisions=N` stops the chute at its N-th particle collision exactly, with a last
  timeseries row there.
- `run.protocol = "campbell"` runs the chute in segments of exactly `segment_collisions` collisions
  (Campbell's I5 field held at most 99,999), stops after `max_segments` with a warning when none
  converged, and otherwise at the first segment steady throughout by the section 2.5 check.
- An elastic hard-disc gas run through the CLI reports a compressibility factor that matches
  Henderson's equation of state Z = (1 + phi^2/8) / (1 - phi)^2 (the summary's virial pressure,
  end to end).
- Bad EDMD inputs exit with status 2 before writing anything, naming the file, the key and the
  reason: restitution 1.5, tangential_restitution 2, overlapping explicit particles in a particle
  file, a packing fraction random placement cannot reach, a [contact] table in an EDMD case, and a
  few more.

Usage: /usr/bin/python3 tests/integration/test_edmd_cli.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, elastic_gas_case, executable_from_argv, finish, read_csv, run, write_text  # noqa: E402

CHUTE = "cases/campbell1982/chute_30deg.toml"
CHUTE_DURATION = 50.0   # of the case's 500 (units sqrt(R/g)): ~0.1 s of wall time
SUMMARY_KEYS = ["engine", "dimension", "particles", "case", "version", "simulated_time", "wall_seconds", "events",
                "collisions", "events_per_second", "pressure", "packing_fraction", "compressibility_factor",
                "kinetic_energy", "granular_temperature", "errors", "warnings"]
TIMESERIES_COLUMNS = ["time", "kinetic_energy", "rotational_energy", "granular_temperature", "collisions",
                      "wall_collisions", "events", "pressure"]
FINAL_STATE_HEADER = "id,species,diameter,x,y,z,vx,vy,vz,wx,wy,wz"


def check_chute(exe, tmp):
    out = os.path.join(tmp, "chute")
    status, _, err = run(exe, "run", CHUTE, "-o", out, "--quiet", "--set", f"run.duration={CHUTE_DURATION}",
                         "--set", "output.average_start=10.0")
    if not check(status == 0, f"chute: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    for key in SUMMARY_KEYS:
        check(key in summary, f"chute: summary.json lacks '{key}'")
    if any(key not in summary for key in SUMMARY_KEYS):
        return
    check(summary["engine"] == "edmd", f"chute: engine is {summary['engine']!r}, expected 'edmd'")
    check(summary["dimension"] == 2 and summary["particles"] == 40,
          f"chute: dimension {summary['dimension']}, particles {summary['particles']}: expected 2 and 40")
    check(summary["errors"] == [], f"chute: errors {summary['errors']}")
    check(abs(summary["simulated_time"] - CHUTE_DURATION) < 1e-9,
          f"chute: simulated_time {summary['simulated_time']}, expected {CHUTE_DURATION}")
    for key in ("events", "collisions"):
        check(isinstance(summary[key], int) and summary[key] > 1000, f"chute: {key} = {summary[key]!r}")
    # Every collision (particle or wall) is an event; cell crossings and stale events are the rest.
    check(summary["events"] >= summary["collisions"] + summary.get("wall_collisions", 0),
          f"chute: events {summary['events']} < collisions {summary['collisions']} + wall collisions")
    # events_per_second = events / wall_seconds (the values are printed to 10 significant digits).
    if check(summary["wall_seconds"] > 0, f"chute: wall_seconds = {summary['wall_seconds']}"):
        rate = summary["events"] / summary["wall_seconds"]
        check(abs(summary["events_per_second"] / rate - 1) < 1e-6,
              f"chute: events_per_second {summary['events_per_second']} is not events / wall_seconds = {rate}")
    # 40 discs of R = 1 in the 9.6 x 80 control volume: packing fraction 40 pi / 768.
    phi = 40 * math.pi / (9.6 * 80.0)
    check(abs(summary["packing_fraction"] - phi) < 1e-8 * phi,
          f"chute: packing_fraction {summary['packing_fraction']}, expected {phi}")
    # Z = P / (n m T): unit masses, n = 40 / 768 per unit area, T the averaged granular temperature.
    check(math.isfinite(summary["pressure"]) and summary["pressure"] > 0, f"chute: pressure {summary['pressure']}")
    n_m_t = 40 / (9.6 * 80.0) * 1.0 * summary["granular_temperature"]
    check(n_m_t > 0 and abs(summary["compressibility_factor"] - summary["pressure"] / n_m_t) < 1e-6 * summary[
        "compressibility_factor"], f"chute: compressibility_factor {summary['compressibility_factor']} is not "
                                   f"P / (n m T) = {summary['pressure'] / n_m_t if n_m_t > 0 else 'n/a'}")

    rows = read_csv(os.path.join(out, "timeseries.csv"))
    if check(len(rows) > 0, "chute: timeseries.csv has no rows"):
        for column in TIMESERIES_COLUMNS:
            check(column in rows[0], f"chute: timeseries.csv lacks the column '{column}'")
        # Output interval 1.0: rows at t = 0, 1, ..., 50.
        times = [float(r["time"]) for r in rows]
        check(len(rows) == int(CHUTE_DURATION) + 1 and all(abs(t - k) < 1e-9 for k, t in enumerate(times)),
              f"chute: timeseries times {times[:3]}...{times[-2:]} ({len(rows)} rows), expected 0, 1, ..., 50")
        for column in ("collisions", "wall_collisions", "events"):
            if column not in rows[0]:
                continue
            values = [int(r[column]) for r in rows]
            check(all(b >= a for a, b in zip(values, values[1:])), f"chute: timeseries {column} decreases")
            summary_key = column
            check(values[-1] == summary.get(summary_key), f"chute: last {column} {values[-1]} != summary "
                                                          f"{summary.get(summary_key)}")
        check(all(math.isfinite(float(r["kinetic_energy"])) and float(r["kinetic_energy"]) >= 0 for r in rows),
              "chute: timeseries kinetic_energy not finite and non-negative")

    with open(os.path.join(out, "final_state.csv")) as f:
        lines = [line.rstrip("\n") for line in f if not line.startswith("#")]
    check(lines and lines[0] == FINAL_STATE_HEADER, f"chute: final_state.csv header {lines[:1]}")
    discs = [dict(zip(FINAL_STATE_HEADER.split(","), line.split(","))) for line in lines[1:]]
    check(len(discs) == 40, f"chute: final_state.csv has {len(discs)} rows, expected 40")
    # No disc through the floor (y >= R) or into another (periodic in x, width 9.6): hard discs may
    # touch, with positions round-off (1e-9 of a diameter) from exact contact.
    worst = 0.0
    for i, a in enumerate(discs):
        xa, ya, ra = float(a["x"]), float(a["y"]), 0.5 * float(a["diameter"])
        worst = max(worst, (ra - ya) / ra)
        for b in discs[i + 1:]:
            dx = xa - float(b["x"])
            dx -= 9.6 * round(dx / 9.6)
            dy = ya - float(b["y"])
            sigma = ra + 0.5 * float(b["diameter"])
            worst = max(worst, 1 - math.hypot(dx, dy) / sigma)
    check(worst < 1e-9, f"chute: final_state.csv has an overlap of {worst} diameters")


def check_run_in_collisions(exe, tmp):
    # [run] collisions = N (runs given in collisions, as Campbell's listings count them): the run
    # stops at its N-th particle collision, long before the case's duration of 500, and writes a
    # last row there.
    target = 20000
    out = os.path.join(tmp, "chute_collisions")
    status, _, err = run(exe, "run", CHUTE, "-o", out, "--quiet", "--set", f"run.collisions={target}")
    if not check(status == 0, f"run.collisions: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    rows = read_csv(os.path.join(out, "timeseries.csv"))
    check(summary["collisions"] == target, f"run.collisions: stopped after {summary['collisions']}, not {target}")
    check(summary["simulated_time"] < 500.0, f"run.collisions: ran to t = {summary['simulated_time']}")
    check(len(rows) >= 2 and int(rows[-1]["collisions"]) == target and int(rows[-2]["collisions"]) < target,
          f"run.collisions: the last rows do not end at {target} collisions ({[r['collisions'] for r in rows[-2:]]})")
    check(abs(float(rows[-1]["time"]) - summary["simulated_time"]) < 1e-9 * summary["simulated_time"],
          f"run.collisions: last row at t = {rows[-1]['time']}, the run ended at {summary['simulated_time']}")


def check_campbell_protocol(exe, tmp):
    # Segments of 20,000 collisions, at most 3: the 30 degree chute is still accelerating then, so
    # no segment passes the check; each ends at its budget's last collision exactly.
    budget, most = 20000, 3
    out = os.path.join(tmp, "chute_segments")
    status, _, err = run(exe, "run", CHUTE, "-o", out, "--quiet", "--set", 'run.protocol="campbell"', "--set",
                         f"run.segment_collisions={budget}", "--set", f"run.max_segments={most}")
    if not check(status == 0, f"campbell protocol: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    rows = read_csv(os.path.join(out, "timeseries.csv"))
    check(summary["protocol"] == "campbell", f"campbell protocol: protocol {summary.get('protocol')!r}")
    check(summary["segments"] == most and not summary["segment_converged"],
          f"campbell protocol: {summary['segments']} segments, converged {summary['segment_converged']}: expected "
          f"{most}, not converged (the chute still accelerates)")
    check(summary["segment_collisions"] == budget,
          f"campbell protocol: last segment {summary['segment_collisions']} collisions, budget {budget}")
    check(summary["collisions"] == most * budget,
          f"campbell protocol: {summary['collisions']} collisions in {most} segments of {budget}")
    ends = [int(r["collisions"]) for r in rows if int(r["collisions"]) % budget == 0 and int(r["collisions"]) > 0]
    check(ends == [budget * (k + 1) for k in range(most)], f"campbell protocol: rows at the segments' ends {ends}")
    check(any("Campbell's protocol" in w for w in summary["warnings"]),
          f"campbell protocol: no warning that no segment converged: {summary['warnings']}")
    # Campbell's own budget of 99,999: a later segment is steady throughout, and the run stops there.
    out = os.path.join(tmp, "chute_converged")
    status, _, err = run(exe, "run", CHUTE, "-o", out, "--quiet", "--set", 'run.protocol="campbell"', "--set",
                         "output.average_start=0")
    if not check(status == 0, f"campbell protocol (converging): exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    check(summary["segment_converged"] and summary["steady_from"] == summary["segment_start_time"],
          f"campbell protocol: converged {summary['segment_converged']}, steady from {summary['steady_from']}, "
          f"segment from {summary['segment_start_time']}")
    check(summary["averaged_when_steady"] and summary["warnings"] == [],
          f"campbell protocol: the converged segment's averages are not the steady ones: {summary['warnings']}")
    check(summary["segment_collisions"] == 99999,
          f"campbell protocol: the converged segment has {summary['segment_collisions']} collisions")


def check_average_window_in_collisions(exe, tmp):
    # output.average_start_collisions = N: the summary's long-term pressure averages only the rows
    # reached after N particle collisions. With rows of equal length the long-term pressure is the
    # mean of the rows' interval pressures, so it must equal the mean over exactly those rows (to the
    # 6 significant digits timeseries.csv prints), and differ from the mean over all rows (the chute
    # accelerates, so its pressure drifts).
    target = 20000
    out = os.path.join(tmp, "chute_average_collisions")
    status, _, err = run(exe, "run", CHUTE, "-o", out, "--quiet", "--set", "run.duration=60", "--set", "output.average_start=0",
                         "--set", f"output.average_start_collisions={target}")
    if not check(status == 0, f"average_start_collisions: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    rows = read_csv(os.path.join(out, "timeseries.csv"))[1:]  # the t = 0 row has no interval
    late = [float(r["pressure"]) for r in rows if int(r["collisions"]) >= target]
    every = [float(r["pressure"]) for r in rows]
    if not check(0 < len(late) < len(every), f"average_start_collisions: {len(late)} of {len(every)} rows averaged"):
        return
    expected = sum(late) / len(late)
    check(abs(summary["pressure"] / expected - 1) < 1e-5,
          f"average_start_collisions: summary pressure {summary['pressure']} != mean of late rows {expected}")
    check(abs(sum(every) / len(every) / expected - 1) > 1e-3,
          "average_start_collisions: the window made no difference (test cannot tell)")


def check_hard_disc_pressure(exe, tmp):
    # 400 elastic smooth discs at packing fraction 0.35 (20 x 20 square lattice melting within a few
    # collisions per particle, ~1.6 collisions per unit time per disc). Averaged from t = 10 to 300:
    # ~1.9e5 collisions. Henderson (1975) is within ~0.5% of simulations at this density (the engine
    # test checks it more closely); the statistical error is estimated from the timeseries rows,
    # each a pressure over an interval of 10 (~40 collisions per disc, so nearly independent).
    # Tolerance: 1% of Z plus 3 standard errors; the standard error must be below 0.5%.
    phi, side = 0.35, 20
    spacing = math.sqrt(math.pi / 4 / phi)
    text, _ = elastic_gas_case(2, side, phi, 300.0, "interval = 10.0\naverage_start = 10.0", seed=12)
    case = write_text(os.path.join(tmp, "hard_discs.toml"), text)
    out = os.path.join(tmp, "hard_discs")
    status, _, err = run(exe, "run", case, "-o", out, "--quiet")
    if not check(status == 0, f"hard discs: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    henderson = (1 + phi * phi / 8) / (1 - phi) ** 2
    z = summary["compressibility_factor"]
    check(abs(summary["packing_fraction"] - phi) < 1e-6, f"hard discs: packing_fraction {summary['packing_fraction']}")
    # Per-row Z from the interval pressures; the temperature of an elastic gas is constant.
    n_m_t = side * side / (side * spacing) ** 2 * summary["granular_temperature"]
    rows = [r for r in read_csv(os.path.join(out, "timeseries.csv")) if float(r["time"]) > 10.0]
    zs = [float(r["pressure"]) / n_m_t for r in rows]
    mean = sum(zs) / len(zs)
    error = math.sqrt(sum((x - mean) ** 2 for x in zs) / (len(zs) - 1) / len(zs))
    print(f"hard discs phi = {phi}: Z = {z:.4f} (rows {mean:.4f} +- {error:.4f}), Henderson {henderson:.4f}, "
          f"{summary['collisions']} collisions, {summary['events_per_second']:.3g} events/s")
    check(error < 0.005 * henderson, f"hard discs: standard error {error} too large for the comparison")
    check(abs(z - henderson) < 0.01 * henderson + 3 * error,
          f"hard discs: compressibility_factor {z} vs Henderson {henderson} (tolerance 1% + 3 x {error})")


# A valid 2D EDMD case: 30 discs (d = 2 mm) in a periodic channel with a rough floor.
VALID = """[engine]
kind = "edmd"
dimension = 2

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.01]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[gravity]
vector = [0.0, -9.81, 0.0]

[[species]]
name = "disc"
diameter = 0.002
density = 2.0
count = 30

[particles]
init = "random"
initial_temperature = 0.01
seed = 3

[collision]
restitution = 0.9
roughness = "rough"
elastic_speed = 1e-4

[walls.ylo]
condition = "rough"
restitution = 0.8

[run]
duration = 0.05

[output]
interval = 0.01
"""

FILE_CASE = VALID.replace("count = 30", "count = 0").replace('init = "random"', 'init = "file"\nfile = "{file}"')

# (name, case text, key the message must name, words of the reason)
BAD_CASES = [
    ("restitution_above_1", VALID.replace("restitution = 0.9", "restitution = 1.5"), "collision.restitution",
     "[0, 1]"),
    ("tangential_restitution_2", VALID.replace('roughness = "rough"', "tangential_restitution = 2.0"),
     "collision.tangential_restitution", "[-1, 1]"),
    ("random_fraction_unreachable", VALID.replace("count = 30", "count = 250"), "species.count",
     "random placement"),
    ("contact_table", VALID + "\n[contact]\nk1 = 1.0e6\n", "'contact'", "[collision]"),
    ("wall_restitution_negative", VALID.replace("restitution = 0.8", "restitution = -0.1"), "walls.ylo.restitution",
     "must lie in"),
    ("unknown_wall_condition", VALID.replace('condition = "rough"', 'condition = "sticky"'), "walls.ylo.condition",
     "no_slip"),
    ("unknown_roughness", VALID.replace('roughness = "rough"', 'roughness = "sandpaper"'), "collision.roughness",
     "must be"),
    ("unknown_restitution_law", VALID.replace("elastic_speed = 1e-4", 'restitution_law = "hertz"'),
     "collision.restitution_law", "campbell"),
    ("negative_elastic_speed", VALID.replace("elastic_speed = 1e-4", "elastic_speed = -1.0"),
     "collision.elastic_speed", "negative"),
    ("strips_thinner_than_a_radius", VALID.replace("interval = 0.01", "interval = 0.01\nzone_thickness = 0.0005"),
     "output.zone_thickness", "radius"),
]


def check_bad_inputs(exe, tmp):
    valid = write_text(os.path.join(tmp, "valid_edmd.toml"), VALID)
    status, _, err = run(exe, "run", valid, "-o", os.path.join(tmp, "valid_out"), "--quiet")
    check(status == 0, f"the valid EDMD case exited {status}: {err.strip()}")

    # Overlapping explicit particles: two discs 1.5 mm apart (d = 2 mm) in a particle file. The
    # file and the key (the two particles) are named, the reason says they overlap. A file with the
    # same discs 2.5 mm apart is accepted (the check is about the overlap, not the file).
    overlap_file = write_text(os.path.join(tmp, "overlap.csv"),
                              "species,x,y,z,vx,vy,vz\ndisc,0.005,0.01,0.0,0,0,0\ndisc,0.0065,0.01,0.0,0,0,0\n")
    apart_file = write_text(os.path.join(tmp, "apart.csv"),
                            "species,x,y,z,vx,vy,vz\ndisc,0.005,0.01,0.0,0,0,0\ndisc,0.0075,0.01,0.0,0,0,0\n")
    apart = write_text(os.path.join(tmp, "apart.toml"), FILE_CASE.replace("{file}", apart_file))
    status, _, err = run(exe, "check", apart)
    check(status == 0, f"two discs apart in a particle file: check exited {status}: {err.strip()}")

    cases = [(name, write_text(os.path.join(tmp, name + ".toml"), text), key, reason, None)
             for name, text, key, reason in BAD_CASES]
    cases.append(("overlapping_particles", write_text(os.path.join(tmp, "overlap.toml"),
                                                      FILE_CASE.replace("{file}", overlap_file)),
                  "particles 1 and 2", "overlap", overlap_file))
    for name, path, key, reason, named_file in cases:
        for command in ("run", "check"):
            out_dir = os.path.join(tmp, "out_" + name)
            args = [command, path] + (["-o", out_dir] if command == "run" else [])
            status, _, err = run(exe, *args)
            where = f"{name}: `grainflow {command}`"
            check(status == 2, f"{where} exited {status}, expected 2 (stderr: {err.strip()})")
            check((named_file or path) in err, f"{where}: stderr does not name the file: {err.strip()}")
            check(key in err, f"{where}: stderr does not name the key {key}: {err.strip()}")
            # The reason follows the key (the folder and file names must not supply it).
            check(key in err and reason in err.split(key, 1)[1],
                  f"{where}: stderr lacks the reason '{reason}' after the key: {err.strip()}")
            check(not os.path.exists(out_dir), f"{where} created the output folder")


def check_sparse_huge_box(exe, tmp):
    # 1000 spheres in a 20-diameter corner of a periodic box 10^6 diameters wide: a grid of cells one
    # diameter wide would need 2048^3 cells (the per-axis cap), 34 GB of cell heads; the engine widens
    # its cells instead (at most 32768 here) and runs, every collision found (energy conserved).
    out = os.path.join(tmp, "sparse")
    status, _, err = run(exe, "run", "cases/bench/hard_spheres.toml", "-o", out, "--quiet", "--set",
                         "species.0.count=1000", "--set", "domain.hi=[1.0e6,1.0e6,1.0e6]", "--set",
                         "particles.lattice_spacing=1.2", "--set", "particles.region_hi=[20.0,20.0,20.0]",
                         "--set", "run.duration=1.0")
    if not check(status == 0, f"sparse huge box: exited {status}: {err.strip()}"):
        return
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    check(summary["collisions"] > 500, f"sparse huge box: {summary['collisions']} collisions")
    check(summary["peak_memory_bytes"] < 500e6, f"sparse huge box: peak memory {summary['peak_memory_bytes']} bytes")


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    check(os.access(exe, os.X_OK), f"{exe} is not an executable")
    os.chdir(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))  # the repo root
    with tempfile.TemporaryDirectory(prefix="grainflow_edmd_") as tmp:
        check_chute(exe, tmp)
        check_run_in_collisions(exe, tmp)
        check_campbell_protocol(exe, tmp)
        check_average_window_in_collisions(exe, tmp)
        check_hard_disc_pressure(exe, tmp)
        check_bad_inputs(exe, tmp)
        check_sparse_huge_box(exe, tmp)
    return finish("test_edmd_cli")


if __name__ == "__main__":
    sys.exit(main())
