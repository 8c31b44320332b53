"""The one-Newton solver (model/monolithic_newton.py, docs/physics.md section 20) and the
pieces it stands on: the Fischer-Burmeister function and the Reynolds residual's film slope. Each against an independent truth: the complementarity
conditions themselves, finite differences of the assembled residual, the nested solver on
the same discrete problem, and the isoviscous-elastic reference table of docs/physics.md
section 5 where the nested solver fails."""

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.model import monolithic_newton as mn
from lubecontact.model.auto_effects import operating_point
from lubecontact.model.fluid_film import fluid_faces, fluid_film, open_film_diagonal
from lubecontact.model.model import Model
from lubecontact.model.prepare import prepare
from lubecontact.numerics.complementarity import fischer_burmeister
from lubecontact.numerics.reynolds import reynolds_system
from lubecontact.numerics.reynolds_jacobian import outflow_film_jacobian
from lubecontact.scene import SceneError
from lubecontact.unsteady import integrator
from lubecontact.unsteady.motion import SpeedHistory

TABLE1 = "config/scenes/table1.yaml"
SIGMA, MU = 0.5e-6, 0.1


def test_fischer_burmeister_vanishes_exactly_on_the_complementarity_set():
    a = np.array([0.0, 2.0, 0.0, 1.0, -1.0, 0.5, 3.0])
    b = np.array([3.0, 0.0, 0.0, 1.0, 0.5, -2.0, -1e-9])
    phi, _, _ = fischer_burmeister(a, b)
    solution = (a >= 0) & (b >= 0) & (a * b == 0)
    assert np.all((np.abs(phi) < 1e-15) == solution)
    # smoothed: zero where a, b > 0 and a b = mu^2
    mu = 0.3
    phi_mu, _, _ = fischer_burmeister(np.array([0.9, mu]), np.array([mu**2 / 0.9, mu]), mu)
    assert np.allclose(phi_mu, 0.0, atol=1e-15)


def test_fischer_burmeister_slopes_against_finite_differences():
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=200), rng.normal(size=200)
    for mu in (0.0, 0.2):
        _, da, db = fischer_burmeister(a, b, mu)
        step = 1e-7
        fd_a = (fischer_burmeister(a + step, b, mu)[0] - fischer_burmeister(a - step, b, mu)[0]) / (2 * step)
        fd_b = (fischer_burmeister(a, b + step, mu)[0] - fischer_burmeister(a, b - step, mu)[0]) / (2 * step)
        np.testing.assert_allclose(da, fd_a, atol=1e-6)
        np.testing.assert_allclose(db, fd_b, atol=1e-6)
        assert np.all((da >= 0) & (da <= 2) & (db >= 0) & (db <= 2) & (da + db > 0))


@pytest.mark.parametrize("rough", [True, False], ids=["faces", "nodal"])
def test_outflow_film_slope_against_finite_differences_of_the_assembled_residual(rough):
    overrides = {"mesh.nx": 21, "mesh.ny": 9, "operating.speed": 0.1}
    if not rough:
        overrides["effects.asperity_contact"] = False
    model = Model.assemble(prepare(lc.load_scene(TABLE1, overrides)).scene)
    rng = np.random.default_rng(7)
    film = model.undeformed_gap + (0.3 * SIGMA if rough else 2e-7) + (0.4 * SIGMA * rng.random(model.mesh.shape))
    pressure = np.zeros(model.mesh.shape)
    pressure[1:-1, 1:-1] = 1e6 * rng.random((model.mesh.ny - 2, model.mesh.nx - 2))

    def outflow_and_diagonal(h):
        h_t, k = fluid_film(model, h)
        faces, _ = fluid_faces(model, h)
        system = reynolds_system(model.mesh, h_t, k, 0.1, faces)
        return system.matrix @ pressure[system.unknown] - system.rhs, system.matrix.diagonal(), system.unknown

    _, _, unknown = outflow_and_diagonal(film)
    faces, face_slopes = fluid_faces(model, film)
    _, _, gap_slope, coefficient_slope = fluid_film(model, film, slopes=True)
    slopes = (face_slopes, None, None) if rough else (None, gap_slope, coefficient_slope)
    d_outflow, d_diagonal = outflow_film_jacobian(model.mesh, pressure, unknown, 0.1, *slopes)
    step = 1e-4 * SIGMA
    for node in rng.choice(film.size, 12, replace=False):
        bump = np.zeros(film.size)
        bump[node] = step
        up = outflow_and_diagonal(film + bump.reshape(film.shape))
        down = outflow_and_diagonal(film - bump.reshape(film.shape))
        for analytic, numeric in ((d_outflow[:, node].toarray().ravel(), (up[0] - down[0]) / (2 * step)),
                                  (d_diagonal[:, node].toarray().ravel(), (up[1] - down[1]) / (2 * step))):
            np.testing.assert_allclose(analytic, numeric, rtol=1e-4, atol=1e-6 * np.abs(numeric).max() + 1e-300)


