"""Cost of mass-conserving (JFO) against Reynolds (Swift-Stieber) cavitation.

For the Table 1 scene at 1 m/s (mixed lubrication) on n x n meshes: the film of the
converged coupled solve is taken, and on it the fluid problem alone is solved cold (nested
start) and warm (from the converged cavitated set), median of ``--repeats`` runs; then the
whole coupled solve with each condition, cold. Prints a table (s). ~1 min.

    PYTHONPATH=src python bench/cavitation_cost.py [--nodes 51 201] [--repeats 5]
"""

from __future__ import annotations

import argparse
import statistics
import time

import lubecontact as lc
from lubecontact.model.fluid_film import fluid_film
from lubecontact.model.model import Model
from lubecontact.numerics.cavitation_jfo import solve_jfo
from lubecontact.numerics.reynolds import solve_reynolds


def _median_time(run, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--nodes", type=int, nargs="+", default=[51, 201])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--speed", type=float, default=1.0)
    args = parser.parse_args()
    lc.solve(lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": 15, "mesh.ny": 11}))  # warm-up: imports
    print(f"{'mesh':>8} {'fluid cold R':>13} {'fluid cold JFO':>15} {'fluid warm R':>13} {'fluid warm JFO':>15} "
          f"{'coupled R':>10} {'coupled JFO':>12}")
    for n in args.nodes:
        scene = lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": n, "mesh.ny": n, "operating.speed": args.speed})
        jfo_scene = scene.replace({"effects.cavitation": "jfo"})
        start = time.perf_counter()
        ds, state = lc.solve(scene, return_state=True)
        coupled_r = time.perf_counter() - start
        start = time.perf_counter()
        ds_jfo = lc.solve(jfo_scene)
        coupled_j = time.perf_counter() - start
        model = Model.assemble(scene)
        h_t, k = fluid_film(model, state.film)
        mesh, speed, guess = model.mesh, scene.operating.speed, state.reynolds.cavitated
        cold_r = _median_time(lambda: solve_reynolds(mesh, h_t, k, speed), args.repeats)
        cold_j = _median_time(lambda: solve_jfo(mesh, h_t, k, speed), args.repeats)
        warm_r = _median_time(lambda: solve_reynolds(mesh, h_t, k, speed, cavitated_guess=guess), args.repeats)
        warm_j = _median_time(lambda: solve_jfo(mesh, h_t, k, speed, cavitated_guess=guess), args.repeats)
        print(f"{n:>4}x{n:<3} {cold_r:13.4f} {cold_j:15.4f} {warm_r:13.4f} {warm_j:15.4f} {coupled_r:10.3f} {coupled_j:12.3f}"
              f"   (converged {int(ds['converged'])}/{int(ds_jfo['converged'])}, "
              f"R {float(ds['contact_resistance']):.4g}/{float(ds_jfo['contact_resistance']):.4g} ohm)")


if __name__ == "__main__":
    main()
