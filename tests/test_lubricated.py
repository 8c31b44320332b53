"""The lubricated, coupled solve (Eqs. 1-18) against independent truths: Martin's rigid
cylinder, the isoviscous-elastic line contact (docs/physics.md section 5), symmetry, the
paper's qualitative findings, and the hard cases of the stability suite."""

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.model.coupling import WarmStart

TABLE1 = "config/scenes/table1.yaml"
SCALARS = ["contact_resistance", "friction_coefficient", "fluid_force", "contact_force", "min_film_thickness"]


def scene(**overrides):
    return lc.load_scene(TABLE1, overrides)


def test_rigid_smooth_line_contact_carries_martins_load():
    # Martin 1916 with the Reynolds condition: w' = 4.895 mu u_m R / h_min, u_m = U/2.
    speed, force, mu, radius, length = 0.1, 5.0, 0.1, 0.01, 1e-3
    h0 = 4.895 * mu * 0.5 * speed * radius * length / force
    inlet = np.sqrt(2 * radius * h0)
    ds = lc.solve(scene(**{
        "effects.asperity_contact": False, "effects.elastic_deformation": False,
        "mesh.ny": 1, "mesh.nx": 2001, "mesh.x_min": -40 * inlet, "mesh.x_max": 2 * inlet,
    }))
    assert ds["converged"].item() == 1
    assert ds["min_film_thickness"].item() == pytest.approx(h0, rel=0.02)
    assert ds["contact_force"].item() == 0.0


@pytest.mark.parametrize(
    "speed, h_min, h_c, x_range",
    [
        # docs/physics.md section 9 (E'_H = 47.56 GPa): reference solver, 1000-1600 nodes, ~1 % grid error
        (0.01, 20.9e-9, 26.6e-9, (-2.5e-4, 1e-4)),
        (0.1, 93.5e-9, 117e-9, (-4e-4, 1.5e-4)),
        (1.0, 0.559e-6, 0.575e-6, (-1.2e-3, 4e-4)),
    ],
)
def test_smooth_elastic_line_contact_matches_isoviscous_elastic_films(speed, h_min, h_c, x_range):
    ds = lc.solve(scene(**{
        "effects.asperity_contact": False, "operating.speed": speed,
        "mesh.ny": 1, "mesh.nx": 401, "mesh.x_min": x_range[0], "mesh.x_max": x_range[1],
    }))
    assert ds["converged"].item() == 1
    assert ds["min_film_thickness"].item() == pytest.approx(h_min, rel=0.03)
    assert ds["central_film_thickness"].item() == pytest.approx(h_c, rel=0.03)


def test_elastic_film_is_thicker_than_rigid_at_moderate_load():
    # g_E = 3.24 at 0.1 m/s: deformation opens the conjunction (H_min 9.35 against Martin's 4.9).
    common = {"effects.asperity_contact": False, "operating.speed": 0.1, "mesh.ny": 1, "mesh.nx": 401,
              "mesh.x_min": -4e-4, "mesh.x_max": 1.5e-4}
    rigid = lc.solve(scene(**common, **{"effects.elastic_deformation": False}))
    elastic = lc.solve(scene(**common))
    assert elastic["min_film_thickness"].item() > 1.5 * rigid["min_film_thickness"].item()


def test_finite_cylinder_is_symmetric_in_y():
    ds = lc.solve(scene(**{"operating.speed": 0.1, "mesh.nx": 31, "mesh.ny": 21}), fields=True)
    for name in ("fluid_pressure", "contact_pressure", "film_thickness"):
        field = ds[name].values
        np.testing.assert_allclose(field, field[::-1, :], rtol=1e-7, atol=1e-9 * np.abs(field).max())


def test_a_crowned_cylinder_carries_a_smooth_film_where_its_straight_twin_closes_at_its_ends():
    """Smooth surfaces (no asperity contact), 51 x 51 on x in [-0.6, 0.2] mm, 0.1 m/s. The
    straight cylinder's ends, where the fluid pressure is ambient, sink less than its middle
    and its film closes there (model/solve.SMOOTH_ENDS). Crowned at 0.1 m its ends stand
    (0.5 mm)^2 / 0.2 m = 1.25 um off the flat, far above the film: it carries the whole load
    on the fluid, its thinnest film within the contact (the side lobes of an elliptical EHL
    film, 65 nm at y = -0.14 mm), the film at the ends ten times thicker."""
    smooth = {"effects.asperity_contact": False, "operating.speed": 0.1, "mesh.x_min": -6e-4, "mesh.x_max": 2e-4}
    straight = lc.solve(lc.load_scene(TABLE1, smooth))
    assert straight["converged"].item() == 0 and "thinnest at its ends" in straight.attrs["notes"]
    crowned = lc.solve(lc.load_scene(TABLE1, {**smooth, "geometry.crown_radius": 0.1}), fields=True)
    assert crowned["converged"].item() == 1
    assert crowned["fluid_force"].item() == pytest.approx(5.0, rel=1e-6)
    h = crowned["film_thickness"].values
    row, _ = np.unravel_index(np.argmin(h), h.shape)
    assert h.min() > 10e-9 and 0 < row < h.shape[0] - 1
    assert h[[0, -1], :].min() > 5.0 * h.min()