def newton_and_nested(overrides):
    nested = lc.solve(lc.load_scene(TABLE1, overrides))
    newton = lc.solve(lc.load_scene(TABLE1, {**overrides, "solver.method": "newton"}))
    return nested, newton


@pytest.mark.parametrize("speed", [1e-4, 1e-2, 0.1, 1.0, 10.0])
def test_newton_finds_the_nested_solvers_answer_on_table1(speed):
    """Both solve the same discrete problem to the same tolerance: their answers agree to
    well within it (line contact, 51 nodes, the paper's sweep range)."""
    nested, newton = newton_and_nested({"mesh.nx": 51, "mesh.ny": 1, "operating.speed": speed})
    assert int(nested.converged) == 1 and int(newton.converged) == 1
    # ln R: the resistance of a separating contact is exponential in the film (1e15 ohm at
    # 10 m/s, d ln R/dh ~ h/sigma^2): the 1e-6 force tolerance of each solve allows ~2e-4
    assert np.log(float(newton.contact_resistance)) == pytest.approx(np.log(float(nested.contact_resistance)), abs=5e-4)
    for name in ("friction_coefficient", "min_film_thickness"):
        assert float(newton[name]) == pytest.approx(float(nested[name]), rel=2e-5), name
    # the loads within the force tolerance both meet (1e-6 of the applied 5 N), with room
    assert float(newton.fluid_force) == pytest.approx(float(nested.fluid_force), abs=1e-5 * 5.0)


def test_newton_on_the_2d_table1_contact():
    nested, newton = newton_and_nested({"mesh.nx": 31, "mesh.ny": 31, "operating.speed": 1.0})
    assert int(newton.converged) == 1
    assert float(newton.contact_resistance) == pytest.approx(float(nested.contact_resistance), rel=2e-5)
    assert abs(float(newton.force_residual)) <= 1e-6 * 5.0


@pytest.mark.parametrize("speed", [0.003, 0.001])
def test_soft_elastic_films_where_the_nested_solver_fails(speed):
    """Issue 27's soft elastic film: Table 1 without asperity contact as a line contact at
    g_E = 19 and 32 (Moes M ~ 13 and 23). The nested solver stops there (a film closing at a
    node, or 200 iterations); one Newton converges, and its film agrees with the
    isoviscous-elastic reference table of docs/physics.md section 5 (a separate solver) within 3 %."""
    overrides = {"effects.asperity_contact": False, "operating.speed": speed, "mesh.ny": 1, "mesh.nx": 401,
                 "mesh.x_min": -2.5e-4, "mesh.x_max": 1e-4, "solver.method": "newton"}
    scene = lc.load_scene(TABLE1, overrides)
    ds = lc.solve(scene)
    assert int(ds.converged) == 1 and abs(float(ds.force_residual)) <= 1e-6 * 5.0
    assert float(ds.min_film_thickness) == pytest.approx(operating_point(scene).elastic_film, rel=0.03)


