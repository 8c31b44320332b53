"""Mass-conserving (JFO) cavitation in the one Newton (numerics/jfo_outflow.py,
model/monolithic_newton.py; docs/physics.md section 20, "JFO in the one Newton"), steady and
in time (unsteady/integrator.py).

Truths: the Reynolds outflow of reynolds.py, which the JFO outflow must equal in a full film;
finite differences of the assembled outflow, for its slopes in u and in the film; the
active-set JFO solver (numerics/cavitation_jfo.py, a separate solver) and the conservation of
the face flux where a film ruptures and re-forms (two contacts in a row); Martin's rigid
cylinder with the Reynolds exit condition, which JFO reproduces on a single
convergent-divergent gap; the nested coupled solver with JFO on Table 1; in time, the fluid a
cavitated cell holds at rest (no flow reaches it), the active-set solver's storage hook at a
step's film, and the face-flux volume balance of every step.
"""

import dataclasses
import re

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

import lubecontact as lc
from lubecontact.model import monolithic_newton as mn
from lubecontact.model.fluid_film import fluid_faces, fluid_film, squeeze_content
from lubecontact.numerics.cavitation_jfo import couette_operator, solve_jfo, upwind_content
from lubecontact.numerics.jfo_outflow import mass_conserving_outflow
from lubecontact.numerics.mesh import Mesh
from lubecontact.numerics.reynolds import reynolds_system
from lubecontact.numerics.reynolds_jacobian import outflow_film_jacobian
from lubecontact.unsteady.integrator import TimeIntegrator
from lubecontact.unsteady.motion import SpeedHistory

pytestmark = pytest.mark.filterwarnings("error")

TABLE1 = "config/scenes/table1.yaml"
R, H0, MU, U = 0.01, 1e-6, 0.1, 1.0
B = np.sqrt(2 * R * H0)
UNIT = 1e5  # Pa, the universal variable's unit in the fixed-film tests


def two_contacts(nx):
    """A line film that ruptures behind one contact and re-forms at the next (the truth of
    test_cavitation_jfo.py's mass balance)."""
    x = np.linspace(-4.0, 12.0, nx) * B
    mesh = Mesh(x=x, y=np.zeros(1), length=1.0)
    h = (H0 + np.minimum(x**2, (x - 8 * B) ** 2) / (2 * R))[None, :]
    return mesh, h, h**3 / (12 * MU)


def outflow(mesh, h, k, variable, unit=UNIT):
    """The JFO outflow of ``variable`` at film ``h`` with the film slopes of a smooth film
    (sliding, every unknown can cavitate: p = max(u, 0))."""
    system = reynolds_system(mesh, h, k, U)
    gap_slope, coefficient_slope = np.ones_like(h), 3.0 * h**2 / (12 * MU)
    pressure = pressure_field(mesh, system.unknown, np.maximum(variable, 0.0))

    def film_slopes(content):
        return outflow_film_jacobian(mesh, pressure, system.unknown, U, None, gap_slope, coefficient_slope,
                                     face_content=upwind_content(mesh, content, U))

    parts, split = mass_conserving_outflow(mesh, system, h, U, None, variable, unit, film_slopes)
    return parts, split, system


def pressure_field(mesh, unknown, values):
    field = np.zeros(mesh.shape)
    field[unknown] = values
    return field


def newton_at_fixed_film(mesh, h, k, unit=UNIT):
    """A plain semismooth Newton on w(u) = 0 (no line search: the residual is piecewise linear)."""
    system = reynolds_system(mesh, h, k, U)
    u = np.zeros(int(system.unknown.sum()))
    for _ in range(60):
        parts, split, _ = outflow(mesh, h, k, u, unit)
        if np.abs(parts.outflow).max() <= 1e-13 * np.abs(parts.matrix).max() * UNIT:
            return split, system.unknown
        u = u - spsolve(sp.csc_matrix(parts.matrix), parts.outflow)
    raise AssertionError("the fixed-film Newton did not converge")


def test_in_a_full_film_the_jfo_outflow_is_the_reynolds_outflow():
    mesh, h, k = two_contacts(201)
    system = reynolds_system(mesh, h, k, U)
    p = np.random.default_rng(3).uniform(1e3, 1e6, int(system.unknown.sum()))
    parts, split, _ = outflow(mesh, h, k, p)
    assert split.pressurised.all() and np.all(split.content == 1.0)
    reynolds = system.matrix @ p - system.rhs
    np.testing.assert_allclose(parts.outflow, reynolds, rtol=0, atol=1e-12 * np.abs(reynolds).max())


