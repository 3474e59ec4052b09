"""The figures of `grainflow plot DIR` (tools/plot_run.py), after the appendix of Lan (1994).

One module per family of figures; each has plot(outdir, info) -> [paths of the PNGs written]
(convection: plot_mean and plot_phase_bins, for its two inputs) and draws only from the inputs that
exist in the folder:

  profiles     profiles.png, mass_below.png               (Figs. A4.1-A4.4, A4.7, A4.9, A4.15, A4.18-19)
  timeseries   timeseries.png                             (approach to the steady state)
  diffusion    vacf.png, msd.png                          (Figs. A4.16-A4.22, A4.25-A4.27)
  zone_waves   zone_spectra.png, floor_correlation.png    (Figs. A4.13, A4.14)
  convection   convection.png, convection_columns.png    (Figs. A5.1-A5.9)
               convection_phases.png                      (Fig. A5.11)
  tracers      tracer_height.png, tracer_spectrum.png, tracer_coordination.png  (Figs. A5.12-A5.17)
  snapshots    snapshots_phases.png                       (Figs. A4.10, A5.10)
  sweep        sweep_*.png of a `grainflow sweep` folder  (Figs. A4.4-A4.9, A4.11, A4.12, A4.23, A4.24)
  silo         discharge.png of a run with [[outlet]]s; silo_beverloo.png of a sweep over orifices

and of an event-driven run, after Campbell (1982) Chapter 3:

  strips       strip_profiles.png, temperature_components.png  (Figs. 3.1, 3.10-3.16, 3.18-3.19)
  stresses     stresses.png, collision_angles.png         (section 3.3, Figs. 3.32-3.34)
  distributions  velocity_distributions.png, pair_distributions.png  (Figs. 3.25-3.29, 3.35-3.39)
  constitutive   constitutive_chi.png, constitutive_f.png of constitutive.csv or of the table
                 `grainflow constitutive` collects over runs   (Figs. 3.5, 3.21-3.24)
  animation    animation.mp4 (ffmpeg) or .gif (pillow) of snapshots/   (the film of section 2.15)

A malformed input stops only the figures drawn from it (one plotter): the others are still drawn,
and plot_folder returns the problems, each naming its file.
"""

import os

from . import (animation, constitutive, convection, diffusion, distributions, profiles, silo, snapshots, stresses, strips,
               sweep, timeseries, tracers, zone_waves)
from .common import PlotError, RunInfo, existing, read_json

PLOTTERS = [profiles.plot, timeseries.plot, diffusion.plot, zone_waves.plot, convection.plot_mean,
            convection.plot_phase_bins, tracers.plot, snapshots.plot, sweep.plot, strips.plot, stresses.plot,
            distributions.plot, constitutive.plot, silo.plot, animation.plot]

# What makes a folder plottable at all (for the message when nothing is there).
INPUTS = ["profiles.csv", "timeseries.csv", "analysis/vacf.csv", "analysis/msd.csv",
          "analysis/zone_spectra.csv", "analysis/floor_correlation.csv", "convection.csv",
          "convection_phases.csv", "tracers.csv", "snapshots/", "sweep.csv", "stresses.csv",
          "collision_angles.csv", "analysis/velocity_distributions.csv", "analysis/pair_distributions.csv", "constitutive.csv",
          "constitutive_table.csv", "discharge.csv"]


def plot_folder(outdir):
    """Draws every figure whose inputs exist in `outdir`. Returns (PNG paths written, problems)."""
    if not os.path.isdir(outdir):
        raise PlotError(f"{outdir}: no such folder")
    problems = []
    summary = {}
    summary_path = existing(outdir, "summary.json")
    if summary_path:
        try:
            summary = read_json(summary_path)
        except PlotError as error:
            problems.append(str(error))
    info = RunInfo(outdir, summary)
    written = []
    for plotter in PLOTTERS:
        try:
            written += plotter(outdir, info)
        except PlotError as error:
            problems.append(str(error))
    return written, problems
