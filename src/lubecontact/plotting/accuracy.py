"""The accuracy-cost figures: error of each quantity against the mesh-converged value
versus solve time, one panel per quantity, one line per speed (studies/accuracy.py), and
the transient's: a reconnect time on a ladder of meshes and of time-step tolerances
(studies/transient_accuracy.py).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from lubecontact.studies.accuracy import QUANTITIES

REGIME_MARKERS = {"boundary": "s", "mixed": "o", "full film": "^"}


def plot_accuracy_cost(table: xr.Dataset):
    """Figure ``accuracy_cost``: relative error against solve time, one panel per quantity,
    one line per speed (regime), each point labelled with its mesh (nodes a side)."""
    quantities = table.attrs["quantities"].split(",")
    fig = Figure(figsize=(4.6 * len(quantities) + 0.8, 4.4), layout="constrained")
    axes = fig.subplots(1, len(quantities), squeeze=False)[0]
    cmap = colormaps["viridis"]
    speeds = table["speed"].values
    for ax, q in zip(axes, quantities):
        for i, speed in enumerate(speeds):
            error = table[f"{q}_error"].values[i]
            times = table["solve_time"].values[i]
            keep = np.isfinite(error) & (error > 0.0)
            colour = cmap(0.85 * i / max(len(speeds) - 1, 1))
            label = f"U = {speed:g} m/s ({table['regime'].values[i]})"
            ax.plot(times[keep], error[keep], marker=REGIME_MARKERS[str(table["regime"].values[i])], markersize=4,
                    color=colour, label=label)
            for n, t, e in zip(table["mesh"].values[keep], times[keep], error[keep]):
                ax.annotate(f"{n}", (t, e), textcoords="offset points", xytext=(3, 3), fontsize=6, color=colour)
        ax.axhline(0.01, color="0.5", linestyle=":", linewidth=0.8)
        ax.annotate("1 %", (0.0, 0.01), xycoords=("axes fraction", "data"), xytext=(2, 2),
                    textcoords="offset points", fontsize=7, color="0.4")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("solve time (s)")
        ax.set_ylabel(f"relative error of the {QUANTITIES[q].label} (\u2013)")
        ax.set_title(QUANTITIES[q].label, fontsize="medium")
        ax.grid(True, which="major", alpha=0.3)
    axes[-1].legend(fontsize="small", title="points: nodes a side (n \u00d7 n)", title_fontsize="small")
    fig.suptitle("What accuracy costs: error against the Richardson-extrapolated value vs wall time of one solve",
                 fontsize="medium")
    return fig


def plot_transient_accuracy(table: xr.Dataset, title: str):
    """Figure ``transient_accuracy`` (studies/transient_accuracy.py): (a) the reconnect time
    on each mesh of the ladder with its Richardson extrapolation and the grid convergence
    index as a band; (b) the relative error of every ladder member (meshes, tolerances,
    refinements of the mesh at rest) against its ladder's extrapolation versus the wall time of its run, the 5 % and 1 %
    levels dotted. A ladder without extrapolation (a run that did not converge or never
    reconnected) shows its reconnect times only."""
    fig = Figure(figsize=(10.0, 4.4), layout="constrained")
    left, right = fig.subplots(1, 2)
    styles = {"mesh": ("C0", "o", "meshes (nodes along the sliding direction)"), "tolerance": ("C1", "s", "time-step tolerance"),
              "rest_refinement": ("C2", "^", "mesh at rest, times finer along the sliding direction")}
    if "mesh" in table.coords:
        nodes, times = table["mesh"].values, table["mesh_reconnect_time"].values * 1e3
        left.plot(nodes, times, "o-", color="C0", label="reconnect time on the mesh")
        extrapolated = float(table["mesh_extrapolated"]) * 1e3
        if np.isfinite(extrapolated):
            band = float(table["mesh_gci"]) * times[-1]
            left.axhline(extrapolated, color="0.3", linestyle="--", linewidth=1.0,
                         label=f"extrapolated: {extrapolated:.3g} ms (order {float(table['mesh_order']):.2f})")
            left.axhspan(extrapolated - band, extrapolated + band, color="0.85", label="\u00b1 grid convergence index")
        left.set_xlabel("nodes along the sliding direction")
        left.set_ylabel("reconnect time (ms)")
        left.legend(fontsize="small")
        left.grid(True, alpha=0.3)
    for part, (colour, marker, label) in styles.items():
        if part not in table.coords:
            continue
        error, run_time = table[f"{part}_error"].values, table[f"{part}_run_time"].values
        keep = np.isfinite(error) & (error > 0.0)
        right.plot(run_time[keep], error[keep], marker=marker, color=colour, label=label)
        for value, t, e in zip(table[part].values[keep], run_time[keep], error[keep]):
            right.annotate(f"{value:g}", (t, e), textcoords="offset points", xytext=(3, 3), fontsize=7, color=colour)
    for level, text in ((0.05, "5 %"), (0.01, "1 %")):
        right.axhline(level, color="0.5", linestyle=":", linewidth=0.8)
        right.annotate(text, (0.0, level), xycoords=("axes fraction", "data"), xytext=(2, 2),
                       textcoords="offset points", fontsize=7, color="0.4")
    right.set_xscale("log")
    right.set_yscale("log")
    right.xaxis.set_minor_formatter(NullFormatter())  # within a decade the labels overlap
    right.set_xlabel("wall time of the run (s)")
    right.set_ylabel("relative error of the reconnect time (\u2013)")
    right.legend(fontsize="small", title="points: nodes, tolerance, or refinement", title_fontsize="small")
    right.grid(True, which="major", alpha=0.3)
    fig.suptitle(title, fontsize="medium")
    return fig
