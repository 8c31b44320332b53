"""Time (lubecontact.transient, docs/DESIGN.md "Time") against independent truths: the
analytic squeeze law of a rigid smooth cylinder (docs/physics.md section 14), the steady solve,
the limit of shrinking ramps, the integrator's order, the discrete volume balance and
trends argued from the equations. Line mode and coarse meshes keep them cheap."""

import functools
import math
import re
from types import SimpleNamespace

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.cli.transient import summary
from lubecontact.model import coupling
from lubecontact.model.monolithic_newton import NearFieldPreconditioner
from lubecontact.unsteady import integrator
from lubecontact.unsteady.events import dense_resistance
from lubecontact.unsteady.integrator import SAFETY, SHRINK, bdf_coefficients, error_fraction, rejection_factor
from lubecontact.unsteady.motion import SpeedHistory, motion_problems
from lubecontact.unsteady.series import THRESHOLD_SHIFT, cycle_peaks, reconnect_time, threshold_times

TABLE1 = "config/scenes/table1.yaml"
# Table 1 as a rigid rough line contact on a coarse mesh, stopped from 1 m/s over 1 ms
ROUGH_STOP = {"operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-3, "motion.duration": 0.05,
              "mesh.ny": 1, "mesh.nx": 31, "effects.elastic_deformation": False}
# rigid smooth long cylinder (w' = 5000 N/m, mu = 0.1 Pa s, R = 10 mm) on a domain of
# ten inlet lengths sqrt(2 R h) of the 0.5 um film each side
SMOOTH_STOP = {"operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-4, "motion.duration": 3e-3,
               "effects.asperity_contact": False, "effects.elastic_deformation": False,
               "mesh.ny": 1, "mesh.nx": 2001, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3}


# a test that reads the one run's reconnect_time: without the mesh error bar the default adds
ONE_RUN = {"motion.mesh_error_bar": False}

# a dotted config key (lubricant.viscosity) in a figure's text: figures speak in words and units
CONFIG_KEY = re.compile(r"\b[a-z_]+\.[a-z_]+\b")


def scene(base, **overrides):
    return lc.load_scene(TABLE1, {**base, **overrides})


def test_default_motion_keeps_every_old_hash():
    table1 = lc.load_scene(TABLE1)
    # the canonical form (and so the hash) of a scene without motion has no motion section:
    # the same as an explicit steady motion, and as the scene written before motion: existed
    assert "motion" not in table1.canonical_yaml()
    assert lc.load_scene(TABLE1, {"motion.kind": "steady"}).hash == table1.hash
    stop = lc.load_scene(TABLE1, {"motion.kind": "stop"})
    assert stop.hash != table1.hash and "motion" in stop.canonical_yaml()
    assert lc.load_scene(stop) == stop


def test_bad_motion_is_refused_naming_the_key():
    with pytest.raises(lc.SceneError) as err:
        lc.load_scene(TABLE1, {"motion.kind": "stpo", "motion.ramp": -1, "motion.reconnect_factor": 0.5})
    text = str(err.value)
    assert "motion.kind = 'stpo'" in text and "did you mean 'stop'" in text
    assert "motion.ramp = -1" in text and "motion.reconnect_factor = 0.5" in text
    with pytest.raises(lc.SceneError, match="motion.table is missing"):
        lc.load_scene(TABLE1, {"motion.kind": "table"})
    with pytest.raises(lc.SceneError, match="motion.table"):
        lc.load_scene(TABLE1, {"motion.kind": "table", "motion.table": [[0.1, 1.0], [0.2, 0.0]]})


def test_speed_histories():
    stop = SpeedHistory.from_scene(lc.load_scene(TABLE1, {"motion.kind": "stop", "motion.speed": 2.0,
                                                           "motion.stop_time": 1.0, "motion.ramp": 0.5}))
    assert [stop.speed(t) for t in (0.0, 1.0, 1.25, 1.5, 9.0)] == [2.0, 2.0, 1.0, 0.0, 0.0]
    assert stop.rest_from == 1.5 and stop.end == 11.0
    jump = SpeedHistory.from_scene(lc.load_scene(TABLE1, {"motion.kind": "stop", "motion.ramp": 0.0}))
    assert jump.initial_speed() == 0.1 and jump.speed(0.0) == 0.0  # operating.speed, then at rest
    osc = SpeedHistory.from_scene(lc.load_scene(TABLE1, {"motion.kind": "oscillation", "motion.amplitude": 1e-3,
                                                          "motion.frequency": 2.0, "motion.cycles": 2}))
    # x = A (1 - cos 2 pi f t): U = 2 pi f A sin(2 pi f t), at rest after two cycles
    assert osc.speed(0.125) == pytest.approx(2 * math.pi * 2.0 * 1e-3)
    assert osc.speed(0.0) == 0.0 and osc.speed(1.2) == 0.0 and osc.rest_from == 1.0
    table = SpeedHistory.from_scene(lc.load_scene(TABLE1, {"motion.kind": "table",
                                                            "motion.table": [[0, 1.0], [1, 3.0], [2, 0.0]]}))
    assert [table.speed(t) for t in (0.5, 1.5, 5.0)] == [2.0, 1.5, 0.0] and table.rest_from == 2.0


def test_bdf2_coefficients_and_error_constants_at_constant_step():
    # constant-step BDF2: (3/2, -2, 1/2)/h; local error (2/9) h^3 y''' against the quadratic
    # predictor's -h^3 y''': the error is 2/11 of their difference; BDF1 1/3 (h^2/2 vs h^2)
    assert bdf_coefficients([0.1, 0.1]) == pytest.approx([15.0, -20.0, 5.0])
    assert error_fraction([0.1, 0.1, 0.1]) == pytest.approx(2 / 11)
    assert error_fraction([0.1, 0.1]) == pytest.approx(1 / 3)


@pytest.mark.parametrize("power", [1.0, 2.0, 3.0])
def test_a_rejected_step_follows_the_error_it_observed(power):
    # an error estimate E = C dt^power: a smooth film's BDF2 gives power 3, a kink within the
    # step (a pocket sealing) power 1. The first rejection assumes 3; the second reads the power
    # off the two attempts and lands where E = SAFETY^power, as the first does on a smooth film
    def error(dt):
        return 5.0 * (dt / 1e-3) ** power

    first = 1e-3 * rejection_factor(1e-3, error(1e-3), 2, None)
    assert first == pytest.approx(1e-3 * SAFETY * 5.0 ** (-1 / 3))
    if error(first) <= 1.0:  # power 3: the first cut already passes
        assert power == 3.0 and error(first) == pytest.approx(SAFETY ** 3)
        return
    second = first * rejection_factor(first, error(first), 2, (1e-3, error(1e-3)))
    assert error(second) == pytest.approx(SAFETY ** power)
    # no faster than the BDF's own order, and a cut by SHRINK where the error did not fall
    assert rejection_factor(first, 2.0, 2, (1e-3, 1.5)) == SHRINK
    assert rejection_factor(5e-4, 1.01, 2, (1e-3, 100.0)) == pytest.approx(SAFETY * 1.01 ** (-1 / 3))


