"""``lubecontact.transient(scene)``: the contact along its ``motion:`` (docs/DESIGN.md "Time")."""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import xarray as xr

from lubecontact.model.fluid_film import yield_stress_law
from lubecontact.model.model import Model
from lubecontact.model.monolithic_newton import steady_solve
from lubecontact.model.prepare import prepare
from lubecontact.numerics.blas_threads import one_blas_thread
from lubecontact.physics.yield_stress_flow import creep_squeeze_rate
from lubecontact.scene import SceneError
from lubecontact.unsteady.events import dense_resistance, level_events
from lubecontact.unsteady.integrator import TimeIntegrator, scene_at
from lubecontact.unsteady.motion import SpeedHistory, motion_problems
from lubecontact.unsteady.series import (
    cycle_peaks,
    event_scalars,
    instant,
    level_rows,
    open_resistance,
    reconnect_time,
    series_dataset,
    threshold_times,
    validity_over_time,
)


def _rest_resistance(integrator) -> float:
    """Resistance of the contact at rest: the steady dry solve (no fluid pressure), the
    state every stop settles to, on the mesh its steps end on (the mesh at rest where there
    is one, TimeIntegrator.rest_domain)."""
    if integrator.contact is None:
        return math.inf
    model = integrator.rest_domain()
    if model is None:
        model = Model.assemble(scene_at(integrator.scene, 0.0), integrator.steady_model.mesh, integrator.contact)
    state, _, _ = steady_solve(model)
    integrator.coupled_solves += 1
    return instant(model, state)["contact_resistance"]


# motion.error_bar: the second run's tolerance is this many times tighter. With the local
# error per step held at the tolerance, steps scale as tol^(1/(p+1)) and the global error
# of BDF_p as tol^(p/(p+1)) (Hairer, Norsett & Wanner, "Solving ODEs I", section II.4), so
# for BDF2 the tighter run's error is 10^(-2/3) of the first's, and the first's error is
# (t(tol) - t(tol/10)) / (1 - 10^(-2/3)) (Richardson extrapolation in the tolerance).
ERROR_BAR_TIGHTENING = 10.0
ERROR_ORDER_IN_TOLERANCE = 2.0 / 3.0


def impasse_jumps(levels) -> list[tuple[object, object]]:
    """(level before, level after) of each step that jumped over an impasse at a sealing
    pocket (integrator.Level.impasse, TimeIntegrator.jump_over_impasse)."""
    return [(before, level) for before, level in zip(levels, levels[1:]) if level.impasse]


def impasse_note(jumps) -> str:
    """What a run that jumped over impasses at sealing pockets says (``impasse_jumps``)."""
    return (f"{len(jumps)} impasse jump(s): where a pocket of the film sealed the film's rate had no bound and no "
            "short step continued the state "
            "(docs/physics.md section 14, \"The impasse at a sealing pocket\"), so the pocket's pressure fell to its "
            "neighbours' at once, as the model says, over one first-order step accepted without the error test: "
            + "; ".join(f"t = {before.time:.6g} s over {level.time - before.time:.3g} s (error estimate "
                        f"{level.error:.3g} times the tolerance), a pocket sealing at {level.impasse}"
                        for before, level in jumps)
            + ". A time within such a step is uncertain by its length (longest_impasse_jump)")


def step_back_note(backs, reconnected_at: float) -> str:
    """What a run says whose grease at rest stepped back (integrator.TimeIntegrator.step_backs:
    (time of the dropped level, time returned to), s), "" where it did not: each dropped level
    had passed its own step, yet no step from it converged, so the run went on from the level
    before on another path (docs/DESIGN.md "Time"). The plug pressure such a level holds is
    not known (docs/physics.md section 21), so a time located after the first return
    (``reconnected_at``, absolute, s; NaN: none) is on the path around it."""
    if not backs:
        return ""
    first = min(back for _, back in backs)
    after = (f"the reconnection (t = {reconnected_at:.6g} s) comes before them"
             if math.isfinite(reconnected_at) and reconnected_at <= first else
             "a time located after them is on the path around them: a run at another motion.tolerance "
             "(motion.error_bar) shows whether it moves")
    return (f"{len(backs)} step(s) back at rest: a level of the yield-stress lubricant's film passed its step, "
            "but no step from it converged, so the run dropped it and stepped again from the level before at "
            "half the dropped step (docs/DESIGN.md \"Time\"): "
            + "; ".join(f"the level at t = {dropped:.6g} s, back to {back:.6g} s" for dropped, back in backs)
            + f". {after[0].upper()}{after[1:]}")


