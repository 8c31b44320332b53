"""The transient figures, drawn from case files (lubecontact.transient Datasets).

(a) ``stop_figure``: contact resistance and minimum film thickness against time (log axis,
time after the motion stops) for several variants of one contact; the resting resistance
times the reconnect factor as a dotted line, the reconnect time as a marker.
(b) ``reconnect_figure``: reconnect time (log) against a swept parameter (log, or linear for a
temperature), one line per
series value; a run that never reconnected within its duration is drawn as a triangle on
the top edge, one already reconnected when the block stopped (reconnect_time = 0) as a
triangle on the bottom edge, a run that did not converge as a red cross.
(c) ``vibration_figure``: speed and resistance over the cycles with the open threshold.
Library code: matplotlib's object API, no files read.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import yaml
from matplotlib.figure import Figure



# A title line of at most this many characters fits the figures' 6.4 in width at 9 pt.
TITLE_CHARACTERS = 80


def wrapped(title: str) -> str:
    """``title`` broken into lines that fit the figure (a long title is never cut)."""
    return textwrap.fill(title, TITLE_CHARACTERS)

def _rest_from(ds) -> float:
    """Instant the motion stopped: stop_time + ramp of the stop scene."""
    motion = yaml.safe_load(ds.attrs["scene"]).get("motion", {})
    return float(motion.get("stop_time", 0.0)) + float(motion.get("ramp", 0.0))


def stop_figure(cases: list[tuple[str, object]], title: str) -> Figure:
    fig = Figure(figsize=(7.0, 6.5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    for i, (label, ds) in enumerate(cases):
        color = f"C{i}"
        t = ds["time"].values - _rest_from(ds)
        after = t > 0
        top.loglog(t[after], ds["contact_resistance"].values[after], color=color, label=label)
        top.axhline(float(ds["rest_resistance"]) * 2.0, color=color, ls=":", lw=0.8)
        recon = float(ds["reconnect_time"])
        if math.isfinite(recon) and recon > 0:
            top.plot([recon], [2.0 * float(ds["rest_resistance"])], "o", color=color, ms=5)
        bottom.semilogx(t[after], ds["min_film_thickness"].values[after] * 1e6, color=color)
        if not int(ds["converged"]):
            top.plot(t[after][-1:], ds["contact_resistance"].values[after][-1:], "x", color="red", ms=9)
    top.set_ylabel("contact resistance (\u03a9)")
    bottom.set_ylabel("minimum film thickness h (\u00b5m)")
    bottom.set_xlabel("time after the stop (s)")
    top.legend(fontsize=7, loc="upper right")
    top.set_title(wrapped(title) + "\ndotted: 2 \u00d7 resistance at rest; dots: reconnect time", fontsize=9)
    return fig


SERIES_MARKERS = ("o", "s", "D", "^", "v")


def reconnect_figure(points: list[dict], x_label: str, x_units: str, title: str, log_x: bool = True) -> Figure:
    """points: {"x", "series", "label", "ds"} of the design chart; ``log_x`` False for an x
    that may be zero or negative (a temperature in C)."""
    fig = Figure(figsize=(6.5, 4.5), layout="constrained")
    ax = fig.subplots()
    finite = [t for p in points if math.isfinite(t := float(p["ds"]["reconnect_time"])) and t > 0]
    top = max(finite) * 3 if finite else 1.0
    bottom = min(finite) / 3 if finite else 1e-3
    for i, series in enumerate(sorted({p["series"] for p in points})):
        line = sorted((p for p in points if p["series"] == series), key=lambda p: p["x"])
        x = np.array([p["x"] for p in line])
        y = np.array([float(p["ds"]["reconnect_time"]) for p in line])
        ok = np.array([int(p["ds"]["converged"]) == 1 for p in line])
        color = f"C{i}"
        drawn = np.isfinite(y) & (y > 0) & ok
        # series that coincide stay visible: each its own marker, the later ones smaller and on top
        ax.plot(x[drawn], y[drawn], "-", marker=SERIES_MARKERS[i % len(SERIES_MARKERS)], markersize=max(9 - 2 * i, 3),
                  color=color, label=line[0]["label"], zorder=2 + i)
        never = ~np.isfinite(y) & ok
        ax.plot(x[never], np.full(never.sum(), top), "^", color=color)
        already = (y == 0) & ok
        ax.plot(x[already], np.full(already.sum(), bottom), "v", color=color)
        ax.plot(x[~ok], np.where(np.isfinite(y[~ok]), y[~ok], top), "x", color="red", ms=9)
    ax.set_xscale("log" if log_x else "linear")
    ax.set_yscale("log")
    ax.set_xlabel(f"{x_label} ({x_units})")
    ax.set_ylabel("reconnect time (s)")
    ax.set_title(wrapped(title) + "\n\u25b2 not within the run; \u25bc before the block stopped; red \u00d7 not converged",
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def vibration_figure(ds, title: str) -> Figure:
    fig = Figure(figsize=(7.0, 5.5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    t = ds["time"].values
    top.plot(t, ds["speed"].values, color="C0")
    top.set_ylabel("sliding speed U (m/s)")
    bottom.semilogy(t, ds["contact_resistance"].values, color="C1", label="contact resistance")
    threshold = float(ds["open_resistance"])
    bottom.axhline(threshold, color="red", ls="--", label=f"open threshold {threshold:g} \u03a9")
    bottom.axhline(float(ds["rest_resistance"]), color="grey", ls=":", label="at rest")
    bottom.set_ylabel("contact resistance (\u03a9)")
    bottom.set_xlabel("time (s)")
    bottom.legend(fontsize=8)

    scene = yaml.safe_load(ds.attrs["scene"])
    motion = scene["motion"]
    details = (f"amplitude {motion['amplitude'] * 1e3:g} mm at {motion['frequency']:g} Hz, "
               f"\u03bc = {scene['lubricant']['viscosity']:g} Pa s, F = {scene['operating']['force']:g} N")
    fraction = float(ds["open_fraction"])
    open_text = "open fraction unknown (the run ended early)" if math.isnan(fraction) else (
        f"open {100 * fraction:.0f} % of the oscillation time")
    fig.suptitle(f"{title}\n{details}; {open_text}", fontsize=9)  # wraps on its own lines: never cut
    return fig
