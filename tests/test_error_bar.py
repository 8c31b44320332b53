"""motion.error_bar and motion.mesh_error_bar: reconnect_time with its estimated
time-integration error and mesh error (issue 28 item 5).

Truth: a run at a tolerance ten times below the tighter of the two runs the estimate uses;
the estimate (Richardson in the tolerance, global error ~ tol^(2/3) for BDF2) must bracket
the actual error of the default-tolerance result within a factor of two. The mesh error
alike against a run on a mesh at rest eight times as fine, and the default run's
reconnect_time_extrapolated within 5 % of a converged run."""

import dataclasses
import math

import pytest

import lubecontact as lc
from lubecontact.cli.main import main
from lubecontact.cli.transient import explained
from lubecontact.unsteady import transient as transient_module
from lubecontact.unsteady.transient import extrapolated, finer_mesh_scene

TABLE1 = "config/scenes/table1.yaml"
STOP = {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.speed": 1.0, "motion.duration": 0.1}
ALONE = {"motion.mesh_error_bar": False}  # one run: these tests are of the time-integration error


def run(tolerance, error_bar):
    return lc.transient(lc.load_scene(TABLE1, {**STOP, **ALONE, "motion.tolerance": tolerance,
                                               "motion.error_bar": error_bar}), progress=False)


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
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in {**STOP, **ALONE}.items()],
                 "--set", "motion.tolerance=1e-2",
                 "--set", "motion.error_bar=true", "--out", str(tmp_path / "s.nc")]) == 0
    assert "reconnect_time_error" in capsys.readouterr().out


def test_no_error_bar_without_a_reconnection():
    # a start never comes to rest: no reconnection to time, and no second run made
    ds = lc.transient(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 1, "motion.kind": "start", "motion.speed": 0.1,
                                             "motion.duration": 0.01, "motion.tolerance": 1e-2,
                                             "motion.error_bar": True, **ALONE}), progress=False)
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
    fine = lc.transient(lc.load_scene(TABLE1, {**LINE_STOP, "motion.rest_refinement": 8, **ALONE}), progress=False)
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
    finer = finer_mesh_scene(scene)[0]
    whole = lc.transient(dataclasses.replace(finer, motion=dataclasses.replace(finer.motion, mesh_error_bar=False)),
                         progress=False)["reconnect_time"].item()
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


def test_the_mesh_error_bar_is_on_by_default_and_off_costs_nothing(capsys, tmp_path):
    """On by default (the one run's reconnect time is short by its mesh error, most of its
    error on the Table 1 stop); off, no second run and no variable. On and off are two cases
    (the key is in the scene's hash)."""
    assert lc.load_scene(TABLE1, STOP).motion.mesh_error_bar
    assert "reconnect_time_mesh_error" not in run(1e-2, False)
    assert lc.load_scene(TABLE1, STOP).hash != lc.load_scene(TABLE1, {**STOP, **ALONE}).hash
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in STOP.items()], "--set", "motion.tolerance=1e-2",
                 "--out", str(tmp_path / "s.nc")]) == 0
    out, err = capsys.readouterr()
    assert "reconnect_time_mesh_error" in out and "mesh error bar: a second run" in err
    assert "reconnect_time_extrapolated" in out and "not estimated" not in out


def test_the_extrapolated_reconnect_time_is_the_run_plus_its_mesh_error():
    ds = lc.transient(lc.load_scene(TABLE1, {**STOP, "motion.tolerance": 1e-2}), progress=False)
    assert ds["reconnect_time_extrapolated"].item() == (ds["reconnect_time"].item()
                                                        + ds["reconnect_time_mesh_error"].item())
    assert ds["reconnect_time_extrapolated"].attrs["units"] == "s"


def test_the_default_runs_extrapolated_reconnect_time_is_within_5_percent_of_a_converged_run():
    """Issue 28's aim at default settings, on the Table 1 stop as a 51-node line (the 2-D
    stop's reference takes minutes; its numbers are in docs/physics.md section 14): the
    default run (motion.tolerance and the mesh error bar at their defaults) against a run
    ten times tighter with the mesh at rest eight times as fine (0.2 % from sixteen times,
    above). The one run alone is more than 5 % short: the bar is what brings it within."""
    line = {**STOP, "mesh.nx": 51, "motion.duration": 0.03}
    ds = lc.transient(lc.load_scene(TABLE1, line), progress=False)
    converged = lc.transient(lc.load_scene(TABLE1, {**line, **ALONE, "motion.tolerance": 1e-4,
                                                    "motion.rest_refinement": 8}), progress=False)
    assert ds["converged"].item() == 1 and converged["converged"].item() == 1
    truth = converged["reconnect_time"].item()
    assert abs(ds["reconnect_time_extrapolated"].item() / truth - 1.0) < 0.05, (ds["reconnect_time_extrapolated"].item(), truth)
    assert ds["reconnect_time"].item() / truth - 1.0 < -0.05


