"""Cost of a transient: the Table 1 contact stopped from 1 m/s (ramp 1 ms) to rest and on
to reconnection, on one core: wall and CPU time (the CPU time is what counts on a shared machine), accepted and rejected steps, coupled solves.

    PYTHONPATH=src python bench/transient.py [NX ...]   (default 51; NX x NX nodes; NX,1 = line)
"""

import sys
import time

import lubecontact as lc


def run(nx: int, ny: int, duration: float = 0.1) -> None:
    scene = lc.load_scene("config/scenes/table1.yaml", {
        "mesh.nx": nx, "mesh.ny": ny, "operating.speed": 1.0,
        "motion.kind": "stop", "motion.ramp": 1e-3, "motion.duration": duration,
    })
    start, cpu = time.perf_counter(), time.process_time()
    ds = lc.transient(scene, progress=False)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    print(f"{nx}x{ny}: {wall:.1f} s wall, {cpu:.1f} s CPU, {ds['steps'].item()} steps (+{ds['rejected_steps'].item()} rejected), "
          f"{ds['coupled_solves'].item()} coupled solves, {cpu / ds['coupled_solves'].item() * 1e3:.0f} ms CPU/solve, "
          f"reconnect_time {ds['reconnect_time'].item() * 1e3:.3f} ms, converged {ds['converged'].item()}", flush=True)


if __name__ == "__main__":
    from threadpoolctl import threadpool_limits

    with threadpool_limits(1):
        for arg in sys.argv[1:] or ["51"]:
            nx, _, ny = arg.partition(",")
            run(int(nx), int(ny or nx))