def step_tests_note(since: float | None) -> str:
    """What a grease's run says whose steps switched to a Newtonian step's tests
    (integrator.TimeIntegrator.step_tests_from: the time, s; None: they did not), "" otherwise."""
    if since is None:
        return ""
    return (f"from t = {since:.6g} s the grease's steps stalled under the steady tests (solver.tolerance on "
            "the pressure of a near-plug, which its law leaves almost free) at steps shorter than "
            "motion.tolerance needs, so from there on each step is judged first by a Newtonian step's tests "
            "(its film, force and outflow against the step's error weight, docs/physics.md section 20), "
            "the steady ones after; a run at another motion.tolerance (motion.error_bar) shows how far "
            "the times after it move")


def times_within_jumps(jumps, located: dict[str, float]) -> str:
    """What a run says of the times it located (``located``: name -> absolute time, s: the
    reconnection, the events' edges) that fall inside an impasse jump (``impasse_jumps``),
    "" where none does. The state jumped somewhere within such a step, accepted without the
    error test, and the dense output across it is a first-order line through its ends: a
    crossing found on it is known only to lie within the step, not where the root puts it."""
    inside = [f"{name} at t = {t:.6g} s, within the jump from {before.time:.6g} to {level.time:.6g} s"
              for name, t in located.items() for before, level in jumps if before.time < t < level.time]
    if not inside:
        return ""
    return ("located within an impasse jump, so known only to lie somewhere in that step (its length is the "
            "uncertainty): " + "; ".join(inside))


def jumps_before(jumps, instant: float) -> float:
    """Total length (s) of the impasse jumps (``impasse_jumps``) that start before ``instant``
    (an absolute time, s): NaN where ``instant`` is not finite (no reconnection), 0 without a
    jump. Where the state jumped within such a step is not known, so a time after it carries
    its length as uncertainty, as a time within it does (docs/physics.md section 14, "The
    impasse at a sealing pocket")."""
    if not math.isfinite(instant):
        return math.nan
    return float(sum(level.time - before.time for before, level in jumps if before.time < instant))


def jump_share_note(jumped: float, reconnected: float, tolerance: float, moving: float = 0.0) -> str:
    """What a run says whose reconnection comes after impasse jumps of ``jumped`` s in all
    (jumps_before), "" where it need not: below ``tolerance`` (motion.tolerance) of its
    reconnect time ``reconnected`` (s) the jumps at rest are within the accuracy the run was
    asked for. On a crowned Table 1 stop at 51 x 21 with the mesh at rest four times finer a
    jump of 16.7 ms (error estimate 132 times the tolerance) preceded a reconnection 15 ms
    later than the same stop's on the meshes either side of it (bench/EXPERIMENTS.md,
    twenty-eighth session). ``moving`` (s) of them started while the contact still moved
    (before the reconnect clock starts): such a jump skips part of the path that leaves the
    film the rest starts from, so their length bounds nothing, and the run says so whatever
    their share: the 1 Pa s fretting under 20 N on the 51-node line (tests/test_hard_cases.py)
    reconnects 11.7 ms after its stop at motion.tolerance 1e-3 and 5.5 ms at 1e-4, its jumps
    at most 1.0 ms long, its resistance at the stop 51 and 3.3 times the rest's
    (bench/EXPERIMENTS.md, forty-eighth session)."""
    if not (math.isfinite(reconnected) and reconnected > 0.0 and (jumped > tolerance * reconnected or moving > 0.0)):
        return ""
    share = f"reconnect_time comes after impasse jumps of {jumped:.3g} s in all ({100.0 * jumped / reconnected:.2g} % of it)"
    if moving > 0.0:
        return (f"{share}, {moving:.3g} s of them while the contact still moved: a jump in the motion skips part of "
                "the path that leaves the film the rest starts from, so their length does not bound reconnect_time's "
                "uncertainty, which may be many times larger; a run at a tenth of motion.tolerance (motion.error_bar) "
                "measures it (reconnect_time_error)")
    return (f"{share}: the state after a jump is that step's first-order landing, so reconnect_time carries their "
            "length as its uncertainty (reconnect_time_jumps); a run at another motion.tolerance or mesh "
            "(motion.error_bar, motion.mesh_error_bar) shows how far it moves")


