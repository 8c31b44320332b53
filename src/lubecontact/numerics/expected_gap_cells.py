"""The half-cell means of Patir-Cheng's expected gap frozen below h = 0 in closed form
(docs/physics.md section 14, "The content a cell holds").

The squeeze term's cell content (numerics/control_volume.py) is, for each half cell, the mean
of the content law over a film linear from the node's H_a = h_a/sigma to the face's H_f,

    m = int_0^1 gamma(H_a + u D) du,   D = H_f - H_a,

with gamma(H) = H Phi(H) + phi(H) (h_T/sigma, the expected gap of docs/physics.md section 3) for H >= 0
and gamma(0) = phi(0) below (the content frozen where the surfaces interpenetrate). Its
antiderivative is known: d/dH [(H^2 + 1) Phi(H) + H phi(H)]/2 = gamma(H). Written so that
no large terms cancel (D may be 1e-6 in a flat film, H 400 in an inlet):

    gamma = P + T,   Gamma = P^2/2 + phi(0) N + S,   P = max(H, 0), N = min(H, 0),
    T = phi(H) - H Phi(-H),   S = [1 - (H^2 + 1) Phi(-H) + H phi(H)]/2   (H >= 0),
    T = phi(0),               S = 1/4                                      (H < 0),

T and S bounded (0 ... phi(0), 1/4 ... 1/2) and continuous at 0. Then, with I0 = int gamma'
and I1 = int u gamma' (the half cell's slopes: d m/d h_a = I0 - I1/2, d m/d h_b = I1/2, h_b
the neighbour, as numerics/control_volume.py):

- both ends at or above 0, |D| >= TAYLOR_BELOW: m = (H_a + H_f)/2 + dS/D,
  I0 = 1 + dT/D, I1 = 1/2 + (T_f - dS/D)/D;
- both ends at or above 0, |D| < TAYLOR_BELOW: the Taylor series at H_a through D^5 (the
  derivatives gamma' = Phi, gamma^(k+2) = (-1)^k He_k(H) phi(H));
- both ends below 0: m = phi(0), I0 = I1 = 0;
- a half cell across the kink (a contour of the film): with r = gamma - phi(0) and
  R = int_0^H r at its positive end (0 at the other), m = phi(0) + dR/D, I0 = dr/D,
  I1 = (r_f - dR/D)/D; no cancellation, as |D| is at least the positive end, where r and R
  take the series at 0 below TAYLOR_BELOW.

Rounding: the differences dS, dT lose eps/|D| and the slopes eps/D^2, 1e-12 at the switch,
where the series' first omitted term, |gamma^(6)| D^5/720, is ~1e-13. Checked against the
quadrature and a fine trapezoidal rule in tests/test_control_volume.py. Measured on the
Table 1 stop at 51 x 51 (bench/EXPERIMENTS.md, twenty-fourth session): the quadrature's 16
law evaluations per node were a fifth of the run's CPU.
"""

from __future__ import annotations

import numpy as np
from scipy.special import ndtr

_PHI_0 = 1.0 / np.sqrt(2.0 * np.pi)
# Below this |D| (in sigma) a half cell takes the Taylor series: see the module's "Rounding".
TAYLOR_BELOW = 1e-2


def _parts(H: np.ndarray):
    """(P, T, S, Phi, phi) of the decomposition above at H (Phi, phi: the Gaussian's cdf and
    density at max(H, 0), for the series)."""
    P = np.maximum(H, 0.0)
    upper = ndtr(-P)
    density = _PHI_0 * np.exp(-0.5 * P * P)
    T = density - P * upper
    S = 0.5 * (1.0 - (P * P + 1.0) * upper + P * density)
    return P, T, S, 1.0 - upper, density


def _above_the_floor(P: np.ndarray, T: np.ndarray, S: np.ndarray):
    """(r, R) at P >= 0: r = gamma(P) - phi(0) and R = int_0^P r, what a half cell across the
    kink holds above the frozen content; the series at 0 below TAYLOR_BELOW, where the closed
    forms P + T - phi(0) and P^2/2 + S - 1/4 - phi(0) P lose eps/P and eps/P^2 relatively."""
    with np.errstate(under="ignore"):
        r_series = P * (0.5 + P * (_PHI_0 / 2 - P * P * _PHI_0 / 24))
        R_series = P * P * (0.25 + P * (_PHI_0 / 6 - P * P * _PHI_0 / 120))
    near = P < TAYLOR_BELOW
    return (np.where(near, r_series, P + T - _PHI_0),
            np.where(near, R_series, 0.5 * P * P + S - 0.25 - _PHI_0 * P))


class ExpectedGapHalfCells:
    """(mean, d mean/d start, d mean/d neighbour) of h_T (sigma gamma above) over each half
    cell, for films in m: the interface of numerics/control_volume.GaussHalfCells."""

    def __init__(self, sigma: float):
        self.sigma = sigma

    def __call__(self, start: np.ndarray, neighbour: np.ndarray):
        sigma = self.sigma
        A = start / sigma
        F = 0.5 * (start + neighbour) / sigma
        D = F - A
        P_a, T_a, S_a, g1, g2 = _parts(A)
        P_f, T_f, S_f, _, _ = _parts(F)
        frozen = (A < 0.0) & (F < 0.0)
        across = (A < 0.0) != (F < 0.0)
        series = np.abs(D) < TAYLOR_BELOW

        with np.errstate(divide="ignore", invalid="ignore"):  # D = 0 only where the series holds
            dS = (S_f - S_a) / D
            closed = (0.5 * (A + F) + dS, 1.0 + (T_f - T_a) / D, 0.5 + (T_f - dS) / D)

        g3 = -A * g2
        g4 = (A * A - 1.0) * g2
        g5 = -(A * A - 3.0) * A * g2
        d = np.where(series, D, 0.0)  # the series' powers only where it holds
        taylor = (P_a + T_a + d * (g1 / 2 + d * (g2 / 6 + d * (g3 / 24 + d * (g4 / 120 + d * g5 / 720)))),
                  g1 + d * (g2 / 2 + d * (g3 / 6 + d * (g4 / 24 + d * g5 / 120))),
                  g1 / 2 + d * (g2 / 3 + d * (g3 / 8 + d * (g4 / 30 + d * g5 / 144))))
        mean, I0, I1 = (np.where(series, t, c) for t, c in zip(taylor, closed))

        mean[frozen], I0[frozen], I1[frozen] = _PHI_0, 0.0, 0.0
        if across.any():
            r_a, R_a = _above_the_floor(P_a[across], T_a[across], S_a[across])
            r_f, R_f = _above_the_floor(P_f[across], T_f[across], S_f[across])
            d = D[across]
            excess = (R_f - R_a) / d
            mean[across] = _PHI_0 + excess
            I0[across] = (r_f - r_a) / d
            I1[across] = (r_f - excess) / d
        return sigma * mean, I0 - 0.5 * I1, 0.5 * I1
