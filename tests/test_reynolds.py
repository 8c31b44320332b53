"""Averaged Reynolds equation (Eq. 1) with the Reynolds cavitation condition.

Truths: Martin's rigid cylinder (docs/physics.md section 4, #11) and its exact solution on the
truncated domain by quadrature; half-Sommerfeld (#12); antisymmetry and y-symmetry; the line
limit of a long cylinder; mass conservation; an independent projected-SOR solution of the
same complementarity problem on a small grid; plain Reynolds as the thick-film limit.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from lubecontact.numerics.mesh import Mesh
from lubecontact.numerics.reynolds import boundary_flux, solve_reynolds
from lubecontact.physics.flow_factors import expected_gap, poiseuille_coefficient

pytestmark = pytest.mark.filterwarnings("error")

R, H0, MU, U = 0.01, 1e-6, 0.1, 1.0  # m, m, Pa s, m/s (block speed)
UM = U / 2  # entrainment speed: the cylinder does not rotate
B = np.sqrt(2 * R * H0)  # x = X B
SIGMA = 0.5e-6


def line_problem(x_in, x_out, nx):
    """Rigid smooth cylinder h = h0 + x^2/2R on X in [x_in, x_out], line mode, unit length."""
    x = np.linspace(x_in, x_out, nx) * B
    mesh = Mesh(x=x, y=np.zeros(1), length=1.0)
    h = (H0 + x**2 / (2 * R))[None, :]
    return mesh, h, h**3 / (12 * MU)


def load_per_length(mesh, p):
    return np.sum(p * mesh.nodal_area) / mesh.length


def martin_reference(x_in):
    """Exact Reynolds-condition solution with p(x_in) = 0: exit X_e from
    int_{x_in}^{X_e} (s^2 - X_e^2)/(1+s^2)^3 ds = 0; load w' h0/(mu u_m R) = 24 int P dX."""
    def integrand(s, xe):
        return (s * s - xe * xe) / (1 + s * s) ** 3

    def pressure_integral(xe):
        return quad(integrand, x_in, xe, args=(xe,), epsabs=1e-14, epsrel=1e-12, limit=200)[0]

    xe = brentq(pressure_integral, 0.1, 1.0, xtol=1e-15)
    moment = quad(lambda s: s * integrand(s, xe), x_in, xe, epsabs=1e-14, epsrel=1e-12, limit=200)[0]
    return xe, -24.0 * moment  # integration by parts: int P dX = -int X P' dX


def exit_flux(mesh, h, k, p):
    """Full-film flux per length through the first face (m^2/s): (U/2) h* with h* = h(X_e)."""
    return -0.5 * (k[0, 0] + k[0, 1]) * (p[1] - p[0]) / mesh.dx + 0.5 * U * 0.5 * (h[0, 0] + h[0, 1])


def test_martin_rigid_cylinder_published_values():
    mesh, h, k = line_problem(-50.0, 2.0, 5201)
    solution = solve_reynolds(mesh, h, k, U)
    assert solution.converged
    p = solution.pressure[0]
    load = load_per_length(mesh, p) * H0 / (MU * UM * R)
    assert load == pytest.approx(4.8950, rel=5e-3)
    assert p.max() / (MU * UM * np.sqrt(R) * H0**-1.5) == pytest.approx(2.1509, rel=5e-3)
    # h* from the mass flux (the full-film flux (U/2) h* enters at the inlet), X_e from h*
    h_star = exit_flux(mesh, h, k, p) / UM / H0
    assert h_star == pytest.approx(1.22575, rel=5e-3)
    assert np.sqrt(h_star - 1.0) == pytest.approx(0.47513, rel=5e-3)
    # the node-resolved film end brackets X_e within one cell; cavitated from there to the outlet
    X = mesh.x / B
    last = np.flatnonzero(p > 0.0)[-1]
    assert X[last] <= 0.47513 <= X[last + 1]
    np.testing.assert_array_equal(solution.cavitated[0], (X > X[last]) & (X < X[-1]))


def test_martin_grid_convergence_order():
    """Second order (central differences; the free boundary does not spoil it here)."""
    xe_ref, load_ref = martin_reference(-8.0)
    errors = []
    for nx in (201, 401, 801, 1601):
        mesh, h, k = line_problem(-8.0, 2.0, nx)
        p = solve_reynolds(mesh, h, k, U).pressure[0]
        errors.append(abs(load_per_length(mesh, p) * H0 / (MU * UM * R) / load_ref - 1.0))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders[1:] > 1.8) & (orders[1:] < 2.2)), orders
    assert errors[-1] < 3e-5
    assert np.sqrt(exit_flux(mesh, h, k, p) / UM / H0 - 1.0) == pytest.approx(xe_ref, rel=1e-4)


