"""The long runs behind the numbers README.md quotes (scripts/doc_numbers.py calls this):
transient stops of the Table 1 contact and its oil and grease variants (film, reconnect
time, steps, their mesh dependence and CPU time), the cases of the transient study's grease
figure (config/transient.yaml figures.grease), the accuracy study of
config/accuracy.yaml (the coarsest mesh for a target error, observed orders) and the
transient's (config/transient.yaml's ``accuracy`` ladders: the reconnect time's mesh and
time-step errors).

Each function returns the text of one block ``<!-- run:NAME -->…<!-- /run -->`` of
README.md; doc_numbers.py writes them with ``--runs`` (minutes: every transient below one
after another, then the accuracy study). Times are CPU or wall times of this machine, so
every block that quotes one says when and where it was measured; no test checks them. A
result is checked by ``doc_numbers.py --check`` when it is cheap (CHECKED: seconds), inside
its block between ``<!-- measured:NAME -->`` and ``<!-- /measured -->``.
"""

import contextlib
import datetime
import io
import json
import math
import os
import platform
import subprocess
import time
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from lubecontact.physics.yield_stress_flow import bingham_squeeze_stop_film
from lubecontact.plotting.transient import closed_form_stop_film, film_at_stop
from lubecontact.scene import load_scene
from lubecontact.studies import transient_cases
from lubecontact.studies.accuracy import accuracy_table, cost_table, run_study
from lubecontact.studies.accuracy_plan import study_spec
from lubecontact.studies.transient_accuracy import ladder_table, least_work_within
from lubecontact.studies.transient_cases import figure_cases
from lubecontact.studies.transient_cases import study_spec as transient_spec
from lubecontact.unsteady.transient import PERCOLATION_ALTERNATIVES, transient

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "config" / "scenes"
# A stop from 1 m/s over 1 ms (motion.ramp's default), reconnected at 2 x the resting resistance
TABLE1_STOP = {"motion.kind": "stop", "motion.speed": 1.0}
# a row that compares its run with another row's on the same mesh: the one run, without the
# mesh error bar the default adds (a second run of about three times the first's CPU)
ALONE = {"motion.mesh_error_bar": False}
OIL = 0.1  # s simulated: the oils reconnect within milliseconds
GREASE = 1000.0  # s simulated: the greases within seconds

# 2-D percolation's universal conductivity exponent (the default 1 is the effective medium's):
# how much the model's own law below Patir-Cheng's range moves a reconnect time
PERCOLATION_EXPONENT = PERCOLATION_ALTERNATIVES[1]
# name -> (row label, scene file, overrides): the reconnect table
RECONNECT = {
    "table1": ("0.1 Pa s oil (Table 1)", "table1.yaml", {**TABLE1_STOP, "motion.duration": OIL}),
    "table1_101": ("0.1 Pa s oil (Table 1), 101 × 101 nodes", "table1.yaml",
                   {**TABLE1_STOP, "motion.duration": OIL, "mesh.nx": 101, "mesh.ny": 101, **ALONE}),
    "table1_rest4": ("0.1 Pa s oil (Table 1), the mesh at rest 4 times finer along x", "table1.yaml",
                     {**TABLE1_STOP, "motion.duration": OIL, "motion.rest_refinement": 4, **ALONE}),
    "vg100": ("ISO VG 100 mineral oil, 0.087 Pa s (`stop_hydrocarbon_oil.yaml`)", "stop_hydrocarbon_oil.yaml", {"motion.duration": OIL}),
    "grease": ("grease-like, 10 Pa s (`stop_grease.yaml`)", "stop_grease.yaml", {"motion.duration": GREASE}),
    "grease_1N": ("grease-like, 10 Pa s, F = 1 N", "stop_grease.yaml",
                  {"motion.duration": GREASE, "operating.force": 1.0, **ALONE}),
    "grease_R50": ("grease-like, 10 Pa s, R = 50 mm", "stop_grease.yaml",
                   {"motion.duration": GREASE, "geometry.radius": 0.05, **ALONE}),
    # at 51 x 51 this one takes minutes (ms steps at ~0.5 s each near contact): a line contact
    "grease_smooth": ("grease-like, 10 Pa s, σ = 0.1 µm (line contact, 51 × 1)", "stop_grease.yaml",
                      {"motion.duration": GREASE, "roughness.sigma": 0.1e-6, "mesh.ny": 1, **ALONE}),
    "grease_100": ("100 Pa s (a grease's apparent viscosity near rest)", "stop_grease.yaml",
                   {"motion.duration": GREASE, "lubricant.viscosity": 100.0, **ALONE}),
}
# the Table 1 oil, the ISO VG 100 oil and the grease again, with the flow below h/sigma = 0.5
# at PERCOLATION_EXPONENT: how much each reconnect time rests on that law
PERCOLATION_ROWS = ("table1", "vg100", "grease")
# Those three rows are default runs, with the mesh error bar the default adds. The same three
# with the time-integration error bar too (motion.error_bar), the reconnect table's last column,
# and alone (without the mesh error bar), what the default's second run costs: each such run is
# the row's run again, with other second runs
RECONNECT |= {f"{name}_bars": (f"{RECONNECT[name][0]}, with its error bars", RECONNECT[name][1],
                               {**RECONNECT[name][2], "motion.error_bar": True, "motion.mesh_error_bar": True})
              for name in PERCOLATION_ROWS}
