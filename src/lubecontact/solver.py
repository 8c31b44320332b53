"""Coupled solve of one operating point (paper section 2.5 and Fig. 1; Eqs. 1-18).

The cylinder sits at height z above the block; the film is h = h_o + z + delta (Eq. 3) with
the undeformed gap h_o of Eq. (4) and the macro deformation delta. Asperities carry the
nominal contact pressure p_c(h) (Eq. 11), the fluid the Reynolds pressure p(h) (Eq. 1),
and both deform the surfaces: delta = K (p + p_c). The cylinder's position balances the
applied force: F = F_cont + F_fluid (Eq. 18).

Algorithm (only the enabled effects are assembled and run):
0. Nested iteration: with asperity contact, the same problem is first solved on the mesh
   with every other node (recursively, loosely), and the fine mesh starts from its
   position, deformation and cavitated zone (``nested_start``).
1. For the current deformation, find z with the force balance satisfied to
   ``tolerance * F``: safeguarded Newton on the total force, whose slope dF/dz comes with
   each evaluation (contact law slope + Reynolds adjoint, ``force_gradient``); bisection
   once bracketed when a step misbehaves (the contact law has a jump at 1.9 omega_c).
2. Recompute the deformation from the pressures at that z and take a Newton step of the
   fixed point delta -> K(p + p_c): with Reynolds fluid pressure between rough surfaces the
   coupled step of newton.py ((I - K P') step = K(p + p_c) - delta, P' the linearised
   contact and fluid pressure with the force balance kept, by GMRES with the Reynolds
   factors and the FFT operator; 3-6 iterations on Table 1 where the contact-only step took
   4-11; near a fold, where full steps cycle between cavitated sets, they are shortened by
   backtracking, newton.Backtracking). Without fluid (or with JFO or no cavitation) the
   step is preconditioned by the contact part of the Jacobian only,
   (I + K D) step = K(p + p_c) - delta with D = -dp_c/dh >= 0 (a Newton step for the dry
   contact), and accelerated by Anderson mixing (also for smooth steady films, where full
   coupled Newton steps overshoot to h <= 0). The next z is predicted to first order from
   the load gradient, so a balance near convergence takes one evaluation. Stop when the
   change is below ``tolerance`` times the deformation's range.
Consecutive Reynolds solves reuse the previous LU factors as a CG preconditioner while the
pressurised set stays (reynolds.BlockInverse). The solve runs with one BLAS thread.
Every solve reports its residuals and a ``converged`` flag; nothing is silently accepted.
The discrete coupled problem can have more than one converged solution at some hard points
(very smooth surfaces on coarse meshes, where the fluid load jumps as the contact edge
crosses nodes; 500 N at 10 m/s, a fluid-lifted and a contact-carried branch): which one a
solve finds then depends on its start (bench/RESULTS.md, "Several solutions").
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import cache

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from .anderson import AndersonMixer
from .materials import effective_modulus
from .mesh import Mesh, build_mesh
from .newton import Backtracking, coupled_newton_step


class SolveError(RuntimeError):
    """The force balance failed; ``state`` is the last state evaluated (or None). A solve
    reports it as ``converged = 0`` with the message in the case notes, never swallowed."""

    def __init__(self, message: str, state=None):
        super().__init__(message)
        self.state = state


@dataclass
class Model:
    """The sub-models a scene calls for, built once (disabled effects are None / False)."""

    scene: object
    mesh: Mesh
    undeformed_gap: np.ndarray  # h_o of Eq. (4), (ny, nx)
    contact: object | None  # RoughContact when effects.asperity_contact
    deformation: object | None  # ElasticDeformation when effects.elastic_deformation
    hydrodynamic: bool  # Reynolds solved (effect on and speed > 0)
    # A transient step's time derivative of h_T (unsteady.integrator.Squeeze: rate(h_T) m/s,
    # coefficient = d rate/d h_T 1/s, film_scale m), None for a steady solve
    squeeze: object | None = None

    @classmethod
    def assemble(cls, scene, mesh: Mesh | None = None, contact=None) -> "Model":
        """The model of ``scene`` on its mesh (or on ``mesh``, same domain), reusing the
        rough-contact tables ``contact`` of the same scene when given."""
        effects = scene.effects
        mesh = build_mesh(scene) if mesh is None else mesh
        radius = scene.geometry.radius
        gap_x = radius - np.sqrt(radius**2 - mesh.x**2)  # Eq. (4)
        undeformed = np.broadcast_to(gap_x, mesh.shape).copy()
        if not effects.asperity_contact:
            contact = None
        elif contact is None:
            from .effects import contact_table

            contact = contact_table(scene)  # built once per roughness/materials, not per solve
        deformation = None
        if effects.elastic_deformation:
            from .deformation import ElasticDeformation

            deformation = ElasticDeformation(mesh, effective_modulus(scene))
        hydrodynamic = bool(effects.hydrodynamics) and scene.operating.speed > 0.0
        return cls(scene, mesh, undeformed, contact, deformation, hydrodynamic)

    def coarsened(self) -> "Model | None":
        """The same model on the mesh with every other node (same domain) in each direction
        longer than NESTED_COARSEST nodes; None when there is none, or for a transient step
        (its squeeze history lives on this mesh; it starts from the previous step)."""
        from .reynolds import _coarser

        if self.squeeze is not None:
            return None

        coarse = _coarser(self.mesh, NESTED_COARSEST)
        return None if coarse is None else Model.assemble(self.scene, coarse, self.contact)

    @property
    def effects_run(self) -> dict:
        e = self.scene.effects
        return {
            "hydrodynamics": self.hydrodynamic,
            "flow_factors": self.hydrodynamic and self.contact is not None and e.flow_factors,
            "cavitation": self.hydrodynamic and e.cavitation != "none",
            "asperity_contact": self.contact is not None,
            "plasticity": self.contact is not None and e.plasticity,
            "elastic_deformation": self.deformation is not None,
            "alleviation": self.contact is not None and e.alleviation and not e.macro_constriction,
            "macro_constriction": e.macro_constriction,
            "film_conduction": e.film_conduction,
            "tunnelling": e.tunnelling,
        }


@dataclass
class State:
    """Everything at one (z, delta)."""

    z: float
    delta: np.ndarray
    film: np.ndarray  # h, (ny, nx)
    contact_pressure: np.ndarray
    fluid_pressure: np.ndarray
    expected_gap: np.ndarray | None  # h_T used by the fluid
    reynolds: object | None  # ReynoldsSolution
    contact_force: float
    fluid_force: float
    contact_slope: np.ndarray | None = None  # dp_c/dh (Pa/m) of the contact law, <= 0
    flow_coefficient: np.ndarray | None = None  # k used by the fluid, m^3/(Pa s)
    load_gradient: np.ndarray | None = None  # dF/dh_j (N/m), set by balance_force
    # the film on the faces (rough surfaces, percolation.FaceFilm) and its slopes d/dh_f, as
    # the fluid used them (fluid_faces), else None
    faces: object | None = None
    face_slopes: object | None = None

    @property
    def total_force(self) -> float:
        return self.contact_force + self.fluid_force

    @property
    def total_pressure(self) -> np.ndarray:
        return self.contact_pressure + self.fluid_pressure


# Where the mean planes interpenetrate (h < 0) the fluid sees the gap frozen at its h = 0
# value (h_T = sigma/sqrt(2 pi)). For the film content there is a physical reason: below the
# percolation threshold of a Gaussian gap (h = 0, flow_factors.py) the lubricant sits in
# closed pockets, incompressible, and is carried through the contact with the volume it was
# sealed with, so its Couette content stops following h_T(h). The Poiseuille coefficient is
# not floored: it follows the percolation law down to the threshold and leaks below it
# (flow_factors.percolating_coefficient_and_slope), evaluated on the faces
# (percolation.py), where it closes continuously. Friction does not use this floor
# (friction.py: Patir-Cheng shear factors are finite for h <= 0).
FLUID_FILM_FLOOR_SIGMAS = 0.0


def _content_law(model: Model):
    """h -> (h_T, dh_T/dh): Patir-Cheng expected gap, or with flow factors between surfaces of
    unequal roughness (roughness.split != 0.5) the Couette gap h_T + sigma phi_s of the shear
    flow factor (shear_factors.couette_gap)."""
    from .flow_factors import expected_gap_and_slope

    scene = model.scene
    sigma = model.contact.sigma if model.contact is not None else None
    if sigma is not None and scene.effects.flow_factors and scene.roughness.split != 0.5:
        from functools import partial

        from .shear_factors import couette_gap

        return partial(couette_gap, sigma=sigma, split=scene.roughness.split)
    return lambda h: expected_gap_and_slope(h, sigma)


def _coefficient_law(model: Model):
    """h -> (k, dk/dh): Patir-Cheng's Poiseuille coefficient down to percolation (rough
    surfaces), or h^3/(12 mu) (smooth)."""
    from .flow_factors import percolating_coefficient_and_slope, poiseuille_coefficient_and_slope

    scene = model.scene
    law = poiseuille_coefficient_and_slope if model.contact is None else percolating_coefficient_and_slope
    sigma = None if model.contact is None else model.contact.sigma
    return lambda h: law(h, sigma, scene.lubricant.viscosity, scene.effects.flow_factors)


def fluid_film(model: Model, film: np.ndarray, slopes: bool = False):
    """(h_T, k) at the nodes for the Reynolds equation (Eqs. 1-2; _content_law and
    _coefficient_law, the content frozen below FLUID_FILM_FLOOR_SIGMAS); with ``slopes``
    also their derivatives (dh_T/dh, dk/dh) for the adjoint (content slope 0 below the floor)."""
    sigma = model.contact.sigma if model.contact is not None else None
    k, dk = _coefficient_law(model)(film)
    held = np.zeros(film.shape, dtype=bool)
    if sigma is not None:
        held = film < FLUID_FILM_FLOOR_SIGMAS * sigma
        film = np.maximum(film, FLUID_FILM_FLOOR_SIGMAS * sigma)
    h_t, dh_t = _content_law(model)(film)
    if slopes:
        return h_t, k, np.where(held, 0.0, dh_t), dk
    return h_t, k


def fluid_faces(model: Model, film: np.ndarray):
    """(values, slopes) percolation.FaceFilm of the film on the faces (rough surfaces), or
    (None, None) for smooth ones (nodal means, reynolds.py)."""
    if model.contact is None:
        return None, None
    from .percolation import face_film

    return face_film(film, _coefficient_law(model), _content_law(model))


def evaluate(model: Model, z: float, delta: np.ndarray, cavitated_guess=None, reuse=None,
             pressure_guess=None) -> State:
    """Pressures and forces at cylinder position z with deformation delta (Eqs. 3-5, 11).
    ``cavitated_guess`` and ``reuse`` (a previous ReynoldsSolution on this mesh) warm-start
    the Reynolds solve (reynolds.solve_reynolds), or ``pressure_guess`` (a coarser mesh's
    pressure interpolated to this one) a Reynolds-cavitation solve in their place."""
    mesh, scene = model.mesh, model.scene
    film = model.undeformed_gap + z + delta
    area = mesh.nodal_area
    contact_pressure, contact_slope = np.zeros(mesh.shape), None
    if model.contact is not None:
        contact_pressure, contact_slope = model.contact.pressure_and_slope(film)
    fluid_pressure = np.zeros(mesh.shape)
    h_t = k = reynolds = faces = face_slopes = None
    if model.hydrodynamic:
        h_t, k = fluid_film(model, film)
        if scene.effects.cavitation == "jfo":  # mass-conserving cavitation (cavitation_jfo.py)
            from .cavitation_jfo import solve_jfo as solve_fluid
        else:
            from functools import partial

            from .reynolds import solve_reynolds

            solve_fluid = partial(solve_reynolds, cavitation=scene.effects.cavitation == "reynolds",
                                  pressure_guess=pressure_guess)
        faces, face_slopes = fluid_faces(model, film)
        transient = {} if model.squeeze is None else {"squeeze_rate": model.squeeze.rate(h_t)}  # unsteady/
        reynolds = solve_fluid(mesh, h_t, k, scene.operating.speed, cavitated_guess=cavitated_guess, reuse=reuse,
                               faces=faces, **transient)
        fluid_pressure = reynolds.pressure
    return State(
        z=z,
        delta=delta,
        film=film,
        contact_pressure=contact_pressure,
        fluid_pressure=fluid_pressure,
        expected_gap=h_t,
        reynolds=reynolds,
        contact_force=float(np.sum(contact_pressure * area)),
        fluid_force=float(np.sum(fluid_pressure * area)),
        contact_slope=contact_slope,
        flow_coefficient=k,
        faces=faces,
        face_slopes=face_slopes,
    )


def _film_scale(model: Model) -> float:
    """A length on which the force changes appreciably: sigma, or a rigid Martin film."""
    if model.contact is not None:
        return model.contact.sigma
    if model.squeeze is not None:
        return model.squeeze.film_scale
    from .effects import martin_film

    return martin_film(model.scene)


def fluid_slopes(model: Model, state: State):
    """(face slopes, nodal dh_T/dh, nodal dk/dh) of the film the fluid saw at ``state``, for
    the linearised Reynolds residual (force_gradient, newton.fluid_pressure_response): the
    face slopes (percolation.FaceFilm; None for smooth surfaces) and the nodal slopes of
    fluid_film where they are used (smooth faces, a transient's squeeze term), else None."""
    if state.face_slopes is not None and model.squeeze is None:
        return state.face_slopes, None, None
    _, _, gap_slope, coefficient_slope = fluid_film(model, state.film, slopes=True)
    return state.face_slopes, gap_slope, coefficient_slope


def force_gradient(model: Model, state: State) -> np.ndarray:
    """dF/dh_j, N/m (ny, nx): how the carried load changes with the film at each node, at the
    state's cavitated set: contact dp_c/dh times the nodal area plus the Reynolds adjoint
    (the fluid solution's load_sensitivity, one back-substitution). Its sum is dF/dz (< 0)."""
    gradient = np.zeros(model.mesh.shape)
    if state.contact_slope is not None:
        gradient += state.contact_slope * model.mesh.nodal_area
    if state.reynolds is not None:
        face_slopes, gap_slope, coefficient_slope = fluid_slopes(model, state)
        squeeze = {} if model.squeeze is None else {"squeeze_slope": model.squeeze.coefficient * gap_slope}
        if face_slopes is not None:  # rough surfaces: the film on the faces (percolation.py)
            gap_slope, coefficient_slope = None, face_slopes
        gradient += state.reynolds.load_sensitivity(model.mesh, gap_slope, coefficient_slope, model.scene.operating.speed,
                                                    **squeeze)
    return gradient


def balance_force(model: Model, delta: np.ndarray, z_guess: float | None, tolerance: float,
                  stiffness_guess: float | None = None, cavitated_guess=None, reuse=None,
                  pressure_guess=None) -> tuple[State, float]:
    """Solve Eq. (18) for z at fixed deformation; returns the state and dF/dz (N/m, > 0 up).

    Safeguarded Newton: the total force F(z) falls as the cylinder rises (not everywhere:
    see the module docstring) and its slope is known at each evaluation (force_gradient,
    stored as state.load_gradient). Each step is Newton's; once the root is bracketed, a
    step that leaves the bracket or did not halve the force error (the contact law jumps at
    1.9 omega_c, the cavitated set moves) is replaced by bisection. Before the bracket, a
    step without a usable slope (or that stalls) moves by |F error| / stiffness_guess, or
    the film scale, doubling each time. Each evaluation may cost a Reynolds solve, so the
    stopping test is on the force: |F_cont + F_fluid - F| <= tolerance * F.
    ``cavitated_guess``, ``reuse`` and ``pressure_guess`` warm-start the first evaluation
    (evaluate); the later ones start from the evaluation before.
    """
    force = model.scene.operating.force
    ftol = tolerance * force
    scale = _film_scale(model)
    lowest = -np.inf
    if model.contact is None:  # smooth film: h must stay positive everywhere
        lowest = -float(np.min(model.undeformed_gap + delta))
    z = z_guess if z_guess is not None else (lowest + scale if np.isfinite(lowest) else 0.0)
    if z <= lowest:
        z = lowest + scale
    cavitated, previous = cavitated_guess, reuse
    below = above = None  # z known to carry too much (root above it) / too little load
    step = None
    previous_error = np.inf
    for _ in range(400):
        state = evaluate(model, z, delta, cavitated, previous, pressure_guess)
        pressure_guess = None
        if state.reynolds is not None:
            cavitated, previous = state.reynolds.cavitated, state.reynolds
        error = state.total_force - force
        state.load_gradient = force_gradient(model, state)
        slope = float(np.sum(state.load_gradient))  # dF/dz
        if abs(error) <= ftol:
            return state, -slope
        if step is None:
            step = abs(error) / stiffness_guess if stiffness_guess and stiffness_guess > 0.0 else scale
        if error > 0.0:
            below = z
        else:
            above = z
        newton = z - error / slope if slope < 0.0 else None
        if below is not None and above is not None:
            if abs(above - below) <= 4 * np.finfo(float).eps * max(abs(above), abs(below)):
                return state, -slope
            halved = abs(error) <= 0.5 * previous_error
            inside = newton is not None and min(below, above) < newton < max(below, above)
            z = newton if inside and halved else 0.5 * (below + above)
        else:
            if newton is None or abs(error) > 0.5 * previous_error:  # no slope, or stalling
                newton = z + (step if error > 0.0 else -step)  # too much load: move up
                step *= 2.0
            if newton <= lowest:
                newton = lowest + 0.5 * (z - lowest)
            z = newton
        previous_error = abs(error)
    raise SolveError(
        f"force balance did not converge (z = {z:.6g} m, force error {error:.4g} N, bracket {below}, {above})",
        state,
    )


# GMRES of the contact Newton step: basis size and restart cycles (at most 400 iterations).
GMRES_RESTART = 20
GMRES_CYCLES = 20


def contact_newton_step(model: Model, state: State, residual: np.ndarray) -> np.ndarray:
    """Newton step of the dry contact for the deformation, with the force balance kept.

    Linearising delta = K p_c(h_o + z + delta) and sum(p_c dA) = F about the current state
    (D = -dp_c/dh >= 0, w = nodal area) and eliminating the rigid shift dz gives
        step + K(D (step - <step>)) = residual,   <step> = sum(w D step) / sum(w D),
    solved matrix-free by GMRES with the FFT influence operator. Without asperity contact
    the step is the plain fixed-point step. With Reynolds fluid pressure the coupled
    iteration takes newton.coupled_newton_step instead (the fluid's stiffness too).
    """
    if model.contact is None:
        return residual
    stiffness = -state.contact_slope  # >= 0, Pa/m
    weight = stiffness * model.mesh.nodal_area
    total = float(np.sum(weight))
    if not total > 0.0:
        return residual
    shape = model.mesh.shape
    n = residual.size

    def matvec(v):
        v = v.reshape(shape)
        load_neutral = v - float(np.sum(weight * v)) / total
        return (v + model.deformation(stiffness * load_neutral)).ravel()

    operator = LinearOperator((n, n), matvec=matvec, dtype=float)
    # It takes 1-4 iterations (Table 1, 51^2-201^2); a restart-80 basis was 104 MB at 401^2.
    step, info = gmres(operator, residual.ravel(), rtol=1e-4, atol=0.0, restart=GMRES_RESTART, maxiter=GMRES_CYCLES)
    if info < 0 or not np.all(np.isfinite(step)):
        return residual  # fall back to the plain fixed-point step; convergence is still judged below
    return step.reshape(shape)


def _predicted_position(state: State, force: float, change: np.ndarray) -> float:
    """z balancing ``force`` after the deformation changes by ``change``, to first order from
    the state's load gradient: F + dF/dz dz + sum_j dF/dh_j change_j = force (the state's z
    when the slope is not negative)."""
    gradient = state.load_gradient
    slope = float(np.sum(gradient))
    if not slope < 0.0:
        return state.z
    return state.z - (state.total_force - force + float(np.sum(gradient * change))) / slope


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


def _fine_warm_start(model: Model, initial: dict | None) -> bool:
    """Whether ``initial`` is a converged solution on this very mesh (a sweep's previous
    point): it is then a better start than a coarse-mesh solve, which is skipped. A 26-speed
    Table 1 sweep at 51^2 then costs 0.65-0.7 of 26 cold solves instead of 0.96, with the
    same answers to 2e-7 (bench/RESULTS.md)."""
    return bool(initial) and "delta" in initial and np.size(initial["delta"]) == model.mesh.nx * model.mesh.ny


def nested_start(model: Model, tolerance: float, initial: dict | None = None) -> dict | None:
    """``initial`` of coupled_solve on ``model``'s mesh: the solution on the coarser mesh,
    itself started from ``initial`` (a warm start, interpolated to it) and so on down to
    the coarsest mesh, where ``initial`` is used as it is.

    Without a coarser mesh, with a warm start on this mesh (``_fine_warm_start``), or when a
    coarse level does not converge or cannot bracket its force balance, ``initial`` is
    returned: the fine mesh then starts from it and is judged on its own.
    """
    from .reynolds import _interpolate

    coarse = model.coarsened() if model.contact is not None else None
    if coarse is None or _fine_warm_start(model, initial):
        return initial
    coarse_initial = None
    if initial:
        coarse_initial = {key: initial[key] for key in ("z", "stiffness") if key in initial}
        if "delta" in initial:
            delta = np.asarray(initial["delta"], dtype=float).reshape(model.mesh.shape)
            coarse_initial["delta"] = _interpolate(delta, model.mesh, coarse.mesh)
    try:
        state, diag = coupled_solve(coarse, coarse_initial, tolerance=max(tolerance, NESTED_TOLERANCE))
    except SolveError:
        return initial
    if not diag["converged"]:
        return initial
    start = {"z": state.z, "delta": _interpolate(state.delta, coarse.mesh, model.mesh), "stiffness": diag["stiffness"]}
    if state.reynolds is not None:
        pressure = _interpolate(state.fluid_pressure, coarse.mesh, model.mesh)
        start["cavitated"] = pressure <= 0.0
        start["pressure"] = pressure  # smoothed on the fine mesh (Reynolds cavitation)
    return start


def coupled_solve(model: Model, initial: dict | None = None, tolerance: float | None = None) -> tuple[State, dict]:
    """Iterate force balance and deformation to convergence; returns the state and diagnostics.

    ``initial``: {"z", "delta"} and optionally {"cavitated", "pressure", "stiffness"} to start from
    (None: cold); either way the fine mesh starts from the nested (coarse-mesh) solution
    where there is one (nested_start). ``tolerance`` overrides the scene's.
    """
    scene = model.scene
    tol = scene.solver.tolerance if tolerance is None else tolerance
    force = scene.operating.force
    max_iterations = scene.solver.max_iterations
    initial = nested_start(model, tol, initial)
    delta = np.zeros(model.mesh.shape)
    z = stiffness = cavitated = reynolds = pressure_guess = None
    if initial:
        if model.deformation is not None:  # a rigid model has no deformation to start from
            delta = np.array(initial.get("delta", delta), dtype=float).reshape(model.mesh.shape)
        z = initial.get("z")
        stiffness = initial.get("stiffness")
        cavitated = initial.get("cavitated")
        pressure_guess = initial.get("pressure")
    deformation_step, mixer = deformation_stepper(model)
    smallest_change, stalled = np.inf, 0
    restart = (delta.copy(), z, stiffness, cavitated, pressure_guess)
    change = 0.0
    balance_tol = tol if model.deformation is None else LOOSEST_BALANCE_TOLERANCE
    deformation_converged = False
    failure = ""
    iteration = 0
    backtracking = None  # Backtracking of the coupled Newton steps once they stall
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
            change = float(np.max(np.abs(new_delta - delta)))
            relative_change = change / max(float(np.ptp(new_delta)), 1e-15)
            if relative_change <= tol:
                deformation_converged = True
                break
            if backtracking is not None:
                fraction = backtracking.retry(relative_change)
                if fraction is not None:  # too little decrease: a shorter step from the anchor
                    anchor, _, anchored_step, anchored_state = backtracking.anchor
                    delta = anchor + fraction * anchored_step
                    z = _predicted_position(anchored_state, force, fraction * anchored_step)
                    continue
            balance_tol = max(tol, min(LOOSEST_BALANCE_TOLERANCE, INEXACT_BALANCE_FACTOR * relative_change))
            if relative_change <= NEWTON_STALL_FACTOR * smallest_change:
                smallest_change, stalled = relative_change, 0
            else:
                stalled += 1
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
            step = deformation_step(model, state, new_delta - delta)
            if backtracking is not None:
                backtracking.accept(delta, relative_change, step, state)
            new_delta = delta + step if mixer is None else mixer.step(delta, delta + step)
            z = _predicted_position(state, force, new_delta - delta)
            delta = new_delta
        if abs(force - state.total_force) > tol * force:  # last inner solve was inexact
            state, _ = balance_force(model, state.delta, state.z, tol, stiffness, cavitated, reynolds)
    except SolveError as err:  # reported as not converged, with the last state evaluated
        if err.state is None:
            raise
        state, failure = err.state, str(err)
    reynolds_ok = state.reynolds is None or bool(state.reynolds.converged)
    force_residual = force - state.total_force
    diagnostics = {
        "iterations": iteration,
        "deformation_residual": change,
        "force_residual": force_residual,
        "reynolds_residual": 0.0 if state.reynolds is None else float(state.reynolds.residual),
        "converged": not failure and deformation_converged and reynolds_ok and abs(force_residual) <= tol * force,
        "stiffness": stiffness,
        "failure": failure,
    }
    return state, diagnostics


@cache
def _blas_controller():
    """The BLAS thread pools of numpy and scipy (threadpoolctl), looked up once.

    The solve runs with one BLAS thread: its BLAS calls are small (vector norms and dots of
    GMRES and Anderson, SuperLU's dense kernels of a 2D problem), so threads only add
    synchronisation, and where other processes share the cores (a parallel workflow) an
    idle-spinning OpenBLAS thread makes each call 10-100 times slower (bench/RESULTS.md).
    The limit holds only inside solve(); the caller's setting is restored after it.
    """
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def _central_value(mesh: Mesh, field: np.ndarray) -> float:
    row = field[mesh.ny // 2]
    return float(np.interp(0.0, mesh.x, row))


def point_outputs(model: Model, state: State) -> tuple[dict, list[str]]:
    """(outputs, notes) of a solved state, as a case reports them: the electrical path
    (electrical.path), real contact area, friction (DESIGN.md; the shear resists the sliding
    whichever way the block moves), loads and films. Shared by solve() and each instant of a
    transient (unsteady/series.py)."""
    from .electrical import electrical_path
    from .friction import fluid_shear_force, friction_coefficient

    scene, mesh = model.scene, model.mesh
    area = mesh.nodal_area
    path = electrical_path(scene, mesh, model.contact, state.film)
    notes = list(path.notes)
    if model.contact is not None:  # a node with A_r/A_n > 1 is fully in contact (validity: area_capped)
        real_area = float(np.sum(np.minimum(model.contact.area_fraction(state.film), 1.0) * area))
    else:
        real_area = 0.0
        notes.append("asperity_contact off: no metallic path")
    shear = 0.0
    if state.reynolds is not None:
        shear = np.sign(scene.operating.speed) * fluid_shear_force(
            mesh, state.expected_gap, state.fluid_pressure, state.reynolds.cavitated,
            scene.lubricant.viscosity, scene.operating.speed, film=state.film,
            sigma=model.contact.sigma if model.contact is not None else None,
            content=getattr(state.reynolds, "content", None), split=scene.roughness.split,
        )
    force = scene.operating.force
    carried = state.total_force
    outputs = {
        **path.scalars(scene.interface.open_resistance),
        "friction_coefficient": friction_coefficient(scene.interface.boundary_friction, state.contact_force, shear, force),
        "fluid_force": state.fluid_force,
        "contact_force": state.contact_force,
        "applied_force": force,
        "fluid_load_fraction": state.fluid_force / carried if carried > 0 else 0.0,
        "min_film_thickness": float(np.min(state.film)),
        "central_film_thickness": _central_value(mesh, state.film),
        "separation": state.z,
        "real_contact_area": real_area,
    }
    return outputs, notes


def solve(scene, fields: bool = False, initial: dict | None = None, return_state: bool = False):
    """Solve one operating point; returns the case ``xarray.Dataset`` (DESIGN.md outputs),
    with ``return_state`` also the solver's final state (``solve_case``)."""
    result, state = solve_case(scene, fields, initial)
    ds = result.to_dataset()
    return (ds, state) if return_state else ds


def solve_case(scene, fields: bool = False, initial: dict | None = None):
    """Solve one operating point; returns (case_result.CaseResult, the solver's final state).

    ``initial`` ({"z": float, "delta": array}, optionally "cavitated" and "pressure" of a
    previous solution on this mesh) warm-starts the coupling loop (a sweep's continuation);
    a cold start must give the same answer within tolerance.
    """
    from .case_result import CaseResult
    from .validity import assess

    start = time.perf_counter()
    notes = []
    requested = scene
    contact = None
    if scene.effects.auto:
        from .effects import auto_effects

        decided = auto_effects(scene)
        scene, contact = decided.scene, decided.contact  # the table the decision built
        notes.append("effects: auto -> " + "; ".join(f"{k}: {v}" for k, v in decided.reasons.items()))
    with _blas_controller().limit(limits=1, user_api="blas"):
        model = Model.assemble(scene, contact=contact)
        state, diag = coupled_solve(model, initial)
    if diag["failure"]:
        notes.append("NOT CONVERGED: " + diag["failure"])
    outputs, output_notes = point_outputs(model, state)
    notes.extend(output_notes)
    mesh = model.mesh
    validity = assess(scene, mesh, model.contact, state, model.hydrodynamic)
    notes.extend(f"validity {flag}: {note}" for flag, note in validity.items())
    scalars = {
        **outputs,
        "converged": int(diag["converged"]),
        "iterations": diag["iterations"],
        "force_residual": diag["force_residual"],
        "deformation_residual": diag["deformation_residual"],
        "reynolds_residual": diag["reynolds_residual"],
        "solve_time": time.perf_counter() - start,
        "speed": scene.operating.speed,
        "valid": int(not validity),
    }
    field_data = None
    if fields:
        field_data = {
            "fluid_pressure": state.fluid_pressure,
            "contact_pressure": state.contact_pressure,
            "film_thickness": state.film,
            "deformation": state.delta,
        }
        if getattr(state.reynolds, "content", None) is not None:  # effects.cavitation: jfo
            field_data["film_content"] = state.reynolds.content
    result = CaseResult.build(requested, scalars, field_data, mesh, model.effects_run, "; ".join(notes), ",".join(validity) or "ok")
    return result, state
