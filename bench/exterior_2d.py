"""Does the modal exterior carry a 2-D inlet? Issue 27's "inlet at its own resolution" on a
cylinder of finite length (docs/physics.md section 17, "The far inlet").

On a line contact the far inlet is Martin's film in closed form (numerics/far_inlet.py). On a
2-D mesh a per-row exterior is wrong (the fluid upstream leaks sideways: +4 % in the film,
bench/EXPERIMENTS.md, thirty-second session); the modal exterior (numerics/
modal_far_inlet.py) solves each discrete sine mode across the rows in x, the leak included.

The test: Table 1 at 10 m/s on the automatic (long) inlet, whose film has converged
(lengthening it to 0.9 R moves it by 8e-6). Its converged film and pressures at the column
where the short domain would begin (x_1 = -3.5 s + dx) go into the modal exterior; its
flux into that column's cells east of x_1 and its load upstream of x_1 are the truth the
exterior must reproduce. Rows: the row fluxes' largest relative error, the total flux's
(and that of each row's own exterior without the sideways leak, the line's law), the
upstream load's, on 51² and 101², and the exterior's CPU for one film.

    cd bench && PYTHONPATH=../src ../.venv/bin/python exterior_2d.py     # ~10 seconds
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

import lubecontact as lc
from lubecontact.numerics.mesh import Mesh, auto_length_scale, build_mesh
from lubecontact.numerics.modal_far_inlet import ModalFarInlet
from run import SCENE

SPEED = 10.0  # m/s: where the automatic inlet is longest
MESHES = (51, 101)


def probe(n: int) -> dict:
    """The modal exterior (numerics/modal_far_inlet.py) at the column where the short domain's
    first Reynolds node lies, against Table 1's long-inlet solution on n x n at SPEED: the
    flux into that node's cell east of x_1 (the face upstream less the west half cell's
    sideways leak) and the load upstream of x_1 (the trapezoid over the columns up to it)."""
    scene = lc.load_scene(SCENE, {"mesh.nx": n, "mesh.ny": n, "operating.speed": SPEED})
    ds = lc.solve(scene, fields=True)
    mesh = build_mesh(scene)
    x, dx, dy = np.asarray(mesh.x), mesh.dx, mesh.dy
    i1 = int(np.argmin(np.abs(x - (-3.5 * auto_length_scale(scene) + dx))))  # the short domain's x_1
    p = np.asarray(ds["fluid_pressure"].values).reshape(mesh.shape)
    h = np.asarray(ds["film_thickness"].values).reshape(mesh.shape)
    mu, rows = scene.lubricant.viscosity, slice(1, n - 1)
    k_x = (0.5 * (h[rows, i1 - 1] + h[rows, i1])) ** 3 / (12.0 * mu)  # flow factors 1 this far upstream
    face_flux = dy * (k_x * (p[rows, i1 - 1] - p[rows, i1]) / dx + 0.25 * SPEED * (h[rows, i1 - 1] + h[rows, i1]))
    k_y = (0.5 * (h[:-1, i1] + h[1:, i1])) ** 3 / (12.0 * mu) * dx / dy * (p[:-1, i1] - p[1:, i1])
    leak = 0.5 * (k_y[1:] - k_y[:-1])  # the west half cell's net outflow across the rows
    truth_flux = face_flux - leak
    trapezoid = np.full(i1 + 1, dx)
    trapezoid[[0, -1]] = 0.5 * dx
    truth_load = float(np.sum(p[rows, : i1 + 1] @ trapezoid) * dy)
    short = Mesh(x=x[i1 - 1:], y=mesh.y, length=mesh.length, far_inlet=True)
    inlet = ModalFarInlet.on(short, scene.geometry.radius, mu, SPEED)
    own_rows = dataclasses.replace(inlet, eigenvalues=np.zeros_like(inlet.eigenvalues), cache={})
    start = time.process_time()
    exterior = inlet.exterior(h[:, i1 - 1:])
    cpu = time.process_time() - start
    row_exterior = own_rows.exterior(h[:, i1 - 1:])
    modal_flux = exterior.inflow - exterior.block @ p[rows, i1]
    row_flux = row_exterior.inflow - row_exterior.block @ p[rows, i1]
    modal_load = inlet.load(p[:, i1 - 1:], h[:, i1 - 1:])[0] + 0.5 * dx * dy * float(p[rows, i1].sum())
    return {"n": n, "columns": mesh.nx, "column": i1, "row_flux": float(np.max(np.abs(modal_flux / truth_flux - 1))),
            "flux": float(modal_flux.sum() / truth_flux.sum() - 1),
            "per_row": float(row_flux.sum() / truth_flux.sum() - 1),
            "load": modal_load / truth_load - 1, "load_share": truth_load / scene.operating.force, "cpu": cpu}


def main() -> int:
    print("| mesh | nodes along x | first column kept | row flux, largest error | total flux | "
          "total flux, rows' own exteriors | upstream load | upstream load / F | exterior CPU (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n in MESHES:
        r = probe(n)
        print(f"| {n}² | {r['columns']} | {r['column']} | {100 * r['row_flux']:.3f} % | {100 * r['flux']:+.3f} % | "
              f"{100 * r['per_row']:+.3f} % | "
              f"{100 * r['load']:+.3f} % | {100 * r['load_share']:.3f} % | {r['cpu']:.3f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
