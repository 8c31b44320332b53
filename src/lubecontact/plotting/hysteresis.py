"""Curves swept speeding up and slowing down (studies/hysteresis_cases.py): where a contact
has two steady states, the two branches side by side (docs/physics.md section 23).

Library code: matplotlib's object API, no files read.
"""

from __future__ import annotations

from collections.abc import Sequence

import xarray as xr
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from lubecontact.plotting.figures import NOT_CONVERGED_STYLE, axis_label, curve_colours
from lubecontact.plotting.transient import wrapped

# each direction of a sweep (studies/sweep.DIRECTIONS): its line style and its words in the legend
WAYS = {"up": ("-", "speeding up"), "down": ("--", "slowing down")}
# a point the sweep solved cold because the state continued from its neighbour did not converge
COLD_RESTART_STYLE = {"marker": "o", "markersize": 9, "markerfacecolor": "none", "linestyle": "none"}
# the panels: variable -> its axis label in words (None: its long_name and units)
PANELS = {"contact_resistance": None, "fluid_load_fraction": "fluid share of the load F_fluid/F (\u2013)"}
# the resistance axis ends this many times above the highest closed contact's resistance: an
# open circuit's (up to 1e77 ohm on Fig. 8) would flatten the branches into one line
OPEN_HEADROOM = 100.0


def hysteresis_figure(curves: Sequence[tuple[str, xr.Dataset]], title: str) -> Figure:
    """Contact resistance (log, up to OPEN_HEADROOM times the highest closed contact's) and
    fluid load fraction against the sliding speed for each (label, Dataset along direction
    and speed) of ``curves``: one colour a curve, solid speeding up, dashed slowing down, a
    red cross where a point did not converge, a ring where the sweep solved it cold
    (``cold_restart``: the branch it followed ended there)."""
    fig = Figure(figsize=(12, 5), layout="constrained")
    axes = fig.subplots(1, 2)
    handles = []
    for colour, (label, ds) in zip(curve_colours(len(curves)), curves):
        handles.append(Line2D([], [], color=colour, label=label))
        for way, (style, _) in WAYS.items():
            branch = ds.sel(direction=way)
            failed = branch["converged"].values != 1
            restarted = branch["cold_restart"].values == 1
            for ax, name in zip(axes, PANELS):
                ax.plot(branch["speed"].values, branch[name].values, linestyle=style, color=colour, marker=".")
                ax.plot(branch["speed"].values[failed], branch[name].values[failed], **NOT_CONVERGED_STYLE)
                ax.plot(branch["speed"].values[restarted], branch[name].values[restarted], color=colour,
                        **COLD_RESTART_STYLE)
    speed = curves[0][1]["speed"]
    for ax, (name, label) in zip(axes, PANELS.items()):
        data = curves[0][1][name]
        ax.set_xscale("log")
        ax.set_xlabel(axis_label(speed.attrs["long_name"], speed.attrs["units"]))
        ax.set_ylabel(label or axis_label(data.attrs["long_name"], data.attrs["units"]))
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_yscale("log")
    closed = [float(ds["contact_resistance"].where(ds["open_circuit"] != 1).max()) for _, ds in curves]
    closed = [r for r in closed if r > 0.0]  # NaN: every point of that curve open
    if closed and any(int(ds["open_circuit"].max()) == 1 for _, ds in curves):
        axes[0].set_ylim(top=OPEN_HEADROOM * max(closed))
        axes[0].set_title("above: open circuits, off the axis", fontsize="small")
    axes[1].set_ylim(0.0, 1.0)
    handles += [Line2D([], [], color="black", linestyle=style, label=words) for style, words in WAYS.values()]
    handles.append(Line2D([], [], label="did not converge", **NOT_CONVERGED_STYLE))
    handles.append(Line2D([], [], color="black", label="solved cold: the branch followed ended", **COLD_RESTART_STYLE))
    axes[1].legend(handles=handles, loc="upper left", fontsize="small")
    fig.suptitle(wrapped(title))
    return fig
