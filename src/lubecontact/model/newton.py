"""Newton step of the deformation with the contact's and the fluid's stiffness (steady and
transient solves).

The coupled iteration (model/coupling.coupled_solve) updates the deformation delta -> K(p + p_c)
at the balanced position. Preconditioned with the contact's stiffness alone
(model/newton.contact_newton_step) the fixed point converges linearly, at a rate set by the
fluid's stiffness (0.2-0.4 per iteration on Table 1, 8-11 iterations on a 201^2 mesh). In a
transient step the squeeze term makes the fluid pressure respond to the film as c0 ~ 1/dt,
so at short steps that rate exceeds 1. Here the linearisation includes the fluid: with
P'(v) the change of the total pressure for a film change v (contact -D v, fluid by the
linearised Reynolds equation at the current cavitated set, with the squeeze term of a
transient step) and the rigid shift dz eliminated by the force balance,
sum dA P'(v + dz) = 0,

    step - K P'(step + dz(step)) = residual,      dz(v) = -sum dA P'(v) / sum dA P'(1),

solved matrix-free by GMRES (each product: a few array operations on the faces, one
back-substitution with the LU factors of the Reynolds solve and one FFT; 3-4 products per
step on Table 1). dA is the load's weight of each node's pressure: its nodal area, and on a
line open to the far inlet the first Reynolds node's also carries the exterior's load
(evaluation.fluid_load_slopes). Without fluid pressure it is model/newton.contact_newton_step's
equation.

The fluid pressure is a piecewise smooth function of the film (the cavitated set changes
with it), so near a fold full Newton steps can cycle between sets; once they stall the
coupled iteration shortens them by backtracking (``Backtracking``).
"""

from __future__ import annotations

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from lubecontact.model.evaluation import fluid_load_slopes
from lubecontact.model.fluid_film import fluid_exterior, fluid_slopes
from lubecontact.model.model import Model, State
from lubecontact.numerics.reynolds import interior_nodes

# Relative residual of the GMRES solve of the Newton step: an inexact Newton step is enough,
# the coupled iteration judges convergence on its own residuals.
NEWTON_RTOL = 1e-2


def fluid_pressure_response(model, state):
    """v (ny, nx) m -> change of the fluid pressure (Pa) for the film change v, at the state's
    cavitated set: dp_F = -A_FF^{-1} (dr/dh v)_F, r = A(k) p - b(h_T) (+ dA dh_T/dt in a
    transient step) the finite-volume residual of reynolds.reynolds_system, differentiated
    face by face: with rough surfaces k and h_T of each face are evaluated at the face's
    film (model/fluid_film.fluid_faces, percolation.py), with smooth ones they are face means of the
    nodal values (model/fluid_film.fluid_slopes).
    A_FF^{-1} is applied with the LU factors the Reynolds solve used (its own or a nearby
    matrix's: an approximate Newton step, judged by the outer loop)."""
    mesh, solution, squeeze = model.mesh, state.reynolds, model.squeeze
    speed = model.scene.operating.speed
    free = interior_nodes(mesh.shape, mesh.line) & ~solution.cavitated
    face_slopes, gap_slope, coefficient_slope = fluid_slopes(model, state)
    p = solution.pressure
    factors = None if solution.factor is None else solution.factor.factors
    gx, gy = mesh.dy / mesh.dx, mesh.dx / mesh.dy
    content = state.squeeze_content  # a time step's cells' content (fluid_film.squeeze_content)
    exterior = fluid_exterior(model, state.film)  # a 2-D mesh's far inlet: its outflow moves with c
    exterior_slope = None if exterior is None else exterior.outflow_slope(p)

    def on_faces(v):
        """dk and dh_T of the x faces and dk of the y faces for the film change v."""
        vx, vy = 0.5 * (v[:, :-1] + v[:, 1:]), 0.5 * (v[:-1, :] + v[1:, :])
        if face_slopes is not None:
            return face_slopes.coefficient_x * vx, face_slopes.gap_x * vx, face_slopes.coefficient_y * vy
        kv, gv = coefficient_slope * v, gap_slope * v
        return 0.5 * (kv[:, :-1] + kv[:, 1:]), 0.5 * (gv[:, :-1] + gv[:, 1:]), 0.5 * (kv[:-1, :] + kv[1:, :])

    def apply(v):
        response = np.zeros(mesh.shape)
        if factors is None:
            return response
        dk_x, dg_x, dk_y = on_faces(v)
        dr = np.zeros(mesh.shape) if squeeze is None else squeeze.coefficient * mesh.nodal_area * content.apply(v)
        flux = gx * dk_x * (p[:, :-1] - p[:, 1:]) + 0.5 * speed * mesh.dy * dg_x  # Poiseuille + Couette
        dr[:, :-1] += flux
        dr[:, 1:] -= flux
        flux_y = gy * dk_y * (p[:-1, :] - p[1:, :])
        dr[:-1, :] += flux_y
        dr[1:, :] -= flux_y
        if exterior is not None:
            dr[1:-1, 1] += exterior_slope * float(np.sum(exterior.offset_slope * v))
        response[free] = -factors.solve(dr[free])
        return response

    return apply


