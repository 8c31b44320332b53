"""The transient's accuracy study (studies/transient_accuracy.py, transient_cases.ladder_cases):
the ladder's plan, and its Richardson extrapolation against sequences whose limit is known
in closed form (a power law in the mesh spacing, and in the tolerance with BDF2's 2/3)."""

import math

import numpy as np
import pytest
import xarray as xr

from lubecontact.plotting.accuracy import plot_transient_accuracy
from lubecontact.studies import transient_cases as study
from lubecontact.studies.transient_accuracy import ladder_table, least_work_within, markdown

LIMIT = 0.014  # s: the converged reconnect time of the synthetic ladders


def run(reconnect_time: float, seconds: float, converged: int = 1) -> xr.Dataset:
    """A stand-in for a transient's case file: the variables the table reads."""
    return xr.Dataset({"reconnect_time": reconnect_time, "solve_time": seconds, "steps": 70, "rejected_steps": 10,
                       "converged": converged})


def ladder(meshes=(31, 51, 71, 101), tolerances=(1e-3, 5e-4, 2.5e-4), **overrides):
    cases = study.ladder_cases("accuracy", {"meshes": list(meshes),
                                            "tolerances": {"mesh": 51, "values": list(tolerances)}, **overrides})
    data = []
    for case in cases:
        if case["part"] == "mesh":  # second order in h = 1/(n - 1): t = T (1 - 30 h^2)
            h = 1.0 / (case["value"] - 1)
            data.append(run(LIMIT * (1.0 - 30.0 * h**2), case["value"] ** 2 / 300.0))
        elif case["part"] == "rest_refinement":  # first order in the spacing at rest, 1/r: t = T (1 - 0.1/r)
            data.append(run(LIMIT * (1.0 - 0.1 / case["value"]), 5.0 * case["value"]))
        else:  # BDF2's global error ~ tol^(2/3): t = T (1 - 5 tol^(2/3))
            data.append(run(LIMIT * (1.0 - 5.0 * case["value"] ** (2.0 / 3.0)), 3e-3 / case["value"]))
    return cases, data


def test_the_ladder_plans_square_meshes_then_tolerances_on_one_mesh():
    cases, _ = ladder(meshes=(71, 31, 51))
    assert [(c["part"], c["value"]) for c in cases] == [("mesh", 31), ("mesh", 51), ("mesh", 71), ("tolerance", 1e-3),
                                                         ("tolerance", 5e-4), ("tolerance", 2.5e-4)]
    assert cases[0]["overrides"] == {"mesh.nx": 31, "mesh.ny": 31}
    assert cases[-1]["overrides"] == {"mesh.nx": 51, "mesh.ny": 51, "motion.tolerance": 2.5e-4}
    line = study.ladder_cases("accuracy", {"line": True, "meshes": [21, 31, 41], "set": {"lubricant.viscosity": 1.0}})
    assert line[0]["overrides"] == {"lubricant.viscosity": 1.0, "mesh.nx": 21, "mesh.ny": 1}
    assert line[0]["label"] == "21 \u00d7 1 nodes"
    # refined along the sliding direction only (the reconnect time's mesh error is along x),
    # the tolerance ladder still on its square mesh
    along_x, _ = ladder(meshes=(31, 51, 101), mesh_ny=21)
    assert along_x[0]["overrides"] == {"mesh.nx": 31, "mesh.ny": 21} and along_x[0]["label"] == "31 \u00d7 21 nodes"
    assert along_x[-1]["overrides"] == {"mesh.nx": 51, "mesh.ny": 51, "motion.tolerance": 2.5e-4}
    cases, data = ladder(meshes=(31, 51, 101), mesh_ny=21)
    # as the workflow's rule passes them: without the overrides
    table = ladder_table([{k: v for k, v in c.items() if k != "overrides"} for c in cases], data)
    assert list(table["mesh_ny"].values) == [21, 21, 21] and list(table["tolerance_ny"].values) == [51, 51, 51]
    assert "| 31 | 21 |" in markdown(table)


def test_the_refinement_ladder_refines_the_mesh_at_rest_and_extrapolates_in_its_spacing():
    """A third ladder (motion.rest_refinement on one mesh) is planned after the others and
    extrapolated in the spacing at rest, 1/r: a first-order sequence gives its limit and order 1."""
    cases, data = ladder(rest_refinements={"mesh": 51, "mesh_ny": 21, "values": [4, 1, 2]})
    refined = [c for c in cases if c["part"] == "rest_refinement"]
    assert [c["value"] for c in refined] == [1, 2, 4]
    assert refined[0]["overrides"] == {"mesh.nx": 51, "mesh.ny": 21, "motion.rest_refinement": 1}
    assert refined[-1]["label"] == "mesh at rest 4 times finer, 51 \u00d7 21 nodes"
    table = ladder_table(cases, data)
    assert float(table["rest_refinement_extrapolated"]) == pytest.approx(LIMIT, rel=1e-9)
    assert float(table["rest_refinement_order"]) == pytest.approx(1.0, rel=1e-6)
    np.testing.assert_allclose(table["rest_refinement_error"].values, 0.1 / np.array([1.0, 2.0, 4.0]), rtol=1e-6)
    assert "## rest refinement ladder" in markdown(table) and "| motion.rest_refinement |" in markdown(table)
    assert len(plot_transient_accuracy(table, "three ladders").axes) == 2


