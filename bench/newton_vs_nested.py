"""The one-Newton solver (solver.method: newton) against the nested one, in one process:
wall time of each solve, their ratio, iterations and whether each converged.

    .venv/bin/python bench/newton_vs_nested.py > bench/newton_vs_nested.md

Points: Table 1 as a 51-node line contact across the paper's speeds, Table 1 on 31 x 31
and on the default 51 x 51 at 0.01 and 1 m/s, and the soft elastic line contact (no asperity contact, 401 nodes) at
0.01, 0.003 and 0.001 m/s (g_E 10, 19, 32), where the nested solver stops; and Table 1 with
mass-conserving cavitation (JFO) as a 51-node line and on 51 x 51. Each solve is
timed once after a warm-up solve of the same scene (tables built, imports done).
"""

import datetime
import os
import subprocess
import time

import lubecontact as lc

TABLE1 = "config/scenes/table1.yaml"
SOFT = {"effects.asperity_contact": False, "mesh.ny": 1, "mesh.nx": 401, "mesh.x_min": -2.5e-4, "mesh.x_max": 1e-4}
POINTS = (
    [(f"Table 1, line 51, {u:g} m/s", {"mesh.nx": 51, "mesh.ny": 1, "operating.speed": u}) for u in (1e-4, 1e-2, 1.0, 10.0)]
    + [(f"Table 1, {n} x {n}, {u:g} m/s", {"mesh.nx": n, "mesh.ny": n, "operating.speed": u})
       for n in (31, 51) for u in (0.01, 1.0)]
    + [(f"soft elastic film, line 401, {u:g} m/s", {**SOFT, "operating.speed": u}) for u in (0.01, 0.003, 0.001)]
    + [(f"Table 1 with JFO, {mesh}, {u:g} m/s", {**sizes, "operating.speed": u, "effects.cavitation": "jfo"})
       for mesh, sizes in (("line 51", {"mesh.nx": 51, "mesh.ny": 1}), ("51 x 51", {"mesh.nx": 51, "mesh.ny": 51}))
       for u in (0.01, 1.0)]
)


def timed(overrides):
    """(seconds, converged, iterations) of one solve, or the error's name."""
    scene = lc.load_scene(TABLE1, overrides)
    try:
        lc.solve(scene)  # warm-up
        start = time.perf_counter()
        ds = lc.solve(scene)
        return time.perf_counter() - start, int(ds.converged), int(ds.iterations)
    except Exception as err:  # the nested solver raises on a film closing at a node
        return float("nan"), type(err).__name__, 0


if __name__ == "__main__":
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    print("# One Newton against the nested solver\n")
    print(f"Written by `bench/newton_vs_nested.py` on {datetime.date.today()} at {commit} (load average "
          f"{os.getloadavg()[0]:.2f} at the start, {os.cpu_count()} CPUs). The nested column is the default (nested, "
          "finished by one Newton where it stops); wall seconds of one solve after a warm-up.\n")
    print("| point | nested (s) | converged | it. | newton (s) | converged | it. | newton / nested |")
    print("|---|---|---|---|---|---|---|---|")
    for label, overrides in POINTS:
        nested = timed(overrides)
        newton = timed({**overrides, "solver.method": "newton"})
        print(f"| {label} | {nested[0]:.3f} | {nested[1]} | {nested[2]} | {newton[0]:.3f} | {newton[1]} | {newton[2]} | "
              f"{newton[0] / nested[0]:.2f} |", flush=True)
