"""Coupled solve of one operating point (paper section 2.5 and Fig. 1; Eqs. 1-18).

The cylinder sits at height z above the block; the film is h = h_o + z + delta (Eq. 3) with
the undeformed gap h_o of Eq. (4) and the macro deformation delta. Asperities carry the
nominal contact pressure p_c(h) (Eq. 11), the fluid the Reynolds pressure p(h) (Eq. 1),
and both deform the surfaces: delta = K (p + p_c). The cylinder's position balances the
applied force: F = F_cont + F_fluid (Eq. 18).

Algorithm (only the enabled effects are assembled and run):
1. For the current deformation, find z with the force balance satisfied to
   ``tolerance * F``: a bracketed Brent root on the monotone total force (the contact law
   has a jump at 1.9 omega_c, so nothing here relies on its smoothness).
2. Recompute the deformation from the pressures at that z. The fixed point
   delta -> K(p + p_c) is stiff where the asperities are stiff against the surface
   compliance, so each correction is preconditioned by the contact part of its Jacobian:
   (I + K D) step = K(p + p_c) - delta with D = -dp_c/dh >= 0, solved by GMRES with the
   FFT operator (a Newton step for the dry contact), and the preconditioned map is then
   accelerated by Anderson mixing (which also picks up the fluid's stiffness). Stop when
   the change is below ``tolerance`` times the deformation's range.
Every solve reports its residuals and a ``converged`` flag; nothing is silently accepted.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from .anderson import AndersonMixer
from .materials import effective_modulus
from .mesh import Mesh, build_mesh

# Rigid-cylinder, smooth-film estimate of the load per unit length (Martin 1916 with the
# Reynolds condition; physics.md section 4): w' = 4.9 mu u_m R / h0, u_m = U/2.
MARTIN_LOAD_COEFFICIENT = 4.9


class SolveError(RuntimeError):
    """The force balance could not even be bracketed (reported, never swallowed)."""


@dataclass
class Model:
    """The sub-models a scene calls for, built once (disabled effects are None / False)."""

    scene: object
    mesh: Mesh
    undeformed_gap: np.ndarray  # h_o of Eq. (4), (ny, nx)
    contact: object | None  # RoughContact when effects.asperity_contact
    deformation: object | None  # ElasticDeformation when effects.elastic_deformation
    hydrodynamic: bool  # Reynolds solved (effect on and speed > 0)

    @classmethod
    def assemble(cls, scene) -> "Model":
        effects = scene.effects
        mesh = build_mesh(scene)
        radius = scene.geometry.radius
        gap_x = radius - np.sqrt(radius**2 - mesh.x**2)  # Eq. (4)
        undeformed = np.broadcast_to(gap_x, mesh.shape).copy()
        contact = None
        if effects.asperity_contact:
            from .rough_surface import RoughContact

            contact = RoughContact.from_scene(scene)
        deformation = None
        if effects.elastic_deformation:
            from .deformation import ElasticDeformation

            deformation = ElasticDeformation(mesh, effective_modulus(scene))
        hydrodynamic = bool(effects.hydrodynamics) and scene.operating.speed > 0.0
        return cls(scene, mesh, undeformed, contact, deformation, hydrodynamic)

    @property
    def effects_run(self) -> dict:
        e = self.scene.effects
        return {
            "hydrodynamics": self.hydrodynamic,
            "flow_factors": self.hydrodynamic and self.contact is not None and e.flow_factors,
            "cavitation": self.hydrodynamic and e.cavitation,
            "asperity_contact": self.contact is not None,
            "plasticity": self.contact is not None and e.plasticity,
            "elastic_deformation": self.deformation is not None,
            "alleviation": self.contact is not None and e.alleviation,
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

    @property
    def total_force(self) -> float:
        return self.contact_force + self.fluid_force

    @property
    def total_pressure(self) -> np.ndarray:
        return self.contact_pressure + self.fluid_pressure


# Where the mean planes interpenetrate (h < 0) the fluid sees the gap frozen at its h = 0
# value (h_T = sigma/sqrt(2 pi)): the lubricant then flows only through the valley network.
# Without this floor the regularised flow coefficient k ~ h_T^3 and the Couette source
# ~ dh_T/dx vanish at different rates as h_T -> 0, and the pressure they imply grows like
# 1/h_T^2 without bound (1e9 Pa at 1 mm/s for sigma = 0.05 um, 1e170 Pa at 500 N; the
# coupled iteration then wanders). Above h = 0, Eqs. 1-2 and DESIGN.md's regularisation
# below h/sigma = 0.5 apply unchanged.
FLUID_FILM_FLOOR_SIGMAS = 0.0


def fluid_film(model: Model, film: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(h_T, k) for the Reynolds equation: Patir-Cheng gap and flow coefficient (Eqs. 1-2)."""
    from .flow_factors import expected_gap, poiseuille_coefficient

    scene = model.scene
    sigma = model.contact.sigma if model.contact is not None else None
    if sigma is not None:
        film = np.maximum(film, FLUID_FILM_FLOOR_SIGMAS * sigma)
    h_t = expected_gap(film, sigma) if sigma is not None else film
    k = poiseuille_coefficient(film, sigma, scene.lubricant.viscosity, flow_factors=scene.effects.flow_factors)
    return h_t, k


