"""The far inlet of a 2-D mesh (numerics/modal_far_inlet.py, docs/physics.md section 17)
against independent truths: each mode without sideways leak against the closed-form
exterior of a line (Martin's film) by adaptive quadrature, the modal flux and load against a direct sparse solve of the
2-D exterior written here, the offset slopes against finite differences of the whole
exterior, and Table 1 on a 2-D mesh without its inlet columns against the long inlet, whose
film has converged (8e-6 when it is lengthened to 0.9 R, bench/EXPERIMENTS.md)."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.integrate import quad
from scipy.sparse.linalg import spsolve

import lubecontact as lc
from lubecontact.numerics.mesh import MAX_DOMAIN_RADII, Mesh, build_mesh
from lubecontact.numerics.modal_far_inlet import ModalFarInlet, graded_grid, mode_responses

TABLE1 = "config/scenes/table1.yaml"
RADIUS, VISCOSITY, SPEED = 0.01, 0.1, 10.0


def small_mesh(ny=9, nx=12, length=1e-3):
    x = np.linspace(-1.2e-3, 3e-4, nx)
    return Mesh(x=x, y=np.linspace(-length / 2, length / 2, ny), length=length, far_inlet=True)


def finite_integral(power, offset, end, moment=False):
    """int_{-0.9 R}^{end} (end - x)^moment h^-power dx, h = c + R - sqrt(R^2 - x^2) (Eq. 4), by
    adaptive quadrature."""
    def integrand(x):
        return (end - x) ** moment * (offset + RADIUS - np.sqrt(RADIUS**2 - x * x)) ** -power

    return quad(integrand, -MAX_DOMAIN_RADII * RADIUS, end, points=[end - 1e-5, end - 1e-4], epsrel=1e-12, limit=500)[0]


@pytest.mark.parametrize("offset", [1e-7, 2e-6, 3e-5])
def test_a_mode_without_sideways_leak_is_the_lines_closed_form_exterior(offset):
    """Without the leak a mode is a line's exterior, whose flux is constant: in closed form
    (as numerics/far_inlet.py's, on the cylinder's gap) with the integrals I_n, K_n taken from
    -0.9 R, where p = 0."""
    end = -1.1e-3
    xi = graded_grid(end + MAX_DOMAIN_RADII * RADIUS, 1e-9, 4000, 1e-5)
    r = mode_responses(offset, np.zeros(1), xi, int(np.searchsorted(xi, 1e-5)), end, RADIUS, VISCOSITY, SPEED)
    i2, i3 = finite_integral(2, offset, end), finite_integral(3, offset, end)
    k2, k3 = finite_integral(2, offset, end, True), finite_integral(3, offset, end, True)
    # flux into the mesh q = U I2/(2 I3) - p_1/(12 mu I3), load p_1 K3/I3 + 6 mu U (K2 - K3 I2/I3)
    np.testing.assert_allclose(r.flux[0], -1.0 / (12.0 * VISCOSITY * i3), rtol=2e-4)
    np.testing.assert_allclose(r.flux[1], SPEED * i2 / (2.0 * i3), rtol=2e-4)
    np.testing.assert_allclose(r.load[0], k3 / i3, rtol=2e-4)
    np.testing.assert_allclose(r.load[1], 6.0 * VISCOSITY * SPEED * (k2 - k3 * i2 / i3), rtol=2e-3)


def direct_exterior(inlet: ModalFarInlet, offset: float, first_column: np.ndarray):
    """(flux into the mesh per row, m^2/s; load upstream of x_1, N) of the 2-D exterior solved
    as one sparse system over (rows, xi) with p = 0 on the end rows and at the far end: the
    same finite volumes, no modes."""
    xi, rows, dy = inlet.xi, inlet.rows, inlet.row_spacing
    x = inlet.end - xi
    mid = 0.5 * (x[:-1] + x[1:])
    film, film_mid = offset + RADIUS - np.sqrt(RADIUS**2 - x**2), offset + RADIUS - np.sqrt(RADIUS**2 - mid**2)
    k, conduct = film**3 / (12 * VISCOSITY), film_mid**3 / (12 * VISCOSITY) / np.diff(xi)
    n = xi.size
    width = np.zeros(n)
    width[1:-1] = 0.5 * (xi[2:] - xi[:-2])
    width[0] = 0.5 * xi[1]
    index = np.arange(rows * n).reshape(rows, n)
    entries, rhs = [], np.zeros(rows * n)

    def add(a, b, value):
        entries.append((a, b, value))

    for j in range(rows):
        for i in range(1, n - 1):  # node 0 is given, node n-1 is 0
            me = index[j, i]
            add(me, me, conduct[i - 1] + conduct[i] + 2 * k[i] * width[i] / dy**2)
            add(me, index[j, i - 1], -conduct[i - 1]) if i > 1 else None
            add(me, index[j, i + 1], -conduct[i]) if i < n - 2 else None
            for other in (j - 1, j + 1):
                if 0 <= other < rows:
                    add(me, index[other, i], -k[i] * width[i] / dy**2)
            rhs[me] = -0.5 * SPEED * (film_mid[i - 1] - film_mid[i])
            if i == 1:
                rhs[me] += conduct[0] * first_column[j]
    a, b, v = map(np.array, zip(*entries))
    matrix = sp.csr_matrix((v, (a, b)), shape=(rows * n, rows * n))
    inner = index[:, 1:-1].ravel()
    solution = np.zeros(rows * n)
    solution[inner] = spsolve(matrix[inner][:, inner].tocsc(), rhs[inner])
    p = solution.reshape(rows, n)
    p[:, 0] = first_column
    leak = np.zeros(rows)  # x_1's own half cell leaks sideways too
    padded = np.concatenate([[0.0], first_column, [0.0]])
    leak = -k[0] * width[0] * (padded[:-2] - 2 * padded[1:-1] + padded[2:]) / dy**2
    flux = 0.5 * SPEED * film_mid[0] - conduct[0] * (p[:, 0] - p[:, 1]) - leak
    load = dy * float(np.sum(0.5 * (p[:, :-1] + p[:, 1:]) * np.diff(xi)))
    return flux, load


def test_the_modal_exterior_is_the_direct_solve_of_the_2d_exterior():
    mesh = small_mesh()
    inlet = ModalFarInlet.on(mesh, RADIUS, VISCOSITY, SPEED)
    rng = np.random.default_rng(7)
    pressure = np.zeros(mesh.shape)
    pressure[1:-1, 1] = rng.uniform(0.0, 2e5, mesh.ny - 2)
    film = np.full(mesh.shape, 3e-6) + mesh.x**2 / (2 * RADIUS)
    c = inlet.offset(film)
    flux, load = direct_exterior(inlet, c, pressure[1:-1, 1])
    exterior = inlet.exterior(film)
    # the exterior's outflow of the first column's cells is -dy times the flux into the mesh
    np.testing.assert_allclose(exterior.block @ pressure[1:-1, 1] - exterior.inflow, -mesh.dy * flux, rtol=1e-9)
    value, weights, _ = inlet.load(pressure, film)
    half_cells = 0.5 * mesh.dx * mesh.dy * pressure[1:-1, 1].sum()
    np.testing.assert_allclose(value, load - half_cells, rtol=1e-9)
    np.testing.assert_allclose(float(np.sum(weights * pressure)) + inlet.load(np.zeros(mesh.shape), film)[0], value,
                               rtol=1e-12)
    np.testing.assert_allclose(exterior.block, exterior.block.T, rtol=1e-10, atol=1e-12 * np.abs(exterior.block).max())


def test_the_offset_slopes_are_the_exteriors_derivatives_in_the_first_faces_film():
    mesh = small_mesh()
    inlet = ModalFarInlet.on(mesh, RADIUS, VISCOSITY, SPEED)
    film = np.full(mesh.shape, 3e-6) + mesh.x**2 / (2 * RADIUS)
    pressure = np.zeros(mesh.shape)
    pressure[1:-1, 1] = np.linspace(1e4, 9e4, mesh.ny - 2)
    exterior = inlet.exterior(film)
    node, step = (3, 1), 1e-10
    moved = film.copy()
    moved[node] += step
    after = inlet.exterior(moved)
    outflow = exterior.block @ pressure[1:-1, 1] - exterior.inflow
    changed = after.block @ pressure[1:-1, 1] - after.inflow
    np.testing.assert_allclose((changed - outflow) / step, exterior.outflow_slope(pressure) * exterior.offset_slope[node],
                               rtol=2e-3)
    slope = inlet.load(pressure, film)[2][node]
    np.testing.assert_allclose((inlet.load(pressure, moved)[0] - inlet.load(pressure, film)[0]) / step, slope, rtol=2e-3)


@pytest.mark.parametrize("method", ["nested", "newton"])
def test_a_2d_mesh_without_its_inlet_columns_carries_the_long_inlets_film(method):
    """Table 1 on 31 x 31 at 10 m/s, where the long inlet is longest: the same film within
    0.02 % and the resistance within 1 % on a third of the nodes."""
    base = {"mesh.nx": 31, "mesh.ny": 31, "operating.speed": SPEED, "solver.method": method, "mesh.far_inlet": False}
    long_inlet = lc.solve(lc.load_scene(TABLE1, base))
    scene = lc.load_scene(TABLE1, {**base, "mesh.far_inlet": True})
    open_mesh = lc.solve(scene)
    assert open_mesh["converged"].item() == 1 and build_mesh(scene).nx == 31
    assert build_mesh(lc.load_scene(TABLE1, {**base, "mesh.far_inlet": "auto"})).far_inlet  # the default here
    assert build_mesh(lc.load_scene(TABLE1, base)).nx > 3 * 31
    for name, tolerance in (("central_film_thickness", 2e-4), ("min_film_thickness", 2e-4),
                            ("contact_resistance", 1e-2), ("friction_coefficient", 1e-2)):
        np.testing.assert_allclose(open_mesh[name].item(), long_inlet[name].item(), rtol=tolerance, err_msg=name)


def test_a_film_that_needs_lubricant_from_beyond_the_exteriors_end_is_flagged():
    """The 2-D exterior stops at 0.9 R with p = 0: a small cylinder with a thick film (R = 1 mm,
    1 Pa s at 10 m/s: X = 10.3, a rigid film 0.977 of the flooded one) needs lubricant from
    beyond it, and the flag ``inlet`` says so, where Table 1 itself (R = 10 mm) does not."""
    small = lc.solve(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 21, "operating.speed": SPEED,
                                            "lubricant.viscosity": 1.0, "geometry.radius": 1e-3,
                                            "mesh.far_inlet": True}))
    assert small["converged"].item() == 1 and "inlet" in small.attrs["validity"]
    assert "beyond 0.9 R" in small.attrs["notes"] and "stops, at p = 0" in small.attrs["notes"]
    table1 = lc.solve(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 21, "operating.speed": SPEED,
                                             "mesh.far_inlet": True}))
    assert "inlet" not in table1.attrs["validity"]