def test_a_newton_that_cannot_converge_says_where_and_keeps_its_state():
    ds = lc.solve(lc.load_scene(TABLE1, {"mesh.nx": 51, "mesh.ny": 1, "operating.speed": 1.0, "solver.method": "newton",
                                         "solver.max_iterations": 1}))
    assert int(ds.converged) == 0
    assert "NOT CONVERGED" in ds.attrs["notes"] and "Newton" in ds.attrs["notes"]
    assert np.isfinite(float(ds.contact_resistance))
    # each continuation it tried is named, with how far it got: here no cold start of either
    assert "; load continuation: no cold start converged at 0.5 to 0.015625 of the force" in ds.attrs["notes"]
    assert "; speed continuation: no cold start converged at 0.5 to 0.015625 of the speed" in ds.attrs["notes"]


def test_the_open_films_diagonal_is_patir_and_chengs_conductance_at_half_sigma():
    """fluid_film.open_film_diagonal against Eq. (2) by hand: k = phi_x(0.5) (0.5 sigma)^3 /
    (12 mu), phi_x = 1 - 0.9 exp(-0.56 H), on the four faces of an interior cell."""
    model = Model.assemble(prepare(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 11})).scene)
    mesh = model.mesh
    k = (1.0 - 0.9 * np.exp(-0.56 * 0.5)) * (0.5 * SIGMA) ** 3 / (12.0 * MU)
    expected = k * (2.0 * mesh.dy / mesh.dx + 2.0 * mesh.dx / mesh.dy)
    np.testing.assert_allclose(open_film_diagonal(model)[1:-1, 1:-1], expected, rtol=1e-12)


def test_a_newton_stalled_by_sealed_cells_converges_on_the_open_films_scale_to_the_nested_answer(monkeypatch):
    """Table 1 on 51 x 51 at 1.6 mm/s with the Fischer-Burmeister function: the Newton on the
    cells' own outflow scales stalls (cells sealed below the percolation threshold leak at 1e-3
    of the open conductance, and their outflow over their own diagonal swings by the pressure
    of the whole contact); on the open film's scale it converges, and the polish on the cells'
    own scales lands on the nested solver's answer (a separate solver of the same discrete
    problem)."""
    calls = []
    iteration = mn.newton_iteration

    def recorded(model, start, tolerance, max_iterations, open_film_floor=False, universal=False):
        result = iteration(model, start, tolerance, max_iterations, open_film_floor, universal)
        calls.append((open_film_floor, not result[3]))
        return result

    monkeypatch.setattr(mn, "newton_iteration", recorded)
    monkeypatch.setattr(mn, "universal_applies", lambda model: False)
    nested, newton = newton_and_nested({"operating.speed": 0.001585})
    assert int(nested.converged) == 1 and int(newton.converged) == 1
    assert (False, False) in calls and (True, True) in calls  # stalled, then converged on the open film's scale
    assert "continuation" not in newton.attrs["notes"]
    assert float(newton.contact_resistance) == pytest.approx(float(nested.contact_resistance), rel=1e-5)
    assert float(newton.friction_coefficient) == pytest.approx(float(nested.friction_coefficient), rel=1e-5)
    assert float(newton.fluid_force) == pytest.approx(float(nested.fluid_force), abs=1e-6 * 5.0)


def test_the_solver_method_is_checked():
    with pytest.raises(SceneError, match="method"):
        lc.load_scene(TABLE1, {"solver.method": "fast"})
    assert lc.load_scene(TABLE1, {"solver.method": "nested"}).hash == lc.load_scene(TABLE1).hash


def test_a_failed_nested_solve_is_finished_by_one_newton_and_says_so():
    """The soft elastic film at g_E = 32 with the default method: the nested solver's force
    balance fails (h_min ~ 1e-22 m), one Newton from its last state cannot recover from
    there, one from a cold start converges (a line mesh: the dense step), and the notes say
    which; the film is the reference table's (docs/physics.md section 5) within 3 %."""
    scene = lc.load_scene(TABLE1, {"effects.asperity_contact": False, "operating.speed": 0.001, "mesh.ny": 1,
                                   "mesh.nx": 401, "mesh.x_min": -2.5e-4, "mesh.x_max": 1e-4})
    ds = lc.solve(scene)
    assert int(ds.converged) == 1 and abs(float(ds.force_residual)) <= 1e-6 * 5.0
    assert "the nested solver stopped" in ds.attrs["notes"] and "one Newton from a cold start" in ds.attrs["notes"]
    assert float(ds.min_film_thickness) == pytest.approx(operating_point(scene).elastic_film, rel=0.03)


