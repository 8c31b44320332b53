"""Benchmark of lubecontact: solve time per mesh and regime, start-up costs, peak memory.

    .venv/bin/python bench/run.py            # 51^2, 101^2, 201^2 at 4 speeds, 5 repeats (~2 min)
    .venv/bin/python bench/run.py --quick    # 51^2 and 101^2, 3 repeats (~20 s)
    .venv/bin/python bench/run.py --figures  # also time regenerating every figure from scratch

Writes bench/out/<timestamp>.json and .md (git-ignored) and prints the comparison with the
previous run in bench/out. Not a test: numbers depend on the machine and on what else runs
on it (the load average at the start is recorded; CPU time is reported beside wall time
because it is much less sensitive to other processes). bench/README.md tells what each
number means; bench/RESULTS.md keeps the numbers measured on the project's machine.

Each mesh runs in its own Python process, so its peak resident memory (getrusage) is its
own: a warm-up solve first (imports, numba cache, FFT plans), then ``repeats`` timed solves
per speed, each from a cold start as the workflow solves its cases; the median is reported.
"""

from __future__ import annotations

import argparse
import datetime as dt
import json
import os
import platform
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
TARGETS = {51: 0.3, 201: 5.0}  # s per point after warm-up (the performance issue's targets)
RATIO_TARGET = 25.0  # time(201^2) / time(51^2)


# --- child processes -------------------------------------------------------------------


def child_mesh(n: int, repeats: int) -> dict:
    """Run in a fresh process: warm-up, then ``repeats`` solves per speed on an n x n mesh."""
    import resource
    import tracemalloc

    import lubecontact

    scene = lubecontact.load_scene(SCENE, {"mesh.nx": n, "mesh.ny": n})
    lubecontact.solve(scene.replace({"mesh.nx": 15, "mesh.ny": 11}))  # warm-up: JIT cache, imports
    lubecontact.solve(scene)  # warm-up on this mesh: FFT plans, first-touch memory
    out = {"nodes": n * n, "speeds": {}}
    for speed in SPEEDS:
        point = scene.replace({"operating.speed": speed})
        wall, cpu = [], []
        for _ in range(repeats):
            c0, w0 = time.process_time(), time.perf_counter()
            ds = lubecontact.solve(point)
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
        out["speeds"][f"{speed:g}"] = {
            "wall_median_s": statistics.median(wall),
            "wall_min_s": min(wall),
            "cpu_median_s": statistics.median(cpu),
            "iterations": int(ds["iterations"]),
            "converged": int(ds["converged"]),
            "contact_resistance_ohm": float(ds["contact_resistance"]),
        }
    tracemalloc.start()
    lubecontact.solve(scene.replace({"operating.speed": 1.0}))
    out["tracemalloc_peak_mb"] = tracemalloc.get_traced_memory()[1] / 2**20
    tracemalloc.stop()
    out["max_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
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


def run_child(args: list[str], env: dict | None = None) -> dict:
    """Run this script as a child with ``args`` and return the JSON it prints last."""
    cmd = [sys.executable, str(Path(__file__).resolve()), *args]
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])


# --- whole-figure regeneration -----------------------------------------------------------


def time_figures(configfile: str | None) -> dict:
    """Regenerate every figure from nothing in a scratch copy of the workflow; wall time."""
    snakemake = Path(sys.executable).with_name("snakemake")
    with tempfile.TemporaryDirectory(prefix="lubecontact-bench-") as tmp:
        for name in ("Snakefile", "config", "workflow", "src"):
            source = ROOT / name
            (shutil.copytree if source.is_dir() else shutil.copy2)(source, Path(tmp) / name)
        cmd = [str(snakemake), "--workflow-profile", "workflow/profiles/default", "--cores", str(os.cpu_count())]
        if configfile:
            cmd += ["--configfile", configfile]
        t0 = time.perf_counter()
        done = subprocess.run(cmd, cwd=tmp, capture_output=True, text=True, check=False)
        seconds = time.perf_counter() - t0
        if done.returncode != 0:
            raise RuntimeError(f"figure regeneration failed:\n{done.stderr[-3000:]}")
        cases = len(list((Path(tmp) / "results" / "cases").glob("*.nc")))
    return {"config": configfile or "config/config.yaml", "wall_s": seconds, "cases": cases, "cores": os.cpu_count()}


# --- report ------------------------------------------------------------------------------


def machine() -> dict:
    import numpy
    import scipy

    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    return {
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "cpus": os.cpu_count(),
        "processor": platform.processor() or platform.machine(),
        "load_average_at_start": os.getloadavg(),
        "commit": commit.stdout.strip() or "unknown",
    }