def evaluate(model: Model, z: float, delta: np.ndarray, cavitated_guess=None) -> State:
    """Pressures and forces at cylinder position z with deformation delta (Eqs. 3-5, 11)."""
    mesh, scene = model.mesh, model.scene
    film = model.undeformed_gap + z + delta
    area = mesh.nodal_area
    contact_pressure = model.contact.pressure(film) if model.contact is not None else np.zeros(mesh.shape)
    fluid_pressure = np.zeros(mesh.shape)
    h_t = reynolds = None
    if model.hydrodynamic:
        from .reynolds import solve_reynolds

        h_t, k = fluid_film(model, film)
        reynolds = solve_reynolds(
            mesh, h_t, k, scene.operating.speed, cavitation=scene.effects.cavitation, cavitated_guess=cavitated_guess
        )
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
    )


def _film_scale(model: Model) -> float:
    """A length on which the force changes appreciably: sigma, or a rigid Martin film."""
    if model.contact is not None:
        return model.contact.sigma
    s = model.scene
    w = s.operating.force / s.geometry.length
    return MARTIN_LOAD_COEFFICIENT * s.lubricant.viscosity * 0.5 * s.operating.speed * s.geometry.radius / w


def balance_force(model: Model, delta: np.ndarray, z_guess: float | None, tolerance: float,
                  stiffness_guess: float | None = None, cavitated_guess=None) -> tuple[State, float]:
    """Solve Eq. (18) for z at fixed deformation; returns the state and dF/dz (N/m, > 0 up).

    The total force falls monotonically as the cylinder rises, so the root is bracketed
    (first step from the previous stiffness when known, then doubling) and refined by
    Illinois regula falsi until |F_cont + F_fluid - F| <= tolerance * F. Each evaluation
    may cost a Reynolds solve, so the stopping test is on the force itself.
    """
    force = model.scene.operating.force
    ftol = tolerance * force
    scale = _film_scale(model)
    lowest = -np.inf
    if model.contact is None:  # smooth film: h must stay positive everywhere
        lowest = -float(np.min(model.undeformed_gap + delta))
    z0 = z_guess if z_guess is not None else (lowest + scale if np.isfinite(lowest) else 0.0)
    if z0 <= lowest:
        z0 = lowest + scale
    cavitated = cavitated_guess

    def residual(z: float) -> tuple[float, State]:
        nonlocal cavitated
        state = evaluate(model, z, delta, cavitated)
        if state.reynolds is not None:
            cavitated = state.reynolds.cavitated
        return state.total_force - force, state

    fa, state_a = residual(z0)
    a = z0
    if abs(fa) <= ftol:
        return state_a, stiffness_guess or 0.0
    step = abs(fa) / stiffness_guess if stiffness_guess else scale
    for _ in range(200):
        if fa > 0.0:  # too much load: move the cylinder up
            b = a + step
        else:
            b = max(a - step, lowest + 0.5 * (a - lowest)) if np.isfinite(lowest) else a - step
        fb, state_b = residual(b)
        if abs(fb) <= ftol:
            return state_b, abs(fb - fa) / abs(b - a)
        if np.sign(fb) != np.sign(fa):
            break
        a, fa, state_a = b, fb, state_b
        step *= 2.0
    else:
        raise SolveError(f"could not bracket the force balance (last z = {a:.4g} m, force error {fa:.4g} N)")
    side = 0
    for _ in range(200):
        c = (a * fb - b * fa) / (fb - fa)
        fc, state_c = residual(c)
        if abs(fc) <= ftol or abs(b - a) <= 4 * np.finfo(float).eps * max(abs(a), abs(b)):
            return state_c, abs(fb - fa) / abs(b - a)
        if np.sign(fc) == np.sign(fb):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5  # Illinois: stop the stale end from stalling the interval
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    raise SolveError(f"force balance did not converge in the bracket [{a:.6g}, {b:.6g}] m")