RECONNECT |= {f"{name}_alone": (f"{RECONNECT[name][0]}, the run alone", RECONNECT[name][1], {**RECONNECT[name][2], **ALONE})
              for name in PERCOLATION_ROWS}
RECONNECT |= {f"{name}_percolation": (f"{RECONNECT[name][0]}, flow below h/σ = 0.5 with exponent {PERCOLATION_EXPONENT:g}",
                                      RECONNECT[name][1],
                                      {**RECONNECT[name][2], "roughness.percolation_exponent": PERCOLATION_EXPONENT,
                                       **ALONE})
              for name in PERCOLATION_ROWS}
# the same three at half the default motion.tolerance (the finest of the accuracy study's
# tolerance ladder; a tenth, motion.error_bar's, costs minutes on 51 x 51): how far the
# default's time-integration error reaches at least, on each
TIGHTER = load_scene(SCENES / "table1.yaml").motion.tolerance / 2.0
RECONNECT |= {f"{name}_tight": (f"{RECONNECT[name][0]}, motion.tolerance {TIGHTER:g}", RECONNECT[name][1],
                                {**RECONNECT[name][2], "motion.tolerance": TIGHTER, **ALONE})
              for name in PERCOLATION_ROWS}
LINE_NODES = (31, 41, 51, 75, 101)  # Table 1 as a line contact (ny = 1): the mesh dependence
# cheap enough for the test (seconds): name -> the run whose reconnect time it is
CHECKED = {"line31": ("table1.yaml", {**TABLE1_STOP, "motion.duration": OIL, "mesh.nx": 31, "mesh.ny": 1, **ALONE})}


def stop(scene_file: str, overrides: dict) -> dict:
    """One transient run: reconnect time (s), film at the initial speed, when the block came
    to rest and at the end (m), the closed-form stop film of a grease where it describes the
    run (m, else None: plotting/transient.closed_form_stop_film), whether the contact stayed
    open (above the open threshold) all the time at rest, steps, rejected steps, coupled
    solves, CPU seconds."""
    scene = load_scene(SCENES / scene_file, overrides)
    cpu = time.process_time()
    ds = transient(scene, progress=False)
    cpu = time.process_time() - cpu
    if int(ds["converged"]) != 1:
        raise RuntimeError(f"{scene_file} {overrides}: the transient did not converge; no number is quoted from it")
    at_rest = ds["time"].values >= scene.motion.stop_time + scene.motion.ramp
    return {"reconnect": float(ds["reconnect_time"]), "film": float(ds["min_film_thickness"].values[0]),
            "film_at_stop": film_at_stop(ds), "final_film": float(ds["min_film_thickness"].values[-1]),
            "stop_film": closed_form_stop_film(scene, film_at_stop(ds)),
            "open": bool((ds["contact_resistance"].values[at_rest] > float(ds["open_resistance"])).all()),
            "mesh_error": float(ds["reconnect_time_mesh_error"]) if "reconnect_time_mesh_error" in ds else None,
            "extrapolated": float(ds["reconnect_time_extrapolated"]) if "reconnect_time_extrapolated" in ds else None,
            "time_error": float(ds["reconnect_time_error"]) if "reconnect_time_error" in ds else None,
            "steps": int(ds["steps"]), "rejected": int(ds["rejected_steps"]),
            "solves": int(ds["coupled_solves"]), "cpu": cpu}


