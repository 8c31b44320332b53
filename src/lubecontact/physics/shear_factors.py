"""Patir & Cheng's (1979) shear stress factors and shear flow factor (docs/physics.md section 3).

Patir & Cheng, "Application of average flow model to lubrication between rough sliding
surfaces", J. Lubr. Technol. 101 (1979) 220. For Gaussian heights of combined standard
deviation sigma (H = h/sigma, h the mean-plane separation) the mean shear stress on a
surface of a film whose surfaces slide at u1, u2 is

    tau = mu (u2 - u1)/h (phi_f +- phi_fs) + phi_fp (h/2) dp/dx.

- phi_f (Couette part) is the expectation of h/h_local over the gap (their distribution is
  the polynomial (35/32)(1 - z^2)^3 on |z| < 1, z = height/(3 sigma), local gaps cut off at
  1/300 of the range). It is an integral over the wetted part of the gap, so it holds for
  any H: mu U phi_f/h stays finite at h = 0 and vanishes at H = -3, where the surfaces
  touch everywhere (``couette_shear_factor`` returns sigma phi_f/h, finite for all H).
- phi_fp = 1 - 1.40 exp(-0.66 H) (isotropic, gamma = 1; fitted for H > 0.5). The fit
  crosses zero at H = ln(1.4)/0.66 = 0.5098; below that the Poiseuille shear is taken as
  zero (continuous; the fit has no meaning there, and dp/dx is small where the film is
  that thin and its pressure flow has stopped: flow_factors).
- Phi_fs and the shear flow factor Phi_s (gamma = 1) enter only for surfaces of unequal
  roughness: phi_fs = V_r2 Phi_fs - V_r1 Phi_fs and phi_s = (V_r1 - V_r2) Phi_s with the
  shares V_ri = sigma_i^2/sigma^2 of the variance (both vanish for equal roughness).
  Here surface 1 is the sliding block (u1 = U) and surface 2 the cylinder (u2 = 0), and
  ``roughness.split`` = V_r1, the block's share of sigma^2: the Couette flux becomes
  (U/2)(h_T + sigma phi_s) (``couette_gap``) and the shear on the block gains
  mu U phi_fs/h (upper signs of docs/physics.md section 3 for surface 1).
"""

from __future__ import annotations

import numpy as np

from lubecontact.physics.flow_factors import expected_gap, expected_gap_slope

# Zero of the phi_fp fit: 1 - 1.40 exp(-0.66 H) = 0.
FP_ZERO = np.log(1.40) / 0.66


# For z = H/3 > 1 the two terms of phi_f's bracket grow like z^6 and cancel to ~1/z: at
# H = 300 the closed form is 1 % off in double precision, at H = 3000 it is 5e4 (thick films
# at the inlet of a long domain). From z = SERIES_FROM_Z on phi_f is summed from its
# expansion in w = 1/z, phi_f = sum_k 105 w^(2k) / ((2k+1)(2k+3)(2k+5)(2k+7)) (derived by
# expanding ln((z+1)/(z-1)) = 2 sum w^(2k+1)/(2k+1); the negative powers cancel exactly),
# 24 terms: truncation below w^48/k^4 ~ 1e-31 at z = 4, where both forms agree to 1e-12.
SERIES_FROM_Z = 4.0
_K = np.arange(24.0)
_SERIES = 105.0 / ((2 * _K + 1) * (2 * _K + 3) * (2 * _K + 5) * (2 * _K + 7))


def _couette_bracket(z: np.ndarray) -> np.ndarray:
    """(35/96) x the bracket of phi_f for |z| <= 1 (z = H/3): sigma phi_f/h there."""
    zp = np.clip(z, -1.0 + 1e-12, 1.0)
    poly = -55.0 + zp * (132.0 + zp * (345.0 + zp * (-160.0 + zp * (-405.0 + zp * (60.0 + 147.0 * zp)))))
    log_term = (1.0 - zp * zp) ** 3 * np.log(300.0 * (zp + 1.0))
    return (35.0 / 96.0) * (log_term + poly / 60.0)