def contact_newton_step(model: Model, state: State, residual: np.ndarray) -> np.ndarray:
    """Newton step of the dry contact for the deformation, with the force balance kept.

    Linearising delta = K p_c(h_o + z + delta) and sum(p_c dA) = F about the current state
    (D = -dp_c/dh >= 0, w = nodal area) and eliminating the rigid shift dz gives
        step + K(D (step - <step>)) = residual,   <step> = sum(w D step) / sum(w D),
    solved matrix-free by GMRES with the FFT influence operator. Without asperity contact
    the step is the plain fixed-point step.
    """
    if model.contact is None:
        return residual
    _, slope = model.contact.pressure_and_slope(state.film)
    stiffness = -slope  # >= 0, Pa/m
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
    step, info = gmres(operator, residual.ravel(), rtol=1e-4, atol=0.0, restart=80, maxiter=5)
    if info < 0 or not np.all(np.isfinite(step)):
        return residual  # fall back to the plain fixed-point step; convergence is still judged below
    return step.reshape(shape)


# While the deformation is still far from converged, the force balance need not be exact:
# the inner tolerance follows the outer progress (an inexact Newton-type schedule) and is
# tightened to ``solver.tolerance`` for the final iterate.
INEXACT_BALANCE_FACTOR = 0.1
LOOSEST_BALANCE_TOLERANCE = 1e-3


def coupled_solve(model: Model, initial: dict | None = None) -> tuple[State, dict]:
    """Iterate force balance and deformation to convergence; returns the state and diagnostics."""
    scene = model.scene
    tol = scene.solver.tolerance
    force = scene.operating.force
    max_iterations = scene.solver.max_iterations
    delta = np.zeros(model.mesh.shape)
    z = None
    if initial:
        delta = np.array(initial.get("delta", delta), dtype=float).reshape(model.mesh.shape)
        z = initial.get("z")
    mixer = AndersonMixer(beta=1.0)
    stiffness = cavitated = None
    change = 0.0
    balance_tol = tol if model.deformation is None else LOOSEST_BALANCE_TOLERANCE
    deformation_converged = False
    for iteration in range(1, max_iterations + 1):
        state, stiffness = balance_force(model, delta, z, balance_tol, stiffness, cavitated)
        z = state.z
        if state.reynolds is not None:
            cavitated = state.reynolds.cavitated
        if model.deformation is None:
            deformation_converged = True
            break
        new_delta = model.deformation(state.total_pressure)
        change = float(np.max(np.abs(new_delta - delta)))
        relative_change = change / max(float(np.ptp(new_delta)), 1e-15)
        if relative_change <= tol:
            deformation_converged = True
            break
        balance_tol = max(tol, min(LOOSEST_BALANCE_TOLERANCE, INEXACT_BALANCE_FACTOR * relative_change))
        step = contact_newton_step(model, state, new_delta - delta)
        delta = mixer.step(delta, delta + step)
    if abs(force - state.total_force) > tol * force:  # last inner solve was inexact
        state, _ = balance_force(model, state.delta, state.z, tol, stiffness, cavitated)
    reynolds_ok = state.reynolds is None or bool(state.reynolds.converged)
    force_residual = force - state.total_force
    diagnostics = {
        "iterations": iteration,
        "deformation_residual": change,
        "force_residual": force_residual,
        "reynolds_residual": 0.0 if state.reynolds is None else float(state.reynolds.residual),
        "converged": deformation_converged and reynolds_ok and abs(force_residual) <= tol * force,
    }
    return state, diagnostics


