"""Implicit time integration of the lubricated contact (docs/physics.md section 14).

At each instant the cylinder is in force balance: F = F_contact(h) + F_fluid, F the
applied force (constant, or that of a contact with mass and spring, unsteady/dynamics.py),
where the fluid pressure solves the averaged Reynolds equation with the squeeze term,

    div(k grad p) = (U/2) dh_T/dx + dh_T/dt,

so the film h(x, y, t) is the state. dh_T/dt at the new time level is the variable-step
BDF2 difference (BDF1 on the first step and after a breakpoint of the motion)

    dh_T/dt ~ c0 h_T^{n+1} + c1 h_T^n + c2 h_T^{n-1}    (Squeeze.rate),

which enters the Reynolds right-hand side as a nodal source and, through c0, the load
sensitivity, so Newton on z keeps its quadratic convergence. Each step is one coupled
solve (step_solve: one Newton on a line contact, the nested solve where it fails; the nested
solve and one Newton where it fails on a 2-D mesh) warm-started from the extrapolated film of
the last steps.

Error control (Milne's device): the film predicted by polynomial extrapolation through the
last p + 1 levels and the BDF_p result differ by (P_p - D_p/c0) h^{(p+1)}, of which the
BDF's local error is -D_p/c0 h^{(p+1)}; both constants are computed for the actual steps
(error_fraction). A step is accepted when that estimate, node by node relative to
``tolerance`` times max(|h|, floor) (floor: sigma with roughness, FILM_FLOOR without), has
a root mean square over the nodes below 1 (the weighted RMS norm of ODE codes such as
SUNDIALS: a sharp change in one node's history does not force the whole contact to tiny
steps), or with motion.error_norm = max its largest below 1 (step_error: the RMS of one
node's error falls as the mesh refines, the largest does not), and the
next step is scaled by 0.9 E^{-1/(p+1)} within [SHRINK, GROWTH]: steps are short while the
film moves and grow geometrically (log-spaced) as it settles. A step rejected twice from one
level is scaled by the order its two estimates show instead (rejection_factor: a kink within
the step, a pocket sealing, makes the estimate fall as dt). Steps land on the motion's
breakpoints. A step's coupled solve stops on the same weight: its last film correction
below NONLINEAR_FRACTION of it at every node (Squeeze.settled, docs/physics.md section 14).
Where a pocket of the film seals, the state jumps (an impasse of the model): a step over it
is accepted without the error test, and said (TimeIntegrator.jump_over_impasse).

Cavitation is Swift-Stieber (reynolds.solve_reynolds), as in the steady model, which does
not conserve mass where a film re-forms, or mass-conserving (JFO, effects.cavitation: jfo;
each step one Newton: numerics/jfo_outflow.py), whose cells hold theta times
their content: the levels then carry theta c (held_content), and the squeeze term
differentiates that.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from lubecontact.model.coupling import Diagnostics, WarmStart, coupled_solve
from lubecontact.model.fluid_film import FLUID_FILM_FLOOR_SIGMAS, squeeze_content, yield_stress_law
from lubecontact.model.model import Model, SolveError
from lubecontact.model.monolithic_newton import (KeptPreconditioner, dense_step_serves, monolithic_solve, needs_newton,
                                                steady_solve)
from lubecontact.numerics.cavitation_jfo import JFOSolution
from lubecontact.numerics.mesh import build_mesh, mirrored_mesh, rest_mesh
from lubecontact.numerics.transfer import interpolate_field, spline_along_x
from lubecontact.unsteady.dynamics import BaseExcitation, Dynamics
from lubecontact.unsteady.motion import MAX_STEPS

FIRST_STEP = 1.0e-9  # s: first step from the steady start (with a mass at least Dynamics.shortest_step)
GROWTH, SHRINK, SAFETY = 4.0, 0.2, 0.9  # step-size controller limits
FILM_FLOOR = 1.0e-10  # m: error floor of a smooth film (relative error above it)
MIN_STEP = 1.0e-15  # s: below this a failing step ends the run, flagged
# Coupled solves that fail in a row before the run gives up, flagged, with what it computed:
# each failure quarters the step (4^6 = 4096 times shorter), and a step that six shorter
# attempts cannot pass is stuck (a shorter step makes the squeeze film stiffer, not easier).
MAX_FAILED_IN_A_ROW = 6
# A coupled solve that fails on a step shorter than motion.tolerance times the step the error
# test last asked for (after a step none of whose attempts failed its solve) ends the run: such a step changes
# the solution by less than the tolerance allows of one step, so shortening it further is not
# for accuracy, and it only stiffens the squeeze film (mu/dt): what failed is the solver, and
# the run stops there cheaply instead of creeping on (issue 27: the R = 5 mm stop at 51 x 51).
# With a yield-stress lubricant at rest (after the motion's stop), a coupled solve that failed
# on a step L grown beyond the last accepted one, whose retry at L/4 then passed (a step grown
# too far), bounds the next steps: they stay below half the shortest such L, and that bound
# doubles once its patience of accepted steps have reached it (StepCeiling). There the plug leaves the
# pressure undetermined as the squeeze term weakens (c0 ~ 1/dt): without the bound a step grown
# fourfold from one that passed failed again, from 1 ms to 5 s (29 failed solves of 107 on
# the Bingham stop, three quarters of its time). Where the shorter retry fails too, the
# failure was not the step's length (a stiff squeeze film also fails at short steps: the
# 10 Pa s oscillation of tests/test_hard_cases.py crept into failure so), nor in motion
# (the 100 Pa s fretting did), nor with a Newtonian film: bounded so, the 201 x 21 Table 1
# stop of the accuracy study failed at t = 10.6 ms, where the tight line stop meets the
# impasse of a sealing pocket (docs/DESIGN.md "Hard cases", tight stop to its reconnect).
# A step's coupled solve has converged when its last film correction is below this fraction
# of the step's error weight at every node (Squeeze.settled): the nonlinear error then adds at
# most a tenth of the tolerance to the step's local error. SUNDIALS' CVODE takes the same
# fraction (its nonlinear convergence coefficient, 0.1; Hindmarsh et al. 2005, ACM TOMS
# 31:363, section 2.1).
NONLINEAR_FRACTION = 0.1
# A line contact's step answered by one Newton alone (step_solve) stops at this fraction instead:
# two decades further, one or two more Newton iterations where it converges quadratically. The
# nested solve that used to polish that answer (at most 10 iterations: its Reynolds solves are
# exact, so each cell's volume balance closed to round-off) cost more than the Newton where it
# failed to converge: 10 of the 15 s of the 100 Pa s fretting on the 51-node line
# (tests/test_hard_cases.py). Without it, at a tenth, the unpolished answers' noise made the
# error test reject steps: the 31-node Table 1 stop at motion.tolerance 1e-4 took 218 steps
# and 127 rejections against 126 and 39 polished (123 and 36 here). At a hundredth the
# answers' bias added up over a long, slow squeeze: the 10 Pa s smooth line stop (README's
# reconnect table, sigma = 0.1 um, 51 x 1) reconnected at 73.6 s against 65.0 s at
# motion.tolerance 1e-4, where the polished run gave 66.7 s; here 67.5 s
# (bench/EXPERIMENTS.md, forty-third session).
LINE_NEWTON_FRACTION = 0.001
# Where a line step's Newton fails, the nested solve that answers it (step_solve) fails, as a
# stall, once its deformation iteration has not halved its change in this many iterations,
# not the 2-D primary's 50 (model/coupling.STEP_STALL_ITERATIONS): the step is then retried
# shorter. Measured in the forty-fifth session (bench/EXPERIMENTS.md): on the three
# line cases (bench/solver_core.py) every such nested solve that converged took at most 18
# iterations, and three on the 100 Pa s fretting stalled after 60 to 70 iterations, 2.9 of
# its 8.0 s; at 20 the fretting took 6.4-7.7 s against 8.7-9.3 s (three alternated runs each)
# with the same steps and resistance to the last bit, as did the 15 Newtonian line transients
# of the hard-case suite and the Table 1 line stops at motion.tolerance 1e-4; at 10 the 20 N
# stop took another path.
LINE_FALLBACK_STALL_ITERATIONS = 20
# Steps tried over an impasse at a sealing pocket (TimeIntegrator.jump_over_impasse), each
# four times the last: up to 4096 times the step the error test last asked for. Measured on the
# Table 1 line stop at motion.tolerance 1e-5 (31 to 51 nodes) and the R = 5 mm stop at
# 51 x 51: the first to third converged (bench/EXPERIMENTS.md, seventeenth session).
IMPASSE_PROBES = 6
# What a step that is not tried says (TimeIntegrator.run): where a pocket seals, the one Newton
# follows its film to the kink (its complementarity measures a sealed cell's outflow as a film
# change, integrator.Squeeze.outflow_scale_floor), and there the film's rate has no bound
# (docs/physics.md section 14): the error test asks for ever shorter steps, down to 1e-13 s on
# the tight stop of tests/test_hard_cases.py, which crept so for minutes. A step shorter than
# motion.tolerance times the longest the error test asked for since the motion last changed is
# not needed for accuracy (as after a failed solve, MAX_FAILED_IN_A_ROW): there the run jumps
# over the impasse, or stops and says why.
CREEPING = ("the steps creep towards a sealing pocket's kink, where the film's rate has no bound; "
            "no step was tried")


@dataclass
class Squeeze:
    """dh_T/dt at the new time level as a function of its h_T (model/model.Model.squeeze)."""

    coefficient: float  # c0, 1/s
    history: np.ndarray  # c1 h_T^n + c2 h_T^{n-1}, m/s
    film_scale: float  # m, a length on which the force changes (model/evaluation.film_scale)
    tolerance: float  # motion.tolerance: the step's relative local error
    floor: float  # m: the film below which the error weight stays absolute (sigma, or FILM_FLOOR)
    fraction: float = NONLINEAR_FRACTION  # of the error weight at which a step's solve stops
    # a grease's step retried with a Newtonian film's residual scale, search and tests
    # (monolithic_newton.newtonian_step; step_solve, where its steady tests failed)
    step_tests: bool = False
    # the one Newton's preconditioner, kept across the steps of a run (TimeIntegrator.preconditioner)
    preconditioner: KeptPreconditioner = dataclasses.field(default_factory=KeptPreconditioner)

    def rate(self, expected_gap: np.ndarray) -> np.ndarray:
        return self.coefficient * expected_gap + self.history

    def error_weight(self, film: np.ndarray) -> np.ndarray:
        """The step's error weight at each node, m: tolerance x max(|h|, floor) (module docstring)."""
        return self.tolerance * np.maximum(np.abs(film), self.floor)

    def settled(self, film: np.ndarray, correction: np.ndarray) -> bool:
        """Whether a film correction (m, per node: a deformation iteration's change or a
        Newton's deformation residual) is below ``fraction`` of the step's error weight
        at every node: the step's stopping test on the film, in place of the steady solve's
        relative change (solver.tolerance), which a stiff step's iteration may never reach
        (the 10 and 100 Pa s oscillations of tests/test_hard_cases.py failed on it)."""
        return bool(np.all(np.abs(correction) <= self.fraction * self.error_weight(film)))

    def settled_position(self, displacement: float) -> bool:
        """Whether the cylinder's displacement that would close the force balance (m: the
        force residual over the contact's stiffness dF/dz) is below ``fraction`` of the
        smallest error weight of a film (tolerance x floor): the step's test on the force
        balance, the same as on the film, in place of the steady solve's relative force
        (solver.tolerance), which a stiff step's Newton may stall above (the 100 Pa s fretting
        on the 51-node line, tests/test_hard_cases.py, stalled at 3e-6 of the force)."""
        return abs(displacement) <= self.fraction * self.tolerance * self.floor

    def settled_pressure(self, residual: float) -> bool:
        """Whether a Reynolds residual (the complementarity residual's largest value over the
        peak pressure) is below ``fraction`` of the step's relative tolerance: the
        step's own test on the pressure, at the relative level of its test on the film, which a
        step's Newton that has stalled short of the steady solve's (solver.tolerance, 1e-6 by
        default) may take (model/monolithic_newton.converged). The 10 Pa s oscillation and the
        100 Pa s fretting on the 51-node line (tests/test_hard_cases.py) stalled there, their
        film and force tests met, at 1.3e-6 of the peak pressure."""
        return residual <= self.fraction * self.tolerance

    def settled_outflow(self, outflow: np.ndarray, cell_area: np.ndarray, film: np.ndarray) -> bool:
        """Whether each cell's outflow left over by a Newton (m^3/s: its scale times its
        complementarity residual, model/monolithic_newton.Linearisation.outflow_error) would
        move its film over the step, outflow / (c0 dA), by less than ``fraction`` of the
        step's error weight: the step's own test on the Reynolds residual, as on the film
        (settled). The steady test alone (solver.tolerance times the peak pressure p_s) let
        cells at the cavitation boundary, with p ~ 2e-6 p_s, keep an outflow that left the
        face-flux volume balance (series.volume_balance) up to 0.29 off on a rough 2-D stop and
        0.16 on a line, at motion.tolerance 1e-4 (bench/EXPERIMENTS.md, thirty-eighth session)."""
        return bool(np.all(np.abs(outflow) <= self.fraction * self.coefficient * cell_area
                           * self.error_weight(film)))

    def outflow_scale_floor(self, cell_area: np.ndarray, pressure: float) -> np.ndarray:
        """The smallest scale (m^3/(Pa s)) by which the one Newton divides a cell's outflow
        in its complementarity residual (model/monolithic_newton.py): c0 dA h_s / p, the
        outflow of squeezing the cell's film by the film scale h_s over the step, per
        pressure ``pressure`` (Pa, the nominal contact pressure). A cell whose own
        conductance (its Poiseuille diagonal A_ii) is below it is sealed for this step: its
        outflow is then measured as that film change, not as the pressure that would drive it
        through the seal (docs/physics.md section 20)."""
        return self.coefficient * cell_area * self.film_scale / pressure