def test_the_outflow_slopes_in_u_and_in_the_film_against_finite_differences():
    mesh, h, k = two_contacts(121)
    system = reynolds_system(mesh, h, k, U)
    rng = np.random.default_rng(11)
    n = int(system.unknown.sum())
    u = rng.uniform(-0.8, 1.0, n) * UNIT  # both branches, away from the kink at u = 0
    u[np.abs(u) < 0.05 * UNIT] = 0.3 * UNIT
    parts, split, _ = outflow(mesh, h, k, u)
    assert split.pressurised.any() and not split.pressurised.all()
    step = 1e-6 * UNIT
    for i in rng.choice(n, 10, replace=False):
        bump = np.zeros(n)
        bump[i] = step
        numeric = (outflow(mesh, h, k, u + bump)[0].outflow - outflow(mesh, h, k, u - bump)[0].outflow) / (2 * step)
        np.testing.assert_allclose(parts.matrix[:, i].toarray().ravel(), numeric, rtol=1e-6,
                                   atol=1e-9 * np.abs(numeric).max())
    d_outflow, _ = parts.film_jacobians
    dh = 1e-5 * H0
    for node in rng.choice(np.flatnonzero(system.unknown.ravel()), 10, replace=False):
        bump = np.zeros(h.shape)
        bump[0, node] = dh

        def at(film):
            return outflow(mesh, film, film**3 / (12 * MU), u)[0].outflow

        numeric = (at(h + bump) - at(h - bump)) / (2 * dh)
        np.testing.assert_allclose(d_outflow[:, node].toarray().ravel(), numeric, rtol=1e-5,
                                   atol=1e-8 * np.abs(numeric).max())


@pytest.mark.parametrize("unit", [1e3, 1e5, 1e7])
def test_newton_on_the_universal_variable_finds_the_active_set_solution_and_conserves_mass(unit):
    """Two contacts in a row (the film ruptures behind the first and re-forms at the second):
    the same p and theta as the active-set solver, whatever the unit P, and the same volume
    flux through every face to round-off (Swift-Stieber misses it by over 5 %, the truth of
    test_cavitation_jfo.py)."""
    mesh, h, k = two_contacts(801)
    split, unknown = newton_at_fixed_film(mesh, h, k, unit)
    truth = solve_jfo(mesh, h, k, U)
    assert truth.converged and (~split.pressurised).sum() > 50
    np.testing.assert_allclose(split.pressure, truth.pressure[unknown], rtol=0, atol=1e-9 * truth.pressure.max())
    # the node where the film re-forms has p and 1 - theta both near zero: the active-set
    # solver accepts it at p = -1.8e-6 Pa (its set tolerance), the Newton at p = +2e-5 Pa, and
    # their contents there differ by 8e-9
    np.testing.assert_allclose(split.content, truth.content[unknown], rtol=0, atol=1e-7)
    p = pressure_field(mesh, unknown, split.pressure)
    theta = np.ones(mesh.shape)
    theta[unknown] = split.content
    poiseuille = -0.5 * (k[0, :-1] + k[0, 1:]) * np.diff(p[0]) / mesh.dx
    flux = poiseuille + 0.5 * U * 0.5 * (h[0, :-1] + h[0, 1:]) * theta[0, :-1]
    assert np.ptp(flux) <= 1e-9 * flux[0]


def test_the_couette_operator_upwinds_the_content():
    """G theta + g0 with theta = 1 is the Couette part of the Reynolds right-hand side."""
    mesh, h, k = two_contacts(101)
    system = reynolds_system(mesh, h, k, U)
    couette, inflow = couette_operator(mesh, h, U, system.unknown)
    poiseuille_only = reynolds_system(mesh, h, k, 0.0)
    np.testing.assert_allclose(couette @ np.ones(couette.shape[0]) + inflow, -(system.rhs - poiseuille_only.rhs),
                               rtol=0, atol=1e-12 * np.abs(inflow).max(initial=1e-30) + 1e-30)