def ended_in_a_jump(jumps, levels, reconnected: float) -> str:
    """What a run says whose last step jumped over an impasse (``impasse_jumps``) and which did
    not reconnect (``reconnected`` infinite), "" otherwise: its end is where that jump, a
    first-order step accepted without the error test, landed, not the state's path, so "not
    within the run" may be the jump's, not the contact's (the 20 N grease stop's whole run
    ended so over a jump of 5.9 s, docs/DESIGN.md "Hard cases")."""
    if not (jumps and jumps[-1][1] is levels[-1] and math.isinf(reconnected)):
        return ""
    before, level = jumps[-1]
    return (f"reconnect_time: no reconnection within the run, whose last step jumped over an impasse from "
            f"t = {before.time:.6g} s to its end at {level.time:.6g} s: where the state went within that step is "
            "not known, so neither is whether the contact reconnected there")


# motion.mesh_error_bar: the second run's mesh is twice as fine where a reconnect time's mesh
# error is made (finer_mesh_scene), and the error of the first run is taken as first order in
# the node spacing, e = (t(dx/2) - t(dx)) 2^p / (2^p - 1) with p = 1: the lowest order measured
# on the Table 1 stop (1.0 to 1.7 over the mesh at rest refined 1 to 16 times, line and 51 x 51,
# docs/physics.md section 14, "Error bar of a reconnect time"), so the estimate errs long where
# the convergence is faster.
MESH_ERROR_ORDER = 1.0
# said with every reconnect time whose mesh error was not estimated: on the Table 1 stop it is
# most of the default mesh's error (docs/physics.md section 14, "Error bar of a reconnect time")
MESH_ERROR_UNSEEN = ("reconnect_time is short by the mesh's error, first order in the spacing along x at rest and "
                     "on the Table 1 stop's default mesh most of its error: with motion.mesh_error_bar off it "
                     "is not estimated; on (the default), a second run on a mesh twice as fine estimates it "
                     "(docs/physics.md section 14, \"Error bar of a reconnect time\")")


def tighter_scene(scene):
    """(``scene`` at motion.tolerance / ERROR_BAR_TIGHTENING, that tolerance in words): the
    second run of motion.error_bar, on the same mesh (so its reconnection is timed against
    the first run's resistance at rest)."""
    tolerance = scene.motion.tolerance / ERROR_BAR_TIGHTENING
    motion = dataclasses.replace(scene.motion, tolerance=tolerance)
    return dataclasses.replace(scene, motion=motion), f"motion.tolerance = {tolerance:g}"


def finer_mesh_scene(scene):
    """(``scene`` with the mesh that sets a reconnect time's mesh error twice as fine along x,
    that mesh in words): the mesh at rest (motion.rest_refinement doubled) on the automatic
    domain, the whole mesh (its mesh.nx - 1 cells doubled) on an explicit one, which keeps its
    mesh throughout (TimeIntegrator.rest_domain). The rows stay: on the Table 1 stop 21, 51
    and 101 rows reconnect within 1 % of each other (docs/physics.md section 14)."""
    if scene.mesh.x_min is None:
        refinement = 2 * scene.motion.rest_refinement
        motion = dataclasses.replace(scene.motion, rest_refinement=refinement)
        return dataclasses.replace(scene, motion=motion), f"the mesh at rest twice as fine (motion.rest_refinement = {refinement})"
    nx = 2 * scene.mesh.nx - 1
    return dataclasses.replace(scene, mesh=dataclasses.replace(scene.mesh, nx=nx)), f"{nx} nodes along x (mesh.nx)"


def reconnection_start(history, base) -> float | None:
    """The instant a reconnect time is counted from (s): the later of the motion's rest
    (``history``, SpeedHistory) and the end of the base excitation (``base``,
    BaseExcitation.quiet_from), None where either never comes (no reconnection to time). A
    connector struck by a shock while at rest opens during the shock, not at t = 0: timed
    from t = 0 its reconnect time read 0 for a contact open for 9.3 ms (the shock figure's
    100 g case). None too where that instant is not before the run's end (history.end): a
    stop whose ramp outlasts motion.duration had read "not reconnected" (inf) for a block
    that never came to rest."""
    quiet = base.quiet_from()
    if history.rest_from is None or quiet is None:
        return None
    since = max(history.rest_from, quiet)
    return since if since < history.end else None


