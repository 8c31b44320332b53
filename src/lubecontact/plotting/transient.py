"""The transient figures, drawn from case files (lubecontact.transient Datasets).

(a) ``stop_figure``: contact resistance and minimum film thickness against time (log axis,
time after the motion stops) for several variants of one contact; the resting resistance
times the reconnect factor as a dotted line, the reconnect time as a marker.
(b) ``reconnect_figure``: reconnect time (log) against a swept parameter (log, or linear for a
temperature), one line per
series value; a run that never reconnected within its duration is drawn as a triangle on
the top edge, one already reconnected when the block stopped (reconnect_time = 0) as a
triangle on the bottom edge, a run that did not converge as a red cross; a vertical bar on
each time spans its threshold moved a tenth either way (reconnect_time_higher_threshold to
reconnect_time_lower_threshold).
(c) ``vibration_figure``: speed and resistance over the cycles with the open threshold.
(d) ``shock_figure``: a contact on its spring struck through its base, one curve per shock:
the base acceleration (g), the resistance with the open threshold and each discontinuity
event shaded, a lift-off (R infinite) drawn on the top edge, and the minimum film.
(e) ``grease_stop_figure``: one contact stopped with a base oil and with Bingham greases: the
minimum film (log) with sigma and each grease's closed-form stop film
(``closed_form_stop_film``), the resistance with the open threshold, whether each reconnects.
Library code: matplotlib's object API, no files read.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import yaml
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter

from lubecontact.physics.yield_stress_flow import bingham_squeeze_stop_film
from lubecontact.scene.scene import load_scene
from lubecontact.unsteady.dynamics import BaseExcitation
from lubecontact.unsteady.series import THRESHOLD_SHIFT


# A title line of at most this many characters fits the figures' 6.4 in width at 9 pt.
TITLE_CHARACTERS = 80


def wrapped(title: str) -> str:
    """``title`` broken into lines that fit the figure (a long title is never cut)."""
    return textwrap.fill(title, TITLE_CHARACTERS)

def _rest_from(ds) -> float:
    """Instant the motion stopped: stop_time + ramp of the stop scene."""
    motion = yaml.safe_load(ds.attrs["scene"]).get("motion", {})
    return float(motion.get("stop_time", 0.0)) + float(motion.get("ramp", 0.0))


# what a vertical bar on a stop's resistance marks (_stop_curves)
JUMP_TEXT = "bars: a step the state jumped over where a pocket of the film sealed (docs/physics.md section 14)"


def _stop_curves(cases: list[tuple[str, object]], resistance_ax, film_ax, edge: float = math.inf) -> bool:
    """Each (label, Dataset) of a stop against the time after the stop (log): its resistance
    on ``resistance_ax`` (log; above ``edge`` along the top edge, ``_clipped_resistance``)
    with 2 x its resistance at rest dotted and its reconnect time a dot, its minimum film (um)
    on ``film_ax``; a run that did not converge ends in a red cross, and the end of each step
    that jumped over an impasse (impasse_jump) is a vertical bar. Colour Ci for case i.
    Whether any bar was drawn (JUMP_TEXT says what they are)."""
    jumped = False
    for i, (label, ds) in enumerate(cases):
        color = f"C{i}"
        t = ds["time"].values - _rest_from(ds)
        after = t > 0
        resistance = ds["contact_resistance"].values[after]
        _clipped_resistance(resistance_ax, t[after], resistance, edge, color, label)
        resistance_ax.axhline(float(ds["rest_resistance"]) * 2.0, color=color, ls=":", lw=0.8)
        recon = float(ds["reconnect_time"])
        if math.isfinite(recon) and recon > 0:
            resistance_ax.plot([recon], [2.0 * float(ds["rest_resistance"])], "o", color=color, ms=5)
        film_ax.plot(t[after], ds["min_film_thickness"].values[after] * 1e6, color=color)
        if not int(ds["converged"]):
            resistance_ax.plot(t[after][-1:], np.minimum(resistance[-1:], edge), "x", color="red", ms=9)
        jumps = after & (ds["impasse_jump"].values == 1) if "impasse_jump" in ds else None  # (a series before it)
        if jumps is not None and jumps.any():
            resistance_ax.plot(t[jumps], np.minimum(ds["contact_resistance"].values[jumps], edge), "|", color=color,
                               ms=14, mew=1.5)
            jumped = True
    resistance_ax.set_xscale("log")
    resistance_ax.set_yscale("log")
    resistance_ax.set_ylabel("contact resistance (\u03a9)")
    film_ax.set_ylabel("minimum film thickness h (\u00b5m)")
    return jumped


def _clipped_resistance(ax, t, resistance, edge: float, color: str, label: str) -> None:
    """``resistance`` against ``t`` on ``ax``, values above ``edge`` along the top edge and
    the instants with R infinite (no asperity touching) marked there with a triangle."""
    ax.plot(t, np.minimum(resistance, edge), color=color, label=label)
    lifted = np.isinf(resistance)
    if lifted.any() and math.isfinite(edge):  # (an empty line off the clip box would still stretch the layout)
        ax.plot(t[lifted], np.full(lifted.sum(), edge), "^", color=color, ms=5, clip_on=False)


def stop_figure(cases: list[tuple[str, object]], title: str) -> Figure:
    fig = Figure(figsize=(7.0, 6.5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    jumped = _stop_curves(cases, top, bottom)
    bottom.set_xlabel("time after the stop (s)")
    top.legend(fontsize=7, loc="upper right")
    top.set_title(wrapped(title) + "\n" + wrapped("dotted: 2 \u00d7 resistance at rest; dots: reconnect time"
                                                  + (f"; {JUMP_TEXT}" if jumped else "")), fontsize=9)
    return fig


SERIES_MARKERS = ("o", "s", "D", "^", "v")


# what the vertical bar on a design chart's reconnect time marks (_threshold_bars)
THRESHOLD_BAR_TEXT = (f"bars: the reconnect time with its threshold {THRESHOLD_SHIFT:.0%} higher and lower (long "
                      "where the resistance creeps past it: the threshold's choice then sets the time)")


def _threshold_bars(ax, x, y, datasets, color: str, zorder: int) -> None:
    """Vertical bars on the reconnect times ``y`` at ``x`` from each Dataset's
    reconnect_time_higher_threshold to its reconnect_time_lower_threshold (the threshold
    moved THRESHOLD_SHIFT either way, series.threshold_times), where both are finite; a
    dataset written before they existed has none."""
    ends = np.array([[float(ds[f"reconnect_time_{name}_threshold"]) if f"reconnect_time_{name}_threshold" in ds
                      else math.nan for name in ("higher", "lower")] for ds in datasets]).reshape(-1, 2)
    shown = np.all(np.isfinite(ends), axis=1) & np.all(ends > 0, axis=1)
    if shown.any():
        below, above = y[shown] - ends[shown, 0], ends[shown, 1] - y[shown]
        ax.errorbar(x[shown], y[shown], yerr=[np.maximum(below, 0.0), np.maximum(above, 0.0)], fmt="none",
                    ecolor=color, elinewidth=1.0, capsize=3, zorder=zorder)


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
        # series that coincide stay visible: each its own marker, the later ones smaller and on
        # top (the edge triangles too: several series may miss the run at one x)
        size = max(9 - 2 * i, 3)
        ax.plot(x[drawn], y[drawn], "-", marker=SERIES_MARKERS[i % len(SERIES_MARKERS)], markersize=size,
                color=color, label=line[0]["label"], zorder=2 + i)
        _threshold_bars(ax, x[drawn], y[drawn], [p["ds"] for p, d in zip(line, drawn) if d], color, 2 + i)
        never = ~np.isfinite(y) & ok
        ax.plot(x[never], np.full(never.sum(), top), "^", color=color, markersize=size, zorder=2 + i)
        already = (y == 0) & ok
        ax.plot(x[already], np.full(already.sum(), bottom), "v", color=color, markersize=size, zorder=2 + i)
        ax.plot(x[~ok], np.where(np.isfinite(y[~ok]), y[~ok], top), "x", color="red", ms=9)
    ax.set_xscale("log" if log_x else "linear")
    ax.set_yscale("log")
    ax.set_xlabel(f"{x_label} ({x_units})")
    ax.set_ylabel("reconnect time (s)")
    ax.set_title(wrapped(title) + "\n\u25b2 not within the run; \u25bc before the block stopped; red \u00d7 not converged"
                 + "\n" + wrapped(THRESHOLD_BAR_TEXT), fontsize=9)
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
        _clipped_resistance(middle, t_ms, resistances[i], edge, color, f"{label}: {_events_text(ds)}")
        for start, duration in zip(ds["event_start"].values, ds["event_duration"].values):
            middle.axvspan(start * 1e3, (start + duration) * 1e3, color=color, alpha=0.15, lw=0)
        bottom.plot(t_ms, ds["min_film_thickness"].values * 1e6, color=color)
    middle.axhline(threshold, color="red", ls="--", label=f"open threshold {threshold:g} \u03a9")
    if any(np.isinf(r).any() for r in resistances):
        middle.plot([], [], "^", color="black", label="lift-off: resistance infinite, asperities apart")
    middle.set_yscale("log")
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
    """A curve's discontinuity events in words: how many, their total open time, and, where
    the series has one, its reconnection after the shock (reconnect_time, counted from the
    shock's end: unsteady/transient.reconnection_start)."""
    count = int(ds["event_count"])
    if count == 0:
        return "no event"
    still = " (still open at the end)" if bool(ds["event_open_at_end"].values[-1]) else ""
    recon = float(ds["reconnect_time"]) if "reconnect_time" in ds else math.nan
    back = f", reconnected {recon * 1e3:.3g} ms after the shock" if math.isfinite(recon) and recon > 0.0 else ""
    return f"{count} event(s), open {float(ds['event_open_time']) * 1e3:.3g} ms in all{still}{back}"


def _contact_text(scene) -> str:
    """The struck contact (a Scene) in words with units: preload, mass, spring, viscosity."""
    return (f"spring preload {scene.operating.force:g} N, moving mass {scene.motion.mass:g} kg, "
            f"spring stiffness {scene.motion.spring_stiffness:g} N/m, "
            f"lubricant viscosity {scene.lubricant.viscosity:g} Pa s")


# A film h above this many sigma is a full film: the film parameter Lambda = h/sigma > 3
# (Hamrock & Dowson, Ball Bearing Lubrication, Wiley 1981), the asperities' share of the
# load small: in the grease figure's runs (Table 1 at 0.5 N, 101 nodes) they carry 1.8-2.6 %
# of it as the film passes 3 sigma, 0.06-0.15 % at 4 sigma (docs/physics.md section 21).
FULL_FILM_RATIO = 3.0


def closed_form_stop_film(scene, film_at_stop: float) -> float | None:
    """The film (m) at which a Bingham grease's yield stress alone holds the load of ``scene``
    (physics/yield_stress_flow.bingham_squeeze_stop_film: a rigid smooth cylinder on a line
    contact, p = 0 at x = -a and a), or None where the closed form does not describe the run:
    not a Bingham grease, not a stop, not a line contact on a domain symmetric about the
    contact (its half-width is a), a force that is not constant (a spring or a base
    excitation), a stop film below FULL_FILM_RATIO sigma (the asperities share the load) or
    not below ``film_at_stop``, the film when the block came to rest (the squeeze never
    reaches it: the plug holds the film where it is)."""
    lubricant, mesh, motion = scene.lubricant, scene.mesh, scene.motion
    if lubricant.rheology != "bingham" or motion.kind != "stop" or mesh.ny != 1:
        return None
    if mesh.x_min is None or mesh.x_max is None or mesh.x_min != -mesh.x_max:
        return None
    if motion.spring_stiffness != 0.0 or motion.vibration != "none":
        return None
    h_stop = float(bingham_squeeze_stop_film(scene.operating.force, scene.geometry.length, scene.geometry.radius,
                                             mesh.x_max, lubricant.yield_stress))
    return h_stop if FULL_FILM_RATIO * scene.roughness.sigma <= h_stop < film_at_stop else None


def film_at_stop(ds) -> float:
    """Minimum film (m) of a stop at the instant the block came to rest."""
    return float(np.interp(_rest_from(ds), ds["time"].values, ds["min_film_thickness"].values))


def grease_stop_figure(cases: list[tuple[str, object]], title: str) -> Figure:
    """(label, Dataset) per lubricant of one contact stopped from sliding: the minimum film
    thickness (um, log) with the RMS roughness sigma dotted and each Bingham grease's
    ``closed_form_stop_film`` dashed in its colour where the closed form describes the run;
    the contact resistance (log) with the open threshold dashed, 2 x the resistance at rest
    dotted and the reconnect time a dot (``_stop_curves``); against the time after the stop
    (log). Each legend entry says whether and when its case reconnects. Resistances above
    ``RESISTANCE_AXIS_TOP`` x the open threshold run along the top edge (as in shock_figure)."""
    fig = Figure(figsize=(7.0, 8.0), layout="constrained")
    film_ax, resistance_ax = fig.subplots(2, 1, sharex=True)
    threshold = float(cases[0][1]["open_resistance"])
    edge = RESISTANCE_AXIS_TOP * threshold
    jumped = _stop_curves([(f"{label}: {_reconnect_text(ds)}", ds) for label, ds in cases], resistance_ax, film_ax,
                          edge)
    scenes = [load_scene(yaml.safe_load(ds.attrs["scene"])) for _, ds in cases]
    for i, ((_, ds), scene) in enumerate(zip(cases, scenes)):
        h_stop = closed_form_stop_film(scene, film_at_stop(ds))
        if h_stop is not None:
            film_ax.axhline(h_stop * 1e6, color=f"C{i}", ls="--", lw=1.0,
                            label=f"yield stress {scene.lubricant.yield_stress:g} Pa alone holds the load: "
                                  f"{h_stop * 1e6:.3g} \u00b5m")
    sigma = scenes[0].roughness.sigma
    film_ax.axhline(sigma * 1e6, color="grey", ls=":", label=f"RMS roughness \u03c3 = {sigma * 1e6:g} \u00b5m")
    film_ax.set_yscale("log")
    # plain numbers (0.5, 2, 3 rather than 5 x 10^-1 ...), between decades only at 2, 3 and 5 (room)
    film_ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    film_ax.yaxis.set_minor_formatter(FuncFormatter(
        lambda value, _: f"{value:g}" if round(value / 10.0 ** math.floor(math.log10(value))) in (2, 3, 5) else ""))
    film_ax.legend(fontsize=7, loc="upper right")
    resistance_ax.axhline(threshold, color="red", ls="--", label=f"open threshold {threshold:g} \u03a9")
    resistance_ax.set_ylim(top=edge)
    resistance_ax.set_xlabel("time after the stop (s)")
    fig.legend(*resistance_ax.get_legend_handles_labels(), fontsize=7, loc="outside lower center")
    fig.suptitle(wrapped(title) + "\n" + wrapped(
        f"dashed (film): the film at which the grease's yield stress alone carries the load (closed form for a rigid "
        f"smooth cylinder), drawn where it lies above {FULL_FILM_RATIO:g}\u03c3 and below the film at the stop; "
        f"dotted (resistance): 2 \u00d7 resistance at rest, dots: reconnect time; resistances above {edge:g} "
        f"\u03a9 on the top edge" + (f"; {JUMP_TEXT}" if jumped else "")), fontsize=9)
    return fig


def _reconnect_text(ds) -> str:
    """Whether and when a stop reconnects (reconnect_time finite, 0 or inf), in words; a
    case that never does says whether it stayed open (above the open threshold) throughout."""
    if not int(ds["converged"]):
        return "did not converge"
    recon = float(ds["reconnect_time"])
    if recon == 0.0:
        return "reconnected before the block stopped"
    if math.isfinite(recon):
        return f"reconnects {_duration_text(recon)} after the stop"
    rest, t = _rest_from(ds), ds["time"].values
    threshold = float(ds["open_resistance"])
    opened = bool(np.all(ds["contact_resistance"].values[t >= rest] > threshold))
    return (f"not reconnected {_duration_text(t[-1] - rest)} after the stop"
            + (f", open (above {threshold:g} \u03a9) throughout" if opened else ""))


def _duration_text(seconds: float) -> str:
    """A time in words: 3 significant digits, in ms below 1 s."""
    return f"{seconds * 1e3:.3g} ms" if seconds < 1.0 else f"{seconds:.3g} s"