def seconds(t: float) -> str:
    """A time as the docs print it: 3 significant digits, in ms below 1 s."""
    if not math.isfinite(t):
        return "not within the run"
    return f"{t * 1e3:.3g} ms" if t < 1.0 else f"{t:.3g} s"


def num(x: float) -> str:
    """Two significant digits, never in e-notation (142 stays 142)."""
    return f"{x:.{max(0, 1 - math.floor(math.log10(abs(x))))}f}" if x else "0"


def measured_on() -> str:
    """When and where: today's date, the machine and the commit (the times depend on them),
    "modified" where the package's sources differ from it (the run is not that commit's)."""
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    changed = subprocess.run(["git", "status", "--porcelain", "--", "src"], cwd=ROOT, capture_output=True,
                             text=True).stdout.strip()
    return (f"measured {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d} on {os.cpu_count()} "
            f"{platform.machine()} CPUs (load average {os.getloadavg()[0]:.1f} at the start), commit "
            f"{commit or 'unknown'}{' (modified)' if changed else ''}")


def percent(change: float) -> str:
    """A signed relative change in per cent, two significant digits."""
    return f"{'+' if change >= 0 else '−'}{num(abs(change) * 100.0)} %"


def later(a: float, b: float) -> str:
    return "later" if a > b else "sooner"


def transient_runs(record: Path, resume: bool = False, log=print, stops: dict | None = None) -> dict:
    """Every stop of ``stops`` (name -> (scene file in config/scenes, overrides); by default
    those of RECONNECT and LINE_NODES), one after another, by name. Each result
    goes to ``record`` (JSON) as soon as it ends, with when and where the runs began; with
    ``resume`` the stops already in ``record`` with the same scene are not run again (a run
    killed half-way goes on from there)."""
    if stops is None:
        stops = {name: (scene_file, overrides) for name, (_, scene_file, overrides) in RECONNECT.items()}
        stops |= {f"line{n}": ("table1.yaml", {**TABLE1_STOP, "motion.duration": OIL, "mesh.nx": n, "mesh.ny": 1, **ALONE})
                  for n in LINE_NODES}
    done = json.loads(record.read_text()) if resume and record.is_file() else {"when": measured_on(), "runs": {}}
    for name, (scene_file, overrides) in stops.items():
        kept = done["runs"].get(name)
        if kept and kept["scene"] == [scene_file, overrides]:
            continue
        done["runs"][name] = {"scene": [scene_file, overrides], **stop(scene_file, overrides)}
        log(f"{name}: {done['runs'][name]}")
        record.parent.mkdir(parents=True, exist_ok=True)
        record.write_text(json.dumps(done, indent=1) + "\n")
    return done


