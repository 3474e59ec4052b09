#!/usr/bin/python3
"""PNG figures of a grainflow run folder or sweep folder, after the appendix of Lan (1994).

Usage: /usr/bin/python3 tools/plot_run.py DIR     (what `grainflow plot DIR` runs)

Draws every figure whose inputs exist in DIR and skips the others without a word: depth profiles
and mass below a depth (profiles.csv), time series (timeseries.csv), velocity autocorrelation and
mean-square displacement (analysis/vacf.csv, msd.csv), zone spectra and floor correlations
(analysis/zone_spectra.csv, floor_correlation.csv), convection fields (convection.csv,
convection_phases.csv), tracer histories (tracers.csv), projected snapshots at eight floor phases
(snapshots/), and for a sweep folder (sweep.csv) the runs' results against Gamma or the varied key;
for an event-driven run Campbell's (1982) figures: strip profiles, temperature components, stresses,
collision angles, velocity and pair distributions, and a film of the snapshots.
docs/OUTPUTS.md lists each figure with its Lan or Campbell figure; the modules are in
tools/grainflow_plots/.

Each PNG is written under a temporary name in DIR and renamed into place. Needs Debian's
python3-matplotlib and python3-numpy (python3-h5py for the zone histories and correlation curves).
Exit status 1 when DIR is missing, holds nothing to plot, or an input is malformed (the message
names the file; the figures of the other inputs are still written).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from grainflow_plots import INPUTS, plot_folder  # noqa: E402
from grainflow_plots.common import PlotError  # noqa: E402


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print("usage: plot_run.py DIR   (the output folder of `grainflow run` or `grainflow sweep`)", file=sys.stderr)
        return 1
    outdir = argv[1]
    written, problems = plot_folder(outdir)
    for problem in problems:
        print(f"plot_run: {problem}", file=sys.stderr)
    if written:
        print(f"plot_run: wrote {', '.join(os.path.basename(path) for path in written)} in {outdir}")
    elif not problems:
        raise PlotError(f"{outdir}: nothing to plot (none of {', '.join(INPUTS)})")
    return 1 if problems else 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except PlotError as error:
        print(f"plot_run: {error}", file=sys.stderr)
        sys.exit(1)
