"""One evaluation of the coupled model: pressures and forces at a cylinder position z and a
deformation delta (Eqs. 1, 3-5, 11), and the load's gradient with respect to the film
(contact law slope plus the Reynolds adjoint) that the force balance and the position
predictor use.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from lubecontact.model.fluid_film import fluid_exterior, fluid_faces, fluid_film, fluid_slopes, squeeze_content
from lubecontact.model.model import Model, State
from lubecontact.numerics.cavitation_jfo import solve_jfo
from lubecontact.numerics.mesh import contact_width_estimate
from lubecontact.numerics.reynolds import solve_reynolds
from lubecontact.physics.film_estimates import entrained_film


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
    h_t = k = reynolds = faces = face_slopes = content = None
    if model.hydrodynamic:
        h_t, k = fluid_film(model, film)
        if scene.effects.cavitation == "jfo":  # mass-conserving cavitation (cavitation_jfo.py)
            solve_fluid = solve_jfo
        else:
            solve_fluid = partial(solve_reynolds, cavitation=scene.effects.cavitation == "reynolds",
                                  pressure_guess=pressure_guess)
        faces, face_slopes = fluid_faces(model, film)
        options = {}
        if model.squeeze is not None:  # a time step (unsteady/): the cells' content, squeezed
            content = squeeze_content(model, film)
            options["squeeze_rate"] = model.squeeze.rate(content.value)
        exterior = fluid_exterior(model, film)
        if exterior is not None:  # a 2-D mesh open to the far inlet (Reynolds cavitation only)
            options["exterior"] = exterior
        reynolds = solve_fluid(mesh, h_t, k, scene.operating.speed, cavitated_guess=cavitated_guess, reuse=reuse,
                               faces=faces, **options)
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
        fluid_force=fluid_load(model, fluid_pressure, film),
        contact_slope=contact_slope,
        flow_coefficient=k,
        faces=faces,
        face_slopes=face_slopes,
        squeeze_content=content,
    )


def fluid_load(model: Model, pressure: np.ndarray, film: np.ndarray) -> float:
    """The fluid's load (N): the trapezoidal sum of p dA over the mesh, plus on a mesh open to
    the far inlet the load of Martin's film upstream of it (numerics/far_inlet.FarInlet.load)."""
    load = float(np.sum(pressure * model.mesh.nodal_area))
    if model.far_inlet is not None:
        load += model.far_inlet.load(pressure, film)[0]
    return load


def fluid_load_slopes(model: Model, state: State) -> tuple[np.ndarray, np.ndarray | None]:
    """(dW/dp (ny, nx, m^2), dW/dh at fixed p (ny, nx, N/m) or None) of fluid_load at
    ``state``: the nodal areas, and on a mesh open to the far inlet its exterior's weight on
    the first Reynolds node and its film slope."""
    area = model.mesh.nodal_area
    if model.far_inlet is None:
        return area, None
    _, weights, film_slope = model.far_inlet.load(state.fluid_pressure, state.film)
    return area + weights, film_slope


def beyond_the_radius(model: Model, film: np.ndarray) -> str:
    """Why ``film`` (m) is outside the model where its size (a gap, or an interference where
    negative) reaches the cylinder's radius, else "": the lubrication approximation, the
    parabolic gap of Eq. (4) and the contact laws need |h| << R. Only an iteration that ran
    away gets there (long steps over an impasse, integrator.jump_over_impasse: the cylinder's
    position grew without bound, 254 m, 1.6e9 m, ...), and the solvers refuse such a position
    instead of evaluating it."""
    radius = model.scene.geometry.radius
    size = np.abs(film)
    if np.all(size < radius):
        return ""
    why = (f"a film of {film.ravel()[np.argmax(size)]:.3g} m is not smaller than the cylinder's radius ({radius:g} m): "
           "the lubrication approximation, the parabolic gap (Eq. 4) and the contact laws need |h| << R")
    x, width = model.mesh.x, contact_width_estimate(model.scene)
    if x[-1] - x[0] < width:  # a hostile run's explicit domain of 2 nm, under a 0.35 mm contact
        why += (f"; the domain mesh.x_min..mesh.x_max, {x[-1] - x[0]:.3g} m long, is narrower than the contact "
                f"expected under operating.force ({width:.3g} m), so the cylinder sank to carry it: widen the "
                "domain, or leave mesh.x_min and mesh.x_max out for the automatic one")
    return why


def film_scale(model: Model) -> float:
    """A length on which the force changes appreciably: sigma, or a rigid Martin film (a
    grease's at its flowing viscosity, film_estimates.entrained_film)."""
    if model.contact is not None:
        return model.contact.sigma
    if model.squeeze is not None:
        return model.squeeze.film_scale

    return entrained_film(model.scene)


def force_gradient(model: Model, state: State) -> np.ndarray:
    """dF/dh_j, N/m (ny, nx): how the carried load changes with the film at each node, at the
    state's cavitated set: contact dp_c/dh times the nodal area plus the Reynolds adjoint
    (the fluid solution's load_sensitivity, one back-substitution). Its sum is dF/dz (< 0)."""
    gradient = np.zeros(model.mesh.shape)
    if state.contact_slope is not None:
        gradient += state.contact_slope * model.mesh.nodal_area
    if state.reynolds is not None:
        face_slopes, gap_slope, coefficient_slope = fluid_slopes(model, state)
        options = {} if model.squeeze is None else {"squeeze": (model.squeeze.coefficient, state.squeeze_content)}
        if face_slopes is not None:  # rough surfaces: the film on the faces (percolation.py)
            gap_slope, coefficient_slope = None, face_slopes
        weight, film_slope = fluid_load_slopes(model, state)
        if film_slope is not None:  # the far inlet's load (fluid_load)
            options["load_weight"] = weight
            gradient += film_slope
        exterior = fluid_exterior(model, state.film)
        if exterior is not None:  # and a 2-D mesh's exterior flux (numerics/modal_far_inlet.py)
            options["exterior"] = exterior
        gradient += state.reynolds.load_sensitivity(model.mesh, gap_slope, coefficient_slope, model.scene.operating.speed,
                                                    **options)
    return gradient
