#!/usr/bin/python3
"""A silo discharging, kept full, on a short, small version of cases/geometry/silo_beverloo.toml
(COUNT spheres of d = 1, density 1, g = 1, orifice D = 6 d, DURATION time units):

- discharge.csv: its units line, one row per output time for the one outlet, `removed` never
  decreasing and `removed_mass` = removed x pi/6 (each sphere's mass) to the printed digits;
- the particle count stays COUNT (each discharged sphere goes back in at the top: summary.json's
  particles plus those still waiting is COUNT, and discharged is what discharge.csv ends with);
- summary.json's discharge_rate is measured (with its window), its error below 15 % of it;
- summary.json's bulk_solids_fraction, measured in the outlet's bed box (10 x 10 x 4 d, 2 d above
  the floor, below the ~8 d deep bed's surface) over the discharge window: between 0.5 and 0.66
  (a flowing bed of frictional spheres, below random close packing) and within 0.05 of the final
  state's in a cylinder r < 7 over the same heights;
- the rate against Beverloo's law: with that bulk density rho_b and k = 1.5 (the middle of the published 1.3 - 1.6), C = W / (rho_b sqrt(g)
  (D - k d)^2.5) must lie in [0.45, 0.85]: the published 0.55 - 0.65 (Beverloo 1961; Nedderman
  1992), widened by k's range (+-8 % on (D - k d)^2.5 at D = 6) and this short run's error
  (~10 %). A rate off by a factor (an orifice of the wrong size, particles removed twice) falls
  outside.
- `grainflow plot` draws discharge.png;
- an orifice of 2.2 d clogs (an arch of a few grains, To et al. 2001): the run stops by itself
  once no grain has left for run.clog_time (the default, 50 sqrt(d / g)), well before its end,
  with summary.json's clogged = true, clogged_at and a warning, and exits 0 with its outputs.

Usage: /usr/bin/python3 tests/integration/test_silo_discharge.py PATH_TO_grainflow  (from the repo root)
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, read_csv, run  # noqa: E402

CASE = "cases/geometry/silo_beverloo.toml"
COUNT = 3000
DURATION = 40.0
D = 6.0
K = 1.5


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    with tempfile.TemporaryDirectory(prefix="grainflow_silo_") as tmp:
        out = os.path.join(tmp, "silo")
        status, _, err = run(exe, "run", CASE, "-o", out, "--quiet", "--set", f"run.duration={DURATION}",
                             "--set", f"species.0.count={COUNT}", "--set", "particles.region_hi=[10,10,25]",
                             "--set", f"geometry.1.hole_radius={D / 2}", "--set", "output.snapshot_interval=0",
                             "--set", "outlet.0.bed_lo=[-5,-5,2]", "--set", "outlet.0.bed_hi=[5,5,6]")
        if not check(status == 0, f"silo: exited {status}: {err.strip()}"):
            return finish("test_silo_discharge")
        with open(os.path.join(out, "discharge.csv")) as f:
            check(f.readline().startswith("# units:"), "discharge.csv: no '# units:' line first")
        rows = read_csv(os.path.join(out, "discharge.csv"))
        series = read_csv(os.path.join(out, "timeseries.csv"))
        check([r["time"] for r in rows] == [r["time"] for r in series],
              "discharge.csv: not one row at each of timeseries.csv's times")
        check(all(r["outlet"] == "orifice" for r in rows), "discharge.csv: a row not of the outlet 'orifice'")
        removed = [int(r["removed"]) for r in rows]
        check(all(b >= a for a, b in zip(removed, removed[1:])), "discharge.csv: removed decreases")
        mass = math.pi / 6.0
        for r in rows:
            check(abs(float(r["removed_mass"]) - int(r["removed"]) * mass) <= 1e-9 * max(1.0, float(r["removed_mass"])),
                  f"discharge.csv, t = {r['time']}: removed_mass {r['removed_mass']} is not {r['removed']} x pi/6")
        summary = json.load(open(os.path.join(out, "summary.json")))
        check(summary.get("discharged") == removed[-1], f"summary discharged {summary.get('discharged')}, csv {removed[-1]}")
        final = read_csv(os.path.join(out, "final_state.csv"))
        check(COUNT - 200 <= len(final) <= COUNT, f"{len(final)} particles at the end, {COUNT} sent round")
        if not check("discharge_rate" in summary, f"no discharge_rate in summary.json: {sorted(summary)}"):
            return finish("test_silo_discharge")
        rate, error = summary["discharge_rate"], summary["discharge_rate_error"]
        print(f"discharge rate {rate:.4g} +- {error:.2g} over [{summary['discharge_window_start']}, "
              f"{summary['discharge_window_end']}], {removed[-1]} discharged")
        check(0.0 < error < 0.15 * rate, f"discharge rate {rate} +- {error}: error not below 15 %")
        bed = [r for r in final if 2.0 < float(r["z"]) < 6.0 and math.hypot(float(r["x"]), float(r["y"])) < 7.0]
        at_end = len(bed) * mass / (math.pi * 49.0 * 4.0)
        rho_b = summary.get("bulk_solids_fraction", 0.0)  # density 1: the bulk density
        # The bed's mean over the window against the final state's in a wider cylinder: a flowing
        # bed's solids fraction varies by ~0.02 from place to place and time to time.
        check(0.5 < rho_b < 0.66 and abs(rho_b - at_end) < 0.05,
              f"bulk solids fraction {rho_b} (the final state's: {at_end:.3f})")
        C = rate / (rho_b * (D - K) ** 2.5)
        print(f"bulk density {rho_b:.3f}, Beverloo C = {C:.3f} (k = {K})")
        check(0.45 <= C <= 0.85, f"Beverloo C = {C:.3f} outside [0.45, 0.85]")
        status, _, err = run(exe, "plot", out)
        png = os.path.join(out, "discharge.png")
        check(status == 0 and os.path.isfile(png) and open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n",
              f"grainflow plot: no discharge.png ({status}: {err.strip()[-300:]})")

        out = os.path.join(tmp, "clog")
        status, _, err = run(exe, "run", CASE, "-o", out, "--quiet", "--set", "run.duration=400",
                             "--set", "species.0.count=1000", "--set", "particles.region_hi=[10,10,25]",
                             "--set", "geometry.1.hole_radius=1.1", "--set", "output.snapshot_interval=0")
        if check(status == 0, f"clogging silo: exited {status}: {err.strip()}"):
            summary = json.load(open(os.path.join(out, "summary.json")))
            last = float(read_csv(os.path.join(out, "timeseries.csv"))[-1]["time"])
            check(summary.get("clogged") is True, f"clogging silo: clogged = {summary.get('clogged')}")
            check(last < 300.0 and abs(summary.get("clogged_at", -1.0) - last) < 1e-9,
                  f"clogging silo: ran to t = {last}, clogged_at {summary.get('clogged_at')}")
            check(any("clogged" in w for w in summary.get("warnings", [])), "clogging silo: no warning")
    return finish("test_silo_discharge")


if __name__ == "__main__":
    sys.exit(main())
