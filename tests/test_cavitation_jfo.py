"""Mass-conserving (JFO) cavitation against independent truths.

Truths: Martin's rigid cylinder with the Reynolds exit condition (docs/physics.md section 4:
X_e = 0.47513, w' = 4.8950 mu u_m R/h0), which JFO must reproduce for a steady single
convergent-divergent gap (section 16); conservation of the volumetric flux, computed here
from the face formula q = -k_f dp/dx + (U/2) h_T,f theta_up, across a film that ruptures and
re-forms (two contacts in a row), where Swift-Stieber is known to create mass; Couette
transport theta h_T = const through a cavitated diverging gap; a uniform gap; the storage
hook's global balance; the adjoint load sensitivity against finite differences.
"""

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.numerics.cavitation_jfo import solve_jfo
from lubecontact.numerics.mesh import Mesh
from lubecontact.numerics.reynolds import solve_reynolds

pytestmark = pytest.mark.filterwarnings("error")

R, H0, MU, U = 0.01, 1e-6, 0.1, 1.0
B = np.sqrt(2 * R * H0)


def line(gap_of_x, x_in, x_out, nx):
    x = np.linspace(x_in, x_out, nx) * B
    mesh = Mesh(x=x, y=np.zeros(1), length=1.0)
    h = gap_of_x(x)[None, :]
    return mesh, h, h**3 / (12 * MU)


def cylinder(x):
    return H0 + x**2 / (2 * R)


def two_contacts(x):
    return H0 + np.minimum(x**2, (x - 8 * B) ** 2) / (2 * R)


def face_flux(mesh, h, k, p, theta):
    """Volumetric flux per length through every x face, m^2/s (U > 0: theta of the left node)."""
    poiseuille = -0.5 * (k[0, :-1] + k[0, 1:]) * np.diff(p[0]) / mesh.dx
    return poiseuille + 0.5 * U * 0.5 * (h[0, :-1] + h[0, 1:]) * theta[0, :-1]


def load(mesh, p):
    return float(np.sum(p * mesh.nodal_area))


def test_martin_cylinder_jfo_equals_the_reynolds_condition():
    mesh, h, k = line(cylinder, -50.0, 2.0, 5201)
    jfo = solve_jfo(mesh, h, k, U)
    reynolds = solve_reynolds(mesh, h, k, U)
    assert jfo.converged and reynolds.converged
    w = load(mesh, jfo.pressure)
    # the published values (infinite inlet) within 1 %
    assert w * H0 / (MU * 0.5 * U * R) == pytest.approx(4.8950, rel=1e-2)
    assert w == pytest.approx(load(mesh, reynolds.pressure), rel=1e-9)
    np.testing.assert_array_equal(jfo.cavitated, reynolds.cavitated)
    # downstream of rupture the content carries the rupture flux: theta h = h* = 1.22575 h0,
    # and h* = h0 (1 + X_e^2) puts the rupture at X_e = 0.47513
    tail = jfo.cavitated[0]
    theta_h = jfo.content[0, tail] * 0.5 * (h[0, tail] + h[0, np.flatnonzero(tail) + 1])
    np.testing.assert_allclose(theta_h / H0, 1.22575, rtol=1e-2)
    assert np.sqrt(theta_h.mean() / H0 - 1.0) == pytest.approx(0.47513, rel=1e-2)
    X = mesh.x / B  # the node-resolved film end brackets it
    first = np.flatnonzero(tail)[0]
    assert X[first - 1] <= 0.47513 <= X[first]


def test_mass_is_conserved_where_the_film_reforms():
    mesh, h, k = line(two_contacts, -4.0, 12.0, 1601)
    jfo = solve_jfo(mesh, h, k, U)
    assert jfo.converged and jfo.cavitated.any()
    q = face_flux(mesh, h, k, jfo.pressure, jfo.content)
    assert np.ptp(q) <= 1e-10 * q[0]  # the same flux through every face, to round-off
    reynolds = solve_reynolds(mesh, h, k, U)
    q_swift = face_flux(mesh, h, k, reynolds.pressure, np.ones_like(h))
    assert abs(q_swift[-1] - q_swift[0]) > 0.05 * q_swift[0]  # Swift-Stieber creates mass there
    # the second contact is fed only what the first lets through: less load than Swift-Stieber
    assert load(mesh, jfo.pressure) < 0.6 * load(mesh, reynolds.pressure)


def test_couette_transport_through_a_cavitated_diverging_gap():
    mesh, h, k = line(lambda x: H0 * (1.0 + x / B), 0.0, 5.0, 101)
    jfo = solve_jfo(mesh, h, k, U)
    assert jfo.converged and jfo.cavitated[0, 1:-1].all()
    h_face = 0.5 * (h[0, :-1] + h[0, 1:])
    carried = jfo.content[0, :-1] * h_face  # theta h_T through each face
    np.testing.assert_allclose(carried, h_face[0], rtol=1e-12)
    assert not jfo.pressure.any()


