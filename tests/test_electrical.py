"""Holm spots, alleviation and nodes in parallel (paper Eqs. 15-17), docs/physics.md section 8 and
checks #22, #23; log-sum-exp robustness of the resistance in the Gaussian tails."""

import math

import numpy as np
import pytest

import lubecontact
from lubecontact.physics.electrical import (
    MAX_AREA_FRACTION,
    alleviation_factor,
    contact_resistance,
)
from lubecontact.physics.materials import spot_conductance_factor

pytestmark = pytest.mark.filterwarnings("error")

RHO = 1.15e-7  # Table 1 tin, ohm m


def test_holm_one_spot():
    """rho/(2a) = 5.75 mOhm for a = 10 um (check #22), through the scene's spot factor too."""
    a = 10e-6
    factor = spot_conductance_factor(lubecontact.load_scene({}))
    assert 1.0 / (factor * a) == pytest.approx(5.75e-3, rel=1e-14)
    resistance, clamped = contact_resistance([math.log(2 * a / RHO)], [0.0], [1.0], alleviation=False)
    assert resistance == pytest.approx(5.75e-3, rel=1e-14) and clamped == 0


def test_alleviation_factor_values():
    psi, clamped = alleviation_factor(np.array([0.0, 0.25, 0.5, 1.0, 3.0]))
    assert psi[0] == 1.0
    assert psi[1] == pytest.approx(0.35355, abs=5e-6)  # check #23
    assert psi[1] == pytest.approx(0.5**1.5, rel=1e-15)
    assert psi[2] == pytest.approx((1 - math.sqrt(0.5)) ** 1.5, rel=1e-15)
    at_max = (1 - math.sqrt(MAX_AREA_FRACTION)) ** 1.5
    np.testing.assert_allclose(psi[3:], at_max, rtol=1e-15)  # A_r/A_n >= 1 held at 0.99: finite, > 0
    np.testing.assert_array_equal(clamped, [False, False, False, True, True])


def test_parallel_nodes_with_alleviation():
    """R = 1/sum(g dA/Psi) against a plain evaluation of the same sum on moderate numbers."""
    g = np.array([[1e10, 3e9], [2e11, 0.0]])
    area = np.array([[1e-9, 2e-9], [5e-10, 1e-9]])
    af = np.array([[0.1, 0.02], [1.2, 0.0]])
    psi = np.where(af > 0.99, 0.99, af)
    expected = 1.0 / np.sum(g * area / (1 - np.sqrt(psi)) ** 1.5)
    with np.errstate(divide="ignore"):
        log_g = np.log(g)  # log 0 = -inf: a node without contact
    resistance, clamped = contact_resistance(log_g, af, area, alleviation=True)
    assert resistance == pytest.approx(expected, rel=1e-13) and clamped == 1
    resistance, clamped = contact_resistance(log_g, af, area, alleviation=False)
    assert resistance == pytest.approx(1.0 / np.sum(g * area), rel=1e-13) and clamped == 0


def test_equal_nodes_add_in_parallel():
    one, _ = contact_resistance(np.full((1, 1), 20.0), np.full((1, 1), 0.1), np.full((1, 1), 1e-8), True)
    many, _ = contact_resistance(np.full((3, 5), 20.0), np.full((3, 5), 0.1), np.full((3, 5), 1e-8), True)
    assert many == pytest.approx(one / 15, rel=1e-13)


def test_nodes_without_area_are_ignored():
    log_g = np.array([10.0, 700.0])  # the second would dominate, but its nodal area is 0
    resistance, _ = contact_resistance(log_g, [0.0, 0.0], [1e-6, 0.0], alleviation=False)
    assert resistance == pytest.approx(math.exp(-10.0) / 1e-6, rel=1e-13)


def test_tails_finite_then_infinite_never_nan():
    """Shifting every log g by -k multiplies R by e^k exactly while R is representable, also
    where exp(log g) has underflowed to 0.0 (a plain sum would divide by zero); +inf beyond."""
    base = np.array([-700.0, -702.0, -705.0])
    area = np.full(3, 1e100)  # an (unphysically) large area keeps R representable deep in the tail
    r0, _ = contact_resistance(base, np.zeros(3), area, alleviation=False)
    assert r0 == pytest.approx(1.0 / np.sum(np.exp(base) * area), rel=1e-12)  # log R0 = 469.7
    previous = r0
    for shift in np.linspace(0.0, 400.0, 201):
        r, _ = contact_resistance(base - shift, np.zeros(3), area, alleviation=False)
        assert not math.isnan(r) and r >= previous
        previous = r
        if shift < 235:
            assert r == pytest.approx(r0 * math.exp(shift), rel=1e-12) and math.isfinite(r)
        if shift > 245:
            assert r == math.inf
    assert np.exp(base - 230.0).sum() == 0.0  # where R above was still finite and exact
    assert contact_resistance(np.full(3, -np.inf), np.zeros(3), area, alleviation=True)[0] == math.inf
    assert contact_resistance(np.array([np.inf, 0.0]), np.zeros(2), np.ones(2), alleviation=False)[0] == 0.0


def test_nan_and_bad_areas_rejected():
    with pytest.raises(ValueError, match="NaN"):
        contact_resistance(np.array([np.nan]), [0.0], [1.0], alleviation=False)
    with pytest.raises(ValueError, match="NaN"):
        alleviation_factor(np.array([0.1, np.nan]))
    with pytest.raises(ValueError, match="nodal areas"):
        contact_resistance(np.array([1.0]), [0.0], [-1.0], alleviation=False)


def test_resistance_from_rough_contact_monotone_in_separation():
    """End to end with the Table 1 scene: R rises monotonically as the surfaces separate,
    finite while representable, then +inf."""
    from lubecontact.physics.rough_surface import RoughContact

    scene = lubecontact.load_scene({})
    contact = RoughContact.from_scene(scene)
    area = np.full(101, 1e-3 * 1e-3 / 101)  # 1 mm^2 over 101 nodes
    sigma = scene.roughness.sigma
    results = []
    for h in sigma * np.linspace(-1.0, 60.0, 123):
        nodes = np.full(101, h)
        results.append(contact_resistance(contact.log_conductance(nodes), contact.area_fraction(nodes), area, True)[0])
    results = np.array(results)
    assert not np.isnan(results).any()
    finite = np.isfinite(results)
    assert finite[0] and not finite[-1] and np.all(np.diff(finite.astype(int)) <= 0)
    assert np.all(np.diff(results[finite]) > 0)
