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
import html.parser
import json
import math
import re
import shutil
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from matplotlib.image import imread

from lubecontact.plotting.transient import closed_form_stop_film, film_at_stop
from lubecontact.scene import load_scene
from lubecontact.studies import figure_grids as grid

ROOT = Path(__file__).resolve().parents[1]
TREE = ("Snakefile", "config", "workflow", "src")
TINY = ("--configfile", "config/test.yaml")
PROFILE = ("--workflow-profile", "workflow/profiles/default")
FIGURES = [f"fig{n:02d}" for n in range(3, 12)] + ["fig04_alpha", "fig04_measured"]
# swept dimension of each figure's data in the tiny config (test.yaml: 2 values, 4 speeds)
SWEPT = {"fig03": "mesh", "fig04": "sigma", "fig05": "sigma", "fig06": "radius", "fig07": "radius",
         "fig08": "force", "fig09": "force", "fig10": "viscosity", "fig11": "viscosity",
         "fig04_alpha": "roughness", "fig04_measured": "surface"}


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
# the measured surfaces' spectra (workflow/rules/surfaces.smk)
SURFACES = {"surfaces_psd": 1}
# the transient figures (workflow/rules/transient.smk, config/transient.yaml): test.yaml has
# 2 stop curves (Table 1, mu = 0.3), the same 2 cases as the reconnect chart, 2 temperatures
# of the datasheet oil, 1 vibration, 2 shocks, the accuracy ladders' 4 more (meshes 21 and
# 41, tolerances 3e-3 and 1e-3; 31 nodes at 1e-2 is the stop figure's case) with their table,
# and 2 greases, which are also the yield-stress chart's 2 cases
TRANSIENT = {"transient_case": 15, "transient_figure": 7, "transient_accuracy": 1}
# the curves swept speeding up and slowing down (workflow/rules/hysteresis.smk, config key
# hysteresis: [fig08]): test.yaml's fig08 has 2 curves (5 and 10 N) of 4 speeds, one figure
HYSTERESIS = {"hysteresis_curve": 2, "hysteresis_figure": 1}
TRANSIENT_FIGURES = ["transient_stop", "transient_reconnect", "transient_temperature", "transient_vibration",
                     "transient_shock", "transient_accuracy", "transient_grease", "transient_yield_stress"]


# --- plans and lint (no solving) ---------------------------------------------------------------


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    return copy_tree(tmp_path_factory.mktemp("fresh"))


@pytest.mark.slow
def test_tiny_config_plans_every_figure(fresh):
    # test.yaml: 6 grids of 2 curves on the same coarse mesh, 5 with the base value, so the
    # baseline curve is shared: 1 + 5 + 1 curves; fig04_measured: 2 surfaces: 9 jobs of 4
    # speeds. With the full electrical path (fig04p-10p): 1 + 4 curves; fig12: 2 x 2 curves
    # of 3 speeds, one of them 3 of the 4 cases of fig08p's 10 N curve (the figure planned
    # first claims them, the other keeps its own: one job more): 4 jobs; 16 figures; the transient cases and figures.
    assert planned(fresh, *TINY) == Counter(solve=18, collect=16, plot=16, all=1, **ACCURACY, **SURFACES, **TRANSIENT,
                                            **HYSTERESIS)