def test_full_sommerfeld_antisymmetric_and_half_sommerfeld_load():
    mesh, h, k = line_problem(-50.0, 50.0, 10001)
    solution = solve_reynolds(mesh, h, k, U, cavitation=False)
    assert solution.converged and solution.iterations == 1 and not solution.cavitated.any()
    p = solution.pressure[0]
    half = load_per_length(mesh, np.maximum(p, 0.0))
    assert abs(load_per_length(mesh, p)) < 1e-12 * half
    np.testing.assert_allclose(p, -p[::-1], atol=1e-12 * p.max())
    assert half * H0 / (MU * UM * R) == pytest.approx(4.000, rel=5e-3)


def rough_cylinder_2d(nx=41, ny=31, tilt=0.0, h0=0.2 * SIGMA):
    """Finite rough cylinder, L = 1 mm, flow factors on, gap crossing H = 0.5; ``tilt``
    (m/m) skews it along y."""
    length = 1e-3
    x = np.linspace(-0.6e-3, 0.3e-3, nx)
    y = np.linspace(-length / 2, length / 2, ny)
    mesh = Mesh(x=x, y=y, length=length)
    X, Y = np.meshgrid(x, y)
    h = h0 + X**2 / (2 * R) + tilt * Y
    return mesh, expected_gap(h, SIGMA), poiseuille_coefficient(h, SIGMA, MU)


def test_finite_cylinder_symmetric_in_y():
    mesh, hT, k = rough_cylinder_2d(nx=61, ny=41)
    solution = solve_reynolds(mesh, hT, k, 0.1)
    assert solution.converged
    p = solution.pressure
    np.testing.assert_allclose(p, p[::-1], rtol=0.0, atol=1e-12 * p.max())
    np.testing.assert_array_equal(solution.cavitated, solution.cavitated[::-1])
    assert p.max() > 0.0 and solution.cavitated.any()