def no_reconnection_note(scene, history, base) -> str:
    """Why a run has no reconnection to time (reconnection_start is None), in words."""
    if history.rest_from is None:
        return f"motion.kind = {scene.motion.kind} never comes to rest: there is no reconnection to time"
    quiet = base.quiet_from()
    if quiet is None:
        return (f"motion.vibration = {scene.motion.vibration} shakes the base to the end of the run: there is no "
                "reconnection to time (reconnect_time counts from when the motion and the excitation have ended; "
                "the events give the open intervals)")
    what = (f"the block comes to rest at t = {history.rest_from:.6g} s" if history.rest_from >= quiet else
            f"the half-sine shock ends at t = {quiet:.6g} s")
    return (f"{what}, not before the run ends (t = {history.end:.6g} s): there is no time at rest in which to "
            f"reconnect; lengthen motion.duration so that the run goes on past it")


def second_reconnect_time(scene, history, since: float, progress: bool, rest: float | None = None) -> tuple[float, str]:
    """(reconnect_time of ``scene`` along ``history``, counted from ``since``
    (reconnection_start; NaN if the run fails), why it failed or was interrupted, "" if it
    did not), to ``rest`` times
    motion.reconnect_factor, or to the run's own resistance at rest where ``rest`` is None
    (a finer mesh's, whose resting resistance is its own). The run ends at its first level
    at rest at or below that threshold: reconnect_time is the first crossing, located between
    that level and the one before, so nothing after it can change the answer, and a step that
    fails after it no longer voids the bar. (The CPU saved is small: the steps after a
    reconnection are long. On the Table 1 stop they took 1.6 of the second run's 17 s, and on
    the 10 Pa s grease the bar cost the same either way.) Without a bar
    (``progress``) it reports each decade of simulated time on stderr, as the first run does."""
    integrator = TimeIntegrator(scene, history)
    if rest is None:
        rest = _rest_resistance(integrator)
    threshold = scene.motion.reconnect_factor * rest
    resistances = {}  # level time -> its contact resistance, each level's computed once

    def resistance_of(level) -> float:
        if level.time not in resistances:
            resistances[level.time] = instant(level.model, level.state)["contact_resistance"]
        return resistances[level.time]

    def reconnected(level) -> bool:
        return level.time >= since and resistance_of(level) <= threshold

    levels, failure = integrator.run(progress, report=None if progress else _to_stderr, until=reconnected)
    if failure:
        return math.nan, failure
    times = [lv.time for lv in levels]
    return reconnect_time(times, [resistance_of(lv) for lv in levels], since, threshold, dense_resistance(levels)), ""


def second_run_outcome(value: float, failure: str, what: str) -> str:
    """What a second run (second_reconnect_time: its reconnect time ``value`` and ``failure``)
    gave, in words for the notes; ``what`` is the bar it makes ("mesh error", "error bar")."""
    if not failure:
        return f"{value!r} s there"
    if failure.startswith("interrupted"):
        return f"it was interrupted ({failure}), so no {what} is given"
    return f"it did not converge ({failure}), so no {what} is given"


def mesh_error(value: float, finer: float | None) -> float:
    """The converged reconnect time minus ``value`` (s), estimated from ``finer`` (the run on
    the mesh twice as fine, finer_mesh_scene) at MESH_ERROR_ORDER: positive where the finer
    mesh reconnects later; NaN where either is not finite."""
    if finer is None or not (math.isfinite(value) and math.isfinite(finer)):
        return math.nan
    gain = 2.0**MESH_ERROR_ORDER
    return (finer - value) * gain / (gain - 1.0)


