"""The film the fluid sees (Eqs. 1-2): the film content h_T and Poiseuille coefficient k at
the nodes and on the faces, and their slopes for the linearised Reynolds residual.

Rough surfaces use Patir-Cheng's expected gap and flow factor down to percolation
(physics/flow_factors.py, physics/percolation.py, docs/physics.md sections 3 and 15);
smooth surfaces h itself with k = h^3/(12 mu).
"""

from __future__ import annotations

from functools import partial

import numpy as np

from lubecontact.model.model import Model, State
from lubecontact.numerics.control_volume import ControlVolumeMean, GaussHalfCells, control_volume_mean
from lubecontact.numerics.expected_gap_cells import ExpectedGapHalfCells
from lubecontact.numerics.reynolds import cell_diagonal, face_transmissibilities
from lubecontact.physics.flow_factors import (
    H_VALID,
    expected_gap_and_slope,
    percolating_coefficient_and_slope,
    poiseuille_coefficient_and_slope,
)
from lubecontact.physics.percolation import face_film
from lubecontact.physics.shear_factors import couette_gap
from lubecontact.physics.yield_stress_flow import YieldStressLaw, lubricant_law

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


def carries_shear_flow(model: Model) -> bool:
    """Whether the Couette content holds the shear flow factor: flow factors between rough
    surfaces of unequal roughness (roughness.split != 0.5)."""
    scene = model.scene
    return model.contact is not None and scene.effects.flow_factors and scene.roughness.split != 0.5


def content_law(model: Model):
    """h -> (h_T, dh_T/dh): Patir-Cheng expected gap, or where the shear flow factor enters
    (carries_shear_flow) the Couette gap h_T + sigma phi_s (shear_factors.couette_gap)."""
    sigma = model.contact.sigma if model.contact is not None else None
    if carries_shear_flow(model):
        return partial(couette_gap, sigma=sigma, split=model.scene.roughness.split)
    return lambda h: expected_gap_and_slope(h, sigma)


def coefficient_law(model: Model):
    """h -> (k, dk/dh): Patir-Cheng's Poiseuille coefficient down to percolation with
    roughness.percolation_exponent (rough surfaces), or h^3/(12 mu) (smooth)."""
    scene = model.scene
    if model.contact is None:
        return lambda h: poiseuille_coefficient_and_slope(h, None, scene.lubricant.viscosity, scene.effects.flow_factors)
    sigma, exponent = model.contact.sigma, scene.roughness.percolation_exponent
    return lambda h: percolating_coefficient_and_slope(h, sigma, scene.lubricant.viscosity, scene.effects.flow_factors,
                                                       exponent)


def yield_stress_law(model: Model) -> YieldStressLaw | None:
    """The flow law of a grease (lubricant.rheology bingham or herschel_bulkley,
    docs/physics.md section 21), None for a Newtonian lubricant."""
    return lubricant_law(model.scene.lubricant)


def squeeze_content(model: Model, film: np.ndarray) -> ControlVolumeMean:
    """The film content each cell holds, for a transient's squeeze term dA dh_T/dt
    (docs/physics.md section 14): with rough surfaces the cell's mean of the content frozen
    below FLUID_FILM_FLOOR_SIGMAS (numerics/control_volume.py: a cell empties gradually as
    its film crosses the floor, not at once when its node does); smooth surfaces, whose
    content is the film itself, keep the nodal value (lumped: second order without a kink).
    The expected gap's half cells have a closed form (numerics/expected_gap_cells.py, for the
    floor at h = 0); the Couette gap's are a quadrature."""
    if model.contact is None:
        return ControlVolumeMean.lumped(*content_law(model)(film))
    if carries_shear_flow(model):
        return control_volume_mean(film, GaussHalfCells(frozen_content_law(model),
                                                        FLUID_FILM_FLOOR_SIGMAS * model.contact.sigma))
    return control_volume_mean(film, ExpectedGapHalfCells(model.contact.sigma))


def frozen_content_law(model: Model):
    """h -> (h_T, dh_T/dh) of content_law, frozen below FLUID_FILM_FLOOR_SIGMAS x sigma with
    rough surfaces (slope 0 there); smooth surfaces: content_law itself."""
    content = content_law(model)
    if model.contact is None:
        return content
    floor = FLUID_FILM_FLOOR_SIGMAS * model.contact.sigma

    def frozen(h):
        value, slope = content(np.maximum(h, floor))
        return value, np.where(h < floor, 0.0, slope)

    return frozen


def fluid_film(model: Model, film: np.ndarray, slopes: bool = False):
    """(h_T, k) at the nodes for the Reynolds equation (Eqs. 1-2; content_law and
    coefficient_law, the content frozen below FLUID_FILM_FLOOR_SIGMAS); with ``slopes``
    also their derivatives (dh_T/dh, dk/dh) for the adjoint (content slope 0 below the floor:
    frozen_content_law)."""
    k, dk = coefficient_law(model)(film)
    h_t, dh_t = frozen_content_law(model)(film)
    if slopes:
        return h_t, k, dh_t, dk
    return h_t, k


def open_film_diagonal(model: Model) -> np.ndarray:
    """The Poiseuille diagonal A_ii (ny, nx), m^3/(Pa s), each cell of the mesh would have
    were every face to conduct as the film at the percolation law's reference H = H_VALID
    (flow_factors.percolating_coefficient_and_slope: Patir-Cheng's coefficient there, the
    percolation law below it): the conductance of a just-open rough film. Rough surfaces."""
    reference = float(coefficient_law(model)(np.array(H_VALID * model.contact.sigma))[0])
    return cell_diagonal(model.mesh, *face_transmissibilities(model.mesh, np.full(model.mesh.shape, reference)))


def fluid_faces(model: Model, film: np.ndarray):
    """(values, slopes) percolation.FaceFilm of the film on the faces (rough surfaces), or
    (None, None) for smooth ones (nodal means, reynolds.py); on a mesh open to the far inlet
    the first x face carries the exterior's flux (numerics/far_inlet.FarInlet.faces)."""
    if model.contact is None:
        return None, None
    values, slopes = face_film(film, coefficient_law(model), content_law(model))
    if model.far_inlet is not None:
        return model.far_inlet.faces(film, values, slopes)
    return values, slopes


def fluid_exterior(model: Model, film: np.ndarray):
    """The dense exterior of a 2-D mesh open to the far inlet at ``film``
    (numerics/modal_far_inlet.Exterior), else None (a line's is its first face, fluid_faces)."""
    return None if model.far_inlet is None else model.far_inlet.exterior(film)


def fluid_slopes(model: Model, state: State):
    """(face slopes, nodal dh_T/dh, nodal dk/dh) of the film the fluid saw at ``state``, for
    the linearised Reynolds residual (force_gradient, newton.fluid_pressure_response): the
    face slopes (percolation.FaceFilm; None for smooth surfaces) and the nodal slopes of
    fluid_film where they are used (smooth faces), else None (a transient's squeeze term
    has its own, State.squeeze_content)."""
    if state.face_slopes is not None:
        return state.face_slopes, None, None
    _, _, gap_slope, coefficient_slope = fluid_film(model, state.film, slopes=True)
    return state.face_slopes, gap_slope, coefficient_slope
