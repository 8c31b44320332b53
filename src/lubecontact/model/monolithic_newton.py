"""One semismooth Newton for the coupled contact, steady and one time step at a time
(docs/physics.md section 20).

The unknowns are the fluid pressure p at the Reynolds nodes, the deformation delta at every
node and the cylinder position z; the film is h = h_o + z + delta (Eq. 3). One residual
holds the whole problem:

    R_p     = phi_FB(p, w(p, h) / A_ii)          cavitation p >= 0 _|_ outflow w >= 0
    R_delta = delta - K (p + p_c(h))             deformation, Eq. (3)
    R_z     = h_s (F_fluid + F_contact - F) / F  force balance, Eq. (18)

(a time step adds its squeeze outflow to w, and a contact with mass and spring has F(z),
Model.load). With mass-conserving (JFO) cavitation the pressure unknown is Elrod and Adams'
universal variable u, p = max(u, 0) and film content theta = 1 + min(u, 0)/P, and R_p is the
cell's mass balance w(u)/A_ii itself (numerics/jfo_outflow.py); the pressure's step is then
the pressure branch of u's (Linearisation.physical).

with w = A(h) p - b(h) the finite-volume outflow of each cell (numerics/reynolds.py), scaled
by its diagonal to a pressure, phi_FB the Fischer-Burmeister function
(numerics/complementarity.py) and h_s the film scale (sigma, or Martin's film). Every law in
it is at least semismooth, so Newton's method applies to the whole residual at once: no
active set inside a force balance inside a deformation fixed point.

A steady Newtonian film's Reynolds condition is first written in the universal variable u
instead (newton, universal_applies): p = max(u, 0) and R_p = w(p)/A_ii + min(u, 0), zero exactly
where u > 0 with w = 0, or u <= 0 with p = 0 and w = -u A_ii >= 0: the same complementarity,
piecewise linear in u (generalised Jacobian S A/A_ii + I - S, S = diag(u > 0)), with no
smoothing; where that Newton fails, the Fischer-Burmeister one follows from the same start.

Each Newton step linearises all three blocks: the Reynolds block J_pp = D_a + D_b A / A_ii
(sparse, one LU factorisation), its film slope J_ph (numerics/reynolds_jacobian.py), the
contact stiffness and the influence operator K (an FFT). The pressure update is eliminated
with the LU factors and the remaining (delta, z) system, the identity minus K times the
fluid and contact stiffness, is solved densely on line contacts up to DENSE_NODES nodes and
otherwise by GMRES, each product one back-substitution and one FFT, preconditioned by the
same system with K cut to its near field (NearFieldPreconditioner, factorised once and kept
across the steps of a solve while it serves: KeptPreconditioner; without deformation it is
one scalar equation). A backtracking line search on the
scaled residual norm (Armijo) globalises the step; with smooth surfaces the step is also
kept short of closing the film (h > 0 at every node: the smooth film has no contact law).

A cold start begins from the physics (cold_start); with asperity contact it first solves
the same problem on the mesh with every other node (down to NESTED_COARSEST nodes a side)
and starts from its interpolated solution; where Newton still fails from the start, the
load is approached by continuation from a fraction of it, and where that stalls (near
lift-off) the speed from a fraction of it (continuation_paths). A steady Newton on a rough
Newtonian film that stalls is retried first with each cell's outflow scaled by at least the
open film's diagonal, then polished on the cells' own scales (newton): a cell sealed below
the percolation threshold otherwise measures its outflow as the pressure that would push it
through the seal.

Stopping tests, in physical units and all met together (``solver.tolerance`` = tol):
|F_fluid + F_contact - F| <= tol F, max |R_delta| <= tol max(range of delta, h_s) (in a
time step: a tenth of the step's error weight at every node, Model.squeeze.settled), and
max |R_p| <= tol p_s with p_s the peak pressure (a Newtonian film's time step whose Newton
has stalled: a tenth of motion.tolerance p_s, Model.squeeze.settled_pressure).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, gmres, splu

from lubecontact.model.auto_effects import decreasing_root
from lubecontact.model.coupling import Diagnostics, WarmStart, coupled_solve
from lubecontact.model.evaluation import beyond_the_radius, film_scale, fluid_load, fluid_load_slopes
from lubecontact.model.fluid_film import (fluid_exterior, fluid_faces, fluid_film, open_film_diagonal, squeeze_content,
                                          yield_stress_law)
from lubecontact.model.grease_start import newtonian_stand_in, start_film
from lubecontact.model.model import Model, SolveError, State
from lubecontact.numerics.cavitation_jfo import JFOSolution, upwind_content
from lubecontact.numerics.complementarity import fischer_burmeister
from lubecontact.numerics.jfo_outflow import content_field, mass_conserving_outflow
from lubecontact.numerics.mesh import Mesh
from lubecontact.numerics.reynolds import ReynoldsSolution, interior_nodes, reynolds_system, solve_reynolds
from lubecontact.numerics.reynolds_jacobian import (LinearOutflow, exterior_film_jacobian, outflow_film_jacobian,
                                                     squeeze_film_jacobian, with_scale_floor)
from lubecontact.numerics.transfer import interpolate_field
from lubecontact.numerics.yield_stress_reynolds import yield_stress_outflow
from lubecontact.physics.film_estimates import hertz_half_width

# Armijo's sufficient decrease and the shortest step tried (Kelley 1995, "Iterative Methods
# for Linear and Nonlinear Equations", SIAM, section 8.1: 1e-4 and halving).
SUFFICIENT_DECREASE = 1e-4
SMALLEST_STEP = 2.0**-12
# A Newtonian film's line search is non-monotone (Grippo, Lampariello & Lucidi 1986, SIAM J.
# Numer. Anal. 23:707): a step need only lower the merit below the largest of the last this
# many iterates' merits, so a step that crosses the kinks of several cavitation pairs at once
# (a squeeze film's inlet near zero pressure) is taken whole instead of in slivers. Measured on
# the 100 Pa s fretting on the 51-node line (tests/test_hard_cases.py): with the monotone
# search, steps of 1/16 to 1/1024 stalled a step's Newton at a residual of 1e-5 (bench/
# EXPERIMENTS.md, twentieth session). Their own memory was 10; 5 keeps the stall test
# (STALL_ITERATIONS) meaningful. Since a stalled step may meet its own pressure test
# (converged, twenty-first session) the memory sets the cost, not the outcome: with 1, 2, 3,
# 5 and 10 the fretting and the 10 Pa s oscillation on the 51-node line both run to the end,
# in 22, 12, 16, 12 and 14 s and in 15, 12, 12, 11 and 15 s. A steady solve of a Newtonian
# film searches so too since the twenty-fourth session: monotone, the steady Newton on the
# default 51 x 51 Table 1 mesh at 0.01 m/s stalled (halving its steps to 1/32 at two pairs at
# the cylinder's ends) and failed after 26 s of load continuation; non-monotone it converges
# in 10 iterations, 1.2 s. A grease's solves stay monotone: non-monotone, the steady starts of
# three Bingham stops (tests/test_grease_stop.py) stalled.
NONMONOTONE_MEMORY = 5
# With smooth surfaces a step may close the film by at most this fraction at any node
# (fraction to the boundary, as interior-point methods keep their iterates feasible).
FILM_STEP_FRACTION = 0.9
# Inexact Newton steps (Dembo, Eisenstat & Steihaug 1982): GMRES solves the (delta, z) block
# to eta times its right-hand side, with the forcing term eta = min(0.1, this + the residual's
# decrease ratio), enough for fast local convergence; the outer test judges the result. The
# block's right-hand side holds K times the pressure step at fixed film, which in a time step
# can be far larger than the residual: where the line search finds no descent along such a
# direction, GMRES solves again to eta h_s |R| too (newton_iteration, ``whole``), the
# linearised residual of the whole system (the block's residual, in m, its force row scaled
# by h_s/F and its pressure rows eliminated exactly), Dembo, Eisenstat and Steihaug's own
# condition. Measured (bench/EXPERIMENTS.md, thirty-eighth session): without it the Table 1
# stop on 21 x 21 with one Newton a step rejected 324 steps by t = 10 us; with the whole
# residual's test at every step the steady 20 N Newton near lift-off took 67 s against 23 s
# (684 factorisations of the preconditioner: GMRES needed more than a cycle with a kept one).
GMRES_FORCING = 1e-3
GMRES_RESTART = 30
GMRES_CYCLES = 10
# A kept preconditioner (KeptPreconditioner) is factorised anew for the next direction once
# GMRES needs more than this many times the iterations it needed with it fresh: it has gone
# stale. Kept across the time steps of a run, measured on the Table 1 stop with one Newton a
# step (solver.method newton, bench/EXPERIMENTS.md, forty-fourth session), CPU s kept within a
# solve only / across the steps without a refresh / with it at 3: 51 x 51 21.4 / 13.7 / 14.8
# (112 / 15 / 23 factorisations), 31 x 15 3.55 / 4.72 / 3.43, 23 x 11 1.80 / 2.05 / 1.83,
# 21 x 9 4.03 / 4.38 / 4.24; at 2 the 51 x 51 stop took 18.1 s (46 factorisations, 6 more
# steps). On the small meshes the stale factors needed 10-30 iterations against 2-4 fresh.
# Across time steps only: a steady solve keeps its preconditioner while GMRES meets its
# tolerance with it within one restart cycle (KeptPreconditioner.growth None). With the
# refresh in steady solves too, the one-Newton point at 20 N and 0.1 m/s (hard case
# newton_lift_off_20_N_0100) took more than 120 s instead of 2.8 s: its directions took
# another path, into GMRES solves that failed after 4-9 s each (bench/EXPERIMENTS.md,
# forty-sixth session, bisected to the commit that brought the refresh).
KEPT_GROWTH = 3
# GMRES is preconditioned by the same reduced system with K cut to its near field, the
# influence coefficients between nodes at most this many nodes apart along each axis
# (NearFieldPreconditioner). Measured on Table 1 time steps at 51 x 51 (bench/EXPERIMENTS.md,
# thirteenth session): 2-3 GMRES iterations a Newton step at a radius of 2, where the
# unpreconditioned GMRES did not reach 0.1 in 300. A radius of 1 (9 coefficients a node
# instead of 25) fills the factors far less: cold steady solves of Table 1 on 51 x 51 took
# 0.26 / 0.43 / 0.77 s of CPU at 0.01 / 1 / 10 m/s against 0.35 / 0.59 / 0.99 s (single
# solves; radius 0: 0.26 / 0.38 / 0.71 s, with 14 Newton iterations instead of 10 at
# 0.01 m/s), and the 20 N grease stop on 51 x 51 (tests/test_hard_cases.py, its steps one
# Newton each) 92 s against 88 s (thirty-fifth session).
NEAR_FIELD_RADIUS = 1
# Smoothing of the Fischer-Burmeister function relative to the scaled residual: nodes in a
# sealed pocket have p = 0 and outflow 0 together, where phi is not differentiable and the
# generalised Newton step can fail to descend (seen on Table 1 at 1 mm/s: 506 such nodes).
SMOOTHING_FACTOR = 1e-3
# The smoothing is lowered (one more evaluation) once the residual allows a tenth of it.
SMOOTHING_UPDATE = 0.1
# Up to this many nodes a line contact's reduced Newton system is solved densely: its
# matrix costs n back-substitutions (K is built once per mesh), and its LU (n^3/3 flops) is
# ~0.1 s at 1500. A 2-D mesh's goes to preconditioned GMRES whatever its size: on Table 1 at
# 31 x 31 (1395 nodes) a steady Newton took 0.40 and 0.43 s with it at 0.01 and 1 m/s
# against 1.37 and 2.49 s dense (bench/EXPERIMENTS.md, thirteenth session).
DENSE_NODES = 1500
# A Newton iteration whose squared residual norm has not halved in STALL_ITERATIONS
# iterations has stalled (far from its quadratic convergence): it stops there, cheaply, and
# says so, instead of running to solver.max_iterations.
STALL_ITERATIONS = 8
STALL_FACTOR = 0.5
# Nested start: the coarsest mesh solved first (nodes a side); only with asperity contact,
# as the nested solver (model/coupling.py): a coarse mesh may not resolve a smooth film.
# 13, not the nested solver's 26: on the far inlet (a 2-D mesh without inlet columns, the
# default since the forty-first session) 51 x 51 coarsened once to 26 x 26, whose cold
# Newton stalled at the contact (scaled residual 54 -> 62 in 8 iterations, every variant)
# and went on by load continuation: Table 1 at 1 m/s took 2.37 s against 0.27 s from 13 x 13
# (10 m/s: 1.35 against 0.59 s; 101 x 101: 3.10 against 0.69 s and 2.06 against 1.06 s); the
# long inlet had reached its coarsest mesh, 26 x 20, by halving x alone. Without the far
# inlet (0.01 and 0.1 m/s) 13 costs 5-10 % more (medians of three, alternated in one process;
# forty-second session).
NESTED_COARSEST = 13
# Continuation from a cold start that fails: the first fraction of the load (or speed), then
# doubled back to the whole of it; at most this many halvings, of the start and of each step.
CONTINUATION_HALVINGS = 6
# A smooth film thinner than an atom (0.1 nm) has closed: a nested solve that stops there
# leaves no state to start from, and finished_by_newton starts cold, with load continuation.
# Seen on Table 1 crowned at 0.1 m, smooth, 0.1 m/s: the nested force balance stopped at a
# film of 4e-128 m, and the Newton from it found no descent, where one from a cold start
# converges (65 nm; tests/test_lubricated.py).
CLOSED_FILM = 1e-10


@dataclass
class Iterate:
    """A point of the Newton iteration: fluid pressure (Pa, (ny, nx), zero off the Reynolds
    unknowns), deformation (m, (ny, nx)) and cylinder position (m)."""

    pressure: np.ndarray
    delta: np.ndarray
    z: float


@dataclass
class Linearisation:
    """The residual at an iterate and what its Newton step needs."""

    state: State
    r_p: np.ndarray  # FB residual at the Reynolds unknowns, Pa
    r_delta: np.ndarray | None  # deformation residual, m (ny, nx); None for rigid bodies
    r_z: float  # scaled force residual, m
    unknown: np.ndarray | None  # (ny, nx) bool: the Reynolds unknowns
    contact_slope: np.ndarray  # dp_c/dh, Pa/m (zeros without asperity contact)
    pressure_scale: float  # p_s, Pa
    film_scale: float  # h_s, m
    smoothing: float = 0.0  # the Fischer-Burmeister smoothing mu of r_p, Pa
    load_slope: float = 0.0  # dF/dz of the applied force (Model.load), N/m
    # (dphi/dp, dphi/d(w/A_ii)) of r_p, and the outflow whose residual_jacobians they weight
    # (reynolds_jacobian.LinearOutflow, or a grease's yield_stress_reynolds.YieldStressOutflow)
    slopes: tuple | None = None
    parts: object | None = None
    # the force row's dF/dp (m^2, the nodal areas, or with the far inlet's weight) and its
    # dF/dh at fixed pressure (N/m, the far inlet's load; zeros without it):
    # evaluation.fluid_load_slopes
    load_weight: np.ndarray | None = None
    load_film_slope: np.ndarray | None = None
    outflow_floor: np.ndarray | None = None  # (ny, nx) floor of the outflow scale, m^3/(Pa s) (linearise)
    # where the pressure unknown is a universal variable u (Pa, (ny, nx): JFO's,
    # jfo_outflow.py, or the Reynolds condition's, ``universal``), u and dp/du at every node
    # (1 on the pressure branch, else 0); None: the unknown is the pressure itself
    variable: np.ndarray | None = None
    pressure_slope: np.ndarray | None = None
    universal: bool = False  # the Reynolds condition in the universal variable (linearise)
    # each Reynolds cell's outflow left over, m^3/s: its scale times its unsmoothed R_p
    # (a time step's own test on it, converged); None without a fluid
    outflow_error: np.ndarray | None = None

    def rebranched(self, slopes: tuple) -> "Linearisation":
        """The same residual with J_pp and J_ph weighted by other Fischer-Burmeister slopes
        (those of a nearby point where a pair changed branch)."""
        return dataclasses.replace(self, slopes=slopes)

    @cached_property
    def jacobians(self) -> tuple:
        """(J_pp, J_ph), built when a Newton direction asks for them (not for the trial
        points of a line search); (None, None) without a fluid."""
        return (None, None) if self.parts is None else self.parts.residual_jacobians(*self.slopes)

    @property
    def j_pp(self) -> sp.csc_matrix | None:
        """d R_p / d p at the Reynolds unknowns (sparse)."""
        return self.jacobians[0]

    @property
    def j_ph(self) -> sp.csr_matrix | None:
        """d R_p / d h at every node (sparse)."""
        return self.jacobians[1]

    @cached_property
    def j_pp_factors(self):
        """SuperLU factors of J_pp (minimum degree on A + A^T), None without Reynolds unknowns;
        factorised once per linearisation, so a second direction at the same iterate
        (newton_iteration's ``whole``) reuses them."""
        return splu(self.j_pp, permc_spec="MMD_AT_PLUS_A") if self.j_pp is not None and self.j_pp.shape[0] else None

    def iterate(self) -> Iterate:
        """The iterate this linearisation was taken at (its pressure unknown: p, or u)."""
        state = self.state
        return Iterate(state.fluid_pressure if self.variable is None else self.variable, state.delta, state.z)

    def physical(self, step: np.ndarray) -> np.ndarray:
        """The pressure change (Pa, (ny, nx)) of a change ``step`` of the pressure unknown:
        ``step`` itself, or a universal variable's pressure branch (pressure_slope)."""
        return step if self.pressure_slope is None else self.pressure_slope * step

    def merit(self) -> float:
        """Half the squared norm of the scaled residual (p by p_s, films by h_s); inf where it
        overflows (an iterate that far off is infinitely bad, and the line search rejects it:
        a Python float's ** raised OverflowError, an internal error, at operating.force 1e-200 N)."""
        with np.errstate(over="ignore"):
            total = float(np.sum(np.square(self.r_p / self.pressure_scale)) + np.square(self.r_z / self.film_scale))
            if self.r_delta is not None:
                total += float(np.sum(np.square(self.r_delta / self.film_scale)))
        return 0.5 * total


def newtonian_step(model: Model) -> bool:
    """Whether ``model`` is a time step of a Newtonian film, whose Newton takes a step's own
    residual scale, line search and force test (docs/physics.md section 20, "A time step's
    residual and tests"). A grease's steps keep the steady ones: with them the Bingham stop of
    the figure build (2 N, 101-node line) failed at t = 1.6 s, or, with the monotone search
    alone, ran in 200 steps against 78 and reconnected 2.7 % later (bench/EXPERIMENTS.md,
    twentieth session): its plug leaves the pressure undetermined as the squeeze weakens.
    A grease's step that failed them is retried once with a Newtonian film's
    (Squeeze.step_tests, unsteady/integrator.grease_step_retry)."""
    return model.squeeze is not None and (yield_stress_law(model) is None or model.squeeze.step_tests)


def projects_pressure(model: Model) -> bool:
    """Whether a line search projects its trial pressures onto p >= 0, the projected Newton
    path (Bertsekas 1982, SIAM J. Control Optim. 20:221): a Newtonian film's time step with
    Swift-Stieber cavitation (JFO's unknown u is negative where the film cavitates,
    jfo_outflow.py). A direction that carries a region of an inlet across its cavitation boundary
    at once (10 Pa s at t ~ 1 us: nodes at h/sigma ~ 400 taken from +1.8e-4 to -1.4e-4 of the
    peak pressure by the full step) leaves their linearised pressures below zero, where the
    Fischer-Burmeister residual is 2p; projected they sit at p = 0 with their outflow >= 0,
    their solution (bench/EXPERIMENTS.md, twenty-fourth session). Steady solves are not
    projected: projected, a steady Newton on Table 1 landed elsewhere within its tolerance,
    the steady start of a Bingham stop stalled, and with the non-monotone search Moes' M = 50
    reference line failed."""
    return newtonian_step(model) and model.scene.effects.cavitation == "reynolds"


def linearise(model: Model, it: Iterate, smoothing: float = 0.0,
              outflow_floor: np.ndarray | None = None, universal: bool = False) -> Linearisation:
    """The residual of the module docstring at ``it`` and its Jacobian blocks, the
    Fischer-Burmeister function smoothed by ``smoothing`` (Pa; complementarity.py);
    ``outflow_floor`` ((ny, nx), m^3/(Pa s)): each cell's outflow scaled by at least it instead
    of its own diagonal (newton: the open film's, fluid_film.open_film_diagonal, where a steady
    Newton stalled); ``universal``: the Reynolds condition in the universal variable instead,
    where it applies (universal_applies, module docstring)."""
    mesh, scene = model.mesh, model.scene
    force = scene.operating.force
    film = model.undeformed_gap + it.z + it.delta
    if model.contact is None and model.hydrodynamic and not np.all(film[interior_nodes(mesh.shape, mesh.line)] > 0.0):
        raise ValueError("smooth surfaces need a positive film at every node")
    outside = beyond_the_radius(model, film)
    if outside:
        raise ValueError(outside)
    nominal = nominal_pressure(model)
    universal = universal and universal_applies(model)
    contact_pressure = np.zeros(mesh.shape)
    contact_slope = np.zeros(mesh.shape)
    if model.contact is not None:
        contact_pressure, contact_slope = model.contact.pressure_and_slope(film)
    pressure = np.zeros(mesh.shape)
    r_p = exact = np.zeros(0)
    unknown = reynolds = h_t = k = faces = face_slopes = slopes = parts = content = variable = pressure_slope = None
    pressurised = None  # with a universal variable u, the unknowns on its pressure branch (u > 0)
    if model.hydrodynamic:
        h_t, k = fluid_film(model, film)
        faces, face_slopes = fluid_faces(model, film)
        rate = None
        if model.squeeze is not None:  # a time step: the cells' content, squeezed
            content = squeeze_content(model, film)
            rate = model.squeeze.rate(content.value)
        exterior = fluid_exterior(model, film)  # a 2-D mesh open to the far inlet
        system = reynolds_system(mesh, h_t, k, scene.operating.speed, faces, squeeze_rate=rate, exterior=exterior)
        unknown = system.unknown
        pressure[unknown] = it.pressure[unknown]
        p = pressure[unknown]
        grease = yield_stress_law(model)

        def squeeze_slope():  # the cell's squeeze outflow dA c0 c (docs/physics.md section 14)
            return squeeze_film_jacobian(mesh, unknown, model.squeeze.coefficient, content)

        # the film slopes of the Jacobian are built when a Newton direction asks for them, not
        # at the trial points of a line search (about four in five linearisations)
        added = squeeze_slope if model.squeeze is not None else None

        def film_slopes(film_content=None):
            """(dw/dh, dA_ii/dh) of the Newtonian outflow, built when a direction asks; with
            JFO (jfo_outflow.py) its Couette faces and a step's squeezed cells weighted by the
            film content ``film_content`` ((ny, nx), theta)."""
            nodal = (None, None) if face_slopes is not None else fluid_film(model, film, slopes=True)[2:]
            carried = None if film_content is None else upwind_content(mesh, film_content, scene.operating.speed)
            j_wh, j_sh = outflow_film_jacobian(mesh, pressure, unknown, scene.operating.speed, face_slopes, *nodal,
                                               face_content=carried)
            if exterior is not None:
                j_wh = j_wh + exterior_film_jacobian(unknown, exterior, pressure)
            if added is not None:
                squeezed = added()
                j_wh = j_wh + (squeezed if film_content is None else sp.diags(film_content[unknown]) @ squeezed)
            return j_wh, j_sh

        mass_conserving = scene.effects.cavitation == "jfo"
        if mass_conserving:  # the unknown is the universal variable u (jfo_outflow.py)
            variable = pressure.copy()
            storage = None
            if model.squeeze is not None:  # a step's cells store theta c: dA (c0 theta c + history)
                cells = mesh.nodal_area[unknown]
                storage = (model.squeeze.coefficient * cells * content.value[unknown],
                           -cells * model.squeeze.history[unknown])
            parts, split = mass_conserving_outflow(mesh, system, h_t, scene.operating.speed, faces, p, nominal,
                                                   film_slopes, storage)
            pressure[unknown], pressurised = split.pressure, split.pressurised
        elif grease is not None:  # the coefficient depends on the pressure (docs/physics.md section 21)
            _, _, gap_slope, coefficient_slope = fluid_film(model, film, slopes=True)  # nodal dh_T/dh, dk/dh
            parts = yield_stress_outflow(mesh, system, pressure, k, h_t, gap_slope, scene.operating.speed, grease,
                                         faces, face_slopes, coefficient_slope, added_outflow_film=added)
        elif universal:  # p = max(u, 0): the Reynolds condition in the variable (module docstring)
            variable = pressure.copy()
            pressurised = p > 0.0
            pressure[unknown] = np.where(pressurised, p, 0.0)
            parts = LinearOutflow((system.matrix @ sp.diags(pressurised * 1.0)).tocsr(), system.matrix.diagonal(),
                                  system.matrix @ pressure[unknown] - system.rhs, film_slopes)
        else:
            parts = LinearOutflow(system.matrix, system.matrix.diagonal(), system.matrix @ p - system.rhs, film_slopes)
        if newtonian_step(model):  # a step's sealed cells (integrator.Squeeze.outflow_scale_floor)
            parts = with_scale_floor(parts, model.squeeze.outflow_scale_floor(mesh.nodal_area[unknown], nominal))
        elif outflow_floor is not None:  # a steady solve's sealed cells, measured on the open film (newton)
            parts = with_scale_floor(parts, outflow_floor[unknown])
        w, scale = parts.outflow, parts.scale
        if universal:  # w/A_ii + min(u, 0): the outflow where u > 0, the outflow minus |u| where not
            r_p, d_a, d_b = w / scale + np.minimum(p, 0.0), 1.0 - pressurised, np.ones_like(p)
            exact = r_p
        elif scene.effects.cavitation in ("none", "jfo"):  # full Sommerfeld, or JFO's u: the flow balance itself
            r_p, d_a, d_b = w / scale, np.zeros_like(p), np.ones_like(p)
            exact = r_p
        else:
            r_p, d_a, d_b = fischer_burmeister(p, w / scale, smoothing)
            exact = fischer_burmeister(p, w / scale)[0] if smoothing > 0.0 else r_p
        slopes = (d_a, d_b)
        # cavitated: the outflow, not the pressure, is the positive partner (a sealed node with
        # p = 0 and no outflow is full of fluid)
        cavitated = np.zeros(mesh.shape, dtype=bool)
        if pressurised is not None:  # dp/du: 1 on the pressure branch, 0 where u cavitates
            pressure_slope = np.zeros(mesh.shape)
            pressure_slope[unknown] = pressurised
            cavitated[unknown] = ~pressurised
        elif scene.effects.cavitation != "none":
            cavitated[unknown] = w / scale > p
        if mass_conserving:
            theta = content_field(mesh, unknown, split)
            reynolds = JFOSolution(pressure=pressure, content=theta, cavitated=cavitated, iterations=0, residual=0.0,
                                   converged=True, face_content=upwind_content(mesh, theta, scene.operating.speed),
                                   unknown=unknown)
        else:
            reynolds = ReynoldsSolution(pressure=pressure, cavitated=cavitated, iterations=0, residual=0.0,
                                        converged=True)
    area = mesh.nodal_area
    total = pressure + contact_pressure
    state = State(
        z=it.z, delta=it.delta, film=film, contact_pressure=contact_pressure, fluid_pressure=pressure,
        expected_gap=h_t, reynolds=reynolds, contact_force=float(np.sum(contact_pressure * area)),
        fluid_force=fluid_load(model, pressure, film), contact_slope=contact_slope if model.contact is not None else None,
        flow_coefficient=k, faces=faces, face_slopes=face_slopes, squeeze_content=content,
    )
    scale_h = film_scale(model)
    r_delta = None if model.deformation is None else it.delta - model.deformation(total)
    pressure_scale = max(float(np.max(total)), nominal)
    outflow_error = None
    if reynolds is not None:
        reynolds.residual = float(np.max(np.abs(exact), initial=0.0)) / pressure_scale
        outflow_error = parts.scale * exact
    target, load_slope = (force, 0.0) if model.load is None else model.load.force(it.z)
    load_weight, load_film_slope = fluid_load_slopes(model, state)
    return Linearisation(state, r_p, r_delta, scale_h * (state.total_force - target) / force, unknown, contact_slope,
                         pressure_scale, scale_h, smoothing, load_slope, slopes, parts, load_weight,
                         np.zeros(mesh.shape) if load_film_slope is None else load_film_slope, outflow_floor,
                         variable, pressure_slope, universal, outflow_error)


def newton_direction(model: Model, lin: Linearisation, forcing: float, influence: np.ndarray | None = None,
                     kept: KeptPreconditioner | None = None, whole: bool = False):
    """(d pressure (ny, nx), d delta (ny, nx), d z, dF/dz at fixed delta) of the Newton step:
    the pressure eliminated with the LU factors of J_pp, then (delta, z) (module docstring);
    ``influence``: K as a dense matrix (dense_influence) for the dense reduced solve of
    small meshes, else GMRES, its preconditioner ``kept`` across the steps of a solve while it
    serves (KeptPreconditioner). Raises RuntimeError where a linear solve fails."""
    mesh = model.mesh
    area = lin.load_weight  # dF/dp: the nodal areas (with the far inlet's weight)
    force = model.scene.operating.force
    weight = lin.film_scale / force
    lu = lin.j_pp_factors

    def pressure_response(dh):
        """Change of the fluid pressure (ny, nx) for a film change dh (ny, nx), R_p held."""
        out = np.zeros(mesh.shape)
        if lu is not None:
            out[lin.unknown] = lu.solve(-(lin.j_ph @ dh.ravel()))
        return out

    base = np.zeros(mesh.shape)  # pressure step at fixed film
    if lu is not None:
        base[lin.unknown] = lu.solve(-lin.r_p)
    fluid_per_dz = pressure_response(np.ones(mesh.shape))
    # dF/dz at fixed delta, N/m (< 0)
    stiffness = float(np.sum((lin.physical(fluid_per_dz) + lin.contact_slope) * area) + np.sum(lin.load_film_slope))
    base_pressure = lin.physical(base)
    if model.deformation is None:
        dz = (-lin.r_z - weight * float(np.sum(base_pressure * area))) / (weight * (stiffness - lin.load_slope))
        return base + dz * fluid_per_dz, None, dz, stiffness

    n = mesh.nx * mesh.ny
    rhs = np.append((-lin.r_delta + model.deformation(base_pressure)).ravel(),
                    -lin.r_z - weight * float(np.sum(base_pressure * area)))
    if influence is not None:
        y = dense_reduced_solve(model, lin, lu, weight, rhs, influence)
    else:
        y = krylov_reduced_solve(model, lin, lambda dh: lin.physical(pressure_response(dh)), weight, rhs, forcing,
                                 kept, whole)
    d_delta, dz = y[:n].reshape(mesh.shape), float(y[n])
    return base + pressure_response(d_delta + dz), d_delta, dz, stiffness


def dense_step_serves(model: Model) -> bool:
    """Whether the Newton's reduced system is solved densely on ``model``'s mesh (a line
    contact of at most DENSE_NODES nodes), where its steps are cheap and robust."""
    return model.mesh.line and model.mesh.nx <= DENSE_NODES


def dense_influence(model: Model) -> np.ndarray | None:
    """K as a dense (n, n) matrix (physics/deformation.ElasticDeformation.matrix, built once
    per mesh), for a deforming model of at most DENSE_NODES nodes (line contacts), else None."""
    if model.deformation is None or not dense_step_serves(model):
        return None
    return model.deformation.matrix


def dense_reduced_solve(model: Model, lin: Linearisation, lu, weight: float, rhs: np.ndarray,
                        influence: np.ndarray) -> np.ndarray:
    """(d delta, dz) of the reduced system by a dense LU: T, the total pressure per unit film
    change, from the sparse factors of J_pp (one solve with many right-hand sides), and K
    (``influence``, dense_influence)."""
    mesh = model.mesh
    n = mesh.nx * mesh.ny
    response = np.diag(lin.contact_slope.ravel())
    if lu is not None:
        fluid = np.zeros((n, n))
        fluid[lin.unknown.ravel()] = lu.solve(-lin.j_ph.toarray())
        response = response + lin.physical(np.ones(mesh.shape)).reshape(n, 1) * fluid  # pressure per film
    coupled = influence @ response
    area, film_slope = lin.load_weight.ravel(), lin.load_film_slope.ravel()
    matrix = np.zeros((n + 1, n + 1))
    matrix[:n, :n] = np.eye(n) - coupled
    matrix[:n, n] = -coupled.sum(axis=1)
    matrix[n, :n] = weight * (area @ response + film_slope)
    matrix[n, n] = weight * (float(area @ response.sum(axis=1)) + float(film_slope.sum()) - lin.load_slope)
    y = np.linalg.solve(matrix, rhs)
    if not np.all(np.isfinite(y)):
        raise RuntimeError("the Newton step's dense solve gave non-finite values")
    return y


@dataclass
class NearFieldPreconditioner:
    """An approximate inverse of the reduced (delta, z) system (newton_direction): the same
    Newton system with the pressure kept as an unknown and K cut to its near field
    (physics/deformation.ElasticDeformation.near_field), sparse in (pressure, delta),

        [ J_pp        J_ph      ] [dp    ]   [0     ]
        [ -K_n E      I - K_n C ] [ddelta] = [v     ] - dz b,
        w a.(E dp + C (ddelta + dz)) - w F'(z) dz = v_z,

    (E: the Reynolds unknowns among the nodes, C: the contact slope, a: nodal areas, w the
    force row's weight), factorised once (SuperLU) and bordered by z through its Schur
    complement. Exact when K is its near field; applying it is one pair of triangular solves.
    The block is factorised in scaled units (pressures by p_s, films by h_s): in Pa and m its
    entries span ~25 decades, and its LU lost six digits on a 15 x 9 mesh."""

    lu: object  # SuperLU factors of the scaled (pressure, delta) block
    units: np.ndarray  # the unknowns' scales (p_s for pressures, h_s for films)
    unknowns: int  # Reynolds unknowns (the leading rows)
    column: np.ndarray  # the block's inverse times the dz column b
    row: np.ndarray  # the force row over (pressure, delta)
    schur: float  # the z pivot left after eliminating (pressure, delta)

    @classmethod
    def build(cls, model: Model, lin: Linearisation, weight: float) -> "NearFieldPreconditioner":
        mesh = model.mesh
        n, m = mesh.nx * mesh.ny, lin.j_pp.shape[0]
        near = model.deformation.near_field(NEAR_FIELD_RADIUS)
        # the unknowns' pressures among the nodes, per unit of the pressure unknown (Linearisation.physical)
        embed = sp.csr_matrix((lin.physical(np.ones(mesh.shape))[lin.unknown], (np.flatnonzero(lin.unknown.ravel()),
                                                                                  np.arange(m))), shape=(n, m))
        slope, area, film_slope = lin.contact_slope.ravel(), lin.load_weight.ravel(), lin.load_film_slope.ravel()
        j_ph = sp.csr_matrix(lin.j_ph)
        block = sp.bmat([[lin.j_pp, j_ph], [-(near @ embed), sp.identity(n) - near @ sp.diags(slope)]], format="csc")
        units = np.concatenate([np.full(m, lin.pressure_scale), np.full(n, lin.film_scale)])
        lu = splu(sp.csc_matrix(sp.diags(1.0 / units) @ block @ sp.diags(units)), permc_spec="MMD_AT_PLUS_A")
        preconditioner = cls(lu, units, m, np.zeros(m + n), np.zeros(m + n), 1.0)
        column = preconditioner.block_solve(np.concatenate([j_ph @ np.ones(n), -(near @ slope)]))
        row = weight * np.concatenate([embed.T @ area, area * slope + film_slope])
        corner = weight * (float(area @ slope) + float(film_slope.sum()) - lin.load_slope)
        return cls(lu, units, m, column, row, corner - float(row @ column))

    def block_solve(self, rhs: np.ndarray) -> np.ndarray:
        """The (pressure, delta) block's solution for ``rhs`` (Pa-rows, m-rows), in Pa and m."""
        return self.units * self.lu.solve(rhs / self.units)

    def apply(self, v: np.ndarray) -> np.ndarray:
        """(d delta, dz) for the right-hand side v = (delta rows, force row)."""
        x = self.block_solve(np.concatenate([np.zeros(self.unknowns), v[:-1]]))
        dz = (v[-1] - float(self.row @ x)) / self.schur
        return np.append((x - dz * self.column)[self.unknowns:], dz)


@dataclass
class KeptPreconditioner:
    """The NearFieldPreconditioner an earlier Newton step factorised on ``mesh``: of the same
    solve, or in time of an earlier step of the run on that mesh (Squeeze.preconditioner; each
    time step changes c0 and the film a little, as the Newton steps of one solve change the
    film). krylov_reduced_solve reuses it while GMRES meets its tolerance with it within one
    restart cycle (GMRES_RESTART iterations, about one factorisation's time), else factorises
    anew, and in time factorises anew for the next direction once it needs more than
    KEPT_GROWTH times the iterations it needed fresh (``growth``)."""

    preconditioner: NearFieldPreconditioner | None = None
    mesh: Mesh | None = None  # the mesh it was factorised on
    fresh_iterations: int = 0  # GMRES iterations of the direction it was factorised for
    # dropped past this many times its fresh iterations (a run's steps); None: kept while it
    # serves within one restart cycle (a steady solve)
    growth: float | None = KEPT_GROWTH

    def serves(self, mesh: Mesh, unknowns: int) -> bool:
        """Whether a preconditioner is kept for ``mesh`` with that many Reynolds unknowns."""
        return self.preconditioner is not None and self.mesh is mesh and self.preconditioner.unknowns == unknowns

    def keep(self, preconditioner: NearFieldPreconditioner | None, mesh: Mesh, iterations: int):
        """Keep a fresh ``preconditioner`` of ``mesh``, under which GMRES needed ``iterations``."""
        self.preconditioner, self.mesh, self.fresh_iterations = preconditioner, mesh, iterations

    def used(self, iterations: int):
        """Drop the preconditioner where it needed ``iterations``, more than ``growth`` times its fresh count."""
        if self.growth is not None and iterations > self.growth * max(self.fresh_iterations, 1):
            self.preconditioner = None


def krylov_reduced_solve(model: Model, lin: Linearisation, pressure_response, weight: float, rhs: np.ndarray,
                         forcing: float, kept: KeptPreconditioner | None = None, whole: bool = False) -> np.ndarray:
    """(d delta, dz) of the reduced system by GMRES to a residual of ``forcing`` times its
    right-hand side, and where ``whole`` at most ``forcing`` h_s |R| too (GMRES_FORCING), each
    product one back-substitution with
    the factors of J_pp and one FFT, preconditioned (NearFieldPreconditioner; ``kept``'s while
    it serves) where there is a fluid. Raises RuntimeError when GMRES does not reach its
    tolerance (its direction then need not lower the residual)."""
    mesh = model.mesh
    n = mesh.nx * mesh.ny
    area, film_slope = lin.load_weight, lin.load_film_slope
    target = forcing * float(np.linalg.norm(rhs))
    if whole:
        target = min(target, forcing * lin.film_scale * np.sqrt(2.0 * lin.merit()))

    def matvec(y):
        d_delta, dz = y[:n].reshape(mesh.shape), y[n]
        dp = pressure_response(d_delta + dz) + lin.contact_slope * (d_delta + dz)
        return np.append((d_delta - model.deformation(dp)).ravel(),
                         weight * (float(np.sum(dp * area) + np.sum(film_slope * (d_delta + dz))) - lin.load_slope * dz))

    operator = LinearOperator((n + 1, n + 1), matvec=matvec, dtype=float)

    def attempt(near: NearFieldPreconditioner | None):
        """(y, info, GMRES iterations) preconditioned by ``near`` (None: none)."""
        iterations = []
        preconditioner = None if near is None else LinearOperator((n + 1, n + 1), matvec=near.apply, dtype=float)
        y, info = gmres(operator, rhs, rtol=0.0, atol=target, restart=GMRES_RESTART, maxiter=GMRES_CYCLES,
                        M=preconditioner, callback=iterations.append, callback_type="pr_norm")
        return y, (info if np.all(np.isfinite(y)) else -1), len(iterations)

    fluid = lin.j_pp is not None and lin.j_pp.shape[0]
    if fluid and kept is not None and kept.serves(mesh, lin.j_pp.shape[0]):
        y, info, iterations = attempt(kept.preconditioner)
        if info == 0 and iterations <= GMRES_RESTART:
            kept.used(iterations)
            return y
    near = NearFieldPreconditioner.build(model, lin, weight) if fluid else None
    y, info, iterations = attempt(near)
    if kept is not None:
        kept.keep(near, mesh, iterations)
    if info != 0:
        raise RuntimeError(f"GMRES of the Newton step did not reach its tolerance {target:.2g} m (info {info})")
    return y


def longest_film_step(model: Model, lin: Linearisation, d_delta, dz) -> float:
    """The largest step fraction (<= 1) that keeps a smooth film positive: no node's film
    closes by more than FILM_STEP_FRACTION of itself. 1 with asperity contact."""
    if model.contact is not None or not model.hydrodynamic:
        return 1.0
    dh = dz + (0.0 if d_delta is None else d_delta)
    dh = np.broadcast_to(dh, lin.state.film.shape)
    closing = dh < 0.0
    if not closing.any():
        return 1.0
    return float(min(1.0, FILM_STEP_FRACTION * np.min(lin.state.film[closing] / -dh[closing])))


def converged(model: Model, lin: Linearisation, tolerance: float, stiffness: float | None = None,
              stalled: bool = False) -> bool:
    """The stopping tests of the module docstring; ``stiffness``: dF/dz (N/m) of the last
    Newton direction, with which a time step judges its force balance by the displacement
    that would close it (integrator.Squeeze.settled_position); ``stalled``: the Newton has
    stalled (STALL_ITERATIONS), and a Newtonian film's step judges its pressure by its own
    tolerance instead of solver.tolerance (integrator.Squeeze.settled_pressure: the steady
    test is pursued while the iteration converges, and the step's own met where it cannot)."""
    force_ok = abs(lin.r_z) / lin.film_scale <= tolerance
    if not force_ok and newtonian_step(model) and stiffness is not None:
        imbalance = lin.r_z * model.scene.operating.force / lin.film_scale  # N
        force_ok = model.squeeze.settled_position(imbalance / (stiffness - lin.load_slope))
    reynolds_ok = lin.state.reynolds is None or lin.state.reynolds.residual <= tolerance
    if reynolds_ok and newtonian_step(model) and lin.outflow_error is not None:
        reynolds_ok = model.squeeze.settled_outflow(lin.outflow_error, model.mesh.nodal_area[lin.unknown],
                                                    lin.state.film[lin.unknown])
    if not reynolds_ok and stalled and newtonian_step(model):
        reynolds_ok = model.squeeze.settled_pressure(lin.state.reynolds.residual)
    deformation_ok = True
    if lin.r_delta is not None and model.squeeze is not None:
        deformation_ok = model.squeeze.settled(lin.state.film, lin.r_delta)
    elif lin.r_delta is not None:
        reach = max(float(np.ptp(lin.state.delta)), lin.film_scale)
        deformation_ok = float(np.max(np.abs(lin.r_delta))) <= tolerance * reach
    return force_ok and reynolds_ok and deformation_ok


def smoothing_for(lin: Linearisation) -> float:
    """The Fischer-Burmeister smoothing of the next step, Pa: SMOOTHING_FACTOR times the
    scaled residual norm times p_s, so it vanishes as the iteration converges (a smoothing
    Newton method, Chen, Qi & Sun 1998, Math. Comp. 67:519)."""
    return SMOOTHING_FACTOR * min(1.0, np.sqrt(2.0 * lin.merit())) * lin.pressure_scale


def measures_sealed_cells(model: Model) -> bool:
    """Whether a stalled Newton on ``model`` retries with the open film's outflow scale
    (newton): a steady solve of a Newtonian film between rough surfaces, whose percolation
    law seals cells (a time step has its own floor, Squeeze.outflow_scale_floor; a grease's
    solves were not tried with it)."""
    return model.squeeze is None and model.contact is not None and model.hydrodynamic and yield_stress_law(model) is None


def universal_applies(model: Model) -> bool:
    """Whether ``model``'s Reynolds condition is written in the universal variable first
    (linearise, newton): a steady Newtonian film with Swift-Stieber cavitation. A grease's
    outflow is not linear in the pressure, and its Jacobian keeps the Fischer-Burmeister rows.
    A time step keeps them too, with its projected line search (projects_pressure): with the
    universal variable in the steps, the Table 1 line stops of tests/test_return_stroke.py,
    forward and mirrored, drifted apart by 1.8e-3 in film and 1.2e-3 in reconnect time
    (their tolerance 1e-3; thirty-seventh session)."""
    return (model.hydrodynamic and model.squeeze is None and model.scene.effects.cavitation == "reynolds"
            and yield_stress_law(model) is None)


def newton(model: Model, start: Iterate, tolerance: float, max_iterations: int):
    """Newton from ``start`` (newton_on): (linearisation at the last iterate, iterations,
    dF/dz, failure message or ""). Where universal_applies, first with the Reynolds condition
    in the universal variable, then, where that fails, with the Fischer-Burmeister function
    from the same start (its pressures held at p >= 0), the failure naming both. Measured on
    the figures' 854 points by one Newton (config/newton.yaml, thirty-seventh session): the
    Fischer-Burmeister function alone failed at 2 (Fig. 4 with alpha fixed, the honed
    surface), the universal variable alone at 3 others (Fig. 12 at 30 N), the two in turn at
    none, and the sum of the points' solve times fell from 621 to 547 s."""
    if not universal_applies(model):
        return newton_on(model, start, tolerance, max_iterations, universal=False)
    first = newton_on(model, start, tolerance, max_iterations, universal=True)
    if not first[3]:
        return first
    second = newton_on(model, Iterate(np.maximum(start.pressure, 0.0), start.delta, start.z), tolerance,
                       max_iterations, universal=False)
    iterations = first[1] + second[1]
    if not second[3]:
        return second[0], iterations, second[2], ""
    return first[0], iterations, first[2], f"{first[3]}; with the Fischer-Burmeister function too: {second[3]}"


def newton_on(model: Model, start: Iterate, tolerance: float, max_iterations: int, universal: bool):
    """Newton with backtracking from ``start`` (newton_iteration, ``universal``: linearise):
    (linearisation at the last iterate, iterations, dF/dz, failure message or ""). Where it fails on a model that
    measures_sealed_cells, a second Newton from the same start scales each cell's outflow by
    at least the open film's diagonal (fluid_film.open_film_diagonal), and a third from its solution
    polishes it with the cells' own scales, whose tests are the ones met: the floor changes
    the path, not the solution (a complementarity pair's zero set does not depend on the
    positive scale of one partner). The first Newton's result where either fails, its failure
    naming both."""
    result = newton_iteration(model, start, tolerance, max_iterations, universal=universal)
    if not result[3] or not measures_sealed_cells(model):
        return result
    floored = newton_iteration(model, start, tolerance, max_iterations, open_film_floor=True, universal=universal)
    iterations = result[1] + floored[1]
    if floored[3]:
        return result[0], iterations, result[2], f"{result[3]}; on the open film's outflow scale too: {floored[3]}"
    polished = newton_iteration(model, floored[0].iterate(), tolerance, max_iterations, universal=universal)
    if polished[3]:
        return result[0], iterations + polished[1], result[2], (
            f"{result[3]}; converged on the open film's outflow scale, but not from there on the cells' own: {polished[3]}")
    return polished[0], iterations + polished[1], polished[2], ""


def newton_iteration(model: Model, start: Iterate, tolerance: float, max_iterations: int,
                     open_film_floor: bool = False, universal: bool = False):
    """Newton with backtracking from ``start``, each cell's outflow scaled by at least the
    open film's diagonal where ``open_film_floor``, the Reynolds condition in the universal
    variable where ``universal`` (linearise): (linearisation at the last iterate, iterations,
    dF/dz, failure message or "")."""
    it = start
    floor = open_film_diagonal(model) if open_film_floor else None
    try:
        lin = linearise(model, it, outflow_floor=floor, universal=universal)
        lin = linearise(model, it, smoothing_for(lin), floor, universal)
    except ValueError as err:
        return None, 0, None, f"the start is outside the model: {err}"
    stiffness = None
    forcing = 0.1
    influence = dense_influence(model)
    kept = KeptPreconditioner(growth=None) if model.squeeze is None else model.squeeze.preconditioner
    history = [lin.merit()]
    memory = NONMONOTONE_MEMORY if yield_stress_law(model) is None else 1
    best = (lin, None)  # the iterate of least merit, and dF/dz of its Newton direction
    for iteration in range(1, max_iterations + 1):
        if converged(model, lin, tolerance, stiffness):
            return lin, iteration - 1, stiffness, ""
        if len(history) > STALL_ITERATIONS and history[-1] > STALL_FACTOR * history[-1 - STALL_ITERATIONS]:
            best_lin, best_stiffness = best[0], stiffness if best[1] is None else best[1]
            if converged(model, best_lin, tolerance, best_stiffness, stalled=True):
                return best_lin, iteration - 1, best_stiffness, ""
            return lin, iteration, stiffness, (
                f"Newton stalled: the scaled residual norm fell from {np.sqrt(2 * history[-1 - STALL_ITERATIONS]):.3g} "
                f"only to {np.sqrt(2 * history[-1]):.3g} in {STALL_ITERATIONS} iterations")
        merit = lin.merit()
        try:
            direction = newton_direction(model, lin, forcing, influence, kept)
            stiffness = direction[3]
            if lin is best[0]:
                best = (lin, stiffness)
            accepted, full = line_search(model, it, lin, direction, max(history[-memory:]))
            whole = accepted is None and influence is None and model.deformation is not None
            if whole:  # GMRES's direction, inexact relative to the reduced system: to the whole residual
                direction = newton_direction(model, lin, forcing, influence, kept, whole)
                accepted, full = line_search(model, it, lin, direction, max(history[-memory:]))
            if accepted is None and full is not None and lin.slopes is not None and not lin.universal \
                    and full.slopes is not None and full.slopes[0].size == lin.slopes[0].size:
                # a cavitation pair changed branch within the step (its outflow crossed zero
                # steeply, as in a squeezed cell of low permeability): the generalised Jacobian
                # of the full step's point, as an active-set method would take it (the
                # Fischer-Burmeister rows; the universal variable's branches are the signs of
                # u, which the line search itself crosses)
                direction = newton_direction(model, lin.rebranched(full.slopes), forcing, influence, kept, whole)
                accepted, _ = line_search(model, it, lin, direction, max(history[-memory:]))
        except RuntimeError as err:
            return lin, iteration, stiffness, f"Newton step {iteration}: {err}"
        if accepted is None:
            return lin, iteration, stiffness, (
                f"Newton step {iteration}: no step of the Newton direction down to {SMALLEST_STEP:g} of it lowers "
                f"the residual (scaled residual norm {np.sqrt(2 * merit):.3g})")
        trial, candidate = accepted
        it, lin = trial, candidate
        if smoothing_for(candidate) < SMOOTHING_UPDATE * candidate.smoothing:
            lin = linearise(model, it, smoothing_for(candidate), candidate.outflow_floor, candidate.universal)
        forcing = min(0.1, GMRES_FORCING + np.sqrt(lin.merit() / max(merit, 1e-300)))
        history.append(lin.merit())
        if lin.merit() < best[0].merit():
            best = (lin, None)
    if converged(model, lin, tolerance, stiffness):
        return lin, max_iterations, stiffness, ""
    return lin, max_iterations, stiffness, f"{max_iterations} Newton iterations without meeting the tolerances"


def line_search(model: Model, it: Iterate, lin: Linearisation, direction, reference: float):
    """Armijo backtracking along ``direction`` (newton_direction): a step is taken when its
    merit is enough below ``reference`` (newton passes the largest merit of its last
    NONMONOTONE_MEMORY iterates for a Newtonian film, a grease's current one); where
    projects_pressure, each trial point's pressure is projected onto p >= 0.
    ((iterate, its linearisation) of the first step taken, or None; the linearisation at the
    longest step tried, or None where it left the model)."""
    d_p, d_delta, dz, _ = direction
    step = longest_film_step(model, lin, d_delta, dz)
    projected = projects_pressure(model)
    merit = reference
    first = None
    while step >= SMALLEST_STEP:
        pressure = it.pressure + step * d_p
        trial = Iterate(np.maximum(pressure, 0.0) if projected else pressure,
                        it.delta if d_delta is None else it.delta + step * d_delta, it.z + step * dz)
        try:
            candidate = linearise(model, trial, lin.smoothing, lin.outflow_floor, lin.universal)
        except ValueError:
            candidate = None
        if candidate is not None:
            first = candidate if first is None else first
            if candidate.merit() <= (1.0 - 2.0 * SUFFICIENT_DECREASE * step) * merit:
                return (trial, candidate), first
        step *= 0.5
    return None, first


def dry_position(model: Model, delta: np.ndarray) -> float:
    """z at which the asperity contact alone carries the force at deformation ``delta``
    (the contact force falls with z: a bracketed root, auto_effects.decreasing_root;
    docs/physics.md section 2)."""
    force, area = model.scene.operating.force, model.mesh.nodal_area
    sigma = model.contact.sigma
    gap = model.undeformed_gap + delta
    return decreasing_root(lambda z: float(np.sum(model.contact.pressure(gap + z) * area)) - force,
                           0.0, sigma, 1e-9 * sigma)


def hertz_pressure(model: Model) -> np.ndarray:
    """Hertz's line-contact pressure p0 sqrt(1 - x^2/b^2), p0 = 2 w'/(pi b), on the mesh
    (Pa; Johnson 1985, eq. 4.44; docs/physics.md section 6)."""
    scene, mesh = model.scene, model.mesh
    half_width = hertz_half_width(scene)
    peak = 2.0 * scene.operating.force / scene.geometry.length / (np.pi * half_width)
    profile = peak * np.sqrt(np.maximum(1.0 - (mesh.x / half_width) ** 2, 0.0))
    return np.broadcast_to(profile, mesh.shape).copy()


def cold_start(model: Model) -> Iterate:
    """A start from the physics: rough surfaces at the asperities' dry balance, deformed by
    their own pressure; smooth ones deformed by Hertz's pressure, the cylinder at the
    isoviscous-elastic (or rigid) film estimate (docs/physics.md sections 4-6); then the
    Reynolds pressure of that film (numerics/reynolds.solve_reynolds). A smooth grease starts
    as the Newtonian lubricant of its flowing viscosity (grease_start.newtonian_stand_in)."""
    mesh = model.mesh
    delta = np.zeros(mesh.shape)
    fluid = model
    if model.contact is not None:
        z = dry_position(model, delta)
        if model.deformation is not None:
            delta = model.deformation(model.contact.pressure(model.undeformed_gap + z))
            z = dry_position(model, delta)
    else:
        fluid = newtonian_stand_in(model)
        if model.deformation is not None:
            delta = model.deformation(hertz_pressure(model))
        z = start_film(fluid.scene, model.deformation is not None) - float(np.min(model.undeformed_gap + delta))
    pressure = np.zeros(mesh.shape)
    if model.hydrodynamic:
        pressure = reynolds_pressure(fluid, model.undeformed_gap + z + delta)
    return Iterate(pressure, delta, z)


def reynolds_pressure(model: Model, film: np.ndarray) -> np.ndarray:
    """The Reynolds pressure (Pa, (ny, nx)) of ``film`` (numerics/reynolds.solve_reynolds)."""
    h_t, k = fluid_film(model, film)
    faces, _ = fluid_faces(model, film)
    return solve_reynolds(model.mesh, h_t, k, model.scene.operating.speed, faces=faces,
                          exterior=fluid_exterior(model, film), cavitation=model.scene.effects.cavitation != "none").pressure


def transferred(coarse: Model, fine: Model, it: Iterate) -> Iterate:
    """A coarse-mesh iterate interpolated to the fine mesh (bilinear; pressure kept >= 0);
    a Newtonian film's pressure then solved again on the fine mesh's film (reynolds_pressure):
    the interpolated one left a Reynolds residual of 0.11 of the peak pressure on Table 1 at
    1 m/s, and its fine Newton took 9 iterations instead of 7 (thirty-fifth session). A
    grease's keeps the interpolated one (its pressure is not the Newtonian Reynolds one)."""
    delta = interpolate_field(it.delta, coarse.mesh, fine.mesh)
    pressure = np.maximum(interpolate_field(it.pressure, coarse.mesh, fine.mesh), 0.0)
    if fine.hydrodynamic and yield_stress_law(fine) is None:
        pressure = reynolds_pressure(fine, fine.undeformed_gap + it.z + delta)
    return Iterate(pressure, delta, it.z)


def nominal_pressure(model: Model) -> float:
    """The load over the mesh's area, Pa: the pressure scale of a sealed cell's outflow and
    the unit P of JFO's universal variable (linearise)."""
    return model.scene.operating.force / float(np.sum(model.mesh.nodal_area))


def warm_iterate(model: Model, initial: WarmStart) -> Iterate | None:
    """The iterate of a WarmStart on this mesh (a sweep's previous point, a time step's
    predictor), else None; with JFO its film content goes into the universal variable,
    u = (theta - 1) P where theta < 1 (numerics/jfo_outflow.py): started at theta = 1 instead,
    the 100 Pa s fretting's step at rest (t = 27 ms) found no descent from a residual of 0.42."""
    shape = model.mesh.shape
    if initial is None or initial.z is None:
        return None
    delta = np.zeros(shape)
    if initial.delta is not None and np.size(initial.delta) == delta.size and model.deformation is not None:
        delta = np.asarray(initial.delta, dtype=float).reshape(shape)
    pressure = np.zeros(shape)
    if initial.pressure is not None and np.shape(initial.pressure) == shape:
        pressure = np.maximum(np.asarray(initial.pressure, dtype=float), 0.0)
    content = initial.content
    if model.scene.effects.cavitation == "jfo" and content is not None and np.shape(content) == shape:
        pressure = np.where(content < 1.0, (content - 1.0) * nominal_pressure(model), pressure)
    return Iterate(pressure, delta, float(initial.z))


def at_force(model: Model, force: float) -> Model:
    """The same model under another applied force."""
    scene = model.scene
    return dataclasses.replace(model, scene=dataclasses.replace(
        scene, operating=dataclasses.replace(scene.operating, force=float(force))))


def at_speed(model: Model, speed: float) -> Model:
    """The same model, on the same mesh, sliding at another speed (the far inlet rebuilt for it)."""
    return Model.assemble(model.scene.replace({"operating.speed": float(speed)}), model.mesh, model.contact)


def at_yield_stress(model: Model, yield_stress: float) -> Model:
    """The same model with a grease of another yield stress (Pa)."""
    scene = model.scene
    return dataclasses.replace(model, scene=dataclasses.replace(
        scene, lubricant=dataclasses.replace(scene.lubricant, yield_stress=float(yield_stress))))


@dataclass(frozen=True)
class Continuation:
    """A path to the scene's own point through the same model at a multiple of one of its
    inputs: ``variant(model, fraction)`` is the model at that fraction of it, ``word`` names
    it in a failure ("load continuation stopped at 0.33 of the force")."""

    word: str
    quantity: str
    variant: Callable[[Model, float], Model]


LOAD = Continuation("load", "force", lambda model, fraction: at_force(model, model.scene.operating.force * fraction))
SPEED = Continuation("speed", "speed", lambda model, fraction: at_speed(model, model.scene.operating.speed * fraction))
YIELD = Continuation("yield-stress", "yield stress",
                     lambda model, fraction: at_yield_stress(model, model.scene.lubricant.yield_stress * fraction))


def continued(model: Model, fraction: float, lin: Linearisation, path: Continuation, tolerance: float):
    """From ``lin``, converged at ``fraction`` (< 1) of the input ``path`` varies, to the
    model's own point in steps that double it, each step halved (up to CONTINUATION_HALVINGS
    times) where Newton fails on it: (linearisation, iterations, stiffness, failure)."""
    limit = model.scene.solver.max_iterations
    total, stiffness, failure = 0, None, ""
    while fraction < 1.0:
        target = min(1.0, 2.0 * fraction)
        for _ in range(CONTINUATION_HALVINGS + 1):
            step_model = model if target == 1.0 else path.variant(model, target)
            trial, iterations, stiffness, failure = newton(step_model, lin.iterate(), tolerance, limit)
            total += iterations
            if not failure:
                lin, fraction = trial, target
                break
            target = 0.5 * (fraction + target)
        if failure:
            return trial, total, stiffness, (f"{path.word} continuation stopped at {fraction:.3g} of the "
                                             f"{path.quantity}: {failure}")
    return lin, total, stiffness, ""


def continuation_paths(model: Model) -> list[tuple[Continuation, list[float]]]:
    """The paths a failed Newton tries in turn, each with the fractions its cold starts try:
    the load from 1/2, 1/4, ... of it; then, for a sliding rough contact, the speed from
    1/2, 1/4, ... of it (the asperities carry the slower contact); last, for a grease, its
    yield stress from 1/2, 1/4, ... of it (the cold start's pressure is the Newtonian film's,
    which a lower yield stress leaves nearer the solution). Near lift-off the load path
    crosses a touch-down (docs/physics.md section 23) and stalls: on Table 1 at 20 N and
    0.1 m/s (51 x 51), after the cold start and the load path stall, the speed path from half
    the speed converges, 9 s in all (tests/test_hard_cases.py, thirty-fifth session; 27 s
    since each stalled Newton of the load path is retried on the open film's scale). Not
    from above: cold starts at 2 to 64 times 0.158 m/s on the same mesh all failed, 39 s in
    all. The yield stress's path: a smooth rigid line at 1 kPa, 0.2 N and 1 m/s on 151 or 201
    nodes, whose Newton ran from the cold start to a film of 5 mm (the scaled Reynolds
    residual of a smooth pressure error falls as the film thickens and the mesh refines) and
    whose load path's cold starts all failed, converges from 1/2 of its yield stress in about
    1 s (forty-fifth session; tests/test_yield_stress_reynolds.py against a shooting solver).
    Last, not first: tried first, it took a 2-D rough grease at 0.003 m/s, whose coarse
    mesh's load path converges, 47 s (1566 Newton iterations) instead of 2 s."""
    fractions = [2.0**-k for k in range(1, CONTINUATION_HALVINGS + 1)]
    paths = [(LOAD, fractions)]
    if model.hydrodynamic and model.contact is not None:
        paths.append((SPEED, fractions))
    if yield_stress_law(model) is not None:
        paths.append((YIELD, fractions))
    return paths


def solve_level(model: Model, start: Iterate, tolerance: float, continuation: bool = True):
    """Newton from ``start``, then, where it fails and ``continuation`` allows, each path of
    continuation_paths in turn from the first of its fractions at which a cold start
    converges: (linearisation, iterations, stiffness, failure, path), the failure naming where
    each path stopped, ``path`` the continuation that reached the point ("" where none did)."""
    limit = model.scene.solver.max_iterations
    result = newton(model, start, tolerance, limit)
    if not result[3] or not continuation:
        return (*result, "")
    failures, total = [], result[1]
    for path, fractions in continuation_paths(model):
        for fraction in fractions:
            other = path.variant(model, fraction)
            lin, iterations, _, failure = newton(other, cold_start(other), tolerance, limit)
            total += iterations
            if not failure:
                lin, more, stiffness, failure = continued(model, fraction, lin, path, tolerance)
                total += more
                if not failure:
                    return lin, total, stiffness, "", f"{path.word} continuation from {fraction:g} of the {path.quantity}"
                failures.append(failure)
                break
        else:
            failures.append(f"{path.word} continuation: no cold start converged at {fractions[0]:g} to "
                            f"{fractions[-1]:g} of the {path.quantity}")
    return (*result[:3], "; ".join([result[3], *failures]), "")


def level_solution(model: Model, initial: WarmStart | None, tolerance: float, continuation: bool = True):
    """(linearisation, iterations, stiffness, failure, path: solve_level) on this mesh, started from a warm
    start on it, else from the solution on the coarser mesh (nested), else cold."""
    start = warm_iterate(model, initial)
    if start is None:
        coarse = model.coarsened(NESTED_COARSEST) if model.contact is not None else None
        if coarse is not None:
            lin, _, _, failure, _ = level_solution(coarse, None, tolerance)
            if lin is not None and not failure:
                state = lin.state
                start = transferred(coarse, model, Iterate(state.fluid_pressure, state.delta, state.z))
        if start is None:
            start = cold_start(model)
    return solve_level(model, start, tolerance, continuation)


def monolithic_solve(model: Model, initial: WarmStart | None = None, tolerance: float | None = None,
                     continuation: bool = True) -> tuple[State, Diagnostics]:
    """Solve the coupled steady contact by one semismooth Newton (module docstring); the
    same (State, Diagnostics) as model/coupling.coupled_solve. ``continuation``: whether a
    failed Newton may go on by continuation (load, then speed: continuation_paths). A failure is reported, never silent:
    ``converged`` False with the message, and the last state evaluated."""
    scene = model.scene
    tol = scene.solver.tolerance if tolerance is None else tolerance
    lin, iterations, stiffness, failure, path = level_solution(model, initial, tol, continuation)
    if lin is None:
        raise SolveError(failure)
    state = lin.state
    return state, Diagnostics(
        iterations=iterations,
        deformation_residual=0.0 if lin.r_delta is None else float(np.max(np.abs(lin.r_delta))),
        force_residual=-lin.r_z * scene.operating.force / lin.film_scale,
        reynolds_residual=0.0 if state.reynolds is None else float(state.reynolds.residual),
        converged=not failure,
        stiffness=None if stiffness is None else -stiffness,
        failure=failure,
        path=path,
    )


def path_notes(diagnostics: Diagnostics) -> list[str]:
    """The note of a solve that reached its point by continuation (Diagnostics.path), else
    none: where the contact has more than one steady state the path decides which."""
    if not diagnostics.path:
        return []
    return [f"one Newton reached this point by {diagnostics.path} (its own cold start did not converge); where "
            "the contact has more than one steady state the path decides which it finds (docs/physics.md section 23)"]


def finished_by_newton(model: Model, state: State, diagnostics: Diagnostics, continued: bool = False):
    """(state, diagnostics, note) where a nested solve stopped without meeting its
    tolerances: one Newton from its last state (no continuation: cheap), then a cold one with
    continuation (continuation_paths); the first that converges, with a note saying so. Else
    the nested solve's own state, its failure naming why each stopped (the nested solver's
    reason first), and an empty note. The cold start was kept to line contacts while a 2-D
    Newton step was a dense solve; with GMRES it takes the two points of Fig. 12 (30 N) where
    the nested solver and the Newton from its state stall: 0.1 and 3.9 s (thirty-sixth
    session). A solve ``continued`` from a warm start (a sweep's previous point) is not
    restarted cold here: a cold start may reach another state (docs/physics.md section 23),
    and the sweep restarts it itself and marks it (studies/sweep.py, cold_restart)."""
    if diagnostics.converged:
        return state, diagnostics, ""
    cold = [] if continued else [("from a cold start", None, True)]
    if model.contact is None and float(np.min(state.film)) < CLOSED_FILM:  # the smooth film closed: no start
        attempts = cold
    else:
        attempts = [("from its last state", WarmStart(z=state.z, delta=state.delta, pressure=state.fluid_pressure,
                                                      content=getattr(state.reynolds, "content", None)),
                     False), *cold]
    why = diagnostics.failure or (f"{diagnostics.iterations} iteration(s) without its deformation change falling below "
                                  f"the tolerance: the last was {diagnostics.deformation_residual:.3g} m")
    newton_failures = []
    for how, start, continuation in attempts:
        try:
            finished, newton_diagnostics = monolithic_solve(model, start, continuation=continuation)
        except SolveError as err:
            newton_failures.append(f"one Newton {how}: {err}")
            continue
        if newton_diagnostics.converged:
            stopped = f"after {diagnostics.iterations} iterations ({why})" if diagnostics.failure else f"after {why}"
            return finished, newton_diagnostics, "; ".join([
                f"the nested solver stopped {stopped}; one Newton {how} converged in {newton_diagnostics.iterations} "
                "Newton iteration(s) (solver.method newton, docs/physics.md section 20)",
                *path_notes(newton_diagnostics)])
        newton_failures.append(f"one Newton {how}: {newton_diagnostics.failure}")
    return state, dataclasses.replace(diagnostics, failure="; then ".join([why, *newton_failures])), ""


# A grease's Poiseuille coefficient depends on the pressure gradient, which the nested
# solver's linear Reynolds solve cannot take: its scenes go to the one Newton, which can.
GREASE_BY_NEWTON = ("lubricant.rheology {}: solved by one Newton (solver.method newton; the nested solver takes a "
                    "pressure-independent coefficient, docs/physics.md section 21)")


def needs_newton(model: Model) -> bool:
    """Whether ``model`` is solved by the one Newton alone: solver.method newton, or a grease."""
    scene = model.scene
    return scene.solver.method == "newton" or scene.lubricant.rheology != "newtonian"


def steady_solve(model: Model, initial: WarmStart | None = None) -> tuple[State, Diagnostics, list[str]]:
    """(state, diagnostics, notes) of a steady point by the scene's solver: the one Newton
    (needs_newton), else the nested solve finished by one Newton where it stops
    (finished_by_newton); the notes say which, where it is not the scene's default."""
    if needs_newton(model):
        notes = [] if model.scene.solver.method == "newton" else [GREASE_BY_NEWTON.format(model.scene.lubricant.rheology)]
        state, diagnostics = monolithic_solve(model, initial)
        return state, diagnostics, notes + path_notes(diagnostics)
    try:
        nested = coupled_solve(model, initial)
    except SolveError as err:  # raised before it had a state to report
        return newton_after_nested_raised(model, initial, err)
    state, diag, finished = finished_by_newton(model, *nested, continued=initial is not None)
    return state, diag, [finished] if finished else []


def newton_after_nested_raised(model: Model, initial: WarmStart | None, error: SolveError):
    """(state, diagnostics, notes) where the nested solve raised before its first state: one
    Newton from the same start, with continuation, the note saying so; SolveError naming
    both failures where it raises too. Seen on a smooth
    line contact whose spacing leaves the Hertz width ten cells (Table 1 without asperity
    contact at 0.01 m/s, 51 nodes on 0.5 mm): the nested solve starts rigid, and the rigid
    film the load needs is thinner than its coarse cells can carry, so the first force
    balance closes the film (tests/test_hard_cases.py, smooth_coarse_line)."""
    try:
        state, diag = monolithic_solve(model, initial)
    except SolveError as newton_error:
        raise SolveError(f"the nested solver: {error}; then one Newton: {newton_error}") from newton_error
    return state, diag, [f"the nested solver stopped at its first force balance ({error}); one Newton with "
                         f"continuation took the solve (solver.method newton, docs/physics.md section 20)",
                         *path_notes(diag)]
