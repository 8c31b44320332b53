"""The far inlet of a cylinder of finite length (a 2-D mesh) as an exact boundary condition
(docs/physics.md section 17, "The far inlet").

Upstream of the first Reynolds column x_1 the film is the rigid cylinder's,
h = c + R - sqrt(R^2 - x^2) (Eq. 4, the mesh's own gap; the parabola of numerics/far_inlet.py
is 39 % narrower at 0.9 R, and with it Fig. 4's resistances moved by up to 0.078 in ln R
against the long inlet, with the circle 0.004), one offset c for every row (no crown; the
mean over the interior rows of the offsets through the first x faces' films), with flow
factors 1 and no deformation. There the fluid also leaks sideways towards the cylinder's
ends, so each row's own exterior (the line's law) is wrong: it let 95 % more fluid in at
the same pressures (bench/exterior_2d.py). Across the rows, with the mesh's own y differences and
p = 0 on the ends (rows 0 and ny - 1), the steady Reynolds equation separates into the
discrete sine modes s_k(j) = sin(k pi j / (ny - 1)), k = 1 .. ny - 2, whose y operator has
the eigenvalues -lambda_k^2, lambda_k^2 = (2/dy)^2 sin^2(k pi / (2 (ny - 1))):

    d/dx(k_P dP_k/dx) - lambda_k^2 k_P P_k = (U/2) f_k dh/dx,    k_P = h^3 / (12 mu),

with f_k the modes of a row of ones (the Couette source is the same in every row), P_k = 0
at x = -0.9 R (where the automatic long inlet ends at the latest, numerics/mesh.py) and
P_k(x_1) the mode of the first column's pressures. Each mode is solved by finite volumes on
a grid in xi = x_1 - x graded from a thousandth of the mesh spacing (one tridiagonal solve
for all modes), twice: with P_k(x_1) = 1 and no source (u_k), and with P_k(x_1) = 0 and the
source (v_k). By linearity the flux into the mesh through x_1,

    q_j = sum_k s_k(j) [P_k F_k(u) + f_k F_k(v)],   F = (U/2) h - k_P dP/dx at x_1,

is a dense symmetric block on the first column's pressures plus a Couette inflow: the
exterior's part of those cells' outflow w = A p - b (reynolds.reynolds_system, argument
``exterior``). The first x face carries nothing then (its flux is the exterior's), and the
first column's cells keep the half of their width downstream of x_1: their y faces carry
half (``faces``), and half their nodal area is the exterior's load. The load upstream of x_1
and the pressure and the shear upstream of the mesh's first node x_0 come from the same
modes (``load``, ``upstream``). The offset c enters every one of them; its slopes are a
forward difference in c, and pass to the films of the first x faces (dc/dh = 1/(2 m) at each
of their nodes, m = ny - 2 rows): a rank-one term in the Reynolds residual's film Jacobian.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import lapack

from lubecontact.numerics.mesh import MAX_DOMAIN_RADII
from lubecontact.physics.percolation import FaceFilm

GRADED_NODES = 200  # nodes of the exterior's grid in xi; 400 moves the resistance of Table 1 on 201² at 10 m/s by 1e-4
FIRST_CELL = 1.0e-3  # the grid's first cell, in mesh spacings
OFFSET_STEP = 1.0e-6  # the forward difference in c, relative to the cylinder's gap at x_1
CACHED_OFFSETS = 16  # mode responses and exteriors kept (an evaluation asks for the same c several times)


def cylinder_gap(x, radius: float):
    """R - sqrt(R^2 - x^2), m: the rigid cylinder's gap above the flat (Eq. 4), in a form
    without the cancellation of the difference (x^2 / (R + sqrt(R^2 - x^2)))."""
    return x * x / (radius + np.sqrt(radius * radius - x * x))


def graded_grid(length: float, first: float, nodes: int, inserted: float) -> np.ndarray:
    """xi from 0 to ``length`` in ``nodes`` cells growing geometrically from ``first``, with
    the node ``inserted`` added (the mesh's first node x_0, where upstream is evaluated)."""
    low, high = 1.0, min(2.0, float(np.exp(600.0 / (nodes - 1))))  # r^(n-1) stays finite
    for _ in range(200):  # the ratio r with first (r^(n-1) - 1)/(r - 1) = length
        ratio = 0.5 * (low + high)
        if first * (ratio ** (nodes - 1) - 1.0) / (ratio - 1.0) > length:
            high = ratio
        else:
            low = ratio
    cells = first * ratio ** np.arange(nodes - 1)
    xi = np.concatenate([[0.0], np.cumsum(cells) * length / cells.sum()])
    return np.unique(np.append(xi, inserted))


def symmetric_tridiagonal(off_diagonal: np.ndarray, diagonal: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """The symmetric positive definite tridiagonal systems along the last axis of ``diagonal``
    (modes, n), coupled to the next node by ``off_diagonal`` (modes, n; its last column
    unused), every mode at once and the right-hand sides of ``rhs`` (r, modes, n): one LAPACK
    ptsv (L D L^T without pivoting) on the modes laid end to end, uncoupled. Each mode's
    matrix is a conductance matrix plus lambda_k^2 times a positive diagonal, so positive
    definite; ptsv took 0.19 ms where the general gtsv took 0.28 ms on 49 modes of 199 nodes,
    the same solution to 1e-15 (forty-second session); gtsv was 2-6x faster than Thomas'
    algorithm in numpy (session 56)."""
    coupling = off_diagonal.copy()
    coupling[:, -1] = 0.0  # no coupling between one mode's last node and the next's first
    columns = np.ascontiguousarray(rhs.reshape(rhs.shape[0], -1).T)
    *_, solution, info = lapack.dptsv(diagonal.ravel(), coupling.ravel()[:-1], columns)
    if info != 0:
        raise np.linalg.LinAlgError(f"the far inlet's mode equations are not positive definite (LAPACK ptsv info {info})")
    return solution.T.reshape(rhs.shape)


@dataclass(frozen=True)
class ModeResponses:
    """Per mode, for P(x_1) = 1 without source (``u``) and P(x_1) = 0 with the source f_k = 1
    (``v``): the flux into the mesh per unit width (m^2/s per Pa, m^2/s), the load upstream of
    x_1 (m per unit width per Pa, N/m), the pressure at x_0 (1, Pa) and the pressure's shear
    (h/2) dp/dx integrated upstream of x_0 (m per Pa, N/m); and the Couette shear mu U / h
    integrated upstream of x_0 (N/m, the same for every row)."""

    flux: tuple[np.ndarray, np.ndarray]
    load: tuple[np.ndarray, np.ndarray]
    at_start: tuple[np.ndarray, np.ndarray]
    shear: tuple[np.ndarray, np.ndarray]
    couette_shear: float


def mode_responses(offset: float, eigenvalues: np.ndarray, xi: np.ndarray, start: int, end: float, radius: float,
                   viscosity: float, speed: float) -> ModeResponses:
    """The modes' responses (ModeResponses) for the cylinder's offset c = ``offset`` on the grid
    ``xi`` (x = ``end`` - xi, its node ``start`` at x_0), eigenvalues lambda_k^2 (1/m^2)."""
    x = end - xi
    mid = 0.5 * (x[:-1] + x[1:])
    film, film_mid = offset + cylinder_gap(x, radius), offset + cylinder_gap(mid, radius)
    poiseuille = film**3 / (12.0 * viscosity)
    conduct = film_mid**3 / (12.0 * viscosity) / np.diff(xi)  # per face
    width = 0.5 * (xi[2:] - xi[:-2])  # the inner nodes' cells
    diagonal = conduct[:-1] + conduct[1:] + eigenvalues[:, None] * (poiseuille[1:-1] * width)
    upper = np.broadcast_to(-conduct[1:], diagonal.shape)  # node j to j + 1 (and back: symmetric)
    rhs = np.zeros((2, *diagonal.shape))
    rhs[0, :, 0] = conduct[0]  # u: P = 1 at x_1
    rhs[1] = -0.5 * speed * (film_mid[:-1] - film_mid[1:])  # v: the Couette source
    inner = symmetric_tridiagonal(upper, diagonal, rhs)
    edge = np.zeros((2, eigenvalues.size, 1))
    u, v = np.concatenate([edge, inner, edge], axis=2)
    u[:, 0] = 1.0
    half = 0.5 * xi[1]  # x_1's own half cell, where the fluid leaks sideways too
    flux_u = -conduct[0] * (1.0 - u[:, 1]) - eigenvalues * poiseuille[0] * half
    flux_v = 0.5 * speed * film_mid[0] + conduct[0] * v[:, 1]
    steps = np.diff(xi)
    upstream = slice(start, None)
    loads, shears = [], []
    for p in (u, v):
        loads.append(np.sum(0.5 * (p[:, :-1] + p[:, 1:]) * steps, axis=1))
        # (h/2) dp/dx dx with dx = -dxi: the faces upstream of x_0
        shears.append(-np.sum((0.5 * film_mid * np.diff(p, axis=1))[:, upstream], axis=1))
    couette_shear = float(np.sum((viscosity * speed / film_mid * steps)[upstream]))
    return ModeResponses((flux_u, flux_v), tuple(loads), (u[:, start], v[:, start]), tuple(shears), couette_shear)


@dataclass(frozen=True)
class Exterior:
    """The modal exterior at one film, for the Reynolds system (reynolds.reynolds_system) and
    its film slopes: the first column's interior cells (rows 1 .. ny-2 of column 1) get
    ``block`` @ p - ``inflow`` in their outflow, and the outflow's slope in c is
    ``block_slope`` @ p - ``inflow_slope``, c's in the film ``offset_slope`` (ny, nx)."""

    block: np.ndarray  # (m, m) m^3/(Pa s)
    inflow: np.ndarray  # (m,) m^3/s
    block_slope: np.ndarray  # (m, m) m^2/(Pa s)
    inflow_slope: np.ndarray  # (m,) m^2/s
    offset_slope: np.ndarray  # (ny, nx) dc/dh, 1

    def outflow_slope(self, pressure: np.ndarray) -> np.ndarray:
        """d(outflow)/dc (m,) m^2/s of the first column's cells at ``pressure`` (ny, nx) Pa."""
        return self.block_slope @ pressure[1:-1, 1] - self.inflow_slope


@dataclass(frozen=True)
class ModalFarInlet:
    """The exact far inlet of a 2-D mesh (module docstring), for a Newtonian lubricant of
    ``viscosity`` sliding at ``speed``."""

    start: float  # x_0, m: the mesh's first node
    end: float  # x_1, m: the first Reynolds column, where the exterior meets the mesh
    spacing: float  # dx, m
    row_spacing: float  # dy, m
    radius: float  # R, m
    viscosity: float  # mu, Pa s
    speed: float  # U, m/s (> 0: the inlet at x_min)
    sine: np.ndarray  # (m, m) s_k(j), mode by row
    eigenvalues: np.ndarray  # (m,) lambda_k^2, 1/m^2
    ones: np.ndarray  # (m,) f_k, the modes of a row of ones
    xi: np.ndarray  # the exterior's grid, m
    start_node: int  # x_0's node in xi
    cache: dict = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def on(cls, mesh, radius: float, viscosity: float, speed: float) -> "ModalFarInlet":
        ny = mesh.ny
        modes = np.arange(1, ny - 1)
        sine = np.sin(np.pi * np.outer(modes, modes) / (ny - 1))
        eigenvalues = (2.0 / mesh.dy) ** 2 * np.sin(0.5 * np.pi * modes / (ny - 1)) ** 2
        ones = 2.0 / (ny - 1) * sine.sum(axis=1)
        start, end = float(mesh.x[0]), float(mesh.x[1])
        xi = graded_grid(end + MAX_DOMAIN_RADII * radius, FIRST_CELL * mesh.dx, GRADED_NODES, end - start)
        return cls(start, end, mesh.dx, mesh.dy, radius, viscosity, speed, sine, eigenvalues, ones, xi,
                   int(np.searchsorted(xi, end - start)))

    @property
    def rows(self) -> int:
        return self.ones.size

    @property
    def projection(self) -> np.ndarray:
        """(m, m): the modes of the first column's pressures, P_k = projection @ p."""
        return 2.0 / (self.rows + 1) * self.sine

    @property
    def mode_width(self) -> float:
        """dy sum_j s_k(j) / f_k = dy (ny - 1)/2, m: a mode's width over the rows."""
        return self.row_spacing * (self.rows + 1) / 2.0

    def offset(self, film: np.ndarray) -> float:
        """c, m: the mean over the interior rows of the offsets of the cylinder's gap through
        the first x faces' films (h_0 + h_1)/2."""
        face = 0.5 * (film[1:-1, 0] + film[1:-1, 1])
        gap = 0.5 * (cylinder_gap(self.start, self.radius) + cylinder_gap(self.end, self.radius))
        return float(np.mean(face)) - gap

    def _cached(self, key, compute):
        """``compute()`` once per ``key`` among the last CACHED_OFFSETS keys."""
        if key not in self.cache:
            if len(self.cache) >= CACHED_OFFSETS:
                self.cache.pop(next(iter(self.cache)))
            self.cache[key] = compute()
        return self.cache[key]

    def responses(self, offset: float) -> ModeResponses:
        return self._cached(("modes", offset), lambda: mode_responses(
            offset, self.eigenvalues, self.xi, self.start_node, self.end, self.radius, self.viscosity, self.speed))

    def _step(self) -> float:
        return OFFSET_STEP * cylinder_gap(self.end, self.radius)

    def _offset_slope(self, shape) -> np.ndarray:
        slope = np.zeros(shape)
        slope[1:-1, :2] = 0.5 / self.rows
        return slope

    def _system(self, responses: ModeResponses) -> tuple[np.ndarray, np.ndarray]:
        """(block, inflow) of the first column's cells at one offset."""
        flux_u, flux_v = responses.flux
        block = -self.row_spacing * (self.sine.T * flux_u) @ self.projection
        return block, self.row_spacing * self.sine.T @ (self.ones * flux_v)

    def exterior(self, film: np.ndarray) -> Exterior:
        """The Exterior at ``film`` (once per offset c: an evaluation and its slopes ask alike)."""
        c = self.offset(film)
        return self._cached(("exterior", c), lambda: self._exterior(c, film.shape))

    def _exterior(self, c: float, shape) -> Exterior:
        step = self._step()
        block, inflow = self._system(self.responses(c))
        above = self._system(self.responses(c + step))
        return Exterior(block, inflow, (above[0] - block) / step, (above[1] - inflow) / step, self._offset_slope(shape))

    def faces(self, film: np.ndarray, values: FaceFilm, slopes: FaceFilm) -> tuple[FaceFilm, FaceFilm]:
        """``values`` and ``slopes`` (percolation.face_film) with nothing through the first x
        face (the exterior's flux replaces it) and half through the first column's y faces
        (their cells end at x_1)."""
        return _opened(values), _opened(slopes)

    def _load_parts(self, responses: ModeResponses) -> tuple[np.ndarray, float]:
        """(weights (m,) m^2 on the first column's pressures, constant N) of the load upstream
        of x_1, without the first column's half cells."""
        load_u, load_v = responses.load
        return (self.mode_width * (self.ones * load_u) @ self.projection,
                self.mode_width * float(np.sum(self.ones**2 * load_v)))

    def load(self, pressure: np.ndarray, film: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        """(W, weights, film slope) as numerics/far_inlet.FarInlet.load: the load upstream of
        x_1 less the half of the first column's cells the mesh's trapezoidal sum counts there;
        ``weights`` (ny, nx, m^2) dW/dp; ``film slope`` (ny, nx, N/m) dW/dh at fixed p."""
        c, step = self.offset(film), self._step()
        p1 = pressure[1:-1, 1]
        weights, constant = self._load_parts(self.responses(c))
        above = self._load_parts(self.responses(c + step))
        slope = (float((above[0] - weights) @ p1) + above[1] - constant) / step
        weights = weights - 0.5 * self.spacing * self.row_spacing
        value = float(weights @ p1 + constant)
        nodal = np.zeros(pressure.shape)
        nodal[1:-1, 1] = weights
        return value, nodal, slope * self._offset_slope(pressure.shape)

    def upstream(self, pressure: np.ndarray, film: np.ndarray) -> tuple[np.ndarray, float]:
        """(p at x_0 (ny,) Pa, shear upstream of x_0 N) as numerics/far_inlet.FarInlet.upstream,
        from the same modes: sum_j dy (mu U / h + (h/2) dp/dx) over the interior rows."""
        responses = self.responses(self.offset(film))
        modes = self.projection @ pressure[1:-1, 1]
        at_u, at_v = responses.at_start
        shear_u, shear_v = responses.shear
        boundary = np.zeros(pressure.shape[0])
        boundary[1:-1] = self.sine.T @ (modes * at_u + self.ones * at_v)
        shear = (self.row_spacing * self.rows * responses.couette_shear
                 + self.mode_width * float(np.sum(self.ones * (modes * shear_u + self.ones * shear_v))))
        return boundary, shear


def _opened(faces: FaceFilm) -> FaceFilm:
    coefficient_x, gap_x, coefficient_y = faces.coefficient_x.copy(), faces.gap_x.copy(), faces.coefficient_y.copy()
    coefficient_x[:, 0] = gap_x[:, 0] = 0.0
    coefficient_y[:, 1] *= 0.5
    return FaceFilm(coefficient_x, coefficient_y, gap_x)