def transient_blocks(record: Path, resume: bool = False, log=print) -> dict[str, str]:
    """The blocks of README.md's transient section: ``reconnect`` (the table and what it
    says), ``reconnect_mesh`` (line contacts of several meshes), ``transient_speed`` (CPU
    times), from ``transient_runs``."""
    done = transient_runs(record, resume, log)
    when, runs = done["when"], done["runs"]
    lines = {n: runs[f"line{n}"] for n in LINE_NODES}

    def extrapolated(name):
        """The row's reconnect time on a converged mesh (a default run's), '' for a row run alone."""
        value = runs[name]["extrapolated"]
        return "" if value is None else seconds(value)

    def bars(name):
        """The row's error bars (its _bars run), '' for a row without."""
        barred = runs.get(f"{name}_bars")
        if barred is None:
            return ""
        return f"+{seconds(barred['mesh_error'])} (mesh), ±{seconds(barred['time_error'])} (time)"

    # a _bars or _alone run is its row's run again: its bars and its CPU are the row's columns and text
    rows = [f"| {label} | {num(runs[name]['film'] * 1e6)} µm | {seconds(runs[name]['reconnect'])} | "
            f"{extrapolated(name)} | {bars(name)} | {runs[name]['steps']} ({runs[name]['rejected']}) |"
            for name, (label, _, _) in RECONNECT.items() if not name.endswith(("_bars", "_alone"))]
    r = {name: run["reconnect"] for name, run in runs.items()}
    law = {name: r[f"{name}_percolation"] / r[name] - 1.0 for name in PERCOLATION_ROWS}  # relative changes
    tight = {name: r[f"{name}_tight"] / r[name] - 1.0 for name in PERCOLATION_ROWS}  # half the tolerance
    mesh_change = r["table1_101"] / r["table1"] - 1.0
    cost_of_bars = {name: runs[f"{name}_bars"]["cpu"] / runs[f"{name}_alone"]["cpu"] for name in PERCOLATION_ROWS}
    cost_of_default = {name: runs[name]["cpu"] / runs[f"{name}_alone"]["cpu"] for name in PERCOLATION_ROWS}
    more_or_less = "more" if abs(law["table1"]) > abs(mesh_change) else "less"
    reconnect = "\n".join([
        "Measured (`scripts/doc_numbers.py --runs`, 51 × 51 nodes unless noted; stop from 1 m/s over 1 ms, "
        "reconnected at 2 × the resting resistance; steps of the whole run, "
        f"{OIL:g} s after the stop for the oils, {GREASE:g} s for the greases):",
        "",
        "| contact (Table 1 unless noted) | film at 1 m/s | reconnect_time | reconnect_time_extrapolated | error bars "
        "| steps (rejected) |",
        "|---|---|---|---|---|---|",
        *rows,
        "",
        f"Ten times the viscosity waits {num(r['grease_100'] / r['grease'])} times longer (10 → 100 Pa s); "
        f"the lighter 1 N load reconnects {later(r['grease_1N'], r['grease'])} than 5 N, the larger radius "
        f"{later(r['grease_R50'], r['grease'])} than 10 mm, and the 0.1 Pa s oil at 101 × 101 nodes "
        f"{later(r['table1_101'], r['table1'])} than at 51 × 51 ({percent(mesh_change)}), with only its mesh at rest "
        f"refined four times {percent(r['table1_rest4'] / r['table1'] - 1.0)} (`motion.rest_refinement`: the film "
        f"drains at rest, docs/physics.md section 14, \"The mesh at rest\"; "
        f"{num(runs['table1_rest4']['cpu'] / runs['table1_alone']['cpu'])} times the CPU time of the run alone).",
        "",
        "The error bars are the run's own estimates (\"Error bars\" under \"Time\" above): `motion.mesh_error_bar`'s "
        "(on by default), the converged value minus the run's, from a second run with the mesh at rest twice as "
        "fine, and `motion.error_bar`'s time-integration error, from a second run at a tenth of the tolerance. "
        "The rows with a `reconnect_time_extrapolated` are default runs; the others are one run each, with "
        "`motion.mesh_error_bar: false`, compared with their row on the same mesh. "
        f"The Table 1 stop's default run gives {seconds(runs['table1']['extrapolated'])}, against "
        f"{seconds(r['table1_rest4'])} with the mesh at rest four times finer (itself short by its own "
        "mesh error: docs/physics.md section 14, \"Error bar of a reconnect time\", gives where the converged "
        f"value lies). A default run took {num(cost_of_default['table1'])} times the CPU time of the run alone "
        f"for the Table 1 oil, {num(cost_of_default['vg100'])} for the ISO VG 100 oil and "
        f"{num(cost_of_default['grease'])} for the grease; a run with both bars {num(cost_of_bars['table1'])}, "
        f"{num(cost_of_bars['vg100'])} and {num(cost_of_bars['grease'])} times.",
        "",
        f"The pressure flow below h/σ = 0.5 is the model's own interpolation to the percolation threshold "
        f"(docs/physics.md section 15). With 2-D percolation's conductivity exponent {PERCOLATION_EXPONENT:g} "
        f"(`roughness.percolation_exponent`) instead of the effective medium's 1, the Table 1 stop reconnects at "
        f"{seconds(r['table1_percolation'])} instead of {seconds(r['table1'])} "
        f"({percent(law['table1'])}), the ISO VG 100 oil at "
        f"{seconds(r['vg100_percolation'])} ({percent(law['vg100'])}), the 10 Pa s grease "
        f"at {seconds(r['grease_percolation'])} ({percent(law['grease'])}), while the "
        f"101 × 101 mesh moves the Table 1 stop by {percent(mesh_change)}: the squeeze's last "
        f"stage drains through that band, and the law there moves the reconnect time {more_or_less} than the mesh does.",
        "",
        f"At `motion.tolerance` {TIGHTER:g}, half the default, the Table 1 stop reconnects at "
        f"{seconds(r['table1_tight'])} ({percent(tight['table1'])}), the ISO VG 100 oil at "
        f"{seconds(r['vg100_tight'])} ({percent(tight['vg100'])}), the 10 Pa s grease at "
        f"{seconds(r['grease_tight'])} ({percent(tight['grease'])}): the default tolerance's time error is at least "
        f"that on each, {'largest' if abs(tight['grease']) > max(abs(tight['table1']), abs(tight['vg100'])) else 'not largest'} "
        "on the grease. The step's error is a mean over the nodes; at rest the steps leave the long inlet a fast, "
        "viscous motion needs, whose films barely move and would dilute it (docs/physics.md section 14, \"The "
        "mesh at rest\"; \"What accuracy costs\" gives Table 1's by its tolerance ladder).",
    ])
    mesh = ", ".join(seconds(lines[n]["reconnect"]) if n != 31 else
                     f"<!-- measured:line31 -->{lines[n]['reconnect'] * 1e3:.3g}<!-- /measured --> ms" for n in LINE_NODES[:-1])
    reconnect_mesh = (f"The reconnect time depends on the mesh: {mesh} and {seconds(lines[LINE_NODES[-1]]['reconnect'])} "
                      f"for Table 1 as a {', '.join(f'{n}-' for n in LINE_NODES[:-1])} and {LINE_NODES[-1]}-node line contact.")

    def cost(run):
        return (f"{run['steps']} steps, {run['rejected']} rejected, {run['solves']} coupled solves, "
                f"{num(run['cpu'] / run['solves'] * 1e3)} ms each")

    t1, t101, line = runs["table1_alone"], runs["table1_101"], lines[51]
    speed = (f"Speed (CPU time of one process with one BLAS thread, {when}): the Table 1 stop from 1 m/s to "
             f"rest and on for {OIL:g} s, the run alone (`motion.mesh_error_bar: false`), takes **{num(t1['cpu'])} s "
             f"at 51²** ({cost(t1)}), **{num(t101['cpu'])} s at 101²** ({cost(t101)}), {num(line['cpu'])} s as a "
             f"51-node line contact ({cost(line)}); with the mesh error bar of the default, "
             f"{num(runs['table1']['cpu'])} s at 51².")
    return {"reconnect": reconnect, "reconnect_mesh": reconnect_mesh, "transient_speed": speed}


