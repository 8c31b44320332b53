"""Newton step of the deformation in a transient step, with the squeeze film's stiffness.

The steady coupled iteration (solver.coupled_solve) preconditions the deformation fixed point
delta -> K(p + p_c) with the contact's stiffness only; the fluid's is left to Anderson
mixing. The squeeze term makes the fluid pressure respond to the film as c0 ~ 1/dt (a short
step nearly freezes the film), so at short steps the fixed point's gain is far above 1 and
the mixing cannot tame it. Here the linearisation includes the fluid: with P'(v) the change
of the total pressure for a film change v (contact -D v, fluid by the linearised Reynolds
equation at the current cavitated set) and the rigid shift dz eliminated by the force
balance, sum dA P'(v + dz) = 0,

    step - K P'(step + dz(step)) = residual,      dz(v) = -sum dA P'(v) / sum dA P'(1),

solved matrix-free by GMRES (each product: one assembly and one back-substitution with the
LU factors of the Reynolds solve). Without fluid pressure it is solver.contact_newton_step's
equation.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from ..reynolds import _interior, reynolds_system
from ..solver import SLOPE_STEP, _film_scale, fluid_film


def fluid_pressure_response(model, state):
    """v (ny, nx) m -> change of the fluid pressure (Pa) for the film change v, at the state's
    cavitated set: dp_F = -A_FF^{-1} (dr/dh v)_F with r = A(k) p - b(h_T), the derivative
    by a forward difference of the assembled residual (step SLOPE_STEP times the film scale)."""
    mesh, solution, squeeze = model.mesh, state.reynolds, model.squeeze
    speed = model.scene.operating.speed
    free = _interior(mesh.shape, mesh.line) & ~solution.cavitated
    base = reynolds_system(mesh, state.expected_gap, state.flow_coefficient, speed, squeeze.rate(state.expected_gap))
    p = solution.pressure[base.unknown]
    r0 = base.matrix @ p - base.rhs
    free_unknown = free[base.unknown]
    eps = SLOPE_STEP * _film_scale(model)

    def apply(v):
        response = np.zeros(mesh.shape)
        norm = float(np.max(np.abs(v)))
        if solution.factor is None or norm == 0.0:
            return response
        h_t, k = fluid_film(model, state.film + (eps / norm) * v)
        moved = reynolds_system(mesh, h_t, k, speed, squeeze.rate(h_t))
        if not np.array_equal(moved.unknown, base.unknown):
            return response
        r1 = moved.matrix @ p - moved.rhs
        response[free] = -solution.factor.solve((r1 - r0)[free_unknown]) * (norm / eps)
        return response

    return apply


def squeeze_newton_step(model, state, residual: np.ndarray) -> np.ndarray:
    """The deformation step of the module docstring (residual = K(p + p_c) - delta)."""
    if model.deformation is None:
        return residual
    mesh = model.mesh
    fluid = fluid_pressure_response(model, state)
    contact = -state.contact_slope if state.contact_slope is not None else 0.0

    def response(v):
        return fluid(v) - contact * v

    rigid = response(np.ones(mesh.shape))
    total = float(np.sum(rigid * mesh.nodal_area))
    if not total < 0.0:
        return residual

    def matvec(v):
        v = v.reshape(mesh.shape)
        dp = response(v)
        shift = -float(np.sum(dp * mesh.nodal_area)) / total
        return (v - model.deformation(dp + shift * rigid)).ravel()

    operator = LinearOperator((residual.size,) * 2, matvec=matvec, dtype=float)
    step, info = gmres(operator, residual.ravel(), rtol=1e-4, atol=0.0, restart=60, maxiter=3)
    if info < 0 or not np.all(np.isfinite(step)):
        return residual
    return step.reshape(mesh.shape)
