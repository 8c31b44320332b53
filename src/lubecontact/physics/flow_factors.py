"""Patir-Cheng average-flow model: expected gap, pressure flow factor, Poiseuille coefficient.

The paper's modified Reynolds equation (Eq. 1) carries the pressure flow factors
phi_x = phi_y = 1 - 0.90 exp(-0.56 h/sigma) of Eq. (2) (Patir & Cheng 1978,
J. Lubr. Technol. 100:12, isotropic roughness gamma = 1). Patir & Cheng's averaged equation
puts the *expected* gap h_T in the Couette term; for Gaussian heights of standard deviation
sigma and mean-plane separation h (H = h/sigma)

    h_T = sigma [H Phi(H) + phi(H)]          (Phi, phi: standard normal CDF and PDF)

which tends to h for H >> 1 and to 0+ (never negative) for H -> -inf.

Eq. (2) is fitted for H > 0.5 only; it turns negative below H ~ -0.19 and h^3 turns negative
with h. Below H = 0.5 the Poiseuille coefficient follows the expected gap
(docs/DESIGN.md, "Physics conventions"):

    k(H) = phi_x(H) h^3 / (12 mu)                       H >= 0.5
    k(H) = k(0.5) [h_T(H) / h_T(0.5)]^3                 H <  0.5

continuous at H = 0.5, positive, and monotone in H. Smooth surfaces (sigma None or 0, i.e.
``asperity_contact`` off) use h itself with phi = 1.

The coupled solver uses, for rough surfaces, the law down to percolation instead
(``percolating_coefficient_and_slope``, docs/physics.md section 15: zero flow at h = 0 up to a
leak); the regularised k above remains the estimate of model/auto_effects.py's automatic decisions.
"""

from __future__ import annotations

import numpy as np
from scipy.special import erfcx, ndtr


# Eq. (2): Patir & Cheng (1978) isotropic (gamma = 1) pressure flow factor 1 - C exp(-r H).
PC_C = 0.90
PC_R = 0.56
# Lower end of the range Patir & Cheng fitted Eq. (2) over; the regularisation starts here.
H_VALID = 0.5

_INV_SQRT_2PI = 1.0 / np.sqrt(2.0 * np.pi)


class ClosedFilmError(ValueError):
    """A smooth film (no asperity contact) closed at a node: k = h^3/(12 mu) has no value
    there. A solver that meets it reports it as not converged (model/coupling.py)."""


def _smooth(sigma) -> bool:
    return sigma is None or sigma == 0


def _mean_gap_ratio(H: np.ndarray, cdf: np.ndarray | None = None) -> np.ndarray:
    """h_T / sigma = H Phi(H) + phi(H), evaluated without cancellation; ``cdf``: Phi(H) when
    the caller has it already.

    For H >= 0 both terms are positive. For H = -t < 0 it is the first partial moment
    F_1(t) = phi(t) - t Phi(-t) = exp(-t^2/2) [1/sqrt(2 pi) - (t/2) erfcx(t/sqrt 2)], whose
    bracket loses only ~eps t^2 relatively; it underflows to 0 (not below) for t > ~38.
    The second form is evaluated only where H < 0.
    """
    H = np.asarray(H, dtype=float)
    cdf = ndtr(H) if cdf is None else cdf
    ratio = H * cdf + _INV_SQRT_2PI * np.exp(-0.5 * H * H)
    negative = H < 0.0
    if np.any(negative):
        t = -H[negative]
        lower = np.exp(-0.5 * t * t) * (_INV_SQRT_2PI - 0.5 * t * erfcx(t / np.sqrt(2.0)))
        ratio = np.array(ratio, dtype=float)  # writable, also for 0-d input
        ratio[negative] = np.maximum(lower, 0.0)
    return ratio


def expected_gap(h, sigma):
    """Patir-Cheng expected gap h_T = sigma [H Phi(H) + phi(H)], H = h/sigma, in m.

    Finite for any finite h, never negative, -> h for H >> 1 (|h_T - h| < 1e-5 sigma for
    H > 3.9). Smooth surfaces (sigma None or 0): h_T = h.
    """
    h = np.asarray(h, dtype=float)
    if _smooth(sigma):
        return h
    return sigma * _mean_gap_ratio(h / sigma)