def test_one_newton_with_jfo_carries_martins_load_on_the_rigid_cylinder():
    """Martin 1916 with the Reynolds exit condition (w' = 4.895 mu u_m R / h_min), which JFO
    reproduces on a single convergent-divergent gap."""
    speed, force, radius, length = 0.1, 5.0, 0.01, 1e-3
    h0 = 4.895 * MU * 0.5 * speed * radius * length / force
    inlet = np.sqrt(2 * radius * h0)
    ds = lc.solve(lc.load_scene(TABLE1, {
        "effects.asperity_contact": False, "effects.elastic_deformation": False, "effects.cavitation": "jfo",
        "solver.method": "newton", "mesh.ny": 1, "mesh.nx": 2001, "mesh.x_min": -40 * inlet, "mesh.x_max": 2 * inlet,
    }), fields=True)
    assert ds["converged"].item() == 1
    assert ds["min_film_thickness"].item() == pytest.approx(h0, rel=0.02)
    assert float(ds["film_content"].min()) < 1.0


@pytest.mark.parametrize("overrides", [
    {"mesh.nx": 121, "mesh.ny": 1, "operating.speed": 0.3},
    {"mesh.nx": 51, "mesh.ny": 1, "operating.speed": 0.01},
    {"mesh.nx": 31, "mesh.ny": 31, "operating.speed": 1.0},
], ids=["line-0.3", "line-0.01", "2d-1"])
def test_one_newton_with_jfo_finds_the_nested_solvers_answer(overrides):
    """Both solve the same discrete JFO problem to the same tolerance (1e-6)."""
    base = {**overrides, "effects.cavitation": "jfo"}
    nested = lc.solve(lc.load_scene(TABLE1, base), fields=True)
    newton = lc.solve(lc.load_scene(TABLE1, {**base, "solver.method": "newton"}), fields=True)
    assert nested["converged"].item() == 1 and newton["converged"].item() == 1
    assert newton.attrs["notes"].count("continuation") == 0
    assert newton["fluid_force"].item() == pytest.approx(nested["fluid_force"].item(), abs=1e-5 * 5.0)
    assert newton["contact_resistance"].item() == pytest.approx(nested["contact_resistance"].item(), rel=1e-4)
    assert newton["friction_coefficient"].item() == pytest.approx(nested["friction_coefficient"].item(), rel=1e-4)
    np.testing.assert_allclose(newton["film_content"], nested["film_content"], rtol=0, atol=1e-4)
    assert float(newton["film_content"].min()) < 0.5


def test_a_stopped_nested_jfo_solve_is_finished_by_one_newton(monkeypatch):
    """The nested solver held to one iteration stops; one Newton from its last state finishes
    it, says so, and lands on the nested solver's own answer with its iterations."""
    overrides = {"mesh.nx": 21, "mesh.ny": 21, "effects.cavitation": "jfo"}
    truth = lc.solve(lc.load_scene(TABLE1, overrides))
    real = mn.coupled_solve

    def one_iteration(model, initial=None):
        scene = model.scene.replace({"solver.max_iterations": 1})
        return real(mn.Model.assemble(scene, model.mesh, model.contact), initial)

    monkeypatch.setattr(mn, "coupled_solve", one_iteration)
    ds = lc.solve(lc.load_scene(TABLE1, overrides))
    assert ds["converged"].item() == 1
    assert "the nested solver stopped after 1 iteration" in ds.attrs["notes"]
    assert re.search(r"one Newton from its last state converged in \d+ Newton iteration\(s\)", ds.attrs["notes"])
    assert ds["fluid_force"].item() == pytest.approx(truth["fluid_force"].item(), abs=1e-5 * 5.0)


# a rigid smooth cylinder stopped from 1 m/s in 0.1 ms, on a domain that keeps the film
# ruptured behind it (a line of 401 nodes, each step one Newton)
SMOOTH_JFO_STOP = {"operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-4, "motion.duration": 3e-3,
                   "effects.asperity_contact": False, "effects.elastic_deformation": False,
                   "effects.cavitation": "jfo", "mesh.ny": 1, "mesh.nx": 401, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3}