@pytest.mark.slow
def test_default_grids(fresh):
    # fig03: 7 meshes up to 201^2 (51^2 is the baseline); fig04: 4 sigma, fig06: 4 radii,
    # fig10: 4 viscosities, each with the baseline; fig08: 5 forces with the baseline;
    # fig05/07/09/11 reuse those grids: 7 + 3 + 3 + 4 + 3 = 20 curves; fig04_alpha: 4 (sigma,
    # R_peak) pairs with the baseline, fig04_measured: 2 surfaces: 25 curves of 26 speeds;
    # the full path (fig04p-10p) 1 + 3 + 3 + 4 + 3 = 14 curves of 26 speeds; fig12: 16 curves of 16.
    # transient: 5 stop curves + 7 viscosities x 3 forces (3 of them stop curves: Table 1,
    # mu = 1 Pa s, F = 2 N) + 6 temperatures x 2 forces (the datasheet oil) + 1 vibration +
    # 3 shocks + the accuracy ladders' meshes 31, 51, 101, 201 along x (21 along y) and
    # tolerances 2e-3, 5e-4 (51 x 51 at 1e-3 is the stop figure's Table 1 case) + the oil and 3
    # greases at 0.5 N + 5 yield stresses x 3 forces (3 of them the grease figure's)
    transient = {"transient_case": 5 + 21 - 3 + 12 + 1 + 3 + 6 + 4 + 15 - 3, "transient_figure": 7,
                 "transient_accuracy": 1}
    # fig08's 5 forces, each curve swept both ways
    assert planned(fresh) == Counter(solve=55, collect=16, plot=16, all=1, **ACCURACY, **SURFACES, **transient,
                                     hysteresis_curve=5, hysteresis_figure=1)
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    specs = {f: grid.figure_spec(f, ROOT / config["figure_dir"]) for f in config["figures"]}
    cases = {c for g in grid.expand_all(specs, ROOT).values() for c in g.unique_cases()}
    assert len(cases) == 25 * 26 + 14 * 26 + 16 * 16


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
    # a value the figure schema refuses names the figure and its file too (a hostile run's
    # finding, thirtieth session: Snakemake's "Error validating config file" named neither)
    with edited(config, "sweep: {roughness.sigma: [0.5e-6, 1.0e-6]}", "sweep: {roughness.sigma: []}"):
        done = subprocess.run([sys.executable, "-m", "snakemake", "-n", *TINY], cwd=fresh, capture_output=True, text=True, timeout=300)
    message = done.stdout + done.stderr
    assert done.returncode != 0 and "figure fig04 (config/figures/fig04.yaml" in message and "figure.schema.yaml" in message
    # and a plot: section is checked at planning, not in its plot job
    with edited(config, "sweep: {roughness.sigma: [0.5e-6, 1.0e-6]}",
                "sweep: {roughness.sigma: [0.5e-6, 1.0e-6]}\n    plot: {y: contact_resistence, x: [speed]}"):
        done = subprocess.run([sys.executable, "-m", "snakemake", "-n", *TINY], cwd=fresh, capture_output=True, text=True, timeout=300)
    message = done.stdout + done.stderr
    assert done.returncode != 0 and "figure fig04, plot.y = 'contact_resistence'" in message


# --- end to end: the tiny grids ----------------------------------------------------------------


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    tree = copy_tree(tmp_path_factory.mktemp("built"))
    snakemake(tree, *PROFILE, "--cores", "2", *TINY)
    return tree


@pytest.mark.slow
def test_data_files_have_dimensions_units_and_provenance(built):
    for figure in FIGURES:
        ds = xr.load_dataset(built / "results" / "test" / "data" / f"{figure}.nc")
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
            assert (built / "results" / "test" / "cases" / f"{case_id}.nc").is_file()
    fig03 = xr.load_dataset(built / "results" / "test" / "data" / "fig03.nc")
    assert fig03["nx"].values.tolist() == [15, 21] and fig03["ny"].values.tolist() == [11, 15]
    # one baseline case, one file: fig04 (sigma = 0.5 um) and fig08 (F = 5 N) share it
    fig04 = xr.load_dataset(built / "results" / "test" / "data" / "fig04.nc")
    fig08 = xr.load_dataset(built / "results" / "test" / "data" / "fig08.nc")
    assert (fig04["case_id"].sel(sigma=0.5e-6).values == fig08["case_id"].sel(force=5.0).values).all()


