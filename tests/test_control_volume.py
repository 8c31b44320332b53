"""Control-volume means of the film content (numerics/control_volume.py, and the expected
gap's closed form, numerics/expected_gap_cells.py), against a brute-force quadrature of the
piecewise-linear film written here, scipy's adaptive quadrature of single half cells, finite
differences of the means, and closed forms: a linear law's cell mean, and a cell's content as
its film crosses the kink."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import ndtr

import lubecontact as lc
from lubecontact.model.fluid_film import FLUID_FILM_FLOOR_SIGMAS, frozen_content_law, squeeze_content
from lubecontact.model.model import Model
from lubecontact.model.prepare import prepare
from lubecontact.numerics.control_volume import ControlVolumeMean, GaussHalfCells, control_volume_mean
from lubecontact.numerics.expected_gap_cells import TAYLOR_BELOW, ExpectedGapHalfCells


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


# the frozen expected gap (sigma = 1) by the quadrature and by its closed form
HALF_CELLS = {"quadrature": GaussHalfCells(frozen_gaussian_content, 0.0), "closed form": ExpectedGapHalfCells(1.0)}


@pytest.mark.parametrize("half_cells", HALF_CELLS.values(), ids=HALF_CELLS.keys())
@pytest.mark.parametrize("shape", [(1, 9), (5, 7)])
def test_cell_means_match_a_fine_quadrature_of_the_linear_film(shape, half_cells):
    film = np.random.default_rng(1).normal(0.3, 1.0, shape)  # films across the kink at h = 0
    means = control_volume_mean(film, half_cells)
    along_x = np.array([brute_force_line(row) for row in film])
    expected = along_x if shape[0] == 1 else 0.5 * (along_x + np.array([brute_force_line(c) for c in film.T]).T)
    np.testing.assert_allclose(means.value, expected, atol=1e-8)


@pytest.mark.parametrize("half_cells", HALF_CELLS.values(), ids=HALF_CELLS.keys())
@pytest.mark.parametrize("shape", [(1, 9), (5, 7)])
def test_slopes_are_the_derivatives_and_apply_transpose_matrix_agree(shape, half_cells):
    rng = np.random.default_rng(2)
    film = rng.normal(0.3, 1.0, shape)
    means = control_volume_mean(film, half_cells)
    jacobian = means.matrix().toarray()
    step = 1e-7
    for k in range(film.size):
        moved = film.ravel().copy()
        moved[k] += step
        change = (control_volume_mean(moved.reshape(shape), half_cells).value - means.value) / step
        np.testing.assert_allclose(jacobian[:, k], change.ravel(), atol=2e-6)
    v, w = rng.normal(size=shape), rng.normal(size=shape)
    np.testing.assert_allclose(means.apply(v).ravel(), jacobian @ v.ravel(), atol=1e-14)
    np.testing.assert_allclose(means.transpose(w).ravel(), jacobian.T @ w.ravel(), atol=1e-14)


def brute_force_cells(film: np.ndarray) -> np.ndarray:
    """Each node's mean of the frozen expected gap over its 2-D cell (half cells at the edges)
    of the film interpolated bilinearly between nodes, by a fine 2-D trapezoidal rule."""
    ny, nx = film.shape
    means = np.empty(film.shape)
    for j in range(ny):
        t = np.linspace(max(j - 0.5, 0.0), min(j + 0.5, ny - 1.0), 401)
        for i in range(nx):
            s = np.linspace(max(i - 0.5, 0.0), min(i + 0.5, nx - 1.0), 401)
            rows = np.array([np.interp(s, np.arange(nx), row) for row in film])  # along x on every row
            grid = np.array([np.interp(t, np.arange(ny), column) for column in rows.T]).T  # then along y
            inner = np.trapezoid(frozen_gaussian_content(grid)[0], s, axis=1)
            means[j, i] = np.trapezoid(inner, t) / ((s[-1] - s[0]) * (t[-1] - t[0]))
    return means


@pytest.mark.xfail(strict=True, reason=(
    "known first-order error, found in the twenty-ninth session: a 2-D cell's content is the mean of its "
    "x and y means through the node, so a film that varies along x alone (an uncrowned cylinder's) gets "
    "half the nodal value's error at the kink (the y mean of a flat film is the node's value); taking "
    "the x means alone moved the Table 1 stop on 51 x 51 from 12.24 to 13.12 ms; exact quarter cells (thirtieth "
    "session) to 13.07 ms, not kept: 2.3x the CPU and a hard case failed at a sealing pocket (bench/EXPERIMENTS.md)"))
@pytest.mark.parametrize("half_cells", HALF_CELLS.values(), ids=HALF_CELLS.keys())
def test_a_2d_cell_of_a_film_varying_along_x_alone_holds_its_true_mean(half_cells):
    """Truth: the 2-D cell mean of the bilinear film by brute force; for a film flat along y it
    is each row's line mean, which the same law's line cells get right (the test above)."""
    row = np.random.default_rng(3).normal(0.3, 1.0, 7)  # films across the kink at h = 0
    film = np.tile(row, (5, 1))
    truth = brute_force_cells(film)
    np.testing.assert_allclose(truth, np.tile(brute_force_line(row), (5, 1)), atol=1e-5)  # the truth itself
    np.testing.assert_allclose(control_volume_mean(film, half_cells).value, truth, atol=1e-5)


def test_a_linear_law_gives_the_consistent_mass_and_a_lumped_one_the_nodal_value():
    film = np.array([[3.0, 1.0, 2.0, 6.0]])
    linear = control_volume_mean(film, GaussHalfCells(lambda h: (h, np.ones_like(h)), -100.0))
    # interior: (6 h_i + h_w + h_e) / 8; ends: (3 h_0 + h_1) / 4
    np.testing.assert_allclose(linear.value[0], [(9 + 1) / 4, (6 + 3 + 2) / 8, (12 + 1 + 6) / 8, (18 + 2) / 4])
    lumped = ControlVolumeMean.lumped(film, 2.0 * np.ones_like(film))
    np.testing.assert_array_equal(lumped.apply(np.ones_like(film)), 2.0 * np.ones_like(film))


@pytest.mark.parametrize("half_cells", HALF_CELLS.values(), ids=HALF_CELLS.keys())
def test_a_cell_empties_gradually_as_its_film_crosses_the_kink(half_cells):
    # a line film through the kink with unit slope: the middle cell's content is the mean of the
    # frozen law over [h - 1/2, h + 1/2], continuous with a continuous slope as h crosses 0,
    # where the nodal value's slope jumps from 1/2 to 0
    def middle(h):
        return control_volume_mean(np.array([[h - 1.0, h, h + 1.0]]), half_cells)

    for h in (-0.3, 0.0, 0.3):
        s = np.linspace(h - 0.5, h + 0.5, 200001)
        assert middle(h).value[0, 1] == pytest.approx(np.trapezoid(frozen_gaussian_content(s)[0], s), rel=1e-9)
    slopes = [float(middle(h).apply(np.ones((1, 3)))[0, 1]) for h in (-1e-9, 1e-9)]
    assert slopes[0] == pytest.approx(slopes[1], rel=1e-6) and 0.1 < slopes[0] < 0.4


def adaptive_half_cell(start: float, neighbour: float) -> float:
    """The mean of the frozen expected gap over one half cell by scipy's adaptive quadrature,
    split at the kink."""
    face = 0.5 * (start + neighbour)
    if face == start:
        return float(frozen_gaussian_content(np.array(start))[0])
    kink = -start / (face - start)
    points = [kink] if 0.0 < kink < 1.0 else None
    return quad(lambda u: float(frozen_gaussian_content(np.array(start + u * (face - start)))[0]), 0.0, 1.0,
                points=points, epsabs=1e-14, epsrel=1e-13, limit=200)[0]


# half cells (start, neighbour) in sigma: wide ones in an inlet and across the kink, flat ones
# (the series below TAYLOR_BELOW) above it and below it, and across it by a little
CASES = [(400.0, 380.0), (30.0, 2.0), (3.0, -9.0), (-6.0, 8.0), (0.7, 0.7), (0.7, 0.7 + 1e-7),
         (2.0, 2.0 - 1.9 * TAYLOR_BELOW), (2.0, 2.0 - 2.1 * TAYLOR_BELOW), (-0.01, 0.03), (0.005, -0.002),
         (-2.0, -1.0), (0.0, 5.0), (1e-3, 1e-3 + 1e-12)]


@pytest.mark.parametrize("start, neighbour", CASES)
def test_the_closed_form_matches_adaptive_quadrature_and_its_own_slopes(start, neighbour):
    closed = ExpectedGapHalfCells(1.0)
    mean, d_start, d_neighbour = (float(q[0]) for q in closed(np.array([start]), np.array([neighbour])))
    assert mean == pytest.approx(adaptive_half_cell(start, neighbour), rel=1e-12, abs=1e-14)
    # central differences of adaptive quadrature
    step = 1e-6 * max(abs(start), abs(neighbour), 1e-3)
    fd_start = (adaptive_half_cell(start + step, neighbour) - adaptive_half_cell(start - step, neighbour)) / (2 * step)
    fd_neighbour = (adaptive_half_cell(start, neighbour + step) - adaptive_half_cell(start, neighbour - step)) / (2 * step)
    assert d_start == pytest.approx(fd_start, abs=2e-6)
    assert d_neighbour == pytest.approx(fd_neighbour, abs=2e-6)


def test_the_closed_form_is_continuous_where_it_changes_formula():
    closed = ExpectedGapHalfCells(1.0)
    for start in (0.0, 0.4, 3.0, 12.0):
        for edge in (2 * TAYLOR_BELOW, -2 * TAYLOR_BELOW):  # D = (neighbour - start)/2 = +-TAYLOR_BELOW
            pair = np.array([start, start]), start + edge * np.array([1 - 1e-12, 1 + 1e-12])
            means, d_starts, d_neighbours = closed(*pair)
            for q in (means, d_starts, d_neighbours):
                assert q[0] == pytest.approx(q[1], rel=1e-10, abs=1e-11)
    # the kink: a half cell from just above it to just below, against one entirely above
    below = closed(np.array([1e-12]), np.array([-1e-12]))
    above = closed(np.array([2e-12]), np.array([1e-12]))
    for q_below, q_above in zip(below, above):
        assert float(q_below[0]) == pytest.approx(float(q_above[0]), abs=1e-11)


@pytest.mark.parametrize("start, neighbour", [(1e-9, -3e-9), (-1e-9, 3e-9)])
def test_a_hair_across_the_kink_has_half_the_slope_of_its_part_above(start, neighbour):
    # the film is linear over the half cell and crosses h = 0 halfway to the face; the content's
    # slope is Phi(0) = 1/2 above and 0 below, so d/d start = (1/2) int (1 - u/2) du and
    # d/d neighbour = (1/2) int u/2 du over the part above, and the mean is phi(0)
    mean, d_start, d_neighbour = (float(q[0]) for q in ExpectedGapHalfCells(1.0)(np.array([start]), np.array([neighbour])))
    above = (0.0, 0.5) if start > 0 else (0.5, 1.0)
    assert mean == pytest.approx(1.0 / np.sqrt(2.0 * np.pi), rel=1e-8)
    assert d_start == pytest.approx(0.5 * quad(lambda u: 1.0 - u / 2, *above)[0], rel=1e-6)
    assert d_neighbour == pytest.approx(0.5 * quad(lambda u: u / 2, *above)[0], rel=1e-6)


@pytest.mark.parametrize("split", [0.5, 0.8])
def test_a_rough_contacts_squeeze_content_is_its_frozen_contents_cell_mean(split):
    # Table 1's content law (the expected gap, or with unequal roughness the Couette gap) frozen
    # at the floor, by the quadrature on a mesh fine enough that its error is below 1e-9 sigma:
    # the closed form (split 0.5) must be the same law and floor
    scene = lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": 11, "mesh.ny": 5, "roughness.split": split})
    model = Model.assemble(prepare(scene).scene)
    sigma = model.contact.sigma
    film = sigma * np.random.default_rng(4).normal(0.3, 0.2, (5, 11))
    content = squeeze_content(model, film)
    quadrature = control_volume_mean(film, GaussHalfCells(frozen_content_law(model), FLUID_FILM_FLOOR_SIGMAS * sigma))
    np.testing.assert_allclose(content.value, quadrature.value, rtol=0, atol=1e-9 * sigma)
    for name in ("own", "west", "east", "south", "north"):
        np.testing.assert_allclose(getattr(content, name), getattr(quadrature, name), rtol=0, atol=1e-8)
