"""A grease in the one-Newton solver (numerics/yield_stress_reynolds.py,
model/monolithic_newton.py; docs/physics.md section 21): the Jacobian of the assembled
residual against its finite differences, the assembled outflow against the slot law, the
Newtonian limit, Newton's convergence, and the solvers that refuse a grease."""

import re
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import brentq

import lubecontact as lc
from lubecontact.model.coupling import coupled_solve
from lubecontact.model.model import Model, SolveError
from lubecontact.model.monolithic_newton import Iterate, linearise, monolithic_solve, newton_direction
from lubecontact.model.prepare import prepare
from lubecontact.numerics.reynolds import boundary_flux, reynolds_system
from lubecontact.numerics.yield_stress_reynolds import reduction_factor, yield_stress_outflow
from lubecontact.physics.yield_stress_flow import YieldStressLaw, slot_flux
from lubecontact.scene import SceneError

TABLE1 = "config/scenes/table1.yaml"
SMOOTH_LINE = {"effects.asperity_contact": False, "effects.elastic_deformation": False, "mesh.ny": 1, "mesh.nx": 101,
               "operating.speed": 1.0}
BINGHAM = {"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0}


def model_of(overrides) -> Model:
    prepared = prepare(lc.load_scene(TABLE1, overrides))
    return Model.assemble(prepared.scene, contact=prepared.contact)


def off_solution(model) -> Iterate:
    """A point near the solution but off it (every outflow and scale term at work)."""
    state, diagnostics = monolithic_solve(model)
    assert diagnostics.converged
    wave = 1.0 + 0.2 * np.sin(np.linspace(0.0, 7.0, state.fluid_pressure.size)).reshape(state.fluid_pressure.shape)
    return Iterate(state.fluid_pressure * wave, state.delta + 0.5 * np.min(state.film) * (wave - 1.0), state.z)


@pytest.mark.parametrize("overrides", [
    {**SMOOTH_LINE, **BINGHAM},
    {**SMOOTH_LINE, "lubricant.rheology": "herschel_bulkley", "lubricant.yield_stress": 300.0,
     "lubricant.flow_index": 0.9, "lubricant.viscosity": 0.3},
    {**BINGHAM, "mesh.nx": 13, "mesh.ny": 9, "effects.elastic_deformation": False},  # rough, 2-D
], ids=["smooth-line-bingham", "smooth-line-hb", "rough-2d-bingham"])
def test_residual_jacobian_against_finite_differences(overrides):
    model = model_of(overrides)
    it = off_solution(model)
    lin = linearise(model, it)
    smoothing = 1e-2 * lin.pressure_scale  # Fischer-Burmeister smoothed: differentiable everywhere
    lin = linearise(model, it, smoothing)
    unknown = lin.unknown
    index = np.flatnonzero(unknown.ravel())

    def residual(pressure=None, delta=None):
        trial = Iterate(it.pressure if pressure is None else pressure, it.delta if delta is None else delta, it.z)
        return linearise(model, trial, smoothing).r_p

    # small, as the law's second derivative jumps at the yield limit; not smaller: round-off where
    # a cavitated cell's w / A_ii is large
    step_p = 1e-8 * lin.pressure_scale
    fd_pp = np.zeros((index.size, index.size))
    for column, node in enumerate(index):
        plus, minus = it.pressure.copy(), it.pressure.copy()
        plus.ravel()[node] += step_p
        minus.ravel()[node] -= step_p
        fd_pp[:, column] = (residual(pressure=plus) - residual(pressure=minus)) / (2 * step_p)
    step_h = 1e-7 * float(np.min(lin.state.film))
    fd_ph = np.zeros((index.size, unknown.size))
    for node in range(unknown.size):
        plus, minus = it.delta.copy(), it.delta.copy()
        plus.ravel()[node] += step_h
        minus.ravel()[node] -= step_h
        fd_ph[:, node] = (residual(delta=plus) - residual(delta=minus)) / (2 * step_h)
    j_pp, j_ph = lin.j_pp.toarray(), lin.j_ph.toarray()
    # central differences err by O(step^2) times the law's third derivative, large near the
    # yield limit (measured: 1.1e-5 of the largest entry at the inlet node of the HB film,
    # falling 100-fold per 10-fold smaller step); a missing term would be O(1)
    assert np.max(np.abs(j_pp - fd_pp)) <= 5e-5 * np.max(np.abs(fd_pp))
    assert np.max(np.abs(j_ph - fd_ph)) <= 5e-5 * np.max(np.abs(fd_ph))
    assert not np.allclose(j_pp, j_pp.T, rtol=1e-3)  # the grease's Jacobian is not A's symmetric one


def uniform_film_flow():
    """A smooth uniform film of 2 um on the 101-node line (its Couette flux divergence-free)
    under a pressure whose gradients lie on both sides of the yield limit of a 300 Pa Bingham
    law: (mesh, law, film, Newtonian coefficient, pressure, its assembled outflow)."""
    mesh = model_of(SMOOTH_LINE).mesh
    law = YieldStressLaw(consistency=0.1, yield_stress=300.0, flow_index=1.0, creep_viscosity=1e4)
    film = np.full(mesh.shape, 2e-6)
    newtonian = film**3 / (12 * law.consistency)
    pressure = np.zeros(mesh.shape)
    limit = 2 * law.yield_stress / film[0, 0]  # the gradient at the yield limit, Pa/m
    amplitude = 100.0 * limit * mesh.dx  # steepest drop ~ amplitude * 3/nx: gradients on both sides of the limit
    pressure[0, 1:-1] = amplitude * np.sin(np.linspace(0.0, 3.0, mesh.nx - 2)) ** 2
    system = reynolds_system(mesh, film, newtonian, 1.0)
    flow = yield_stress_outflow(mesh, system, pressure, newtonian, film, np.ones(mesh.shape), 1.0, law,
                                coefficient_slope=3 * newtonian / film)
    return mesh, law, film, newtonian, pressure, flow


def test_assembled_outflow_is_the_slot_law_on_a_uniform_film():
    """A smooth uniform film (its Couette flux divergence-free): the outflow of a cell is the
    law's flux through its two faces, q(G) dy with G the nodal pressure difference over dx,
    and the scale its secant transmissibilities."""
    mesh, law, film, _, pressure, flow = uniform_film_flow()
    limit = 2 * law.yield_stress / film[0, 0]
    gradient = np.diff(pressure[0]) / mesh.dx
    q = slot_flux(gradient, film[0, 0], law)[0] * mesh.dy  # flux of each face, +x
    assert np.min(np.abs(gradient)) < limit < np.max(np.abs(gradient))
    np.testing.assert_allclose(flow.outflow, q[1:] - q[:-1], rtol=1e-9, atol=1e-12 * np.abs(q).max())
    moving = gradient != 0.0  # at rest the plug creeps: k = h^3/(12 mu_c)
    k = np.where(moving, -q / mesh.dy / np.where(moving, gradient, 1.0), film[0, 0] ** 3 / (12 * law.creep_viscosity))
    secant = k * mesh.dy / mesh.dx
    assert not moving.all()
    np.testing.assert_allclose(flow.scale, secant[1:] + secant[:-1], rtol=1e-9)


def oblique_flow():
    """A smooth uniform 2-D film of 2 um under a pressure quadratic along 45 degrees whose
    gradients' magnitudes lie above the yield limit of a 300 Pa Bingham law and their
    components across the faces below it: (mesh, law, film, Newtonian coefficient, pressure,
    its assembled outflow, dP/dxi as a function of xi)."""
    mesh = model_of({"effects.asperity_contact": False, "effects.elastic_deformation": False, "mesh.nx": 21,
                     "mesh.ny": 17, "operating.speed": 1.0}).mesh
    law = YieldStressLaw(consistency=0.1, yield_stress=300.0, flow_index=1.0, creep_viscosity=1e4)
    h = 2e-6
    film = np.full(mesh.shape, h)
    newtonian = film**3 / (12 * law.consistency)
    limit = 2 * law.yield_stress / h
    x, y = np.meshgrid(mesh.x - mesh.x.mean(), mesh.y, indexing="xy")
    xi, span = (x + y) / np.sqrt(2.0), (np.ptp(mesh.x) + np.ptp(mesh.y)) / np.sqrt(2.0)
    slope = lambda s: limit * (1.2 + 0.3 * s / span)  # dP/dxi: 1.05 to 1.35 times the limit over the domain
    pressure = limit * (1.2 * xi + 0.15 * xi**2 / span)
    system = reynolds_system(mesh, film, newtonian, 0.0)
    flow = yield_stress_outflow(mesh, system, pressure, newtonian, film, np.ones(mesh.shape), 0.0, law,
                                coefficient_slope=3 * newtonian / film)
    assert np.all(slope(xi) > limit) and np.all(slope(xi) / np.sqrt(2.0) < limit)
    return mesh, law, film, newtonian, pressure, flow, slope


def test_a_2d_face_takes_the_whole_gradient_through_the_law():
    """Isotropy: on oblique_flow's film each interior cell's outflow is that of the slot law's
    flux vector q(|grad p|) grad p/|grad p| through its four faces, grad p exact at each
    face's midpoint (the module docstring's differences are exact for a quadratic). A face
    that saw only the gradient across it (until the forty-fourth session) held a plug there."""
    mesh, law, film, _, _, flow, slope = oblique_flow()
    h = film[0, 0]
    x, y = np.meshgrid(mesh.x - mesh.x.mean(), mesh.y, indexing="xy")

    def face_flux(fx, fy):  # the slot law's flux vector (m^2/s) at points (fx, fy), grad p along 45 degrees
        g = slope((fx + fy) / np.sqrt(2.0))
        q = slot_flux(g, h, law)[0]  # along +grad p: negative (down the gradient)
        return q / np.sqrt(2.0), q / np.sqrt(2.0)

    dx, dy = mesh.dx, mesh.dy
    out = (face_flux(x + dx / 2, y)[0] - face_flux(x - dx / 2, y)[0]) * dy \
        + (face_flux(x, y + dy / 2)[1] - face_flux(x, y - dy / 2)[1]) * dx
    interior = np.zeros(mesh.shape, dtype=bool)
    interior[1:-1, 1:-1] = True
    assert np.array_equal(interior, reynolds_system(mesh, film, film**3 / (12 * law.consistency), 0.0).unknown)
    np.testing.assert_allclose(flow.outflow, out[interior], rtol=1e-7, atol=1e-7 * np.abs(out[interior]).max())


def test_bingham_pressure_tends_to_the_newtonian_one_and_newton_converges_fast():
    newtonian = lc.solve(lc.load_scene(TABLE1, SMOOTH_LINE), fields=True)
    p_n = newtonian["fluid_pressure"].values
    changes = []
    for tau in (1.0, 10.0, 100.0, 300.0):
        ds = lc.solve(lc.load_scene(TABLE1, {**SMOOTH_LINE, "lubricant.rheology": "bingham",
                                             "lubricant.yield_stress": tau}), fields=True)
        assert int(ds.converged) == 1 and int(ds.iterations) <= 6
        assert "solved by one Newton" in ds.attrs["notes"]
        changes.append(np.max(np.abs(ds["fluid_pressure"].values - p_n)) / np.max(p_n))
    # relative change ~ tau_y: ten times the yield stress, ten times the change
    assert changes[1] / changes[0] == pytest.approx(10.0, rel=0.05)
    assert changes[2] / changes[1] == pytest.approx(10.0, rel=0.1)
    assert changes[0] < 1e-4


def bingham_slot(viscosity, yield_stress):
    """|q| of a gradient g (Pa/m) in a slot h: Buckingham-Reiner, written here from the formula."""
    def slot(g, h):
        xi = 2.0 * yield_stress / (g * h)
        return np.where(xi < 1.0, h**3 * g / (12.0 * viscosity) * (1.0 - 1.5 * xi + 0.5 * xi**3), 0.0)
    return slot


def herschel_bulkley_slot(consistency, yield_stress, flow_index):
    """|q| of a gradient g in a slot h: 2/(g^2 K^m) [S^(m+2)/(m+2) + tau_y S^(m+1)/(m+1)],
    S = g h/2 - tau_y > 0, m = 1/n (docs/physics.md section 21), written here from the formula."""
    m = 1.0 / flow_index

    def slot(g, h):
        excess = np.maximum(0.5 * g * h - yield_stress, 0.0)
        flux = 2.0 / (g**2 * consistency**m) * (excess ** (m + 2.0) / (m + 2.0)
                                                + yield_stress * excess ** (m + 1.0) / (m + 1.0))
        return np.where(excess > 0.0, flux, 0.0)
    return slot


def shooting_film(slot, yield_stress, radius, length, speed, force, x_in, x_out, films, nodes=4001):
    """The minimum film (m) of a rigid cylinder on a flat carrying ``force`` on a grease whose
    slot flux is ``slot`` (Couette U h/2 plus it, no creep), by shooting: the flux q = U h(x_c)/2
    is constant where the film is pressurised (p = 0 at the inlet x_in and at the film's
    rupture x_c, beyond which the film carries no pressure flux: the Reynolds condition for a
    law whose flux vanishes below 2 tau_y/h), each node's gradient solved from the flux by
    bisection; x_c from p(x_c) = 0, the film from the load, bracketed in ``films``. A solver
    separate from the model's finite volumes, complementarity and Newton."""
    x = np.linspace(x_in, x_out, nodes)

    def gradient(need, h):  # g > 2 tau_y/h carrying the flux ``need``, by bisection in log g
        low = np.log(2.0 * yield_stress / h)
        high = low + 40.0
        for _ in range(80):
            mid = 0.5 * (low + high)
            above = slot(np.exp(mid), h) > need
            low, high = np.where(above, low, mid), np.where(above, mid, high)
        return np.where(need > 0.0, np.exp(0.5 * (low + high)), 0.0)

    def pressure(film, rupture):
        h = film + radius - np.sqrt(radius**2 - x**2)
        surplus = speed * (film + radius - np.sqrt(radius**2 - rupture**2)) / 2.0 - speed * h / 2.0
        g = np.where(x <= rupture, -np.sign(surplus) * gradient(np.abs(surplus), h), 0.0)
        return np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(x))])

    def load(film):
        rupture = brentq(lambda c: np.interp(c, x, pressure(film, c)), 1e-12, 0.999 * x_out, xtol=1e-14)
        return np.trapezoid(np.where(x <= rupture, pressure(film, rupture), 0.0), x) * length

    return brentq(lambda film: load(film) - force, *films, xtol=1e-4 * films[0])


