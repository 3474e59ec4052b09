"""Velocity and pair distributions of an event-driven run (Campbell 1982 sections 3.4.1, 3.4.3),
from `grainflow analyze`'s files.

analysis/velocity_distributions.csv [+ distributions.json] -> velocity_distributions.png
    (Figs. 3.25-3.29): one panel per variable X_i (P1-P5; 3D to P6): the measured density as points,
    the least-squares generalized Maxwellian (solid) and the Maxwellian a = k/2 (dashed), with
    a_i / a_mi +- error and the components of X_i from distributions.json in the panel's legend.
analysis/pair_distributions.csv [+ distributions.json] -> pair_distributions.png (Figs. 3.35-3.39):
    the normal and the parallel (Campbell's forward periodic distance) number densities against
    r/R on [0, 8R], with error bars, and the cell's number density n as a horizontal line.
"""

import os

import matplotlib.pyplot as plt
import numpy as np

from .common import error_bars, existing, number, read_json, read_table, save_atomically


def plot(outdir, info):
    written = []
    meta_path = existing(outdir, "analysis", "distributions.json")
    meta = read_json(meta_path) if meta_path else {}
    path = existing(outdir, "analysis", "velocity_distributions.csv")
    if path:
        table = read_table(path, ["x", "p1", "p1_fit", "p1_maxwell"])
        written.append(plot_velocity(outdir, info, table, meta))
    path = existing(outdir, "analysis", "pair_distributions.csv")
    if path:
        table = read_table(path, ["r", "normal", "parallel", "number_density"])
        written.append(plot_pairs(outdir, info, table, meta))
    return written


def variables(table):
    """The indices k with a p<k> column, ascending."""
    found = []
    k = 1
    while f"p{k}" in table:
        found.append(k)
        k += 1
    return found


def legend_text(meta, k):
    components = meta.get(f"a{k}_components")
    ratio, error = number(meta, f"a{k}_ratio"), number(meta, f"a{k}_ratio_error")
    head = f"X{k} = ({components})" if isinstance(components, str) else f"X{k}"
    if ratio is None:
        return head
    return head + f"\na/a_m = {ratio:.3f}" + (f" \u00b1 {error:.3f}" if error is not None else "")


def plot_velocity(outdir, info, table, meta):
    ks = variables(table)
    ncols = 3
    nrows = (len(ks) + ncols - 1) // ncols
    figure, axes = plt.subplots(nrows, ncols, figsize=(12.0, 3.8 * nrows), squeeze=False)
    x = table["x"]
    for index, k in enumerate(ks):
        a = axes[index // ncols, index % ncols]
        a.plot(x, table[f"p{k}"], linestyle="none", marker="o", markersize=3, color="C0", label="measured")
        if f"p{k}_fit" in table:
            a.plot(x, table[f"p{k}_fit"], color="k", label="generalized Maxwellian")
        if f"p{k}_maxwell" in table:
            a.plot(x, table[f"p{k}_maxwell"], color="C3", linestyle="--", label="Maxwellian")
        a.set_title(f"P{k}", fontsize=9)
        a.set_xlim(0.0, float(x[-1]) + 0.05 if x.size else 5.0)
        a.set_ylim(bottom=0.0)
        a.set_xlabel(f"X{k}")
        a.grid(True, alpha=0.3)
        a.legend(loc="upper right", fontsize=7, title=legend_text(meta, k), title_fontsize=7)
    for index in range(len(ks), nrows * ncols):
        axes[index // ncols, index % ncols].set_visible(False)
    samples = meta.get("particle_samples")
    note = f" over {samples} particle samples" if isinstance(samples, int) else ""
    figure.suptitle(f"{info.name}\nvelocity distributions (Campbell 1982 Figs. 3.25-3.29){note}", fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "velocity_distributions.png"))


def radius(table, meta):
    """R: half distributions.json's diameter, else pair_range / 8, else the slices' end / 8 (the
    slices cover [0, 8R))."""
    diameter = number(meta, "diameter")
    if diameter:
        return 0.5 * diameter
    pair_range = number(meta, "pair_range")
    if pair_range:
        return pair_range / 8.0
    r = table["r"]
    if r.size >= 2:
        return float(r[-1] + 0.5 * (r[1] - r[0])) / 8.0
    return 1.0


def plot_pairs(outdir, info, table, meta):
    big_r = radius(table, meta)
    r = table["r"] / big_r
    n = table["number_density"]
    figure, axes = plt.subplots(1, 2, figsize=(11.0, 4.8))
    for a, name, title in ((axes[0], "normal", "normal: |\u0394y| = r"),
                           (axes[1], "parallel", "parallel: forward distance along the flow")):
        a.errorbar(r, table[name], yerr=error_bars(table.get(name + "_error")), color="C0", marker="o",
                   markersize=3, capsize=2, label="measured")
        finite = n[np.isfinite(n)]
        if finite.size:
            a.axhline(float(np.mean(finite)), color="k", linestyle="--", label=f"bulk n = {float(np.mean(finite)):.4g}")
        a.set_xlim(0.0, 8.0)
        a.set_ylim(bottom=0.0)
        a.set_xlabel("r / R")
        a.set_title(title, fontsize=9)
        a.grid(True, alpha=0.3)
        a.legend(loc="upper right", fontsize=8)
    dim = meta.get("dimension")
    for a in axes:
        a.set_ylabel("number density (1/m\u00b3)" if dim == 3 else "number density (1/m\u00b2)")
    figure.suptitle(f"{info.name}\npair distributions (Campbell 1982 Figs. 3.35-3.39), R = {big_r:.4g} m",
                    fontsize=10)
    figure.tight_layout()
    return save_atomically(figure, os.path.join(outdir, "pair_distributions.png"))
