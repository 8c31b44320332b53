"""The paper's spot resistance: Holm spots, Cooper's alleviation, nodes in parallel (Eqs. 15-17).

This is the whole electrical model of the paper (docs/physics.md section 8) and the first term
of the full path (:mod:`lubecontact.physics.electrical.path`).

- Holm: one circular spot of radius a between half-spaces of resistivities rho1, rho2 has
  resistance (rho1 + rho2)/(4a) (= rho/(2a) for one material); per nominal area the spots
  add in parallel to the conductance g of Eq. (15) (see :mod:`lubecontact.physics.rough_surface`).
- Alleviation (Cooper, Mikic & Yovanovich 1969, IJHMT 12:279), Eq. (16):
  Psi = (1 - sqrt(A_r/A_n))^1.5 multiplies the resistance (Eq. 17), i.e. divides g.
  A_r/A_n of the statistical model can pass 1 at deep interference; it is clamped at
  MAX_AREA_FRACTION = 0.99 for Psi (Psi >= 3.5e-4) and the clamped nodes are reported.
- Nodes conduct in parallel, each with the Psi of its own A_r/A_n (docs/DESIGN.md):
  R = 1 / sum_i (g_i dA_i / Psi_i). The sum is taken in logarithms (log-sum-exp) so that R
  stays finite and monotone for as long as it is representable, even where every g_i
  underflows, and is +inf (open circuit) only beyond.
"""

from __future__ import annotations

import math

import numpy as np

MAX_AREA_FRACTION = 0.99  # A_r/A_n used in Psi is clamped here (Eq. 16 needs A_r/A_n < 1)
_LOG_FLOAT_MAX = math.log(np.finfo(float).max)


def alleviation_factor(area_fraction) -> tuple[np.ndarray, np.ndarray]:
    """(Psi, clamped): Psi = (1 - sqrt(min(A_r/A_n, 0.99)))^1.5 (Eq. 16) and the boolean
    mask of the entries whose A_r/A_n exceeded MAX_AREA_FRACTION."""
    area_fraction = np.asarray(area_fraction, dtype=float)
    if np.isnan(area_fraction).any():
        raise ValueError("alleviation factor of a NaN area fraction")
    clamped = area_fraction > MAX_AREA_FRACTION
    ratio = np.clip(area_fraction, 0.0, MAX_AREA_FRACTION)
    return (1.0 - np.sqrt(ratio)) ** 1.5, clamped


def contact_resistance(log_conductance, area_fraction, nodal_area, alleviation: bool) -> tuple[float, int]:
    """(R in ohm, number of nodes whose A_r/A_n was clamped for Psi).

    R = 1 / sum_i (g_i dA_i / Psi_i) over the nodes with dA_i > 0 (Eqs. 15-17), with
    log g_i = ``log_conductance`` (S/m^2, -inf where g_i = 0), dA_i = ``nodal_area`` (m^2)
    and Psi_i from ``area_fraction`` if ``alleviation`` (else Psi = 1 and no node is
    clamped). +inf when no conductance is representable; 0.0 if some g_i is infinite.
    """
    log_g = np.asarray(log_conductance, dtype=float)
    area = np.asarray(nodal_area, dtype=float)
    if np.isnan(log_g).any():
        raise ValueError("contact resistance of a NaN conductance")
    if (area < 0.0).any() or not np.isfinite(area).all():
        raise ValueError("nodal areas must be finite and non-negative")
    used = np.broadcast_to(area > 0.0, log_g.shape)
    terms = log_g[used] + np.log(np.broadcast_to(area, log_g.shape)[used])
    n_clamped = 0
    if alleviation:
        psi, clamped = alleviation_factor(np.broadcast_to(area_fraction, log_g.shape)[used])
        terms = terms - np.log(psi)
        n_clamped = int(clamped.sum())
    peak = terms.max(initial=-np.inf)
    if peak == np.inf:
        return 0.0, n_clamped
    if peak == -np.inf:
        return np.inf, n_clamped
    log_total = peak + math.log(np.exp(terms - peak).sum())  # log sum_i g_i dA_i / Psi_i
    return (np.inf if -log_total > _LOG_FLOAT_MAX else math.exp(-log_total)), n_clamped