@pytest.mark.parametrize("nodes", [151, 201])
def test_a_stiff_grease_line_finer_than_its_cold_start_reaches_the_shooting_solution(nodes):
    """A smooth rigid line at tau_y = 1 kPa, 0.2 N, 1 m/s: on 151 and 201 nodes the Newton
    from the cold start ran to a film of 5 mm and no load continuation converged (forty-fourth
    session); the yield-stress continuation reaches it (monolithic_newton.YIELD). Measured:
    10.324 um on 151 nodes, 10.326 um on 201, the shooting solver 10.329 um."""
    overrides = {**SMOOTH_LINE, "mesh.nx": nodes, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3, "operating.force": 0.2,
                 "lubricant.rheology": "bingham", "lubricant.yield_stress": 1000.0}
    scene = lc.load_scene(TABLE1, overrides)
    ds = lc.solve(scene)
    assert int(ds.converged) == 1, ds.attrs["notes"]
    assert "yield-stress continuation" in ds.attrs["notes"]
    truth = shooting_film(bingham_slot(scene.lubricant.viscosity, 1000.0), 1000.0, scene.geometry.radius,
                          scene.geometry.length, 1.0, 0.2, -1e-3, 1e-3, (1e-7, 1e-3))
    assert float(ds["min_film_thickness"]) == pytest.approx(truth, rel=2e-3)


