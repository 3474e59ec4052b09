"""Campbell's (1982) constitutive functions against the solids fraction, over strips and runs.

constitutive_table.csv (`grainflow constitutive`; only its runs averaged once steady), else one
run's constitutive.csv ->
  constitutive_chi.png (Fig. 3.5): chi(nu) = P_yy / (rho_p sum <u_i'^2>) of every usable strip, one
      colour per study with its error bar (below: chi_local, with the fluctuations about the
      instantaneous strip mean, free of a small bed's collective surging), beside the elastic gas's nu Z(nu) / D (Henderson's discs,
      Carnahan-Starling's spheres), Campbell's limits drawn as lines: chi -> 0 as nu -> 0, singular
      at large nu (discs cannot exceed the triangular packing 0.907; layers stop sliding past
      pi / (sqrt 3 + 2 pi / 3) = 0.821).
  constitutive_f.png (Figs. 3.21-3.24): f_s(nu) and f_N(nu) of the strips with a resolved shear
      rate, against nu (discs) and against the equivalent 3D solids fraction nu_3D = 4/(3 sqrt pi)
      nu^(3/2) (spheres' own nu), with the limits above and nu_3D = pi / 6, the cubic packing beyond
      which, Campbell argues, Bagnold's and Savage's materials could not have sheared. The thesis's
      experimental points (its Figs. 3.23-3.24) are not in its text: it says only that the
      simulation lies above them. Drawn only when some strip has a resolved shear rate.
"""

import csv

import matplotlib.pyplot as plt
import numpy as np

from .common import PlotError, error_bars, existing, read_table, save_atomically

DISC_TRIANGULAR = 0.9068996821171089   # pi / (2 sqrt 3)
DISC_CONTOUR_SHEAR = 0.8210210538742287  # pi / (sqrt 3 + 2 pi / 3)
SPHERE_CUBIC = 0.5235987755982988      # pi / 6
REQUIRED = ["dimension", "solids_fraction", "solids_fraction_3d", "chi", "chi_error", "f_s", "f_s_error", "f_n",
            "f_n_error", "usable_chi", "usable_f"]


def plot(outdir, info):
    path = existing(outdir, "constitutive_table.csv") or existing(outdir, "constitutive.csv")
    if not path:
        return []
    table = read_table(path, REQUIRED, text_columns=("run",))
    runs = run_labels(path, len(table))
    if "steady" in table:  # a collected table: only runs averaged once steady (Campbell's Fig. 3.5 used converged flows)
        for key in ("usable_chi", "usable_f"):
            table.columns[key] = np.where(table["steady"] == 1, table[key], 0)
    if not np.any(table["usable_chi"] == 1):
        raise PlotError(f"{path}: no strip is usable for chi (usable_chi = 1 in a steady run)")
    written = [plot_chi(outdir, table, runs)]
    if np.any(table["usable_f"] == 1):  # none in a gas at rest: f needs a resolved shear rate
        written.append(plot_f(outdir, table, runs))
    return written


def run_labels(path, rows):
    """The table's run column (one label for a single run's file)."""
    with open(path, newline="") as handle:
        reader = csv.reader(line for line in handle if line.strip() and not line.startswith("#"))
        header = next(reader)
        if "run" not in header:
            return ["this run"] * rows
        column = header.index("run")
        labels = [row[column] for row in reader]
    if len(labels) != rows:
        raise PlotError(f"{path}: {len(labels)} run labels for {rows} rows")
    return labels


def elastic_chi(nu, dimension):
    if dimension == 2:
        return nu * (1 + nu * nu / 8) / (1 - nu) ** 2 / 2
    return nu * (1 + nu + nu * nu - nu ** 3) / (1 - nu) ** 3 / 3


def study_of(label):
    """A run's study: the first part of its folder (a sweep's runs share it)."""
    return label.split("/")[0]


def by_study(runs, mask):
    """[(study, index array)] of the rows in `mask`, one entry per study in first-seen order."""
    studies = np.asarray([study_of(label) for label in runs])
    order = []
    for study, keep in zip(studies, mask):
        if keep and study not in order:
            order.append(study)
    return [(study, np.nonzero(mask & (studies == study))[0]) for study in order]


