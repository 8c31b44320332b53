"""What a grease's stop spends on failed step solves at rest (the step ceiling's probes,
unsteady/integrator.StepCeiling; docs/DESIGN.md "Time"), one process, one BLAS thread.

Each case is a Bingham grease stopped from 1 m/s on a line contact: the grease figure's three
yield stresses (Table 1 at 0.5 N on +-1 mm, 30 s at rest), the figure build's Bingham stop of
the hard-case suite (100 Pa at 2 N) and the Bingham stop on the automatic domain (300 Pa at
0.5 N, 10 ms; 31 and 21 nodes). Per case: CPU seconds, accepted steps, the solves that failed
and their share of the CPU (every attempted step's solve is timed), and the reconnect time.

    .venv/bin/python bench/grease_at_rest.py
"""

from __future__ import annotations

import math
import sys
import time

from threadpoolctl import threadpool_limits

import lubecontact as lc
from lubecontact.unsteady.integrator import TimeIntegrator

TABLE1 = "config/scenes/table1.yaml"
BINGHAM = {"mesh.ny": 1, "lubricant.rheology": "bingham", "operating.speed": 1.0, "motion.kind": "stop"}
FIGURE = {**BINGHAM, "mesh.nx": 101, "mesh.x_min": -1e-3, "mesh.x_max": 1e-3, "operating.force": 0.5,
          "lubricant.creep_viscosity": 1e8, "motion.duration": 30.0, "motion.mesh_error_bar": False}
AUTOMATIC = {**BINGHAM, "mesh.nx": 31, "lubricant.yield_stress": 300.0, "operating.force": 0.5,
             "motion.duration": 0.01, "motion.mesh_error_bar": False, "solver.max_iterations": 20}
CASES = {
    **{f"grease figure, {stress / 1e3:g} kPa": {**FIGURE, "lubricant.yield_stress": stress}
       for stress in (1e3, 3e3, 5e3)},
    "hard case bingham_stop (100 Pa, 2 N)": {**FIGURE, "lubricant.yield_stress": 100.0, "operating.force": 2.0},
    "hard case bingham_stop_automatic_domain (31 nodes)": AUTOMATIC,
    "the same on 21 nodes": {**AUTOMATIC, "mesh.nx": 21},
}


def measured(overrides: dict) -> dict:
    """One transient of Table 1 with ``overrides``, every step solve timed."""
    solves = {True: [0, 0.0], False: [0, 0.0]}  # converged -> [count, CPU s]
    step = TimeIntegrator.step

    def timed(self, *args, **kwargs):
        start = time.process_time()
        level, outcome = step(self, *args, **kwargs)
        solves[level is not None][0] += 1
        solves[level is not None][1] += time.process_time() - start
        return level, outcome

    TimeIntegrator.step = timed
    try:
        start = time.process_time()
        ds = lc.transient(lc.load_scene(TABLE1, overrides), progress=False)
        cpu = time.process_time() - start
    finally:
        TimeIntegrator.step = step
    return {"cpu": cpu, "steps": int(ds["steps"]), "failed": solves[False][0], "failed_cpu": solves[False][1],
            "converged": bool(int(ds["converged"])), "reconnect": float(ds["reconnect_time"])}


def main() -> int:
    lines = ["| case | CPU (s) | steps | failed solves | their CPU | converged | reconnect_time |",
             "|---|---|---|---|---|---|---|"]
    with threadpool_limits(1):
        for label, overrides in CASES.items():
            m = measured(overrides)
            reconnect = f"{m['reconnect'] * 1e3:.3f} ms" if math.isfinite(m["reconnect"]) else "none"
            lines.append(f"| {label} | {m['cpu']:.1f} | {m['steps']} | {m['failed']} | "
                         f"{m['failed_cpu'] / m['cpu']:.0%} | {m['converged']} | {reconnect} |")
            print(lines[-1], file=sys.stderr, flush=True)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