def extrapolated(value: float, error: float) -> float:
    """reconnect_time_extrapolated (s): ``value`` plus its mesh error ``error`` (mesh_error),
    NaN where either is not finite or where the error is as large as the value itself
    (``unextrapolated_note`` says why). A first-order estimate that moves a reconnect time by
    all of it, to zero or below or to twice as long, says that the mesh is outside the range
    where its error is first order: there it extrapolates nothing. Found on the smooth grease
    line stop (stop_grease.yaml, sigma = 0.1 um, 51 x 1): 64.6 s on the mesh, 23.6 s on the
    mesh at rest twice as fine, and -17.5 s extrapolated (thirty-first session)."""
    if not (math.isfinite(value) and math.isfinite(error)) or abs(error) >= value:
        return math.nan
    return value + error


def unextrapolated_note(value: float, finer: float, error: float, finer_words: str) -> str:
    """Why reconnect_time_extrapolated is NaN where both runs reconnected (``value`` this run's,
    ``finer`` the second run's on ``finer_words``, ``error`` the mesh error), said where
    ``extrapolated`` refused them."""
    return (f"reconnect_time_extrapolated = nan: the second run on {finer_words} reconnected at "
            f"{finer:.6g} s against this run's "
            f"{value:.6g} s, a mesh error estimate ({error:+.3g} s) as large as the reconnect time itself: the mesh is "
            "outside the range where its error is first order, so nothing is extrapolated. Refine the mesh where the "
            "film drains (motion.rest_refinement, or mesh.nx on an explicit domain) and run again")


def integration_error(value: float, tighter: float | None) -> float:
    """|value - exact| estimated from ``tighter`` (the run at tolerance / 10), s: NaN where
    either is not finite (no reconnection, a failed run)."""
    if tighter is None or not (math.isfinite(value) and math.isfinite(tighter)):
        return math.nan
    return abs(value - tighter) / (1.0 - ERROR_BAR_TIGHTENING ** -ERROR_ORDER_IN_TOLERANCE)


# the effective medium's exponent and 2-D percolation's (roughness.percolation_exponent): a
# reconnect time run with one is bracketed by a second run with the other
PERCOLATION_ALTERNATIVES = (1.0, 1.3)


def creep_note(levels) -> str:
    """What the bi-viscous regularisation of a grease may cost over the run (docs/physics.md
    section 21), "" for a Newtonian lubricant: a film held at its yield limit thins through
    the thickest film on the domain (its ends) by creep_squeeze_rate, an upper bound, here
    compared with the smallest film of the last instant."""
    last = levels[-1]
    law = yield_stress_law(last.model)
    if law is None:
        return ""
    mesh = last.model.mesh
    thickest, thinnest = float(np.max(last.state.film)), float(np.min(last.state.film))
    rate = creep_squeeze_rate(thickest, 0.5 * float(mesh.x[-1] - mesh.x[0]), law)
    lost = rate * last.time
    return (f"grease creep (bi-viscous regularisation, lubricant.creep_viscosity = {law.creep_viscosity:g} Pa s): a film "
            f"held at its yield limit thins by up to {rate:.2g} m/s, through the thickest film on the domain "
            f"({thickest:.3g} m), so by up to {lost:.2g} m over the {last.time:g} s simulated, {lost / thinnest:.2g} of "
            f"the smallest film ({thinnest:.3g} m){'' if lost < 0.01 * thinnest else ': not negligible; raise lubricant.creep_viscosity'}"
            " (docs/physics.md section 21)")


def band_note(scene, times, rows, reconnected_at: float) -> str:
    """What a reconnect time rests on, "" if nothing beyond the model's ground: when the
    pressurised film drained below h/sigma = 0.5 before the contact reconnected (validity flag
    flow_factor_range), the drain ran through the percolation interpolation (docs/physics.md
    section 15), whose exponent moves the time by tens of per cent there; the note says from
    when, and which run shows how much."""
    if not math.isfinite(reconnected_at):
        return ""
    since = next((t for t, row in zip(times, rows) if "flow_factor_range" in row["validity"]), math.inf)
    if since > reconnected_at:
        return ""
    exponent = scene.roughness.percolation_exponent
    effective_medium, percolation = PERCOLATION_ALTERNATIVES
    other = percolation if exponent == effective_medium else effective_medium
    return (f"reconnect_time rests on the pressure flow below h/sigma = 0.5: the pressurised film drained there from "
            f"t = {since:.4g} s, through the percolation interpolation (roughness.percolation_exponent = "
            f"{exponent:g}, docs/physics.md section 15): run again with the exponent at {other:g} to see how much")


