"""Benchmark of lubecontact: solve time and work per point, cost growth, start-up, sweeps.

    .venv/bin/python bench/run.py                  # 51^2, 201^2, 401^2 at 4 speeds (several minutes)
    .venv/bin/python bench/run.py --quick          # 51^2 and 201^2, 3 repeats (~1 min)
    .venv/bin/python bench/run.py --meshes 51 101  # chosen meshes (n x n nodes)
    .venv/bin/python bench/run.py --figures paper  # also time regenerating Figs. 3-11 (Snakemake)
    .venv/bin/python bench/run.py --json-only      # print the JSON instead of the markdown
    .venv/bin/python bench/run.py --quick --write bench/CURRENT.md   # the current numbers, kept in git

Writes bench/out/<timestamp>.json and .md (git-ignored) and prints the comparison with the
previous run in bench/out. Progress goes to stderr, the report to stdout. Not a test:
numbers depend on the machine and on what else runs on it (the load average at the start is
recorded; CPU time is reported beside wall time because it is much less sensitive to other
processes). bench/README.md tells what each number means; ``--write bench/CURRENT.md`` keeps
the numbers measured on the project's machine.

Each mesh runs in its own Python process, so its peak resident memory (getrusage) is its
own: a warm-up solve first (imports, FFT plans), then ``repeats`` timed solves
per speed (fewer on meshes of 401^2 and more), each from a cold start as the workflow solves
its cases; the median is reported. In that process the LU factorisations and Reynolds solves
of each point are counted by wrapping ``lubecontact.numerics.linear_algebra.factorize`` and
``lubecontact.numerics.reynolds.solve_reynolds``.
"""

from __future__ import annotations

import argparse
import datetime as dt
import functools
import json
import math
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "bench" / "out"
SCENE = ROOT / "config" / "scenes" / "table1.yaml"
SPEEDS = [1e-3, 0.1, 1.0, 10.0]  # m/s: boundary, mixed, mixed (fluid-dominated), full film
MESHES = [51, 201, 401]  # default run; --quick: 51 and 201
BIG_MESH = 401  # from this n on: max(1, repeats // 3) timed solves per speed, no tracemalloc
SWEEP_POINTS = 26  # log-spaced speeds from 1e-3 to 10 m/s, at 51^2
STARTUP_PROCESSES = 3  # fresh processes for the 51^2 start-up (median)
# The transient cost guard: Table 1 at 51^2 with a 1 Pa s oil, stopped from 1 m/s over 1 ms
# and followed for 30 s (config/transient.yaml's stop curve "mu = 1 Pa s"). No test watches
# the transients' cost: a warm-started CG once passed the suite and the steady figures while
# this scene went from 240 to 5800 factorisations (bench/HISTORY.md, issue 14, fifth session).
TRANSIENT_SET = {"mesh.nx": 51, "mesh.ny": 51, "lubricant.viscosity": 1.0, "operating.speed": 1.0,
                 "motion.kind": "stop", "motion.ramp": 1.0e-3, "motion.duration": 30.0}
PAPER_FIGURES = [f"fig{i:02d}" for i in range(3, 12)]  # the paper's Figs. 3-11

# The performance issue's targets (wall time; "point" = worst of the 4 speeds, after warm-up).
TARGETS = {
    "point": {51: 0.02, 201: 0.25, 401: 1.5},  # s per point
    "growth": 60.0,  # time(401^2) / time(51^2), worst speed
    "startup": 0.5,  # s: fresh process, import lubecontact + 51^2 scene + first solve
    "sweep_ratio": 0.5,  # sweep of 26 speeds / 26 cold solves, 51^2
    "paper": 60.0,  # s: Snakemake regenerating Figs. 3-11 from nothing, all cores
}