def test_rigid_smooth_cylinder_follows_the_analytic_squeeze_law():
    # docs/physics.md section 14: h0^(-1/2)(t) = h_i^(-1/2) + w' t / (6 sqrt(2) pi mu R^(3/2)) from the
    # end of the ramp, where the film left by 1 m/s sliding (0.41 um) has 2 % of its load left
    ds = lc.transient(scene(SMOOTH_STOP, **{"motion.tolerance": 1e-5}))
    assert ds["converged"].item() == 1
    t, h = ds["time"].values, ds["min_film_thickness"].values
    after = t >= 1e-4
    t, h = t[after], h[after]
    assert t[0] == 1e-4 and h[-1] < h[0] / 15  # the law is tested down to 20 nm
    prefactor = 5000.0 / (6 * math.sqrt(2) * math.pi * 0.1 * 0.01**1.5)
    analytic = (h[0] ** -0.5 + prefactor * (t - t[0])) ** -2
    assert np.max(np.abs(h / analytic - 1)) < 0.01
    assert np.all(ds["contact_force"].values == 0.0)


def test_shrinking_ramps_converge_to_the_jump():
    # the film 2 ms after the stop begins: the ramp's effect vanishes linearly with its length
    films = []
    for ramp in (4e-4, 2e-4, 1e-4, 0.0):
        ds = lc.transient(scene(SMOOTH_STOP, **{"motion.ramp": ramp, "motion.duration": 2e-3}))
        films.append(ds["min_film_thickness"].values[-1])
    gaps = np.abs(np.array(films[:-1]) - films[-1])
    assert gaps[0] > gaps[1] > gaps[2] > 0
    assert gaps[1] / gaps[2] == pytest.approx(2.0, rel=0.25)


def test_steady_motion_reproduces_the_steady_solve():
    s = lc.load_scene(TABLE1, {"mesh.ny": 1, "mesh.nx": 31, "operating.speed": 0.3, "motion.duration": 1.0})
    ds = lc.transient(s)
    steady = lc.solve(s)
    assert ds["converged"].item() == 1 and ds["time"].values[-1] == 1.0
    assert math.isnan(ds["reconnect_time"].item())
    for name in ("contact_resistance", "min_film_thickness", "fluid_force", "contact_force", "friction_coefficient"):
        np.testing.assert_allclose(ds[name].values, steady[name].item(), rtol=1e-5, err_msg=name)


@pytest.fixture(scope="module")
def rough_stops():
    """reconnect times (s) and step counts of the rough stop at three time tolerances"""
    runs = {tol: lc.transient(scene(ROUGH_STOP, **{"motion.tolerance": tol})) for tol in (1e-3, 1e-4, 1e-5)}
    return runs


def test_time_step_convergence_order_on_the_reconnect_time(rough_stops):
    # error of each run against the tightest, against its number of steps: BDF2 -> N^-2
    reference = rough_stops[1e-5]["reconnect_time"].item()
    loose, tight = rough_stops[1e-3], rough_stops[1e-4]
    errors = [abs(ds["reconnect_time"].item() - reference) for ds in (loose, tight)]
    steps = [ds["steps"].item() for ds in (loose, tight)]
    order = math.log(errors[0] / errors[1]) / math.log(steps[1] / steps[0])
    assert 1.5 < order < 3.5


def test_the_default_tolerance_is_within_five_percent_on_the_reconnect_time(rough_stops):
    """Issue 28's target on the rigid 31-node stop: the default tolerance (1e-3) within 5 % of
    1e-5. It was 7.7 % short while the steps at rest kept the inlet of 1 m/s, whose films
    diluted the error norm; on the domain at rest it is 4.7 % (docs/physics.md section 14,
    "The domain at rest")."""
    reference = rough_stops[1e-5]["reconnect_time"].item()
    assert abs(rough_stops[1e-3]["reconnect_time"].item() - reference) < 0.05 * reference


def test_stop_reconnects_and_the_full_film_volume_balance_closes(rough_stops):
    ds = rough_stops[1e-4]
    assert ds["converged"].item() == 1 and np.all(ds["step_converged"].values == 1)
    rest = ds["rest_resistance"].item()
    resistance = ds["contact_resistance"].values
    assert resistance[0] > 10 * rest  # lifted by the 1 m/s film
    assert resistance[-1] == pytest.approx(rest, rel=1e-3)  # settled at rest
    recon = ds["reconnect_time"].item()
    assert 0.0 < recon < 0.02
    t = ds["time"].values
    first = np.flatnonzero((t >= 1e-3) & (resistance <= 2 * rest))[0]
    assert t[first - 1] - 1e-3 <= recon <= t[first] - 1e-3
    # the threshold moved a tenth either way (1.8 and 2.2 times the rest's): each crossing lies
    # between the levels that bracket it, in order about the reconnect time, and the summary
    # gives them
    lower, higher = ds["reconnect_time_lower_threshold"].item(), ds["reconnect_time_higher_threshold"].item()
    for value, share in ((lower, 1.8), (higher, 2.2)):
        first = np.flatnonzero((t >= 1e-3) & (resistance <= share * rest))[0]
        assert t[first - 1] - 1e-3 <= value <= t[first] - 1e-3
    assert higher < recon < lower and ds["reconnect_time_lower_threshold"].attrs["units"] == "s"
    assert f"reconnect_time_lower_threshold = {lower:.6g} s (the threshold 10% down" in summary(ds)
    # every step: net outflow of the pressurised region (face fluxes) = minus its volume change,
    # to the step's nonlinear tolerance: the one Newton that answers a line contact's step stops
    # at 0.001 of its error weight (integrator.LINE_NEWTON_FRACTION), well below the step's own
    # tolerance (without its outflow test the balance was off by 0.16 on a line, docs/physics.md
    # section 20)
    assert np.max(np.abs(ds["volume_balance"].values)) < 0.1 * 1e-4
    assert np.all(ds["error_estimate"].values <= 1.0)


def test_thicker_oil_and_lighter_load_wait_longer():
    # squeeze flow ~ h^3/mu against a load F: the approach slows with mu and speeds up with F
    times = {}
    for key, value in (("lubricant.viscosity", 0.05), ("lubricant.viscosity", 0.2), ("operating.force", 10.0)):
        times[key, value] = lc.transient(scene(ROUGH_STOP, **{key: value, "motion.tolerance": 1e-2}))["reconnect_time"].item()
    base = lc.transient(scene(ROUGH_STOP, **{"motion.tolerance": 1e-2}))["reconnect_time"].item()
    assert times["lubricant.viscosity", 0.05] < base < times["lubricant.viscosity", 0.2]
    assert times["operating.force", 10.0] < base


