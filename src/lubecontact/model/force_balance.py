"""The force balance of Eq. (18): the cylinder position z at which fluid and asperities
carry the applied force, for a fixed deformation (safeguarded Newton with bisection), and
the first-order prediction of z after the deformation changes.
"""

from __future__ import annotations

import numpy as np

from lubecontact.model.evaluation import beyond_the_radius, evaluate, film_scale, force_gradient
from lubecontact.model.model import Model, SolveError, State


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
    scale = film_scale(model)
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
    state = None
    for _ in range(400):
        outside = beyond_the_radius(model, model.undeformed_gap + z + delta)
        if outside:  # the last state evaluated is kept
            raise SolveError(f"force balance left the model at z = {z:.6g} m: {outside}", state)
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


def predicted_position(state: State, force: float, change: np.ndarray) -> float:
    """z balancing ``force`` after the deformation changes by ``change``, to first order from
    the state's load gradient: F + dF/dz dz + sum_j dF/dh_j change_j = force (the state's z
    when the slope is not negative)."""
    gradient = state.load_gradient
    slope = float(np.sum(gradient))
    if not slope < 0.0:
        return state.z
    return state.z - (state.total_force - force + float(np.sum(gradient * change))) / slope