def test_the_near_field_preconditioner_inverts_the_reduced_system_when_the_near_field_is_all_of_k(monkeypatch):
    """NearFieldPreconditioner solves the (pressure, delta) system with K cut to its near
    field and borders it by z. With the near field reaching every node it is the exact
    inverse of the reduced (delta, z) system, assembled here densely from its definition
    (the total pressure's response T = C - E J_pp^-1 J_ph, the rows I - K T | -K T 1 and the
    force row); with the default radius it is not (GMRES then needs it)."""
    # on the long inlet: the reduced system below has no far inlet's exterior
    model = Model.assemble(lc.load_scene(TABLE1, {"mesh.nx": 15, "mesh.ny": 9, "operating.speed": 1.0,
                                                  "mesh.far_inlet": False}))
    state, diag = mn.monolithic_solve(model)
    assert diag.converged
    lin = mn.linearise(model, mn.Iterate(state.fluid_pressure, state.delta, state.z))
    n = model.mesh.nx * model.mesh.ny
    weight = lin.film_scale / model.scene.operating.force
    response = np.diag(lin.contact_slope.ravel())
    response[lin.unknown.ravel()] -= np.linalg.solve(lin.j_pp.toarray(), lin.j_ph.toarray())
    coupled = model.deformation.matrix @ response
    area = model.mesh.nodal_area.ravel()
    reduced = np.zeros((n + 1, n + 1))
    reduced[:n, :n] = np.eye(n) - coupled
    reduced[:n, n] = -coupled.sum(axis=1)
    reduced[n, :n] = weight * (area @ response)
    reduced[n, n] = weight * float(area @ response.sum(axis=1))
    y = np.random.default_rng(1).standard_normal(n + 1)
    monkeypatch.setattr(mn, "NEAR_FIELD_RADIUS", max(model.mesh.shape))
    exact = mn.NearFieldPreconditioner.build(model, lin, weight).apply(reduced @ y)
    assert np.allclose(exact, y, rtol=0, atol=1e-6)  # 1.4e-8 measured (unscaled units: 1.5e-6)
    monkeypatch.setattr(mn, "NEAR_FIELD_RADIUS", 2)
    approximate = mn.NearFieldPreconditioner.build(model, lin, weight).apply(reduced @ y)
    assert not np.allclose(approximate, y, rtol=0, atol=1e-3)


# A fresh count for a kept preconditioner (KeptPreconditioner.keep) under which any reuse within
# one GMRES cycle keeps it: KEPT_GROWTH times it is GMRES_RESTART
GMRES_ITERATIONS_FRESH = mn.GMRES_RESTART // mn.KEPT_GROWTH


