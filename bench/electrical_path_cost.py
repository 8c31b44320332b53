"""What the electrical path and the validity checks cost per solve (issue 10).

Solves Table 1 once per mesh (0.1 m/s), then times, on the solved state, the paper's spot
resistance alone and each new piece: the film conduction, the Greenwood cluster term (its
DC-FFT kernel built per call, as in a solve) and the validity assessment; compared with the
solve itself. Usage: PYTHONPATH=src python bench/electrical_path_cost.py [--meshes 51 101 201]
"""

import argparse
import time

import lubecontact as lc
from lubecontact.model.validity import assess
from lubecontact.numerics.mesh import build_mesh
from lubecontact.physics.electrical import electrical_path
from lubecontact.physics.rough_surface import RoughContact

VARIANTS = {
    "paper (spots + Psi)": {},
    "+ film_conduction": {"effects.film_conduction": True},
    "+ macro_constriction": {"effects.macro_constriction": True},
    "full path": {"effects.film_conduction": True, "effects.macro_constriction": True, "effects.tunnelling": True},
}


def best_of(f, repeats=5):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--meshes", type=int, nargs="+", default=[51, 101, 201])
    args = parser.parse_args()
    print(f"{'mesh':>8} {'solve s':>8} " + " ".join(f"{name:>22}" for name in [*VARIANTS, "validity"]))
    for n in args.meshes:
        scene = lc.load_scene("config/scenes/table1.yaml", {"mesh.nx": n, "mesh.ny": n})
        start = time.perf_counter()
        _, state = lc.solve(scene, return_state=True)
        solve_time = time.perf_counter() - start
        mesh, contact = build_mesh(scene), RoughContact.from_scene(scene)
        cells = []
        for overrides in VARIANTS.values():
            s = scene.replace(overrides)
            cells.append(best_of(lambda: electrical_path(s, mesh, contact, state.film)))
        cells.append(best_of(lambda: assess(scene, mesh, contact, state, True)))
        print(f"{n:>4}x{n:<3} {solve_time:8.3f} " + " ".join(f"{1e3 * c:19.2f} ms" for c in cells))


if __name__ == "__main__":
    main()