def test_reconnect_time_and_oscillation_metrics_from_series():
    # R(t) = 100 for t <= 1, then 100 exp(-(t - 1)^2 ln 10) (10 at t = 2, 1e-7 at t = 4):
    # the crossing of R = 50 is at t = 1 + sqrt(log10 2), which neither a linear nor a
    # log-linear interpolation of the levels gives
    def exact(t):
        return 100.0 * 10.0 ** (-max(t - 1.0, 0.0) ** 2)

    t = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    r = np.array([exact(ti) for ti in t])

    def dense(step, ti):  # the integrator's dense output, exact here
        return exact(ti)

    assert reconnect_time(t, r, 1.0, 10.0, dense) == pytest.approx(1.0)
    assert reconnect_time(t, r, 1.0, 50.0, dense) == pytest.approx(math.sqrt(math.log10(2.0)), rel=1e-8)
    assert reconnect_time(t, r, 1.0, 50.0, dense) != pytest.approx(math.log10(2.0), rel=1e-3)  # log-linear's
    assert reconnect_time(t, r, 2.0, 20.0, dense) == 0.0  # below the threshold when the motion stops
    assert reconnect_time(t, r, 1.0, 1e-9, dense) == math.inf
    assert math.isnan(reconnect_time(t, r, None, 10.0, dense))
    # the threshold moved a tenth either way: R = 45 and 55, crossed at 1 + sqrt(log10(100 / R))
    shifted = threshold_times(t, r, 1.0, 50.0, dense)
    assert THRESHOLD_SHIFT == 0.1
    assert shifted["reconnect_time_lower_threshold"] == pytest.approx(math.sqrt(math.log10(100.0 / 45.0)), rel=1e-8)
    assert shifted["reconnect_time_higher_threshold"] == pytest.approx(math.sqrt(math.log10(100.0 / 55.0)), rel=1e-8)
    assert threshold_times(t, r, 1.0, 1e-9, dense)["reconnect_time_higher_threshold"] == math.inf
    # the open fraction comes from the located events (tests/test_events.py)
    assert cycle_peaks(t, np.array([0.5, 2.0, 0.5, 3.0, 0.1]), 2.0, 2).tolist() == [2.0, 3.0]


def test_slow_oscillation_peaks_at_the_steady_resistance_of_its_peak_speed():
    # quasi-static limit: at 2 Hz the film (ms response) follows U(t); peak U = 2 pi f A = 1 m/s
    base = {"mesh.ny": 1, "mesh.nx": 31, "effects.elastic_deformation": False}
    ds = lc.transient(scene(base, **{"motion.kind": "oscillation", "motion.frequency": 2.0, "motion.cycles": 1,
                                     "motion.amplitude": 1 / (4 * math.pi), "motion.duration": 0.6}))
    # on the motion's long inlet (a steady solve's default is the far inlet, docs/physics.md section 17)
    steady = lc.solve(scene(base, **{"operating.speed": 1.0, "mesh.far_inlet": False}))["contact_resistance"].item()
    assert ds["converged"].item() == 1 and ds["peak_resistance"].size == 1
    assert ds["peak_resistance"].item() == pytest.approx(steady, rel=0.01)
    assert ds["open_fraction"].item() == 0.0  # Table 1 stays far below the 1 ohm threshold
    assert ds["contact_resistance"].values[-1] == pytest.approx(ds["rest_resistance"].item(), rel=1e-3)


