"""motion.error_bar and motion.mesh_error_bar: reconnect_time with its estimated
time-integration error and mesh error (issue 28 item 5).

Truth: a run at a tolerance ten times below the tighter of the two runs the estimate uses;
the estimate (Richardson in the tolerance, global error ~ tol^(2/3) for BDF2) must bracket
the actual error of the default-tolerance result within a factor of two. The mesh error
alike against a run on a mesh at rest eight times as fine."""

import math

import pytest

import lubecontact as lc
from lubecontact.cli.main import main
from lubecontact.cli.transient import explained
from lubecontact.unsteady.transient import finer_mesh_scene

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


LINE_STOP = {**STOP, "mesh.nx": 51, "motion.duration": 0.03, "motion.tolerance": 1e-4}


def test_the_mesh_error_bar_brackets_the_actual_mesh_error():
    """The Table 1 line stop on 51 nodes at a tolerance tight enough that the mesh error
    dominates (1e-4): its mesh error bar, from a second run with the mesh at rest twice as
    fine, against a run with the mesh at rest eight times as fine (a converged value within
    0.2 %: sixteen times as fine moves it by 0.03 ms). The coarse run reconnects early
    (the finer the mesh at rest, the slower the film drains), and the estimate says how much
    within a factor of two, with its sign."""
    ds = lc.transient(lc.load_scene(TABLE1, {**LINE_STOP, "motion.mesh_error_bar": True}), progress=False)
    fine = lc.transient(lc.load_scene(TABLE1, {**LINE_STOP, "motion.rest_refinement": 8}), progress=False)
    assert ds["converged"].item() == 1 and fine["converged"].item() == 1
    estimate = ds["reconnect_time_mesh_error"].item()
    actual = fine["reconnect_time"].item() - ds["reconnect_time"].item()
    assert actual > 0.0 and 0.5 * estimate <= actual <= 2.0 * estimate, (actual, estimate)
    assert ds["reconnect_time_mesh_error"].attrs["units"] == "s"
    assert "mesh at rest twice as fine" in ds.attrs["notes"]


def test_the_second_run_stops_at_its_reconnection_with_the_whole_runs_reconnect_time():
    """The mesh error bar's second run ends at its first level at rest below its threshold
    (transient.second_reconnect_time): its reconnect time is that of the finer scene run to
    its end by lc.transient, to the last digit."""
    scene = lc.load_scene(TABLE1, {**STOP, "motion.tolerance": 1e-2, "motion.mesh_error_bar": True})
    ds = lc.transient(scene, progress=False)
    whole = lc.transient(finer_mesh_scene(scene)[0], progress=False)["reconnect_time"].item()
    assert whole < scene.motion.duration - scene.motion.ramp  # the whole run goes on after it
    assert f"{whole!r} s there" in ds.attrs["notes"]
    assert ds["reconnect_time_mesh_error"].item() == pytest.approx(2.0 * (whole - ds["reconnect_time"].item()),
                                                                   rel=1e-12)


def test_the_finer_mesh_is_the_mesh_at_rest_or_on_an_explicit_domain_the_whole_mesh():
    auto = lc.load_scene(TABLE1, {**LINE_STOP, "motion.rest_refinement": 3})
    finer, words = finer_mesh_scene(auto)
    assert (finer.motion.rest_refinement, finer.mesh.nx) == (6, 51) and "rest_refinement = 6" in words
    explicit = lc.load_scene(TABLE1, {**LINE_STOP, "mesh.x_min": -3e-4, "mesh.x_max": 3e-4})
    finer, words = finer_mesh_scene(explicit)
    # every second node of the finer mesh is a node of the first: its cells halved
    assert (finer.motion.rest_refinement, finer.mesh.nx) == (1, 101) and "101 nodes" in words


def test_the_mesh_error_bar_is_a_switch_that_costs_nothing_when_off(capsys, tmp_path):
    assert "reconnect_time_mesh_error" not in run(1e-2, False)
    assert lc.load_scene(TABLE1, STOP).hash == lc.load_scene(TABLE1, {**STOP, "motion.mesh_error_bar": False}).hash
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in STOP.items()], "--set", "motion.tolerance=1e-2",
                 "--set", "motion.mesh_error_bar=true", "--out", str(tmp_path / "s.nc")]) == 0
    out, err = capsys.readouterr()
    assert "reconnect_time_mesh_error" in out and "mesh error bar: a second run" in err
    assert "so the converged reconnect time is about" in out and "not estimated" not in out


def test_a_reconnect_time_without_its_mesh_error_says_it_is_not_estimated(capsys, tmp_path):
    """Off, the error stays unseen in the numbers, never in the words: the file's notes and the
    summary say it is not estimated and how to estimate it."""
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in STOP.items()], "--set", "motion.tolerance=1e-2",
                 "--out", str(tmp_path / "s.nc")]) == 0
    assert "its mesh error is not estimated (motion.mesh_error_bar: true)" in capsys.readouterr().out
    ds = run(1e-2, False)
    assert "reconnect_time is short by the mesh's error" in ds.attrs["notes"]
    assert "short by the mesh's error" not in lc.transient(lc.load_scene(TABLE1, {**STOP, "motion.tolerance": 1e-2,
                                                                                  "motion.mesh_error_bar": True}),
                                                            progress=False).attrs["notes"]


def test_no_mesh_error_bar_without_a_reconnection():
    ds = lc.transient(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 1, "motion.kind": "start", "motion.speed": 0.1,
                                             "motion.duration": 0.01, "motion.tolerance": 1e-2,
                                             "motion.mesh_error_bar": True}), progress=False)
    assert math.isnan(ds["reconnect_time_mesh_error"].item())


def test_a_mesh_error_bar_whose_second_run_failed_is_explained_not_a_bare_nan():
    scene = lc.load_scene(TABLE1, {**STOP, "motion.tolerance": 1e-2, "motion.mesh_error_bar": True})
    ds = lc.transient(scene, progress=False)
    assert math.isfinite(ds["reconnect_time_mesh_error"].item())
    assert not any("reconnect_time_mesh_error" in line for line in explained(ds, scene))
    ds["reconnect_time_mesh_error"] = ds["reconnect_time_mesh_error"] * math.nan  # as when the finer run fails
    assert any(line.startswith("  reconnect_time_mesh_error = nan: the second run on a mesh twice as fine")
               for line in explained(ds, scene))
