"""The time series of a transient (docs/DESIGN.md "Time"): the Dataset along ``time``,
``reconnect_time``, the oscillation metrics and the discontinuity events (events.py) along
``event``, with CF units on every variable."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from lubecontact.io.case_schema import SCALARS as CASE
from lubecontact.io.version import package_version
from lubecontact.model.fluid_film import yield_stress_law
from lubecontact.model.outputs import point_outputs
from lubecontact.model.validity import assess
from lubecontact.numerics.reynolds import boundary_flux, interior_nodes
from lubecontact.numerics.yield_stress_reynolds import reduction_factor
from lubecontact.unsteady.events import crossing_time

# name: (units, long_name), along ``time``; a quantity that means what it means in a case
# takes the case's entry (io/case_schema.SCALARS)
SERIES = {
    "speed": CASE["speed"],
    "contact_resistance": ("ohm", "electrical contact resistance: the whole path (electrical/path.py)"),
    "min_film_thickness": CASE["min_film_thickness"],
    "central_film_thickness": CASE["central_film_thickness"],
    "fluid_force": ("N", "load carried by the fluid film (squeeze and wedge)"),
    "contact_force": CASE["contact_force"],
    "friction_coefficient": ("1", "friction coefficient (boundary friction of solid load + |fluid shear|) / applied force"),
    "separation": CASE["separation"],
    "real_contact_area": ("m2", "real area of asperity contact"),
    "step_converged": ("1", "1 if the coupled solve of the step met its tolerances"),
    "iterations": ("1", "outer (deformation) iterations of the step's coupled solve"),
    "order": ("1", "order of the BDF formula of the step (0: the steady start)"),
    "error_estimate": ("1", "estimated local error of the step / its tolerance (accepted: <= 1, except a jump "
                                  "over an impasse)"),
    "impasse_jump": ("1", "1 if the step jumped over an impasse at a sealing pocket, accepted without the error test"),
    "volume_balance": ("1", "net outflow of the full-film region + its volume change rate, relative to the flows"),
    "valid": CASE["valid"],
}
# the reconnect threshold's shift either way for threshold_times: a tenth, a difference an
# engineer would not argue about when choosing reconnect_factor
THRESHOLD_SHIFT = 0.1
SCALARS = {
    "reconnect_time": ("s", "time after the motion stops and a shock ends until contact_resistance first falls to "
                            "reconnect_factor x the resistance at rest (inf: not within duration; nan: the motion or "
                            "a vibration never ends)"),
    "rest_resistance": ("ohm", "contact resistance of the contact at rest (steady, no fluid pressure)"),
    "open_resistance": ("ohm", "resistance above which the contact counts as open"),
    "converged": ("1", "1 if every step converged and the run reached its end"),
    "steps": ("1", "accepted time steps"),
    "rejected_steps": ("1", "time steps rejected by the error control or a failed solve"),
    "coupled_solves": ("1", "coupled solves (accepted and rejected steps, start and rest state)"),
    "solve_time": ("s", "wall time of the run"),
    "impasse_jumps": ("1", "steps over an impasse at a sealing pocket, accepted without the error test (the state "
                           "jumps there)"),
    "step_backs": ("1", "levels of a yield-stress lubricant at rest dropped because no step from them converged "
                        "(the run stepped again from the level before; counted in rejected_steps too)"),
    "longest_impasse_jump": ("s", "the longest such step (0: none): a time within it is uncertain by its length"),
    "reconnect_time_lower_threshold": ("s", f"reconnect_time with its threshold {THRESHOLD_SHIFT:.0%} lower "
                                            f"({1.0 - THRESHOLD_SHIFT:g} x reconnect_factor x the resistance at rest; "
                                            "inf: not within duration): far above reconnect_time where the resistance "
                                            "creeps past the threshold, whose choice then sets the time more than the "
                                            "contact does"),
    "reconnect_time_higher_threshold": ("s", f"reconnect_time with its threshold {THRESHOLD_SHIFT:.0%} higher "
                                             f"({1.0 + THRESHOLD_SHIFT:g} x reconnect_factor x the resistance at rest)"),
    "reconnect_time_jumps": ("s", "total length of the impasse jumps before the reconnection (0: none; nan: no "
                                  "reconnection): reconnect_time's uncertainty from them"),
    "reconnect_time_error": ("s", "estimated time-integration error of reconnect_time (motion.error_bar): "
                                  "from a second run at motion.tolerance / 10, Richardson in the tolerance"),
    "reconnect_time_mesh_error": ("s", "estimated mesh error of reconnect_time (motion.mesh_error_bar): the "
                                       "converged value minus this run's, from a second run on a mesh twice as fine "
                                       "along x, first order in the node spacing"),
    "reconnect_time_extrapolated": ("s", "reconnect_time on a converged mesh, estimated: reconnect_time + "
                                         "reconnect_time_mesh_error (motion.mesh_error_bar; nan where either is not "
                                         "finite)"),
    "open_fraction": ("1", "oscillation: fraction of the oscillation time within events above the open resistance"),
    "relative_threshold": ("ohm", "relative event threshold: the reconnection factor x the resistance at rest"),
    "min_event_duration": ("s", "shortest time above a threshold that counts as an event"),
    "event_count": ("1", "events: contact resistance above the open resistance for at least the minimum duration"),
    "event_open_time": ("s", "total duration of the events above the open resistance"),
    "longest_event": ("s", "duration of the longest event above the open resistance (0: none)"),
    "relative_event_count": ("1", "events: contact resistance above the relative threshold for at least the "
                                  "minimum duration"),
    "relative_event_open_time": ("s", "total duration of the events above the relative threshold"),
    "longest_relative_event": ("s", "duration of the longest event above the relative threshold (0: none)"),
}
CYCLE = {"peak_resistance": ("ohm", "oscillation: largest contact resistance in each cycle")}
# along ``event``: the events above the open resistance (events.py), in time order
EVENT = {
    "event_start": ("s", "time the contact resistance rises above the open resistance (0: open from the start)"),
    "event_duration": ("s", "time the contact resistance stays above the open resistance"),
    "event_peak_resistance": ("ohm", "largest contact resistance at the time levels within the event"),
    "event_open_at_end": ("1", "1 if the event is still open when the run ends (its duration a lower bound)"),
}
INTEGER = ("step_converged", "iterations", "order", "converged", "steps", "rejected_steps", "coupled_solves", "valid",
           "impasse_jumps", "impasse_jump", "step_backs",
           "event_count", "relative_event_count", "event_open_at_end")


def open_resistance(scene) -> float:
    """The open threshold (ohm): interface.open_resistance."""
    return float(scene.interface.open_resistance)


# what each instant of a series reports (model/outputs.point_outputs, as a steady case does)
INSTANT = ("contact_resistance", "min_film_thickness", "central_film_thickness", "fluid_force", "contact_force",
           "friction_coefficient", "separation", "real_contact_area")


def instant(model, state) -> dict:
    """The per-instant outputs of one level, as the steady solve reports them."""
    outputs, _ = point_outputs(model, state)
    return {"speed": model.scene.operating.speed, **{name: outputs[name] for name in INSTANT}}


def volume_balance(level) -> float:
    """Discrete mass balance of the full-film region at one level, from face fluxes
    (reynolds.boundary_flux, independent of the assembled matrix; a grease's with its law) and
    the squeeze rate:
    (net outflow + sum dA dh_T/dt) / (the largest of the wedge inlet flow, sum dA |dh_T/dt|
    and c0 h_s sum dA, the flow of squeezing the region's film by the film scale h_s over
    the step: at rest, once the film has settled, the first two vanish and a balance closed
    to its solver's tolerance read 8e268 of them, on a JFO stop)."""
    state, model = level.state, level.model
    if state.reynolds is None or level.squeeze_rate is None:
        return 0.0
    mesh = model.mesh
    full = interior_nodes(mesh.shape, mesh.line) & ~state.reynolds.cavitated
    squeeze = mesh.nodal_area * level.squeeze_rate
    grease = yield_stress_law(model)
    reduction = None if grease is None else (lambda gradient, content: reduction_factor(gradient, content, grease)[0])
    outflow = boundary_flux(mesh, state.reynolds, state.expected_gap, state.flow_coefficient, model.scene.operating.speed,
                            state.faces, reduction)
    inlet = 0.5 * abs(model.scene.operating.speed) * float(np.max(state.expected_gap)) * mesh.dy * mesh.ny
    squeezed = model.squeeze.coefficient * model.squeeze.film_scale * float(np.sum(mesh.nodal_area[full]))
    scale = max(inlet, float(np.sum(np.abs(squeeze[full]))), squeezed, 1e-300)
    return (outflow + float(np.sum(squeeze[full]))) / scale


def reconnect_time(time, resistance, rest_from, threshold, resistance_at) -> float:
    """First time after ``rest_from`` at which resistance <= threshold, minus rest_from; inf
    if never; NaN without a rest (the motion never stops). Between the last level above and
    the first below, the crossing is the root on the integrator's dense output, as an event's
    edge (events.crossing_time; ``resistance_at(step, t)``: events.dense_resistance), not an
    interpolation of the sampled R."""
    if rest_from is None:
        return math.nan
    time, resistance = np.asarray(time, dtype=float), np.asarray(resistance, dtype=float)
    after = np.flatnonzero(time >= rest_from)
    below = after[resistance[after] <= threshold]
    if below.size == 0:
        return math.inf
    step = int(below[0])
    if step == after[0]:
        return 0.0
    return crossing_time(time, resistance, threshold, step, resistance_at) - rest_from


def threshold_times(time, resistance, rest_from, threshold, resistance_at) -> dict[str, float]:
    """reconnect_time_lower_threshold and reconnect_time_higher_threshold: reconnect_time
    (same arguments) with ``threshold`` moved THRESHOLD_SHIFT down and up. Where the
    resistance falls steeply through the threshold (an asperity contact closing) the three
    times nearly agree; where it creeps past it they spread, and the reconnect time is the
    threshold's choice (reconnect_factor) more than the contact's: the 1 Pa s fretting under
    20 N crosses 2.2, 2.0 and 1.8 times its rest resistance 11.8, 11.8 and 17.8 ms after its
    stop (bench/EXPERIMENTS.md, forty-eighth session)."""
    return {f"reconnect_time_{name}_threshold": reconnect_time(time, resistance, rest_from, share * threshold,
                                                                resistance_at)
            for name, share in (("lower", 1.0 - THRESHOLD_SHIFT), ("higher", 1.0 + THRESHOLD_SHIFT))}


def cycle_peaks(time, resistance, period, cycles) -> np.ndarray:
    """Peak R of each oscillation cycle [k period, (k + 1) period) over the levels in it."""
    time, resistance = np.asarray(time), np.asarray(resistance)
    inside = time < cycles * period
    cycle = np.minimum((time[inside] / period).astype(int), cycles - 1)
    return np.array([resistance[inside][cycle == k].max(initial=-np.inf) for k in range(cycles)])


def event_scalars(opened, relative) -> dict:
    """The events' scalars (SCALARS) of the open resistance (``opened``) and the relative
    threshold (``relative``), both events.Events."""
    return {
        "relative_threshold": relative.threshold, "min_event_duration": opened.min_duration,
        "event_count": opened.count, "event_open_time": opened.open_time, "longest_event": opened.longest,
        "relative_event_count": relative.count, "relative_event_open_time": relative.open_time,
        "longest_relative_event": relative.longest,
    }


def level_rows(levels) -> list[dict]:
    """The values of SERIES at each level, and under "validity" the flags the level raises
    (model/validity.assess, as a steady case's: flag -> note)."""
    rows = []
    for lv in levels:
        flags = assess(lv.model.scene, lv.model.mesh, lv.model.contact, lv.state, lv.model.hydrodynamic)
        rows.append(instant(lv.model, lv.state) | {
            "step_converged": int(lv.diagnostics.converged), "iterations": lv.diagnostics.iterations,
            "order": lv.order, "error_estimate": lv.error, "impasse_jump": int(bool(lv.impasse)),
            "volume_balance": volume_balance(lv),
            "valid": int(not flags), "validity": flags,
        })
    return rows


def validity_over_time(times, rows) -> tuple[str, str]:
    """(the flags raised at any instant, comma-separated or "ok"; one line per flag: when it
    is first and last raised, and its note at the first time)."""
    first, last, notes = {}, {}, {}
    for t, row in zip(times, rows):
        for flag, note in row["validity"].items():
            first.setdefault(flag, t)
            notes.setdefault(flag, note)
            last[flag] = t
    lines = [f"{flag}: from t = {first[flag]:.4g} to {last[flag]:.4g} s; at first: {notes[flag]}" for flag in first]
    return ",".join(first) or "ok", "\n".join(lines)


def event_variables(opened) -> dict:
    """EVENT along ``event`` for the events above the open resistance (events.Events)."""
    values = {
        "event_start": [event.start for event in opened.events],
        "event_duration": [event.duration for event in opened.events],
        "event_peak_resistance": [event.peak_resistance for event in opened.events],
        "event_open_at_end": [int(event.open_at_end) for event in opened.events],
    }
    return {name: xr.Variable(("event",), np.array(values[name], dtype=np.int32 if name in INTEGER else np.float64),
                              {"units": units, "long_name": long_name})
            for name, (units, long_name) in EVENT.items()}


def series_dataset(scene, times, rows, scalars: dict, notes: str, peaks=None, opened=None) -> xr.Dataset:
    """The transient's Dataset: per-level variables (``rows``) along ``time``, the run's
    scalars, ``peak_resistance`` along ``cycle`` and the events above the open resistance
    (``opened``, events.Events) along ``event``."""
    data = {}
    for name, (units, long_name) in SERIES.items():
        dtype = np.int32 if name in INTEGER else np.float64
        data[name] = xr.Variable(("time",), np.array([row[name] for row in rows], dtype=dtype),
                                 {"units": units, "long_name": long_name})
    for name, value in scalars.items():
        units, long_name = SCALARS[name]
        dtype = np.int32 if name in INTEGER else np.float64
        data[name] = xr.Variable((), np.asarray(value, dtype=dtype), {"units": units, "long_name": long_name})
    coords = {"time": xr.Variable(("time",), np.asarray(times, dtype=float),
                                  {"units": "s", "long_name": "time since the start of the motion", "standard_name": "time"})}
    if peaks is not None:
        units, long_name = CYCLE["peak_resistance"]
        data["peak_resistance"] = xr.Variable(("cycle",), peaks, {"units": units, "long_name": long_name})
        coords["cycle"] = xr.Variable(("cycle",), np.arange(1, peaks.size + 1, dtype=np.int32),
                                      {"units": "1", "long_name": "oscillation cycle number"})
    if opened is not None:
        data |= event_variables(opened)
        coords["event"] = xr.Variable(("event",), np.arange(1, opened.count + 1, dtype=np.int32),
                                      {"units": "1", "long_name": "event number, in time order"})
    attrs = {
        "title": "lubecontact transient: a lubricated rough electrical contact after its motion changes",
        "Conventions": "CF-1.10",
        "scene": scene.canonical_yaml(),
        "scene_hash": scene.hash,
        "lubecontact_version": package_version(),
        "notes": notes,
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)