def checks(result: dict) -> list[str]:
    """The performance targets, each as a line 'ok' / 'MISSED'."""
    lines = []
    meshes = result["meshes"]
    for n, target in TARGETS.items():
        if str(n) in meshes:
            worst = max(v["wall_median_s"] for v in meshes[str(n)]["speeds"].values())
            lines.append(f"{'ok' if worst <= target else 'MISSED'}: {n}x{n} worst speed {worst:.3g} s <= {target} s")
    if "51" in meshes and "201" in meshes:
        ratio = max(meshes["201"]["speeds"][s]["wall_median_s"] / meshes["51"]["speeds"][s]["wall_median_s"]
                    for s in meshes["51"]["speeds"])
        lines.append(f"{'ok' if ratio <= RATIO_TARGET else 'MISSED'}: time(201^2)/time(51^2) worst speed {ratio:.3g} <= {RATIO_TARGET}")
    return lines


def markdown(result: dict, previous: dict | None) -> str:
    m = result["machine"]
    lines = [f"# lubecontact benchmark {result['timestamp']}", "",
             f"commit {m['commit']}; Python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}; "
             f"{m['cpus']} CPUs ({m['processor']}); load average at start {m['load_average_at_start'][0]:.2f}; "
             f"repeats {result['repeats']}.", "",
             "## Solve time per point (Table 1 scene, cold start, after warm-up)", "",
             "| mesh | " + " | ".join(f"U = {s:g} m/s" for s in SPEEDS) + " | peak RSS (MB) | tracemalloc peak (MB) |",
             "|" + "---|" * (3 + len(SPEEDS))]
    for n, mesh in result["meshes"].items():
        cells = []
        for s in SPEEDS:
            v = mesh["speeds"][f"{s:g}"]
            cell = f"{v['wall_median_s']:.3g} s (cpu {v['cpu_median_s']:.3g}, {v['iterations']} it)"
            if previous and n in previous.get("meshes", {}):
                old = previous["meshes"][n]["speeds"][f"{s:g}"]["wall_median_s"]
                cell += f" [was {old:.3g}]"
            cells.append(cell)
        lines.append(f"| {n}\u00b2 | " + " | ".join(cells) + f" | {mesh['max_rss_mb']:.0f} | {mesh['tracemalloc_peak_mb']:.0f} |")
    s = result["startup"]
    lines += ["", "## Start-up (fresh process)", "",
              f"- import lubecontact + load a scene: {s['import_and_scene_s']:.2f} s",
              f"- first solve of a 15 x 11 case, numba cache on disk: {s['first_solve_s']:.2f} s "
              f"(second: {s['second_solve_s']:.3f} s)",
              f"- first solve with an empty numba cache (JIT compilation): {result['jit']['first_solve_s']:.2f} s"]
    if "figures" in result:
        f = result["figures"]
        lines += ["", f"## Regenerating every figure from scratch ({f['config']}, {f['cores']} cores)", "",
                  f"{f['wall_s']:.1f} s wall for {f['cases']} cases"]
    lines += ["", "## Targets", ""] + [f"- {c}" for c in checks(result)]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="51^2 and 101^2 only, 3 repeats")
    parser.add_argument("--repeats", type=int, help="timed solves per speed and mesh (default 5; 3 with --quick)")
    parser.add_argument("--figures", nargs="?", const="full", choices=["full", "test"],
                        help="also time regenerating every figure in a scratch copy (full grids, or config/test.yaml)")
    parser.add_argument("--child-mesh", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--child-startup", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    repeats = args.repeats or (3 if args.quick else 5)
    if args.child_mesh:
        print(json.dumps(child_mesh(args.child_mesh, repeats)))
        return 0
    if args.child_startup:
        print(json.dumps(child_startup()))
        return 0

    stamp = dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    result = {"timestamp": stamp, "machine": machine(), "repeats": repeats, "meshes": {}}
    result["startup"] = run_child(["--child-startup"])
    with tempfile.TemporaryDirectory(prefix="lubecontact-numba-") as cache:
        result["jit"] = run_child(["--child-startup"], env={**os.environ, "NUMBA_CACHE_DIR": cache})
    print(f"start-up: {result['startup']}; empty numba cache: {result['jit']}", flush=True)
    for n in ([51, 101] if args.quick else [51, 101, 201]):
        result["meshes"][str(n)] = run_child(["--child-mesh", str(n), "--repeats", str(repeats)])
        print(f"{n}x{n}: " + ", ".join(f"{s}: {v['wall_median_s']:.3f} s" for s, v in result["meshes"][str(n)]["speeds"].items()), flush=True)
    if args.figures:
        result["figures"] = time_figures("config/test.yaml" if args.figures == "test" else None)
        print(f"figures: {result['figures']}", flush=True)

    OUT.mkdir(parents=True, exist_ok=True)
    earlier = sorted(OUT.glob("*.json"))
    previous = json.loads(earlier[-1].read_text()) if earlier else None
    (OUT / f"{stamp}.json").write_text(json.dumps(result, indent=2) + "\n")
    report = markdown(result, previous)
    (OUT / f"{stamp}.md").write_text(report)
    print(report)
    if previous:
        print(f"(compared with {earlier[-1].name}: [was ...] in the table)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