def test_cli_transient_writes_the_series_and_exits_3_when_a_step_fails(tmp_path, capsys):
    import xarray as xr

    from lubecontact.cli.main import main

    common = ["transient", TABLE1, "--set", "mesh.ny=1", "--set", "mesh.nx=31", "--set", "motion.kind=stop",
              "--set", "motion.duration=0.02", "--set", "operating.speed=1.0", "--set", "motion.tolerance=1e-2"]
    out = tmp_path / "series.nc"
    assert main(common + ["--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "reconnect_time" in printed
    assert "open_fraction = nan: only an oscillation has one (motion.kind = stop)" in printed  # a NaN says why
    with xr.open_dataset(out) as ds:
        assert ds["time"].attrs["units"] == "s" and ds["reconnect_time"].attrs["units"] == "s"
        assert all("units" in ds[name].attrs and "long_name" in ds[name].attrs for name in ds.data_vars)
        assert ds.attrs["scene_hash"] == lc.load_scene(TABLE1, {
            "mesh.ny": 1, "mesh.nx": 31, "motion.kind": "stop", "motion.duration": 0.02, "operating.speed": 1.0,
            "motion.tolerance": 1e-2}).hash
        assert 0.0 < ds["reconnect_time"].item() < 0.02
        # validity along time, as a steady case has it (issue 29 item 8): per instant and in words
        assert ds["valid"].dtype.kind == "i" and ds["valid"].attrs["units"] == "1"
        raised = ds.attrs["validity"].split(",")
        assert (ds["valid"].values == 0).any() == (raised != ["ok"])
        assert [line.split(":")[0] for line in ds.attrs["validity_notes"].splitlines()] == [f for f in raised if f != "ok"]
    assert all(f"validity {flag}: from t =" in printed for flag in raised if flag != "ok")
    failed = tmp_path / "failed.nc"
    assert main(common + ["--set", "solver.max_iterations=1", "--out", str(failed)]) == 3
    assert "reconnect_time = nan: the run ended before the contact reconnected" in capsys.readouterr().out
    with xr.open_dataset(failed) as ds:
        assert ds["converged"].item() == 0 and "NOT CONVERGED" in ds.attrs["notes"]
    assert main(common + ["--set", "motion.kind=spin", "--out", str(tmp_path / "bad.nc")]) == 2
    assert not (tmp_path / "bad.nc").exists()


def test_gallery_stops_grease_waits_far_longer_than_oil():
    # the two stop scenes of config/scenes, as rigid coarse line contacts: same contact and
    # film-forming history scaled by mu; after the stop the squeeze time scales with mu
    coarse = {"mesh.nx": 31, "mesh.ny": 1, "effects.elastic_deformation": False, "motion.tolerance": 1e-2}
    oil = lc.transient(lc.load_scene("config/scenes/stop_hydrocarbon_oil.yaml", coarse))
    grease = lc.transient(lc.load_scene("config/scenes/stop_grease.yaml", coarse))
    assert oil["converged"].item() == grease["converged"].item() == 1
    ratio = grease["reconnect_time"].item() / oil["reconnect_time"].item()
    assert 10.0 < ratio < 10.0 / 0.087 * 3


def test_start_settles_at_the_steady_sliding_state_and_a_table_matches_it():
    base = {"mesh.nx": 31, "mesh.ny": 1, "effects.elastic_deformation": False, "motion.duration": 0.05,
            "motion.tolerance": 1e-2}
    start = lc.transient(scene(base, **{"motion.kind": "start", "motion.speed": 1.0, "motion.ramp": 1e-3}))
    table = lc.transient(scene(base, **{"motion.kind": "table", "motion.table": [[0.0, 0.0], [1e-3, 1.0]]}))
    sliding = lc.solve(scene(base, **{"operating.speed": 1.0, "mesh.far_inlet": False}))  # the motion's inlet
    flooded = lc.solve(scene(base, **{"operating.speed": 1.0}))  # the default: the far inlet
    assert start["converged"].item() == 1 and start["contact_resistance"].values[0] == pytest.approx(
        start["rest_resistance"].item(), rel=1e-6)
    assert start["contact_resistance"].values[-1] == pytest.approx(sliding["contact_resistance"].item(), rel=1e-3)
    # the long inlet's shortfall: 1.2 % in the resistance of this rigid line at 1 m/s
    assert flooded["contact_resistance"].item() == pytest.approx(sliding["contact_resistance"].item(), rel=0.02)
    assert math.isnan(start["reconnect_time"].item())
    np.testing.assert_allclose(table["contact_resistance"].values, start["contact_resistance"].values, rtol=1e-9)


def test_a_relative_table_file_is_read_beside_the_scene(tmp_path, monkeypatch):
    """motion.table as a file name is taken from the scene file's directory, as a relative
    roughness.surface is, whatever the working directory (issue 29 item 7)."""
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    (scenes / "speeds.txt").write_text("0 1.0\n1 3.0\n2 0.0\n")
    (scenes / "s.yaml").write_text("motion: {kind: table, table: speeds.txt}\n")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    scene = lc.load_scene(str(scenes / "s.yaml"))
    assert scene.motion.table == ((0.0, 1.0), (1.0, 3.0), (2.0, 0.0))
    (elsewhere / "speeds.txt").write_text("0 5.0\n1 0.0\n")  # a file of that name here is not read
    assert lc.load_scene(str(scenes / "s.yaml")).motion.table == scene.motion.table
    assert lc.load_scene(str(scenes / "s.yaml"), {"motion.table": "speeds.txt"}).hash == scene.hash


def test_a_transient_reports_progress_and_keeps_its_series_when_terminated(tmp_path):
    """Off a terminal a line per decade of simulated time reaches stderr; SIGTERM (or Ctrl-C)
    ends the run with the series so far written beside --out (NAME.interrupted.nc), flagged,
    exit 130 (issue 29 item 3); --out, here an earlier result, is left as it was."""
    import signal
    import subprocess
    import sys

    import xarray as xr

    out = tmp_path / "series.nc"
    out.write_bytes(b"an earlier complete result")
    cmd = [sys.executable, "-m", "lubecontact.cli.main", "transient", TABLE1, "--set", "mesh.nx=31", "--set", "mesh.ny=1",
           "--set", "motion.kind=stop", "--set", "motion.duration=10", "--set", "motion.tolerance=1e-5", "--out", str(out)]
    run = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    seen = []
    for line in run.stderr:  # progress, a line per decade, before the run is over
        seen.append(line)
        if "t = 1e-04 s of 10 s reached" in line:
            run.send_signal(signal.SIGTERM)
            break
    rest, last = run.communicate(timeout=120)
    assert run.returncode == 130, "".join(seen) + rest + last
    assert [line.split(" s of")[0].split("= ")[1] for line in seen] == ["1e-09", "1e-08", "1e-07", "1e-06", "1e-05", "1e-04"]
    assert out.read_bytes() == b"an earlier complete result" and "--out was not written" in last
    with xr.open_dataset(tmp_path / "series.interrupted.nc") as ds:
        assert ds.attrs["interrupted"] == 1 and ds["converged"].item() == 0 and "interrupted at t =" in ds.attrs["notes"]
        assert ds["time"].size > 10 and ds["time"].values[-1] >= 1e-4


def test_a_stuck_step_gives_up_after_a_few_attempts(monkeypatch):
    """Every time step fails: the run stops after MAX_FAILED_IN_A_ROW attempts at one step,
    not after quartering dt down to 1e-15 s (55 attempts), and says so."""

    attempts = []

    def failing(self, levels, t_new, order, **options):
        attempts.append(t_new - levels[-1].time)
        return None, "forced failure"

    monkeypatch.setattr(integrator.TimeIntegrator, "step", failing)
    scene = lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.duration": 0.02})
    series = lc.transient(scene, progress=False)
    assert series["converged"].item() == 0 and len(attempts) == integrator.MAX_FAILED_IN_A_ROW
    assert attempts == pytest.approx([attempts[0] / 4**k for k in range(len(attempts))], abs=0.0)
    assert f"({integrator.MAX_FAILED_IN_A_ROW} attempt(s) in a row): forced failure" in series.attrs["notes"]
    assert "pocket" not in series.attrs["notes"]  # the sliding film at 1 m/s has none (integrator.sealing_pocket)


def test_a_singular_factor_in_a_step_is_a_failed_solve_not_a_crash(monkeypatch):
    """SuperLU raises RuntimeError on an exactly singular factor. Inside a step's nested
    solve it is a failed nested solve (the Newton's fallback answers the step, or it is
    retried shorter), not an exception that ends the run. On a 2-D mesh, where the nested
    solve answers a step first (a line contact's step is the Newton's)."""
    real_solve = integrator.coupled_solve
    raised = []

    def singular_once(model, initial, **limits):
        if model.squeeze is not None and not raised:
            raised.append(True)
            raise RuntimeError("Factor is exactly singular")
        return real_solve(model, initial, **limits)

    monkeypatch.setattr(integrator, "coupled_solve", singular_once)
    scene = lc.load_scene(TABLE1, {"mesh.nx": 15, "mesh.ny": 7, "motion.kind": "stop", "motion.duration": 0.02,
                                   "motion.mesh_error_bar": False})
    series = lc.transient(scene, progress=False)
    assert raised and series["converged"].item() == 1


def test_a_creeping_run_stops_once_its_steps_are_far_below_what_accuracy_asks(monkeypatch):
    """From t = 1e-5 s on, two of every three attempts fail: dt shrinks fourfold a cycle, with
    steps accepted in between (the R = 5 mm stop at 51 x 51 crept so from 1e-5 to 1e-15 s
    steps over 48 failed solves). The run stops at the first failure on a step shorter than
    motion.tolerance times the step the error test last asked for, and says so."""

    real_step = integrator.TimeIntegrator.step
    attempts = []

    def creeping(self, levels, t_new, order, **options):
        if levels[-1].time < 1e-5:
            return real_step(self, levels, t_new, order, **options)
        attempts.append(t_new - levels[-1].time)
        if len(attempts) % 3:
            return None, "forced failure"
        return real_step(self, levels, t_new, order, **options)

    monkeypatch.setattr(integrator.TimeIntegrator, "step", creeping)
    scene = lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.duration": 0.02})
    series = lc.transient(scene, progress=False)
    notes = series.attrs["notes"]
    assert series["converged"].item() == 0 and "the error test last asked for" in notes
    asked = float(notes.split("times the ")[1].split(" s the error test last asked for")[0])  # 3 digits
    limit = scene.motion.tolerance * asked
    failed = [dt for k, dt in enumerate(attempts, start=1) if k % 3]
    # the first failure below the limit ends the run; a creep to MIN_STEP took ~45 attempts
    assert failed[-1] < 1.01 * limit and min(failed[:-1]) > 0.99 * limit
    assert len(attempts) < 20


# Table 1 stopped from its speed on the 31-node line, 5 ms; and with a Bingham grease of 2 kPa
# on +-1 mm under 2 N, stopped from 1 m/s (the two tests below)
SHORT_STOP = {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.duration": 0.005}
GREASE_STOP = {**SHORT_STOP, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3, "operating.speed": 1.0, "operating.force": 2.0,
               "lubricant.rheology": "bingham", "lubricant.yield_stress": 2000.0, "lubricant.creep_viscosity": 1e8}


def test_a_solver_limit_on_a_grease_at_rest_costs_a_failed_solve_per_four_accepted_steps_at_most(monkeypatch):
    """Every attempted step longer than ``limit`` fails its solve (as a Bingham grease at rest
    fails beyond a step that grows with time). Retrying at a quarter and growing fourfold again
    failed about once per accepted step (67 failures for 90 steps on this grease stop); with
    the ceiling at rest at half the failed step, doubled by each accepted step that reaches it,
    once per two or three (48 for 133); doubled once its patience of steps have reached it, the
    patience doubled by each failure (integrator.StepCeiling), 16 for 118. A Newtonian film
    keeps the old rule (the ceiling drove the accuracy study's 201 x 21 stop into a sealing
    pocket's impasse): 74 failures for 89 steps on the Table 1 stop."""
    limit = 2e-4
    real_step = integrator.TimeIntegrator.step

    def counted(scene):
        outcomes = []

        def limited(self, levels, t_new, order, **options):
            if t_new - levels[-1].time > limit:
                outcomes.append(False)
                return None, "forced failure"
            level, outcome = real_step(self, levels, t_new, order, **options)
            outcomes.append(level is not None)
            return level, outcome

        monkeypatch.setattr(integrator.TimeIntegrator, "step", limited)
        series = lc.transient(scene, progress=False)
        assert series["converged"].item() == 1
        assert np.all(np.diff(series["time"].values) <= limit)
        return outcomes.count(False), outcomes.count(True)

    failed, accepted = counted(lc.load_scene(TABLE1, GREASE_STOP))
    assert 0 < failed <= 0.25 * accepted
    failed, accepted = counted(lc.load_scene(TABLE1, SHORT_STOP))
    assert failed > 0.5 * accepted


def test_a_grease_at_rest_steps_back_from_a_level_no_step_starts_from(monkeypatch):
    """integrator.TimeIntegrator.run: where every step from an accepted level of a grease at
    rest fails (the tight Bingham stop of tests/test_hard_cases.py reached such states from
    7.58 ms on), the run drops that level and steps again from the one before it, at half the
    dropped step, each return to a later level than the last, and names each dropped level
    in its notes (step_backs). A Newtonian film's run ends there, saying why."""
    real_step = integrator.TimeIntegrator.step
    dead = []  # the time of the level no step starts from: the first accepted after 2 ms

    def dead_end(self, levels, t_new, order, **options):
        if dead and levels[-1].time == dead[0]:
            return None, "forced dead end"
        level, outcome = real_step(self, levels, t_new, order, **options)
        if level is not None and not dead and level.time > 2e-3:
            dead.append(level.time)
        return level, outcome

    monkeypatch.setattr(integrator.TimeIntegrator, "step", dead_end)
    series = lc.transient(lc.load_scene(TABLE1, GREASE_STOP), progress=False)
    assert series["converged"].item() == 1 and series["time"].values[-1] == pytest.approx(0.005)
    assert dead and dead[0] not in series["time"].values
    assert series["step_backs"].item() >= 1 and f"the level at t = {dead[0]:.6g} s, back to" in series.attrs["notes"]
    dead.clear()
    series = lc.transient(lc.load_scene(TABLE1, SHORT_STOP), progress=False)
    assert series["converged"].item() == 0 and "forced dead end" in series.attrs["notes"]
    assert series["time"].values[-1] == dead[0] and series["step_backs"].item() == 0


def ceiling_run(limit_at, steps: int = 400) -> tuple[int, float]:
    """A model of the run's loop at rest against a solver whose step limit at time t is
    limit_at(t): the controller asks for fourfold growth, integrator.StepCeiling bounds it, a
    step beyond the limit fails and is retried at a quarter. (failed solves, mean ratio of
    the last 100 accepted steps to the limit)."""
    ceiling, t, last, failures, ratios = integrator.StepCeiling(), 0.0, 1e-3, 0, []
    while len(ratios) < steps:
        dt = ceiling.limit(4.0 * last)
        while dt > limit_at(t):
            failures += 1
            ceiling.solve_failed(dt, last)
            dt *= 0.25
        ratios.append(dt / limit_at(t))
        t, last = t + dt, dt
        ceiling.accepted(dt)
    return failures, sum(ratios[-100:]) / 100


def test_a_step_ceiling_probes_a_limit_that_stays_put_ever_more_rarely_and_follows_one_that_grows():
    """integrator.StepCeiling against a step limit that stays put: each failed probe doubles
    the patience, so 400 accepted steps cost about log2(400) failures (8), where a probe at every
    other step failed 198 times and kept the steps at 0.38 of the limit; against limits that
    grow linearly with time, a few failures per hundred steps, at half the limit or more."""
    failures, ratio = ceiling_run(lambda t: 1.0)
    assert failures <= 12 and ratio >= 0.45
    for rate in (0.1, 0.01):
        failures, ratio = ceiling_run(lambda t, rate=rate: 1.0 + rate * t)
        assert failures <= 40 and ratio >= 0.45


def line_stop(tolerance=1e-3):
    return lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.speed": 1.0,
                                  "motion.duration": 0.02, "motion.tolerance": tolerance})


def test_at_rest_a_stop_steps_on_the_mesh_at_rest():
    """The mesh of a stop from 1 m/s carries the inlet of that speed (48 columns on the
    31-node line). At rest its steps move to the mesh at rest (numerics/mesh.rest_mesh: the
    domain symmetric about the contact, motion.rest_refinement times finer), once the nodes
    outside it carry less than motion.tolerance of the load, and stay there; the dense output
    of the first step at rest runs through levels on both meshes."""
    scene = line_stop()
    history = SpeedHistory.from_scene(scene)
    runner = integrator.TimeIntegrator(scene, history)
    rest_model = runner.rest_domain()
    levels, failure = runner.run()
    assert not failure and runner.steady_model.mesh.nx == 48
    at_rest = rest_model.mesh.nx
    switch = next(k for k, level in enumerate(levels) if level.model.mesh.nx == at_rest)
    assert levels[switch - 1].time >= history.rest_from
    assert abs(runner.outside_load(levels[switch - 1], rest_model)) <= scene.motion.tolerance
    assert all(level.model.mesh.nx == at_rest for level in levels[switch:])
    assert all(level.model.mesh is runner.steady_model.mesh for level in levels[:switch])
    midway = 0.5 * (levels[switch - 1].time + levels[switch].time)
    assert np.isfinite(dense_resistance(levels)(switch, midway))


def test_a_run_ends_at_the_first_level_its_until_holds_for_and_is_the_whole_run_up_to_there():
    """TimeIntegrator.run(until=...): no failure, the first accepted level at or past the
    time asked for is the last, and every level before it is the whole run's."""
    scene = line_stop()
    history = SpeedHistory.from_scene(scene)
    whole, _ = integrator.TimeIntegrator(scene, history).run()
    levels, failure = integrator.TimeIntegrator(scene, history).run(until=lambda level: level.time >= 2e-3)
    assert failure == "" and levels[-1].time >= 2e-3 > levels[-2].time
    assert [level.time for level in levels] == [level.time for level in whole[:len(levels)]]
    assert np.array_equal(levels[-1].state.film, whole[len(levels) - 1].state.film)


def test_a_refined_mesh_at_rest_gives_the_reconnect_time_of_a_refined_mesh():
    """The reconnect time's mesh error is made at rest, where the film drains from the contact
    (docs/physics.md section 14, "The mesh at rest"): the Table 1 line stop on 61 nodes with
    its mesh at rest twice as fine reconnects within 1 % of the stop on 121 nodes throughout,
    less than half as far off as on 61 nodes throughout (measured at motion.tolerance 1e-4:
    14.69 and 14.56 against 14.75 ms)."""
    def reconnect(nodes, refinement):
        scene = lc.load_scene(TABLE1, {"mesh.nx": nodes, "mesh.ny": 1, "motion.kind": "stop", "motion.speed": 1.0,
                                       "motion.duration": 0.03, "motion.tolerance": 1e-4,
                                       "motion.rest_refinement": refinement, **ONE_RUN})
        ds = lc.transient(scene, progress=False)
        assert int(ds.converged) == 1
        return ds["reconnect_time"].item()

    fine = reconnect(121, 1)
    refined_at_rest, coarse = abs(reconnect(61, 2) / fine - 1.0), abs(reconnect(61, 1) / fine - 1.0)
    assert refined_at_rest < 0.01 and refined_at_rest < 0.5 * coarse


@functools.cache
def line_stop_reconnect(nodes: int, refinement: int, tolerance: float, norm: str = "rms") -> float:
    """reconnect_time (s) of the Table 1 line stop from 1 m/s on ``nodes`` nodes with its
    mesh at rest ``refinement`` times as fine, at motion.tolerance ``tolerance`` in ``norm``."""
    scene = lc.load_scene(TABLE1, {"mesh.nx": nodes, "mesh.ny": 1, "motion.kind": "stop", "motion.speed": 1.0,
                                   "motion.duration": 0.03, "motion.rest_refinement": refinement,
                                   "motion.tolerance": tolerance, "motion.error_norm": norm, **ONE_RUN})
    ds = lc.transient(scene, progress=False)
    assert int(ds.converged) == 1
    return ds["reconnect_time"].item()


def test_the_max_norm_holds_the_tolerance_on_a_finer_mesh_at_rest():
    """Where a pocket of the film seals, a step's error is one node's own, and the root mean
    square over the nodes divides it by the root of their count: on the Table 1 line stop
    with its mesh at rest eight times as fine (241 nodes), the default motion.tolerance
    (1e-3) in the RMS norm reconnects 5 % early (14.08 ms against 14.84 ms at a tolerance ten
    times tighter; 22 % before a sealed cell's rate was made exact, bdf_history).
    motion.error_norm = max holds the tolerance on any mesh: at 1e-3 it reconnects within
    1 % of the tight run (14.85 ms), several times nearer than the RMS norm."""
    tight = line_stop_reconnect(51, 8, 1e-4)
    off_max = abs(line_stop_reconnect(51, 8, 1e-3, "max") / tight - 1.0)
    assert off_max < 0.01
    assert abs(line_stop_reconnect(51, 8, 1e-3) / tight - 1.0) > 3.0 * off_max


def test_a_sealed_cell_keeps_its_volume_through_the_seal():
    """BDF2's difference through a seal gives a cell sealed at the last level the rate
    c2 (h_T^{n-1} - h_T^n) > 0, a flow into a content that is frozen, destroying half a step's
    outflow at every seal; the longer the steps over the seals (the RMS norm on a fine mesh),
    the faster the film drains. With the sealed cell's rate exact (integrator.bdf_history)
    the 401-node line stop at the default motion.tolerance reconnects within 3 % of the run
    on 51 nodes with its mesh at rest eight times as fine at a tolerance ten times tighter
    (14.58 against 14.84 ms; 11.56 ms before, 22 % early)."""
    tight = line_stop_reconnect(51, 8, 1e-4)
    assert abs(line_stop_reconnect(401, 1, 1e-3) / tight - 1.0) < 0.03


def test_the_history_of_a_sealed_cell_gives_it_no_rate():
    """integrator.bdf_history against BDF2's rate written out (variable steps, Hairer, Norsett
    & Wanner III.5): a cell open at every level keeps BDF2's rate; a cell that sealed at the last
    level (content frozen, Level.sealed) has rate 0 at the next step while it stays sealed,
    where BDF2 gives c2 (h_T^{n-1} - h_T^n) > 0; a cell that reopens gets c0 times its content's
    change since the last level."""
    dt, previous = 1e-4, 2e-4
    c = bdf_coefficients([dt, previous])
    omega = dt / previous
    assert c[0] == pytest.approx((1 + 2 * omega) / (1 + omega) / dt)
    frozen, older = 0.4, np.array([[0.9, 0.7, 0.6]])
    last = np.array([[0.8, frozen, frozen]])
    levels = [SimpleNamespace(expected_gap=older, sealed=np.zeros((1, 3), bool)),
              SimpleNamespace(expected_gap=last, sealed=np.array([[False, True, True]]))]
    history = integrator.bdf_history(c, levels)
    new = np.array([[0.75, frozen, 0.5]])
    rate = c[0] * new + history
    assert rate[0, 0] == pytest.approx(c[0] * 0.75 + c[1] * 0.8 + c[2] * 0.9, rel=1e-12)
    assert rate[0, 1] == 0.0 and c[0] * frozen + c[1] * frozen + c[2] * 0.7 > 0.0
    assert rate[0, 2] == pytest.approx(c[0] * (0.5 - frozen), rel=1e-12)


def test_a_jump_tries_its_long_steps_first_then_shorter_ones():
    """integrator.impasse_lengths: 4, 16, ... 4^IMPASSE_PROBES times the asked step first (a
    run whose jumps converge so keeps its steps), then the failed step's multiples below the
    first of those, shortest first; none where the failed step is the asked one."""
    probes = integrator.IMPASSE_PROBES
    long = [1e-3 * 4.0 ** k for k in range(1, probes + 1)]
    # 4^6 x 1e-6 = 4.1e-3 is not shorter than the first long step, 4e-3
    assert integrator.impasse_lengths(1e-3, 1e-6) == pytest.approx(long + [1e-6 * 4.0 ** k for k in range(1, probes)])
    assert integrator.impasse_lengths(1e-3, 1e-4) == pytest.approx(long + [4e-4, 1.6e-3])
    assert integrator.impasse_lengths(1e-3, 1e-3) == pytest.approx(long)


def test_a_step_error_is_the_rms_or_the_largest_of_its_nodes():
    """integrator.step_error: one node's error e among n others at zero is e/sqrt(n + 1) in
    the RMS norm and e in the max norm, whatever its sign."""
    scaled = np.zeros(100)
    scaled[37] = -3.0
    assert integrator.step_error(scaled, "rms") == pytest.approx(0.3, rel=1e-12)
    assert integrator.step_error(scaled, "max") == 3.0


def test_a_reconnect_time_says_it_rests_on_the_flow_below_patir_cheng():
    """The Table 1 stop drains through h/sigma < 0.5 before it reconnects: its notes say from
    when (the instant the validity flag flow_factor_range is first raised, before the
    reconnect) and which run brackets it (transient.band_note); a run with the other exponent
    points back; a motion that never stops has no reconnect time and no such note."""
    base = {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.speed": 1.0, "motion.duration": 0.02}
    scene = lc.load_scene(TABLE1, base)
    ds = lc.transient(scene, progress=False)
    note = next(n for n in ds.attrs["notes"].split("; ") if n.startswith("reconnect_time rests on"))
    since = float(note.split("from t = ")[1].split(" s")[0])
    flagged = next(line for line in ds.attrs["validity_notes"].splitlines() if line.startswith("flow_factor_range"))
    assert since == float(flagged.split("from t = ")[1].split(" to")[0])
    assert since < scene.motion.ramp + ds["reconnect_time"].item()  # reconnect_time counts from the ramp's end
    assert "exponent at 1.3" in note
    other = lc.transient(lc.load_scene(TABLE1, {**base, "roughness.percolation_exponent": 1.3}), progress=False)
    assert "exponent at 1 to see how much" in other.attrs["notes"]
    steady = lc.transient(lc.load_scene(TABLE1, {**base, "motion.kind": "steady", "motion.duration": 2e-3}), progress=False)
    assert "rests on" not in steady.attrs["notes"]


def test_a_small_2d_mesh_steps_by_the_nested_solve_only(monkeypatch):
    """A 2-D mesh small enough for the dense Newton step (31 x 31 = 961 nodes) still steps
    by the nested solve alone (unsteady/integrator.step_solve): with the dense Newton first a
    Table 1 stop took 160 s against 8 s nested."""

    def refused(*args, **kwargs):
        raise AssertionError("a 2-D time step ran the dense Newton")

    monkeypatch.setattr(integrator, "monolithic_solve", refused)
    scene = lc.load_scene(TABLE1, {"mesh.nx": 15, "mesh.ny": 11, "motion.kind": "stop", "motion.duration": 2e-3})
    series = lc.transient(scene, progress=False)
    assert series["converged"].item() == 1, series.attrs["notes"]


def test_one_newton_steps_a_2d_stop_to_the_nested_solvers_reconnect_time(monkeypatch):
    """solver.method newton on a 2-D mesh, each step one Newton whose reduced system GMRES
    solves, against the nested solve's steps (a separate solver) on the Table 1 stop at
    21 x 11: the same reconnect time within 0.5 % (measured 0.04 %, in 4.3 s against 3.9 s),
    and each step's face-flux volume balance closed to motion.tolerance (measured 4.1e-4).
    The Newton's preconditioner is kept across the run's steps (integrator.Squeeze.preconditioner):
    half as many factorisations as steps at most (measured 25 for 137 steps accepted and
    rejected; 130 for 132 with a preconditioner kept within each step's solve only)."""
    stop = {"mesh.nx": 21, "mesh.ny": 11, "operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-3,
            "motion.duration": 0.03, "motion.mesh_error_bar": False}
    nested = lc.transient(lc.load_scene(TABLE1, stop), progress=False)
    built = []
    build = NearFieldPreconditioner.build
    monkeypatch.setattr(NearFieldPreconditioner, "build", lambda *args: built.append(1) or build(*args))
    newton = lc.transient(lc.load_scene(TABLE1, {**stop, "solver.method": "newton"}), progress=False)
    assert nested["converged"].item() == 1 and newton["converged"].item() == 1, newton.attrs["notes"]
    assert newton["reconnect_time"].item() == pytest.approx(nested["reconnect_time"].item(), rel=5e-3)
    assert np.max(np.abs(newton["volume_balance"].values)) < 1e-3
    assert len(built) < 0.5 * (newton["steps"].item() + newton["rejected_steps"].item())


def test_a_newton_only_steps_volume_balance_closes_to_the_step_tolerance():
    """series.volume_balance (face fluxes, independent of the assembled system) of a line
    stop whose every step is one Newton with Swift-Stieber cavitation (no nested polish), at
    motion.tolerance 1e-4: below it (measured 7.2e-5). With the steady Reynolds test alone
    (solver.tolerance times the peak pressure) it read 0.16: cells at the cavitation boundary
    kept an outflow (integrator.Squeeze.settled_outflow)."""
    stop = {"mesh.nx": 31, "mesh.ny": 1, "operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-3,
            "motion.duration": 0.05, "motion.tolerance": 1e-4, "motion.mesh_error_bar": False,
            "solver.method": "newton"}
    series = lc.transient(lc.load_scene(TABLE1, stop), progress=False)
    assert series["converged"].item() == 1
    assert np.max(np.abs(series["volume_balance"].values)) < 1e-4


def test_a_grease_in_time_is_refused_on_a_2d_mesh_only():
    """Its steps fail where the plug forms on 2-D meshes (docs/physics.md section 21):
    refused, saying why and what is allowed; the line steps it."""
    grease = {"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0, "motion.kind": "stop"}
    refused = motion_problems(lc.load_scene(TABLE1, grease))
    assert any("where the plug forms" in problem and "allowed: mesh.ny = 1" in problem for problem in refused)
    assert not motion_problems(lc.load_scene(TABLE1, {**grease, "mesh.ny": 1}))


def recorded_nested_failures(monkeypatch) -> list:
    """The failure message of every nested coupled solve a time step runs from here on
    ("" where it converged), in a list that fills as they run."""
    failures = []

    def recorded(model, initial, **limits):
        state, diag = coupling.coupled_solve(model, initial, **limits)
        failures.append(diag.failure)
        return state, diag

    monkeypatch.setattr(integrator, "coupled_solve", recorded)
    return failures


def test_a_stalled_time_step_fails_early_and_a_steady_solve_does_not(monkeypatch):
    """model/coupling.STEP_STALL_ITERATIONS: a time step's deformation iteration that has not
    halved its change in that many iterations fails, naming the stall, and on a 2-D mesh
    the step is then taken by one Newton (integrator.nested_then_newton); a steady solve,
    which has no fallback, keeps iterating. With the limit at one iteration every step that
    does not halve its change at once stalls."""
    monkeypatch.setattr(coupling, "STEP_STALL_ITERATIONS", 1)
    nested_failures = recorded_nested_failures(monkeypatch)
    overrides = {"mesh.nx": 15, "mesh.ny": 11, "motion.kind": "stop", "motion.duration": 2e-3}
    steady = lc.solve(lc.load_scene(TABLE1, overrides))
    assert steady["converged"].item() == 1
    series = lc.transient(lc.load_scene(TABLE1, overrides), progress=False)
    assert any("deformation iteration stalled" in failure for failure in nested_failures)
    assert series["converged"].item() == 1, series.attrs["notes"]


def test_a_line_steps_nested_fallback_stalls_sooner(monkeypatch):
    """integrator.LINE_FALLBACK_STALL_ITERATIONS: where a line step's Newton fails, the nested
    solve that answers it fails as stalled after 20 iterations that do not halve its change,
    not the 2-D primary's 50 (coupling.STEP_STALL_ITERATIONS). Every line Newton is made to
    fail here, and the step's tolerance (motion.tolerance) is set so tight that the nested
    solve's test on the film cannot be met and it stalls."""
    failed_newton = lambda model, initial, **_: (None, coupling.Diagnostics(
        iterations=0, deformation_residual=0.0, force_residual=0.0, reynolds_residual=0.0, converged=False,
        stiffness=None, failure="made to fail"))
    monkeypatch.setattr(integrator, "monolithic_solve", failed_newton)
    failures = recorded_nested_failures(monkeypatch)
    scene = lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop", "motion.duration": 2e-3,
                                   "motion.mesh_error_bar": False, "motion.tolerance": 1e-12})
    lc.transient(scene, progress=False)
    stalls = [int(m.group(1)) for f in failures if (m := re.search(r"has not halved in (\d+) iterations", f or ""))]
    assert stalls and set(stalls) == {integrator.LINE_FALLBACK_STALL_ITERATIONS}, failures


@pytest.mark.parametrize("changes, turning, period", [
    ([5.0, 1.0e-2] + [2.4e4, 1.1e4] * 4, False, 2),  # alternating sizes (a 101 x 21 stop's failure)
    ([7.0, 9.0] + [5.6e4, 2.4e4, 5.8e4, 5.5e4] * 3, False, 4),  # a cycle of four
    ([3.0] + [2.0e3, 1.0e3, 4.0e3] * 2 + [2.0e3, 1.0e3], False, 0),  # one period and a bit: too soon to tell
    ([v for k in range(8) for v in (2.4e4 * 1.05 ** k, 1.1e4)], False, 0),  # each period 5 % on: not the same states
    ([0.5] + [0.882, 0.887] * 6, True, 1),  # the same size again, each change turning back: two states
    ([6.0e4] * 12, False, 0),  # the same size again in the same direction: a drift, left to the stall test
    (list(np.geomspace(1e3, 1e-3, 20)), True, 0),  # converging
])
def test_a_cycle_is_a_repeat_of_the_period_before(changes, turning, period):
    """model/coupling.cycle_period, on sequences built with a known period (or none)."""
    assert coupling.cycle_period(changes, [turning] * len(changes)) == period


def test_a_steady_start_that_fails_says_why():
    series = lc.transient(lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 1, "motion.kind": "stop",
                                                  "solver.max_iterations": 1}), progress=False)
    assert "the steady start did not converge: 1 iteration(s) without its deformation change falling below" in series.attrs["notes"]