@pytest.mark.slow
def test_physical_trends(built):
    for figure in ("fig03", "fig04", "fig06", "fig08", "fig10"):
        ds = xr.load_dataset(built / "results" / "test" / "data" / f"{figure}.nc")
        resistance = ds["contact_resistance"].transpose(..., "speed").values
        assert (np.diff(resistance, axis=-1) > 0).all(), f"{figure}: resistance must rise with speed"
        slowest = ds["friction_coefficient"].isel(speed=0).values
        contact_share = 1.0 - ds["fluid_load_fraction"].isel(speed=0).values
        assert (contact_share > 0.95).all(), f"{figure}: asperities carry ~all at the slowest speed"
        # viscous shear negligible there: f -> mu_b F_cont / F (the fluid carries up to 2.6 % at
        # 1e-3 m/s on these 15 x 11 meshes since sealed pockets hold their pressure: README)
        np.testing.assert_allclose(slowest, 0.1 * contact_share, rtol=0.01)
    fastest = {f: xr.load_dataset(built / "results" / "test" / "data" / f"{f}.nc")["contact_resistance"].isel(speed=-1) for f in ("fig04", "fig08", "fig10")}
    assert fastest["fig04"].sel(sigma=1e-6) < fastest["fig04"].sel(sigma=0.5e-6)  # rougher: lower
    assert fastest["fig08"].sel(force=10.0) < fastest["fig08"].sel(force=5.0)  # more force: lower
    assert fastest["fig10"].sel(viscosity=0.03) < fastest["fig10"].sel(viscosity=0.1)  # thinner: lower


@pytest.mark.slow
def test_transient_cases_have_units_and_reconnect(built):
    cases = sorted((built / "results" / "test" / "transient").glob("*.nc"))
    assert len(cases) == 15
    for path in cases:
        ds = xr.load_dataset(path)
        assert ds.attrs["scene_hash"] == path.stem and ds["converged"].item() == 1
        for name, var in ds.variables.items():
            assert var.attrs.get("units") and var.attrs.get("long_name"), (path.stem, name)
        scene = yaml.safe_load(ds.attrs["scene"])
        kind = scene["motion"]["kind"]
        # (a datasheet oil's scene, which carries its derived viscosity, is not loaded again)
        grease = load_scene(scene) if scene["lubricant"].get("rheology") == "bingham" else None
        if grease is not None and closed_form_stop_film(grease, film_at_stop(ds)) is not None:
            # the 5 kPa grease: its yield stress alone holds the load in the full film, open throughout
            assert math.isinf(ds["reconnect_time"].item())
            at_rest = ds["time"].values >= grease.motion.stop_time + grease.motion.ramp
            assert (ds["contact_resistance"].values[at_rest] > ds["open_resistance"].item()).all()
        elif kind == "stop":  # Table 1, mu = 0.3 Pa s, the VG 100 oil at 20 and 45 C and the 1 kPa
            assert 0.0 < ds["reconnect_time"].item() < 0.05  # grease reconnect within the 50 ms run
        elif kind == "oscillation":
            assert ds["peak_resistance"].size == 1 and 0.0 <= ds["open_fraction"].item() <= 1.0
        else:  # a shock: 30 g (m a below the 0.5 N preload) stays closed, 100 g (above) opens
            pull = -scene["motion"]["mass"] * scene["motion"]["vibration_acceleration"]
            assert (ds["event_count"].item() > 0) == (pull > scene["operating"]["force"])
    # the accuracy ladders: every member reconnects, each ladder is extrapolated. (Since the
    # squeeze term takes each cell's content the 21- to 41-node meshes are within the time
    # error of 1e-2 of each other, 7.5-8.2 ms, no longer growing with the mesh as with nodal
    # content: bench/EXPERIMENTS.md, twelfth session)
    ladder = xr.load_dataset(built / "results" / "test" / "data" / "transient_accuracy.nc")
    for part in ("mesh", "tolerance"):
        times = ladder[f"{part}_reconnect_time"].values
        assert np.all(np.isfinite(times) & (times > 0.0)) and np.isfinite(float(ladder[f"{part}_extrapolated"]))
        assert np.isfinite(ladder[f"{part}_error"].values).all() and ladder.attrs["notes"] == ""


@pytest.mark.slow
def test_figures_are_images(built):
    for figure in FIGURES + ["surfaces_psd", "hysteresis_fig08"] + TRANSIENT_FIGURES:
        png = built / "results" / "test" / "figures" / f"{figure}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        height, width, _ = imread(png).shape
        assert height > 300 and width > 400
        assert (built / "results" / "test" / "figures" / f"{figure}.pdf").read_bytes()[:5] == b"%PDF-"