def coupled_newton_step(model, state, residual: np.ndarray) -> np.ndarray:
    """The deformation step of the module docstring (residual = K(p + p_c) - delta), for a
    state with fluid pressure (state.reynolds); the plain fixed-point step when GMRES fails
    (convergence is judged by the caller)."""
    if model.deformation is None:
        return residual
    mesh = model.mesh
    fluid = fluid_pressure_response(model, state)
    contact = -state.contact_slope if state.contact_slope is not None else 0.0

    def response(v):
        return fluid(v) - contact * v

    weight, _ = fluid_load_slopes(model, state)  # dF/dp: the nodal areas (with the far inlet's weight)
    rigid = response(np.ones(mesh.shape))
    total = float(np.sum(rigid * weight))
    if not total < 0.0:
        return residual

    def matvec(v):
        v = v.reshape(mesh.shape)
        dp = response(v)
        shift = -float(np.sum(dp * weight)) / total
        return (v - model.deformation(dp + shift * rigid)).ravel()

    operator = LinearOperator((residual.size,) * 2, matvec=matvec, dtype=float)
    step, info = gmres(operator, residual.ravel(), rtol=NEWTON_RTOL, atol=0.0, restart=40, maxiter=2)
    if info < 0 or not np.all(np.isfinite(step)):
        return residual
    return step.reshape(mesh.shape)


# Armijo's rule for the backtracking of stalled Newton steps (Kelley 1995, "Iterative Methods
# for Linear and Nonlinear Equations", SIAM, section 8.1): a step fraction t is kept when the
# residual falls to (1 - SUFFICIENT_DECREASE t) times the anchor's, else t is halved, down to
# SMALLEST_STEP_FRACTION (four halvings; Kelley's 1e-4 and halving).
SUFFICIENT_DECREASE = 1e-4
SMALLEST_STEP_FRACTION = 1.0 / 16.0


class Backtracking:
    """Line search along Newton steps by halving (Armijo's rule), for an iteration whose
    full steps stall.

    ``accept(iterate, norm, step, data)`` anchors the search at an accepted iterate, the norm
    of its residual, its Newton step and whatever the caller needs to start from it
    (``data``); the caller then tries anchor + step. ``retry(norm)`` judges the residual norm
    of the point just tried: None keeps that point (enough decrease, or the fraction cannot
    be halved again: then ``exhausted`` is set and the caller decides what to do), else the
    fraction of the anchored step to try next from the anchor.
    """

    def __init__(self):
        self.anchor = None  # (iterate, residual norm, step, data) of the last accepted iterate
        self.fraction = 1.0
        self.exhausted = False

    def accept(self, iterate, norm: float, step, data=None) -> None:
        self.anchor = (iterate, norm, step, data)
        self.fraction = 1.0

    def retry(self, norm: float) -> float | None:
        self.exhausted = False
        if self.anchor is None or norm <= (1.0 - SUFFICIENT_DECREASE * self.fraction) * self.anchor[1]:
            return None
        if self.fraction <= SMALLEST_STEP_FRACTION:
            self.exhausted = True
            return None
        self.fraction *= 0.5
        return self.fraction


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
