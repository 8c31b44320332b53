"""Where the steady contact has two states (lift-off and touch-down, docs/physics.md section
23): Fig. 8's grid swept up and down in speed, and the 20 N loop on four meshes.

    .venv/bin/python bench/hysteresis.py                            # ~5 minutes, one core
    .venv/bin/python bench/hysteresis.py --write bench/HYSTERESIS.md   # the numbers kept in git

For each force of Fig. 8 (config/figures/fig08.yaml: its speeds, Table 1 otherwise, the default
51 x 51 mesh) ``lubecontact.sweep(direction="both")``; a row for every speed where the two
directions' fluid load fractions differ by more than LISTED (a cut for the table only: every
value is in the sweeps), with the cold start the figure build solves there (its cases are
cold, workflow/scripts/solve_chunk.py). Then Fig. 8's heaviest force on 31, 51, 81 and 101 nodes a
side at 13 speeds around its lift-off: how the loop moves with the mesh.
"""

from __future__ import annotations

import argparse
import datetime as dt
import subprocess
import time
from pathlib import Path

import numpy as np

import lubecontact as lc
from lubecontact.studies import figure_grids

ROOT = Path(__file__).resolve().parents[1]
TABLE1 = ROOT / "config" / "scenes" / "table1.yaml"
FIG08 = ROOT / "config" / "figures" / "fig08.yaml"
LISTED = 0.01  # fluid load fraction: rows of the table where up and down differ by more
MESHES = (31, 51, 81, 101)
LOOP_SPEEDS = np.geomspace(0.0631, 0.251, 13)  # m/s: around the 20 N lift-off of Fig. 8 on each mesh


def figure_rows() -> tuple[list[str], float]:
    spec = figure_grids.read_yaml(FIG08)
    speeds = figure_grids.speeds_of(spec, "fig08")
    rows, start = [], time.process_time()
    for force in spec["sweep"]["operating.force"]:
        scene = lc.load_scene(TABLE1, {"operating.force": force})
        ds = lc.sweep(scene, speeds, direction="both", progress=False)
        up, down = ds.sel(direction="up"), ds.sel(direction="down")
        apart = np.abs(up["fluid_load_fraction"].values - down["fluid_load_fraction"].values) > LISTED
        for i in np.flatnonzero(apart):
            speed = float(ds["speed"][i])
            cold = lc.solve(scene.replace({"operating.speed": speed}))
            rows.append(f"| {force:g} | {speed:.3g} | {float(up['fluid_load_fraction'][i]):.3f} | "
                        f"{float(down['fluid_load_fraction'][i]):.3f} | {float(cold['fluid_load_fraction']):.3f} | "
                        f"{float(up['contact_resistance'][i]):.3g} | {float(down['contact_resistance'][i]):.3g} | "
                        f"{float(cold['contact_resistance']):.3g} | {int(up['converged'][i])}/{int(down['converged'][i])}"
                        f"/{int(cold['converged'])} |")
        print(f"{force:g} N: {int(apart.sum())} speed(s) apart", flush=True)
    return rows, time.process_time() - start


def mesh_rows() -> list[str]:
    """One row per speed of LOOP_SPEEDS: the fluid load fraction up / down on each of MESHES
    (a star: that point did not converge; a dagger: the sweep solved it cold, cold_restart)."""
    columns = []
    for n in MESHES:
        scene = lc.load_scene(TABLE1, {"operating.force": 20.0, "mesh.nx": n, "mesh.ny": n})
        ds = lc.sweep(scene, LOOP_SPEEDS, direction="both", progress=False)

        def cell(way, i):
            point = ds.sel(direction=way).isel(speed=i)
            marks = ("" if int(point["converged"]) == 1 else "*") + ("†" if int(point["cold_restart"]) == 1 else "")
            return f"{float(point['fluid_load_fraction']):.3f}{marks}"

        columns.append([f"{cell('up', i)} / {cell('down', i)}" for i in range(LOOP_SPEEDS.size)])
        print(f"{n}^2 done", flush=True)
    return [f"| {u:.3g} | " + " | ".join(column[i] for column in columns) + " |" for i, u in enumerate(LOOP_SPEEDS)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", type=Path, help="also write the markdown to this file")
    args = parser.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT).stdout.strip()
    rows, seconds = figure_rows()
    loop = mesh_rows()
    text = "\n".join([
        "<!-- written by: .venv/bin/python bench/hysteresis.py --write bench/HYSTERESIS.md -->",
        "",
        f"# Two steady states: Fig. 8 swept up and down, {dt.date.today()}",
        "",
        f"`bench/hysteresis.py` at {commit}. Fig. 8's grid (Table 1, 51 × 51) swept in speed both ways "
        f"({seconds:.0f} CPU s with the cold solves); each speed where the fluid load fractions of the two "
        f"directions differ by more than {LISTED:g}, with the cold start the figure build solves there. "
        "Converged: up / down / cold (1 = yes).",
        "",
        "| force (N) | speed (m/s) | fluid share up | down | cold | resistance up (Ω) | down (Ω) | cold (Ω) | converged |",
        "|---|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        "Fluid load fraction at 20 N around the lift-off, speeding up / slowing down, on each mesh "
        "(a star: that point did not converge; a dagger: the state continued from the previous speed did not "
        "converge and the sweep solved the point cold, cold_restart):",
        "",
        "| speed (m/s) | " + " | ".join(f"{n}²" for n in MESHES) + " |",
        "|---|" + "---|" * len(MESHES),
        *loop,
        "",
    ])
    print(text)
    if args.write:
        args.write.write_text(text)


if __name__ == "__main__":
    main()