def test_transient_figure_labels_name_no_config_key():
    """Issue 29 item 12: legends and axes of the transient figures are words and units."""
    from lubecontact.studies import transient_cases as study

    cases = study.figure_cases(study.study_spec("config/transient.yaml", None))
    labels = [case["label"] for group in cases.values() for case in group]
    assert labels and not [label for label in labels if CONFIG_KEY.search(label)]
    assert study.key_words("lubricant.viscosity") == "dynamic viscosity mu"
    assert study.key_words("operating.force") == "normal force on the cylinder F"


def test_a_billion_cycles_are_refused_before_anything_runs():
    """Issue 29 item 4: a motion that needs more steps than a run may take is refused at once,
    with the bound (40 steps a period, 20000 steps a run), by transient and by show."""
    import time

    from lubecontact.cli.main import main

    scene = lc.load_scene(TABLE1, {"motion.kind": "oscillation", "motion.cycles": 1_000_000_000})
    start = time.perf_counter()
    with pytest.raises(lc.SceneError, match="needs at least 4e"):
        lc.transient(scene)
    assert time.perf_counter() - start < 1.0
    assert main(["transient", TABLE1, "--set", "motion.kind=oscillation", "--set", "motion.cycles=1000000000",
                 "--out", "never.nc"]) == 2


def test_the_newton_fallback_stops_after_failing_twice_in_a_row():
    """integrator.NewtonFallback: a 2-D step's Newton fallback is skipped once it has failed
    MAX_FALLBACK_FAILURES (2) times in a row; a step it takes before that resets the count."""
    fallback = integrator.NewtonFallback()
    assert fallback.enabled
    fallback.record(False)
    assert fallback.enabled
    fallback.record(True)
    fallback.record(False)
    assert fallback.enabled
    fallback.record(False)
    assert not fallback.enabled
