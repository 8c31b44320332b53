"""The yield-stress flow law of a plane slot (physics/yield_stress_flow.py, docs/physics.md
section 21) against independent truths: the velocity profile integrated numerically from
the constitutive law, its limits, and finite differences."""

import numpy as np
import pytest
from scipy.integrate import quad

from lubecontact.physics.film_estimates import hertz_half_width
from lubecontact.physics.yield_stress_flow import (
    YieldStressLaw,
    bingham_squeeze_stop_film,
    creep_squeeze_rate,
    effective_coefficient,
    slot_flux,
)
from lubecontact.scene.scene import load_scene

H = 2.0e-6  # m
BINGHAM = YieldStressLaw(consistency=0.1, yield_stress=300.0, flow_index=1.0, creep_viscosity=1.0e4)


def quadrature_flux(gradient, h, shear_rate, yield_stress):
    """|q| of the slot by integrating the velocity profile twice: tau(y) = |G| y (momentum
    balance), u(y) = int_y^{h/2} gamma_dot(tau) dy' (no slip at the wall), q = 2 int_0^{h/2} u."""
    g = abs(gradient)
    half = 0.5 * h

    plug = yield_stress / g  # where the law changes branch

    def velocity(y):
        kink = [plug] if y < plug < half else None
        return quad(lambda s: shear_rate(g * s), y, half, limit=200, points=kink, epsabs=0.0, epsrel=1e-12)[0]

    return 2.0 * quad(velocity, 0.0, half, limit=200, points=[plug] if plug < half else None, epsabs=0.0, epsrel=1e-12)[0]


def herschel_bulkley_rate(law):
    """The bi-viscous shear rate of the law at stress tau >= 0 (the constitutive law itself)."""
    def rate(tau):
        model = (max(tau - law.yield_stress, 0.0) / law.consistency) ** (1.0 / law.flow_index)
        return model + min(tau, law.yield_stress) / law.creep_viscosity
    return rate


@pytest.mark.parametrize("law", [
    BINGHAM,
    YieldStressLaw(consistency=2.0, yield_stress=300.0, flow_index=0.5, creep_viscosity=1.0e4),
    YieldStressLaw(consistency=0.05, yield_stress=300.0, flow_index=1.4, creep_viscosity=1.0e4),
])
@pytest.mark.parametrize("xi", [0.05, 0.5, 0.9, 1.5])
def test_flux_matches_the_quadrature_of_the_velocity_profile(law, xi):
    gradient = -2.0 * law.yield_stress / (xi * H)
    q = slot_flux(gradient, H, law)[0]
    truth = quadrature_flux(gradient, H, herschel_bulkley_rate(law), law.yield_stress)
    assert q > 0.0
    assert q == pytest.approx(truth, rel=1e-8, abs=0.0)
    assert slot_flux(-gradient, H, law)[0] == pytest.approx(-q, rel=1e-14, abs=0.0)  # odd in G


def test_bingham_is_buckingham_reiner_as_the_creep_viscosity_grows():
    gradient = -2.0 * BINGHAM.yield_stress / (0.4 * H)
    xi = 0.4
    reiner = -H**3 * gradient / (12 * BINGHAM.consistency) * (1 - 1.5 * xi + 0.5 * xi**3)
    errors = []
    for mu_c in (1e2, 1e4, 1e6):
        law = YieldStressLaw(BINGHAM.consistency, BINGHAM.yield_stress, 1.0, mu_c)
        errors.append(abs(slot_flux(gradient, H, law)[0] / reiner - 1.0))
    assert errors[0] > 10 * errors[1] > 100 * errors[2]  # the creep flux falls as 1/mu_c
    assert errors[2] < 1e-5


def test_newtonian_limit_and_the_plug():
    gradient = -1.0e9
    newtonian = -H**3 * gradient / (12 * BINGHAM.consistency)
    for tau_y, tolerance in ((1e-3, 1e-5), (1e-6, 1e-8)):
        law = YieldStressLaw(BINGHAM.consistency, tau_y, 1.0, 1e4)
        assert slot_flux(gradient, H, law)[0] == pytest.approx(newtonian, rel=tolerance, abs=0.0)
    plug = -0.5 * 2 * BINGHAM.yield_stress / H  # xi = 2: only creep
    assert slot_flux(plug, H, BINGHAM)[0] == pytest.approx(-H**3 * plug / (12 * BINGHAM.creep_viscosity), rel=1e-14, abs=0.0)