def test_cold_start_equals_continuation():
    s = scene(**{"mesh.nx": 31, "mesh.ny": 11})
    speeds = [1e-3, 1e-2, 1e-1, 1.0]
    swept = lc.sweep(s, speeds, progress=False)
    for i, speed in enumerate(speeds):
        cold = lc.solve(s.replace({"operating.speed": speed}))
        for name in SCALARS:
            assert swept[name].values[i] == pytest.approx(cold[name].item(), rel=1e-4, abs=1e-12)


def test_table1_sweep_resistance_rises_by_orders_and_friction_falls_then_levels():
    speeds = np.geomspace(1e-4, 10, 7)
    ds = lc.sweep(scene(**{"mesh.nx": 31, "mesh.ny": 15}), speeds, progress=False)
    assert np.all(ds["converged"].values == 1)
    resistance = ds["contact_resistance"].values
    assert np.all(np.diff(resistance) > 0)
    assert resistance[-1] / resistance[0] > 1e3
    friction = ds["friction_coefficient"].values
    assert friction[0] == pytest.approx(0.1, rel=0.02)  # boundary friction carries the load at low speed
    assert friction.min() < 0.5 * friction[0]
    assert ds["fluid_load_fraction"].values[-1] > 0.99


@pytest.mark.parametrize(
    "key, low, high, resistance_rises",
    [
        ("roughness.sigma", 0.25e-6, 1e-6, False),  # rougher -> lower resistance (Fig. 4)
        ("geometry.radius", 0.005, 0.02, True),  # larger radius -> more lift (Fig. 6)
        ("operating.force", 2.0, 10.0, False),  # more force -> lower resistance (Fig. 8)
        ("lubricant.viscosity", 0.05, 0.2, True),  # more viscous -> higher resistance (Fig. 10)
    ],
)
def test_papers_qualitative_findings(key, low, high, resistance_rises):
    base = {"operating.speed": 0.1, "mesh.nx": 31, "mesh.ny": 11}
    r_low = lc.solve(scene(**base, **{key: low}))["contact_resistance"].item()
    r_high = lc.solve(scene(**base, **{key: high}))["contact_resistance"].item()
    assert (r_high > r_low) == resistance_rises


def test_non_convergence_is_reported_and_the_cli_exits_3(tmp_path):
    from lubecontact.cli.main import main

    s = scene(**{"solver.max_iterations": 1, "mesh.nx": 21, "mesh.ny": 11})
    ds = lc.solve(s)
    assert ds["converged"].item() == 0
    out = tmp_path / "case.nc"
    code = main(["solve", TABLE1, "--set", "solver.max_iterations=1", "--set", "mesh.nx=21", "--set", "mesh.ny=11",
                 "--out", str(out)])
    assert code == 3
    assert out.exists()


HARD = [
    ("roughness.sigma", 0.05e-6), ("roughness.sigma", 5e-6),
    ("operating.force", 0.05), ("operating.force", 500.0),
    ("lubricant.viscosity", 1e-3), ("lubricant.viscosity", 10.0),
    ("geometry.radius", 1e-3), ("geometry.radius", 1.0),
]
HARD_SPEEDS = [1e-6, 1e-3, 1e-1, 10.0, 100.0]


def assert_stable_curve(ds):
    """Converged, balanced, finite (or flagged open), never NaN, monotone in speed."""
    force = ds["applied_force"].values
    assert np.all(ds["converged"].values == 1)
    assert np.all(np.abs(ds["force_residual"].values) <= 1e-6 * force)
    for name in ds.data_vars:
        assert not np.any(np.isnan(ds[name].values)), name
    resistance = ds["contact_resistance"].values
    assert np.all(resistance >= 0)
    assert np.all(np.isfinite(resistance) | (ds["open_circuit"].values == 1))
    assert np.all(resistance[1:] >= resistance[:-1]), resistance
    assert np.all(np.diff(ds["fluid_load_fraction"].values) >= -1e-9)
    assert np.all(np.diff(ds["real_contact_area"].values) <= 1e-20)