def test_long_cylinder_mid_length_approaches_line_contact():
    x_in, x_out, nx = -8.0, 2.0, 101
    line_mesh, h, k = line_problem(x_in, x_out, nx)
    p_line = solve_reynolds(line_mesh, h, k, U).pressure[0]
    for length, tolerance in ((3 * B, None), (40 * B, 1e-6)):
        ny = 41
        mesh = Mesh(x=line_mesh.x, y=np.linspace(-length / 2, length / 2, ny), length=length)
        p = solve_reynolds(mesh, np.repeat(h, ny, 0), np.repeat(k, ny, 0), U).pressure
        mid = load_per_length(line_mesh, p[ny // 2][None, :])
        if tolerance is None:  # short: side leakage lowers the mid-length film pressure
            assert mid < 0.9 * load_per_length(line_mesh, p_line[None, :])
        else:
            np.testing.assert_allclose(p[ny // 2], p_line, rtol=0, atol=tolerance * p_line.max())


@pytest.mark.parametrize("case", ["line", "2d"])
def test_mass_conservation(case):
    if case == "line":
        mesh, hT, k = line_problem(-8.0, 2.0, 801)
        speed = U
    else:
        mesh, hT, k = rough_cylinder_2d(tilt=2e-4)
        speed = 0.1
    solution = solve_reynolds(mesh, hT, k, speed)
    inlet = 0.5 * speed * np.sum(hT[:, 0]) * mesh.dy
    assert abs(boundary_flux(mesh, solution, hT, k, speed)) < 1e-11 * inlet
    # perturbing the pressure in the film breaks the balance: the check can fail
    perturbed = solve_reynolds(mesh, hT, k, speed)
    perturbed.pressure[perturbed.pressure > 0] *= 1.01
    assert abs(boundary_flux(mesh, perturbed, hT, k, speed)) > 1e-4 * inlet


def independent_lcp(mesh, hT, k, speed):
    """Same finite volumes assembled node by node, solved by projected SOR to convergence."""
    ny, nx = mesh.shape
    nodes = [(j, i) for j in range(ny) for i in range(1, nx - 1) if mesh.line or 0 < j < ny - 1]
    index = {node: n for n, node in enumerate(nodes)}
    A = np.zeros((len(nodes), len(nodes)))
    b = np.zeros(len(nodes))
    for n, (j, i) in enumerate(nodes):
        neighbours = [((j, i + 1), mesh.dy / mesh.dx), ((j, i - 1), mesh.dy / mesh.dx)]
        if not mesh.line:
            neighbours += [((j + 1, i), mesh.dx / mesh.dy), ((j - 1, i), mesh.dx / mesh.dy)]
        for node, geometry in neighbours:
            t = 0.5 * (k[j, i] + k[node]) * geometry
            A[n, n] += t
            if node in index:
                A[n, index[node]] -= t
        east, west = 0.5 * (hT[j, i] + hT[j, i + 1]), 0.5 * (hT[j, i] + hT[j, i - 1])
        b[n] = -0.5 * speed * (east - west) * mesh.dy
    p = np.zeros(len(nodes))
    for _ in range(100000):
        change = 0.0
        for n in range(len(nodes)):
            new = max(0.0, p[n] + 1.6 * (b[n] - A[n] @ p) / A[n, n])
            change = max(change, abs(new - p[n]))
            p[n] = new
        if change <= 1e-15 * p.max():
            break
    pressure = np.zeros(mesh.shape)
    for n, node in enumerate(nodes):
        pressure[node] = p[n]
    return pressure, A, b, [index[node] for node in nodes]


def small_lcp(case):
    """(mesh, h_T, k, U) of a complementarity problem small enough for projected SOR:
    ``case`` "line" (Martin's cylinder) or "2d" (a tilted rough cylinder)."""
    if case == "line":
        return (*line_problem(-4.0, 2.0, 41), U)
    return (*rough_cylinder_2d(nx=17, ny=11, tilt=5e-4), 0.1)


@pytest.mark.parametrize("case", ["line", "2d"])
def test_active_set_equals_projected_sor(case):
    mesh, hT, k, speed = small_lcp(case)
    solution = solve_reynolds(mesh, hT, k, speed)
    reference, A, b, _ = independent_lcp(mesh, hT, k, speed)
    np.testing.assert_allclose(solution.pressure, reference, rtol=0, atol=1e-8 * reference.max())
    # complementarity with the independently assembled operator
    interior = np.zeros(mesh.shape, bool)
    if mesh.line:
        interior[0, 1:-1] = True
    else:
        interior[1:-1, 1:-1] = True
    p = solution.pressure[interior]
    w = A @ p - b
    scale = np.abs(b).max()
    assert np.all(p >= 0.0) and np.all(w >= -1e-10 * scale)
    assert np.max(np.abs(p * w)) <= 1e-10 * scale * p.max()
    assert solution.converged and solution.residual < 1e-10
    np.testing.assert_array_equal(solution.cavitated[interior], p == 0.0)


def test_warm_start_and_bad_guesses_reach_the_same_solution():
    mesh, h, k = line_problem(-8.0, 2.0, 61)
    cold = solve_reynolds(mesh, h, k, U)
    warm = solve_reynolds(mesh, h, k, U, cavitated_guess=cold.cavitated)
    assert warm.iterations == 1
    np.testing.assert_array_equal(warm.pressure, cold.pressure)
    for guess in (np.zeros(mesh.shape, bool), np.ones(mesh.shape, bool)):
        other = solve_reynolds(mesh, h, k, U, cavitated_guess=guess)
        assert other.converged
        np.testing.assert_allclose(other.pressure, cold.pressure, rtol=0, atol=1e-12 * cold.pressure.max())


def test_step_limit_reported_as_not_converged():
    mesh, h, k = line_problem(-8.0, 2.0, 61)
    capped = solve_reynolds(mesh, h, k, U, cavitated_guess=np.ones(mesh.shape, bool), max_iterations=3)
    assert capped.iterations == 3 and not capped.converged and capped.residual > 1e-5
    assert np.all(capped.pressure[capped.cavitated] == 0.0)


def test_cold_start_needs_few_steps_on_fine_meshes():
    mesh, h, k = line_problem(-8.0, 2.0, 6401)
    assert solve_reynolds(mesh, h, k, U).iterations <= 4
    # a far-off warm start (the free boundary would creep ~5000 nodes) falls back to the cold one
    far = solve_reynolds(mesh, h, k, U, cavitated_guess=np.ones(mesh.shape, bool))
    assert far.converged and far.iterations <= 4 + 4
    mesh, hT, k = rough_cylinder_2d(nx=121, ny=81)
    solution = solve_reynolds(mesh, hT, k, 0.1)
    assert solution.converged and solution.iterations <= 4


def _flipped(free, count, rng):
    """A copy of the pressurised-set mask ``free`` with ``count`` random nodes switched."""
    flipped = free.copy()
    flip = rng.choice(free.size, count, replace=False)
    flipped[flip] = ~flipped[flip]
    return flipped


def test_factors_of_a_nearby_set_solve_exactly_without_a_factorisation():
    """BlockInverse with the factors of another pressurised set (ExtendedFactors): CG reaches the
    direct solution of the new block (scipy spsolve, independent of SuperLU's reuse) for a set
    a few nodes away and a perturbed film, without factorising; a set too far away is
    factorised."""
    from scipy.sparse.linalg import spsolve

    from lubecontact.numerics.linear_algebra import REUSE_MAX_CHANGES, BlockInverse
    from lubecontact.numerics.reynolds import reynolds_system

    mesh, hT, k = rough_cylinder_2d(nx=61, ny=41)
    system = reynolds_system(mesh, hT, k, 0.1)
    index = np.flatnonzero(system.unknown)
    rng = np.random.default_rng(3)
    free = _flipped(np.ones(index.size, bool), 40, rng)
    old = BlockInverse(system.matrix[free][:, free].tocsc(), index[free])
    perturbed = reynolds_system(mesh, hT * 1.01, k * 1.03, 0.1).matrix
    for changes, factorised in ((0, False), (REUSE_MAX_CHANGES, False), (REUSE_MAX_CHANGES + 1, True)):
        new_free = _flipped(free, changes, rng)
        block = perturbed[new_free][:, new_free].tocsc()
        rhs = rng.random(block.shape[0])
        inverse = BlockInverse(block, index[new_free], old)
        x = inverse.solve(rhs)
        np.testing.assert_allclose(x, spsolve(block, rhs), rtol=1e-9)
        assert (inverse.lu is not None) == factorised


def test_capacitance_corrections_invert_the_block_on_a_moved_set_exactly():
    """ExtendedFactors from the factors of A on one set is the exact inverse of A on a set
    with nodes removed and added (the Schur complement identities it is built on), checked
    against scipy spsolve on the new block: CG would stop after one step."""
    from scipy.sparse.linalg import splu, spsolve

    from lubecontact.numerics.linear_algebra import ExtendedFactors
    from lubecontact.numerics.reynolds import reynolds_system

    mesh, hT, k = rough_cylinder_2d(nx=61, ny=41)
    system = reynolds_system(mesh, hT, k, 0.1)
    index = np.flatnonzero(system.unknown)
    rng = np.random.default_rng(5)
    old = _flipped(np.ones(index.size, bool), 30, rng)
    new = _flipped(old, 12, rng)
    assert np.any(old & ~new) and np.any(new & ~old)  # both removed and added nodes
    lu = splu(system.matrix[old][:, old].tocsc())
    block = system.matrix[new][:, new].tocsc()
    inverse = ExtendedFactors(lu, index[old], index[new], block)
    assert inverse.usable and inverse.changes == 12
    rhs = rng.random(block.shape[0])
    np.testing.assert_allclose(inverse.solve(rhs), spsolve(block, rhs), rtol=1e-10)


def test_plain_reynolds_recovered_for_thick_films():
    """flow_factors on or off, rough with H >= 60 everywhere: the smooth solution."""
    mesh, h, k_smooth = line_problem(-8.0, 2.0, 201)
    sigma = H0 / 60
    smooth = solve_reynolds(mesh, h, k_smooth, U).pressure
    for flow_factors in (True, False):
        k = poiseuille_coefficient(h, sigma, MU, flow_factors=flow_factors)
        rough = solve_reynolds(mesh, expected_gap(h, sigma), k, U).pressure
        np.testing.assert_allclose(rough, smooth, rtol=0, atol=1e-9 * smooth.max())


def test_dry_patch_is_held_at_zero_pressure():
    """Deep interference (H < -21): k underflows to 0; nodes whose faces all have k = 0
    carry no film (their rows of the operator vanish) and are held at p = 0."""
    mesh, hT, k = rough_cylinder_2d(nx=41, ny=21, h0=-25e-6)
    solution = solve_reynolds(mesh, hT, k, 0.1)
    assert solution.converged and np.all(np.isfinite(solution.pressure))
    wet = np.pad(k > 0, 1, constant_values=True)  # a node is dry when it and its 4 neighbours have k = 0
    dry = ~(wet[1:-1, 1:-1] | wet[:-2, 1:-1] | wet[2:, 1:-1] | wet[1:-1, :-2] | wet[1:-1, 2:])
    assert dry.sum() > 20
    assert np.all(solution.pressure[dry] == 0.0) and np.all(solution.cavitated[dry])


def test_no_sliding_no_pressure():
    mesh, hT, k = rough_cylinder_2d(nx=21, ny=11)
    solution = solve_reynolds(mesh, hT, k, 0.0)
    assert solution.converged and not solution.pressure.any()


def test_bad_fields_rejected():
    mesh, hT, k = rough_cylinder_2d(nx=21, ny=11)
    with pytest.raises(ValueError, match="shape"):
        solve_reynolds(mesh, hT[:, 1:], k, 0.1)
    k[3, 4] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        solve_reynolds(mesh, hT, k, 0.1)
    k[3, 4] = -1.0
    with pytest.raises(ValueError, match=">= 0"):
        solve_reynolds(mesh, hT, k, 0.1)
