"""Flow down to percolation (docs/physics.md section 15): the percolating Poiseuille coefficient and
the film on the faces of the finite volumes (percolation.py).

Truths: the law's limits (Patir-Cheng above H = 0.5, continuity there, zero conductance at
the level-set threshold H = 0 up to the leakage, the effective-medium onset slope), finite
differences for every derivative, the nodal discretisation where the film is uniform, and
mass conservation across a sealed band (a 1D flux that must be constant to round-off).
"""

import numpy as np
import pytest
from scipy.stats import norm

import lubecontact as lc
from lubecontact.model.model import Model
from lubecontact.numerics.reynolds import solve_reynolds
from lubecontact.physics.flow_factors import (
    SEALED_LEAKAGE,
    expected_gap,
    expected_gap_slope,
    percolating_coefficient_and_slope,
    poiseuille_coefficient,
)
from lubecontact.physics.percolation import face_film

pytestmark = pytest.mark.filterwarnings("error")

SIGMA = 0.5e-6  # m
MU = 0.1  # Pa s
K_VALID = poiseuille_coefficient(0.5 * SIGMA, SIGMA, MU)


def law(h):
    return percolating_coefficient_and_slope(h, SIGMA, MU)


def test_patir_cheng_above_half_sigma_and_continuous_there():
    H = np.array([0.5, 0.7, 1.0, 3.0, 10.0])
    np.testing.assert_allclose(law(H * SIGMA)[0], poiseuille_coefficient(H * SIGMA, SIGMA, MU), rtol=1e-14)
    below = law(0.5 * SIGMA * (1.0 - 1e-9))[0]
    assert below == pytest.approx(K_VALID, rel=1e-8)


def test_conductance_vanishes_at_the_threshold_up_to_the_leakage():
    k, dk = law(np.array([-3.0, -0.1, 0.0]) * SIGMA)
    np.testing.assert_allclose(k, SEALED_LEAKAGE * K_VALID, rtol=1e-14)
    np.testing.assert_array_equal(dk, 0.0)
    assert SEALED_LEAKAGE <= 1e-3  # a leak, not a floor that carries the flow


def test_onset_is_linear_in_the_open_area_fraction():
    # k / k(0.5) = (Phi(H) - 1/2) / (Phi(1/2) - 1/2), i.e. the open fraction's distance from
    # the Zallen-Scher threshold 1/2, exponent 1 (effective medium)
    H = np.array([0.02, 0.1, 0.25, 0.4])
    expected = (norm.cdf(H) - 0.5) / (norm.cdf(0.5) - 0.5)
    np.testing.assert_allclose(law(H * SIGMA)[0] / K_VALID, expected, rtol=1e-12)


@pytest.mark.parametrize("exponent", [1.3, 2.0])
def test_an_exponent_raises_the_open_share_and_keeps_its_limits(exponent):
    # roughness.percolation_exponent t: k / k(0.5) = share^t, the share of the test above;
    # still k(0.5) at H = 0.5, the leakage at the threshold, and its slope by finite differences
    H = np.array([0.05, 0.1, 0.25, 0.4, 0.5 * (1.0 - 1e-9)])
    share = (norm.cdf(H) - 0.5) / (norm.cdf(0.5) - 0.5)
    k, dk = percolating_coefficient_and_slope(H * SIGMA, SIGMA, MU, exponent=exponent)
    np.testing.assert_allclose(k / K_VALID, share**exponent, rtol=1e-12)
    step = 1e-7 * SIGMA
    fd = (percolating_coefficient_and_slope((H + 1e-7) * SIGMA, SIGMA, MU, exponent=exponent)[0]
          - percolating_coefficient_and_slope((H - 1e-7) * SIGMA, SIGMA, MU, exponent=exponent)[0]) / (2 * step)
    np.testing.assert_allclose(dk[:-1], fd[:-1], rtol=1e-6)
    sealed = percolating_coefficient_and_slope(np.array([-0.2, 0.0]) * SIGMA, SIGMA, MU, exponent=exponent)[0]
    np.testing.assert_allclose(sealed, SEALED_LEAKAGE * K_VALID, rtol=1e-14)


