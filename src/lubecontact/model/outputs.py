"""What a solved state reports (docs/DESIGN.md "Output of one case"): the electrical path,
real contact area, friction, loads and films. Shared by ``solve`` and each instant of a
transient.
"""

from __future__ import annotations

import numpy as np

from lubecontact.model.model import Model, State
from lubecontact.numerics.mesh import Mesh
from lubecontact.physics.electrical.path import electrical_path
from lubecontact.physics.friction import fluid_shear_force, friction_coefficient


def central_value(mesh: Mesh, field: np.ndarray) -> float:
    row = field[mesh.ny // 2]
    return float(np.interp(0.0, mesh.x, row))


def point_outputs(model: Model, state: State) -> tuple[dict, list[str]]:
    """(outputs, notes) of a solved state, as a case reports them: the electrical path
    (electrical.path), real contact area, friction (docs/DESIGN.md; the shear resists the sliding
    whichever way the block moves), loads and films. Shared by solve() and each instant of a
    transient (unsteady/series.py)."""
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
        pressure, exterior = state.fluid_pressure, 0.0
        if model.far_inlet is not None:  # Martin's film upstream: its pressure at x_min, its shear beyond
            pressure = pressure.copy()
            pressure[:, 0], exterior = model.far_inlet.upstream(pressure, state.film)
        shear = np.sign(scene.operating.speed) * (exterior + fluid_shear_force(
            mesh, state.expected_gap, pressure, state.reynolds.cavitated,
            scene.lubricant.viscosity, scene.operating.speed, film=state.film,
            sigma=model.contact.sigma if model.contact is not None else None,
            content=getattr(state.reynolds, "content", None), split=scene.roughness.split,
        ))
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
        "central_film_thickness": central_value(mesh, state.film),
        "separation": state.z,
        "real_contact_area": real_area,
    }
    return outputs, notes