@pytest.mark.parametrize("cavitation", ["reynolds", "jfo"])
@pytest.mark.parametrize("key, value", HARD, ids=[f"{k}={v:g}" for k, v in HARD])
def test_hard_cases_stay_numerically_stable(key, value, cavitation):
    s = scene(**{key: value, "mesh.nx": 21, "mesh.ny": 11, "solver.tolerance": 1e-7, "effects.cavitation": cavitation})
    assert_stable_curve(lc.sweep(s, HARD_SPEEDS, warm_start=False, progress=False))


@pytest.mark.parametrize("nodes", [11, 101, 201], ids=lambda n: f"{n}x{n}")
def test_hard_cases_meshes_stay_numerically_stable(nodes):
    speeds = HARD_SPEEDS if nodes < 200 else [1e-3, 1.0]
    s = scene(**{"mesh.nx": nodes, "mesh.ny": nodes, "solver.tolerance": 1e-7})
    assert_stable_curve(lc.sweep(s, speeds, progress=False))


def test_a_failed_force_balance_is_written_as_not_converged(monkeypatch):
    from lubecontact.model import coupling
    from lubecontact.model.evaluation import evaluate
    from lubecontact.model.model import SolveError

    def failing(model, delta, z_guess, tolerance, *args, **kwargs):
        state = evaluate(model, 0.0, delta)
        raise SolveError("forced failure for the test", state)

    monkeypatch.setattr(coupling, "balance_force", failing)
    # one Newton takes over from the failed nested solve, and the notes say so
    ds = lc.solve(scene(**{"mesh.nx": 21, "mesh.ny": 11}))
    assert ds["converged"].item() == 1
    assert "the nested solver stopped" in ds.attrs["notes"] and "forced failure for the test" in ds.attrs["notes"]
    # where Newton fails too, the nested solve's failure is what is written
    from lubecontact.model import monolithic_newton

    monkeypatch.setattr(monolithic_newton, "newton", lambda model, start, tol, limit: (None, 0, None, "forced as well"))
    ds = lc.solve(scene(**{"mesh.nx": 21, "mesh.ny": 11}))
    assert ds["converged"].item() == 0
    assert "NOT CONVERGED: forced failure" in ds.attrs["notes"]
    assert not np.isnan(ds["contact_resistance"].item())


def test_a_nested_solve_that_runs_out_of_iterations_is_finished_and_its_count_said_once():
    """A nested solve stopped by solver.max_iterations, without a failure of its own, is
    finished by one Newton; the note gives the iteration count and the last deformation
    change once (it read "stopped after 3 iterations (3 iteration(s) without ...)"). Three
    iterations: the Newton's own limit is solver.max_iterations too."""
    ds = lc.solve(scene(**{"mesh.nx": 21, "mesh.ny": 11, "solver.max_iterations": 3}))
    notes = ds.attrs["notes"]
    assert ds["converged"].item() == 1
    assert "the nested solver stopped after 3 iteration(s) without its deformation change" in notes, notes
    assert "iterations (3 iteration(s)" not in notes


def test_rigid_model_ignores_a_deformation_warm_start():
    # a sweep under effects: auto can switch elastic_deformation off between neighbours
    elastic = scene(**{"mesh.nx": 21, "mesh.ny": 11, "effects.hydrodynamics": False})
    _, state = lc.solve(elastic, return_state=True)
    rigid = elastic.replace({"effects.elastic_deformation": False})
    warm = lc.solve(rigid, initial=WarmStart(z=state.z, delta=state.delta))
    cold = lc.solve(rigid)
    assert warm["contact_resistance"].item() == pytest.approx(cold["contact_resistance"].item(), rel=1e-6)


def test_sweep_continuation_gives_the_cold_answers():
    # the warm start skips the coarse-mesh levels (coupling.is_fine_warm_start): the answer must
    # still be each point's cold-start answer, across boundary, mixed and full-film speeds
    s = lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 21})
    speeds = np.geomspace(1e-4, 10.0, 7)
    warm = lc.sweep(s, speeds, warm_start=True, progress=False)
    cold = lc.sweep(s, speeds, warm_start=False, progress=False)
    assert warm["converged"].values.all() and cold["converged"].values.all()
    for name in ("contact_resistance", "friction_coefficient", "min_film_thickness"):
        np.testing.assert_allclose(warm[name].values, cold[name].values, rtol=1e-5, err_msg=name)
