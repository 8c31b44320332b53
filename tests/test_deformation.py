"""Elastic deformation by influence coefficients (docs/physics.md section 7, checks #17-21).

Truths: Love's closed-form values for a square, the plane-strain strip difference, quadrature
of the point-load Green's functions, Hertz line contact (Johnson ch. 4), the mid-length
displacement of a finite Hertzian strip, Boussinesq's far field, the direct O(N^2) sum,
linearity and Betti's reciprocity.
"""

import numpy as np
import pytest
from scipy import integrate

from lubecontact.numerics.mesh import Mesh
from lubecontact.physics.deformation import (
    ElasticDeformation,
    love_rectangle,
    plane_strain_strip,
)

E_STAR = 23.78e9  # Pa, Table 1 tin on tin (Eq. 19)
LOAD_PER_LENGTH = 5000.0  # N/m, 5 N on L = 1 mm
RADIUS = 0.01  # m
LENGTH = 1e-3  # m
HALF_WIDTH = np.sqrt(4 * LOAD_PER_LENGTH * RADIUS / (np.pi * E_STAR))  # Hertz b
PEAK = 2 * LOAD_PER_LENGTH / (np.pi * HALF_WIDTH)  # Hertz p0
# mid-length displacement of a Hertzian strip of length L >> b (docs/physics.md section 6)
STRIP_CENTRE = 2 * LOAD_PER_LENGTH / (np.pi * E_STAR) * (np.log(2 * LENGTH / HALF_WIDTH) + 0.5)


def hertz_pressure(x):
    return PEAK * np.sqrt(np.clip(1.0 - (x / HALF_WIDTH) ** 2, 0.0, None))


def test_hertz_inputs_are_table_1():
    assert HALF_WIDTH == pytest.approx(51.74e-6, rel=2e-4)
    assert PEAK == pytest.approx(61.52e6, rel=2e-4)
    assert STRIP_CENTRE == pytest.approx(0.556e-6, rel=1e-3)


def test_love_square_centre_corner_edges():
    p, s = 3.0e6, 2.0e-4
    centre = p * love_rectangle(0.0, 0.0, s / 2, s / 2, E_STAR)
    corner = p * love_rectangle(s / 2, -s / 2, s / 2, s / 2, E_STAR)
    assert centre == pytest.approx(1.12220 * p * s / E_STAR, rel=1e-5)
    assert corner == pytest.approx(0.56110 * p * s / E_STAR, rel=1e-5)
    # closed form 4 asinh(1)/pi and half of it, to 1e-10
    assert centre == pytest.approx(4 * np.arcsinh(1.0) / np.pi * p * s / E_STAR, rel=1e-10)
    assert corner == pytest.approx(0.5 * centre, rel=1e-10)
    # every corner, edge and the lines through them: finite and positive
    grid = np.array([-1.0, -0.5, 0.0, 0.5, 1.0]) * s
    u = love_rectangle(grid[:, None], grid[None, :], s / 2, s / 2, E_STAR)
    assert np.all(np.isfinite(u)) and np.all(u > 0)
    assert np.allclose(u, u.T, rtol=1e-12) and np.allclose(u, u[::-1, ::-1], rtol=1e-12)


@pytest.mark.parametrize("x0, y0", [(0.7, -0.2), (-0.1, 0.9), (-2.0, -3.0)])
def test_love_rectangle_equals_point_load_quadrature(x0, y0):
    """u = (1/(pi E*)) integral dA / r over a non-square rectangle (a != b catches swapped axes)."""
    a, b = 0.3, 0.5
    expected, _ = integrate.dblquad(
        lambda y, x: 1.0 / np.hypot(x0 - x, y0 - y), -a, a, -b, b, epsabs=1e-13, epsrel=1e-12
    )
    assert love_rectangle(x0, y0, a, b, 1.0) * np.pi == pytest.approx(expected, rel=1e-9)


def test_plane_strain_strip_centre_minus_edge():
    p, a = 5.0e7, 3.0e-5
    u = p * plane_strain_strip(np.array([0.0, a]), 2 * a, E_STAR, 1e-3)
    assert np.all(np.isfinite(u))
    assert u[0] - u[1] == pytest.approx(4 * p * a * np.log(2) / (np.pi * E_STAR), rel=1e-8)
    assert u[0] - u[1] == pytest.approx(0.88254 * p * a / E_STAR, rel=1e-5)


@pytest.mark.parametrize("d", [0.0, 0.7, -2.5])
def test_plane_strain_strip_equals_line_load_quadrature(d):
    """K(d) = -(2/(pi E*)) integral ln(|d - s|/l) ds over the strip (E* = 2/pi), datum l."""
    width, datum = 1.0, 7.0
    expected, _ = integrate.quad(
        lambda s: np.log(abs(d - s) / datum), -width / 2, width / 2, points=[d] if abs(d) < width / 2 else None
    )
    assert plane_strain_strip(d, width, 2 / np.pi, datum) == pytest.approx(-expected, rel=1e-10)


