"""Mesh convergence (lubecontact.studies.accuracy) against closed forms, and the solver's Newton
machinery (force gradient) against finite differences."""

import math

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.plotting.accuracy import plot_accuracy_cost
from lubecontact.studies import accuracy as cv
from lubecontact.studies import accuracy_plan

TABLE1 = "config/scenes/table1.yaml"


def power_law(h, f0=1.7, c=-0.8, p=2.0):
    return f0 + c * np.asarray(h, dtype=float) ** p


@pytest.mark.parametrize("p", [1.0, 2.0, 3.0])
def test_observed_order_and_extrapolation_are_exact_for_a_pure_power_law(p):
    # non-uniform refinement ratios (1.4 and 1.5), as the sqrt(2) ladders of real meshes
    h = np.array([0.05, 0.07, 0.105])
    f = power_law(h, p=p)
    order, oscillatory = cv.observed_order(f[0], f[1], f[2], h[1] / h[0], h[2] / h[1])
    assert order == pytest.approx(p, rel=1e-9)
    assert not oscillatory
    result = cv.extrapolate(h, f)
    assert result.value == pytest.approx(1.7, rel=1e-12)
    assert result.asymptotic


def test_uniform_ratio_order_is_the_textbook_formula():
    # constant ratio r: p = ln(e32/e21)/ln r (Roache 1998)
    f1, f2, f3, r = 1.0, 1.01, 1.05, 2.0
    order, _ = cv.observed_order(f1, f2, f3, r, r)
    assert order == pytest.approx(math.log(0.04 / 0.01) / math.log(2.0), rel=1e-12)
    assert cv.richardson(f1, f2, r, order) == pytest.approx(f1 + (f1 - f2) / (r**order - 1.0))


def test_higher_order_terms_fade_under_refinement():
    # f = f0 + h^2 + 5 h^3: the observed order tends to 2 as h -> 0 and the extrapolated
    # value to f0, faster than the finest mesh itself
    errors, orders = [], []
    for h1 in (0.1, 0.05, 0.025):
        h = h1 * np.array([1.0, 1.4, 2.0])
        f = 3.0 + h**2 + 5.0 * h**3
        result = cv.extrapolate(h, f)
        orders.append(result.order)
        errors.append((abs(result.value - 3.0), abs(f[0] - 3.0)))
    assert abs(orders[-1] - 2.0) < abs(orders[1] - 2.0) < abs(orders[0] - 2.0) < 0.6
    assert all(extrapolated < finest for extrapolated, finest in errors)


def test_oscillatory_and_exactly_converged_sequences_are_flagged():
    result = cv.extrapolate([0.1, 0.2, 0.4], [1.0, 1.1, 0.9])
    assert result.oscillatory and not result.asymptotic
    converged = cv.extrapolate([0.1, 0.2, 0.4], [2.0, 2.0, 2.5])
    assert math.isnan(converged.order) and converged.value == 2.0 and not converged.asymptotic


def test_extrapolation_refuses_bad_input():
    with pytest.raises(ValueError, match="at least three"):
        cv.extrapolate([0.1, 0.2], [1.0, 2.0])
    with pytest.raises(ValueError, match="non-finite"):
        cv.extrapolate([0.1, 0.2, 0.4], [1.0, np.inf, 2.0])
    with pytest.raises(ValueError, match="ratios"):
        cv.observed_order(1.0, 2.0, 3.0, 1.0, 2.0)


def test_log_quantity_error_is_relative_in_the_value():
    # resistance is extrapolated in ln R; its error is |R/R_ext - 1|
    error = cv.relative_error([1.1e-5, 0.9e-5], math.log(1.0e-5), "contact_resistance")
    np.testing.assert_allclose(error, [0.1, 0.1], rtol=1e-12)
    # the film error is relative to max(|h_ext|, sigma): a film near zero is not a huge error
    error = cv.relative_error([1e-9], 0.0, "min_film_thickness", floor=0.5e-6)
    np.testing.assert_allclose(error, [2e-3], rtol=1e-12)


def test_table1_resistance_converges_under_mesh_refinement():
    # mixed regime (1 m/s): on meshes refined by ~sqrt(2) the change of R shrinks level by
    # level, and the observed order of the three finest is positive
    meshes = [26, 36, 51, 72]
    r = [lc.solve(lc.load_scene(TABLE1, {"mesh.nx": n, "mesh.ny": n, "operating.speed": 1.0}))["contact_resistance"].item()
         for n in meshes]
    changes = np.abs(np.diff(np.log(r)))
    assert np.all(np.diff(changes) < 0), changes
    result = cv.extrapolate(1.0 / (np.array(meshes) - 1.0), np.log(r))
    assert result.order > 0.5
    assert math.exp(result.value) > r[-1] > r[0]  # R grows with refinement: the limit beyond the finest