def _central_value(mesh: Mesh, field: np.ndarray) -> float:
    row = field[mesh.ny // 2]
    return float(np.interp(0.0, mesh.x, row))


def solve(scene, fields: bool = False, initial: dict | None = None, return_state: bool = False):
    """Solve one operating point; returns the case ``xarray.Dataset`` (DESIGN.md outputs).

    ``initial`` ({"z": float, "delta": array}) warm-starts the coupling loop (a sweep's
    continuation); a cold start must give the same answer within tolerance.
    """
    from .electrical import contact_resistance
    from .friction import fluid_shear_force, friction_coefficient
    from .output import case_dataset

    start = time.perf_counter()
    notes = []
    requested = scene
    if scene.effects.auto:
        from .effects import resolve_auto_effects

        scene, reasons = resolve_auto_effects(scene)
        notes.append("effects: auto -> " + "; ".join(f"{k}: {v}" for k, v in reasons.items()))
    model = Model.assemble(scene)
    state, diag = coupled_solve(model, initial)
    mesh = model.mesh
    area = mesh.nodal_area
    if model.contact is not None:
        area_fraction = model.contact.area_fraction(state.film)
        resistance, clamped = contact_resistance(
            model.contact.log_conductance(state.film), area_fraction, area, scene.effects.alleviation
        )
        real_area = float(np.sum(area_fraction * area))
    else:
        resistance, clamped, real_area = np.inf, 0, 0.0
        notes.append("asperity_contact off: no conducting path (open circuit by construction)")
    shear = 0.0
    if model.hydrodynamic:
        shear = fluid_shear_force(
            mesh, state.expected_gap, state.fluid_pressure, state.reynolds.cavitated,
            scene.lubricant.viscosity, scene.operating.speed,
            model.contact.sigma if model.contact is not None else None,
        )
    force = scene.operating.force
    carried = state.total_force
    scalars = {
        "contact_resistance": resistance,
        "friction_coefficient": friction_coefficient(scene.interface.boundary_friction, state.contact_force, shear, force),
        "fluid_force": state.fluid_force,
        "contact_force": state.contact_force,
        "applied_force": force,
        "fluid_load_fraction": state.fluid_force / carried if carried > 0 else np.nan,
        "min_film_thickness": float(np.min(state.film)),
        "central_film_thickness": _central_value(mesh, state.film),
        "separation": state.z,
        "real_contact_area": real_area,
        "converged": int(diag["converged"]),
        "iterations": diag["iterations"],
        "force_residual": diag["force_residual"],
        "deformation_residual": diag["deformation_residual"],
        "reynolds_residual": diag["reynolds_residual"],
        "solve_time": time.perf_counter() - start,
        "open_circuit": int(not np.isfinite(resistance)),
        "clamped_nodes": int(clamped),
        "speed": scene.operating.speed,
    }
    field_data = None
    if fields:
        field_data = {
            "fluid_pressure": state.fluid_pressure,
            "contact_pressure": state.contact_pressure,
            "film_thickness": state.film,
            "deformation": state.delta,
        }
    ds = case_dataset(requested, scalars, field_data, mesh, model.effects_run, "; ".join(notes))
    if return_state:
        return ds, state
    return ds