@pytest.mark.slow
def test_nothing_to_do_after_a_build(built):
    assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_plot_style_change_only_redraws(built):
    with edited(built / "config" / "figures" / "fig06.yaml", 'title: "cylinder radius R"', 'title: "radius"'):
        assert planned(built, *TINY) == Counter(plot=1, all=1)
    with edited(built / "src" / "lubecontact" / "plotting" / "figures.py", '"\\u2013",\n', '"-",\n'):
        assert planned(built, *TINY) == Counter(plot=16, hysteresis_figure=1, all=1)  # it draws with figures.py's styles
    # the collecting code re-collects (found by a hostile run in the thirtieth session: an
    # edit of it left every dataset stale)
    with edited(built / "src" / "lubecontact" / "studies" / "collect.py", '"""', '"""Edited. '):
        assert planned(built, *TINY) == Counter(collect=16, plot=16, all=1)
    # the CLI and the studies' planning decide no case: editing them reruns nothing
    with edited(built / "src" / "lubecontact" / "cli" / "main.py", '"""', '"""Edited. '):
        assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_one_grid_value_solves_one_curve(built):
    with edited(built / "config" / "test.yaml", "roughness.sigma: [0.5e-6, 1.0e-6]", "roughness.sigma: [0.5e-6, 2.0e-6]"):
        assert planned(built, *TINY) == Counter(solve=2, collect=3, plot=3, all=1)  # fig04, fig05, fig04p


@pytest.mark.slow
def test_solver_change_resolves_every_case_and_content_decides(built):
    solver = built / "src" / "lubecontact" / "model" / "coupling.py"  # the coupling loop: steady and transient
    with edited(solver, '"""', '"""Edited. '):  # the transient cases run the solver too
        assert planned(built, *TINY) == Counter(solve=18, collect=16, plot=16, all=1, **ACCURACY, **TRANSIENT, **HYSTERESIS)
    # restored: newer time stamp, same content -> nothing to do
    assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_measured_surfaces_and_fixed_alpha(built):
    """fig04_measured: the rougher, sharper sample (honed, sigma ~1 um, R_peak ~26 um) keeps
    lower resistance at speed; fig04_alpha: sigma R_peak held, the curves are other cases
    than fig04's except the shared baseline."""
    measured = xr.load_dataset(built / "results" / "test" / "data" / "fig04_measured.nc")
    fastest = measured["contact_resistance"].isel(speed=-1)
    assert measured["surface"].values.tolist() == ["../surfaces/ground.asc", "../surfaces/honed.asc"]
    assert fastest.sel(surface="../surfaces/honed.asc") < fastest.sel(surface="../surfaces/ground.asc")
    alpha = xr.load_dataset(built / "results" / "test" / "data" / "fig04_alpha.nc")
    assert (alpha["sigma"] * alpha["asperity_radius"]).values == pytest.approx([5e-11, 5e-11])
    fig04 = xr.load_dataset(built / "results" / "test" / "data" / "fig04.nc")
    assert (alpha["case_id"].isel(roughness=0).values == fig04["case_id"].sel(sigma=0.5e-6).values).all()
    assert not set(alpha["case_id"].isel(roughness=1).values) & set(fig04["case_id"].values.ravel())


@pytest.mark.slow
def test_surface_file_content_decides_its_cases(built):
    """Editing one height of ground.asc reruns its curve (and the spectra), nothing else."""
    path = built / "config" / "surfaces" / "ground.asc"
    first = path.read_text().splitlines()[4].split()[0]  # the first height, after the header
    with edited(path, f"\n{first} ", f"\n{float(first) * 1.5:.5e} "):
        assert planned(built, *TINY) == Counter(solve=1, collect=1, plot=1, all=1, **SURFACES)
    assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_report(built):
    snakemake(built, "--report", "report.html", *TINY)
    html = (built / "report.html").read_text(errors="replace")
    assert "fig04" in html and "effective RMS roughness" in html.replace("\n", " ")


@pytest.mark.slow
def test_test_config_writes_only_its_own_directory(built):
    assert sorted(p.name for p in (built / "results").iterdir()) == ["test"]  # config key results


@pytest.mark.slow
def test_products_pass_the_cf_checker(built):
    from cfcheck import cf_findings

    out = built / "results" / "test"
    case = next((out / "cases").glob("*.nc"))
    files = [case, out / "data" / "fig03.nc", out / "data" / "fig04.nc", out / "data" / "accuracy_cost.nc", out / "accuracy" / "study.nc",
             next((out / "hysteresis").glob("*.nc"))]
    assert [f for path in files for f in cf_findings(path)] == []


