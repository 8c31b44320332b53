"""Would a modal exterior carry a 2-D inlet? A probe for issue 27's "inlet at its own
resolution" on a cylinder of finite length (docs/physics.md section 17, "The far inlet").

On a line contact the far inlet is exact (numerics/far_inlet.py). On a 2-D mesh a per-row
exterior is wrong (the fluid upstream leaks sideways: +4 % in the film, bench/EXPERIMENTS.md,
thirty-second session), so the 201² point at 10 m/s still solves 201 x 853 nodes. The exact
2-D exterior this probe tests before anyone wires it into the solvers:

Upstream of a column x_1 the film is the rigid parabola h = c + x^2/(2R) (one c for every
row: no crown, no deformation there) with flow factors 1, and the semi-discrete Reynolds
equation across the rows (the mesh's own y differences, p = 0 on the cylinder's ends)
separates into discrete sine modes s_k(j) = sin(k pi j / (ny - 1)), eigenvalues
lambda_k^2 = (2/dy)^2 sin^2(k pi / (2 (ny - 1))):

    d/dx(k dP_k/dx) - lambda_k^2 k P_k = (U/2) f_k dh/dx,   k = h^3 / (12 mu),

f_k the modes of a uniform row (the Couette source is the same in every row), P_k = 0 at the
long inlet's end. Each mode is solved on a graded grid in x (tridiagonal, all modes at once),
once with P_k(x_1) = 1 and no source, once with P_k(x_1) = 0 and the source: the flux into the
mesh at x_1 is then linear in the column's pressures (a dense Dirichlet-to-Neumann matrix in
the row index) plus a Couette part, and so is the load upstream.

The test: Table 1 at 10 m/s on the automatic (long) inlet. Its converged pressures at the
column where the short domain would begin (x_1 = -3.5 s + dx) go into the modal exterior;
its flux through that column's upstream face and its load upstream are the truth the
exterior must reproduce (the long inlet has converged: lengthening it to 0.9 R moves the film
by 1e-5). Rows: the row fluxes' largest relative error, the total flux's (and that of each
row's own exterior without the sideways leak, the line's law that failed on 2-D meshes), the
upstream load's, on 51² and 101², and the exterior's CPU per evaluation.

    cd bench && PYTHONPATH=../src ../.venv/bin/python exterior_2d.py     # ~1 minute
"""

from __future__ import annotations

import time

import numpy as np

import lubecontact as lc
from lubecontact.numerics.mesh import auto_length_scale, build_mesh
from run import SCENE

SPEED = 10.0  # m/s: where the automatic inlet is longest
MESHES = (51, 101)
GRADED_NODES = 600  # nodes of the exterior's graded grid in x
FIRST_CELL = 1e-3  # the graded grid's first cell, in mesh spacings


def graded_grid(length: float, first: float, nodes: int) -> np.ndarray:
    """xi_0 = 0 < ... < xi_{nodes-1} = length, cells growing geometrically from ``first``."""
    low, high = 1.0 + 1e-12, 2.0
    for _ in range(200):  # the ratio r with first (r^(n-1) - 1)/(r - 1) = length
        r = 0.5 * (low + high)
        if first * (r ** (nodes - 1) - 1.0) / (r - 1.0) > length:
            high = r
        else:
            low = r
    cells = first * r ** np.arange(nodes - 1)
    return np.concatenate([[0.0], np.cumsum(cells) * length / cells.sum()])


def tridiagonal(lower, diagonal, upper, rhs):
    """Thomas' algorithm along axis -1, every leading index (mode) at once."""
    n = diagonal.shape[-1]
    c, d = np.zeros_like(diagonal), np.zeros_like(rhs)
    c[..., 0], d[..., 0] = upper[..., 0] / diagonal[..., 0], rhs[..., 0] / diagonal[..., 0]
    for i in range(1, n):
        m = diagonal[..., i] - lower[..., i] * c[..., i - 1]
        c[..., i] = upper[..., i] / m if i < n - 1 else 0.0
        d[..., i] = (rhs[..., i] - lower[..., i] * d[..., i - 1]) / m
    x = np.zeros_like(d)
    x[..., -1] = d[..., -1]
    for i in range(n - 2, -1, -1):
        x[..., i] = d[..., i] - c[..., i] * x[..., i + 1]
    return x