# said with a reconnect time of 0, whose error bars are 0 without a second run
AT_ONCE = ("reconnect_time = 0: the contact was within motion.reconnect_factor x rest_resistance when the motion and "
           "the excitation ended, so nothing drains, on any mesh or at any tolerance: no second run was made and "
           "its error bars are 0")


def error_bars(scene, history, since, rest: float, recon: float, failure: str, progress: bool) -> tuple[dict, list[str]]:
    """The error bars of ``recon`` (the run's reconnect_time, s, counted from ``since``; ``rest``
    its resistance at rest) that ``scene`` asks for (motion.error_bar, motion.mesh_error_bar):
    their scalars and notes. A second run is made only where the run converged (``failure``
    empty) and reconnected after some time. One that reconnected at once (``recon`` = 0) has
    bars of 0: a shock that never opened the contact had read "the mesh error as large as the
    reconnect time" (thirty-first session). One that did not reconnect has NaN bars."""
    motion = scene.motion
    scalars, notes = {}, []
    if recon == 0.0 and (motion.error_bar or motion.mesh_error_bar):
        if motion.error_bar:
            scalars["reconnect_time_error"] = 0.0
        if motion.mesh_error_bar:
            scalars |= {"reconnect_time_mesh_error": 0.0, "reconnect_time_extrapolated": 0.0}
        return scalars, [AT_ONCE]
    run_again = math.isfinite(recon) and not failure

    def second_run(second_scene, where: str, bar: str, what: str, rest_of_run: float | None):
        """The reconnect time of ``second_scene`` (``where`` in words) for ``bar`` (its key's
        words), said on stderr and in the notes as ``what`` it gives."""
        _to_stderr(f"{bar}: a second run {where}")
        with one_blas_thread():
            value, why = second_reconnect_time(second_scene, history, since, progress, rest_of_run)
        notes.append(f"reconnect_time {what} from a second run {where}: " + second_run_outcome(value, why, what))
        return value

    if motion.error_bar:
        tight = None
        if run_again:
            tighter, words = tighter_scene(scene)
            tight = second_run(tighter, f"at {words}", "error bar", "error bar", rest)
        scalars["reconnect_time_error"] = integration_error(recon, tight)
    if motion.mesh_error_bar:
        finer = None
        if run_again:
            finer_scene, words = finer_mesh_scene(scene)
            finer = second_run(finer_scene, f"on {words}", "mesh error bar", "mesh error", None)
        error = mesh_error(recon, finer)  # finite only where both runs reconnected
        scalars |= {"reconnect_time_mesh_error": error, "reconnect_time_extrapolated": extrapolated(recon, error)}
        if math.isfinite(error) and math.isnan(scalars["reconnect_time_extrapolated"]):
            notes.append(unextrapolated_note(recon, finer, error, words))
    elif math.isfinite(recon) and recon > 0.0:
        notes.append(MESH_ERROR_UNSEEN)
    return scalars, notes


def _to_stderr(line: str) -> None:
    print(f"lubecontact: transient {line}", file=sys.stderr, flush=True)