def scatter_runs(axis, table, runs, mask, x_key, y_key, error_key):
    """One colour and marker per study, the same in every panel (numbered over the whole table);
    returns how many runs the points come from."""
    styles = ["o", "s", "^", "v", "D", "<", ">", "p", "h", "*"]
    numbers = {study: k for k, (study, _) in enumerate(by_study(runs, np.ones(len(runs), dtype=bool)))}
    for study, rows in by_study(runs, mask):
        number = numbers[study]
        errors = error_bars(table[error_key][rows])
        axis.errorbar(table[x_key][rows], table[y_key][rows], yerr=errors, fmt=styles[number % len(styles)], ms=4,
                      capsize=2, color=f"C{number % 10}", label=study)
    return len({label for label, keep in zip(runs, mask) if keep})


def limit_lines(axis, three_d_axis=False):
    if three_d_axis:
        axis.axvline(SPHERE_CUBIC, color="0.4", ls=":", label="pi/6 (cubic packing)")
    else:
        axis.axvline(DISC_CONTOUR_SHEAR, color="0.4", ls="--", label="0.821 (layers lock)")
        axis.axvline(DISC_TRIANGULAR, color="0.4", ls=":", label="0.907 (triangular packing)")


def plot_chi(outdir, table, runs):
    usable = table["usable_chi"] == 1
    dimensions = [d for d in (2, 3) if np.any(usable & (table["dimension"] == d))]
    rows = [("chi", "chi = p / (rho_p sum <u_i'^2>)", "time-mean fluctuations (Campbell)")]
    if "chi_local" in table:
        rows.append(("chi_local", "chi with D T_Lan", "fluctuations about the instantaneous strip mean"))
    figure, axes = plt.subplots(len(rows), len(dimensions), figsize=(6.4 * len(dimensions), 4.8 * len(rows)),
                                squeeze=False)
    for row, (key, ylabel, what) in enumerate(rows):
        for axis, dim in zip(axes[row], dimensions):
            mask = usable & (table["dimension"] == dim) & (table[key] > 0)
            count = scatter_runs(axis, table, runs, mask, "solids_fraction", key, key + "_error")
            upper = 0.88 if dim == 2 else 0.6
            nu = np.linspace(0.005, upper, 200)
            axis.plot(nu, elastic_chi(nu, dim), "k-", lw=1,
                      label="elastic gas, " + ("Henderson" if dim == 2 else "Carnahan-Starling"))
            if dim == 2:
                limit_lines(axis)
            axis.set_yscale("log")
            axis.set_xlim(0, 0.95 if dim == 2 else 0.7)
            axis.set_xlabel("solids fraction nu" + (" (discs)" if dim == 2 else " (spheres)"))
            axis.set_ylabel(ylabel)
            axis.set_title(f"{what}: {int(np.count_nonzero(mask))} strips of {count} runs", fontsize=9)
            axis.legend(fontsize=6, loc="upper left")
    figure.suptitle("Campbell 1982 Fig. 3.5: chi -> 0 as nu -> 0, singular at large nu")
    figure.tight_layout()
    return save_atomically(figure, f"{outdir}/constitutive_chi.png")


def plot_f(outdir, table, runs):
    usable = table["usable_f"] == 1
    figure, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    discs = usable & (table["dimension"] == 2)
    for row, (key, name) in enumerate((("f_s", "f_s(nu) = tau_s / (rho_p R^2 (du/dy)^2)"),
                                       ("f_n", "f_N(nu) = tau_N / (rho_p R^2 (du/dy)^2)"))):
        axis = axes[row][0]
        mask = discs & (table[key] > 0)
        scatter_runs(axis, table, runs, mask, "solids_fraction", key, key + "_error")
        limit_lines(axis)
        axis.set_xlim(0, 0.95)
        axis.set_xlabel("solids fraction nu (discs)")
        axis.set_title(f"{key}: {int(np.count_nonzero(mask))} disc strips (Figs. 3.21-3.22)")
        axis = axes[row][1]
        mask = usable & (table[key] > 0)
        scatter_runs(axis, table, runs, mask, "solids_fraction_3d", key, key + "_error")
        limit_lines(axis, three_d_axis=True)
        axis.set_xlim(0, 0.7)
        axis.set_xlabel("equivalent 3D solids fraction nu_3D (spheres: their nu)")
        axis.set_title(f"{key} against nu_3D (Figs. 3.23-3.24)")
        for axis in axes[row]:
            axis.set_yscale("log")
            axis.set_ylabel(name)
            axis.legend(fontsize=6, loc="upper left")
    figure.suptitle("Bagnold/Savage functions: -> 0 as nu -> 0, -> infinity as nu -> 0.821 (Campbell 1982 3.3.1)")
    figure.tight_layout()
    return save_atomically(figure, f"{outdir}/constitutive_f.png")