def modal_exterior(x1, x_end, c, radius, mu, speed, ny, dy, first, leak=True):
    """(flux matrix G (m^2/(Pa s)), Couette flux b (m^2/s), load weights w (m), load constant
    W0 (N/m)) per unit width of each interior row: q_j = b_j - sum_j' G_jj' p_j' through x_1
    into the mesh, and the load upstream per row spacing, sum_j dy (w . p + W0). Without
    ``leak`` every mode is solved with lambda = 0: each row's own exterior, as a line's."""
    xi = graded_grid(x1 - x_end, first, GRADED_NODES)
    x = x1 - xi
    mid = 0.5 * (x[:-1] + x[1:])

    def h(at):  # the exterior's film
        return c + at * at / (2.0 * radius)

    k_node, k_face = h(x) ** 3 / (12.0 * mu), h(mid) ** 3 / (12.0 * mu)
    conduct = k_face / np.diff(xi)  # per face between nodes i and i+1
    width = np.zeros_like(xi)
    width[1:-1] = 0.5 * (xi[2:] - xi[:-2])
    rows = np.arange(1, ny - 1)
    modes = np.arange(1, ny - 1)
    sine = np.sin(np.pi * np.outer(modes, rows) / (ny - 1))  # (mode, row)
    lam2 = (2.0 / dy) ** 2 * np.sin(0.5 * np.pi * modes / (ny - 1)) ** 2 * leak
    uniform = 2.0 / (ny - 1) * sine.sum(axis=1)  # f_k
    # unknowns: nodes 1 .. N-2 (node 0 given, node N-1 at p = 0)
    inner = slice(1, GRADED_NODES - 1)
    diag = conduct[:-1] + conduct[1:] + lam2[:, None] * k_node[inner] * width[inner]
    lower = np.broadcast_to(-conduct[:-1], diag.shape).copy()
    upper = np.broadcast_to(-conduct[1:], diag.shape).copy()
    source = 0.5 * speed * (h(mid[:-1]) - h(mid[1:]))  # (U/2)[h(x_{i-1/2}) - h(x_{i+1/2})]
    homogeneous = np.zeros(diag.shape)
    homogeneous[:, 0] = conduct[0]  # from a_0 = 1
    u = np.concatenate([np.ones((len(modes), 1)), tridiagonal(lower, diag, upper, homogeneous),
                        np.zeros((len(modes), 1))], axis=1)
    v = np.concatenate([np.zeros((len(modes), 1)), tridiagonal(lower, diag, upper,
                                                                  -np.broadcast_to(source, diag.shape)),
                        np.zeros((len(modes), 1))], axis=1)
    half = 0.5 * xi[1]
    flux_u = -conduct[0] * (u[:, 0] - u[:, 1]) - lam2 * k_node[0] * half * u[:, 0]
    flux_v = 0.5 * speed * h(mid[0]) - conduct[0] * (v[:, 0] - v[:, 1]) - lam2 * k_node[0] * half * v[:, 0]
    load_u, load_v = (np.sum(0.5 * (f[:, :-1] + f[:, 1:]) * np.diff(xi), axis=1) for f in (u, v))
    project = 2.0 / (ny - 1) * sine  # P_k = project @ p
    flux_matrix = -(sine.T * flux_u) @ project  # q = b - G p
    couette = sine.T @ (uniform * flux_v)
    weights = (sine.T * load_u) @ project  # row load: weights @ p + constant
    constant = sine.T @ (uniform * load_v)
    return flux_matrix, couette, weights, constant


def probe(n: int) -> dict:
    scene = lc.load_scene(SCENE, {"mesh.nx": n, "mesh.ny": n, "operating.speed": SPEED})
    ds = lc.solve(scene, fields=True)
    mesh = build_mesh(scene)
    x, dx, dy = np.asarray(mesh.x), mesh.dx, mesh.dy
    x1 = -3.5 * auto_length_scale(scene) + dx  # the short domain's first Reynolds node
    i1 = int(np.argmin(np.abs(x - x1)))
    p = np.asarray(ds["fluid_pressure"].values).reshape(mesh.shape)
    h = np.asarray(ds["film_thickness"].values).reshape(mesh.shape)
    mu, radius = scene.lubricant.viscosity, scene.geometry.radius
    rows = slice(1, n - 1)
    # the long inlet's flux per unit width through the face upstream of column i1, and its load upstream
    face_h = 0.5 * (h[rows, i1 - 1] + h[rows, i1])
    truth_flux = -face_h**3 / (12.0 * mu) * (p[rows, i1] - p[rows, i1 - 1]) / dx + 0.5 * SPEED * face_h
    weights_x = np.full(i1, dx)  # the trapezoid up to column i1 - 1, then the half cell to the face
    weights_x[0] = weights_x[-1] = 0.5 * dx
    p_face = 0.5 * (p[rows, i1 - 1] + p[rows, i1])
    truth_load = float(np.sum(p[rows, :i1] @ weights_x + 0.25 * dx * (p[rows, i1 - 1] + p_face)) * dy)
    c = float(np.mean(face_h - 0.5 * ((x[i1 - 1]) ** 2 + x[i1] ** 2) / (2.0 * radius)))
    start = time.process_time()
    g, b, w, w0 = modal_exterior(x[i1] - 0.5 * dx, x[0], c, radius, mu, SPEED, n, dy, FIRST_CELL * dx)
    cpu = time.process_time() - start
    modal_flux = b - g @ p_face
    modal_load = float(np.sum(w @ p_face + w0) * dy)
    g1, b1, _, _ = modal_exterior(x[i1] - 0.5 * dx, x[0], c, radius, mu, SPEED, n, dy, FIRST_CELL * dx, leak=False)
    row_flux = b1 - g1 @ p_face
    return {"n": n, "columns": mesh.nx, "column": i1, "row_flux": float(np.max(np.abs(modal_flux / truth_flux - 1))),
            "flux": float(modal_flux.sum() / truth_flux.sum() - 1),
            "per_row": float(row_flux.sum() / truth_flux.sum() - 1), "load": modal_load / truth_load - 1,
            "load_share": truth_load / scene.operating.force, "cpu": cpu}


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