def test_a_reconnect_time_without_its_mesh_error_says_it_is_not_estimated(capsys, tmp_path):
    """Off, the error stays unseen in the numbers, never in the words: the file's notes and the
    summary say it is not estimated and how to estimate it."""
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in {**STOP, **ALONE}.items()],
                 "--set", "motion.tolerance=1e-2", "--out", str(tmp_path / "s.nc")]) == 0
    assert "its mesh error is not estimated (motion.mesh_error_bar: false)" in capsys.readouterr().out
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


def test_an_extrapolation_that_moves_the_time_by_all_of_it_gives_nan():
    """extrapolated(value, error): value + error, but NaN where |error| >= value (to zero or
    below, or to twice as long: outside the range where the error is first order)."""
    assert extrapolated(0.0122, 0.0018) == pytest.approx(0.0140)
    assert extrapolated(1.0, -0.99) == pytest.approx(0.01)
    assert math.isnan(extrapolated(64.6, -82.1)) and math.isnan(extrapolated(1.0, 1.0))
    assert math.isnan(extrapolated(math.inf, 0.1)) and math.isnan(extrapolated(1.0, math.nan))


def test_a_smooth_grease_whose_finer_mesh_reconnects_much_sooner_extrapolates_nothing_and_says_why():
    """Found in the thirty-first session with the mesh error bar on by default: the gallery's
    10 Pa s grease with sigma = 0.1 um as a 51-node line (README.md's reconnect table) reconnects
    at 64.6 s after impasse jumps, and on the mesh at rest twice as fine at 23.6 s: a first-order
    extrapolation gave -17.5 s. Both runs are kept in the notes, the extrapolation is NaN, and
    the file and the summary say why and what to refine."""
    scene = lc.load_scene("config/scenes/stop_grease.yaml", {"roughness.sigma": 0.1e-6, "mesh.ny": 1})
    ds = lc.transient(scene, progress=False)
    assert ds["converged"].item() == 1
    value, error = ds["reconnect_time"].item(), ds["reconnect_time_mesh_error"].item()
    assert math.isfinite(value) and math.isfinite(error) and abs(error) >= value
    assert math.isnan(ds["reconnect_time_extrapolated"].item())
    assert "reconnect_time_extrapolated = nan: the second run on the mesh at rest twice as fine" in ds.attrs["notes"]
    assert any(line.startswith("  reconnect_time_extrapolated = nan: the mesh error estimate")
               and "motion.rest_refinement" in line for line in explained(ds, scene))


def test_a_second_run_that_was_interrupted_says_so_and_the_first_is_kept(monkeypatch):
    """Ctrl-C during the default's second run ends that run (integrator.run returns its
    failure), not the first: the first run's series and reconnect time stay, and the notes
    say that the second run was interrupted rather than that it did not converge."""
    def interrupted(scene, history, since, progress, rest=None):
        return math.nan, "interrupted at t = 0.002 s: the series up to there"

    monkeypatch.setattr(transient_module, "second_reconnect_time", interrupted)
    ds = lc.transient(lc.load_scene(TABLE1, {**STOP, "motion.tolerance": 1e-2}), progress=False)
    assert ds["converged"].item() == 1 and math.isfinite(ds["reconnect_time"].item())
    assert math.isnan(ds["reconnect_time_mesh_error"].item())
    assert "it was interrupted (interrupted at t = 0.002 s" in ds.attrs["notes"]
    assert "did not converge" not in ds.attrs["notes"]


def test_a_contact_that_reconnects_at_once_has_error_bars_of_0_without_a_second_run(monkeypatch, capsys, tmp_path):
    """A 30 g half-sine shock leaves the shock figure's contact closed (reconnect_time = 0 from
    the shock's end). Found in the thirty-first session: the default's bar ran a second run and
    read its 0 as "a mesh error as large as the reconnect time", NaN. Nothing drains, on any
    mesh or tolerance: both bars are 0, no second run starts, and the words say why."""
    shock = {"mesh.ny": 1, "operating.speed": 0.0, "operating.force": 0.5, "motion.kind": "steady",
             "motion.duration": 0.05, "motion.mass": 1.0e-3, "motion.spring_stiffness": 2000.0,
             "motion.vibration": "half_sine_shock", "motion.shock_duration": 0.011,
             "motion.vibration_acceleration": -294.2, "motion.error_bar": True}

    def no_second_run(*args, **kwargs):
        raise AssertionError("a second run for a contact that reconnected at once")

    monkeypatch.setattr(transient_module, "second_reconnect_time", no_second_run)
    ds = lc.transient(lc.load_scene(TABLE1, shock), progress=False)
    assert ds["converged"].item() == 1 and ds["reconnect_time"].item() == 0.0
    assert ds["reconnect_time_error"].item() == 0.0 and ds["reconnect_time_mesh_error"].item() == 0.0
    assert ds["reconnect_time_extrapolated"].item() == 0.0
    assert "no second run was made and its error bars are 0" in ds.attrs["notes"]
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in shock.items()], "--out", str(tmp_path / "s.nc")]) == 0
    assert "reconnected at once: nothing drains on any mesh" in capsys.readouterr().out
