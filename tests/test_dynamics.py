"""The contact as a mass on its spring (unsteady/dynamics.py, docs/physics.md section 22)
against independent truths: a dry contact struck lightly rings at sqrt(k/m), k the contact
stiffness measured by two steady solves (and k + k_s with a spring); a light contact follows
the massless force balance; the excitations and the applied force in closed form."""

import math

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.cli.main import main
from lubecontact.unsteady.dynamics import BaseExcitation, Dynamics
from lubecontact.unsteady.motion import SpeedHistory
from lubecontact.unsteady.transient import reconnection_start

TABLE1 = "config/scenes/table1.yaml"
# Table 1 dry, at rest, as a 51-node line contact (elastic, rough)
DRY_LINE = {"mesh.ny": 1, "mesh.nx": 51, "effects.hydrodynamics": False, "operating.speed": 0.0}
MASS = 1e-4  # kg
# a half-sine shock short against the ringing period (28 us at 5 N): the contact is struck,
# then rings freely; 1000 m/s^2 moves it by ~5 nm, 1 % of sigma (a linear response)
STRUCK = {**DRY_LINE, "motion.kind": "steady", "motion.mass": MASS, "motion.vibration": "half_sine_shock",
          "motion.vibration_acceleration": 1000.0, "motion.shock_duration": 2e-6, "motion.duration": 1.5e-4,
          "motion.tolerance": 1e-6}


# the line, and a 2-D mesh whose steps' reduced systems GMRES solves (measured within 0.5 and
# 0.6 % of sqrt(k/m) there, 1.1 and 1.5 s a run)
MESHES = {"line": {}, "21 x 11": {"mesh.nx": 21, "mesh.ny": 11}}


def contact_stiffness(mesh: dict) -> float:
    """-dF/dz of the dry contact on ``mesh`` (overrides), N/m, by a central difference of two
    steady solves."""
    z = [lc.solve(lc.load_scene(TABLE1, {**DRY_LINE, **mesh, "operating.force": f}))["separation"].item()
         for f in (4.95, 5.05)]
    return 0.1 / (z[0] - z[1])


