"""Two steady states at the same inputs: lift-off and touch-down (docs/physics.md section 23).

The truth here is not a sweep's own output: each state the sweeps find is checked against the
one Newton's residual (model/monolithic_newton.linearise, the Fischer-Burmeister form of
Reynolds with cavitation, the deformation and the force balance), a different statement of
the discrete problem than the nested solve that found it. Where both directions meet it, at
the same speed and far apart, the discrete problem has two solutions and a sweep's answer
depends on where it came from. Where the contact has one state both directions agree.
"""

import numpy as np
import pytest
import xarray as xr

import lubecontact as lc
from lubecontact.cli import main as cli
from lubecontact.model.coupling import WarmStart
from lubecontact.model.model import Model
from lubecontact.model.monolithic_newton import Iterate, converged, linearise

TABLE1 = "config/scenes/table1.yaml"
# Fig. 8's heaviest force on a 31 x 31 mesh (a second a sweep): its lift-off loop spans
# 0.08-0.25 m/s there (bench/HYSTERESIS.md has it on 31, 51 and 81 nodes a side)
HEAVY = {"operating.force": 20.0, "mesh.nx": 31, "mesh.ny": 31}
IN_THE_LOOP = 0.1  # m/s


def followed(scene, speeds):
    """The last state of a continuation through ``speeds`` in their order (lc.solve's warm starts)."""
    initial = None
    for speed in speeds:
        ds, state = lc.solve(scene.replace({"operating.speed": speed}), initial=initial, return_state=True)
        assert ds["converged"].item() == 1, speed
        initial = WarmStart(z=state.z, delta=state.delta, pressure=state.reynolds.pressure,
                            cavitated=state.reynolds.cavitated)
    return state


def test_speeding_up_and_slowing_down_reach_two_solutions_of_the_same_problem():
    scene = lc.load_scene(TABLE1, HEAVY)
    up = followed(scene, [0.01, 0.0251, 0.0631, IN_THE_LOOP])
    down = followed(scene, [1.0, 0.398, 0.158, IN_THE_LOOP])
    model = Model.assemble(scene.replace({"operating.speed": IN_THE_LOOP}))
    tolerance = scene.solver.tolerance
    for state in (up, down):  # each meets every stopping test of the one Newton (its residual, not the nested one's)
        assert converged(model, linearise(model, Iterate(state.fluid_pressure, state.delta, state.z)), tolerance)
    share = [s.fluid_force / s.total_force for s in (up, down)]
    assert share[0] < 0.2 and share[1] > 0.6, share  # contact-carried up, fluid-carried down (0.07, 0.77)
    assert down.z - up.z > scene.roughness.sigma  # the fluid-carried state lifted the cylinder (by 1.2 um)


def test_sweep_both_ways_returns_each_branch_and_says_where_they_part():
    speeds = np.geomspace(0.01, 1.0, 11)
    ds = lc.sweep(lc.load_scene(TABLE1, HEAVY), speeds, direction="both", progress=False)
    assert ds["contact_resistance"].dims == ("direction", "speed") and list(ds["direction"].values) == ["up", "down"]
    assert np.all(ds["converged"].values == 1) and np.all(np.diff(ds["speed"].values) > 0)
    up, down = (ds.sel(direction=d) for d in ("up", "down"))
    np.testing.assert_allclose(up["fluid_load_fraction"][[0, -1]], down["fluid_load_fraction"][[0, -1]], rtol=1e-4)
    loop = (speeds > 0.08) & (speeds < 0.2)  # 0.1 and 0.158 m/s
    assert np.all(down["fluid_load_fraction"].values[loop] - up["fluid_load_fraction"].values[loop] > 0.5)
    assert "differ most at" in ds.attrs["hysteresis"] and "ohm up" in ds.attrs["hysteresis"]
    assert ds.attrs["validity_notes"].startswith("up, 0.01 m/s")


def test_where_the_contact_has_one_state_both_directions_agree():
    # Table 1 (5 N) from boundary to full film on a coarse mesh: speeding up, slowing down and
    # each point cold give one curve (tests/test_lubricated.py checks up against cold)
    scene = lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 21})
    ds = lc.sweep(scene, np.geomspace(1e-4, 10.0, 7), direction="both", progress=False)
    assert np.all(ds["converged"].values == 1)
    for name in ("contact_resistance", "friction_coefficient", "min_film_thickness"):
        np.testing.assert_allclose(ds[name].sel(direction="up"), ds[name].sel(direction="down"), rtol=1e-5,
                                   err_msg=name)


def test_cli_sweep_both_ways_writes_both_and_prints_the_difference(tmp_path, capsys):
    out = tmp_path / "both.nc"
    args = ["sweep", TABLE1, *(f"--set={k}={v}" for k, v in HEAVY.items()), "--speeds", "0.0631,0.1,0.158"]
    assert cli.main([*args, "--direction", "both", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "hysteresis: speeding up and slowing down differ most at" in printed
    with xr.open_dataset(out) as ds:
        assert ds["contact_resistance"].dims == ("direction", "speed")


def test_sweep_refuses_a_direction_it_does_not_know():
    with pytest.raises(ValueError, match="direction must be one of 'up', 'down', 'both'"):
        lc.sweep(lc.load_scene(TABLE1), [0.1], direction="sideways")
    with pytest.raises(SystemExit):
        cli.main(["sweep", TABLE1, "--speeds", "0.1", "--direction", "sideways", "--out", "x.nc"])