@pytest.mark.parametrize(
    "x, y",
    [
        (np.linspace(-2e-4, 1e-4, 23), np.linspace(-5e-4, 5e-4, 14)),  # 2D, dx != dy, nx != ny
        (np.linspace(-1e-4, 3e-4, 9), np.linspace(-5e-4, 5e-4, 31)),  # 2D, ny > nx
        (np.linspace(-3e-4, 1e-4, 37), np.zeros(1)),  # line mode
    ],
)
def test_dcfft_equals_direct_sum(x, y):
    deformation = ElasticDeformation(Mesh(x=x, y=y, length=1e-3), E_STAR)
    pressure = np.random.default_rng(7).uniform(0.0, 1e8, size=(y.size, x.size))
    fast, slow = deformation(pressure), deformation.direct(pressure)
    assert fast.shape == pressure.shape
    assert np.max(np.abs(fast - slow)) <= 1e-12 * np.max(np.abs(slow))


def test_inside_hertz_line_contact_displacement_is_parabolic():
    """Hertz: the deformed gap inside the contact is flat, so u(0) - u(x) = x^2/(2R) (#17);
    the datum l = L gives the mid-length value of a strip of length L (section 6)."""
    x = np.linspace(-2 * HALF_WIDTH, 2 * HALF_WIDTH, 201)
    u = ElasticDeformation(Mesh(x=x, y=np.zeros(1), length=LENGTH), E_STAR)(hertz_pressure(x)[None, :])[0]
    inside = np.abs(x) <= HALF_WIDTH
    error = (u[100] - u - x**2 / (2 * RADIUS))[inside]
    assert np.max(np.abs(error)) < 0.01 * HALF_WIDTH**2 / (2 * RADIUS)
    assert u[100] == pytest.approx(STRIP_CENTRE, rel=0.01)


def test_finite_hertz_strip_centre_displacement():
    """2D mode, Hertz in x, uniform over the cylinder length in y (#20). The end nodes at
    y = +-L/2 carry half weight, so the loaded strip ends at +-L/2 (total load w' L)."""
    x = np.linspace(-HALF_WIDTH, HALF_WIDTH, 101)
    y = np.linspace(-LENGTH / 2, LENGTH / 2, 21)
    mesh = Mesh(x=x, y=y, length=LENGTH)
    pressure = np.broadcast_to(hertz_pressure(x), mesh.shape)
    assert np.sum(pressure * mesh.nodal_area) == pytest.approx(LOAD_PER_LENGTH * LENGTH, rel=2e-3)
    u = ElasticDeformation(mesh, E_STAR)(pressure)
    assert u[10, 50] == pytest.approx(STRIP_CENTRE, rel=0.01)
    assert u[10, 50] == pytest.approx(0.556e-6, rel=0.01)


def test_corner_node_force_matches_boussinesq_far_field():
    """A force F on a corner node (quarter cell weight) acts as F: far away u = F/(pi E* r)."""
    x, y = np.linspace(0.0, 1e-3, 41), np.linspace(0.0, 2e-3, 61)
    mesh = Mesh(x=x, y=y, length=2e-3)
    pressure = np.zeros(mesh.shape)
    force = 2.0
    pressure[0, 0] = force / mesh.nodal_area[0, 0]
    u = ElasticDeformation(mesh, E_STAR)(pressure)
    r = np.hypot(x[-1], y[-1])
    assert u[-1, -1] == pytest.approx(force / (np.pi * E_STAR * r), rel=1e-4)


@pytest.mark.parametrize("y", [np.linspace(-5e-4, 5e-4, 12), np.zeros(1)])
def test_linear_in_pressure_inverse_in_modulus_and_reciprocal(y):
    x = np.linspace(-2e-4, 1e-4, 17)
    mesh = Mesh(x=x, y=y, length=1e-3)
    rng = np.random.default_rng(3)
    p1, p2 = rng.uniform(0.0, 1e8, size=(2, *mesh.shape))
    deformation = ElasticDeformation(mesh, E_STAR)
    u1, u2 = deformation(p1), deformation(p2)
    scale = np.max(np.abs(u1))
    assert np.allclose(deformation(2.5 * p1 - 0.5 * p2), 2.5 * u1 - 0.5 * u2, rtol=0, atol=1e-12 * scale)
    assert np.allclose(ElasticDeformation(mesh, 3 * E_STAR)(p1), u1 / 3, rtol=0, atol=1e-12 * scale)
    # Betti: u at i due to a force at j equals u at j due to the same force at i
    force = 1.0
    nodes = [(0, 0), (0, 5), (y.size - 1, 16), (y.size // 2, 8)]
    response = {}
    for node in nodes:
        pressure = np.zeros(mesh.shape)
        pressure[node] = force / mesh.nodal_area[node]
        response[node] = deformation(pressure)
    for i in nodes:
        for j in nodes:
            assert response[j][i] == pytest.approx(response[i][j], rel=1e-10)


def test_wrong_pressure_shape_is_refused():
    deformation = ElasticDeformation(Mesh(x=np.linspace(0, 1e-4, 5), y=np.zeros(1), length=1e-3), E_STAR)
    with pytest.raises(ValueError, match="shape"):
        deformation(np.zeros((2, 5)))