def test_a_shear_thinning_grease_line_a_hundred_times_thinner_than_its_consistency_film():
    """Herschel-Bulkley n = 0.7, K = 0.5 Pa s^n, tau_y = 300 Pa, Table 1's rigid smooth line at
    1 m/s: its film is 18 nm, where Martin's at the consistency is 2.45 um. Started from that
    (until the forty-sixth session), the Newton found no descent on any mesh, even from the right
    film; from the Newtonian stand-in at the grease's flowing viscosity (model/grease_start.py)
    it converges, on 401 nodes over -0.3 ... 0.1 mm (1 um cells against a pressure zone of
    35 um), to within 0.2 % of the shooting film (measured: 17.893 against 17.918 nm)."""
    overrides = {**SMOOTH_LINE, "mesh.nx": 401, "mesh.x_min": -0.3e-3, "mesh.x_max": 0.1e-3,
                 "lubricant.rheology": "herschel_bulkley", "lubricant.yield_stress": 300.0, "lubricant.flow_index": 0.7,
                 "lubricant.viscosity": 0.5}
    scene = lc.load_scene(TABLE1, overrides)
    ds = lc.solve(scene)
    assert int(ds.converged) == 1, ds.attrs["notes"]
    truth = shooting_film(herschel_bulkley_slot(0.5, 300.0, 0.7), 300.0, scene.geometry.radius, scene.geometry.length,
                          1.0, scene.operating.force, -0.3e-3, 0.1e-3, (1e-9, 1e-7))
    assert float(ds["min_film_thickness"]) == pytest.approx(truth, rel=2e-3)