def test_herschel_bulkley_with_unit_index_is_bingham():
    law = YieldStressLaw(BINGHAM.consistency, BINGHAM.yield_stress, 1.0 + 1e-12, BINGHAM.creep_viscosity)
    gradients = -np.logspace(7, 10, 9)
    np.testing.assert_allclose(slot_flux(gradients, H, law)[0], slot_flux(gradients, H, BINGHAM)[0], rtol=1e-9)


@pytest.mark.parametrize("flow_index", [1.0, 0.6, 1.3])
def test_derivatives_match_finite_differences(flow_index):
    law = YieldStressLaw(0.1 if flow_index == 1.0 else 1.0, 300.0, flow_index, 1e4)
    gradients = np.array([-3e9, -5e8, -2e8, 0.0, 1e8, 4e8, 2e9])  # plug, near and far from yielding
    gaps = np.full(gradients.shape, H)
    for function in (slot_flux, effective_coefficient):
        value, d_g, d_h = function(gradients, gaps, law)
        step_g, step_h = 1e-6 * np.maximum(np.abs(gradients), 1e6), 1e-6 * H
        fd_g = (function(gradients + step_g, gaps, law)[0] - function(gradients - step_g, gaps, law)[0]) / (2 * step_g)
        fd_h = (function(gradients, gaps + step_h, law)[0] - function(gradients, gaps - step_h, law)[0]) / (2 * step_h)
        np.testing.assert_allclose(d_g, fd_g, rtol=1e-5, atol=1e-9 * np.max(np.abs(fd_g)))
        np.testing.assert_allclose(d_h, fd_h, rtol=1e-5, atol=1e-9 * np.max(np.abs(fd_h)))


def test_the_coefficient_is_the_flux_over_the_gradient_and_creeps_at_rest():
    gradients = np.array([-2e9, -3e8, 1e8, 7e8])
    k = effective_coefficient(gradients, H, BINGHAM)[0]
    np.testing.assert_allclose(k, -slot_flux(gradients, H, BINGHAM)[0] / gradients, rtol=1e-12)
    newtonian = H**3 / (12 * BINGHAM.consistency)
    assert np.all((k > 0) & (k <= newtonian))  # the reduction factor f lies in (0, 1]
    assert effective_coefficient(0.0, H, BINGHAM)[0] == pytest.approx(H**3 / (12 * BINGHAM.creep_viscosity), rel=1e-12, abs=0.0)


def test_a_film_at_its_yield_limit_creeps_under_half_a_percent_in_ten_seconds():
    """docs/physics.md section 21: Table 1's Hertz half-width, the gallery grease (its yield
    stress, the default creep viscosity), films of 1 and 5 um: 0.097 % and 0.48 % over 10 s."""
    scene = load_scene("config/scenes/connector_grease_bingham.yaml")
    law = YieldStressLaw(scene.lubricant.viscosity, scene.lubricant.yield_stress, 1.0,
                         scene.lubricant.creep_viscosity)
    half_width = hertz_half_width(load_scene({}))
    for film, fraction in ((1.0e-6, 1e-3), (5.0e-6, 5e-3)):
        # the creep flux at the yield limit (xi = 1) is the closed form's
        q = slot_flux(-2 * law.yield_stress / film, film, law)[0]
        assert q == pytest.approx(law.yield_stress * film**2 / (6 * law.creep_viscosity), rel=1e-12, abs=0.0)
        rate = creep_squeeze_rate(film, half_width, law)
        assert rate * half_width == pytest.approx(q, rel=1e-12, abs=0.0)
        assert 0.5 * fraction < rate * 10.0 / film < fraction


def test_squeeze_stop_film_against_the_quadrature_of_the_plug_limit_pressure():
    force, length, radius, a, tau_y = 0.05, 1e-3, 0.01, 2e-3, 500.0
    h_stop = bingham_squeeze_stop_film(force, length, radius, a, tau_y)

    def gap(x):
        return h_stop + x**2 / (2 * radius)

    def pressure(x):  # the largest pressure the plug holds, from p(a) = 0
        return quad(lambda s: 2 * tau_y / gap(s), abs(x), a, limit=200)[0]

    load = quad(pressure, -a, a, limit=200, points=[0.0])[0] * length
    assert load == pytest.approx(force, rel=1e-8)
    thicker = bingham_squeeze_stop_film(0.5 * force, length, radius, a, tau_y)
    assert thicker > h_stop  # a lighter load stops on a thicker film
