"""Patir & Cheng's (1979) shear stress and shear flow factors, and the friction they give.

Truths: docs/physics.md section 10 #9 (published fits' values and their continuity), the
defining integral of phi_f (h E[1/h_local] over the polynomial height distribution of
Patir & Cheng) by quadrature, and the smooth-surface limit.
"""

import numpy as np
import pytest
from scipy.integrate import quad

from lubecontact.physics.shear_factors import (
    couette_shear_factor,
    couette_stress_factor,
    poiseuille_stress_factor,
    shear_flow_factor_unit,
    shear_stress_factor_unit,
)

pytestmark = pytest.mark.filterwarnings("error")


def test_published_values():  # docs/physics.md section 9
    assert shear_flow_factor_unit(1.0) == pytest.approx(0.79559, abs=1e-5)
    assert couette_stress_factor(1.0) == pytest.approx(1.63659, abs=1e-5)
    assert poiseuille_stress_factor(2.0) == pytest.approx(0.62601, abs=1e-5)
    assert shear_stress_factor_unit(1.0) == pytest.approx(1.14677, abs=1e-5)


def test_branches_meet():
    eps = 1e-9
    assert couette_stress_factor(3.0 - eps) == pytest.approx(couette_stress_factor(3.0 + eps), abs=1e-6)
    assert shear_flow_factor_unit(5.0 - eps) == pytest.approx(shear_flow_factor_unit(5.0 + eps), abs=1e-4)
    assert poiseuille_stress_factor(np.log(1.4) / 0.66 + 1e-9) == pytest.approx(0.0, abs=1e-8)


def _by_quadrature(H, cutoff=0.01):
    """sigma phi_f/h = int f(s)/(H - s) ds over the local gaps H - s > cutoff, with Patir &
    Cheng's height density f(s) = (35/96)(1 - (s/3)^2)^3 on |s| < 3 (s in sigma)."""
    density = lambda s: (35.0 / 96.0) * (1.0 - (s / 3.0) ** 2) ** 3
    return quad(lambda s: density(s) / (H - s), -3.0, min(H - cutoff, 3.0), limit=200)[0]


@pytest.mark.parametrize("H", [3.2, 4.0, 6.0, 11.9, 12.1, 20.0, 300.0, 3000.0, 1e6])
def test_couette_factor_is_its_defining_integral_without_contact(H):
    assert couette_shear_factor(H) == pytest.approx(_by_quadrature(H), rel=1e-10)


@pytest.mark.parametrize("H", [-2.0, -1.0, 0.0, 1.0, 2.0, 2.9])
def test_couette_factor_with_contact_cuts_gaps_below_a_hundredth_sigma(H):
    # the closed form keeps only the leading terms in the cut-off (1/300 of the 6-sigma range)
    assert couette_shear_factor(H) == pytest.approx(_by_quadrature(H), abs=2e-3)


def test_couette_factor_finite_nonnegative_and_plain_couette_for_thick_films():
    H = np.linspace(-5.0, 40.0, 9001)
    g = couette_shear_factor(H)
    assert np.all(np.isfinite(g)) and np.all(g >= 0.0)
    assert np.all(g[H <= -3.0] == 0.0)
    assert couette_stress_factor(40.0) == pytest.approx(1.0, abs=2e-3)


def test_viscous_shear_between_rough_surfaces_exceeds_the_mean_gap_estimate():
    # the "1.2-1.8x too low at h/sigma = 0.5-3": mu U phi_f/h against mu U/h_T
    from lubecontact.physics.flow_factors import expected_gap

    H = np.array([0.5, 1.0, 2.0, 3.0])
    ratio = couette_shear_factor(H) / (1.0 / expected_gap(H, 1.0))
    assert np.all(ratio > 1.1) and np.all(ratio < 1.9)


def test_couette_gap_of_unequal_roughness():
    from lubecontact.physics.flow_factors import expected_gap
    from lubecontact.physics.shear_factors import couette_gap

    sigma = 0.5e-6
    h = np.array([-1.0, 0.3, 1.0, 2.0, 4.9, 5.1, 9.0]) * sigma
    equal, _ = couette_gap(h, sigma, 0.5)
    np.testing.assert_array_equal(equal, expected_gap(h, sigma))  # phi_s vanishes for equal roughness
    block, slope = couette_gap(h, sigma, 1.0)  # all roughness on the sliding block: + sigma Phi_s
    assert block[2] / sigma == pytest.approx(1.08332 + 0.79559, abs=2e-5)  # docs/physics.md section 9, #10
    cylinder, _ = couette_gap(h, sigma, 0.0)
    np.testing.assert_allclose(0.5 * (block + cylinder), equal, rtol=1e-14)  # odd in the split
    assert np.all(cylinder > 0.0)
    step = 1e-7 * sigma
    central = (couette_gap(h + step, sigma, 1.0)[0] - couette_gap(h - step, sigma, 1.0)[0]) / (2 * step)
    np.testing.assert_allclose(slope, central, rtol=1e-6)


def test_split_is_a_scene_key_that_leaves_equal_roughness_unchanged():
    import lubecontact as lc

    base = {"operating.speed": 1.0, "mesh.nx": 21, "mesh.ny": 1}
    table1 = lc.load_scene("config/scenes/table1.yaml", base)
    assert "split" not in table1.canonical_yaml()
    equal = table1.replace({"roughness.split": 0.5})
    assert equal.hash == table1.hash
    rough_block = table1.replace({"roughness.split": 1.0})
    assert "split: 1.0" in rough_block.canonical_yaml() and rough_block.hash != table1.hash
    with pytest.raises(lc.SceneError, match="roughness.split"):
        lc.load_scene({}, {"roughness.split": 1.5})
    a, b = lc.solve(table1), lc.solve(rough_block)
    assert b["converged"].item() == 1
    assert b["fluid_force"].item() != pytest.approx(a["fluid_force"].item(), rel=1e-3)