def grease_figure_stops() -> dict[str, tuple[str, dict, str]]:
    """The cases of the transient study's grease figure as the workflow runs them
    (config/transient.yaml alone, as the default run): name -> (scene file in config/scenes,
    overrides, label)."""
    spec = transient_cases.study_spec(ROOT / "config" / "transient.yaml")
    cases = transient_cases.figure_cases(spec)["grease"]
    overrides = transient_cases.case_overrides(spec, {"grease": cases})
    scene_file = os.path.relpath(ROOT / spec["base"], SCENES)
    return {f"grease{i}": (scene_file, overrides[case["id"]], case["label"]) for i, case in enumerate(cases)}


def film_text(h: float) -> str:
    """A film as the docs print it: two significant digits, in nm below 10 nm."""
    return f"{num(h * 1e9)} nm" if h < 1e-8 else f"{num(h * 1e6)} µm"


def grease_block(record: Path, resume: bool = False, log=print) -> str:
    """README.md's ``grease`` block: the grease figure's cases (``grease_figure_stops``), each
    with its films, its closed-form stop film, its reconnect time and its cost, and which of
    them reconnect, stay open or end at their closed-form film."""
    figure = grease_figure_stops()
    done = transient_runs(record, resume, log, {name: (f, o) for name, (f, o, _) in figure.items()})
    runs = done["runs"]
    scenes = {name: load_scene(SCENES / f, o) for name, (f, o, _) in figure.items()}
    first = scenes[next(iter(scenes))]
    rows = []
    for name, (_, _, label) in figure.items():
        run, scene = runs[name], scenes[name]
        closed = "–"
        if scene.lubricant.rheology == "bingham":
            h_stop = bingham_squeeze_stop_film(scene.operating.force, scene.geometry.length, scene.geometry.radius,
                                               scene.mesh.x_max, scene.lubricant.yield_stress)
            closed = film_text(h_stop) + ("" if run["stop_film"] else " (not drawn: the asperities share the load)")
        at_rest = ("reconnected" if math.isfinite(run["reconnect"]) else
                   f"open (above {scene.interface.open_resistance:g} Ω) throughout" if run["open"] else
                   f"closed, above {scene.motion.reconnect_factor:g} × its resistance at rest")
        rows.append(f"| {label} | {film_text(run['film'])} | {film_text(run['film_at_stop'])} | "
                    f"{film_text(run['final_film'])} | {closed} | {seconds(run['reconnect'])} | {at_rest} | "
                    f"{num(run['cpu'])} s | {run['steps']} ({run['rejected']}) |")
    ended = [f"{figure[n][2]}: the film ends at {runs[n]['final_film'] / runs[n]['stop_film']:.4f} of its "
             f"closed-form stop film. " for n in figure if runs[n]["stop_film"]]
    rest = first.motion.duration - first.motion.ramp
    return "\n".join([
        f"Measured (`scripts/doc_numbers.py --runs --only grease`, CPU time of one process, {done['when']}): the cases of "
        f"`transient_grease`, Table 1 at {first.operating.force:g} N as a {first.mesh.nx}-node line contact on "
        f"±{first.mesh.x_max * 1e3:g} mm, stopped from {first.motion.speed or first.operating.speed:g} m/s over "
        f"{first.motion.ramp * 1e3:g} ms and at rest for {rest:.3g} s:",
        "",
        f"| lubricant | film at {first.motion.speed or first.operating.speed:g} m/s | film at the stop | film at the end | "
        "closed-form stop film | reconnect_time | at rest | CPU | steps (rejected) |",
        "|---|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        "".join(ended) + f"The figure's {len(figure)} cases take {num(sum(runs[n]['cpu'] for n in figure))} s of CPU "
        "in all.",
    ])


