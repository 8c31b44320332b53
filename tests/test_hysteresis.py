"""Two steady states at the same inputs: lift-off and touch-down (docs/physics.md section 23).

The truth here is not a sweep's own output: each state the sweeps find is checked against the
one Newton's residual (model/monolithic_newton.linearise, the Fischer-Burmeister form of
Reynolds with cavitation, the deformation and the force balance), a different statement of
the discrete problem than the nested solve that found it. Where both directions meet it, at
the same speed and far apart, the discrete problem has two solutions and a sweep's answer
depends on where it came from. Where the contact has one state both directions agree.
"""

import re

import numpy as np
import pytest
import xarray as xr

import lubecontact as lc
from lubecontact.cli import main as cli
from lubecontact.model.coupling import WarmStart
from lubecontact.model.model import Model
from lubecontact.model.monolithic_newton import Iterate, converged, linearise
from lubecontact.plotting.hysteresis import hysteresis_figure
from lubecontact.studies import figure_grids, hysteresis_cases
from lubecontact.studies.sweep import largest_difference

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


def test_a_continued_point_that_fails_is_solved_cold_and_says_so(tmp_path, capsys):
    # slowing down on the default 51 x 51 mesh at 20 N: the state continued from 0.178 m/s
    # does not converge at 0.158 m/s (bench/HYSTERESIS.md); a cold start there does
    speeds = np.geomspace(0.0631, 0.251, 13)[-5:]
    scene = lc.load_scene(TABLE1, {"operating.force": 20.0})
    out = tmp_path / "down.nc"
    assert cli.main(["sweep", TABLE1, "--set", "operating.force=20", "--speeds", ",".join(repr(float(u)) for u in speeds),
                     "--direction", "down", "--out", str(out)]) == 0
    assert f"cold restart at {speeds[0]:g} m/s:" in capsys.readouterr().out
    ds = xr.load_dataset(out)
    assert ds["converged"].values.tolist() == [1] * 5 and ds["cold_restart"].values.tolist() == [1, 0, 0, 0, 0]
    cold = lc.solve(scene.replace({"operating.speed": float(speeds[0])}))
    assert ds["fluid_load_fraction"].values[0] == pytest.approx(cold["fluid_load_fraction"].item(), rel=1e-9)
    assert "cold start" in ds["cold_restart"].attrs["long_name"] and ds["cold_restart"].attrs["units"] == "1"


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


def test_the_largest_difference_takes_open_contacts_and_says_so():
    def branch(resistance, share):
        return xr.Dataset({"contact_resistance": ("speed", resistance), "fluid_load_fraction": ("speed", share),
                           "converged": ("speed", [1, 1, 1])}, coords={"speed": [0.1, 1.0, 10.0]})

    inf = np.inf  # no metallic path at all: both open at 10 m/s (the same), one open at 1 m/s
    said = largest_difference(branch([1e-8, 1e-6, inf], [0.2, 0.5, 1.0]), branch([1e-8, inf, inf], [0.2, 1.0, 1.0]))
    assert said.startswith("speeding up and slowing down differ most at 1 m/s: contact resistance 1e-06 ohm up, inf")
    same = largest_difference(branch([1e-8, 2e-8, inf], [0.2, 0.3, 1.0]), branch([1e-8, 2e-8, inf], [0.2, 0.3, 1.0]))
    assert "ln R apart by 0" in same


def test_sweep_refuses_a_direction_it_does_not_know():
    with pytest.raises(ValueError, match="direction must be one of 'up', 'down', 'both'"):
        lc.sweep(lc.load_scene(TABLE1), [0.1], direction="sideways")
    with pytest.raises(SystemExit):
        cli.main(["sweep", TABLE1, "--speeds", "0.1", "--direction", "sideways", "--out", "x.nc"])


def test_a_figure_grid_gives_one_continuation_case_per_curve():
    specs = {name: figure_grids.figure_spec(name, "config/figures", {"fig08": {
        "set": {"mesh.nx": 15, "mesh.ny": 11}, "sweep": {"operating.force": [5.0, 20.0]}, "speeds": [0.1, 0.001, 1.0]}})
        for name in ("fig08",)}
    grid = figure_grids.expand_all(specs)["fig08"]
    cases = hysteresis_cases.curve_cases(grid)
    assert [c["label"] for c in cases] == ["normal force on the cylinder F = 5 N", "normal force on the cylinder F = 20 N"]
    assert all(c["speeds"] == [0.001, 0.1, 1.0] and "operating.speed" not in c["set"] for c in cases)
    assert all(re.fullmatch(r"[0-9a-f]{16}", c["id"]) for c in cases) and cases[0]["id"] != cases[1]["id"]
    # a speed more renames the curve (its file is another case); the same grid gives the same ids
    specs["fig08"]["speeds"] = [0.001, 0.1, 1.0, 10.0]
    assert {c["id"] for c in hysteresis_cases.curve_cases(figure_grids.expand_all(specs)["fig08"])}.isdisjoint(
        c["id"] for c in cases)
    assert hysteresis_cases.curve_cases(grid) == cases
    assert hysteresis_cases.study_problems(["fig08", "fig99"], {"fig08": grid}) == [
        "hysteresis: fig99 is not among the figures of this config (fig08)"]


def test_the_figure_draws_both_branches_with_units_and_marks_a_failed_point():
    speeds = [0.0631, 0.1, 0.158]
    ds = lc.sweep(lc.load_scene(TABLE1, HEAVY), speeds, direction="both", progress=False)
    failed = ds.copy(deep=True)
    failed["converged"].loc[{"direction": "down", "speed": 0.1}] = 0
    failed["cold_restart"].loc[{"direction": "up", "speed": 0.158}] = 1
    fig = hysteresis_figure([("20 N", ds), ("20 N, one point failed", failed)], "title")
    resistance, share = fig.axes[:2]
    assert resistance.get_xlabel() == "sliding speed U of the block (m/s)" and resistance.get_ylabel().endswith("(\u03a9)")
    assert share.get_ylabel() == "fluid share of the load F_fluid/F (\u2013)" and resistance.get_yscale() == "log"
    # per curve and direction: the line, then its failed points (red crosses): 2 curves x 2 ways
    crosses = [line for line in share.get_lines() if line.get_marker() == "x"]
    assert [len(line.get_xdata()) for line in crosses] == [0, 0, 0, 1]
    drawn = [line for line in share.get_lines() if line.get_marker() == "."]
    for line, way in zip(drawn, ("up", "down")):  # each branch as the sweep found it (they part at 0.1 m/s)
        np.testing.assert_array_equal(line.get_ydata(), ds["fluid_load_fraction"].sel(direction=way).values)
    assert drawn[0].get_linestyle() == "-" and drawn[1].get_linestyle() == "--"
    legend = [text.get_text() for text in share.get_legend().get_texts()]
    rings = [line for line in share.get_lines() if line.get_marker() == "o"]
    assert [len(line.get_xdata()) for line in rings] == [0, 0, 1, 0]
    assert {"speeding up", "slowing down", "did not converge", "20 N"} <= set(legend)
