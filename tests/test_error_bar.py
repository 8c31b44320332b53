"""motion.error_bar: reconnect_time with its estimated time-integration error (issue 28 item 5).

Truth: a run at a tolerance ten times below the tighter of the two runs the estimate uses;
the estimate (Richardson in the tolerance, global error ~ tol^(2/3) for BDF2) must bracket
the actual error of the default-tolerance result within a factor of two."""

import math

import pytest

import lubecontact as lc
from lubecontact.cli.main import main

TABLE1 = "config/scenes/table1.yaml"
STOP = {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.speed": 1.0, "motion.duration": 0.1}


def run(tolerance, error_bar):
    return lc.transient(lc.load_scene(TABLE1, {**STOP, "motion.tolerance": tolerance, "motion.error_bar": error_bar}),
                        progress=False)


@pytest.fixture(scope="module")
def reference():
    ds = run(1e-4, False)
    assert ds["converged"].item() == 1
    return ds["reconnect_time"].item()


@pytest.mark.parametrize("tolerance", [1e-2, 1e-3])
def test_the_error_bar_brackets_the_actual_integration_error(tolerance, reference):
    ds = run(tolerance, True)
    estimate, value = ds["reconnect_time_error"].item(), ds["reconnect_time"].item()
    actual = abs(value - reference)
    assert 0.5 * estimate <= actual <= 2.0 * estimate, (value, reference, estimate)
    assert ds["reconnect_time_error"].attrs["units"] == "s"


def test_the_error_bar_is_a_switch_that_costs_nothing_when_off(tmp_path, capsys):
    plain = run(1e-2, False)
    assert "reconnect_time_error" not in plain
    assert lc.load_scene(TABLE1, {**STOP}).hash == lc.load_scene(TABLE1, {**STOP, "motion.error_bar": False}).hash
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in STOP.items()], "--set", "motion.tolerance=1e-2",
                 "--set", "motion.error_bar=true", "--out", str(tmp_path / "s.nc")]) == 0
    assert "reconnect_time_error" in capsys.readouterr().out


def test_no_error_bar_without_a_reconnection():
    # a start never comes to rest: no reconnection to time, and no second run made
    ds = lc.transient(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 1, "motion.kind": "start", "motion.speed": 0.1,
                                             "motion.duration": 0.01, "motion.tolerance": 1e-2,
                                             "motion.error_bar": True}), progress=False)
    assert math.isnan(ds["reconnect_time"].item())
    assert math.isnan(ds["reconnect_time_error"].item())
