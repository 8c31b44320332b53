"""An oscillation's return stroke draws its film from x_max (docs/physics.md section 17): its
steps go on the motion's mesh mirrored about the line of contact (TimeIntegrator.reversed_domain),
whose inlet lies upstream of the sliding on both strokes."""

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.numerics.mesh import Mesh, build_mesh, mirrored_mesh
from lubecontact.unsteady import integrator
from lubecontact.unsteady.motion import SpeedHistory

TABLE1 = "config/scenes/table1.yaml"
# Table 1 with a 1 Pa s oil as the default 51-node line, 1 mm at 20 Hz: U = 0.126 m/s at the
# peaks of the forward and return strokes (t = 12.5 and 37.5 ms)
OSCILLATION = {"mesh.ny": 1, "mesh.nx": 51, "lubricant.viscosity": 1.0, "motion.kind": "oscillation",
               "motion.amplitude": 1e-3, "motion.frequency": 20.0, "motion.cycles": 1, "motion.duration": 0.05}
RETURN = np.array([31.25, 37.5, 43.75]) * 1e-3  # the return stroke: accelerating, its peak, slowing


def symmetric(overrides: dict) -> dict:
    """``overrides`` on the domain symmetric about the contact at the spacing of the automatic
    mesh, its inlet's length on both sides: a mesh on which neither stroke starves."""
    mesh = build_mesh(lc.load_scene(TABLE1, overrides))
    cells = int(round(-mesh.x[0] / mesh.dx))
    return {**overrides, "mesh.x_min": -cells * mesh.dx, "mesh.x_max": cells * mesh.dx, "mesh.nx": 2 * cells + 1}


def both(overrides: dict):
    """The motion on its automatic domain and on the symmetric one (the truth)."""
    return (lc.transient(lc.load_scene(TABLE1, overrides), progress=False),
            lc.transient(lc.load_scene(TABLE1, symmetric(overrides)), progress=False))


@pytest.fixture(scope="module")
def strokes():
    """At motion.tolerance 1e-4: the two meshes compared, not their time integration (at the
    default 1e-3 the two runs' time errors add up to 0.28 % in the film, forty-third session)."""
    return both({**OSCILLATION, "motion.tolerance": 1e-4})


def test_the_return_stroke_is_as_flooded_as_on_a_symmetric_domain(strokes):
    """The truth is the same motion on the domain symmetric about the contact (the inlet's
    length on both sides, the same spacing), where the return stroke is the forward one
    mirrored. On the forward mesh alone its film was 6.7 % thinner at the stroke's peak
    (0.720 against 0.772 um) and its resistance 19 % lower; on the mirrored mesh both agree
    within 0.25 % and 1 %: measured 0.10-0.18 % for the films and 0.3-0.5 % for the
    resistance, at motion.tolerance 1e-3 and 1e-4 alike (the two meshes' discretisations differ
    at that level, not the time integration), with a time step's Reynolds test in the step's
    own units and before it (thirty-eighth session); since a line contact's steps are the
    Newton's answers (forty-third session) 0.05-0.09 % and 0.13-0.29 % at 1e-4, where the test
    runs, and up to 0.28 % and 0.78 % at 1e-3, the time error of the two runs added."""
    automatic, truth = strokes
    assert int(automatic["converged"]) == 1 and int(truth["converged"]) == 1
    for name, tolerance in (("min_film_thickness", 2.5e-3), ("central_film_thickness", 2.5e-3),
                            ("contact_resistance", 1e-2)):
        np.testing.assert_allclose(automatic[name].interp(time=RETURN).values, truth[name].interp(time=RETURN).values,
                                   rtol=tolerance, err_msg=name)


def test_a_viscous_oscillation_opens_as_on_a_symmetric_domain():
    """Under 10 Pa s the contact lifts off for the whole of two cycles: one event of 91.2 ms
    above the open resistance, as on the symmetric domain. With the return strokes starved
    (on the forward mesh) it closed on each, two events of 82.2 ms in all."""
    automatic, truth = both({**OSCILLATION, "lubricant.viscosity": 10.0, "motion.cycles": 2, "motion.duration": 0.1})
    assert int(automatic["converged"]) == 1 and int(truth["converged"]) == 1
    assert int(automatic["event_count"]) == int(truth["event_count"]) == 1
    assert float(automatic["event_open_time"]) == pytest.approx(float(truth["event_open_time"]), rel=1e-3)