class LandingPage(html.parser.HTMLParser):
    """The report's landing page as a reader sees it: its headings, the figures named in bold,
    and docutils' system messages (warnings a broken page shows)."""

    def __init__(self, report: str):
        super().__init__()
        self.headings, self.bold, self.messages, self._in = [], [], [], None
        start = report.index('var workflow_desc = "') + len("var workflow_desc = ")
        self.feed(json.JSONDecoder().raw_decode(report[start:])[0])

    def handle_starttag(self, tag, attrs):
        if tag in ("h1", "h2", "strong"):
            self._in = tag
        if "system-message" in (dict(attrs).get("class") or ""):
            self.messages.append(dict(attrs))

    def handle_endtag(self, tag):
        self._in = None if tag == self._in else self._in

    def handle_data(self, data):
        if self._in in ("h1", "h2"):
            self.headings.append(data.strip())
        elif self._in == "strong":
            self.bold.append(data.strip())


@pytest.mark.slow
def test_report_landing_page_names_every_figure_without_warnings(built):
    """Issue 29 item 13: the page rendered (no docutils system message), headed for what the
    run makes, and naming every figure of the run: the sweeps, the transients, the measured
    surfaces and the accuracy study."""
    snakemake(built, "--report", "report.html", *TINY)
    page = LandingPage((built / "report.html").read_text(errors="replace"))
    assert page.messages == []
    assert "Figures 3-11" not in " ".join(page.headings)
    assert {"The contact in time", "Measured surfaces", "What accuracy costs"} <= set(page.headings)
    figures = {p.stem for p in (built / "results" / "test" / "figures").glob("*.png")}
    assert figures and figures <= set(page.bold)


@pytest.mark.slow
def test_report_landing_page_says_what_the_run_is(built):
    snakemake(built, "--report", "report.html", *TINY)
    html = (built / "report.html").read_text(errors="replace")
    import lubecontact

    assert f"lubecontact version: {lubecontact.__version__}" in html and "git commit of the workflow tree" in html
    assert "roughness.sigma = 5e-07, 1e-06" in html and "config/scenes/table1.yaml" in html
    assert re.search(r"solve_fig04_sigma_1e_06_[0-9a-f]{6}", html)  # readable rule names


@pytest.mark.slow
def test_a_redirected_build_says_each_finished_job(built):
    """Issue 29 item 14: with the output going to a file, the default profile still prints a
    line per finished job (no progress bar can), and Snakemake's log file holds them too.
    And the run ends with its log: the scheduler's pending re-examinations, one profile
    timespan (60 s) long, are cancelled once the run is over (workflow/rules/scheduler.smk)."""
    done = snakemake(built, *PROFILE, "--cores", "2", *TINY, "--forcerun", "plot", "results/test/figures/fig04.png",
                     "results/test/figures/fig05.png")
    ended = time.time()
    printed = done.stdout + done.stderr
    jobs = int(re.search(r"total\s+(\d+)", printed).group(1))
    assert printed.count("Finished jobid") == jobs and f"{jobs} of {jobs} steps (100%) done" in printed
    log = Path(re.search(r"Complete log\(s\): (\S+)|Complete Log: (\S+)", printed).group(0).split()[-1])
    assert log.read_text().count("Finished jobid") == jobs
    timespan = yaml.safe_load((ROOT / "workflow/profiles/default/config.yaml").read_text())["max-jobs-per-timespan"]
    assert timespan == "1000/60s" and ended - log.stat().st_mtime < 20.0, ended - log.stat().st_mtime


@pytest.mark.slow
def test_quiet_dry_run_without_parameter_dumps(fresh):
    """No job's inputs, outputs or parameters are listed (a solve job has ~20 files and its
    scenes): the job table and the reasons only. The plain logger's table has a row per
    solve chunk (it was 60 lines with the rich logger's, 75 now for the 61 jobs of test.yaml)."""
    out = snakemake(fresh, *PROFILE, *TINY, "-n")
    text = out.stdout + out.stderr
    assert not re.search(r"^\s*(input|output|params|wildcards):", text, re.M)
    assert len(text.splitlines()) < 100 and "'set'" not in text and "scene_hash" not in text