def test_the_boundary_flux_takes_each_face_through_the_law():
    """reynolds.boundary_flux with a grease's reduction factor (the transient's face-flux
    volume balance, series.volume_balance) against the assembled outflow of the same film
    and pressures: the net outflow of the region is the sum of its cells' outflows. With the
    Newtonian face fluxes (until the thirty-ninth session) a grease's balance read up to 119
    on a stop whose steps closed to 2e-4."""
    mesh, law, film, newtonian, pressure, flow = uniform_film_flow()
    solution = SimpleNamespace(pressure=pressure, cavitated=np.zeros(mesh.shape, dtype=bool))
    grease = boundary_flux(mesh, solution, film, newtonian, 1.0,
                           reduction=lambda gradient, content: reduction_factor(gradient, content, law)[0])
    assert grease == pytest.approx(flow.outflow.sum(), rel=1e-9, abs=0.0)
    oil = boundary_flux(mesh, solution, film, newtonian, 1.0)
    assert abs(oil - grease) > 0.1 * abs(grease)


def test_a_2d_boundary_flux_takes_the_whole_gradient_through_the_law():
    """The same balance in 2-D, on oblique_flow's film, whose faces' gradients across them lie
    below the yield limit and whose magnitudes above it: with each face's gradient along it
    (reynolds.boundary_flux) the region's net outflow is its cells' outflows summed; with the
    gradient across the face alone (until the forty-fifth session) the boundary's faces held
    plugs and the balance read 2.4e-5 of it. (The flows are near 1e-13 m^3/s: compared with no
    absolute tolerance, which pytest.approx would otherwise set at 1e-12.)"""
    mesh, law, film, newtonian, pressure, flow, _ = oblique_flow()
    solution = SimpleNamespace(pressure=pressure, cavitated=np.zeros(mesh.shape, dtype=bool))
    grease = boundary_flux(mesh, solution, film, newtonian, 0.0,
                           reduction=lambda gradient, content: reduction_factor(gradient, content, law)[0])
    assert grease == pytest.approx(flow.outflow.sum(), rel=1e-9, abs=0.0)


