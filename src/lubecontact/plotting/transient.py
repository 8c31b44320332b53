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
(d) ``shock_figure``: a contact on its spring struck through its base, one curve per shock:
the base acceleration (g), the resistance with the open threshold and each discontinuity
event shaded, a lift-off (R infinite) drawn on the top edge, and the minimum film.
Library code: matplotlib's object API, no files read.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import yaml
from matplotlib.figure import Figure

from lubecontact.scene.scene import load_scene
from lubecontact.unsteady.dynamics import BaseExcitation


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


# standard gravity (m/s^2): shock tests give their peaks in g
STANDARD_GRAVITY = 9.80665
# the resistance axis of the shock figure ends at this many times the open threshold
RESISTANCE_AXIS_TOP = 100.0
# samples of the base acceleration drawn over the run (its formula, not the time levels)
EXCITATION_SAMPLES = 1000


def shock_figure(cases: list[tuple[str, object]], title: str) -> Figure:
    """(label, Dataset) per shock of one contact (the same contact, scene.motion.mass and
    spring_stiffness, struck through its base): base acceleration away from the block (g),
    contact resistance (log) with the open threshold and its events shaded, minimum film
    thickness (um), against time (ms). The resistance axis ends at ``RESISTANCE_AXIS_TOP`` x
    the open threshold (above it the asperity tail gives finite but meaningless values, up to
    1e175 ohm): higher values run along the top edge, and an instant with R infinite (the
    asperities apart) is marked there with a triangle."""
    fig = Figure(figsize=(7.0, 8.0), layout="constrained")
    base, middle, bottom = fig.subplots(3, 1, sharex=True, height_ratios=(1.0, 2.0, 1.0))
    resistances = [ds["contact_resistance"].values for _, ds in cases]
    threshold = float(cases[0][1]["open_resistance"])
    edge = RESISTANCE_AXIS_TOP * threshold
    scenes = [load_scene(yaml.safe_load(ds.attrs["scene"])) for _, ds in cases]
    for i, (label, ds) in enumerate(cases):
        color = f"C{i}"
        t_ms = ds["time"].values * 1e3
        excitation = BaseExcitation.from_scene(scenes[i])
        t = np.linspace(0.0, float(ds["time"].values[-1]), EXCITATION_SAMPLES)
        away = [-excitation.acceleration_at(ti) / STANDARD_GRAVITY for ti in t]
        base.plot(t * 1e3, away, color=color, label=label)
        r = resistances[i]
        lifted = np.isinf(r)
        middle.semilogy(t_ms, np.minimum(r, edge), color=color, label=f"{label}: {_events_text(ds)}")
        if lifted.any():  # (an empty line off the clip box would still stretch the layout)
            middle.plot(t_ms[lifted], np.full(lifted.sum(), edge), "^", color=color, ms=5, clip_on=False)
        for start, duration in zip(ds["event_start"].values, ds["event_duration"].values):
            middle.axvspan(start * 1e3, (start + duration) * 1e3, color=color, alpha=0.15, lw=0)
        bottom.plot(t_ms, ds["min_film_thickness"].values * 1e6, color=color)
    middle.axhline(threshold, color="red", ls="--", label=f"open threshold {threshold:g} \u03a9")
    if any(np.isinf(r).any() for r in resistances):
        middle.plot([], [], "^", color="black", label="lift-off: resistance infinite, asperities apart")
    middle.set_ylim(top=edge)
    films = np.concatenate([ds["min_film_thickness"].values for _, ds in cases])
    bottom.set_yscale("log" if (films > 0).all() else "linear")  # a film at or below zero stays drawn
    base.set_ylabel("base acceleration\naway from the block (g)")
    middle.set_ylabel("contact resistance (\u03a9)")
    bottom.set_ylabel("minimum film\nthickness h (\u00b5m)")
    bottom.set_xlabel("time (ms)")
    middle.legend(fontsize=7, loc="center right")  # the curves' colours in every panel
    fig.suptitle(wrapped(f"{title}: {_contact_text(scenes[0])}") + "\nshaded: events above the open threshold; "
                 f"resistances above {edge:g} \u03a9 on the top edge",
                 fontsize=9)
    return fig


def _events_text(ds) -> str:
    """A curve's discontinuity events in words: how many and their total open time."""
    count = int(ds["event_count"])
    if count == 0:
        return "no event"
    still = " (still open at the end)" if bool(ds["event_open_at_end"].values[-1]) else ""
    return f"{count} event(s), open {float(ds['event_open_time']) * 1e3:.3g} ms in all{still}"


def _contact_text(scene) -> str:
    """The struck contact (a Scene) in words with units: preload, mass, spring, viscosity."""
    return (f"spring preload {scene.operating.force:g} N, moving mass {scene.motion.mass:g} kg, "
            f"spring stiffness {scene.motion.spring_stiffness:g} N/m, "
            f"lubricant viscosity {scene.lubricant.viscosity:g} Pa s")
