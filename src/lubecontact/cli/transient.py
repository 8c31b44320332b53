"""``lubecontact transient SCENE --out SERIES.nc``: run, write, summarise (cli/exit_codes.py)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

from lubecontact.cli.exit_codes import EXIT_BAD_INPUT, EXIT_INTERRUPTED, EXIT_NOT_CONVERGED, EXIT_OK
from lubecontact.io.case_schema import write_case
from lubecontact.scene import SceneError
from lubecontact.unsteady.dynamics import BaseExcitation
from lubecontact.unsteady.motion import SpeedHistory
from lubecontact.unsteady.series import THRESHOLD_SHIFT
from lubecontact.unsteady.transient import MESH_ERROR_UNSEEN, no_reconnection_note, reconnection_start, transient

WIDTH = len("reconnect_time_higher_threshold")  # the summary's names, right-aligned on their '='
SUMMARY = ("reconnect_time", "rest_resistance", "open_fraction", "steps", "rejected_steps", "coupled_solves", "solve_time")


def summary(ds) -> str:
    r = ds["contact_resistance"].values
    lines = [f"{'time':>{WIDTH}s} = 0 .. {ds['time'].values[-1]:.6g} s",
             f"{'contact_resistance':>{WIDTH}s} = {r.min():.4g} .. {r.max():.4g} ohm"]
    for name in SUMMARY:
        var = ds[name]
        units = "" if var.attrs["units"] == "1" else f" {var.attrs['units']}"
        lines.append(f"{name:>{WIDTH}s} = {var.item():.6g}{units}")
    if "reconnect_time_lower_threshold" in ds and math.isfinite(ds["reconnect_time"].item()):
        for name, way in (("lower", "down; where these two spread, the threshold's choice sets the time"),
                          ("higher", "up")):
            value = ds[f"reconnect_time_{name}_threshold"].item()
            lines.append(f"{f'reconnect_time_{name}_threshold':>{WIDTH}s} = {value:.6g} s (the threshold "
                         f"{THRESHOLD_SHIFT:.0%} {way})")
    jumped = ds["reconnect_time_jumps"].item() if "reconnect_time_jumps" in ds else 0.0
    if jumped > 0.0:
        lines.append(f"{'reconnect_time_jumps':>{WIDTH}s} = {jumped:.3g} s (impasse jumps before the reconnection: "
                     "reconnect_time is uncertain by their length at least; notes say where a jump in "
                     "the motion makes it more)")
    at_once = ds["reconnect_time"].item() == 0.0  # no second run: the bars are 0 (transient.error_bars)
    if "reconnect_time_error" in ds:
        lines.append(f"{'reconnect_time_error':>{WIDTH}s} = {ds['reconnect_time_error'].item():.3g} s "
                     + ("(reconnected at once: nothing to integrate)" if at_once else
                        "(time integration, from a run at motion.tolerance / 10)"))
    if "reconnect_time_mesh_error" in ds:
        error = ds["reconnect_time_mesh_error"].item()
        lines.append(f"{'reconnect_time_mesh_error':>{WIDTH}s} = {error:+.3g} s "
                     + ("(reconnected at once: nothing drains on any mesh)" if at_once else
                        "(the converged value minus this run's, from a run on a mesh twice as fine along x)"))
        if math.isfinite(error):
            lines.append(f"{'reconnect_time_extrapolated':>{WIDTH}s} = {ds['reconnect_time_extrapolated'].item():.6g} s "
                         "(reconnect_time on a converged mesh: reconnect_time + reconnect_time_mesh_error)")
    lines.append(f"{'converged':>{WIDTH}s} = {'yes' if ds['converged'].item() == 1 else 'NO'}")
    return "\n".join(lines)


def explained(ds, scene) -> list[str]:
    """Why a summary value is NaN or infinite, in words (a bare 'nan' tells nothing)."""
    lines = []
    motion, ended = scene.motion, ds["converged"].item() != 1
    reconnect, fraction = ds["reconnect_time"].item(), ds["open_fraction"].item()
    history, base = SpeedHistory.from_scene(scene), BaseExcitation.from_scene(scene)
    since = reconnection_start(history, base)
    if math.isnan(reconnect):
        why = "the run ended before the contact reconnected" if ended else no_reconnection_note(scene, history, base)
        lines.append(f"  reconnect_time = nan: {why}")
    elif motion.vibration == "half_sine_shock" and since is not None:
        lines.append(f"  reconnect_time: counted from t = {since:.6g} s, when the block is at rest and the shock over")
    elif math.isinf(reconnect):
        lines.append(f"  reconnect_time = inf: not reconnected by the run's end at t = {history.end:.6g} s "
                     f"(motion.duration = {motion.duration:g} s; R stayed above {motion.reconnect_factor:g} x "
                     "rest_resistance)")
    if MESH_ERROR_UNSEEN in ds.attrs["notes"]:
        lines.append("  reconnect_time: its mesh error is not estimated (motion.mesh_error_bar: false), and on the "
                     "default mesh it is most of the error (docs/physics.md section 14)")
    if "reconnect_time_extrapolated" in ds and math.isnan(ds["reconnect_time_extrapolated"].item()):
        error = ds["reconnect_time_mesh_error"].item()
        if math.isfinite(reconnect) and math.isfinite(error):
            lines.append(f"  reconnect_time_extrapolated = nan: the mesh error estimate ({error:+.3g} s) is as large as "
                         "reconnect_time itself: the mesh is outside the range where its error is first order, so "
                         "nothing is extrapolated (the file's notes give both runs; refine motion.rest_refinement, or "
                         "mesh.nx on an explicit domain)")
    for name, second in (("reconnect_time_error", "at motion.tolerance / 10"),
                         ("reconnect_time_mesh_error", "on a mesh twice as fine along x")):
        if name in ds and math.isnan(ds[name].item()) and math.isfinite(reconnect):
            lines.append(f"  {name} = nan: the second run {second} did not converge or did not reconnect within "
                         f"motion.duration (its outcome is in the file's notes)")
    valid = ds["valid"].values == 1
    lines.append(f"{'valid':>{WIDTH}s} = " + ("yes at every instant (every sub-model within its range)" if valid.all() else
                                         f"NO at {int((~valid).sum())} of {valid.size} instants: left a sub-model's ground"))
    lines += [f"  validity {line}" for line in ds.attrs["validity_notes"].splitlines()]
    if math.isnan(fraction):
        why = "the run ended before the oscillation did" if ended and motion.kind == "oscillation" else (
            f"only an oscillation has one (motion.kind = {motion.kind})")
        lines.append(f"  open_fraction = nan: {why}")
    return lines


def events_summary(ds, scene) -> list[str]:
    """The discontinuity events above both thresholds in words, and why there are none."""
    r = ds["contact_resistance"].values
    shortest = ds["min_event_duration"].item()
    thresholds = (
        ("", ds["open_resistance"].item(), "interface.open_resistance"),
        ("relative_", ds["relative_threshold"].item(),
         f"{scene.motion.reconnect_factor:g} x rest_resistance, motion.reconnect_factor"),
    )
    lines = [f"{'events':>{WIDTH}s} = intervals with contact_resistance above a threshold for at least "
             f"{shortest:.3g} s (interface.min_event_duration)"]
    for prefix, threshold, source in thresholds:
        count = ds[f"{prefix}event_count"].item()
        head = f"  above {threshold:.4g} ohm ({source}):"
        if count:
            longest = ds[f"longest_{prefix}event"].item()
            still = " (the last still open when the run ended)" if prefix == "" and ds["event_open_at_end"].values[-1] else ""
            lines.append(f"{head} {count} event(s), open {ds[f'{prefix}event_open_time'].item():.4g} s in total, "
                         f"longest {longest:.4g} s{still}")
        elif not math.isfinite(threshold):
            lines.append(f"{head} none: the threshold is infinite (no metallic contact at rest)")
        elif r.max() <= threshold:
            lines.append(f"{head} none: contact_resistance never exceeded it (at most {r.max():.4g} ohm)")
        else:
            lines.append(f"{head} none: every interval above it was shorter than {shortest:.3g} s")
    return lines


def interrupted_path(out: Path) -> Path:
    """Where an interrupted transient writes its series so far: beside ``out`` (NAME.nc ->
    NAME.interrupted.nc), never over it, so --out keeps the last complete run's result."""
    return out.with_name(f"{out.stem}.interrupted{out.suffix}")


def run_transient(scene, out: Path, source: str) -> int:
    """`lubecontact transient`: the run of ``scene`` (read from the file ``source``, which a
    refusal names) written to ``out``; the exit code."""
    try:
        ds = transient(scene)
    except SceneError as err:
        print(f"lubecontact: bad input:\n{SceneError(source, err.problems)}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if ds.attrs["interrupted"]:
        out = interrupted_path(out)
    try:
        write_case(ds, out)
    except OSError as err:
        print("\n".join([summary(ds), *explained(ds, scene), *events_summary(ds, scene)]))
        print(f"lubecontact: could not write {out}: {err.strerror or err}; the result is lost", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    print("\n".join([summary(ds), *explained(ds, scene), *events_summary(ds, scene)]))
    print(f"wrote {out}")
    if ds.attrs["interrupted"]:
        print(f"lubecontact: interrupted; the series up to t = {ds['time'].values[-1]:.6g} s is in {out} "
              "(converged = 0); --out was not written", file=sys.stderr)
        return EXIT_INTERRUPTED
    if ds["converged"].item() != 1:
        print(f"lubecontact: the transient did NOT converge: {ds.attrs['notes']}", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    return EXIT_OK