def test_at_rest_a_cavitated_zone_holds_its_fluid():
    """Once the cylinder stops (U = 0) there is no Couette flux, and a cavitated node between
    cavitated neighbours has no pressure gradient on either side: no flow, so the fluid its
    cell holds, theta h_T, cannot change while the film closes around it (Swift-Stieber has no
    theta and would fill it at once). Measured: within 5e-7 of itself from step to step."""
    scene = lc.load_scene(TABLE1, SMOOTH_JFO_STOP)
    levels, failure = TimeIntegrator(scene, SpeedHistory.from_scene(scene)).run(until=lambda lv: lv.time >= 1e-3)
    assert not failure
    at_rest = [level for level in levels if level.time > 1e-4]
    checked = 0
    for before, after in zip(at_rest[:-1], at_rest[1:]):
        both = before.state.reynolds.cavitated[0] & after.state.reynolds.cavitated[0]
        inner = np.zeros_like(both)
        inner[1:-1] = both[1:-1] & both[:-2] & both[2:]
        held = [level.state.reynolds.content[0] * level.state.expected_gap[0] for level in (before, after)]
        np.testing.assert_allclose(held[1][inner], held[0][inner], rtol=5e-6)
        assert np.all(after.state.film[0][inner] < before.state.film[0][inner])  # while the film closes
        checked += int(inner.sum())
    assert checked > 1000 and float(at_rest[-1].state.reynolds.content.min()) < 0.1


def test_a_jfo_time_step_is_the_active_set_solvers_step_at_its_film():
    """The first step of a rough stop against the active-set JFO solver with its storage hook
    (a separate solver), given the step's film and the stored fluid of the steady start,
    theta c, written out here: the same pressure and film content to the step's tolerance."""
    scene = lc.load_scene(TABLE1, {"operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-3,
                                   "effects.elastic_deformation": False, "effects.cavitation": "jfo",
                                   "mesh.ny": 1, "mesh.nx": 31})
    runner = TimeIntegrator(scene, SpeedHistory.from_scene(scene))
    start = runner.start()
    level, _ = runner.step([dataclasses.replace(start, time=-2e-4), start], 2e-4, 1)  # as run() starts
    assert level is not None and level.diagnostics.converged
    model, state = level.model, level.state
    mesh, dt = model.mesh, 2e-4
    stored = start.state.reynolds.content * squeeze_content(start.model, start.state.film).value
    assert float(start.state.reynolds.content.min()) < 0.5
    h_t, k = fluid_film(model, state.film)
    faces, _ = fluid_faces(model, state.film)
    capacity = mesh.nodal_area * squeeze_content(model, state.film).value / dt  # BDF1: c0 = 1/dt
    truth = solve_jfo(mesh, h_t, k, level.speed, storage=(capacity, mesh.nodal_area * stored / dt), faces=faces)
    assert truth.converged
    peak = truth.pressure.max()
    np.testing.assert_allclose(state.fluid_pressure, truth.pressure, rtol=0, atol=1e-5 * peak)
    np.testing.assert_allclose(state.reynolds.content, truth.content, rtol=0, atol=1e-5)


# a rigid rough stop from 1 m/s: (mesh, bound on the reconnect time's distance to the Reynolds
# condition's); on 21 x 11 each step is one Newton as on the line (rigid, so without GMRES),
# and with side leakage the ruptured film refills otherwise than on the line (measured 1.8 %
# on the line, 4.3 % on 21 x 11)
RIGID_STOPS = {"line 31": ({"mesh.ny": 1, "mesh.nx": 31}, 0.05), "21 x 11": ({"mesh.ny": 11, "mesh.nx": 21}, 0.1)}


@pytest.mark.parametrize("mesh", RIGID_STOPS)
def test_a_rough_jfo_stop_reconnects_and_its_full_film_volume_balance_closes(mesh):
    """Table 1 rigid stopped from 1 m/s: every step's full film balances its
    volume change by its face fluxes (series.volume_balance, independent of the assembled
    system; measured 5e-6 on both meshes, the one Newton's tolerance: a Swift-Stieber step
    is polished by the nested solve to round-off), and with one contact, whose film ruptures
    once, it reconnects near the Reynolds condition's run (RIGID_STOPS)."""
    overrides, bound = RIGID_STOPS[mesh]
    stop = {"operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-3, "motion.duration": 0.05,
            "effects.elastic_deformation": False, "motion.tolerance": 1e-4, "motion.mesh_error_bar": False,
            **overrides}
    jfo = lc.transient(lc.load_scene(TABLE1, {**stop, "effects.cavitation": "jfo"}))
    reynolds = lc.transient(lc.load_scene(TABLE1, stop))
    assert jfo["converged"].item() == 1 and np.all(jfo["step_converged"].values == 1)
    assert np.max(np.abs(jfo["volume_balance"].values)) < 1e-4
    assert jfo["reconnect_time"].item() == pytest.approx(reynolds["reconnect_time"].item(), rel=bound)
