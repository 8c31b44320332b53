"""Control-volume means of the film content (numerics/control_volume.py), against a brute-force
quadrature of the piecewise-linear film written here, finite differences of the means, and
closed forms: a linear law's cell mean, and a cell's content as its film crosses the kink."""

import numpy as np
import pytest
from scipy.special import ndtr

from lubecontact.numerics.control_volume import ControlVolumeMean, control_volume_mean


def frozen_gaussian_content(h):
    """Patir-Cheng's expected gap (sigma = 1) frozen below h = 0, and its slope."""
    top = np.maximum(h, 0.0)
    value = top * ndtr(top) + np.exp(-0.5 * top * top) / np.sqrt(2.0 * np.pi)
    return value, np.where(h > 0.0, ndtr(top), 0.0)


def brute_force_line(row: np.ndarray) -> np.ndarray:
    """Each node's cell mean of the law over the film interpolated linearly, by a fine
    trapezoidal rule (cells end halfway to the neighbours; the end cells are half cells)."""
    nodes = np.arange(row.size)
    means = []
    for i in nodes:
        s = np.linspace(max(i - 0.5, 0.0), min(i + 0.5, row.size - 1.0), 20001)
        means.append(np.trapezoid(frozen_gaussian_content(np.interp(s, nodes, row))[0], s) / (s[-1] - s[0]))
    return np.array(means)


@pytest.mark.parametrize("shape", [(1, 9), (5, 7)])
def test_cell_means_match_a_fine_quadrature_of_the_linear_film(shape):
    film = np.random.default_rng(1).normal(0.3, 1.0, shape)  # films across the kink at h = 0
    means = control_volume_mean(film, frozen_gaussian_content, 0.0)
    along_x = np.array([brute_force_line(row) for row in film])
    expected = along_x if shape[0] == 1 else 0.5 * (along_x + np.array([brute_force_line(c) for c in film.T]).T)
    np.testing.assert_allclose(means.value, expected, atol=1e-8)


@pytest.mark.parametrize("shape", [(1, 9), (5, 7)])
def test_slopes_are_the_derivatives_and_apply_transpose_matrix_agree(shape):
    rng = np.random.default_rng(2)
    film = rng.normal(0.3, 1.0, shape)
    means = control_volume_mean(film, frozen_gaussian_content, 0.0)
    jacobian = means.matrix().toarray()
    step = 1e-7
    for k in range(film.size):
        moved = film.ravel().copy()
        moved[k] += step
        change = (control_volume_mean(moved.reshape(shape), frozen_gaussian_content, 0.0).value - means.value) / step
        np.testing.assert_allclose(jacobian[:, k], change.ravel(), atol=2e-6)
    v, w = rng.normal(size=shape), rng.normal(size=shape)
    np.testing.assert_allclose(means.apply(v).ravel(), jacobian @ v.ravel(), atol=1e-14)
    np.testing.assert_allclose(means.transpose(w).ravel(), jacobian.T @ w.ravel(), atol=1e-14)


def test_a_linear_law_gives_the_consistent_mass_and_a_lumped_one_the_nodal_value():
    film = np.array([[3.0, 1.0, 2.0, 6.0]])
    linear = control_volume_mean(film, lambda h: (h, np.ones_like(h)), -100.0)
    # interior: (6 h_i + h_w + h_e) / 8; ends: (3 h_0 + h_1) / 4
    np.testing.assert_allclose(linear.value[0], [(9 + 1) / 4, (6 + 3 + 2) / 8, (12 + 1 + 6) / 8, (18 + 2) / 4])
    lumped = ControlVolumeMean.lumped(film, 2.0 * np.ones_like(film))
    np.testing.assert_array_equal(lumped.apply(np.ones_like(film)), 2.0 * np.ones_like(film))


def test_a_cell_empties_gradually_as_its_film_crosses_the_kink():
    # a line film through the kink with unit slope: the middle cell's content is the mean of the
    # frozen law over [h - 1/2, h + 1/2], continuous with a continuous slope as h crosses 0,
    # where the nodal value's slope jumps from 1/2 to 0
    def middle(h):
        return control_volume_mean(np.array([[h - 1.0, h, h + 1.0]]), frozen_gaussian_content, 0.0)

    for h in (-0.3, 0.0, 0.3):
        s = np.linspace(h - 0.5, h + 0.5, 200001)
        assert middle(h).value[0, 1] == pytest.approx(np.trapezoid(frozen_gaussian_content(s)[0], s), rel=1e-9)
    slopes = [float(middle(h).apply(np.ones((1, 3)))[0, 1]) for h in (-1e-9, 1e-9)]
    assert slopes[0] == pytest.approx(slopes[1], rel=1e-6) and 0.1 < slopes[0] < 0.4