def test_a_kept_preconditioner_gives_the_dense_newton_direction_and_one_that_fails_is_replaced(monkeypatch):
    """The Krylov direction with the preconditioner kept from an earlier iterate
    (KeptPreconditioner) against the dense reduced solve (dense_reduced_solve, no GMRES) at
    the current one: the same direction to GMRES's tolerance, without a new factorisation;
    one that needed more than KEPT_GROWTH times its fresh iterations gives the same
    direction and is dropped for the next; one factorised on another mesh is not used; one
    under which GMRES cannot converge is replaced by a fresh one."""
    model = Model.assemble(lc.load_scene(TABLE1, {"mesh.nx": 15, "mesh.ny": 9, "operating.speed": 1.0}))
    start = mn.cold_start(model)
    earlier = mn.linearise(model, start)
    d_p, d_delta, dz, _ = mn.newton_direction(model, earlier, 1e-10)
    later = mn.linearise(model, mn.Iterate(np.maximum(start.pressure + d_p, 0.0), start.delta + d_delta, start.z + dz))
    dense = mn.newton_direction(model, later, 1e-10, model.deformation.matrix)
    built = []
    build = mn.NearFieldPreconditioner.build
    monkeypatch.setattr(mn.NearFieldPreconditioner, "build", lambda *args: built.append(1) or build(*args))
    weight = earlier.film_scale / model.scene.operating.force
    near = build(model, earlier, weight)
    kept = mn.KeptPreconditioner()
    kept.keep(near, model.mesh, GMRES_ITERATIONS_FRESH)
    reused = mn.newton_direction(model, later, 1e-10, kept=kept)
    assert not built and kept.preconditioner is near
    for a, b in zip(reused[:3], dense[:3]):
        np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-6 * np.max(np.abs(b)))

    kept.keep(near, model.mesh, 1)  # as if fresh it had needed one iteration: now it needs more than KEPT_GROWTH
    stale = mn.newton_direction(model, later, 1e-10, kept=kept)
    assert not built and kept.preconditioner is None
    for a, b in zip(stale[:3], dense[:3]):
        np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-6 * np.max(np.abs(b)))

    other = Model.assemble(lc.load_scene(TABLE1, {"mesh.nx": 15, "mesh.ny": 9, "operating.speed": 1.0})).mesh
    kept.keep(near, other, GMRES_ITERATIONS_FRESH)  # the same sizes, another mesh (a rest domain's)
    mn.newton_direction(model, later, 1e-10, kept=kept)
    assert built == [1] and kept.preconditioner is not near and kept.mesh is model.mesh

    class Scrambled:  # a diagonal of random signs over six decades: GMRES needs far more than a cycle
        scale = np.random.default_rng(2).choice([-1.0, 1.0], dense[1].size + 1) * np.logspace(-3, 3, dense[1].size + 1)
        unknowns = near.unknowns

        def apply(self, v):
            return self.scale * v

    kept.keep(Scrambled(), model.mesh, GMRES_ITERATIONS_FRESH)
    replaced = mn.newton_direction(model, later, 1e-10, kept=kept)
    assert built == [1, 1] and isinstance(kept.preconditioner, mn.NearFieldPreconditioner)
    for a, b in zip(replaced[:3], dense[:3]):
        np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-6 * np.max(np.abs(b)))


def scaled_residual(lin: mn.Linearisation, scales: mn.Linearisation) -> np.ndarray:
    """``lin``'s residual as the merit weighs it (Linearisation.merit), p by p_s and films by
    h_s of ``scales`` (p_s moves with the iterate: a finite difference holds it fixed)."""
    parts = [lin.r_p / scales.pressure_scale, [lin.r_z / scales.film_scale]]
    if lin.r_delta is not None:
        parts.append((lin.r_delta / scales.film_scale).ravel())
    return np.concatenate([np.ravel(part) for part in parts])


def test_a_krylov_step_meets_the_inexact_newton_condition_on_the_whole_residual(monkeypatch):
    """The inexact-Newton condition |R + J d| <= eta |R| (Dembo, Eisenstat and Steihaug),
    with J d by finite differences of the assembled residual along the step d that GMRES gives
    at forcing eta = 0.1 to the whole residual (newton_direction's ``whole``, taken where the
    line search finds no descent along the first direction), at the predictors of the first
    time steps of the Table 1 stop on 21 x 21: the reduced system's right-hand side, K times
    the pressure step at fixed film, is much larger than the residual there, and GMRES to eta
    times it alone leaves 3.0, 0.26 and 0.12 at three of these seven predictors (0.07 at
    most to the whole residual)."""
    scene = lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 21, "operating.speed": 1.0, "motion.kind": "stop",
                                   "motion.ramp": 1e-3})
    steps = []
    solve = integrator.step_solve
    monkeypatch.setattr(integrator, "step_solve", lambda model, initial, fallback, *rest, **named: steps.append(
        (model, initial)) or solve(model, initial, fallback, *rest, **named))
    integrator.TimeIntegrator(scene, SpeedHistory.from_scene(scene)).run(until=lambda level: level.time >= 2e-6)
    eta, eps, checked = 0.1, 1e-4, 0
    for model, initial in steps:
        it = mn.warm_iterate(model, initial)
        lin = mn.linearise(model, it)
        lin = mn.linearise(model, it, mn.smoothing_for(lin))
        d_p, d_delta, dz, _ = mn.newton_direction(model, lin, eta, whole=True)
        moved = mn.linearise(model, mn.Iterate(it.pressure + eps * d_p, it.delta + eps * d_delta, it.z + eps * dz),
                             lin.smoothing)
        residual = scaled_residual(lin, lin)
        linearised = residual + (scaled_residual(moved, lin) - residual) / eps
        assert np.linalg.norm(linearised) <= 1.01 * eta * np.linalg.norm(residual)
        checked += 1
    assert checked >= 5