def test_study_pipeline_on_tiny_meshes(tmp_path):
    spec = accuracy_plan.study_spec(TABLE1.replace("scenes/table1.yaml", "accuracy.yaml"), {
        "speeds": [1.0], "meshes": [11, 15, 21], "timing": {"repeats": 1},
        "domain": {"mesh": 11, "scales": [1.0, 1.5]}, "tolerance": {"mesh": 11, "values": [1e-4, 1e-7]},
        "newton": {"mesh": 11, "values": [1e-3, 1e-7]},
    })
    table = cv.accuracy_table(cv.run_study(spec, log=lambda line: None))
    for q in spec["quantities"]:
        assert table[f"{q}_error"].dims == ("speed", "mesh")
        assert np.all(np.isfinite(table[f"{q}_error"].values))
        assert table[f"{q}_error"].attrs["units"] == "1"
    assert np.all(table["solve_time"].values > 0) and table["solve_time"].attrs["units"] == "s"
    # the reference of each check is its own zero
    assert np.all(table["domain_contact_resistance_change"].values[:, -1] == 0.0)
    assert np.all(table["tolerance_contact_resistance_change"].values[:, 1] == 0.0)  # 1e-7
    # the one Newton against the nested solver's tightest: the same discrete problem, so at a
    # tight tolerance the two agree to it, and a loose one shows its own error (not zero)
    newton = table["newton_contact_resistance_change"]
    assert newton.values[0, 1] < 1e-5 and 0.0 < newton.values[0, 0] and newton.attrs["units"] == "1"
    assert "nested solver's tightest tolerance" in newton.attrs["long_name"]
    text = cv.markdown(table, spec["targets"])
    assert ("the one Newton (solver.method newton) at each solver tolerance on the 11² mesh; change against the "
            "nested solver's tightest tolerance") in text
    assert "the one Newton" not in cv.markdown(table.drop_dims(["newton", "tolerance"]), spec["targets"])  # a study without them
    # 1 m/s: the far inlet, no inlet columns (the long inlet had 21 + 12, 693 nodes from -2.06 mm)
    assert "| 21 \u00d7 21 | 441 | -1.11 |" in text and "Coarsest square mesh" in text
    assert np.all(table["x_min"].values < 0) and table["x_min"].attrs["units"] == "m"
    fig = plot_accuracy_cost(table)
    assert [ax.get_xlabel() for ax in fig.axes] == ["solve time (s)"] * 3


def test_study_spec_rejects_unknown_keys_and_short_ladders():
    path = TABLE1.replace("scenes/table1.yaml", "accuracy.yaml")
    with pytest.raises(ValueError, match="unknown keys"):
        accuracy_plan.study_spec(path, {"mehses": [11, 15, 21]})
    with pytest.raises(ValueError, match="three different"):
        accuracy_plan.study_spec(path, {"meshes": [11, 21]})


@pytest.mark.parametrize("speed", [0.1, 10.0])
def test_force_gradient_matches_finite_differences(speed):
    # the Newton force balance uses dF/dh_j from the Reynolds adjoint plus the contact
    # slope; check it against central differences of the full evaluation (Reynolds solve
    # with cavitation included) for a uniform shift (dF/dz) and for the most sensitive node
    from lubecontact.model.evaluation import evaluate, force_gradient
    from lubecontact.model.model import Model

    scene = lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 15, "operating.speed": speed})
    _, state = lc.solve(scene, return_state=True)
    model = Model.assemble(scene)
    gradient = force_gradient(model, evaluate(model, state.z, state.delta))
    step = 1e-4 * model.contact.sigma

    def force(shift):
        return evaluate(model, state.z, state.delta + shift).total_force

    uniform = (force(step) - force(-step)) / (2 * step)
    assert gradient.sum() == pytest.approx(uniform, rel=1e-4)
    j = np.unravel_index(np.argmax(np.abs(gradient)), gradient.shape)
    bump = np.zeros(model.mesh.shape)
    bump[j] = step
    assert gradient[j] == pytest.approx((force(bump) - force(-bump)) / (2 * step), rel=1e-4)


def test_domain_study_stays_inside_the_cylinder():
    """The film-following inlet at 10 m/s is 6.3 mm of R = 10 mm: the domain study's scaled
    domains stop at DOMAIN_RADIUS_FRACTION R (Eq. 4 needs |x| < R), in whole cells of the
    reference mesh, and every one of them is a valid scene (the default figure build failed
    on the 3x domain before)."""
    import lubecontact as lc

    spec = accuracy_plan.study_spec(TABLE1.replace("scenes/table1.yaml", "accuracy.yaml"), {"speeds": [0.1, 10.0]})
    radius = lc.load_scene(TABLE1).geometry.radius
    base = lc.load_scene(TABLE1)
    points = [p for p in cv.study_points(spec) if p["part"] == "domain"]
    for point in points:
        o = point["overrides"]
        assert -cv.DOMAIN_RADIUS_FRACTION * radius <= o["mesh.x_min"] < o["mesh.x_max"] <= cv.DOMAIN_RADIUS_FRACTION * radius
        base.replace({"operating.speed": point["speed"], **o})  # raises SceneError if invalid
    slow = {p["key"]: p["overrides"]["mesh.x_min"] for p in points if p["speed"] == 0.1}
    assert slow[3.0] == pytest.approx(3.0 * slow[1.0], rel=0.02)  # far from the radius: scaled as asked