def test_reversed_sliding_mirrors_the_solution():
    mesh, h, k = line(two_contacts, -4.0, 12.0, 401)
    forward = solve_jfo(mesh, h, k, U)
    backward = solve_jfo(mesh, h[:, ::-1], k[:, ::-1], -U)
    assert backward.converged
    np.testing.assert_allclose(backward.pressure[:, ::-1], forward.pressure, rtol=0, atol=1e-9 * forward.pressure.max())
    np.testing.assert_allclose(backward.content[:, ::-1], forward.content, rtol=0, atol=1e-9)


def test_uniform_gap_flows_as_couette():
    mesh, h, k = line(lambda x: np.full_like(x, H0), -1.0, 1.0, 41)
    jfo = solve_jfo(mesh, h, k, U)
    assert jfo.converged and not jfo.pressure.any() and np.all(jfo.content == 1.0)
    np.testing.assert_allclose(face_flux(mesh, h, k, jfo.pressure, jfo.content), 0.5 * U * H0, rtol=1e-14)


def test_storage_hook_balances_the_flux():
    # a backward-Euler-like storage term: the net outflow of the domain equals the stored volume
    mesh, h, k = line(two_contacts, -4.0, 12.0, 401)
    dt = 1e-4
    capacity = h * mesh.nodal_area / dt
    history = 0.7 * capacity  # as if the film had been 70 % full
    jfo = solve_jfo(mesh, h, k, U, storage=(capacity, history))
    assert jfo.converged
    q = face_flux(mesh, h, k, jfo.pressure, jfo.content)
    interior = slice(1, -1)
    stored = np.sum(capacity[0, interior] * jfo.content[0, interior] - history[0, interior])
    assert q[0] - q[-1] == pytest.approx(stored, rel=1e-9)
    none = solve_jfo(mesh, h, k, U, storage=(np.zeros_like(h), np.zeros_like(h)))
    np.testing.assert_allclose(none.pressure, solve_jfo(mesh, h, k, U).pressure, rtol=0, atol=1e-9)


def test_adjoint_load_sensitivity_matches_finite_differences():
    mesh, h, k = line(two_contacts, -4.0, 12.0, 401)
    jfo = solve_jfo(mesh, h, k, U)
    slope_k = h**2 / (4 * MU)
    gradient = jfo.load_sensitivity(mesh, np.ones_like(h), slope_k, U)
    step = 1e-6 * H0
    shifted = [solve_jfo(mesh, h + s, (h + s) ** 3 / (12 * MU), U, cavitated_guess=jfo.cavitated) for s in (step, -step)]
    dW = (load(mesh, shifted[0].pressure) - load(mesh, shifted[1].pressure)) / (2 * step)
    assert gradient.sum() == pytest.approx(dW, rel=1e-4)
    # one node at a time, backwards: the forward side flips a degenerate node (p = 0 and
    # theta = 1 at once, midway between the contacts) to the other set
    step = 1e-5 * H0
    for node in (75, 290):  # the inlets of the first and of the re-formed second film
        bump = np.zeros_like(h)
        bump[0, node] = step
        moved = solve_jfo(mesh, h - bump, (h - bump) ** 3 / (12 * MU), U, cavitated_guess=jfo.cavitated)
        np.testing.assert_array_equal(moved.cavitated, jfo.cavitated)
        dW_node = (load(mesh, jfo.pressure) - load(mesh, moved.pressure)) / step
        assert gradient[0, node] == pytest.approx(dW_node, rel=1e-4)


def test_coupled_solve_with_jfo_agrees_with_reynolds_for_one_contact():
    base = {"mesh.nx": 121, "mesh.ny": 1, "operating.speed": 0.3}
    reynolds = lc.solve(lc.load_scene("config/scenes/table1.yaml", base), fields=True)
    jfo = lc.solve(lc.load_scene("config/scenes/table1.yaml", {**base, "effects.cavitation": "jfo"}), fields=True)
    assert jfo["converged"].item() == 1
    for name in ("contact_resistance", "fluid_force", "min_film_thickness"):
        assert jfo[name].item() == pytest.approx(reynolds[name].item(), rel=1e-5)
    theta = jfo["film_content"]
    assert theta.attrs["units"] == "1" and float(theta.min()) < 1.0 and float(theta.max()) == 1.0
    assert "film_content" not in reynolds
    assert jfo["friction_coefficient"].item() == pytest.approx(reynolds["friction_coefficient"].item(), rel=0.05)


def test_scene_accepts_the_old_flags_and_keeps_their_hash():
    table1 = lc.load_scene("config/scenes/table1.yaml")
    assert table1.effects.cavitation == "reynolds"
    assert "cavitation: true" in table1.canonical_yaml()
    assert lc.load_scene({}, {"effects.cavitation": True}).hash == lc.load_scene({}, {"effects.cavitation": "reynolds"}).hash
    assert lc.load_scene({}, {"effects.cavitation": False}).effects.cavitation == "none"
    assert "cavitation: jfo" in lc.load_scene({}, {"effects.cavitation": "jfo"}).canonical_yaml()
    with pytest.raises(lc.SceneError, match="effects.cavitation"):
        lc.load_scene({}, {"effects.cavitation": "elrod"})
