#!/usr/bin/python3
"""The rotating drum's forms of motion over a sweep, and the convection profile of a vibrated
cylindrical bed.

Usage:
  /usr/bin/python3 tools/drum_analysis.py SWEEP_DIR [--radius R] [--gravity G] [--max-snapshots N]
      the folder of `grainflow sweep cases/geometry/rotating_drum.toml --vary ...angular_velocity=...`:
      each run's dynamic angle of repose and form of motion (Mellmann 2001) against
      Fr = omega^2 R / g, printed and written to SWEEP_DIR/drum_regimes.csv and drum_regimes.png.
      R and omega come from each run's resolved_case.toml (its [[geometry]] cylinder; omega else
      from the varied key); --radius and --gravity override the case files.
  /usr/bin/python3 tools/drum_analysis.py --convection RUN_DIR --radius R [--center X,Z]
      [--annuli N] [--exclude D] [--subtract-bed-motion]
      a vibrated bed in a cylinder of radius R whose axis is along y (through x, z = X, Z; 0, 0 by
      default): the mean vertical velocity in N equal-area annuli (8) over the later half of the
      run's snapshots, the top and bottom D diameters (3) of the bed left out; printed and written
      to RUN_DIR/convection_profile.csv.
  /usr/bin/python3 tools/drum_analysis.py --drift RUN_DIR --radius R [--start T] [--center X,Z]
      the same bed's convection from snapshots one drive period apart (output.snapshot_interval =
      1 / f, as cases/geometry/vibrated_cylinder.toml writes them): the grains' mean rise per period
      in the wall layer and four annuli inside it, from the snapshots at t >= T (default: the later
      half); printed and written to RUN_DIR/convection_drift.csv.

The criteria and their thresholds are in tools/grainflow_plots/drum.py. Needs Debian's
python3-numpy and python3-matplotlib. Exit status 1 when an input is missing or malformed, 2 for
a command line it does not take.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from grainflow_plots.common import PlotError  # noqa: E402
from grainflow_plots.drum import axial_convection_profile, axial_drift_profile  # noqa: E402
from grainflow_plots.snapshots import read_vtu, snapshot_list  # noqa: E402
from grainflow_plots.drum_sweep import COLUMNS, MAX_SNAPSHOTS, analyze_sweep, steady_snapshots  # noqa: E402


def parse(argv):
    parser = argparse.ArgumentParser(prog="drum_analysis.py", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", nargs="?", help="the sweep folder (SWEEP_DIR)")
    parser.add_argument("--convection", metavar="RUN_DIR", help="a vibrated cylindrical bed's run folder")
    parser.add_argument("--drift", metavar="RUN_DIR", help="a vibrated cylindrical bed's run folder (phase-locked)")
    parser.add_argument("--start", type=float, help="with --drift: the first snapshot's time (s)")
    parser.add_argument("--radius", type=float, help="the cylinder's radius (m); needed with --convection")
    parser.add_argument("--gravity", type=float, help="|g| (m/s^2), instead of the case file's")
    parser.add_argument("--max-snapshots", type=int, default=MAX_SNAPSHOTS,
                        help=f"snapshots read per run from its later half (default {MAX_SNAPSHOTS})")
    parser.add_argument("--center", default="0,0", help="the convection cylinder's axis: X,Z (default 0,0)")
    parser.add_argument("--annuli", type=int, default=8, help="equal-area annuli (default 8)")
    parser.add_argument("--exclude", type=float, default=3.0, help="diameters left out at the bed's top and bottom")
    parser.add_argument("--subtract-bed-motion", action="store_true",
                        help="remove each snapshot's mean vertical velocity of the bulk (the floor's motion)")
    options = parser.parse_args(argv)
    if (options.folder is not None) + (options.convection is not None) + (options.drift is not None) != 1:
        parser.error("give one of SWEEP_DIR, --convection RUN_DIR or --drift RUN_DIR")
    if (options.convection is not None or options.drift is not None) and options.radius is None:
        parser.error("--convection and --drift need --radius")
    return options


def sweep_table(options):
    rows, written = analyze_sweep(options.folder, radius=options.radius, gravity=options.gravity,
                                  max_snapshots=options.max_snapshots)
    shown = COLUMNS[:-1]  # the run's folder is long: last, alone
    print("  ".join(f"{name:>12.12}" for name in shown) + "  run")
    for row in rows:
        cells = [f"{row[c]:>12}" if isinstance(row[c], str) else f"{row[c]:>12.4g}" for c in shown]
        print("  ".join(cells) + f"  {row['run']}")
    print(f"drum_analysis: wrote {', '.join(written)}")


def convection(options):
    try:
        center = tuple(float(v) for v in options.center.split(","))
    except ValueError:
        center = ()
    if len(center) != 2:
        raise PlotError(f"--center '{options.center}': expected X,Z")
    snapshots = steady_snapshots(options.convection, max_snapshots=10 ** 9)
    if not snapshots:
        raise PlotError(f"{options.convection}: no snapshots (snapshots/particles_*.vtu)")
    r_mid, mean_vy, count = axial_convection_profile(snapshots, options.radius, center, options.annuli,
                                                     options.exclude, options.subtract_bed_motion)
    path = os.path.join(options.convection, "convection_profile.csv")
    lines = [f"# radial convection profile of {os.path.basename(os.path.normpath(options.convection))}: "
             f"{options.annuli} equal-area annuli of a cylinder of radius {options.radius:g} m (axis along y through "
             f"x, z = {center[0]:g}, {center[1]:g}), {len(snapshots)} snapshots (the later half), the top and bottom "
             f"{options.exclude:g} d left out" + ("; each snapshot's mean vy removed" if options.subtract_bed_motion
                                                  else ""),
             "# units: r_mid m, mean_vy m/s, count grain samples",
             "r_mid,mean_vy,count"]
    lines += [f"{r:.6g},{'nan' if math.isnan(v) else f'{v:.6g}'},{n}" for r, v, n in zip(r_mid, mean_vy, count)]
    write_table(path, lines)
    print("\n".join(lines[2:]))
    print(f"drum_analysis: wrote {path}")


def write_table(path, lines):
    """`lines` to `path` through a temporary file, so that a failure leaves no half-written table."""
    temporary = f"{path}.tmp-{os.getpid()}"
    try:
        with open(temporary, "w") as handle:
            handle.write("\n".join(lines) + "\n")
        os.replace(temporary, path)
    except OSError as error:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise PlotError(f"cannot write {path}: {error.strerror}") from error


def drift(options):
    center = tuple(float(v) for v in options.center.split(","))
    series = snapshot_list(os.path.join(options.drift, "snapshots"))
    chosen = [s for s in series if s[0] is not None and s[0] >= options.start] if options.start is not None \
        else series[len(series) // 2:]
    if len(chosen) < 2:
        raise PlotError(f"{options.drift}: fewer than two snapshots to compare")
    edges, mean, error, pairs = axial_drift_profile([read_vtu(path) for _, path in chosen], options.radius, center)
    lines = [f"# convection of {os.path.basename(os.path.normpath(options.drift))}: mean vertical displacement per "
             f"snapshot interval (one drive period) of the bulk's grains by radius, {pairs} pairs of snapshots "
             f"from t = {chosen[0][0]:g}; the last annulus is the wall layer",
             "# units: r_from m, r_to m, dy_per_period m, standard_error m",
             "r_from,r_to,dy_per_period,standard_error"]
    lines += [f"{a:.6g},{b:.6g},{m:.6g},{e:.3g}" for a, b, m, e in zip(edges[:-1], edges[1:], mean, error)]
    path = os.path.join(options.drift, "convection_drift.csv")
    write_table(path, lines)
    print("\n".join(lines[2:]))
    print(f"drum_analysis: wrote {path}")


def main(argv):
    options = parse(argv[1:])
    if options.drift is not None:
        drift(options)
    elif options.convection is not None:
        convection(options)
    else:
        sweep_table(options)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except PlotError as error:
        print(f"drum_analysis: {error}", file=sys.stderr)
        sys.exit(1)
