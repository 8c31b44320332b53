"""Patir-Cheng flow factor (Eq. 2), expected gap and regularised Poiseuille coefficient.

Truths: docs/physics.md section 10 #8 and #10 (published/derived values), the defining integral
of the expected gap by quadrature, and limits.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.stats import norm

from lubecontact.physics.flow_factors import (
    expected_gap,
    poiseuille_coefficient,
    pressure_flow_factor,
)

pytestmark = pytest.mark.filterwarnings("error")

SIGMA = 0.5e-6  # m
MU = 0.1  # Pa s


def expected_gap_by_quadrature(H):
    """h_T/sigma = E[max(H - z, 0)], z standard normal: integral of (H - z) phi(z) below H,
    written as int_0^inf s phi(s - H) ds so the far tail keeps its relative accuracy."""
    return quad(lambda s: s * norm.pdf(s - H), 0.0, np.inf, epsabs=0.0, epsrel=1e-12)[0]


@pytest.mark.parametrize(
    "H, expected", [(0.5, 0.31979), (1.0, 0.48591), (2.0, 0.70635), (3.0, 0.83226), (5.0, 0.94527)]
)
def test_pressure_flow_factor_table(H, expected):
    assert pressure_flow_factor(H) == pytest.approx(expected, abs=1e-5)


def test_pressure_flow_factor_tends_to_one_monotonically():
    H = np.linspace(0.5, 40.0, 2000)
    phi = pressure_flow_factor(H)
    assert np.all(np.diff(phi) > 0.0) and np.all(phi < 1.0)
    assert 1.0 - pressure_flow_factor(6.0) < 0.035  # "flow factors lose influence" beyond 6
    assert 1.0 - pressure_flow_factor(25.0) < 1e-6


@pytest.mark.parametrize("H, expected", [(0.5, 0.69780), (1.0, 1.08332)])
def test_expected_gap_table(H, expected):
    assert expected_gap(H * SIGMA, SIGMA) / SIGMA == pytest.approx(expected, abs=1e-5)


@pytest.mark.parametrize("H", [-30.0, -12.0, -5.0, -1.0, -0.19, 0.0, 0.3, 1.7, 4.0, 8.0])
def test_expected_gap_equals_its_defining_integral(H):
    truth = expected_gap_by_quadrature(H)
    assert expected_gap(H * SIGMA, SIGMA) / SIGMA == pytest.approx(truth, rel=1e-10, abs=0.0)


def test_expected_gap_tends_to_h_for_thick_films():
    # docs/physics.md section 10 says "h_T -> h for H > 3" at 1e-5: that holds from H ~ 3.9 on; at H = 3
    # the difference is the Gaussian tail moment 3.8e-4 sigma.
    H = np.linspace(4.0, 50.0, 200)
    assert np.max(np.abs(expected_gap(H * SIGMA, SIGMA) / SIGMA - H)) < 1e-5
    assert expected_gap(3.0 * SIGMA, SIGMA) / SIGMA - 3.0 == pytest.approx(3.8215e-4, rel=1e-4)


def test_expected_gap_finite_and_never_negative():
    H = np.concatenate([-np.logspace(4, -3, 300), np.logspace(-3, 4, 300)])
    gap = expected_gap(H * SIGMA, SIGMA)
    assert np.all(np.isfinite(gap)) and np.all(gap >= 0.0)
    assert np.all(np.diff(gap) >= 0.0)  # non-decreasing in h
    assert gap[0] == 0.0 and expected_gap(-8.0 * SIGMA, SIGMA) > 0.0  # -> 0+ then underflows


def test_smooth_surfaces_use_the_gap_itself():
    h = np.array([1e-8, 1e-7, 3e-6])
    for sigma in (None, 0.0):
        np.testing.assert_array_equal(expected_gap(h, sigma), h)
        np.testing.assert_allclose(poiseuille_coefficient(h, sigma, MU), h**3 / (12 * MU), rtol=1e-15)
    with pytest.raises(ValueError, match="positive film"):
        poiseuille_coefficient(np.array([1e-7, -1e-9]), None, MU)


@pytest.mark.parametrize("flow_factors", [True, False])
def test_regularised_coefficient_continuous_positive_monotone(flow_factors):
    H = np.linspace(-10.0, 10.0, 4001)
    k = poiseuille_coefficient(H * SIGMA, SIGMA, MU, flow_factors=flow_factors)
    assert np.all(k > 0.0) and np.all(np.isfinite(k))
    assert np.all(np.diff(k) > 0.0)
    edge = np.array([0.5 - 1e-10, 0.5]) * SIGMA
    left, right = poiseuille_coefficient(edge, SIGMA, MU, flow_factors=flow_factors)
    assert left == pytest.approx(right, rel=1e-8, abs=0.0)


@pytest.mark.parametrize("flow_factors", [True, False])
def test_coefficient_below_half_follows_expected_gap_cubed(flow_factors):
    phi_half = pressure_flow_factor(0.5) if flow_factors else 1.0
    k_half = phi_half * (0.5 * SIGMA) ** 3 / (12 * MU)
    for H in (-3.0, -0.7, 0.0, 0.25):
        ratio = expected_gap_by_quadrature(H) / expected_gap_by_quadrature(0.5)
        k = poiseuille_coefficient(H * SIGMA, SIGMA, MU, flow_factors=flow_factors)
        assert k == pytest.approx(k_half * ratio**3, rel=1e-10, abs=0.0)


def test_coefficient_above_half_is_eq2_times_plain_reynolds():
    H = np.array([0.5, 1.0, 2.0, 3.0, 5.0])
    h = H * SIGMA
    plain = h**3 / (12 * MU)
    np.testing.assert_allclose(poiseuille_coefficient(h, SIGMA, MU, flow_factors=False), plain, rtol=1e-14)
    phi = [0.31979, 0.48591, 0.70635, 0.83226, 0.94527]
    np.testing.assert_allclose(poiseuille_coefficient(h, SIGMA, MU) / plain, phi, atol=1e-5)
    # thick films: the flow-factor coefficient becomes plain Reynolds
    thick = 40 * SIGMA
    assert poiseuille_coefficient(thick, SIGMA, MU) / (thick**3 / (12 * MU)) == pytest.approx(1.0, abs=1e-9)


def test_extreme_interference_stays_finite():
    H = np.array([-1e6, -200.0, -21.0])
    assert np.all(np.isfinite(poiseuille_coefficient(H * SIGMA, SIGMA, MU)))
    assert np.all(poiseuille_coefficient(H * SIGMA, SIGMA, MU) >= 0.0)


@pytest.mark.parametrize("flow_factors", [True, False])
def test_analytic_slopes_match_central_differences(flow_factors):
    from lubecontact.physics.flow_factors import (
        expected_gap_slope,
        poiseuille_coefficient_and_slope,
    )

    H = np.array([-6.0, -1.0, 0.0, 0.3, 0.49, 0.51, 1.0, 3.0, 12.0])
    step = 1e-6 * SIGMA
    k, dk = poiseuille_coefficient_and_slope(H * SIGMA, SIGMA, MU, flow_factors)
    plus = poiseuille_coefficient(H * SIGMA + step, SIGMA, MU, flow_factors)
    minus = poiseuille_coefficient(H * SIGMA - step, SIGMA, MU, flow_factors)
    np.testing.assert_allclose(dk, (plus - minus) / (2 * step), rtol=1e-6)
    gap = (expected_gap(H * SIGMA + step, SIGMA) - expected_gap(H * SIGMA - step, SIGMA)) / (2 * step)
    np.testing.assert_allclose(expected_gap_slope(H * SIGMA, SIGMA), gap, rtol=1e-6)
