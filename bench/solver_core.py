"""The solver-core issue's speed table: each row measured in one process, as ratios.

    .venv/bin/python bench/solver_core.py                             # ~3 minutes
    .venv/bin/python bench/solver_core.py --figures                   # + the figure build (~10 minutes)
    .venv/bin/python bench/solver_core.py --write bench/SOLVER_CORE.md   # the numbers kept in git

Rows (bench/README.md, "The solver core's targets"):

- the unit: one SuperLU factorisation (scipy's splu, its default ordering) of the five-point
  Laplacian on 201 x 201 nodes, the median of UNIT_REPEATS, timed in this process;
- a steady point: the Table 1 scene cold-started by ``lubecontact.solve`` after a warm-up,
  the median of POINT_REPEATS solves, in units; at 1 m/s and the worst of SPEEDS (the default
  mesh.far_inlet, auto: open to the far inlet where the long inlet adds columns); and each
  point again on the long inlet (mesh.far_inlet: false, the default before the forty-first
  session) and by the one Newton alone (solver.method: newton; VARIANTS);
- the Table 1 stop (bench/transient.py's ``stop_scene``: from 1 m/s over 1 ms, followed for
  0.1 s) at 51², in steady 51² points at 1 m/s, and at 71² against 51²;
- the issue's failing cases (a 20 N line stop, a 10 Pa s oscillation, a 100 Pa s fretting of
  50 um at 100 Hz, each on the default 51-node line at default tolerances): completed or not;
- with ``--figures`` the whole figure build (bench/run.py's ``time_figures``: every target of
  config/config.yaml from nothing in a scratch copy, all cores, the venv warm).

All times are CPU seconds of this process (less sensitive than wall time to what else runs on
the machine); the solver runs with one BLAS thread. Not a test: the numbers depend on the
machine; the ratios much less.
"""

from __future__ import annotations

import argparse
import datetime as dt
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import scipy.sparse as sp
from scipy.sparse.linalg import splu
from threadpoolctl import threadpool_limits

import lubecontact as lc
from run import SCENE, SPEEDS, log, time_figures
from transient import stop_scene

UNIT_NODES = 201  # the unit's Laplacian: UNIT_NODES x UNIT_NODES nodes
UNIT_REPEATS = 7
POINT_REPEATS = 3
LINE = {"mesh.ny": 1, "mesh.nx": 51}  # the default 51-node line of the failing cases
FAILING = {  # the cases that failed when it was filed, at default tolerances
    "20 N line stop from 1 m/s (0.1 Pa s, 10 ms)": {**LINE, "operating.force": 20.0, "operating.speed": 1.0,
                                                   "motion.kind": "stop", "motion.duration": 0.01},
    "10 Pa s oscillation (1 mm, 20 Hz, one cycle)": {**LINE, "lubricant.viscosity": 10.0, "motion.kind": "oscillation",
                                                     "motion.amplitude": 1e-3, "motion.frequency": 20.0,
                                                     "motion.cycles": 1},
    "100 Pa s fretting (50 um, 100 Hz, one cycle)": {**LINE, "lubricant.viscosity": 100.0, "motion.kind": "oscillation",
                                                     "motion.amplitude": 50e-6, "motion.frequency": 100.0,
                                                     "motion.cycles": 1},
}
# The steady points again with other settings: the long inlet (the default until the
# forty-first session) and the one Newton alone (the solver meant to replace the nested one).
VARIANTS = {"long_points": {"mesh.far_inlet": False}, "newton_points": {"solver.method": "newton"}}
TARGETS = {"point_51": 0.2, "point_201": 2.5, "stop_in_points": 30.0, "stop_71_over_51": 3.0, "figures_min": 10.0}


def cpu_seconds(call) -> tuple[float, object]:
    """(CPU seconds of ``call()``, its result)."""
    start = time.process_time()
    result = call()
    return time.process_time() - start, result


