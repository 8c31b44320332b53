"""Cost of a transient: the Table 1 contact stopped from 1 m/s (ramp 1 ms) to rest and on
to reconnection, on one core: wall and CPU time (the CPU time is what counts on a shared machine), accepted and rejected steps, coupled solves.

    PYTHONPATH=src python bench/transient.py [--tolerance TOL] [NX ...]
    (default 51; NX x NX nodes; NX,1 = line; TOL = motion.tolerance, default the scene's)
"""

import argparse
import time

import lubecontact as lc


def stop_scene(nx: int, ny: int, tolerance: float | None, duration: float = 0.1) -> dict:
    """The overrides of Table 1 for its stop on nx x ny nodes (bench/solver_core.py uses it too),
    one run: the integrator's cost, without the second run of the mesh error bar that a run
    makes by default (README.md's reconnect table gives what that costs)."""
    overrides = {"mesh.nx": nx, "mesh.ny": ny, "operating.speed": 1.0, "motion.kind": "stop", "motion.ramp": 1e-3,
                 "motion.duration": duration, "motion.mesh_error_bar": False}
    if tolerance is not None:
        overrides["motion.tolerance"] = tolerance
    return overrides


def run(nx: int, ny: int, tolerance: float | None, duration: float = 0.1) -> None:
    scene = lc.load_scene("config/scenes/table1.yaml", stop_scene(nx, ny, tolerance, duration))
    start, cpu = time.perf_counter(), time.process_time()
    ds = lc.transient(scene, progress=False)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    print(f"{nx}x{ny} (tolerance {scene.motion.tolerance:g}): {wall:.1f} s wall, {cpu:.1f} s CPU, {ds['steps'].item()} steps (+{ds['rejected_steps'].item()} rejected), "
          f"{ds['coupled_solves'].item()} coupled solves, {cpu / ds['coupled_solves'].item() * 1e3:.0f} ms CPU/solve, "
          f"reconnect_time {ds['reconnect_time'].item() * 1e3:.3f} ms, converged {ds['converged'].item()}", flush=True)


if __name__ == "__main__":
    from threadpoolctl import threadpool_limits

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("meshes", nargs="*", default=["51"], help="NX (square) or NX,NY")
    parser.add_argument("--tolerance", type=float, help="motion.tolerance (default: the scene's)")
    args = parser.parse_args()
    with threadpool_limits(1):
        for arg in args.meshes:
            nx, _, ny = arg.partition(",")
            run(int(nx), int(ny or nx), args.tolerance)
