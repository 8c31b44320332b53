"""What the automatic inlet costs, and what an exact far-inlet boundary condition would save
(issue 27, "the inlet at its own resolution"; docs/physics.md section 17).

Two measurements, one process:

1. The truncation error, on Martin's rigid smooth line contact (h = h_c (1 + xi^2),
   xi = x / sqrt(2 R h_c), Reynolds' outlet condition), by quadrature of its closed-form
   pressure gradient dp/dxi ~ (h - h*) / h^3. For an inlet that ends at xi = -X: the load at
   the same central film (a) with p = 0 there, as the automatic inlet does today, and (b)
   with the far inlet's exact flux (the rigid film upstream of -X solved in closed form, so
   the flux and the pressure inside are exact) but without the load the fluid carries
   upstream of -X. An exterior that carries its own load too is exact by construction.
2. The cost of the inlet cells in the model: the Table 1 point at 10 m/s on 51² and 201²,
   on the automatic domain (the inlet of 20 film lengths, physics section 17) against the
   same spacing on the domain before those cells ([-3.5 s, 1.5 s]; p = 0 at its end), and
   as a 51- and a 201-node line open to the far inlet (mesh.far_inlet, numerics/far_inlet.py)
   against the automatic long inlet at the same spacing, in factorisation units
   (bench/solver_core.py) and with the central film of each.

    PYTHONPATH=src .venv/bin/python bench/inlet_exterior.py     # ~1 minute
"""

from __future__ import annotations

import statistics
import time

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from threadpoolctl import threadpool_limits

import lubecontact as lc
from lubecontact.numerics.mesh import auto_length_scale, build_mesh
from run import SCENE
from solver_core import factorisation_unit

ENDS = (2.0, 3.0, 3.5, 5.0, 10.0, 20.0)  # X: the inlet ends at xi = -X
MESHES = (51, 201)
SPEED = 10.0  # m/s: the bench's worst speed, where the inlet is longest
REPEATS = 3


def film_power(n: int, start: float, end: float) -> float:
    """int_start^end (1 + xi^2)^-n dxi."""
    return quad(lambda xi: (1.0 + xi * xi) ** -n, start, end, limit=200)[0]


def load_moment(n: int, start: float, end: float) -> float:
    """int_start^end (end - xi) (1 + xi^2)^-n dxi: the load of a pressure whose gradient is
    (1 + xi^2)^-n, zero at ``start``, integrated up to ``end``."""
    return quad(lambda xi: (end - xi) * (1.0 + xi * xi) ** -n, start, end, limit=200)[0]


def martin(start: float) -> tuple[float, float]:
    """(outlet xi_o, load) of the rigid film with p = 0 at xi = ``start``: p(xi_o) = 0 fixes
    h* = 1 + xi_o^2 (p' = 0 there too), and the load is int p dxi in units of the scale."""

    def pressure_at(outlet):
        return film_power(2, start, outlet) - (1.0 + outlet**2) * film_power(3, start, outlet)

    outlet = brentq(pressure_at, 1e-3, 1.0)
    return outlet, load_moment(2, start, outlet) - (1.0 + outlet**2) * load_moment(3, start, outlet)


def truncation_rows() -> list[str]:
    outlet, full = martin(-np.inf)
    rows = [f"Fully flooded: outlet at xi = {outlet:.4f}. Errors of the load at the same central film:", "",
            "| inlet ends at xi = -X | p = 0 there | exact flux, the exterior's load dropped |", "|---|---|---|"]
    for end in ENDS:
        # the fully flooded film's load upstream of -X, int_{-inf}^{-X} p: all that an exact
        # flux at -X leaves out (inside, the flux and so the pressure are the flooded ones)
        exterior = load_moment(2, -np.inf, -end) - (1.0 + outlet**2) * load_moment(3, -np.inf, -end)
        truncated = martin(-end)[1]
        rows.append(f"| {end:g} | {truncated / full - 1:+.2%} | {-exterior / full:+.2%} |")
    return rows


def cpu_median(scene) -> tuple[float, object]:
    lc.solve(scene)  # warm-up
    runs = []
    for _ in range(REPEATS):
        start = time.process_time()
        ds = lc.solve(scene)
        runs.append((time.process_time() - start, ds))
    return statistics.median(t for t, _ in runs), runs[-1][1]


def compared(n: int, line: bool) -> tuple[tuple[str, object], tuple[str, object]]:
    """((name, scene), (name, scene)) to compare: on 2-D the automatic domain and the same
    without the inlet cells, on a line the far inlet and the automatic long inlet."""
    automatic = lc.load_scene(SCENE, {"mesh.nx": n, "mesh.ny": 1 if line else n, "operating.speed": SPEED})
    if line:
        return (("mesh.far_inlet: true", automatic.replace({"mesh.far_inlet": True})),
                ("automatic: the long inlet, p = 0 at its end", automatic))
    s = auto_length_scale(automatic)
    short = automatic.replace({"mesh.x_min": -3.5 * s, "mesh.x_max": 1.5 * s})
    return ("automatic: the long inlet", automatic), ("without the inlet cells, p = 0 at its end", short)


def cost_rows(unit: float) -> list[str]:
    rows = ["| mesh | domain | nodes solved | CPU | units | central film | film change |", "|---|---|---|---|---|---|---|"]
    for line in (False, True):
        for n in MESHES:
            films = []
            for name, scene in compared(n, line):
                cpu, ds = cpu_median(scene)
                films.append(float(ds.central_film_thickness))
                change = "" if len(films) == 1 else f"{films[1] / films[0] - 1:+.1%}"
                ny, nx = build_mesh(scene).shape
                rows.append(f"| {f'{n}-node line' if line else f'{n}²'} | {name} | {ny} x {nx} | {cpu:.3f} s | "
                            f"{cpu / unit:.2f} | {films[-1] * 1e6:.3f} um | {change} |")
    return rows


def main() -> int:
    with threadpool_limits(1):
        unit = factorisation_unit()
        lines = ["## 1. Truncating the inlet (Martin's rigid smooth line contact)", "", *truncation_rows(), "",
                 f"## 2. The inlet's cost, Table 1 at {SPEED:g} m/s (unit: one 201² Laplacian factorisation, "
                 f"{unit * 1e3:.1f} ms)", "", *cost_rows(unit)]
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