def test_a_solve_that_stops_says_why_each_solver_stopped(monkeypatch):
    """Never silent: where the nested solve runs out of iterations without a failure of its own
    and the Newton that finishes it fails too, the notes say NOT CONVERGED with the nested
    solver's iterations and last deformation change, then the Newton's reason (it was
    converged = 0 with neither in the figure build: Fig. 12 at F = 30 N)."""
    def failing_newton(model, initial=None, tolerance=None, continuation=True):
        raise mn.SolveError("no descent (simulated)")

    monkeypatch.setattr(mn, "monolithic_solve", failing_newton)
    ds = lc.solve(lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": 21, "mesh.ny": 21,
                                                                "solver.max_iterations": 1}))
    notes = ds.attrs["notes"]
    assert ds["converged"].item() == 0
    assert "NOT CONVERGED: 1 iteration(s) without its deformation change falling below the tolerance" in notes
    assert "then one Newton from its last state: no descent (simulated)" in notes


@pytest.mark.parametrize("force, speed", [(5.0, 1e-4), (5.0, 6.31e-4), (5.0, 0.001585)])
def test_the_universal_variable_lands_on_the_active_set_answer(force, speed, monkeypatch):
    """The Reynolds condition in the universal variable (p = max(u, 0), monolithic_newton.
    linearise) has the complementarity's solutions exactly, and its Newton ends on an exact
    active set: Table 1 on 51 x 51 at low speeds, where the fluid carries 0.1 to 3 % of the
    load, equals the nested solver's answer (its active set solved exactly) to 1e-7 of the
    force in the fluid's share, without the open film's scale. The Fischer-Burmeister Newton
    met its own tests there 1.2e-5 of the force away (thirty-seventh session)."""
    calls = []
    iteration = mn.newton_iteration

    def recorded(model, start, tolerance, max_iterations, open_film_floor=False, universal=False):
        result = iteration(model, start, tolerance, max_iterations, open_film_floor, universal)
        calls.append((open_film_floor, universal, not result[3]))
        return result

    monkeypatch.setattr(mn, "newton_iteration", recorded)
    nested, newton = newton_and_nested({"operating.force": force, "operating.speed": speed})
    assert int(nested.converged) == 1 and int(newton.converged) == 1
    assert all(universal and converged and not floor for floor, universal, converged in calls)
    assert float(newton.fluid_force) == pytest.approx(float(nested.fluid_force), abs=1e-7 * force)
    assert float(newton.contact_resistance) == pytest.approx(float(nested.contact_resistance), rel=1e-6)


def test_the_universal_residual_vanishes_at_the_complementarity_solution():
    """At the nested solver's pressure p and outflow w (its active set solved exactly), the
    universal variable u = p - w/A_ii gives p = max(u, 0) back and a residual of zero: the
    two forms have the same solutions."""
    model = Model.assemble(prepare(lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 31, "operating.speed": 0.3})).scene)
    state, diagnostics = mn.coupled_solve(model)
    assert diagnostics.converged and state.reynolds.cavitated.any()
    exact = mn.linearise(model, mn.Iterate(state.fluid_pressure, state.delta, state.z))
    unknown = exact.unknown
    u = np.zeros(model.mesh.shape)
    u[unknown] = state.fluid_pressure[unknown] - exact.parts.outflow / exact.parts.scale
    lin = mn.linearise(model, mn.Iterate(u, state.delta, state.z), universal=True)
    assert lin.universal
    np.testing.assert_allclose(lin.state.fluid_pressure, state.fluid_pressure, rtol=0, atol=1e-9 * lin.pressure_scale)
    assert np.max(np.abs(lin.r_p)) <= 1e-9 * lin.pressure_scale
    assert (u[unknown] < 0.0).sum() == state.reynolds.cavitated.sum()  # the cavitated cells: u = -w/A_ii < 0