def pressure_flow_factor(H):
    """Eq. (2): phi_x = phi_y = 1 - 0.90 exp(-0.56 H), H = h/sigma (fitted for H > 0.5)."""
    return 1.0 - PC_C * np.exp(-PC_R * np.asarray(H, dtype=float))


def expected_gap_slope(h, sigma):
    """dh_T/dh = Phi(H), the fraction of the gap that is open (1 for smooth surfaces)."""
    h = np.asarray(h, dtype=float)
    if _smooth(sigma):
        return np.ones_like(h)
    return ndtr(h / sigma)


def expected_gap_and_slope(h, sigma):
    """(h_T, dh_T/dh) of ``expected_gap`` and ``expected_gap_slope`` with Phi(H) evaluated once."""
    h = np.asarray(h, dtype=float)
    if _smooth(sigma):
        return h, np.ones_like(h)
    H = h / sigma
    cdf = ndtr(H)
    return sigma * _mean_gap_ratio(H, cdf), cdf


def pressure_flow_factor_slope(H):
    """d phi_x/dH of Eq. (2): 0.90 x 0.56 exp(-0.56 H)."""
    return PC_C * PC_R * np.exp(-PC_R * np.asarray(H, dtype=float))


def poiseuille_coefficient_and_slope(h, sigma, viscosity, flow_factors=True):
    """(k, dk/dh): the Poiseuille coefficient of the averaged Reynolds equation (Eq. 1),
    m^3/(Pa s), and its derivative in the film, m^2/(Pa s), for the Newton/adjoint steps.

    k = phi_x(H) h^3/(12 mu) for H = h/sigma >= 0.5 and k(0.5) [h_T(H)/h_T(0.5)]^3 below
    (continuous, positive, monotone in H). ``flow_factors=False`` sets phi_x = 1 (plain
    Reynolds) with the same regularisation below H = 0.5, so k stays positive.
    Smooth surfaces (sigma None or 0): k = h^3/(12 mu), which needs h > 0 everywhere.
    """
    h = np.asarray(h, dtype=float)
    if _smooth(sigma):
        if not np.all(h > 0.0):
            raise ClosedFilmError(
                f"smooth surfaces need a positive film everywhere; min h = {np.min(h):.3g} m "
                "(the solid bodies interpenetrate without asperity contact)"
            )
        return h**3 / (12.0 * viscosity), h**2 / (4.0 * viscosity)

    H = h / sigma
    H_upper = np.maximum(H, H_VALID)  # evaluate the fit only where it applies (no overflow)
    if flow_factors:
        phi, dphi = pressure_flow_factor(H_upper), pressure_flow_factor_slope(H_upper)
        phi_valid = pressure_flow_factor(H_VALID)
    else:
        phi, dphi, phi_valid = np.ones_like(H_upper), np.zeros_like(H_upper), 1.0
    cube = sigma**3 / (12.0 * viscosity)
    upper = phi * H_upper**3 * cube
    upper_slope = (dphi * H_upper**3 + 3.0 * phi * H_upper**2) * cube / sigma
    gap_ratio = _mean_gap_ratio(H) / _mean_gap_ratio(H_VALID)
    lower = phi_valid * H_VALID**3 * cube * gap_ratio**3
    # d/dh of k(0.5) (h_T/h_T(0.5))^3 = 3 k Phi(H) / h_T (0 where h_T underflowed)
    h_t = sigma * _mean_gap_ratio(H)
    lower_slope = np.divide(3.0 * lower * ndtr(H), h_t, out=np.zeros_like(h_t), where=h_t > 0.0)
    above = H >= H_VALID
    return np.where(above, upper, lower), np.where(above, upper_slope, lower_slope)


def poiseuille_coefficient(h, sigma, viscosity, flow_factors=True):
    """k of ``poiseuille_coefficient_and_slope``, m^3/(Pa s)."""
    return poiseuille_coefficient_and_slope(h, sigma, viscosity, flow_factors)[0]


