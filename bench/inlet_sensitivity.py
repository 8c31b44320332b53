"""Inlet-length sensitivity of the contact resistance (docs/physics.md section 17; issue 10).

For Table 1 (F = 5 N, 51 x 51 unless --line) at the given speeds: solve on the automatic
domain, then with the inlet lengthened by --factor at the same node spacing (more nodes),
and print the relative change of the paper's resistance and of the full path's
(macro_constriction + film_conduction). Usage:
    PYTHONPATH=src python bench/inlet_sensitivity.py [--speeds 1 10] [--factor 1.5] [--line]
"""

import argparse

import lubecontact as lc
from lubecontact.numerics.mesh import build_mesh

FULL = {"effects.macro_constriction": True, "effects.film_conduction": True}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--speeds", type=float, nargs="+", default=[1.0, 10.0])
    parser.add_argument("--factor", type=float, default=1.5)
    parser.add_argument("--line", action="store_true")
    parser.add_argument("--scene", default="config/scenes/table1.yaml")
    args = parser.parse_args()
    mesh_keys = {"mesh.ny": 1} if args.line else {}
    print(f"{'U m/s':>6} {'x_min mm':>9} {'nx':>4} {'paper R ohm':>12} {'change':>9} {'full R ohm':>12} {'change':>9}")
    for speed in args.speeds:
        base = lc.load_scene(args.scene, {"operating.speed": speed, **mesh_keys})
        mesh = build_mesh(base)
        x_min = args.factor * mesh.x[0]
        nx = int(round((mesh.x[-1] - x_min) / mesh.dx)) + 1
        longer = {"mesh.x_min": x_min, "mesh.x_max": float(mesh.x[-1]), "mesh.nx": nx}
        rows = []
        for domain in ({}, longer):
            values = []
            for effects in ({}, FULL):
                ds = lc.solve(base.replace({**domain, **effects}))
                values.append(float(ds.contact_resistance))
            rows.append((domain.get("mesh.x_min", mesh.x[0]), domain.get("mesh.nx", mesh.nx), *values))
        for row in rows:
            dp, df = row[2] / rows[0][2] - 1, row[3] / rows[0][3] - 1
            print(f"{speed:6g} {row[0] * 1e3:9.3f} {row[1]:4d} {row[2]:12.4g} {dp:+9.2%} {row[3]:12.4g} {df:+9.2%}")


if __name__ == "__main__":
    main()