def factorisation_unit() -> float:
    """CPU seconds of one SuperLU factorisation of the 5-point Laplacian on UNIT_NODES² nodes."""
    n = UNIT_NODES
    second = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    laplacian = sp.csc_matrix(sp.kronsum(second, second))
    return statistics.median(cpu_seconds(lambda: splu(laplacian))[0] for _ in range(UNIT_REPEATS))


def steady_point(n: int, speed: float, overrides: dict | None = None) -> dict:
    """Median CPU seconds of a cold solve of Table 1 on n x n at ``speed`` (after a warm-up),
    with the scene's ``overrides`` besides (None: the defaults)."""
    scene = lc.load_scene(SCENE, {"mesh.nx": n, "mesh.ny": n, "operating.speed": speed, **(overrides or {})})
    lc.solve(scene)
    times, ds = zip(*(cpu_seconds(lambda: lc.solve(scene)) for _ in range(POINT_REPEATS)))
    return {"cpu_s": statistics.median(times), "converged": bool(int(ds[-1]["converged"]))}


def transient_run(overrides: dict) -> dict:
    """CPU seconds, completion, steps and coupled solves of one transient (no warm-up)."""
    scene = lc.load_scene(SCENE, overrides)
    seconds, ds = cpu_seconds(lambda: lc.transient(scene, progress=False))
    return {"cpu_s": seconds, "converged": bool(int(ds["converged"])), "steps": int(ds["steps"]),
            "coupled_solves": int(ds["coupled_solves"]), "reconnect_time_s": float(ds["reconnect_time"])}


def measure(figures: bool) -> dict:
    out = {"unit_s": factorisation_unit()}
    log(f"unit: {out['unit_s']:.4f} s")
    out["points"] = {}
    for n in (51, 201):
        for speed in SPEEDS:
            out["points"][(n, speed)] = steady_point(n, speed)
            log(f"{n}^2 at {speed:g} m/s: {out['points'][(n, speed)]['cpu_s']:.3f} s")
    for key, overrides in VARIANTS.items():  # the same points on the long inlet, and by the one Newton
        out[key] = {}
        for n in (51, 201):
            for speed in SPEEDS:
                out[key][(n, speed)] = steady_point(n, speed, overrides)
                log(f"{n}^2 at {speed:g} m/s, {key}: {out[key][(n, speed)]['cpu_s']:.3f} s")
    out["stops"] = {}
    for n in (51, 71):
        out["stops"][n] = transient_run(stop_scene(n, n, None))
        log(f"stop at {n}^2: {out['stops'][n]['cpu_s']:.1f} s")
    out["failing"] = {}
    for label, overrides in FAILING.items():
        out["failing"][label] = transient_run(overrides)
        log(f"{label}: {out['failing'][label]['cpu_s']:.1f} s")
    if figures:
        out["figures"] = time_figures("full")
    return out


def verdict(value: float, target: float) -> str:
    return "met" if value <= target else "missed"