# Below the percolation threshold (docs/physics.md section 15) the lubricant sits in closed pockets
# and the averaged film stops conducting. Threshold: the mean gap h = 0, where the open part
# of a Gaussian gap {gap > 0} covers half the plane, the 2D level-set percolation threshold
# of a symmetric random field (Zallen & Scher 1971, Phys. Rev. B 4:4471; the effective-medium
# threshold of Bruggeman/Kirkpatrick is the same area fraction 1/2).
# Between the threshold and H = 0.5 the conductance rises as the open fraction's distance
# from it, exponent t = 1 (the effective-medium conductivity exponent):
#     k(H) = k(0.5) [(Phi(H) - 1/2) / (Phi(0.5) - 1/2)]^t     0 < H < 0.5,    0 for H <= 0,
# t = 1 by default; roughness.percolation_exponent sets it (1.3: 2-D percolation's universal
# conductivity exponent, for the sensitivity of a result to this law).
# A sealed film still leaks a little (finite pockets, the asperity-scale remaking of closed
# clusters by sliding): k never falls below SEALED_LEAKAGE k(0.5). In steady state any leak
# equilibrates the pockets with the film around them, so the answer is the limit of a
# vanishing leak: on Table 1 (line mode, 51-201 nodes, 0.01 m/s) the fluid load changes by
# < 0.9 % between leakages 1e-2 and 1e-4 and by < 0.1 % between 1e-3 and 1e-4.
SEALED_LEAKAGE = 1e-3


def percolating_coefficient_and_slope(h, sigma, viscosity, flow_factors=True, exponent=1.0):
    """(k, dk/dh) of the Poiseuille coefficient down to percolation, m^3/(Pa s) and m^2/(Pa s):
    Patir-Cheng's (``poiseuille_coefficient_and_slope``) for H = h/sigma >= 0.5, the
    percolation law above for H < 0.5 with the share raised to ``exponent`` t (1: effective
    medium; roughness.percolation_exponent), floored at SEALED_LEAKAGE k(0.5) (slope 0 there).
    Continuous at H = 0.5, non-decreasing in h. Needs rough surfaces (sigma > 0).

    Evaluated in one pass (it runs on every face of every evaluation): above H = 0.5 only the
    branch of poiseuille_coefficient_and_slope that applies there, below it one Phi."""
    H = np.asarray(h, dtype=float) / sigma
    H_upper = np.maximum(H, H_VALID)
    cube = sigma**3 / (12.0 * viscosity)
    if flow_factors:
        phi, dphi = pressure_flow_factor(H_upper), pressure_flow_factor_slope(H_upper)
    else:
        phi, dphi = 1.0, 0.0
    upper = phi * H_upper**3 * cube
    upper_slope = (dphi * H_upper**3 + 3.0 * phi * H_upper**2) * (cube / sigma)
    k_valid = poiseuille_coefficient(H_VALID * sigma, sigma, viscosity, flow_factors)
    reference = ndtr(H_VALID) - 0.5
    # below H = -40 Phi(H) and its slope are 0 to double precision: clipped there, a film far
    # out of range (a rejected iterate) cannot overflow the square
    H_lower = np.clip(H, -40.0, H_VALID)
    share = (ndtr(H_lower) - 0.5) / reference
    share_slope = _INV_SQRT_2PI * np.exp(-0.5 * H_lower**2) / reference
    if exponent != 1.0:  # a negative share (sealed, floored below) has no real power
        share = np.maximum(share, 0.0)
        share_slope = exponent * share ** (exponent - 1.0) * share_slope
        share = share**exponent
    above = H >= H_VALID
    k = np.where(above, upper, k_valid * share)
    slope = np.where(above, upper_slope, k_valid * share_slope / sigma)
    leaking = k < SEALED_LEAKAGE * k_valid
    return np.where(leaking, SEALED_LEAKAGE * k_valid, k), np.where(leaking, 0.0, slope)