def couette_shear_factor(H) -> np.ndarray:
    """sigma phi_f(H)/h = phi_f/H: the Couette shear is mu U/sigma times this (finite, >= 0).

    H <= 3: (35/96)[(1 - z^2)^3 ln(300(z + 1)) + (1/60) P(z)], z = H/3 (0 for H <= -3);
    H > 3: (35/96)[(1 - z^2)^3 ln((z + 1)/(z - 1)) + (z/15)(66 + z^2(30 z^2 - 80))], which
    tends to 1/H (phi_f -> 1, plain Couette) for thick films.
    """
    H = np.asarray(H, dtype=float)
    z = H / 3.0
    inner = np.maximum(_couette_bracket(np.minimum(z, 1.0)), 0.0)  # rounding below 0 near z = -1
    zo = np.clip(z, 1.0 + 1e-12, SERIES_FROM_Z)
    outer = (35.0 / 96.0) * ((1.0 - zo * zo) ** 3 * np.log((zo + 1.0) / (zo - 1.0))
                             + (zo / 15.0) * (66.0 + zo * zo * (30.0 * zo * zo - 80.0)))
    zs = np.maximum(z, SERIES_FROM_Z)
    far = np.polynomial.polynomial.polyval(1.0 / (zs * zs), _SERIES) / (3.0 * zs)
    return np.where(H <= -3.0, 0.0, np.where(z <= 1.0, inner, np.where(z < SERIES_FROM_Z, outer, far)))


def couette_stress_factor(H) -> np.ndarray:
    """phi_f(H) = H x couette_shear_factor(H) (Patir & Cheng 1979)."""
    H = np.asarray(H, dtype=float)
    return H * couette_shear_factor(H)


def poiseuille_stress_factor(H) -> np.ndarray:
    """phi_fp = 1 - 1.40 exp(-0.66 H), gamma = 1; 0 below its zero H = 0.5098."""
    H = np.asarray(H, dtype=float)
    return np.where(H > FP_ZERO, 1.0 - 1.40 * np.exp(-0.66 * np.maximum(H, FP_ZERO)), 0.0)


def _branches(H, low, high, split_at):
    H = np.asarray(H, dtype=float)
    return np.where(H <= split_at, low(np.minimum(H, split_at)), high(np.maximum(H, split_at)))


def shear_stress_factor_over_gap(H) -> np.ndarray:
    """Phi_fs(H)/H = 11.1 H^1.31 exp(-2.38 H + 0.11 H^2) (0 for H <= 0 and H >= 7): the shear
    stress it adds is mu U/sigma times this times (V_r2 - V_r1)."""
    H = np.asarray(H, dtype=float)
    x = np.clip(H, 0.0, 7.0)
    return np.where((H > 0.0) & (H < 7.0), 11.1 * x**1.31 * np.exp(-2.38 * x + 0.11 * x * x), 0.0)


def shear_stress_factor_unit(H) -> np.ndarray:
    """Phi_fs(H), gamma = 1: 11.1 H^2.31 exp(-2.38 H + 0.11 H^2) for H < 7, 0 above (fitted
    for 0.5 < H < 7; below 0.5 continued by the same expression, -> 0 at H = 0)."""
    H = np.asarray(H, dtype=float)
    return H * shear_stress_factor_over_gap(H)


def shear_flow_factor_unit(H) -> np.ndarray:
    """Phi_s(H), gamma = 1: 1.899 H^0.98 exp(-0.92 H + 0.05 H^2) for H <= 5, 1.126 exp(-0.25 H)
    above (fitted for H > 0.5; continued to 0 at H = 0 by the same expression)."""
    def low(x):
        x = np.maximum(x, 0.0)
        return 1.899 * x**0.98 * np.exp(-0.92 * x + 0.05 * x * x)

    return _branches(H, low, lambda x: 1.126 * np.exp(-0.25 * x), 5.0)


def shear_flow_factor_slope(H) -> np.ndarray:
    """dPhi_s/dH of ``shear_flow_factor_unit`` (0 for H <= 0)."""
    H = np.asarray(H, dtype=float)
    phi = shear_flow_factor_unit(H)
    low = phi * (0.98 / np.maximum(H, 1e-300) - 0.92 + 0.1 * H)
    return np.where(H <= 0.0, 0.0, np.where(H <= 5.0, low, -0.25 * phi))


def couette_gap(h, sigma, split):
    """(h_T + sigma phi_s, its slope in h): the gap whose Couette flux (U/2) x it carries the
    lubricant between a block with the share ``split`` of sigma^2 and the cylinder, with
    phi_s = (2 split - 1) Phi_s(h/sigma) (Patir & Cheng 1979, gamma = 1)."""
    H = np.asarray(h, dtype=float) / sigma
    weight = 2.0 * split - 1.0
    gap = expected_gap(h, sigma) + sigma * weight * shear_flow_factor_unit(H)
    return gap, expected_gap_slope(h, sigma) + weight * shear_flow_factor_slope(H)