def test_the_nested_solver_and_a_transient_refuse_a_grease():
    scene = lc.load_scene(TABLE1, {**SMOOTH_LINE, **BINGHAM})
    model = Model.assemble(scene)
    with pytest.raises(SolveError, match="one Newton"):
        coupled_solve(model)
    with pytest.raises(SceneError, match="rheology"):
        lc.transient(lc.load_scene(TABLE1, {**BINGHAM, "motion.kind": "stop"}))


def test_full_newton_steps_converge_quadratically_near_the_solution():
    """Pure Newton steps (no line search) from 2 % off the pressure and 1 % off the position:
    each residual is at most a small multiple of the square of the one before (measured:
    0.021, 5.2e-5, 3.5e-8, 6.3e-15 at tau_y = 300 Pa)."""
    model = model_of({**SMOOTH_LINE, **BINGHAM})
    state, _ = monolithic_solve(model)
    it = Iterate(state.fluid_pressure * 1.02, state.delta, state.z * 1.01)
    norms = []
    for _ in range(4):
        lin = linearise(model, it)
        norms.append(np.sqrt(2 * lin.merit()))
        d_p, _, d_z, _ = newton_direction(model, lin, 1e-3)
        it = Iterate(it.pressure + d_p, it.delta, it.z + d_z)
    assert norms[0] > 1e-2
    for before, after in zip(norms[:-1], norms[1:]):
        assert after <= 20.0 * before**2 or after < 1e-13
    assert norms[-1] < 1e-13


def test_a_grease_whose_own_film_is_no_film_fails_cleanly_and_says_what_its_law_entrains():
    """Herschel-Bulkley n = 0.3, K = 0.5 Pa s^n, 300 Pa on Table 1's rigid line at 1 m/s: its
    flowing viscosity puts Martin's film at about 2e-19 m (h^n = 2.45 U R L K U^(n-1)/F with
    the yield stress's share negligible, docs/physics.md section 21). Until the forty-sixth
    session the film estimate's fixed bracket lost such films and the solve ended in a
    ValueError from brentq; now it fails as a solve, and its notes give that film."""
    overrides = {**SMOOTH_LINE, "mesh.nx": 201, "lubricant.rheology": "herschel_bulkley", "lubricant.yield_stress": 300.0,
                 "lubricant.flow_index": 0.3, "lubricant.viscosity": 0.5}
    scene = lc.load_scene(TABLE1, overrides)
    ds = lc.solve(scene)
    notes = ds.attrs["notes"]
    assert int(ds.converged) == 0 and "NOT CONVERGED" in notes
    power_law = (2.45 * scene.geometry.radius * scene.geometry.length * 0.5 / scene.operating.force) ** (1.0 / 0.3)
    estimate = float(re.search(r"the grease's own rigid film estimate is (\S+) m", notes).group(1))
    assert estimate == pytest.approx(power_law, rel=0.05)