def checked_number(name: str) -> str:
    """A cheap measured number as README.md prints it (``--check`` compares it within 2 %;
    the transient's progress lines are kept out of its report)."""
    with contextlib.redirect_stderr(io.StringIO()):
        return f"{stop(*CHECKED[name])['reconnect'] * 1e3:.3g}"


TARGETS = (0.1, 0.03, 0.01)  # the README's rows: contact resistance within 10, 3, 1 %


def accuracy_block(study_file: Path | None = None, log=print, keep: Path | None = None) -> str:
    """README.md's accuracy table: the accuracy study of config/accuracy.yaml (deep-merged
    with config/config.yaml's ``accuracy:``, as the workflow runs it), or a study the
    workflow already ran (``study_file``, its results/accuracy/study.nc), through the
    study's own table code (studies/accuracy.py). A study run here is written to ``keep``."""
    if study_file is None:
        config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
        spec = study_spec(ROOT / "config" / "accuracy.yaml", config.get("accuracy"))
        spec["scene"] = str(ROOT / spec["scene"])
        when = measured_on()
        study = run_study(spec, log=log)
        study.attrs["measured"] = when
        if keep is not None:
            keep.parent.mkdir(parents=True, exist_ok=True)
            study.to_netcdf(keep)
    else:
        study = xr.load_dataset(study_file)
        written = datetime.datetime.fromtimestamp(study_file.stat().st_mtime, datetime.timezone.utc)
        when = study.attrs.get("measured") or f"timed by the run that wrote {study_file.name}, {written:%Y-%m-%d}"
    table = accuracy_table(study)
    q = "contact_resistance"
    orders = table[f"{q}_order"].values
    meshes = list(table["mesh"].values)
    speeds = table["speed"].values
    paper = table[f"{q}_error"].values[:, meshes.index(51)] if 51 in meshes else None
    default = float(yaml.safe_load(study.attrs["scene"])["solver"]["tolerance"])
    tolerance = ""
    if "tolerance" in table.dims:
        values = list(table["tolerance"].values)
        if default in values:
            change = np.nanmax(table[f"tolerance_{q}_change"].values[:, values.index(default)])
            tolerance = (f" Tightening the solver tolerance from its default ({default:g}) to {min(values):g} moves "
                         f"the resistance by at most {100 * change:.2g} %.")
    newton = ""
    if "newton" in table.dims and "tolerance" in table.dims and table.attrs["newton_mesh"] == table.attrs["tolerance_mesh"]:
        by_newton, by_nested = list(table["newton"].values), list(table["tolerance"].values)
        if default in by_newton and default in by_nested:
            k, j = by_newton.index(default), by_nested.index(default)
            change = np.nanmax(table[f"newton_{q}_change"].values[:, k])
            ratio = table["newton_solve_time"].values[:, k] / table["tolerance_solve_time"].values[:, j]
            newton = (f" The one Newton (solver.method: newton) at the default tolerance is within {100 * change:.2g} % "
                      f"of the nested solver's tightest, and takes {np.nanmin(ratio):.2g}–{np.nanmax(ratio):.2g} times "
                      "the nested solver's time at the default.")
    domain = ""
    if "domain" in table.dims:
        scales = list(table["domain"].values)
        if 1.0 in scales:
            change = np.nanmax(table[f"domain_{q}_change"].values[:, scales.index(1.0)])
            domain = (f" Lengthening the automatic domain's long inlet (mesh.far_inlet: false) up to "
                      f"{max(scales):g}× moves it by at most {100 * change:.2g} %.")
    rows = cost_table(table, [q], TARGETS)
    text = [f"Read off, for the Table 1 contact ({when}):", "", *rows, "",
            f"The observed order of ln R is {np.nanmin(orders):.2g}–{np.nanmax(orders):.2g}."
            + (" The 51² mesh of the paper's figures is off by "
               + ", ".join(f"{100 * e:.2g} %" for e in paper) + " at "
               + ", ".join(f"{s:g}" for s in speeds) + " m/s." if paper is not None else "")
            + tolerance + newton + domain]
    return "\n".join(text)