@pytest.mark.slow
def test_corrupt_or_deleted_files_are_restored_by_one_plain_rerun(built):
    """Issue 13: a truncated case, a deleted case and a truncated figure dataset (which
    failed every rerun until the thirtieth session); one plain run moves the bad files aside
    (naming them), re-solves, re-collects and re-draws."""
    out = built / "results" / "test"
    fig04 = xr.load_dataset(out / "data" / "fig04.nc")
    truncated = out / "cases" / f"{fig04['case_id'].values[1, 2]}.nc"  # sigma = 1 um, 1 m/s
    deleted = out / "cases" / f"{xr.load_dataset(out / 'data' / 'fig10.nc')['case_id'].values[0, 0]}.nc"  # viscosity 0.03
    reference = xr.load_dataset(truncated)
    truncated.write_bytes(truncated.read_bytes()[:2000])
    deleted.unlink()
    dataset = out / "data" / "fig08.nc"
    dataset.write_bytes(dataset.read_bytes()[:500])
    figures_before = {p.name: p.stat().st_mtime_ns for p in (out / "figures").glob("fig*.png")}
    done = snakemake(built, *PROFILE, "--cores", "2", *TINY)
    assert f"results/test/cases/{truncated.name}: unreadable" in done.stderr and ".corrupt" in done.stderr
    assert "results/test/data/fig08.nc: unreadable" in done.stderr and "it will be built again" in done.stderr
    repaired = xr.load_dataset(truncated)
    assert repaired["contact_resistance"].item() == pytest.approx(reference["contact_resistance"].item(), rel=1e-9)
    assert deleted.is_file() and (out / "data" / "fig08.nc").is_file()
    redrawn = {p.name for p in (out / "figures").glob("fig*.png") if p.stat().st_mtime_ns != figures_before[p.name]}
    # and the full-path figures drawn over those datasets (compare: figNN)
    assert redrawn == {"fig04.png", "fig05.png", "fig08.png", "fig10.png", "fig11.png", "fig04p.png", "fig08p.png", "fig10p.png"}
    assert len(list((out / "cases" / ".corrupt").glob("*.nc"))) == 1
    assert len(list((out / "data" / ".corrupt").glob("*.nc"))) == 1 and xr.load_dataset(dataset)["case_id"].size
    assert planned(built, *TINY) == Counter()


@pytest.mark.slow
def test_new_speed_solves_only_new_cases(built):
    """Runs last: changes the built tree."""
    cases = built / "results" / "test" / "cases"
    # a rewritten case is a new file (temp file + rename): a new inode; Snakemake only
    # touches the outputs of a job it ran
    before = {p.name: p.stat().st_ino for p in cases.glob("*.nc")}
    logs_before = {p.name for p in (built / "results" / "test" / "logs" / "solve").glob("*.log")}
    config = built / "config" / "test.yaml"
    config.write_text(config.read_text().replace("    speeds: *speeds\n", "    speeds: [1.0e-3, 0.1, 1.0, 3.0, 10.0]\n", 1))
    # fig04 and fig04p, 2 curves each; fig04p's chunk of the full-path baseline changes, so the
    # figures sharing that curve (fig06p, fig08p, fig10p) collect again
    assert planned(built, *TINY) == Counter(solve=4, collect=6, plot=6, all=1)
    snakemake(built, *PROFILE, "--cores", "2", *TINY)
    after = {p.name: p.stat().st_ino for p in cases.glob("*.nc")}
    assert {name: after[name] for name in before} == before  # no case file rewritten
    assert len(after) - len(before) == 4  # 3 m/s for sigma = 0.5 and 1 um, paper and full path
    # the two fig04 chunks have new members, hence new names and logs (older logs stay)
    logs = "".join(p.read_text() for p in (built / "results" / "test" / "logs" / "solve").glob("fig04_*.log") if p.name not in logs_before)
    assert logs.count("kept") == 4 and logs.count("converged") >= 2
    assert xr.load_dataset(built / "results" / "test" / "data" / "fig04.nc").sizes["speed"] == 5