def test_the_steps_change_meshes_where_the_sliding_reverses():
    """Two cycles, x = A (1 - cos 2 pi f t): forward (U > 0) on the motion's mesh, its inlet at
    x_min, backward on its mirror image, forward again on the first, backward again; every
    level on the mesh of its own stroke."""
    scene = lc.load_scene(TABLE1, {**OSCILLATION, "motion.cycles": 2, "motion.duration": 0.1})
    history = SpeedHistory.from_scene(scene)
    runner = integrator.TimeIntegrator(scene, history)
    levels, failure = runner.run()
    assert not failure and runner.backward is not None
    forward, backward = runner.steady_model.mesh, runner.backward.mesh
    np.testing.assert_array_equal(backward.x, -forward.x[::-1])
    moving = [level for level in levels if level.speed != 0.0]
    switches = sum(a.model.mesh is not b.model.mesh for a, b in zip(moving, moving[1:]))
    assert switches == 3
    # a level's mesh is that of its stroke, but for the first level after each reversal,
    # solved on the mesh of the stroke before it
    wrong = [level for level in moving if (level.speed > 0.0) != (level.model.mesh is forward)]
    assert len(wrong) == 3


def test_a_motion_that_never_reverses_builds_no_mirrored_mesh():
    scene = lc.load_scene(TABLE1, {"mesh.ny": 1, "mesh.nx": 31, "operating.speed": 1.0, "motion.kind": "stop",
                                   "motion.duration": 0.002})
    history = SpeedHistory.from_scene(scene)
    assert not history.reverses()
    runner = integrator.TimeIntegrator(scene, history)
    assert runner.reversed_domain() is None
    _, failure = runner.run()
    assert not failure and runner.backward is None


def test_mirrored_mesh_and_which_motions_reverse():
    mesh = Mesh(x=np.array([-3.0, -1.0, 1.0, 2.0]), y=np.zeros(1), length=1e-3)
    np.testing.assert_array_equal(mirrored_mesh(mesh).x, [-2.0, -1.0, 1.0, 3.0])
    table = {"motion.kind": "table", "motion.table": [[0.0, 0.1], [0.01, -0.1], [0.02, 0.0]]}
    assert SpeedHistory.from_scene(lc.load_scene(TABLE1, table)).reverses()
    assert SpeedHistory.from_scene(lc.load_scene(TABLE1, OSCILLATION)).reverses()


@pytest.mark.parametrize("domain", ["automatic", "symmetric"])
def test_a_table_that_starts_backwards_is_the_mirror_image_of_one_that_starts_forwards(domain):
    """Sliding from -1 m/s is sliding from +1 m/s seen from the other side (the gap x^2/2R and
    isotropic roughness are symmetric): the same steady start and the same reconnection, on
    the automatic domain (mirrored for the backward start) and on an explicit one symmetric
    about the contact. It had started dry (the steady solve took U < 0 as no sliding), and on
    the forward mesh, whose inlet was then the outlet's 1.5 length scales, failed at 1 ns."""
    line = {"mesh.ny": 1, "mesh.nx": 31, "motion.duration": 0.02}
    if domain == "symmetric":
        line = symmetric({**line, "operating.speed": 1.0})
    line["motion.kind"] = "table"
    runs = [lc.transient(lc.load_scene(TABLE1, {**line, "motion.table": [[0.0, u], [1e-3, 0.0]]}), progress=False)
            for u in (1.0, -1.0)]
    forward, backward = runs
    assert backward["converged"].item() == 1
    for name in ("contact_resistance", "min_film_thickness", "fluid_force"):
        assert backward[name].values[0] == pytest.approx(forward[name].values[0], rel=1e-5), name
    assert backward["reconnect_time"].item() == pytest.approx(forward["reconnect_time"].item(), rel=1e-3)