@dataclass
class StepCeiling:
    """The longest step the coupled solve is trusted with: half the shortest step grown beyond
    the last accepted one whose solve failed where the retry passed, doubled once ``patience``
    accepted steps have reached it (a search in log(dt) between the quarter step that passed
    and the step that failed, which follows a solver limit that grows with time); none before
    such a failure. Each such failure doubles the patience and each raised ceiling whose
    first step passes halves it (at least 1): where the limit stays put, the probes beyond it
    thin out geometrically instead of failing at every other step (a failed solve costs five to
    seven accepted ones on a grease at rest, bench/EXPERIMENTS.md, fortieth session)."""

    floor: float = 0.0  # s: never bounded below this step (a contact's mass: Dynamics.shortest_step)
    failed: float = math.inf  # s: the bound's step, twice the longest step allowed
    suspect: float | None = None  # s: a grown step whose solve failed, until its retry ends
    patience: int = 1  # accepted steps at the ceiling before it is doubled
    reached: int = 0  # accepted steps at the ceiling since it was last set
    probing: bool = False  # the ceiling was just doubled: its next step at it probes it

    def limit(self, dt: float) -> float:
        return min(dt, max(0.5 * self.failed, self.floor))

    def solve_failed(self, dt: float, last: float):
        """A solve failed on a step dt after an accepted step of length ``last``."""
        self.suspect = dt if dt > last and self.suspect is None else None

    def bound(self, dt: float):
        """A step dt proved too long (its solve failed where a shorter one passed, or no step
        started from the level it reached: TimeIntegrator.run's step back)."""
        self.failed, self.suspect = min(self.failed, dt), None
        self.patience, self.reached, self.probing = 2 * self.patience, 0, False

    def accepted(self, dt: float):
        if self.suspect is not None:
            self.bound(self.suspect)
        elif dt >= 0.5 * self.failed * (1.0 - 1e-12):  # reached, up to the rounding of (t + dt) - t
            if self.probing:
                self.patience, self.probing = max(1, self.patience // 2), False
            self.reached += 1
            if self.reached >= self.patience:
                self.failed, self.reached, self.probing = 2.0 * self.failed, 0, True


def bdf_coefficients(steps: list[float]) -> list[float]:
    """[c0, c1, ...] of dy/dt(t_{n+1}) ~ sum c_j y^{n+1-j} for the last steps
    [dt_n, dt_{n-1}, ...] (order = len(steps), 1 or 2; variable-step BDF)."""
    if len(steps) == 1:
        return [1.0 / steps[0], -1.0 / steps[0]]
    dt, previous = steps
    w = dt / previous
    return [(1 + 2 * w) / ((1 + w) * dt), -(1 + w) / dt, w * w / ((1 + w) * dt)]


def impasse_lengths(shortest: float, failed: float) -> list[float]:
    """The lengths of the steps a jump over an impasse tries, in the order tried
    (TimeIntegrator.jump_over_impasse): 4, 16, ... 4^IMPASSE_PROBES times ``shortest`` (the
    longest of the failed step, the step the error test last asked for and, where the steps
    crept, motion.tolerance times the longest it asked for), then, where all of those fail,
    4, 16, ... 4^IMPASSE_PROBES times ``failed`` (the step that failed, or was not tried)
    while shorter than the first of them. The long ones first: a run whose jumps converge so
    takes the steps it took before, and a short jump that converges may land before the seal,
    where the steps creep to it again (the tight 31-node stop of tests/test_hard_cases.py hung
    so for minutes with the short ones first). The short ones were added where every long one
    failed: on the 20 N grease stop at t = 0.602 s, where 256 times the failed step (3.4 ms)
    converges (docs/physics.md section 14, "The impasse at a sealing pocket")."""
    long = [shortest * 4.0 ** k for k in range(1, IMPASSE_PROBES + 1)]
    return long + [failed * 4.0 ** k for k in range(1, IMPASSE_PROBES + 1) if failed * 4.0 ** k < long[0]]


def bdf_history(coefficients, levels) -> np.ndarray:
    """c1 h_T^n + c2 h_T^{n-1} of Squeeze.history (``coefficients`` c0, c1[, c2] of
    bdf_coefficients, ``levels`` oldest first), except in the cells sealed at the last level
    (Level.sealed: their content frozen below the kink), which take -c0 h_T^n: their rate
    c0 (h_T^{n+1} - h_T^n) is zero while they stay sealed, as a frozen content's is. BDF2's
    difference through the seal is not: with h_T^{n+1} = h_T^n it leaves c2 (h_T^{n-1} - h_T^n)
    > 0, a flow into the sealed cell that its frozen content cannot hold, and so destroys half
    a step's outflow at every cell that seals (docs/physics.md section 14, "A sealed cell's
    rate"). A cell sealed at the two last levels has BDF2's own rate, zero, either way."""
    last = levels[-1]
    history = sum(cj * lv.expected_gap for cj, lv in zip(coefficients[1:], levels[::-1]))
    return np.where(last.sealed, -coefficients[0] * last.expected_gap, history)


def step_error(scaled: np.ndarray, norm: str) -> float:
    """A step's error from its nodes' estimates, each in its own error weight (module
    docstring): their root mean square (``norm`` "rms", the weighted RMS norm of SUNDIALS)
    or their largest magnitude ("max", the maximum norm Hairer, Norsett & Wanner give beside
    it, "Solving ODEs I", section II.4). The RMS of an error at a few nodes falls as one over
    the root of the node count, so the same motion.tolerance is looser on a finer mesh where
    the error is a node's own, as where a pocket of the film seals; the max norm is not
    (docs/physics.md section 14, "The error norm")."""
    if norm == "max":
        return float(np.max(np.abs(scaled)))
    return float(np.sqrt(np.mean(scaled ** 2)))


def error_fraction(steps: list[float]) -> float:
    """Local error of BDF_p as a multiple of (corrector - predictor), the predictor being
    the polynomial through the last p + 1 levels; steps = [dt_n, dt_{n-1}, ...] (p + 1 of them).
    Both constants from y = (t - t_{n+1})^{p+1}/(p+1)!, whose derivative at t_{n+1} is 0."""
    order = len(steps) - 1
    offsets = np.cumsum(steps)  # t_{n+1} - t_{n+1-j}, j = 1..p+1
    c = bdf_coefficients(steps[:order])
    y = (-offsets) ** (order + 1) / math.factorial(order + 1)
    corrector = -sum(cj * yj for cj, yj in zip(c[1:], y[:order])) / c[0]  # y_c - y_true per h^(p+1)
    predictor = -float(np.prod(offsets)) / math.factorial(order + 1)  # y_p - y_true per h^(p+1)
    return abs(corrector / (corrector - predictor))


def rejection_factor(dt: float, error: float, order: int, earlier: tuple[float, float] | None) -> float:
    """The factor on a step of length ``dt`` whose error test failed (``error``, the
    estimate over the tolerance, > 1), for the next attempt from the same level.

    The controller's usual scaling SAFETY E^{-1/q} assumes the estimate falls as dt^q with
    q = order + 1, the BDF's local error on a smooth film. Where a node's film has a kink
    within the step (a pocket sealing at rest, its pressure released or trapped), the
    estimate falls as dt only: the Table 1 stop at 51 x 21 rejected each such step four to
    six times, a fifth of a step shorter each time (bench/EXPERIMENTS.md, twenty-second
    session). So after a second rejection from one level (``earlier``: the previous attempt's
    dt and error) q is the order the two attempts show, ln(E_0/E)/ln(dt_0/dt), at most
    order + 1; where the estimate did not fall, the step is cut by SHRINK, the most a
    rejection cuts. Bounded by [SHRINK, 1]."""
    q = float(order + 1)
    if earlier is not None:
        dt_0, error_0 = earlier
        if dt >= dt_0 or error >= error_0:
            return SHRINK
        q = min(q, math.log(error_0 / error) / math.log(dt_0 / dt))
    return max(SHRINK, min(SAFETY * error ** (-1.0 / q), 1.0))


def lagrange(times: list[float], values: list, t: float):
    """Lagrange polynomial through (times, values) evaluated at t (values: numbers or arrays).
    Beyond the last time it is the predictor of a step; between the times it is the
    integrator's dense output (unsteady/events.py locates resistance crossings on it)."""
    total = 0.0
    for i, (ti, vi) in enumerate(zip(times, values)):
        weight = 1.0
        for j, tj in enumerate(times):
            if j != i:
                weight *= (t - tj) / (ti - tj)
        total = total + weight * vi
    return total


@dataclass
class Level:
    """One accepted time level."""

    time: float
    speed: float
    state: object  # model/model.State
    expected_gap: np.ndarray  # h_T used by the squeeze history
    sealed: np.ndarray  # the cells whose content is frozen (ControlVolumeMean.frozen): bdf_history
    model: Model  # the model of the step (its scene carries the speed)
    diagnostics: Diagnostics
    order: int = 0
    error: float = 0.0  # error estimate / tolerance of the step
    squeeze_rate: np.ndarray | None = None
    velocity: float = 0.0  # dz/dt of the cylinder, m/s (a contact with mass; unsteady/dynamics.py)
    # where a pocket sealed when this step jumped over its impasse, accepted without the error
    # test (jump_over_impasse, sealing_pocket); "" for every other step
    impasse: str = ""


# A 2-D step's Newton fallback (nested_then_newton) that has failed this many times in a row
# is not tried again in the run: where it cannot help it costs a Newton at every failed
# attempt. The R = 5 mm stop at 51 x 51 fails at t = 3.0 ms after
# 256 s of CPU with the Newton tried at every failed attempt, 224 s with this limit and
# 187 s without a fallback; on 21 x 21 it takes the same path with the limit (22 steps
# taken by the Newton, 5.1667 ms, 48 s; bench/EXPERIMENTS.md, thirteenth session).
MAX_FALLBACK_FAILURES = 2


@dataclass
class NewtonFallback:
    """Whether a 2-D step that the nested solve fails is retried by one Newton: until the
    Newton has failed MAX_FALLBACK_FAILURES times in a row (a step it takes resets the count;
    once reached, the rest of the run goes without it, and its failures say so)."""

    failures_in_a_row: int = 0

    @property
    def enabled(self) -> bool:
        return self.failures_in_a_row < MAX_FALLBACK_FAILURES

    def record(self, converged: bool):
        self.failures_in_a_row = 0 if converged else self.failures_in_a_row + 1


def step_solve(model: Model, initial: WarmStart, fallback: NewtonFallback, retrying: bool = False,
               error_tested: bool = True):
    """(state, diagnostics) of one time step from the predictor ``initial``. On a line
    contact (monolithic_newton.dense_step_serves) one Newton (docs/physics.md section 20),
    its tests at LINE_NEWTON_FRACTION of the step's error weight; where it cannot meet them,
    the nested coupled solve (model/coupling.py), then one Newton judged by the step's usual
    NONLINEAR_FRACTION (as a 2-D mesh's or a grease's Newton is), each from the same
    predictor: the first answer that converges, else the failures named (line_fallbacks;
    the usual tests not where the step's answer is not ``error_tested``: a jump over an impasse).
    Measured on Table 1 stops: the Newton alone
    fails on the 201-node line where the nested solve converges, and the nested alone on
    the 20 N stop and at motion.tolerance 1e-5 (tests/test_hard_cases.py). A contact with
    mass and spring (Model.load), a grease, JFO cavitation and solver.method newton have the
    Newton only; a grease's, where it fails on an attempt after one that failed from the same
    level (``retrying``), once more with a Newtonian step's tests (grease_step_retry), and
    where the run has switched to those tests (the squeeze's ``step_tests``,
    TimeIntegrator.step_tests_from), with them first and the steady ones after.
    On a 2-D mesh (or a line beyond the dense Newton's size) the other way round
    (nested_then_newton): the nested solve is cheaper where it converges."""
    # the nested solve has no F(z), nor a grease, nor JFO's stored content theta c
    if model.load is not None or needs_newton(model) or model.scene.effects.cavitation == "jfo":
        grease = yield_stress_law(model) is not None
        if grease and model.squeeze.step_tests:  # TimeIntegrator.step_tests_from
            state, diag = switched_grease_step(model, initial)
        else:
            state, diag = monolithic_solve(model, initial, continuation=False)
            if not diag.converged and retrying and grease:
                state, diag = grease_step_retry(model, initial, state, diag)
        if not diag.converged:
            diag = dataclasses.replace(diag, failure=f"one Newton (the only solver of a contact with mass or "
                                                     f"spring, of a grease, or of JFO in time): {diag.failure}")
        return state, diag
    if not dense_step_serves(model):
        return nested_then_newton(model, initial, fallback)
    alone = dataclasses.replace(model, squeeze=dataclasses.replace(model.squeeze, fraction=LINE_NEWTON_FRACTION))
    state, diag = monolithic_solve(alone, initial, continuation=False)
    if diag.converged:
        return state, diag
    return line_fallbacks(model, initial, state, diag, error_tested)


def line_fallbacks(model: Model, initial: WarmStart, state, diag: Diagnostics, error_tested: bool):
    """(state, diagnostics) of a line step whose Newton failed its tight tests (step_solve):
    the nested coupled solve from the same predictor, then, where the error test will judge
    the answer (``error_tested``), one Newton at the step's usual NONLINEAR_FRACTION; the
    first answer that converges, else the failures named. The nested solve comes first: its
    Reynolds solves are exact, so its answer closes each cell's volume balance. The usual
    tests are what the 51-node line stop at motion.tolerance 1e-4 (tests/test_error_bar.py)
    needs near its reconnection, where the Newton's residual sticks at 2e-5 and the nested
    solve stalls; they are safe where the error test rejects a step whose answer strays, and
    a jump over an impasse is accepted without it: the 10 Pa s fretting under 20 N of
    tests/test_hard_cases.py took a jump of 0.8 ms so, on an answer its Newton reached after
    its residual had risen seventyfold, and failed 2.4 ms later where no solver moved from the
    predictor; without the usual tests on jumps it converges (bench/EXPERIMENTS.md,
    forty-seventh session)."""
    nested_state, nested, why = nested_step(model, initial, LINE_FALLBACK_STALL_ITERATIONS)
    if nested is not None and nested.converged:
        return nested_state, nested
    failure = f"one Newton: {diag.failure}; then the nested coupled solve: {why}"
    if not error_tested:
        return state, dataclasses.replace(diag, failure=failure)
    usual_state, usual = monolithic_solve(model, initial, continuation=False)
    if usual.converged:
        return usual_state, usual
    failure += f"; then one Newton at the step's usual tests: {usual.failure}"
    return state, dataclasses.replace(diag, failure=failure)


def grease_step_retry(model: Model, initial: WarmStart, state, diag: Diagnostics):
    """(state, diagnostics) of a grease's step whose Newton failed under the steady tests
    (monolithic_newton.newtonian_step) on an attempt after one that failed from the same
    level (step_solve's ``retrying``): retried once from the same predictor as a Newtonian
    film's step is solved, with the step's own residual scale, projected search and tests
    (Squeeze.step_tests); the first answer that converges, else both failures named. A
    grease's Newton stalls near its answer where a plug's rows sit at the yield limit: the
    Herschel-Bulkley stop of tests/test_hard_cases.py crept on at steps of 1e-9 s to the
    20 000-step limit under the steady tests alone, and completes with this retry. Not on a
    first attempt: retried at every failed attempt the Bingham stop (hard case bingham_stop)
    took 35.6 s of CPU against 8.2 s, with 67 retries, since the steps it passes set a
    different path of steps; the steady tests stay the first try, since with the step's tests
    alone that stop failed (newtonian_step). bench/EXPERIMENTS.md, forty-sixth session."""
    retry_model = dataclasses.replace(model, squeeze=dataclasses.replace(model.squeeze, step_tests=True))
    retry_state, retry = monolithic_solve(retry_model, initial, continuation=False)
    if retry.converged:
        return retry_state, retry
    return state, dataclasses.replace(diag, failure=f"{diag.failure}; retried with a Newtonian step's tests: "
                                                    f"{retry.failure}")


def switched_grease_step(model: Model, initial: WarmStart):
    """(state, diagnostics) of a grease's step once its run has switched to a Newtonian step's
    tests (``model``'s squeeze has ``step_tests``; TimeIntegrator.step_tests_from): those tests
    first, then the steady ones from the same predictor; the first answer that converges, else
    both failures named. grease_step_retry, the same tests, is not run again: from the same
    predictor it repeats the first solve."""
    state, diag = monolithic_solve(model, initial, continuation=False)
    if diag.converged:
        return state, diag
    steady = dataclasses.replace(model, squeeze=dataclasses.replace(model.squeeze, step_tests=False))
    steady_state, steady_diag = monolithic_solve(steady, initial, continuation=False)
    if steady_diag.converged:
        return steady_state, steady_diag
    return state, dataclasses.replace(diag, failure=f"{diag.failure}; under the steady tests too: {steady_diag.failure}")


def nested_step(model: Model, initial: WarmStart, stall_iterations: int | None = None):
    """(state, diagnostics, failure message) of the nested coupled solve of a step, which
    fails as stalled after ``stall_iterations`` (None: model/coupling.STEP_STALL_ITERATIONS);
    state and diagnostics None where it raised: a SolveError, or SuperLU's RuntimeError on a
    singular factor (seen in an experiment on a step of 16 times the one the error test
    asked for, where a pocket seals on the Table 1 51-node line stop at 1e-5), which the
    step's retry then answers as any failed solve, as the Newton's (monolithic_newton.newton)
    does."""
    try:
        state, diag = coupled_solve(model, initial, stall_iterations=stall_iterations)
    except RuntimeError as err:  # SolveError is one
        return None, None, str(err)
    return state, diag, diag.failure or "it did not meet its tolerances"


def nested_then_newton(model: Model, initial: WarmStart, fallback: NewtonFallback):
    """(state, diagnostics) of a step on a 2-D mesh: the nested coupled solve, and where it
    fails one Newton from the same predictor (its reduced system by preconditioned GMRES,
    monolithic_newton.NearFieldPreconditioner), else both failures named. The nested solve
    is the cheaper where it converges: a Table 1 stop at 51 x 51 took 206 s with a Newton
    every step against 9 s nested (bench/EXPERIMENTS.md, thirteenth session). Where its
    cavitated set flickers on a squeeze film near rest (the R = 5 mm stop at t = 3 ms) its
    deformation iteration stalls, and the Newton's smoothed complementarity does not. The
    Newton is skipped while ``fallback`` says it keeps failing (NewtonFallback)."""
    nested_state, nested, why = nested_step(model, initial)
    if nested is not None and nested.converged:
        return nested_state, nested
    if not fallback.enabled:
        why = (f"the nested coupled solve: {why}; one Newton not tried (it failed the last "
               f"{fallback.failures_in_a_row} times)")
        if nested is None:
            raise SolveError(why)
        return nested_state, dataclasses.replace(nested, failure=why)
    state, diag = monolithic_solve(model, initial, continuation=False)
    fallback.record(diag.converged)
    if diag.converged:
        return state, diag
    return state, dataclasses.replace(diag, failure=f"the nested coupled solve: {why}; then one Newton: {diag.failure}")


def sealing_pocket(levels: list[Level]) -> str:
    """Where a pocket of the film seals at the last of ``levels``, "" if none: "x = .. mm,
    y = .. mm (h/sigma = .., ...)" of a node whose film is at or below the frozen content's kink
    (h <= 0) while its cell still drains (its content still depends on its film through a face
    above the kink, ControlVolumeMean.own > 0; the one whose content depends least on its film),
    else of one whose cell sealed within the last step (own > 0 at the level before). Where
    such a pocket seals the run meets an impasse (docs/physics.md section 14, "The impasse at a
    sealing pocket")."""
    last, before = levels[-1], levels[-2]
    model = last.model
    if model.contact is None:
        return ""
    film = last.state.film
    own = squeeze_content(model, film).own
    at_kink = film <= FLUID_FILM_FLOOR_SIGMAS * model.contact.sigma
    draining = at_kink & (own > 0.0)
    if draining.any():
        where, how = np.argmin(np.where(draining, own, np.inf)), "its cell still open through a face"
    else:
        if before.model.mesh is not model.mesh:  # the first step on the mesh at rest
            return ""
        sealed = at_kink & (own == 0.0) & (squeeze_content(before.model, before.state.film).own > 0.0)
        if not sealed.any():
            return ""
        where, how = np.argmax(sealed), "its cell sealed within the last step"
    row, column = np.unravel_index(where, film.shape)
    return (f"x = {model.mesh.x[column] * 1e3:.3g} mm, y = {model.mesh.y[row] * 1e3:.3g} mm "
            f"(h/sigma = {film[row, column] / model.contact.sigma:.3g}, {how})")


def film_on(level: Level, model: Model) -> np.ndarray:
    """``level``'s film at the nodes of ``model``'s mesh (its own film where the meshes are
    the same): h = h_o + z + delta (Eq. 4 and the deformation), the deformation carried by
    cubic splines along x (numerics/transfer.spline_along_x), the undeformed gap exact."""
    if level.model.mesh is model.mesh:
        return level.state.film
    delta = spline_along_x(level.state.delta, level.model.mesh, model.mesh)
    return model.undeformed_gap + level.state.z + delta


def transferred(level: Level, model: Model) -> Level:
    """``level`` on the mesh of ``model`` the steps move onto (TimeIntegrator.next_domain: the
    mesh at rest, or the motion's mesh mirrored for a return stroke): the fields a step reads
    of its last levels, at its nodes: the film (film_on) and the content it holds (the squeeze
    history), the deformation; the pressure and the cavitated set, a warm start only,
    bilinear, the pressure held at 0 on the new inlet boundary. Only for the steps' history:
    the series keeps ``level`` itself."""
    source, target = level.model.mesh, model.mesh
    state, reynolds = level.state, level.state.reynolds
    if reynolds is not None:
        pressure = interpolate_field(reynolds.pressure, source, target)
        cavitated = interpolate_field(reynolds.cavitated.astype(float), source, target) > 0.5
        pressure[:, 0], cavitated[:, 0] = 0.0, False
        moved = {"pressure": pressure, "cavitated": cavitated, "factor": None}
        if isinstance(reynolds, JFOSolution):  # its film content, which the cells hold (held_content)
            content = np.clip(interpolate_field(reynolds.content, source, target), 0.0, 1.0)
            content[:, 0] = 1.0
            moved.update(content=content, face_content=None, unknown=None)
        reynolds = dataclasses.replace(reynolds, **moved)
    film = film_on(level, model)
    delta = spline_along_x(state.delta, source, target)
    state = dataclasses.replace(state, delta=delta, film=film, reynolds=reynolds)
    rate = None if level.squeeze_rate is None else interpolate_field(level.squeeze_rate, source, target)
    held, sealed = held_content(model, state)
    return dataclasses.replace(level, state=state, expected_gap=held, sealed=sealed, model=model, squeeze_rate=rate)


def held_content(model: Model, state) -> tuple[np.ndarray, np.ndarray]:
    """(the content each cell holds, which the squeeze term differentiates in time: its
    content c (model/fluid_film.squeeze_content), times the film content theta with JFO
    cavitation; the cells where c is frozen, sealed), at ``state`` (model/model.State)."""
    content = squeeze_content(model, state.film)
    theta = getattr(state.reynolds, "content", None)  # JFO's (numerics/cavitation_jfo.JFOSolution)
    return content.value if theta is None else theta * content.value, content.frozen()


def scene_at(scene, speed: float):
    """The scene with operating.speed = speed (any sign: oscillation), without re-validation."""
    return dataclasses.replace(scene, operating=dataclasses.replace(scene.operating, speed=float(speed)))


class TimeIntegrator:
    """Integrates one scene's motion from its steady start; ``run`` gives the levels."""

    def __init__(self, scene, history, contact=None):
        self.scene, self.history = scene, history
        self.tolerance = scene.motion.tolerance
        # one mesh while the contact moves, its automatic inlet sized for the fastest instant
        # (mesh.py: not the far inlet's, whose closed form is steady); at rest the mesh at
        # rest (rest_domain)
        mesh = build_mesh(scene_at(scene, history.peak_speed()), far_inlet=False)
        steady = Model.assemble(scene_at(scene, history.initial_speed()), mesh=mesh, contact=contact)
        self.contact = steady.contact
        self.floor = steady.contact.sigma if steady.contact is not None else FILM_FLOOR
        self.steady_model = steady
        self.step_model = steady  # the model the steps are built on: steady's, reversed_domain's, rest_domain's
        self.backward = None  # the motion's model while it slides backward (reversed_domain), built at need
        self.dynamics = Dynamics.from_scene(scene)
        self.base = BaseExcitation.from_scene(scene)
        self.coupled_solves = 0
        self.rejected = 0
        self.step_backs = []  # (time of the dropped level, time returned to) of each step back (run)
        self.fallback = NewtonFallback()
        # the time (s) from which a grease's steps take a Newtonian step's tests first (run), None: never
        self.step_tests_from: float | None = None
        self.preconditioner = KeptPreconditioner()  # the one Newton's, reused across steps while it serves

    def rest_domain(self) -> Model | None:
        """The model a motion's steps go on with at rest, on its mesh at rest
        (numerics/mesh.rest_mesh): the domain symmetric about the line of contact, within the
        automatic domain of speed 0, at motion.rest_refinement times the nodes per metre of
        the motion's mesh; None without a rest or on an explicit domain (mesh.x_min). The mesh
        of the motion carries the inlet of its fastest instant; at rest nothing is entrained,
        the squeeze film's pressure decays as 1/h^3 where the gap opens, and the contact itself
        is what the steps must resolve (docs/physics.md section 14). The steps move onto it
        once the nodes outside it carry less than motion.tolerance of the load (outside_load)."""
        if self.history.rest_from is None or self.scene.mesh.x_min is not None:
            return None
        mesh = rest_mesh(self.steady_model.mesh, self.scene.motion.rest_refinement)
        return Model.assemble(scene_at(self.scene, 0.0), mesh=mesh, contact=self.contact)

    def reversed_domain(self) -> Model | None:
        """The model a motion's return strokes (U < 0) go on with: the motion's mesh mirrored
        about the line of contact (numerics/mesh.mirrored_mesh), its inlet beyond x_max where
        the block now comes from; None on an explicit domain (mesh.x_min) or for a motion that
        never reverses. On the forward mesh a return stroke draws its film from the outlet's
        1.5 length scales: 1 %, 7 % and 44 % thinner than the forward stroke's under 0.1, 1
        and 10 Pa s (docs/physics.md section 17)."""
        if self.scene.mesh.x_min is not None or not self.history.reverses():
            return None
        if self.backward is None:
            mesh = mirrored_mesh(self.steady_model.mesh)
            self.backward = Model.assemble(scene_at(self.scene, -self.history.peak_speed()), mesh=mesh,
                                           contact=self.contact)
        return self.backward

    def next_domain(self, level: Level, rest: Model | None) -> Model | None:
        """The model the steps move onto after accepting ``level``, None where they stay: the
        mesh at rest (rest_domain) once the nodes outside it carry less than motion.tolerance of
        the load (outside_load), else the motion's mesh whose inlet lies upstream of the sliding
        (steady_model's, or reversed_domain's where U < 0), once the sliding has reversed."""
        if self.step_model is rest:
            return None
        if rest is not None and level.time >= self.history.rest_from and \
                abs(self.outside_load(level, rest)) <= self.tolerance:
            return rest
        if level.speed == 0.0 or (level.speed > 0.0) == (self.step_model is self.steady_model):
            return None
        return self.steady_model if level.speed > 0.0 else self.reversed_domain()

    def outside_load(self, level: Level, model: Model) -> float:
        """The share of the applied force that ``level``'s pressure carries on the nodes of its
        mesh outside ``model``'s domain in x."""
        total = level.state.fluid_pressure + level.state.contact_pressure
        mesh, inside = level.model.mesh, model.mesh.x
        outside = (mesh.x < inside[0] - 1e-9 * mesh.dx) | (mesh.x > inside[-1] + 1e-9 * mesh.dx)
        return float(np.sum((total * mesh.nodal_area)[:, outside])) / self.scene.operating.force

    def start(self) -> Level:
        """The steady state at t = 0 (the motion's initial speed). A motion that starts sliding
        backwards (a table whose first speed is negative) starts with its fluid (the steady
        solve took U < 0 for no sliding, and started dry), on the automatic domain on
        reversed_domain's mesh, whose inlet lies beyond x_max where its fluid comes from (on
        the forward mesh the inlet was the outlet's 1.5 length scales): a table from -1 m/s
        failed at 1 ns."""
        model = self.steady_model
        if self.history.initial_speed() < 0.0:  # Model.assemble takes U < 0 as no sliding (a steady U is >= 0)
            backward = self.reversed_domain()  # None on an explicit domain
            if backward is not None:
                self.step_model = backward
            model = dataclasses.replace(backward or model, scene=scene_at(self.scene, self.history.initial_speed()),
                                        hydrodynamic=bool(self.scene.effects.hydrodynamics))
        state, diag, _ = steady_solve(model)
        self.coupled_solves += 1
        transient = dataclasses.replace(model, hydrodynamic=bool(self.scene.effects.hydrodynamics))
        return Level(0.0, self.history.initial_speed(), state, *held_content(transient, state), model, diag)

    def step(self, levels: list[Level], t_new: float, order: int, jump: bool = False, retrying: bool = False):
        """Coupled solve at t_new with BDF_order; (level, error/tolerance) or (None, reason).
        The solve starts from the position and deformation extrapolated through the levels the
        BDF reads, or, on a ``jump`` over an impasse (jump_over_impasse), from the last level's,
        its answer accepted without the error test (step_solve's ``error_tested``);
        ``retrying``: an earlier attempt from this level failed (step_solve)."""
        last = levels[-1]
        dt = t_new - last.time
        previous = [last.time - levels[-2].time] if order == 2 else []
        c = bdf_coefficients([dt] + previous)
        history = bdf_history(c, levels)
        speed = self.history.speed(t_new)
        scale = max(float(np.min(last.state.film)), self.floor) if self.contact is None else self.floor
        load = None
        if self.dynamics is not None:  # docs/physics.md section 22
            earlier = levels[::-1][:order]
            load = self.dynamics.load(t_new, levels[0].state.z, c, [lv.state.z for lv in earlier],
                                      [lv.velocity for lv in earlier])
        squeeze = Squeeze(c[0], history, scale, self.tolerance, self.floor, preconditioner=self.preconditioner,
                          step_tests=self.step_tests_from is not None)
        model = dataclasses.replace(
            self.step_model, scene=scene_at(self.scene, speed), squeeze=squeeze,
            hydrodynamic=bool(self.scene.effects.hydrodynamics), load=load,
        )
        used = levels[-(order + 1):]
        times = [lv.time for lv in used]
        start = used[-1:] if jump else used
        initial = WarmStart(
            z=lagrange(times[-len(start):], [lv.state.z for lv in start], t_new),
            delta=lagrange(times[-len(start):], [lv.state.delta for lv in start], t_new),
            stiffness=last.diagnostics.stiffness,
        )
        if last.state.reynolds is not None:  # the set follows from the pressure (projected_smoothing)
            initial.cavitated = last.state.reynolds.cavitated
            initial.pressure = last.state.reynolds.pressure
            initial.content = getattr(last.state.reynolds, "content", None)  # JFO's theta
        try:
            state, diag = step_solve(model, initial, self.fallback, retrying, error_tested=not jump)
        except SolveError as err:
            return None, str(err)
        self.coupled_solves += 1
        if not diag.converged:
            return None, diag.failure or "coupled solve did not meet its tolerances"
        predicted = lagrange(times, [lv.state.film for lv in used], t_new)
        fraction = error_fraction([dt] + [lv.time - lv_prev.time for lv, lv_prev in zip(used[::-1], used[::-1][1:])])
        error = step_error(fraction * (state.film - predicted) / model.squeeze.error_weight(state.film),
                           self.scene.motion.error_norm)
        gap, sealed = held_content(model, state)
        if state.reynolds is not None:
            state.reynolds.factor = None  # LU factors: not needed after the step, megabytes each
        level = Level(t_new, speed, state, gap, sealed, model, diag, order, error, model.squeeze.rate(gap),
                      0.0 if load is None else load.velocity(state.z))
        return level, error

    def jump_over_impasse(self, levels: list[Level], shortest: float, target: float, pocket: str,
                          failed: float) -> Level | None:
        """The level after a jump over an impasse at a sealing pocket, None where there is no
        sealing pocket (``pocket`` empty, sealing_pocket) or no jump converges.

        Called where a step's solve has failed at every length the run tries (MAX_FAILED_IN_A_ROW
        and the other limits of ``run``) while a pocket of the film seals. The model then has no
        continuous state past the seal (docs/physics.md section 14, "The impasse at a sealing
        pocket"): with the content frozen below the kink and the leakage floor, the sealed
        pocket's pressure must fall to its neighbours' at once, and the films with it. The
        integrator takes that jump as the model says: first-order steps of 4, 16, ...
        4^IMPASSE_PROBES times ``shortest`` (the failed step, or the longer step the error test
        last asked for), up to the next breakpoint ``target``, and where all of those fail,
        4, 16, ... times ``failed`` (the step that failed, or was not tried) below the first of
        them (impasse_lengths), each solve started from the last
        level (the slope of the short steps before it, carried over a step thousands of times
        longer, is no prediction: a light mass's ringing sent such starts metres away), the
        first whose solve converges accepted without the error test (a jump has no local error
        to test; its estimate stays in the level, whose ``impasse`` says where the pocket
        sealed). Its length bounds how late the jump is taken.
        A run that passes every step never comes here: its answers do not change."""
        if not pocket:
            return None
        start, tried = levels[-1].time, set()
        for length in impasse_lengths(shortest, failed):
            t_new = min(start + length, target)  # past the breakpoint: the breakpoint, once
            if t_new in tried:
                continue
            tried.add(t_new)
            level, outcome = self.step(levels, t_new, 1, jump=True)
            if level is not None:
                return dataclasses.replace(level, impasse=pocket)
            self.rejected += 1
        return None

    def run(self, progress: bool = False, report=None, until=None):
        """(levels, failure message or ''): accepted levels from t = 0 to the motion's end,
        or to the first accepted level for which ``until`` (a callable taking a level, None:
        never) holds (transient.second_reconnect_time: a second run that only times the
        reconnection), or up to where the run stopped: a step that failed
        MAX_FAILED_IN_A_ROW times, below MIN_STEP or below motion.tolerance times the step the
        error test last asked for (see MAX_FAILED_IN_A_ROW), unless a pocket seals there and a jump over its impasse
        converges (jump_over_impasse) or, with a grease at rest, the run steps back (drops that
        last level, from which no step starts, and steps again from the level before;
        docs/DESIGN.md "Time"), MAX_STEPS, or an interruption (KeyboardInterrupt,
        which a SIGTERM handler may raise), whose failure message starts with "interrupted". ``report``
        (a callable taking one line) hears each decade of simulated time reached (1e-6 s,
        1e-5 s, ...): progress where no bar is shown."""
        from tqdm.auto import tqdm

        history = self.history
        self.wall_time = 0.0
        levels = [self.start()]
        start = levels[0].diagnostics
        if not start.converged:
            why = start.failure or f"{start.iterations} iteration(s) without meeting the tolerances"
            return levels, f"the steady start did not converge: {why}"
        # with a mass, no shorter step than the one whose inertial force the force balance
        # resolves to a tenth of its tolerance (Dynamics.shortest_step): below it the rounding of
        # z'' alone exceeds what the balance must meet (a random vibration's first step failed so)
        shortest = 0.0 if self.dynamics is None else self.dynamics.shortest_step(
            levels[0].state.z, NONLINEAR_FRACTION * self.scene.solver.tolerance * self.scene.operating.force)
        first = max(FIRST_STEP, shortest)
        # a steady state has dh/dt = 0: a virtual earlier level makes the first predictor exact
        levels.insert(0, dataclasses.replace(levels[0], time=-first))
        breaks = sorted({b for b in history.breakpoints() + self.base.breakpoints() if 0.0 < b < history.end})
        breaks.append(history.end)
        dt, order, failure, failed = first, 1, "", 0
        attempt = None  # (dt, error) of the last attempt from this level that failed the error test
        asked, solve_failed = None, False  # the error test's last step (above); a failed solve in this step
        longest = None  # the longest step the error test asked for since the motion last changed (creeping)
        ceiling = StepCeiling(floor=shortest)

        def plug_at_rest(instant: float) -> bool:
            """A yield-stress lubricant at rest at ``instant`` (s): StepCeiling and step backs."""
            return (self.scene.lubricant.rheology != "newtonian" and history.rest_from is not None
                    and instant >= history.rest_from)

        rest = self.rest_domain()
        stepping = levels  # the levels the steps read: at rest their last ones restricted to the rest domain
        started = time.perf_counter()
        decade = FIRST_STEP  # the next power of ten of simulated time to report
        bar = tqdm(total=history.end, unit="s", desc="transient", disable=not progress,
                   bar_format="{l_bar}{bar}| t = {n:.3g} of {total:.3g} s [{elapsed}] {postfix}")
        reached = False  # until held for the last accepted level
        try:
            with bar:
                while not reached and levels[-1].time < history.end and len(levels) < MAX_STEPS:
                    t = levels[-1].time
                    target = next(b for b in breaks if b > t)
                    if history.rest_from is None or t < history.rest_from:
                        dt = min(dt, history.max_step)
                    dt = min(dt, self.base.max_step(t))
                    dt = ceiling.limit(dt)
                    t_new = target if t + 1.1 * dt >= target else t + dt
                    # a sealing pocket where the steps crept below what accuracy asks (CREEPING)
                    pocket = sealing_pocket(stepping) if longest is not None and t_new - t < self.tolerance * longest \
                        else ""
                    creeping = bool(pocket)
                    # a step already failed from this level: a grease's Newton is retried (grease_step_retry)
                    level, outcome = (None, CREEPING) if creeping else self.step(stepping, t_new, order,
                                                                                       retrying=failed > 0)
                    if level is None:
                        failed, solve_failed = failed + 1, True
                        if plug_at_rest(t):
                            ceiling.solve_failed(t_new - t, t - stepping[-2].time)
                        needless = asked is not None and t_new - t < self.tolerance * asked
                        unresolved = t_new - t <= shortest
                        if needless and self.step_tests_from is None and self.scene.lubricant.rheology != "newtonian":
                            # a grease's steady tests, not accuracy, stop its steps: retry this one,
                            # and take every later one, with a Newtonian step's tests first
                            # (grease_step_retry's), the steady ones after. The Herschel-Bulkley stop
                            # at a creep viscosity of 1e8 Pa s (tests/test_hard_cases.py) stalled under
                            # the steady tests at every first attempt, the pressure of a near-plug being
                            # almost free, while its retry a quarter as long passed; the next step,
                            # three times longer, failed again, and the steps shrank by 3/4 a cycle to
                            # the end of the deceleration (at rest the same cycle halved them to 1e-16 s).
                            # Those tests first after any passed retry converged it too, but moved the
                            # Bingham stop on the automatic domain by -1.3 % and crept at
                            # motion.tolerance 3e-3; no other hard case gets here (bench/EXPERIMENTS.md,
                            # forty-seventh session)
                            self.step_tests_from = t
                            self.rejected += 1
                            continue
                        if t_new - t <= MIN_STEP or failed >= MAX_FAILED_IN_A_ROW or needless or unresolved or creeping:
                            short = (f"; below motion.tolerance = {self.tolerance:g} times the {asked:.3g} s the error "
                                     "test last asked for, a step is not needed for accuracy and a shorter one only "
                                     "stiffens the squeeze film" if needless else "")
                            short += (f"; {shortest:.3g} s is the shortest step whose inertial force the force balance "
                                      "resolves with motion.mass" if unresolved else "")
                            short += (f"; below motion.tolerance = {self.tolerance:g} times the {longest:.3g} s the error "
                                      "test asked for since the motion last changed" if creeping else "")
                            if not creeping:
                                pocket = sealing_pocket(stepping)
                            probe = max(t_new - t, asked or 0.0, self.tolerance * longest if creeping else 0.0)
                            jump = self.jump_over_impasse(stepping, probe, target, pocket, t_new - t)
                            if jump is not None:  # restart at first order from it, as after a breakpoint
                                levels.append(jump)
                                if stepping is not levels:
                                    stepping.append(jump)
                                bar.update(jump.time - t)
                                failed, solve_failed, order, dt = 0, False, 1, jump.time - t
                                attempt = None
                                # the motion has not changed: the creep test keeps its reference
                                # (a jump is at least 4 times motion.tolerance times it, so the
                                # next jump needs the error test to shorten the steps again)
                                asked, longest = dt, dt if longest is None else max(longest, dt)
                                reached = until is not None and until(jump)
                                continue
                            back = stepping[-2].time  # the level a step back returns to
                            returned_to = self.step_backs[-1][1] if self.step_backs else -math.inf
                            if plug_at_rest(back) and not creeping and back > returned_to \
                                    and (stepping is levels or len(stepping) > 4):
                                # a grease at rest: drop the last level, from which no step starts, and
                                # step again from the one before it, each return later than the last
                                # (so between two returns the run gains a level, and ends)
                                levels.pop()
                                if stepping is not levels:
                                    stepping.pop()
                                self.step_backs.append((t, back))
                                self.rejected += 1
                                ceiling.bound(t - back)
                                bar.update(back - t)
                                dt, failed, solve_failed, attempt = 0.5 * (t - back), 0, False, None
                                continue
                            if pocket:
                                outcome += (f"; a pocket of the film is sealing at {pocket}: there the state must "
                                            "jump (docs/physics.md section 14, \"The impasse at a sealing pocket\"), but no "
                                            f"longer step (up to {4.0 ** IMPASSE_PROBES:g} times) converged either, nor a "
                                            "shorter one of 4, 16, ... times the failed step; a "
                                            "looser motion.tolerance may step over it")
                            verdict = "was not taken" if creeping else "did not converge"
                            failure = (f"time step at t = {t_new:.6g} s (dt = {t_new - t:.3g} s) {verdict} "
                                       f"({failed} attempt(s) in a row{short}): {outcome}")
                            break
                        self.rejected += 1
                        dt = max(0.25 * (t_new - t), shortest)
                        continue
                    failed = 0
                    if outcome > 1.0 and t_new - t > max(MIN_STEP, shortest):
                        self.rejected += 1
                        factor = rejection_factor(t_new - t, outcome, order, attempt)
                        attempt = (t_new - t, outcome)
                        dt = max((t_new - t) * factor, shortest)
                        continue
                    factor = SAFETY * max(outcome, 1e-10) ** (-1.0 / (order + 1))
                    attempt = None
                    levels.append(level)
                    if stepping is not levels:
                        stepping.append(level)
                    domain = self.next_domain(level, rest)
                    if domain is not None:
                        self.step_model = domain
                        stepping = [levels[0], *(transferred(lv, domain) for lv in levels[-3:])]
                    ceiling.accepted(t_new - t)
                    bar.update(t_new - t)
                    bar.set_postfix_str(f"dt = {t_new - t:.2g} s, steps {len(levels) - 2}")
                    while report is not None and t_new >= decade:
                        report(f"t = {decade:.0e} s of {history.end:g} s reached: {len(levels) - 2} steps, "
                               f"{self.rejected} rejected, {time.perf_counter() - started:.1f} s")
                        decade *= 10.0
                    if t_new == target and target in breaks[:-1]:
                        # U(t) is not smooth here: first order, from the last step's size (not
                        # FIRST_STEP: a tiny step makes the squeeze film stiff beyond what the
                        # coupled iteration resolves; the error control shortens it if needed)
                        order = 1
                        dt = t_new - t
                        longest = None
                    else:
                        dt, order = (t_new - t) * min(GROWTH, max(SHRINK, factor)), 2
                    if not solve_failed:
                        asked = dt
                        longest = dt if longest is None else max(longest, dt)
                    solve_failed = False
                    reached = until is not None and until(level)
        except KeyboardInterrupt:
            failure = f"interrupted at t = {levels[-1].time:.6g} s: the series up to there"
        if not failure and not reached and levels[-1].time < history.end:
            failure = f"stopped after {MAX_STEPS} steps at t = {levels[-1].time:.6g} s"
        self.wall_time = time.perf_counter() - started
        return levels[1:], failure