def transient_accuracy_block(table_file: Path | None = None, log=print) -> str:
    """README.md's paragraph on what a reconnect time's accuracy costs: the ladders of
    config/transient.yaml's figure ``accuracy`` (studies/transient_accuracy.py), from the
    workflow's table (``table_file``, its results/data/transient_accuracy.nc) or run here,
    case by case (minutes: the finest mesh's run)."""
    spec = transient_spec(ROOT / "config" / "transient.yaml")
    spec["base"] = str(ROOT / spec["base"])
    default = load_scene(spec["base"], spec.get("set", {})).motion.tolerance  # the mesh ladder's
    if table_file is None:
        cases = figure_cases(spec)["accuracy"]
        when = measured_on()
        data = []
        for case in cases:
            data.append(transient(load_scene(spec["base"], {**spec.get("set", {}), **case["overrides"]}), progress=False))
            log(f"transient accuracy, {case['label']}: reconnect {seconds(float(data[-1]['reconnect_time']))}")
        table = ladder_table(cases, data)
    else:
        table = xr.load_dataset(table_file)
        written = datetime.datetime.fromtimestamp(table_file.stat().st_mtime, datetime.timezone.utc)
        when = f"from the workflow's {table_file.name} of {written:%Y-%m-%d}, its runs two at a time on {os.cpu_count()} CPUs"
    if table.attrs.get("notes"):
        raise RuntimeError(f"the transient accuracy ladders are incomplete: {table.attrs['notes']}")
    nodes, across, times = table["mesh"].values, table["mesh_ny"].values, table["mesh_reconnect_time"].values
    errors, runs = table["mesh_error"].values, table["mesh_run_time"].values
    shapes = [f"{n:g} \u00d7 {m:g}" for n, m in zip(nodes, across)]
    members = ", ".join(f"{seconds(t)} on {s} ({num(100 * e)} % low, {num(r)} s)" for s, t, e, r in zip(shapes, times, errors, runs))
    tolerances = table["tolerance"].values
    if default not in tolerances:
        raise RuntimeError(f"the tolerance ladder {list(tolerances)} lacks the default motion.tolerance {default:g}: "
                           "its error is what the block quotes")
    tol_error = float(table["tolerance_error"].values[list(tolerances).index(default)])
    within = least_work_within(table, "mesh", 0.05)
    five = (f"The coarsest mesh within 5 % is {shapes[list(nodes).index(within[0])]} ({num(within[1])} s)." if within
            else f"No mesh of the ladder is within 5 %: the finest, {shapes[-1]}, is {num(100 * errors[-1])} % low.")
    def rough(part):
        """The caveat of a ladder outside the asymptotic range (studies/accuracy.richardson)."""
        return "" if int(table[f"{part}_asymptotic"]) else "; not in the asymptotic range: extrapolation and errors are rough"

    refined = ""
    if "rest_refinement" in table.coords:
        on = f"{table['rest_refinement_nx'].values[0]} × {table['rest_refinement_ny'].values[0]}"
        refined = (f" Refining only the mesh at rest (`motion.rest_refinement`), where the film drains, on {on}: "
                   + ", ".join(f"{int(r)} times finer {seconds(t)} ({num(100 * e)} % low, {num(w)} s)"
                               for r, t, e, w in zip(table["rest_refinement"].values,
                                                     table["rest_refinement_reconnect_time"].values,
                                                     table["rest_refinement_error"].values,
                                                     table["rest_refinement_run_time"].values))
                   + f"; extrapolated {seconds(float(table['rest_refinement_extrapolated']))} (observed order "
                     f"{float(table['rest_refinement_order']):.2g}{rough('rest_refinement')}).")
    return (f"The Table 1 stop's reconnect time (`results/data/transient_accuracy.md`, {when}; wall time of each run): "
            f"{members}; extrapolated {seconds(float(table['mesh_extrapolated']))} (observed order "
            f"{float(table['mesh_order']):.2g}{rough('mesh')}). {five}{refined} On the default 51² mesh, the time-step "
            f"tolerance's own error at its default ({default:g}) is {num(100 * tol_error)} % against its extrapolation "
            f"{seconds(float(table['tolerance_extrapolated']))} (observed order {float(table['tolerance_order']):.2g}, "
            f"over {', '.join(f'{t:g}' for t in sorted(tolerances, reverse=True))}{rough('tolerance')}).")