def transient(scene, progress: bool | None = None) -> xr.Dataset:
    """Integrate ``scene``'s motion in time; returns the Dataset along ``time`` (s).

    The run starts from the steady state at the motion's initial speed and keeps the
    cylinder in force balance at every instant (integrator.py). ``progress``: a bar on
    stderr (default: when stderr is a terminal); without it a line on stderr per decade of
    simulated time. A step that fails ends the run, and so does an interruption (Ctrl-C, or
    SIGTERM where the caller turns it into KeyboardInterrupt): the levels so far are
    returned with ``converged = 0``, the reason in ``notes`` and, when interrupted, the
    attribute ``interrupted = 1``. A run that converged and reconnected runs again for its
    error bars: on the mesh at rest twice as fine by default (motion.mesh_error_bar, which gives
    reconnect_time_extrapolated), and at a tenth of the tolerance (motion.error_bar).
    """
    scene = prepare(scene).scene
    problems = motion_problems(scene)
    if problems:
        raise SceneError("scene", problems)
    history = SpeedHistory.from_scene(scene)
    if progress is None:
        progress = sys.stderr.isatty()

    with one_blas_thread():  # one BLAS thread, as solve()
        integrator = TimeIntegrator(scene, history)
        levels, failure = integrator.run(progress, report=None if progress else _to_stderr)
        rest = _rest_resistance(integrator)
    since = reconnection_start(history, integrator.base)
    threshold = open_resistance(scene)
    series_t = np.array([lv.time for lv in levels])
    notes = []
    if failure:
        notes.append("NOT CONVERGED: " + failure)
    if since is None:
        notes.append(no_reconnection_note(scene, history, integrator.base))
    scalars = {
        "rest_resistance": rest,
        "open_resistance": threshold,
        "converged": int(not failure),
        "steps": len(levels) - 1,
        "rejected_steps": integrator.rejected,
        "coupled_solves": integrator.coupled_solves,
        "solve_time": integrator.wall_time,
    }
    jumps = impasse_jumps(levels)
    scalars["impasse_jumps"] = len(jumps)
    scalars["longest_impasse_jump"] = max((level.time - before.time for before, level in jumps), default=0.0)
    if jumps:
        notes.append(impasse_note(jumps))
    scalars["step_backs"] = len(integrator.step_backs)
    rows = level_rows(levels)
    resistance = np.array([row["contact_resistance"] for row in rows])
    dense = dense_resistance(levels)
    reconnect_threshold = scene.motion.reconnect_factor * rest  # ohm
    reconnected = {"reconnect_time": reconnect_time(series_t, resistance, since, reconnect_threshold, dense)}
    reconnected |= threshold_times(series_t, resistance, since, reconnect_threshold, dense)
    if failure:  # the run ended early: "not within duration" is unknown
        reconnected = {name: math.nan if math.isinf(value) else value for name, value in reconnected.items()}
    scalars |= reconnected
    recon = reconnected["reconnect_time"]
    bars, bar_notes = error_bars(scene, history, since, rest, recon, failure, progress)
    scalars |= bars
    notes += bar_notes
    # discontinuity events above the open resistance and above reconnect_factor x rest: the
    # reconnected state of reconnect_time is the end of a relative event (docs/DESIGN.md "Time")
    min_duration = scene.interface.min_event_duration
    opened = level_events(levels, resistance, threshold, min_duration)
    relative = level_events(levels, resistance, reconnect_threshold, min_duration)
    scalars |= event_scalars(opened, relative)
    reconnected_at = math.nan if since is None else since + recon  # s since t = 0
    if since is not None:
        scalars["reconnect_time_jumps"] = jumps_before(jumps, reconnected_at)
        shared = jump_share_note(scalars["reconnect_time_jumps"], recon, scene.motion.tolerance,
                                 moving=jumps_before(jumps, since))
        if shared:
            notes.append(shared)
    backs = step_back_note(integrator.step_backs, reconnected_at)
    if backs:
        notes.append(backs)
    switched = step_tests_note(integrator.step_tests_from)
    if switched:
        notes.append(switched)
    located = {"the reconnection": reconnected_at} if math.isfinite(recon) else {}
    for k, event in enumerate(opened.events, start=1):
        located |= {f"event {k}'s start": event.start, f"event {k}'s end": event.end}
    inside = times_within_jumps(jumps, located)
    if inside:
        notes.append(inside)
    unreached = ended_in_a_jump(jumps, levels, recon)  # "" without a rest too: recon is NaN there
    if unreached:
        notes.append(unreached)
    peaks = None
    fraction = math.nan
    if history.period is not None:
        oscillating = history.period * scene.motion.cycles
        fraction = opened.open_time_until(oscillating) / oscillating
        peaks = cycle_peaks(series_t, resistance, history.period, scene.motion.cycles)
    scalars["open_fraction"] = fraction
    creep = creep_note(levels)
    if creep:
        notes.append(creep)
    notes.append(f"open threshold {threshold:g} ohm (interface.open_resistance, default {threshold:g})")
    notes.append(f"cavitation: {scene.effects.cavitation} (Swift-Stieber is not mass-conserving where a film re-forms)")
    band = band_note(scene, series_t, rows, reconnected_at)  # "" without a reconnection
    if band:
        notes.append(band)
    series = series_dataset(scene, series_t, rows, scalars, "; ".join(notes), peaks, opened)
    series.attrs["interrupted"] = int(failure.startswith("interrupted"))
    series.attrs["validity"], series.attrs["validity_notes"] = validity_over_time(series_t, rows)
    return series