def markdown(m: dict) -> str:
    unit = m["unit_s"]
    point = {key: value["cpu_s"] / unit for key, value in m["points"].items()}
    worst = {n: max(SPEEDS, key=lambda s: point[(n, s)]) for n in (51, 201)}
    stop51, stop71 = m["stops"][51], m["stops"][71]
    in_points = stop51["cpu_s"] / m["points"][(51, 1.0)]["cpu_s"]
    growth = stop71["cpu_s"] / stop51["cpu_s"]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                            cwd=Path(__file__).parent).stdout.strip()
    lines = [f"# The solver core's targets, {dt.date.today()}", "",
             f"`bench/solver_core.py` at {commit}, one process, CPU seconds (load average {os.getloadavg()[0]:.2f} at "
             f"the end, {os.cpu_count()} CPUs). Unit: one SuperLU factorisation of the five-point Laplacian on "
             f"{UNIT_NODES}² nodes, {unit * 1e3:.1f} ms here.", "",
             "| row | measured | target | |", "|---|---|---|---|",
             f"| 51² steady point at 1 m/s | {point[(51, 1.0)]:.2f} units ({m['points'][(51, 1.0)]['cpu_s']:.3f} s) "
             f"| ≤ {TARGETS['point_51']:g} | {verdict(point[(51, 1.0)], TARGETS['point_51'])} |",
             f"| 51² steady point, worst speed ({worst[51]:g} m/s) | {point[(51, worst[51])]:.2f} units "
             f"| ≤ {TARGETS['point_51']:g} | {verdict(point[(51, worst[51])], TARGETS['point_51'])} |",
             f"| 201² steady point, worst speed ({worst[201]:g} m/s) | {point[(201, worst[201])]:.2f} units "
             f"({m['points'][(201, worst[201])]['cpu_s']:.2f} s) | ≤ {TARGETS['point_201']:g} "
             f"| {verdict(point[(201, worst[201])], TARGETS['point_201'])} |",
             f"| Table 1 stop at 51², in steady 51² points at 1 m/s | {in_points:.0f} ({stop51['cpu_s']:.1f} s, "
             f"{stop51['steps']} steps, {stop51['coupled_solves']} coupled solves) | ≤ {TARGETS['stop_in_points']:g} "
             f"| {verdict(in_points, TARGETS['stop_in_points'])} |",
             f"| 71² stop / 51² stop | {growth:.2f} ({stop71['cpu_s']:.1f} s, {stop71['steps']} steps) "
             f"| ≤ {TARGETS['stop_71_over_51']:g} | {verdict(growth, TARGETS['stop_71_over_51'])} |"]
    for label, run in m["failing"].items():
        lines.append(f"| {label} | {'completed' if run['converged'] else 'FAILED'} ({run['cpu_s']:.1f} s, "
                     f"{run['steps']} steps) | completes | {'met' if run['converged'] else 'missed'} |")
    if "figures" in m:
        f = m["figures"]
        minutes = f["wall_s"] / 60.0
        lines.append(f"| figure build, every target from nothing (scratch copy, warm venv, {f['cores']} cores) "
                     f"| {minutes:.1f} min wall, {f['cases']} cases, {f['figures_png']} figures | "
                     f"≤ {TARGETS['figures_min']:g} min | {verdict(minutes, TARGETS['figures_min'])} |")
    else:
        lines.append("| figure build | not measured (run with --figures) | ≤ 10 min | |")
    speeds = " / ".join(f"{point[(n, s)]:.2f}" for n in (51, 201) for s in SPEEDS)
    def variant(key: str) -> str:
        """The points of a VARIANTS entry in units, and whether all converged."""
        units = " / ".join(f"{m[key][(n, s)]['cpu_s'] / unit:.2f}" for n in (51, 201) for s in SPEEDS)
        return f"{units}; all converged: {all(p['converged'] for p in m[key].values())}"

    lines += ["", f"Every steady point, in units, 51² then 201² at {', '.join(f'{s:g}' for s in SPEEDS)} m/s: "
              f"{speeds}; all converged: {all(p['converged'] for p in m['points'].values())}.",
              f"The same on the long inlet (mesh.far_inlet: false; the default until the forty-first session): "
              f"{variant('long_points')}.",
              f"The same by the one Newton alone (solver.method: newton; the nested solver is the default): "
              f"{variant('newton_points')}.",
              f"Reconnect time of the stop: {stop51['reconnect_time_s'] * 1e3:.2f} ms at 51², "
              f"{stop71['reconnect_time_s'] * 1e3:.2f} ms at 71²."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--figures", action="store_true", help="also time the whole figure build (~10 minutes)")
    parser.add_argument("--write", metavar="PATH", help="also write the table to PATH (bench/SOLVER_CORE.md)")
    args = parser.parse_args(argv)
    with threadpool_limits(1):
        report = markdown(measure(args.figures))
    if args.write:
        Path(args.write).write_text(f"<!-- written by: .venv/bin/python bench/solver_core.py "
                                    f"{' '.join(argv or sys.argv[1:])} -->\n\n{report}")
    print(report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