def log(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def mesh_repeats(n: int, repeats: int) -> int:
    return repeats if n < BIG_MESH else max(1, repeats // 3)


# --- counting inside a child process ---------------------------------------------------


class Counts:
    """LU factorisations and Reynolds solves, counted by wrapping the module functions
    ``lubecontact.numerics.linear_algebra.factorize`` (one call = one SuperLU factorisation)
    and ``lubecontact.numerics.reynolds.solve_reynolds`` (its mesh tells the level) in every
    module that holds them, so the wrappers reach every call. A function that is not there
    is not counted: its counts are None and ``missing`` says why.

    The factorisations are also timed, and so is every back-substitution with their factors
    (the factors are handed out behind ``_TimedFactors``): where a point's time goes, and
    the floor of a direct solve, one factorisation of the finest mesh's pressurised block.
    """

    WRAPPED = ("factorize", "solve_reynolds")

    def __init__(self):
        self.wrapped = dict.fromkeys(self.WRAPPED, False)
        self.missing: list[str] = []
        self.levels: list[int | None] = []  # nodes of the solve_reynolds calls under way
        self.clear()

    def clear(self) -> None:
        self.factorizations: list[tuple[int | None, int, bool, float]] = []  # (level's nodes, block size, outside, s)
        self.back_substitutions: list[tuple[int | None, int, float]] = []  # (factors' level, columns, s)
        self.solves: list[int | None] = []  # nodes of each solve_reynolds mesh
        self.last_level: int | None = None  # nodes of the last solve_reynolds that returned

    def install(self) -> Counts:
        """Wrap the two functions wherever the package holds them: their own modules and
        every module that imported them by name (the solver's modules import at the top)."""
        try:
            from lubecontact.model import solve  # noqa: F401  (loads every solver module)
            from lubecontact.numerics import linear_algebra, reynolds
        except ImportError as error:
            self.missing.append(f"the solver cannot be imported ({error}): nothing counted")
            return self
        for home, name, wrap in ((linear_algebra, "factorize", self._wrap_factorize),
                                 (reynolds, "solve_reynolds", self._wrap_solve)):
            original = getattr(home, name, None)
            if not callable(original):
                self.missing.append(f"{home.__name__}.{name} does not exist: not counted")
                continue
            wrapped = wrap(original)
            for module in [m for n, m in sys.modules.items() if n.startswith("lubecontact.")]:
                if getattr(module, name, None) is original:
                    setattr(module, name, wrapped)
            self.wrapped[name] = True
        return self

    def _wrap_factorize(self, original):
        @functools.wraps(original)
        def factorize(block, *args, **kwargs):
            # outside a Reynolds solve (a back-substitution with reused factors that fell back
            # to a factorisation, e.g. reynolds.load_sensitivity): the mesh of the last solve
            size = int(getattr(block, "shape", (0,))[0])
            outside = not self.levels
            level = self.last_level if outside else self.levels[-1]
            start = time.perf_counter()
            factors = original(block, *args, **kwargs)
            self.factorizations.append((level, size, outside, time.perf_counter() - start))
            return _TimedFactors(factors, level, self.back_substitutions)

        return factorize

    def _wrap_solve(self, original):
        @functools.wraps(original)
        def solve_reynolds(mesh, *args, **kwargs):
            try:
                nodes = int(mesh.nx) * int(mesh.ny)
            except (AttributeError, TypeError):
                nodes = None
            self.solves.append(nodes)
            self.levels.append(nodes)
            try:
                return original(mesh, *args, **kwargs)
            finally:
                self.levels.pop()
                self.last_level = nodes

        return solve_reynolds

    def summary(self) -> dict:
        lu, rs = self.wrapped["factorize"], self.wrapped["solve_reynolds"]
        finest = max((n for n in self.solves if n is not None), default=None) if rs else None
        timed = {}
        if lu and rs:
            on_finest = [f[3] for f in self.factorizations if f[0] == finest]
            substitutions = [b for b in self.back_substitutions if b[0] == finest]
            timed = {
                "back_substitutions": len(self.back_substitutions),
                "back_substitutions_finest": len(substitutions),
                "back_substitution_columns_finest": sum(b[1] for b in substitutions),
                "seconds": {  # the only entries that differ between repeats of a point
                    "lu": sum(f[3] for f in self.factorizations),
                    "lu_finest": sum(on_finest),
                    "lu_largest_finest": max(on_finest, default=None),  # the floor of a direct solve
                    "back_substitutions": sum(b[2] for b in self.back_substitutions),
                    "back_substitutions_finest": sum(b[2] for b in substitutions),
                },
            }
        return {**timed,
            "lu_factorizations": len(self.factorizations) if lu else None,
            "lu_factorizations_finest": (0 if finest is None else sum(f[0] == finest for f in self.factorizations))
            if lu and rs else None,
            "lu_outside_reynolds": sum(f[2] for f in self.factorizations) if lu and rs else None,
            "lu_largest_size": max((f[1] for f in self.factorizations), default=0) if lu else None,
            "reynolds_solves": len(self.solves) if rs else None,
            "reynolds_solves_finest": (0 if finest is None else self.solves.count(finest)) if rs else None,
            "reynolds_finest_nodes": finest,
        }


class _TimedFactors:
    """LU factors as ``factorize`` returned them, with each ``solve`` (a back-substitution,
    one column or several) timed into ``log`` as (level of the factorisation, columns, s)."""

    def __init__(self, factors, level, log):
        self._factors, self._level, self._log = factors, level, log

    def solve(self, rhs, *args, **kwargs):
        start = time.perf_counter()
        out = self._factors.solve(rhs, *args, **kwargs)
        columns = 1 if getattr(rhs, "ndim", 1) == 1 else int(rhs.shape[1])
        self._log.append((self._level, columns, time.perf_counter() - start))
        return out

    def __getattr__(self, name):
        return getattr(self._factors, name)


# --- child processes -------------------------------------------------------------------


def _untimed(counts: dict) -> dict:
    return {key: value for key, value in counts.items() if key != "seconds"}


def child_mesh(n: int, repeats: int) -> dict:
    """Run in a fresh process: warm-up, then ``repeats`` solves per speed on an n x n mesh."""
    import tracemalloc

    import lubecontact
    from lubecontact.numerics.mesh import build_mesh

    counts = Counts().install()
    scene = lubecontact.load_scene(SCENE, {"mesh.nx": n, "mesh.ny": n})
    lubecontact.solve(scene.replace({"mesh.nx": 15, "mesh.ny": 11}))  # warm-up: imports
    w0 = time.perf_counter()
    lubecontact.solve(scene)  # warm-up on this mesh: FFT plans, first-touch memory
    log(f"  {n}x{n}: warm-up solve {time.perf_counter() - w0:.2f} s; {repeats} timed solve(s) per speed")
    out = {"n": n, "repeats": repeats, "counting": counts.missing, "speeds": {}}
    for speed in SPEEDS:
        point = scene.replace({"operating.speed": speed})
        ny, nx = build_mesh(point).shape
        wall, cpu, work = [], [], []
        for i in range(repeats):
            counts.clear()
            c0, w0 = time.process_time(), time.perf_counter()
            ds = lubecontact.solve(point)
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
            work.append(counts.summary())
            if n >= BIG_MESH:
                log(f"    U = {speed:g} m/s ({ny} x {nx}): solve {i + 1}/{repeats} {wall[-1]:.2f} s (cpu {cpu[-1]:.2f})")
        out["speeds"][f"{speed:g}"] = {
            "shape": [ny, nx],
            "nodes": ny * nx,
            "wall_median_s": statistics.median(wall),
            "wall_min_s": min(wall),
            "cpu_median_s": statistics.median(cpu),
            "wall_s": wall,
            "cpu_s": cpu,
            "iterations": int(ds["iterations"]),
            "converged": int(ds["converged"]),
            "contact_resistance_ohm": float(ds["contact_resistance"]),
            "friction_coefficient": float(ds["friction_coefficient"]),
            "counts": work[0],
            "counts_vary": any(_untimed(w) != _untimed(work[0]) for w in work),  # cold starts: should be False
        }
        log(f"  {n}x{n} U = {speed:g} m/s ({ny} x {nx} nodes): {statistics.median(wall):.3f} s "
            f"(cpu {statistics.median(cpu):.3f}), {int(ds['iterations'])} it, "
            f"{work[0]['lu_factorizations']} LU")
    if n < BIG_MESH:  # tracemalloc slows a solve several-fold: skipped on the big meshes
        tracemalloc.start()
        lubecontact.solve(scene.replace({"operating.speed": 1.0}))
        out["tracemalloc_peak_mb"] = tracemalloc.get_traced_memory()[1] / 2**20
        tracemalloc.stop()
    else:
        out["tracemalloc_peak_mb"] = None
    out["max_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return out


def child_sweep(rounds: int) -> dict:
    """Run in a fresh process: at 51^2, ``sweep`` over SWEEP_POINTS speeds against as many
    cold ``solve`` calls, ``rounds`` times each (after a warm-up); medians and differences."""
    import numpy as np

    import lubecontact

    counts = Counts().install()
    scene = lubecontact.load_scene(SCENE, {"mesh.nx": 51, "mesh.ny": 51})
    lubecontact.solve(scene.replace({"mesh.nx": 15, "mesh.ny": 11}))
    lubecontact.solve(scene)
    speeds = np.logspace(-3, 1, SWEEP_POINTS)
    timing = {"sweep": ([], []), "cold": ([], [])}
    for r in range(rounds):
        counts.clear()
        c0, w0 = time.process_time(), time.perf_counter()
        cold = [lubecontact.solve(scene.replace({"operating.speed": float(s)})) for s in speeds]
        timing["cold"][0].append(time.perf_counter() - w0)
        timing["cold"][1].append(time.process_time() - c0)
        cold_counts = counts.summary()
        counts.clear()
        c0, w0 = time.process_time(), time.perf_counter()
        swept = lubecontact.sweep(scene, speeds, progress=False)
        timing["sweep"][0].append(time.perf_counter() - w0)
        timing["sweep"][1].append(time.process_time() - c0)
        sweep_counts = counts.summary()
        log(f"  sweep round {r + 1}/{rounds}: {SWEEP_POINTS} cold solves {timing['cold'][0][-1]:.2f} s, "
            f"sweep {timing['sweep'][0][-1]:.2f} s")
    out = {"mesh": "51x51", "points": SWEEP_POINTS, "rounds": rounds, "counting": counts.missing,
           "cold_counts": cold_counts, "sweep_counts": sweep_counts}
    for name, (wall, cpu) in timing.items():
        out[f"{name}_wall_s"] = statistics.median(wall)
        out[f"{name}_cpu_s"] = statistics.median(cpu)
    out["ratio_wall"] = out["sweep_wall_s"] / out["cold_wall_s"]
    out["ratio_cpu"] = out["sweep_cpu_s"] / out["cold_cpu_s"]
    out["converged_sweep"] = int(np.sum(swept["converged"].values))
    out["converged_cold"] = int(sum(int(ds["converged"]) for ds in cold))
    out["max_relative_difference"] = {}
    for var in ("contact_resistance", "friction_coefficient"):
        a = np.asarray(swept[var].values, dtype=float)  # sweep sorts ascending, as logspace is
        b = np.array([float(ds[var]) for ds in cold])
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.where(a == b, 0.0, np.abs(a - b) / np.abs(b))
        worst = int(np.nanargmax(rel)) if np.any(np.isfinite(rel)) else 0
        out["max_relative_difference"][var] = {"value": float(rel[worst]), "at_speed": float(speeds[worst])}
    return out


def child_transient() -> dict:
    """Run in a fresh process: the transient of TRANSIENT_SET once (no warm-up: a transient is
    hundreds of solves), with its work: steps, coupled solves, factorisations, Reynolds solves."""
    import lubecontact

    counts = Counts().install()
    scene = lubecontact.load_scene(SCENE, TRANSIENT_SET)
    c0, w0 = time.process_time(), time.perf_counter()
    ds = lubecontact.transient(scene, progress=False)
    out = {"set": TRANSIENT_SET, "wall_s": time.perf_counter() - w0, "cpu_s": time.process_time() - c0,
           "counts": counts.summary(), "counting": counts.missing}
    for name in ("converged", "steps", "rejected_steps", "coupled_solves"):
        out[name] = int(ds[name])
    out["reconnect_time_s"] = float(ds["reconnect_time"])
    return out


def child_startup() -> dict:
    """Run in a fresh process: import time, then the first (cold-process) solve of a tiny
    case, then the same solve again (what is left is the solve itself)."""
    t0 = time.perf_counter()
    import lubecontact

    scene = lubecontact.load_scene(SCENE, {"mesh.nx": 15, "mesh.ny": 11})
    t1 = time.perf_counter()
    lubecontact.solve(scene)
    t2 = time.perf_counter()
    lubecontact.solve(scene)
    t3 = time.perf_counter()
    return {"import_and_scene_s": t1 - t0, "first_solve_s": t2 - t1, "second_solve_s": t3 - t2}


# What a user's first command costs: a bare interpreter (python -c), so nothing of this
# script is loaded before ``import lubecontact``.
STARTUP_51 = """\
import time
c0, t0 = time.process_time(), time.perf_counter()
import lubecontact
t1 = time.perf_counter()
scene = lubecontact.load_scene({scene!r}, {{"mesh.nx": 51, "mesh.ny": 51}})
t2 = time.perf_counter()
lubecontact.solve(scene)
t3, c3 = time.perf_counter(), time.process_time()
lubecontact.solve(scene)
t4 = time.perf_counter()
import json
print(json.dumps({{"import_s": t1 - t0, "scene_s": t2 - t1, "first_solve_s": t3 - t2,
                  "second_solve_s": t4 - t3, "total_s": t3 - t0, "total_cpu_s": c3 - c0}}))
"""


def startup_51() -> dict:
    """STARTUP_PROCESSES fresh processes: import + 51^2 scene + first solve (median), and
    each process's whole life seen from here (interpreter start and exit included)."""
    runs = [_whole_process(["-c", STARTUP_51.format(scene=str(SCENE))]) for _ in range(STARTUP_PROCESSES)]
    out = {key: statistics.median(r[key] for r in runs) for key in runs[0]}
    out["total_min_s"] = min(r["total_s"] for r in runs)
    out["processes"] = len(runs)
    return out


def startup_cli() -> dict:
    """STARTUP_PROCESSES fresh ``lubecontact solve`` processes of the 51^2 scene (what a
    solve job does: import, solve, write the case with netCDF4, no xarray), median of each
    whole process seen from here."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = ["-m", "lubecontact.cli.main", "solve", str(SCENE), "--set", "mesh.nx=51", "--set", "mesh.ny=51",
               "--out", str(Path(tmp) / "case.nc")]
        runs = [_whole_process(cmd, output=False) for _ in range(STARTUP_PROCESSES)]
    out = {key: statistics.median(r[key] for r in runs) for key in runs[0]}
    out["process_wall_min_s"] = min(r["process_wall_s"] for r in runs)
    out["processes"] = len(runs)
    return out


def _whole_process(args: list[str], output: bool = True) -> dict:
    """Run the interpreter with ``args``; wall and CPU time of the whole process, with the
    JSON it prints last (``output``)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    if output:
        run = run_child(args, script=False)
    else:  # the same interpreter, environment and directory as run_child's children
        subprocess.run([sys.executable, *args], stdout=subprocess.DEVNULL, cwd=ROOT, check=True)
        run = {}
    run["process_wall_s"] = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    run["process_cpu_s"] = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return run


def run_child(args: list[str], env: dict | None = None, script: bool = True) -> dict:
    """Run this script (or, ``script=False``, the interpreter) with ``args`` and return the
    JSON it prints last; its stderr (progress, warnings, errors) passes through."""
    cmd = [sys.executable, *([str(Path(__file__).resolve())] if script else []), *args]
    done = subprocess.run(cmd, stdout=subprocess.PIPE, text=True, env=env, cwd=ROOT, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd[:3])} ... failed (exit code {done.returncode}; its error output is above)")
    return json.loads(done.stdout.strip().splitlines()[-1])


# --- whole-figure regeneration -----------------------------------------------------------


def time_figures(which: str) -> dict:
    """Regenerate figures from nothing in a scratch copy of the workflow; wall time.
    ``which``: "full" (every target of config/config.yaml), "test" (config/test.yaml), or
    "paper" (only the paper's Figs. 3-11, PNG and PDF, of config/config.yaml)."""
    import yaml

    snakemake = Path(sys.executable).with_name("snakemake")
    configfile = "config/test.yaml" if which == "test" else None
    results = yaml.safe_load((ROOT / (configfile or "config/config.yaml")).read_text()).get("results", "results")
    targets = [f"{results}/figures/{fig}.{ext}" for fig in PAPER_FIGURES for ext in ("png", "pdf")] if which == "paper" else []
    with tempfile.TemporaryDirectory(prefix="lubecontact-bench-") as tmp:
        for name in ("Snakefile", "config", "workflow", "src"):
            source = ROOT / name
            (shutil.copytree if source.is_dir() else shutil.copy2)(source, Path(tmp) / name)
        cmd = [str(snakemake), "--workflow-profile", "workflow/profiles/default", "--cores", str(os.cpu_count())]
        if configfile:
            cmd += ["--configfile", configfile]
        cmd += targets
        # planning alone (a dry run: the Snakefile expands every figure's grid into scenes),
        # what every Snakemake invocation and every cluster job pays before any work
        t0 = time.perf_counter()
        subprocess.run(cmd + ["--dry-run"], cwd=tmp, capture_output=True, text=True, check=True)
        planning = time.perf_counter() - t0
        log(f"figures ({which}): {' '.join(cmd[1:])}")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        done = subprocess.run(cmd, cwd=tmp, capture_output=True, text=True, check=False)
        seconds = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if done.returncode != 0:
            raise RuntimeError(f"figure regeneration failed:\n{done.stderr[-3000:]}")
        cases = len(list((Path(tmp) / results / "cases").glob("*.nc")))
        figures = len(list((Path(tmp) / results / "figures").glob("*.png")))
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return {"which": which, "config": configfile or "config/config.yaml", "targets": targets, "wall_s": seconds,
            "cpu_s": cpu, "planning_s": planning, "cases": cases, "figures_png": figures, "cores": os.cpu_count()}


# --- analysis ----------------------------------------------------------------------------


def common_exponent(groups: list[list[tuple[float, float]]]) -> float | None:
    """b of time = c_g nodes^b fitted by least squares in log-log, one slope shared by the
    groups (each group its own c_g); None with fewer than two node counts in every group."""
    sxy = sxx = 0.0
    for points in groups:
        logs = [(math.log(n), math.log(t)) for n, t in points if n > 0 and t > 0]
        if len({x for x, _ in logs}) < 2:
            continue
        xm = statistics.fmean(x for x, _ in logs)
        ym = statistics.fmean(y for _, y in logs)
        sxy += sum((x - xm) * (y - ym) for x, y in logs)
        sxx += sum((x - xm) ** 2 for x, _ in logs)
    return sxy / sxx if sxx > 0 else None


def growth(meshes: dict) -> dict:
    """Cost growth with the node count per speed and over all speeds (wall and CPU), and
    time(largest mesh)/time(smallest mesh) per speed."""
    ns = sorted(int(n) for n in meshes)
    out = {"meshes": ns, "speeds": {}}
    if not ns:
        return out
    for key in ("wall", "cpu"):
        groups = []
        for s in (f"{s:g}" for s in SPEEDS):
            points = [(meshes[str(n)]["speeds"][s]["nodes"], meshes[str(n)]["speeds"][s][f"{key}_median_s"]) for n in ns]
            groups.append(points)
            row = out["speeds"].setdefault(s, {})
            row[f"exponent_{key}"] = common_exponent([points])
            row[f"ratio_{key}"] = points[-1][1] / points[0][1] if len(ns) > 1 else None
        out[f"exponent_{key}_all"] = common_exponent(groups)
    out["ratio_meshes"] = [ns[0], ns[-1]]
    return out


def checks(result: dict) -> list[str]:
    """Each target of the performance issue as a line 'ok' / 'MISSED' / 'not measured'."""
    def line(value, target, text, unit=""):
        if value is None:
            return f"not measured: {text} <= {target:g}{unit}"
        return f"{'ok' if value <= target else 'MISSED'}: {text} {value:.3g}{unit} <= {target:g}{unit}"

    meshes = result["meshes"]
    lines = []
    for n, target in TARGETS["point"].items():
        speeds = meshes.get(str(n), {}).get("speeds", {})
        worst = max(speeds.values(), key=lambda v: v["wall_median_s"]) if speeds else None
        floor = (worst or {}).get("counts", {}).get("seconds", {}).get("lu_largest_finest")
        lines.append(line(worst and worst["wall_median_s"], target, f"{n}\u00b2 point, worst speed", " s")
                     + ("" if floor is None else f" (at that speed one factorisation of the finest block alone: {floor:.3g} s)"))
    ratio = None
    if "51" in meshes and "401" in meshes:
        ratio = max(meshes["401"]["speeds"][s]["wall_median_s"] / meshes["51"]["speeds"][s]["wall_median_s"]
                    for s in meshes["51"]["speeds"])
    lines.append(line(ratio, TARGETS["growth"], "growth time(401\u00b2)/time(51\u00b2), worst speed"))
    startup = result.get("startup_51", {}).get("total_s")
    lines.append(line(startup, TARGETS["startup"], "fresh process: import + 51\u00b2 scene + first solve", " s"))
    cli = result.get("startup_cli", {}).get("process_wall_s")
    lines.append(line(cli, TARGETS["startup"], "fresh `lubecontact solve` of the 51\u00b2 scene, whole process", " s"))
    sweep = result.get("sweep", {}).get("ratio_wall")
    lines.append(line(sweep, TARGETS["sweep_ratio"], f"sweep of {SWEEP_POINTS} speeds / {SWEEP_POINTS} cold solves at 51\u00b2"))
    figures = result.get("figures", {})
    paper = figures["wall_s"] if figures.get("which") == "paper" else None
    lines.append(line(paper, TARGETS["paper"], "whole paper (Figs. 3-11, Snakemake, all cores)", " s")
                 + (" (run with --figures paper)" if paper is None else ""))
    return lines


# --- report ------------------------------------------------------------------------------


def machine() -> dict:
    import numpy
    import scipy

    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT, capture_output=True, text=True)
    return {
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "cpus": os.cpu_count(),
        "processor": platform.processor() or platform.machine(),
        "load_average_at_start": os.getloadavg(),
        "commit": (commit.stdout.strip() or "unknown") + (" (modified)" if dirty.stdout.strip() else ""),
    }


def fmt(value, spec=".3g", none="n/a") -> str:
    return none if value is None else format(value, spec)


def _time_split(result: dict) -> list[str]:
    """Markdown lines: where the first timed solve of each point spent its time (SuperLU
    factorisations and back-substitutions, on the finest mesh and on all, and the rest), and
    the floor of a direct solve on that mesh, one factorisation of its pressurised block."""
    lines = ["", "## Where a point's time goes (its first timed solve)", "",
             "SuperLU work on the finest mesh / on all mesh levels; back-substitutions with their "
             "right-hand-side columns; the rest is everything else (assembly, flow factors, FFT "
             "deformation, smoothing, Python). The floor: one factorisation of the finest mesh's "
             "pressurised block, what any point solved by a direct factorisation pays at least.", "",
             "| mesh | U (m/s) | solve (s) | factorisations finest: n, s / all: s | back-substitutions finest: "
             "n (columns), s / all: n, s | rest (s) | floor: one factorisation (s) |",
             "|---|---|---|---|---|---|---|"]
    for n, mesh in result["meshes"].items():
        for s, v in mesh["speeds"].items():
            c = v["counts"]
            if "seconds" not in c:
                return []  # not counted (or a run of an older bench script): nothing to split
            t = c["seconds"]
            rest = v["wall_s"][0] - t["lu"] - t["back_substitutions"]
            lines.append(
                f"| {n}\u00b2 | {s} | {v['wall_s'][0]:.3g} "
                f"| {c['lu_factorizations_finest']}, {t['lu_finest']:.3g} / {t['lu']:.3g} "
                f"| {c['back_substitutions_finest']} ({c['back_substitution_columns_finest']}), "
                f"{t['back_substitutions_finest']:.3g} / {c['back_substitutions']}, "
                f"{t['back_substitutions']:.3g} | {rest:.3g} | {fmt(t['lu_largest_finest'], '.3g')} |")
    return lines


def markdown(result: dict, previous: dict | None) -> str:
    m = result["machine"]
    lines = [f"# lubecontact benchmark {result['timestamp']}", "",
             f"commit {m['commit']}; Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}; "
             f"{m['cpus']} CPUs ({m['processor']}); load average at start {m['load_average_at_start'][0]:.2f}; "
             f"repeats {result['repeats']} (fewer from {BIG_MESH}\u00b2 on: see the table).", ""]

    lines += ["## Solve time and work per point (Table 1 scene, cold start, after warm-up)", "",
              "Median of the timed solves; LU = SuperLU factorisations, Reynolds = Reynolds solves, each "
              "on all mesh levels / on the finest; it = outer iterations.", "",
              "| mesh | U (m/s) | nodes (ny \u00d7 nx) | wall (s) | CPU (s) | repeats | it | LU all / finest "
              "| Reynolds all / finest | converged | previous wall (s) |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    notes = set()
    for n, mesh in result["meshes"].items():
        notes.update(mesh.get("counting", []))
        for s, v in mesh["speeds"].items():
            c = v["counts"]
            old = (previous or {}).get("meshes", {}).get(n, {}).get("speeds", {}).get(s, {}).get("wall_median_s")
            vary = " (varies)" if v.get("counts_vary") else ""
            lines.append(
                f"| {n}\u00b2 | {s} | {v['shape'][0]} \u00d7 {v['shape'][1]} = {v['nodes']} | {v['wall_median_s']:.3g} "
                f"| {v['cpu_median_s']:.3g} | {len(v['wall_s'])} | {v['iterations']} "
                f"| {fmt(c['lu_factorizations'], 'd')} / {fmt(c['lu_factorizations_finest'], 'd')}{vary} "
                f"| {fmt(c['reynolds_solves'], 'd')} / {fmt(c['reynolds_solves_finest'], 'd')} "
                f"| {'yes' if v['converged'] else 'NO'} | {fmt(old, '.3g', '')} |")
    lines += [f"- counting: {note}" for note in sorted(notes)]
    lines += _time_split(result)

    g = result.get("growth", {})
    if len(g.get("meshes", [])) > 1:
        small, large = g["ratio_meshes"]
        names = ", ".join(f"{n}\u00b2" for n in g["meshes"])
        lines += ["", f"## Cost growth: time \u221d nodes^b over meshes {names}", "",
                  f"| U (m/s) | b (wall) | b (CPU) | time({large}\u00b2)/time({small}\u00b2) wall | CPU |",
                  "|---|---|---|---|---|"]
        for s, row in g["speeds"].items():
            lines.append(f"| {s} | {fmt(row['exponent_wall'], '.2f')} | {fmt(row['exponent_cpu'], '.2f')} "
                         f"| {fmt(row['ratio_wall'], '.3g')} | {fmt(row['ratio_cpu'], '.3g')} |")
        lines.append(f"| all (one b, per-speed constants) | {fmt(g['exponent_wall_all'], '.2f')} "
                     f"| {fmt(g['exponent_cpu_all'], '.2f')} | | |")

    lines += ["", "## Memory", "", "| mesh | peak RSS of the process (MB) | tracemalloc peak of one solve (MB) |",
              "|---|---|---|"]
    for n, mesh in result["meshes"].items():
        lines.append(f"| {n}\u00b2 | {mesh['max_rss_mb']:.0f} | {fmt(mesh['tracemalloc_peak_mb'], '.0f', 'not measured')} |")

    s, s51 = result["startup"], result["startup_51"]
    lines += ["", "## Start-up (fresh process)", "",
              f"- import lubecontact + load the 51\u00b2 scene + its first solve: **{s51['total_s']:.2f} s** "
              f"(cpu {s51['total_cpu_s']:.2f}; median of {s51['processes']} processes, fastest {s51['total_min_s']:.2f} s): "
              f"import {s51['import_s']:.3f} s, scene {s51['scene_s']:.3f} s, first solve {s51['first_solve_s']:.2f} s "
              f"(second solve {s51['second_solve_s']:.3f} s)",
              f"- the whole process seen from outside (interpreter start to exit, two solves): "
              f"{s51['process_wall_s']:.2f} s wall, {s51['process_cpu_s']:.2f} s CPU",
              f"- `lubecontact solve` of the 51\u00b2 scene to a case file (what a workflow solve job does per "
              f"process; no xarray), the whole process: **{result['startup_cli']['process_wall_s']:.2f} s** wall "
              f"(fastest {result['startup_cli']['process_wall_min_s']:.2f} s), {result['startup_cli']['process_cpu_s']:.2f} s CPU",
              f"- import lubecontact + load a scene: {s['import_and_scene_s']:.2f} s",
              f"- first solve of a 15 x 11 case: {s['first_solve_s']:.2f} s "
              f"(second: {s['second_solve_s']:.3f} s)"]

    if "sweep" in result:
        w = result["sweep"]
        d = w["max_relative_difference"]
        lines += ["", f"## Speed sweep against cold solves ({w['mesh']}, {w['points']} speeds 1e-3 to 10 m/s)", "",
                  f"- `lubecontact.sweep`: {w['sweep_wall_s']:.2f} s (cpu {w['sweep_cpu_s']:.2f}); "
                  f"{w['points']} cold `solve` calls: {w['cold_wall_s']:.2f} s (cpu {w['cold_cpu_s']:.2f}); "
                  f"median of {w['rounds']} round(s)",
                  f"- ratio sweep / cold: **{w['ratio_wall']:.3g}** (cpu {w['ratio_cpu']:.3g})",
                  f"- LU factorisations: sweep {fmt(w['sweep_counts']['lu_factorizations'], 'd')}, "
                  f"cold {fmt(w['cold_counts']['lu_factorizations'], 'd')}; converged: sweep "
                  f"{w['converged_sweep']}/{w['points']}, cold {w['converged_cold']}/{w['points']}",
                  "- largest relative difference sweep vs cold: " + ", ".join(
                      f"{var} {v['value']:.2g} (at {v['at_speed']:.3g} m/s)" for var, v in d.items())]
        lines += [f"- counting: {note}" for note in w.get("counting", [])]

    if "transient" in result:
        t = result["transient"]
        c = t["counts"]
        old = (previous or {}).get("transient", {})
        was = (f" (previous run: {old['wall_s']:.1f} s, {fmt(old['counts']['lu_factorizations'], 'd')} LU)"
               if old.get("counts") else "")
        lines += ["", "## Transient cost guard (Table 1, 51\u00b2, 1 Pa s, stopped from 1 m/s, 30 s)", "",
                  f"- {t['wall_s']:.1f} s wall (cpu {t['cpu_s']:.1f}){was}; converged: {'yes' if t['converged'] else 'NO'}; "
                  f"reconnect time {t['reconnect_time_s']:.3g} s",
                  f"- {t['steps']} steps ({t['rejected_steps']} rejected), {t['coupled_solves']} coupled solves, "
                  f"{fmt(c['lu_factorizations'], 'd')} LU factorisations, {fmt(c['reynolds_solves'], 'd')} Reynolds solves "
                  f"(a change of these counts is a change of the transient's path; 240 LU and 806 Reynolds solves "
                  f"on the sixth session's code)"]
        lines += [f"- counting: {note}" for note in t.get("counting", [])]

    if "figures" in result:
        f = result["figures"]
        what = {"paper": "the paper's Figs. 3-11", "full": "every target", "test": "every target"}.get(f.get("which"), "")
        lines += ["", f"## Regenerating {what} from scratch ({f['config']}, {f['cores']} cores)", "",
                  f"{f['wall_s']:.1f} s wall for {f['cases']} cases, {f.get('figures_png', '?')} figures "
                  f"(cpu {fmt(f.get('cpu_s'), '.1f')} s, all processes); planning alone (a dry run): "
                  f"{fmt(f.get('planning_s'), '.1f')} s"]
    lines += ["", "## Targets", ""] + [f"- {c}" for c in checks(result)]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="51^2 and 201^2 only, 3 repeats")
    parser.add_argument("--meshes", type=int, nargs="+", metavar="N", help="n of the n x n meshes (default 51 201 401)")
    parser.add_argument("--repeats", type=int, help="timed solves per speed and mesh (default 5; 3 with --quick; "
                        f"max(1, repeats // 3) from {BIG_MESH}^2 on)")
    parser.add_argument("--figures", nargs="?", const="full", choices=["full", "test", "paper"],
                        help="also time regenerating figures in a scratch copy: every target (full), every target of "
                        "config/test.yaml (test), or only the paper's Figs. 3-11 (paper)")
    parser.add_argument("--json-only", action="store_true", help="print the JSON result (not the markdown), write no .md")
    parser.add_argument("--write", metavar="PATH", help="also write the markdown report to PATH "
                        "(bench/CURRENT.md: the current numbers the README's bench section points to)")
    parser.add_argument("--child-mesh", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--child-sweep", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--child-startup", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--child-transient", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    repeats = args.repeats or (3 if args.quick else 5)
    if args.child_mesh:
        print(json.dumps(child_mesh(args.child_mesh, repeats)))
        return 0
    if args.child_sweep:
        print(json.dumps(child_sweep(repeats)))
        return 0
    if args.child_startup:
        print(json.dumps(child_startup()))
        return 0
    if args.child_transient:
        print(json.dumps(child_transient()))
        return 0

    meshes = sorted(set(args.meshes or ([51, 201] if args.quick else MESHES)))
    stamp = dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    result = {"timestamp": stamp, "machine": machine(), "repeats": repeats, "meshes": {}}
    log("start-up ...")
    result["startup"] = run_child(["--child-startup"])
    result["startup_51"] = startup_51()
    result["startup_cli"] = startup_cli()
    log(f"start-up: tiny case {result['startup']}; 51^2: {result['startup_51']['total_s']:.2f} s; "
        f"CLI process {result['startup_cli']['process_wall_s']:.2f} s")
    for n in meshes:
        r = mesh_repeats(n, repeats)
        log(f"{n}x{n} ({r} repeat(s)) ...")
        result["meshes"][str(n)] = run_child(["--child-mesh", str(n), "--repeats", str(r)])
    result["growth"] = growth(result["meshes"])
    rounds = min(repeats, 3)
    log(f"sweep against cold solves at 51x51 ({rounds} round(s)) ...")
    result["sweep"] = run_child(["--child-sweep", "--repeats", str(rounds)])
    log(f"sweep / cold: {result['sweep']['ratio_wall']:.3g}")
    log("transient cost guard (stop, 1 Pa s, 51x51) ...")
    result["transient"] = run_child(["--child-transient"])
    log(f"transient: {result['transient']['wall_s']:.1f} s, {result['transient']['counts']['lu_factorizations']} LU")
    if args.figures:
        result["figures"] = time_figures(args.figures)
        log(f"figures: {result['figures']['wall_s']:.1f} s")
    result["targets"] = checks(result)

    OUT.mkdir(parents=True, exist_ok=True)
    earlier = sorted(OUT.glob("*.json"))
    previous = json.loads(earlier[-1].read_text()) if earlier else None
    (OUT / f"{stamp}.json").write_text(json.dumps(result, indent=2) + "\n")
    if args.json_only:
        print(json.dumps(result, indent=2))
        return 0
    report = markdown(result, previous)
    (OUT / f"{stamp}.md").write_text(report)
    if args.write:
        Path(args.write).write_text(f"<!-- written by: .venv/bin/python bench/run.py {' '.join(argv or sys.argv[1:])} -->\n\n"
                                    + report)
    print(report)
    if previous:
        print(f"(compared with {earlier[-1].name}: 'previous wall' in the table)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