@pytest.mark.parametrize("bad, words", [
    ({"meshes": [31, 51, 51]}, "three different meshes"),
    ({"meshes": [31, 51, 71.5]}, "whole numbers"),
    ({"meshes": [31, 51, 71], "mesh_ny": 2}, "mesh_ny must be whole numbers"),
    ({"meshes": [31, 51, 71], "tolerances": {"mesh": 51, "values": [1e-3, 0.0, 1e-4]}}, "positive"),
    ({"meshes": [31, 51, 71], "rest_refinements": {"mesh": 51, "values": [1, 2, 2.5]}}, "whole numbers >= 1"),
    ({"meshes": [31, 51, 71], "rest_refinements": {"mesh": 51, "values": [1, 2]}}, "three different"),
])
def test_a_bad_ladder_is_refused_naming_the_figure(bad, words):
    with pytest.raises(ValueError, match=f"'accuracy'.*{words}"):
        study.ladder_cases("accuracy", bad)


def test_the_shipped_ladder_shares_its_default_case_with_the_stop_figure():
    cases = study.figure_cases(study.study_spec("config/transient.yaml", None))
    default = next(c for c in cases["accuracy"] if c["part"] == "tolerance" and c["value"] == 1e-3)
    assert default["id"] == cases["stop"][0]["id"]


def test_richardson_recovers_the_closed_form_limit_and_orders():
    table = ladder_table(*ladder())
    assert float(table["mesh_extrapolated"]) == pytest.approx(LIMIT, rel=1e-9)
    assert float(table["mesh_order"]) == pytest.approx(2.0, rel=1e-6)
    assert float(table["tolerance_extrapolated"]) == pytest.approx(LIMIT, rel=1e-9)
    assert float(table["tolerance_order"]) == pytest.approx(2.0 / 3.0, rel=1e-6)
    h = 1.0 / (table["mesh"].values - 1)
    np.testing.assert_allclose(table["mesh_error"].values, 30.0 * h**2, rtol=1e-6)
    assert int(table["mesh_asymptotic"]) == 1 and table.attrs["notes"] == ""
    for name, var in table.variables.items():
        assert var.attrs.get("units") and var.attrs.get("long_name"), name


def test_the_member_of_least_work_within_a_target_and_the_markdown_say_what_it_costs():
    table = ladder_table(*ladder())
    # errors 30 h^2: 3.3 %, 1.2 %, 0.61 %, 0.3 % on 31, 51, 71, 101 nodes (run time n^2/300 s)
    assert least_work_within(table, "mesh", 0.05) == (31.0, pytest.approx(31**2 / 300))
    assert least_work_within(table, "mesh", 0.01) == (71.0, pytest.approx(71**2 / 300))
    assert least_work_within(table, "mesh", 1e-4) is None
    # BDF2's error 5 tol^(2/3): 5 %, 3.1 %, 2 % at 1e-3, 5e-4, 2.5e-4 (3, 6, 12 s): within 4 % the loosest
    assert least_work_within(table, "tolerance", 0.04) == (5e-4, pytest.approx(6.0))
    text = markdown(table)
    assert "Extrapolated: 14 ms, observed order 2.00" in text and "- within 5 %: mesh 31, 3.2 s" in text


def test_a_finer_member_timed_faster_by_noise_is_not_picked():
    """Two runs of similar cost swap places with timing noise; the member of least work
    within the target is the answer either way, with the time it took."""
    cases, data = ladder()
    data[3] = run(float(data[3]["reconnect_time"]), 0.5 * 51**2 / 300.0)  # 101 nodes, timed below 51
    table = ladder_table(cases, data)
    assert least_work_within(table, "mesh", 0.05) == (31.0, pytest.approx(31**2 / 300))
    assert least_work_within(table, "mesh", 0.02) == (51.0, pytest.approx(51**2 / 300))


def test_a_run_that_never_reconnected_leaves_its_ladder_without_extrapolation():
    cases, data = ladder()
    data[2] = run(math.inf, 50.0)
    table = ladder_table(cases, data)
    assert math.isnan(float(table["mesh_extrapolated"])) and np.isnan(table["mesh_error"].values).all()
    assert "the run(s) at mesh 71 did not converge or did not reconnect" in table.attrs["notes"]
    assert math.isfinite(float(table["tolerance_extrapolated"]))
    fig = plot_transient_accuracy(table, "a ladder")
    assert len(fig.axes) == 2