def ringing_period(series) -> float:
    """Mean period of the free oscillation after the shock, from the upward crossings of z's
    mean over the last half, each located by linear interpolation between levels."""
    t, z = series["time"].values, series["separation"].values
    free = t > 2 * STRUCK["motion.shock_duration"]
    t, z = t[free], z[free] - np.mean(z[free][free.sum() // 2:])
    up = np.flatnonzero((z[:-1] < 0.0) & (z[1:] >= 0.0))
    crossings = t[up] - z[up] * (t[up + 1] - t[up]) / (z[up + 1] - z[up])
    assert crossings.size >= 3, crossings
    return float(np.mean(np.diff(crossings)))


@pytest.fixture(scope="module")
def stiffness():
    return {name: contact_stiffness(mesh) for name, mesh in MESHES.items()}


@pytest.mark.parametrize("mesh", MESHES)
@pytest.mark.parametrize("spring_ratio", [0.0, 1.0])
def test_struck_dry_contact_rings_at_sqrt_k_over_m(stiffness, mesh, spring_ratio):
    spring = spring_ratio * stiffness[mesh]
    series = lc.transient(lc.load_scene(TABLE1, {**STRUCK, **MESHES[mesh], "motion.spring_stiffness": spring}),
                          progress=False)
    assert series["converged"].item() == 1, series.attrs["notes"]
    expected = 2.0 * math.pi * math.sqrt(MASS / (stiffness[mesh] + spring))
    assert ringing_period(series) == pytest.approx(expected, rel=0.01)


def test_a_light_contact_follows_the_massless_force_balance():
    # at motion.tolerance 1e-4: at the default 1e-3 each run's own time-integration error
    # (2.2e-8 m late in the stop, against a run at 1e-5) exceeds the 1e-8 m compared below, so
    # two paths that differ within it (a massless step's Newton is finished by the nested solve,
    # a light one's is not) would fail a test of the physics; at 1e-4 they differ by 1.1e-9 m
    stop = {"mesh.ny": 1, "mesh.nx": 31, "operating.speed": 1.0, "motion.kind": "stop", "motion.duration": 0.03,
            "motion.tolerance": 1e-4}
    massless = lc.transient(lc.load_scene(TABLE1, stop), progress=False)
    # 1e-9 kg rings at ~0.1 us on this contact: far faster than anything the stop does
    light = lc.transient(lc.load_scene(TABLE1, {**stop, "motion.mass": 1e-9}), progress=False)
    assert light["converged"].item() == 1 and massless["converged"].item() == 1
    assert light["reconnect_time"].item() == pytest.approx(massless["reconnect_time"].item(), rel=0.05)
    z = np.interp(massless.time.values, light.time.values, light["separation"].values)
    assert np.max(np.abs(z - massless["separation"].values)) < 0.02 * 5e-7


def test_excitations_in_closed_form():
    sine = BaseExcitation("sine", 10.0, 50.0, 1e-3)
    assert sine.acceleration_at(0.005) == pytest.approx(10.0) and sine.max_step(0.0) == pytest.approx(1 / 2000)
    shock = BaseExcitation("half_sine_shock", 500.0, 50.0, 0.011)  # EIA-364-27: 50 g, 11 ms
    assert shock.acceleration_at(0.0055) == pytest.approx(500.0) and shock.acceleration_at(0.02) == 0.0
    assert shock.breakpoints() == [0.011] and shock.max_step(0.02) == math.inf


def test_applied_force_is_the_spring_plus_inertia():
    scene = lc.load_scene(TABLE1, {"mesh.ny": 1, "motion.mass": 2e-3, "motion.spring_stiffness": 1e4,
                                   "motion.vibration": "sine", "motion.vibration_acceleration": 100.0})
    dynamics = Dynamics.from_scene(scene)
    # BDF1 with dt = 1e-3 from z = 1e-6, v = 2e-3 at the last level: v = (z - 1e-6)/dt,
    # a = (v - 2e-3)/dt
    load = dynamics.load(0.0025, 0.0, [1e3, -1e3], [1e-6], [2e-3])
    z = 3e-6
    v, a = (z - 1e-6) / 1e-3, ((z - 1e-6) / 1e-3 - 2e-3) / 1e-3
    force, slope = load.force(z)
    assert force == pytest.approx(5.0 + 1e4 * z + 2e-3 * (a + 100.0))
    assert slope == pytest.approx(1e4 + 2e-3 * 1e6) and load.velocity(z) == pytest.approx(v)
    assert Dynamics.from_scene(lc.load_scene(TABLE1)) is None  # the massless contact: today's model


def test_the_shortest_step_is_where_the_inertial_force_rounds_to_the_resolution():
    # Dynamics.shortest_step against the float evaluation the solver makes: the applied force
    # of a BDF2 step (c0 = 1.5/dt) at z and at its float neighbours, z held at the start
    # (v = a = 0 before). At the shortest step the force moves by no more than the resolution
    # from one float of z to the next; at a third of it (nine times the squared rate) by more.
    scene = lc.load_scene(TABLE1, {"mesh.ny": 1, "motion.mass": 1e-3, "motion.spring_stiffness": 1e3})
    dynamics = Dynamics.from_scene(scene)
    z, resolution = 4.8e-6, 5e-8
    shortest = dynamics.shortest_step(z, resolution)
    neighbours = [np.nextafter(z, -1.0), z, np.nextafter(z, 1.0)]

    def spread(dt):
        c = [1.5 / dt, -2.0 / dt, 0.5 / dt]  # BDF2, equal steps
        load = dynamics.load(0.0, z, c, [z, z], [0.0, 0.0])
        forces = [load.force(x)[0] for x in neighbours]
        return max(abs(forces[1] - forces[0]), abs(forces[2] - forces[1]))

    assert spread(shortest) <= resolution < spread(shortest / 3.0)
    assert 1e-9 < shortest < 1e-8  # above the integrator's first step, 1e-9 s
    assert Dynamics(0.0, 1e3, 5.0, dynamics.base).shortest_step(z, resolution) == 0.0


def test_dynamics_keys_keep_old_hashes_and_bad_ones_are_refused():
    stop = lc.load_scene(TABLE1, {"motion.kind": "stop"})
    assert "mass" not in stop.canonical_yaml() and "vibration" not in stop.canonical_yaml()
    assert lc.load_scene(TABLE1, {"motion.kind": "stop", "motion.mass": 0.0}).hash == stop.hash
    with pytest.raises(lc.SceneError, match="motion.mass = -1"):
        lc.load_scene(TABLE1, {"motion.mass": -1})
    with pytest.raises(lc.SceneError, match="needs motion.mass > 0"):
        lc.transient(lc.load_scene(TABLE1, {"mesh.ny": 1, "motion.vibration": "sine"}), progress=False)
    # the converse, found by a hostile run (thirtieth session): an acceleration with no vibration was ignored
    with pytest.raises(lc.SceneError, match="with motion.vibration = 'none': there is no excitation"):
        lc.transient(lc.load_scene(TABLE1, {"mesh.ny": 1, "motion.kind": "stop", "motion.vibration_acceleration": 100}),
                     progress=False)


def test_random_vibration_has_its_rms_and_its_band():
    # EIA-364-28's random profiles give a flat acceleration density over a band and its RMS
    base = BaseExcitation("random", 74.0, 50.0, 0.2, 2000.0, seed=3)  # 7.56 g rms, 50-2000 Hz, 0.2 s
    t = np.arange(0.0, 0.2, 1e-5)  # 20 000 samples: 100 kHz, far above the band
    signal = np.array([base.acceleration_at(x) for x in t])
    assert np.sqrt(np.mean(signal**2)) == pytest.approx(74.0, rel=1e-3)  # Parseval over whole periods
    power = np.abs(np.fft.rfft(signal)) ** 2
    frequency = np.fft.rfftfreq(t.size, 1e-5)
    inside = (frequency >= 50.0) & (frequency <= 2000.0)
    assert power[inside].sum() > (1 - 1e-9) * power.sum()  # nothing outside the band
    band = power[inside]
    assert np.allclose(band, band.mean(), rtol=1e-6)  # flat: every line of the band carries the same power
    again = BaseExcitation("random", 74.0, 50.0, 0.2, 2000.0, seed=3)
    other = BaseExcitation("random", 74.0, 50.0, 0.2, 2000.0, seed=4)
    assert again.acceleration_at(0.0123) == base.acceleration_at(0.0123) != other.acceleration_at(0.0123)


def test_sine_sweep_frequency_rises_logarithmically():
    sweep = BaseExcitation("sine_sweep", 10.0, 100.0, 1.0, 1000.0)  # 100 Hz to 1 kHz over 1 s
    for when, expected in ((0.05, 100.0 * 10**0.05), (0.5, 100.0 * 10**0.5), (0.95, 100.0 * 10**0.95)):
        t = np.linspace(when - 0.01, when + 0.01, 20001)
        a = np.array([sweep.acceleration_at(x) for x in t])
        up = t[1:][(a[:-1] < 0.0) & (a[1:] >= 0.0)]  # upward zero crossings
        assert 1.0 / np.mean(np.diff(up)) == pytest.approx(expected, rel=0.01)
    assert sweep.max_step(0.3) == pytest.approx(1.0 / (1000.0 * 40))


def test_a_vibration_needing_too_many_steps_is_refused():
    with pytest.raises(lc.SceneError, match="needs at least"):
        lc.transient(lc.load_scene(TABLE1, {**DRY_LINE, "motion.mass": 1e-3, "motion.vibration": "sine",
                                            "motion.vibration_acceleration": 10.0, "motion.vibration_frequency": 1e4,
                                            "motion.duration": 100.0}), progress=False)
    with pytest.raises(lc.SceneError, match="an end above the start"):
        lc.transient(lc.load_scene(TABLE1, {**DRY_LINE, "motion.mass": 1e-3, "motion.vibration": "random",
                                            "motion.vibration_acceleration": 10.0, "motion.vibration_frequency": 500.0,
                                            "motion.vibration_frequency_end": 100.0}), progress=False)


# the shock figure's 100 g case (config/transient.yaml figures.shock) as a rigid 31-node line:
# the preload (0.5 N) over the mass (1 g) is 51 g, so the shock lifts the contact
LIFTED = {"mesh.ny": 1, "mesh.nx": 31, "effects.elastic_deformation": False, "operating.speed": 0.0,
          "operating.force": 0.5, "motion.kind": "steady", "motion.duration": 0.05, "motion.mass": 1e-3,
          "motion.spring_stiffness": 2000.0, "motion.vibration": "half_sine_shock", "motion.shock_duration": 0.011,
          "motion.vibration_acceleration": -100 * 9.80665, "motion.tolerance": 1e-2}


def test_a_shocks_reconnect_time_counts_from_its_end_and_ends_its_relative_event():
    """Timed from t = 0 the reconnect time of a contact closed at the start read 0, however
    long the shock then held it open. Counted from the shock's end (transient.reconnection_start)
    it is where the one event above reconnect_factor x rest_resistance ends, located on its
    own (events.py)."""
    ds = lc.transient(lc.load_scene(TABLE1, LIFTED), progress=False)
    assert ds["converged"].item() == 1 and ds["relative_event_count"].item() == 1 and ds["event_count"].item() >= 1
    recon, threshold = ds["reconnect_time"].item(), ds["relative_threshold"].item()
    t, r = ds["time"].values, ds["contact_resistance"].values
    shock_end = LIFTED["motion.shock_duration"]
    assert r[0] <= threshold and r[np.searchsorted(t, shock_end)] > threshold  # closed at first, open as it ends
    last_above = np.flatnonzero(r > threshold)[-1]
    assert recon > 0.0 and t[last_above] <= shock_end + recon <= t[last_above + 1]


@pytest.mark.parametrize("overrides, expected", [
    ({"motion.kind": "stop", "operating.speed": 1.0, "motion.vibration": "none"}, 1e-3),  # the stop's rest
    ({"motion.kind": "stop", "operating.speed": 1.0, "motion.ramp": 1e-3}, 0.011),  # the shock ends later
    ({"motion.kind": "stop", "operating.speed": 1.0, "motion.ramp": 0.02}, 0.02),  # the stop ends later
    ({"operating.speed": 1.0}, None),  # sliding on: no rest
    ({"motion.vibration": "sine"}, None),  # shaken to the end
])
def test_a_reconnection_is_timed_from_the_later_of_the_rest_and_the_shocks_end(overrides, expected):
    scene = lc.load_scene(TABLE1, {**LIFTED, **overrides})
    assert reconnection_start(SpeedHistory.from_scene(scene), BaseExcitation.from_scene(scene)) == expected


@pytest.mark.parametrize("vibration, expected", [("none", 0.0), ("half_sine_shock", 0.011), ("sine", None),
                                                 ("sine_sweep", None), ("random", None)])
def test_the_base_is_quiet_after_a_shock_and_never_under_a_vibration(vibration, expected):
    scene = lc.load_scene(TABLE1, {**LIFTED, "motion.vibration": vibration})
    assert BaseExcitation.from_scene(scene).quiet_from() == expected


def test_the_summary_says_from_when_a_reconnection_is_timed_and_why_a_vibration_has_none(capsys, tmp_path):
    shock = ["transient", TABLE1, *[f"--set={k}={v}" for k, v in LIFTED.items()], "--out", str(tmp_path / "s.nc")]
    assert main(shock) == 0
    assert "reconnect_time: counted from t = 0.011 s, when the block is at rest and the shock over" in capsys.readouterr().out
    shaken = {**LIFTED, "motion.vibration": "sine", "motion.vibration_frequency": 200.0, "motion.duration": 0.01}
    assert main(["transient", TABLE1, *[f"--set={k}={v}" for k, v in shaken.items()], "--out", str(tmp_path / "v.nc")]) == 0
    out = capsys.readouterr().out
    assert "reconnect_time = nan: motion.vibration = sine shakes the base to the end of the run" in out


@pytest.mark.parametrize("overrides, why, end", [
    ({"motion.kind": "stop", "motion.ramp": 1.0, "motion.duration": 0.005}, "the block comes to rest at t = 1 s", 0.005),
    ({"operating.speed": 0.0, "motion.mass": MASS, "motion.vibration": "half_sine_shock",
      "motion.vibration_acceleration": -3000.0, "motion.shock_duration": 1e-3, "motion.duration": 1e-4},
     "the half-sine shock ends at t = 0.001 s", 1e-4),
    ({"motion.kind": "oscillation", "motion.amplitude": 1e-4, "motion.frequency": 100.0, "motion.cycles": 3,
      "motion.duration": 0.005}, "the block comes to rest at t = 0.03 s", 0.03),
], ids=["ramp outlasts the run", "shock outlasts the run", "cycles outlast motion.duration"])
def test_a_run_that_ends_before_its_rest_has_no_reconnection_and_says_why(overrides, why, end):
    # found by a hostile run (thirtieth session): each read reconnect_time = inf, "not
    # reconnected within motion.duration", for a block that never rested within the run
    scene = lc.load_scene(TABLE1, {"mesh.ny": 1, "mesh.nx": 31, **overrides})
    ds = lc.transient(scene, progress=False)
    assert ds["converged"].item() == 1 and math.isnan(ds["reconnect_time"].item())
    assert f"{why}, not before the run ends" in ds.attrs["notes"]
    assert ds["time"].values[-1] == pytest.approx(end)


def test_keys_a_motion_does_not_read_are_named_and_move_nothing():
    # found by a hostile run (thirtieth session): keys of another motion kind or excitation
    # were accepted and hashed without a word
    from lubecontact.model.validity import scene_warnings
    from lubecontact.scene.scene import Motion
    from lubecontact.scene.unread_keys import KIND_KEYS, VIBRATION_KEYS, unread_motion_keys

    assert set(KIND_KEYS) | set(VIBRATION_KEYS) <= set(Motion.keys())
    stop = {"mesh.ny": 1, "mesh.nx": 31, "motion.kind": "stop", "motion.duration": 0.002}
    unread = {**stop, "motion.frequency": 50.0, "motion.vibration_seed": 3, "motion.ramp": 2e-4}
    scene = lc.load_scene(TABLE1, unread)
    assert [k.split(" ")[0] for k in unread_motion_keys(scene)] == ["motion.frequency", "motion.vibration_seed"]
    assert any("does not read motion.frequency" in w for w in scene_warnings(scene))
    assert scene.hash != lc.load_scene(TABLE1, {**stop, "motion.ramp": 2e-4}).hash
    moved = lc.transient(scene, progress=False)
    plain = lc.transient(lc.load_scene(TABLE1, {**stop, "motion.ramp": 2e-4}), progress=False)
    np.testing.assert_array_equal(moved["contact_resistance"].values, plain["contact_resistance"].values)
    explicit = lc.load_scene(TABLE1, {**stop, "mesh.x_min": -1e-3, "mesh.x_max": 5e-4, "motion.rest_refinement": 4})
    assert [k.split(" ")[0] for k in unread_motion_keys(explicit)] == ["motion.rest_refinement"]
    assert unread_motion_keys(lc.load_scene(TABLE1, {**stop, "motion.rest_refinement": 4})) == []
