"""The Snakemake workflow: plans (dry runs), lint, and one end-to-end build of the tiny grids.

Every test here runs Snakemake in a subprocess and is marked ``slow`` (CI runs them; about
two minutes on two busy cores, most of it the tiny build; ``pytest -m "not slow"`` skips).

Each test works in a temporary copy of the repository tree (Snakefile, config, workflow,
src), never in the working tree. Truths used: job counts worked out by hand from the grid
files; physics that holds whatever the discretisation (resistance rises with speed; at low
speed the asperities carry the load, so friction -> the boundary friction 0.1 of Table 1's
scene); file signatures of PNG and PDF.
"""

import contextlib
import re
import shutil
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from matplotlib.image import imread

from lubecontact import grid

ROOT = Path(__file__).resolve().parents[1]
TREE = ("Snakefile", "config", "workflow", "src")
TINY = ("--configfile", "config/test.yaml")
PROFILE = ("--workflow-profile", "workflow/profiles/default")
FIGURES = [f"fig{n:02d}" for n in range(3, 12)]
# swept dimension of each figure's data in the tiny config (test.yaml: 2 values, 4 speeds)
SWEPT = {"fig03": "mesh", "fig04": "sigma", "fig05": "sigma", "fig06": "radius", "fig07": "radius",
         "fig08": "force", "fig09": "force", "fig10": "viscosity", "fig11": "viscosity"}


def copy_tree(dest: Path) -> Path:
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info", ".snakemake", "*.pyc")
    for name in TREE:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, dest / name, ignore=ignore)
        else:
            shutil.copy2(src, dest / name)
    return dest


