"""Friction of the sliding contact (the paper plots it, Figs. 5, 7, 9, 11, but defines it nowhere).

docs/DESIGN.md convention: f = [mu_b F_cont + int tau dA] / F, with the boundary friction
coefficient mu_b = interface.boundary_friction on the load the asperities carry and the
viscous shear on the moving block, with Patir & Cheng's (1979) shear stress factors
(docs/physics.md section 3, shear_factors.py) between rough surfaces:

    tau = mu U phi_f / h + phi_fp (h / 2) dp/dx        (Couette + Poiseuille)

(h the mean-plane separation; smooth surfaces: phi_f = phi_fp = 1). mu U phi_f/h stays
finite where the mean planes interpenetrate (h <= 0) and vanishes at h = -3 sigma, where
the surfaces touch everywhere: no floor of the gap is needed.

Under the Reynolds cavitation condition the film ruptures where p returns to zero with
dp/dx = 0; beyond it the lubricant flows as Couette streamers carrying the rupture flux
U h_T*/2, so only the fraction theta = h_T*/h_T of the gap is wetted and the Couette shear
there is scaled by theta (row by row in y). Upstream of the pressure peak the film is full.
With mass-conserving cavitation (effects.cavitation: jfo) theta is the solved film content.
"""

from __future__ import annotations

import numpy as np

from lubecontact.physics.shear_factors import couette_shear_factor, poiseuille_stress_factor, shear_stress_factor_over_gap


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


def shear_stress(film, sigma, pressure_gradient, viscosity: float, speed: float,
                 split: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """Full-film shear on the moving block (Pa): Couette and Poiseuille parts, (ny, nx) each.

    ``film`` h (m); ``sigma`` None or 0 for smooth surfaces (plain mu U/h + (h/2) dp/dx);
    ``split`` the block's share of sigma^2 (phi_fs = (1 - 2 split) Phi_fs, 0 when equal).
    """
    if sigma is None or sigma == 0:
        return viscosity * speed / film, 0.5 * film * pressure_gradient
    H = film / sigma
    factor = couette_shear_factor(H)
    if split != 0.5:
        factor = factor + (1.0 - 2.0 * split) * shear_stress_factor_over_gap(H)
    couette = viscosity * speed * factor / sigma
    return couette, poiseuille_stress_factor(H) * 0.5 * film * pressure_gradient


def fluid_shear_force(mesh, expected_gap, pressure, cavitated, viscosity: float, speed: float, *, film, sigma,
                      content=None, split: float = 0.5) -> float:
    """int tau dA over the mesh, in N (positive: resists the sliding of the block).

    ``expected_gap`` h_T (m) gives the wetted fraction of the cavitated zone (or ``content``,
    the film content theta of a mass-conserving solve), ``film`` h (m) and ``sigma`` (m,
    None for smooth surfaces) and ``split`` (the block's share of sigma^2) the shear stress
    factors."""
    dpdx = np.gradient(pressure, mesh.x, axis=1)
    theta = wetted_fraction(expected_gap, pressure, cavitated) if content is None else content
    couette, poiseuille = shear_stress(film, sigma, dpdx, viscosity, speed, split)
    tau = theta * couette + poiseuille * (~cavitated)
    return float(np.sum(tau * mesh.nodal_area))


def friction_coefficient(boundary_friction: float, contact_force: float, shear_force: float, applied_force: float) -> float:
    """f of docs/DESIGN.md: (mu_b F_cont + F_shear) / F."""
    return (boundary_friction * contact_force + shear_force) / applied_force
