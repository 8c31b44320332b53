"""The coupling loop of one operating point (paper section 2.5, Fig. 1): force balance and
deformation iterated to convergence, started from the solution on a coarser mesh.

Algorithm (only the enabled effects are assembled and run):
0. Nested iteration: with asperity contact, the same problem is first solved on the mesh
   with every other node (recursively, loosely), and the fine mesh starts from its
   position, deformation and cavitated zone (``nested_start``).
1. For the current deformation, find z with the force balance satisfied
   (model/force_balance.py: safeguarded Newton on the total force, bisection once
   bracketed; the contact law has a jump at 1.9 omega_c).
2. Recompute the deformation from the pressures at that z and take a Newton step of the
   fixed point delta -> K(p + p_c) (model/newton.py): with Reynolds fluid pressure between
   rough surfaces the coupled step with the fluid's stiffness, shortened by backtracking
   near a fold where full steps cycle between cavitated sets; otherwise the contact Newton
   step accelerated by Anderson mixing. The next z is predicted to first order from the
   load gradient. Stop when the change is below ``tolerance`` times the deformation's range;
   in a time step, when it is below a tenth of the step's error weight at every node
   (Model.squeeze.settled, unsteady/integrator.py).
Every solve reports its residuals and a ``converged`` flag; nothing is silently accepted.
The discrete coupled problem can have more than one converged solution at some hard points
(very smooth surfaces on coarse meshes, where the fluid load jumps as the contact edge
crosses nodes; 500 N at 10 m/s, a fluid-lifted and a contact-carried branch): which one a
solve finds then depends on its start.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lubecontact.model.force_balance import balance_force, predicted_position
from lubecontact.model.model import Model, SolveError, State
from lubecontact.model.newton import Backtracking, contact_newton_step, coupled_newton_step
from lubecontact.numerics.anderson import AndersonMixer
from lubecontact.numerics.transfer import interpolate_field
from lubecontact.physics.flow_factors import ClosedFilmError


@dataclass
class WarmStart:
    """Where a coupled solve starts (None: from scratch): the cylinder position z (m) and the
    deformation delta (m, (ny, nx) of the model's mesh), and optionally the force stiffness
    dF/dz (N/m), the cavitated set, the fluid pressure (Pa) and, with JFO cavitation, the
    film content theta of a previous solution."""

    z: float | None = None
    delta: np.ndarray | None = None
    stiffness: float | None = None
    cavitated: np.ndarray | None = None
    pressure: np.ndarray | None = None
    content: np.ndarray | None = None


@dataclass
class Diagnostics:
    """How a coupled solve ended: outer iterations, the last deformation change (m), force
    residual (N), Reynolds residual (relative), whether every test was met, the force
    stiffness dF/dz (N/m), the failure message ("" when none) and the continuation that
    reached the point ("" when the solve started there: monolithic_newton.solve_level)."""

    iterations: int
    deformation_residual: float
    force_residual: float
    reynolds_residual: float
    converged: bool
    stiffness: float | None
    failure: str
    path: str = ""


def deformation_stepper(model: Model):
    """(step function, AndersonMixer or None) of the coupled iteration's deformation update.

    With Reynolds fluid pressure between rough surfaces, and in every transient step (its
    squeeze stiffness dwarfs the rest), the coupled Newton step (fluid and contact
    stiffness, newton.py); otherwise the contact Newton step: dry contact; JFO cavitation,
    whose content unknowns the step does not linearise; no cavitation (full Sommerfeld: the
    coupled steps did not converge on test_effects' scene); smooth steady films, where
    k ~ h^3 makes full Newton steps overshoot to h <= 0 (elastohydrodynamic line contacts,
    test_lubricated). Anderson mixing picks up what the contact step leaves out, and damps
    the transient's steps as before; a steady coupled Newton step is taken as it is (mixing
    it costs iterations: 5 -> 6-8 on Table 1), until it stalls (NEWTON_STALL_FACTOR): then
    it is shortened by backtracking, and where that fails too the mixed contact step takes over.
    """
    rough_reynolds = model.contact is not None and model.scene.effects.cavitation == "reynolds"
    coupled = model.hydrodynamic and model.deformation is not None and (model.squeeze is not None or rough_reynolds)
    mixer = None if coupled and model.squeeze is None else AndersonMixer(beta=1.0)
    return (coupled_newton_step if coupled else contact_newton_step), mixer


# Newton steps cut the deformation change by far more than this factor per iteration. After
# NEWTON_STALL_ITERATIONS iterations in a row that do not cut the smallest change so far by
# it, the coupled Newton iteration has stalled: its steps are then shortened by backtracking
# (newton.Backtracking), and where no shorter step lowers the change it starts again with
# the mixed contact step (coupled_solve). One worse step is no stall: far from the solution
# (a cold start on the coarsest mesh) Newton's change can grow once before it falls.
NEWTON_STALL_FACTOR = 0.5


NEWTON_STALL_ITERATIONS = 3


# A time step's mixed iteration (Anderson, not monotone) that has not halved its smallest
# deformation change in this many iterations has stalled: the step fails there and the
# integrator retries it shorter, instead of running to solver.max_iterations. A steady solve
# keeps going: it has no shorter step to retry. Chosen by the cost it gives, measured on the
# Table 1 stop from 1 m/s (bench/transient.py, 0.1 s, one core, CPU s; bench/EXPERIMENTS.md):
#   limit        none   100    50    30    20
#   71 x 71      99.0  59.7  31.0  28.9  20.4
#   101 x 101   118.0 104.5  70.3 216.0 153.5
# (30 and 100 run two at a time). Without a limit each mesh has two steps that do not
# converge in solver.max_iterations (200), but on 101 x 101 others converge after 51 to 106
# iterations (71 x 71: at most 30): a limit below ~50 cuts them, and their retries take a
# longer path (99 steps and 30 rejected against 76 and 19). The reconnect time moves within
# the time tolerance: 12.193 ms on 71 x 71 at every limit, 12.709 / 12.744 / 12.799 ms on
# 101 x 101 (none, 50, 20).
STEP_STALL_ITERATIONS = 50

# A time step's mixed iteration cycles when the last CYCLE_REPEATS periods of its relative
# deformation change each repeat the value one period earlier within CYCLE_TOLERANCE, for a
# period of 1 to MAX_CYCLE_PERIOD iterations: the cavitated set flips between the same states
# and the iteration does not end, so the step fails there, as at a stall, cheaply. A change of
# the same size again (a period of 1) is a cycle only where each change turns back on the one
# before (the state alternating between two); one that keeps its direction is a drift, which
# may still end, and waits for the stall test.
# Traced on the Table 1 stop's 101 x 21 member of the accuracy study (bench/EXPERIMENTS.md,
# eighteenth session): each of its 15 failed step solves ran 51-59 iterations (3-5 s), most
# of them cycling with a period of 2 or 4 from iteration 12-32, and the 51 x 51 member at 5e-4
# stalled after 83 iterations alternating between two states (changes of 0.882 and 0.887 of
# the deformation's range, each at a cosine of -0.86 to the one before). On the figure
# build's seven costliest stops (952 step solves) and the 101 x 101 stop the paths stay the
# same step for step (no solve that would converge is cut), and the seven's CPU time fell
# from 198 to 131 s (65 to 28 s on the 101 x 21 member, 18 to 15 s on that 51 x 51 one).
MAX_CYCLE_PERIOD = 6
CYCLE_REPEATS = 2
CYCLE_TOLERANCE = 0.02


def cycle_period(changes: list[float], turns: list[bool]) -> int:
    """The period, in iterations, with which the last values of ``changes`` (an iteration's
    relative changes, newest last) repeat; 0 where they do not, or where they repeat with a
    period of 1 while the changes keep their direction (``turns``: whether each change turned
    back on the one before, its cosine with it negative), a drift."""
    values = np.asarray(changes, dtype=float)
    for period in range(1, MAX_CYCLE_PERIOD + 1):
        span = CYCLE_REPEATS * period
        if len(values) < span + period:
            break
        recent, earlier = values[-span:], values[-span - period:-period]
        if np.all(np.abs(recent - earlier) <= CYCLE_TOLERANCE * recent):
            return period if period > 1 or all(turns[-span:]) else 0
    return 0


# While the deformation is still far from converged, the force balance need not be exact:
# the inner tolerance follows the outer progress (an inexact Newton-type schedule) and is
# tightened to ``solver.tolerance`` for the final iterate.
INEXACT_BALANCE_FACTOR = 0.1


LOOSEST_BALANCE_TOLERANCE = 1e-3


# Nested iteration (coarse-to-fine start). From a cold start the first force balances move
# the cylinder by many film thicknesses and the cavitation boundary by many nodes, each
# evaluation a Reynolds solve of several factorisations. So a cold start first solves the
# same problem on the mesh with every other node (recursively, down to NESTED_COARSEST
# nodes a side) to NESTED_TOLERANCE (the levels differ by their discretisation error
# anyway) and starts from its position, deformation, cavitated zone and force stiffness.
# The fine mesh is then solved by the same stopping tests to the scene's tolerance, so the
# answer is that of a cold start within the tolerance (where the discrete problem has one
# solution: see the module docstring). Only with asperity contact: a smooth film needs
# h > 0 at every node, and a coarse mesh may not resolve the thin film a fine one carries
# the load on (Martin's rigid cylinder needs thousands of nodes), so smooth films start cold.
NESTED_COARSEST = 26


NESTED_TOLERANCE = 1e-3


def is_fine_warm_start(model: Model, initial: WarmStart | None) -> bool:
    """Whether ``initial`` is a converged solution on this very mesh (a sweep's previous
    point): it is then a better start than a coarse-mesh solve, which is skipped. A 26-speed
    Table 1 sweep at 51^2 then costs 0.65-0.7 of 26 cold solves instead of 0.96, with the
    same answers to 2e-7 (the sweep row of bench/run.py)."""
    return initial is not None and initial.delta is not None and np.size(initial.delta) == model.mesh.nx * model.mesh.ny


def nested_start(model: Model, tolerance: float, initial: WarmStart | None = None) -> WarmStart | None:
    """``initial`` of coupled_solve on ``model``'s mesh: the solution on the coarser mesh,
    itself started from ``initial`` (a warm start, interpolated to it) and so on down to
    the coarsest mesh, where ``initial`` is used as it is.

    Without a coarser mesh, with a warm start on this mesh (``is_fine_warm_start``), or when a
    coarse level does not converge or cannot bracket its force balance, ``initial`` is
    returned: the fine mesh then starts from it and is judged on its own.
    """
    coarse = model.coarsened(NESTED_COARSEST) if model.contact is not None else None
    if coarse is None or is_fine_warm_start(model, initial):
        return initial
    coarse_initial = None
    if initial is not None:
        coarse_initial = WarmStart(z=initial.z, stiffness=initial.stiffness)
        if initial.delta is not None:
            delta = np.asarray(initial.delta, dtype=float).reshape(model.mesh.shape)
            coarse_initial.delta = interpolate_field(delta, model.mesh, coarse.mesh)
    try:
        state, diag = coupled_solve(coarse, coarse_initial, tolerance=max(tolerance, NESTED_TOLERANCE))
    except SolveError:
        return initial
    if not diag.converged:
        return initial
    start = WarmStart(z=state.z, delta=interpolate_field(state.delta, coarse.mesh, model.mesh), stiffness=diag.stiffness)
    if state.reynolds is not None:
        pressure = interpolate_field(state.fluid_pressure, coarse.mesh, model.mesh)
        start.cavitated = pressure <= 0.0
        start.pressure = pressure  # smoothed on the fine mesh (Reynolds cavitation)
    return start


def coupled_solve(model: Model, initial: WarmStart | None = None, tolerance: float | None = None,
                  max_iterations: int | None = None, stall_iterations: int | None = None) -> tuple[State, Diagnostics]:
    """Iterate force balance and deformation to convergence; returns the state and diagnostics.

    ``initial``: the WarmStart to start from (None: cold); either way the fine mesh starts from the nested (coarse-mesh) solution
    where there is one (nested_start). ``tolerance`` and ``max_iterations`` override the scene's,
    ``stall_iterations`` a time step's STEP_STALL_ITERATIONS.
    """
    scene = model.scene
    if scene.lubricant.rheology != "newtonian":
        raise SolveError(f"lubricant.rheology = {scene.lubricant.rheology!r}: the nested solver's Reynolds solve takes a "
                         "coefficient independent of the pressure; a grease is solved by one Newton "
                         "(model/monolithic_newton.py, docs/physics.md section 21)")
    tol = scene.solver.tolerance if tolerance is None else tolerance
    force = scene.operating.force
    max_iterations = scene.solver.max_iterations if max_iterations is None else max_iterations
    initial = nested_start(model, tol, initial)
    delta = np.zeros(model.mesh.shape)
    z = stiffness = cavitated = reynolds = pressure_guess = None
    if initial is not None:
        if model.deformation is not None and initial.delta is not None:  # a rigid model has no deformation
            delta = np.array(initial.delta, dtype=float).reshape(model.mesh.shape)
        z, stiffness = initial.z, initial.stiffness
        cavitated, pressure_guess = initial.cavitated, initial.pressure
    deformation_step, mixer = deformation_stepper(model)
    smallest_change, stalled = np.inf, 0
    changes, turns, last_change = [], [], None  # a time step's deformation changes (cycle_period)
    restart = (delta.copy(), z, stiffness, cavitated, pressure_guess)
    change = 0.0
    balance_tol = tol if model.deformation is None else LOOSEST_BALANCE_TOLERANCE
    deformation_converged = False
    failure = ""
    iteration = 0
    backtracking = None  # Backtracking of the coupled Newton steps once they stall
    state = None  # the last state evaluated
    try:
        for iteration in range(1, max_iterations + 1):
            state, stiffness = balance_force(model, delta, z, balance_tol, stiffness, cavitated, reynolds,
                                             pressure_guess)
            z, pressure_guess = state.z, None
            if state.reynolds is not None:
                cavitated, reynolds = state.reynolds.cavitated, state.reynolds
            if model.deformation is None:
                deformation_converged = True
                break
            new_delta = model.deformation(state.total_pressure)
            correction = new_delta - delta  # what the fixed point asks of the deformation, m
            change = float(np.max(np.abs(correction)))
            relative_change = change / max(float(np.ptp(new_delta)), 1e-15)
            if (relative_change <= tol if model.squeeze is None
                    else model.squeeze.settled(state.film, correction)):
                deformation_converged = True
                break
            if backtracking is not None:
                fraction = backtracking.retry(relative_change)
                if fraction is not None:  # too little decrease: a shorter step from the anchor
                    anchor, _, anchored_step, anchored_state = backtracking.anchor
                    delta = anchor + fraction * anchored_step
                    z = predicted_position(anchored_state, force, fraction * anchored_step)
                    continue
            balance_tol = max(tol, min(LOOSEST_BALANCE_TOLERANCE, INEXACT_BALANCE_FACTOR * relative_change))
            if relative_change <= NEWTON_STALL_FACTOR * smallest_change:
                smallest_change, stalled = relative_change, 0
            else:
                stalled += 1
            if mixer is not None and model.squeeze is not None:  # a time step: it fails where it cycles or stalls
                turns.append(last_change is not None and float(np.dot(correction.ravel(), last_change)) < 0.0)
                changes.append(relative_change)
                last_change = correction.ravel()
                period = cycle_period(changes, turns)
                if period:
                    how = (f"cycles with a period of {period} iterations" if period > 1 else
                           "alternates between two states (each change turns back on the one before)")
                    failure = f"the time step's deformation iteration {how}: its relative change repeats at {relative_change:.3g}"
                    break
                if stalled >= (STEP_STALL_ITERATIONS if stall_iterations is None else stall_iterations):
                    failure = (f"the time step's deformation iteration stalled: its relative change has not halved "
                               f"in {stalled} iterations (now {relative_change:.3g}, smallest {smallest_change:.3g})")
                    break
            if mixer is None and stalled >= NEWTON_STALL_ITERATIONS:
                if backtracking is None:
                    # the coupled Newton steps stalled: near a fold the cavitated set can
                    # toggle between two states (Table 1, 51^2, 0.0158 m/s: 650 <-> 654
                    # nodes) and full steps cycle. From here each step is shortened until
                    # the deformation change falls (newton.Backtracking).
                    backtracking = Backtracking()
                elif backtracking.exhausted:
                    # no shorter step helps either (between a contact- and a fluid-carried
                    # branch, Fig. 8, F = 20 N, 0.158 m/s). Start again from this level's
                    # start with the mixed contact step (deformation_stepper), the iteration
                    # that converged there before the Newton step existed; from where
                    # Newton stalled it can wander instead (Fig. 12, F = 30 N: 200 iterations)
                    deformation_step, mixer, backtracking = contact_newton_step, AndersonMixer(beta=1.0), None
                    delta, z, stiffness, cavitated, pressure_guess = restart[0].copy(), *restart[1:]
                    reynolds, balance_tol = None, LOOSEST_BALANCE_TOLERANCE
                    continue
            step = deformation_step(model, state, correction)
            if backtracking is not None:
                backtracking.accept(delta, relative_change, step, state)
            new_delta = delta + step if mixer is None else mixer.step(delta, delta + step)
            z = predicted_position(state, force, new_delta - delta)
            delta = new_delta
        if abs(force - state.total_force) > tol * force:  # last inner solve was inexact
            state, _ = balance_force(model, state.delta, state.z, tol, stiffness, cavitated, reynolds)
    except SolveError as err:  # reported as not converged, with the last state evaluated
        if err.state is None:
            raise
        state, failure = err.state, str(err)
    except ClosedFilmError as err:  # a smooth film closed at a node: the last state evaluated
        if state is None:
            raise SolveError(str(err)) from err
        failure = str(err)
    reynolds_ok = state.reynolds is None or bool(state.reynolds.converged)
    force_residual = force - state.total_force
    diagnostics = Diagnostics(
        iterations=iteration,
        deformation_residual=change,
        force_residual=force_residual,
        reynolds_residual=0.0 if state.reynolds is None else float(state.reynolds.residual),
        converged=not failure and deformation_converged and reynolds_ok and abs(force_residual) <= tol * force,
        stiffness=stiffness,
        failure=failure,
    )
    return state, diagnostics