def test_the_exponent_is_a_scene_key_left_out_of_the_hash_at_its_default():
    table1 = lc.load_scene("config/scenes/table1.yaml")
    effective_medium = lc.load_scene("config/scenes/table1.yaml", {"roughness.percolation_exponent": 1.0})
    steeper = lc.load_scene("config/scenes/table1.yaml", {"roughness.percolation_exponent": 1.3})
    assert "percolation_exponent" not in table1.canonical_yaml()
    assert effective_medium.hash == table1.hash and steeper.hash != table1.hash
    with pytest.raises(ValueError, match="percolation_exponent"):
        lc.load_scene("config/scenes/table1.yaml", {"roughness.percolation_exponent": 0.5})


def test_monotone_and_slopes_match_finite_differences():
    h = np.linspace(-1.0, 4.0, 2001) * SIGMA
    k, dk = law(h)
    assert np.all(np.diff(k) >= 0.0)
    inside = np.abs(h / SIGMA - 0.5) > 1e-3  # the kink at H = 0.5 (monotone, not smooth)
    step = 1e-6 * SIGMA
    fd = (law(h + step)[0] - law(h - step)[0]) / (2 * step)
    sealed = k <= SEALED_LEAKAGE * K_VALID * (1 + 1e-9)
    np.testing.assert_allclose(dk[inside & ~sealed], fd[inside & ~sealed], rtol=1e-6)


def test_face_film_slopes_match_finite_differences():
    film = np.array([[-0.3, 0.1, 0.4, 1.2], [0.2, 0.05, 0.9, 2.0]]) * SIGMA

    def gap_law(h):
        return expected_gap(h, SIGMA), expected_gap_slope(h, SIGMA)

    values, slopes = face_film(film, law, gap_law)
    step = 1e-7 * SIGMA
    up, _ = face_film(film + step, law, gap_law)
    down, _ = face_film(film - step, law, gap_law)
    for name in ("coefficient_x", "coefficient_y", "gap_x"):
        fd = (getattr(up, name) - getattr(down, name)) / (2 * step)  # d/dh_f: both nodes moved
        np.testing.assert_allclose(getattr(slopes, name), fd, rtol=1e-6, atol=1e-12 * np.abs(fd).max())
    # the Couette content is frozen at its threshold value on sealed faces
    assert values.gap_x[0, 0] == pytest.approx(SIGMA / np.sqrt(2 * np.pi), rel=1e-14)


def _faces_for(film):
    def gap_law(h):
        return expected_gap(h, SIGMA), expected_gap_slope(h, SIGMA)

    return face_film(film, law, gap_law)[0]


def test_uniform_film_faces_equal_nodal_means():
    s = lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": 21, "mesh.ny": 11})
    model = Model.assemble(s)
    mesh = model.mesh
    film = np.full(mesh.shape, 1.3 * SIGMA) + np.linspace(0, 1e-9, mesh.nx)  # nearly uniform
    h_t, k = expected_gap(film, SIGMA), law(film)[0]
    faces = _faces_for(film)
    nodal = solve_reynolds(mesh, h_t, k, 0.1, cavitation=False)
    on_faces = solve_reynolds(mesh, h_t, k, 0.1, cavitation=False, faces=faces)
    np.testing.assert_allclose(on_faces.pressure, nodal.pressure, rtol=1e-6, atol=1e-9 * np.abs(nodal.pressure).max())


def test_a_sealed_band_passes_only_its_pockets_mass_conserved():
    # line mode: a converging gap whose middle is below the threshold; full Sommerfeld, so
    # the 1D flux q = -T dp + (U/2) h_T,f dy through every x face must be the same
    s = lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": 81, "mesh.ny": 1})
    mesh = Model.assemble(s).mesh
    x = mesh.x / np.ptp(mesh.x)
    film = SIGMA * (3.0 * (x - 0.1) ** 2 - 0.4)[None, :] * np.ones(mesh.shape)
    speed = 0.05
    faces = _faces_for(film)
    sol = solve_reynolds(mesh, expected_gap(film, SIGMA), law(film)[0], speed, cavitation=False, faces=faces)
    p = sol.pressure[0]
    q = -faces.coefficient_x[0] * np.diff(p) / mesh.dx + 0.5 * speed * faces.gap_x[0]
    np.testing.assert_allclose(q, q[0], rtol=1e-9)
    sealed = faces.coefficient_x[0] <= SEALED_LEAKAGE * K_VALID * (1 + 1e-9)
    assert sealed.sum() >= 5
    # what crosses the sealed band is the pockets' content carried along, plus the leak
    pockets = 0.5 * speed * SIGMA / np.sqrt(2 * np.pi)
    assert q[0] == pytest.approx(pockets, rel=0.05)