def snakemake(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    done = subprocess.run([sys.executable, "-m", "snakemake", *args], cwd=cwd, capture_output=True, text=True, timeout=900)
    if done.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{done.stdout[-4000:]}\n{done.stderr[-6000:]}")
    return done


def planned(cwd: Path, *args: str) -> Counter:
    """Jobs a dry run would run, per rule (solve_* chunk rules counted as 'solve')."""
    out = snakemake(cwd, "-n", "--quiet", "rules", *args).stdout
    jobs = Counter()
    table = re.search(r"job\s+count\n-+\s+-+\n(.*?)\ntotal", out, re.S)
    for line in table.group(1).splitlines() if table else []:
        rule, count = line.split()
        jobs["solve" if rule.startswith("solve_") else rule] += int(count)
    return jobs


@contextlib.contextmanager
def edited(path: Path, old: str, new: str):
    """The file with one text replaced, restored byte for byte afterwards."""
    original = path.read_bytes()
    text = original.decode()
    assert old in text, f"{old!r} not in {path}"
    path.write_text(text.replace(old, new, 1))
    try:
        yield
    finally:
        path.write_bytes(original)


# the accuracy_cost study (workflow/rules/accuracy.smk): one timed solve job, table, figure
ACCURACY = {"accuracy_solve": 1, "accuracy_table": 1, "accuracy_figure": 1}
# the transient figures (workflow/rules/transient.smk, config/transient.yaml): test.yaml has
# 2 stop curves (Table 1, mu = 0.3), the same 2 cases as the reconnect chart, 1 vibration
TRANSIENT = {"transient_case": 3, "transient_figure": 3}
TRANSIENT_FIGURES = ["transient_stop", "transient_reconnect", "transient_vibration"]


# --- plans and lint (no solving) ---------------------------------------------------------------


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    return copy_tree(tmp_path_factory.mktemp("fresh"))


@pytest.mark.slow
def test_tiny_config_plans_every_figure(fresh):
    # test.yaml: 5 grids of 2 curves on the same coarse mesh, each with the base value, so
    # the baseline curve is shared: 1 + 5 curves = 6 jobs of 4 speeds; 9 figures.
    assert planned(fresh, *TINY) == Counter(solve=6, collect=9, plot=9, all=1, **ACCURACY, **TRANSIENT)


@pytest.mark.slow
def test_default_grids(fresh):
    # fig03: 7 meshes up to 201^2 (51^2 is the baseline); fig04: 4 sigma, fig06: 4 radii,
    # fig10: 4 viscosities, each with the baseline; fig08: 5 forces with the baseline;
    # fig05/07/09/11 reuse those grids: 7 + 3 + 3 + 4 + 3 = 20 curves of 26 speeds.
    # transient: 5 stop curves + 7 viscosities x 3 forces, 3 of them stop curves, + 1 vibration
    transient = {"transient_case": 5 + 21 - 3 + 1, "transient_figure": 3}
    assert planned(fresh) == Counter(solve=20, collect=9, plot=9, all=1, **ACCURACY, **transient)
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    specs = {f: grid.figure_spec(f, ROOT / config["figure_dir"]) for f in config["figures"]}
    cases = {c for g in grid.expand_all(specs, ROOT).values() for c in g.unique_cases()}
    assert len(cases) == 20 * 26


@pytest.mark.slow
def test_lint(fresh):
    out = snakemake(fresh, "--lint")
    assert "Congratulations" in out.stdout + out.stderr


@pytest.mark.slow
def test_bad_grid_value_fails_at_parse_time_naming_it(fresh):
    config = fresh / "config" / "test.yaml"
    with edited(config, "sweep: {roughness.sigma: [0.5e-6, 1.0e-6]}", "sweep: {roughness.sigma: [0.5e-6, -1.0e-6]}"):
        done = subprocess.run([sys.executable, "-m", "snakemake", "-n", *TINY], cwd=fresh, capture_output=True, text=True, timeout=300)
    assert done.returncode != 0
    message = done.stdout + done.stderr
    assert "GridError" in message and "figure fig04" in message and "roughness.sigma = -1e-06: out of range" in message


# --- end to end: the tiny grids ----------------------------------------------------------------


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    tree = copy_tree(tmp_path_factory.mktemp("built"))
    snakemake(tree, *PROFILE, "--cores", "2", *TINY)
    return tree


@pytest.mark.slow
def test_data_files_have_dimensions_units_and_provenance(built):
    for figure in FIGURES:
        ds = xr.load_dataset(built / "results" / "data" / f"{figure}.nc")
        assert dict(ds.sizes) == {SWEPT[figure]: 2, "speed": 4}, figure
        np.testing.assert_allclose(ds["speed"].values, [1e-3, 0.1, 1.0, 10.0])
        for name, var in ds.variables.items():
            if var.dtype.kind in "fiu":
                assert var.attrs.get("units") and var.attrs.get("long_name"), (figure, name)
        assert ds["contact_resistance"].attrs["units"] == "ohm"
        assert ds["speed"].attrs["units"] == "m s-1" and ds["force"].attrs["units"] == "N"
        assert ds.attrs["lubecontact_version"] and "roughness" in ds.attrs["base_scene"]
        assert set(ds["converged"].values.ravel()) <= {0, 1}
        for case_id in ds["case_id"].values.ravel():
            assert (built / "results" / "cases" / f"{case_id}.nc").is_file()
    fig03 = xr.load_dataset(built / "results" / "data" / "fig03.nc")
    assert fig03["nx"].values.tolist() == [15, 21] and fig03["ny"].values.tolist() == [11, 15]
    # one baseline case, one file: fig04 (sigma = 0.5 um) and fig08 (F = 5 N) share it
    fig04 = xr.load_dataset(built / "results" / "data" / "fig04.nc")
    fig08 = xr.load_dataset(built / "results" / "data" / "fig08.nc")
    assert (fig04["case_id"].sel(sigma=0.5e-6).values == fig08["case_id"].sel(force=5.0).values).all()


@pytest.mark.slow
def test_physical_trends(built):
    for figure in ("fig03", "fig04", "fig06", "fig08", "fig10"):
        ds = xr.load_dataset(built / "results" / "data" / f"{figure}.nc")
        resistance = ds["contact_resistance"].transpose(..., "speed").values
        assert (np.diff(resistance, axis=-1) > 0).all(), f"{figure}: resistance must rise with speed"
        slowest = ds["friction_coefficient"].isel(speed=0).values
        np.testing.assert_allclose(slowest, 0.1, rtol=0.01)  # asperities carry ~all: f -> mu_b
    fastest = {f: xr.load_dataset(built / "results" / "data" / f"{f}.nc")["contact_resistance"].isel(speed=-1) for f in ("fig04", "fig08", "fig10")}
    assert fastest["fig04"].sel(sigma=1e-6) < fastest["fig04"].sel(sigma=0.5e-6)  # rougher: lower
    assert fastest["fig08"].sel(force=10.0) < fastest["fig08"].sel(force=5.0)  # more force: lower
    assert fastest["fig10"].sel(viscosity=0.03) < fastest["fig10"].sel(viscosity=0.1)  # thinner: lower


@pytest.mark.slow
def test_transient_cases_have_units_and_reconnect(built):
    cases = sorted((built / "results" / "transient").glob("*.nc"))
    assert len(cases) == 3
    for path in cases:
        ds = xr.load_dataset(path)
        assert ds.attrs["scene_hash"] == path.stem and ds["converged"].item() == 1
        for name, var in ds.variables.items():
            assert var.attrs.get("units") and var.attrs.get("long_name"), (path.stem, name)
        kind = yaml.safe_load(ds.attrs["scene"])["motion"]["kind"]
        if kind == "stop":  # Table 1 and mu = 0.3 Pa s reconnect within the 50 ms run
            assert 0.0 < ds["reconnect_time"].item() < 0.05
        else:
            assert ds["peak_resistance"].size == 1 and 0.0 <= ds["open_fraction"].item() <= 1.0


@pytest.mark.slow
def test_figures_are_images(built):
    for figure in FIGURES + TRANSIENT_FIGURES:
        png = built / "results" / "figures" / f"{figure}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        height, width, _ = imread(png).shape
        assert height > 300 and width > 400
        assert (built / "results" / "figures" / f"{figure}.pdf").read_bytes()[:5] == b"%PDF-"


@pytest.mark.slow
def test_nothing_to_do_after_a_build(built):
    assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_plot_style_change_only_redraws(built):
    with edited(built / "config" / "figures" / "fig06.yaml", 'title: "cylinder radius R"', 'title: "radius"'):
        assert planned(built, *TINY) == Counter(plot=1, all=1)
    with edited(built / "src" / "lubecontact" / "plotting.py", '"\\u2013",\n', '"-",\n'):
        assert planned(built, *TINY) == Counter(plot=9, all=1)


@pytest.mark.slow
def test_one_grid_value_solves_one_curve(built):
    with edited(built / "config" / "test.yaml", "roughness.sigma: [0.5e-6, 1.0e-6]", "roughness.sigma: [0.5e-6, 2.0e-6]"):
        assert planned(built, *TINY) == Counter(solve=1, collect=2, plot=2, all=1)  # fig04, fig05


@pytest.mark.slow
def test_solver_change_resolves_every_case_and_content_decides(built):
    solver = built / "src" / "lubecontact" / "solver.py"
    with edited(solver, '"""', '"""Edited. '):  # the transient cases run the solver too
        assert planned(built, *TINY) == Counter(solve=6, collect=9, plot=9, all=1, **ACCURACY, **TRANSIENT)
    # restored: newer time stamp, same content -> nothing to do
    assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_report(built):
    snakemake(built, "--report", "report.html", *TINY)
    html = (built / "report.html").read_text(errors="replace")
    assert "fig04" in html and "effective RMS roughness" in html.replace("\n", " ")


@pytest.mark.slow
def test_new_speed_solves_only_new_cases(built):
    """Runs last: changes the built tree."""
    cases = built / "results" / "cases"
    # a rewritten case is a new file (temp file + rename): a new inode; Snakemake only
    # touches the outputs of a job it ran
    before = {p.name: p.stat().st_ino for p in cases.glob("*.nc")}
    config = built / "config" / "test.yaml"
    config.write_text(config.read_text().replace("    speeds: *speeds\n", "    speeds: [1.0e-3, 0.1, 1.0, 3.0, 10.0]\n", 1))
    assert planned(built, *TINY) == Counter(solve=2, collect=2, plot=2, all=1)
    snakemake(built, *PROFILE, "--cores", "2", *TINY)
    after = {p.name: p.stat().st_ino for p in cases.glob("*.nc")}
    assert {name: after[name] for name in before} == before  # no case file rewritten
    assert len(after) - len(before) == 2  # 3 m/s for sigma = 0.5 and 1 um
    logs = "".join(p.read_text() for p in (built / "results" / "logs" / "solve").glob("fig04_*.log"))
    assert logs.count("kept") == 4 and logs.count("converged") >= 2
    assert xr.load_dataset(built / "results" / "data" / "fig04.nc").sizes["speed"] == 5
