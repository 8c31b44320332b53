"""Friction of the sliding contact (the paper plots it, Figs. 5, 7, 9, 11, but defines it nowhere).

DESIGN.md convention: f = [mu_b F_cont + int tau dA] / F, with the boundary friction
coefficient mu_b = interface.boundary_friction on the load the asperities carry and the
viscous shear on the moving block

    tau = mu U / h_T + (h_T / 2) dp/dx        (Couette + Poiseuille, h_T of Patir & Cheng)

Under the Reynolds cavitation condition the film ruptures where p returns to zero with
dp/dx = 0; beyond it the lubricant flows as Couette streamers carrying the rupture flux
U h_T*/2, so only the fraction theta = h_T*/h_T of the gap is wetted and the Couette shear
there is scaled by theta (row by row in y). Upstream of the pressure peak the film is full.

Where the rough surfaces are in contact (h < 0) h_T -> 0 and mu U/h_T would diverge; the
lubricant there is held in the valleys between contacting asperities. The expected gap this
module receives is the fluid's (solver.fluid_film), which holds the film at h = 0 there, so
the Couette gap is never below h_T(0) = sigma/sqrt(2 pi).
"""

from __future__ import annotations

import numpy as np


def wetted_fraction(expected_gap: np.ndarray, pressure: np.ndarray, cavitated: np.ndarray) -> np.ndarray:
    """theta (ny, nx): 1 in the full film; h_T*/h_T downstream of each row's film rupture."""
    theta = np.ones_like(expected_gap)
    for j in range(expected_gap.shape[0]):
        row_p = pressure[j]
        if not np.any(row_p > 0.0):
            continue
        peak = int(np.argmax(row_p))
        downstream = np.flatnonzero(cavitated[j, peak:])
        if downstream.size == 0:
            continue
        rupture = peak + int(downstream[0])
        h_star = expected_gap[j, rupture - 1] if rupture > 0 else expected_gap[j, rupture]
        tail = slice(rupture, None)
        wet = np.minimum(1.0, h_star / expected_gap[j, tail])
        theta[j, tail] = np.where(cavitated[j, tail], wet, 1.0)
    return theta


def fluid_shear_force(mesh, expected_gap, pressure, cavitated, viscosity: float, speed: float) -> float:
    """int tau dA over the mesh, in N (positive: resists the sliding of the block)."""
    dpdx = np.gradient(pressure, mesh.x, axis=1)
    theta = wetted_fraction(expected_gap, pressure, cavitated)
    tau = theta * viscosity * speed / expected_gap + 0.5 * expected_gap * dpdx * (~cavitated)
    return float(np.sum(tau * mesh.nodal_area))


def friction_coefficient(boundary_friction: float, contact_force: float, shear_force: float, applied_force: float) -> float:
    """f of DESIGN.md: (mu_b F_cont + F_shear) / F."""
    return (boundary_friction * contact_force + shear_force) / applied_force
