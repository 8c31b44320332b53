"""Steady averaged Reynolds equation with the Reynolds (Swift-Stieber) cavitation condition.

Paper Eq. (1) with Patir & Cheng's averaged form (J. Lubr. Technol. 100:12, 1978):

    d/dx(k dp/dx) + d/dy(k dp/dy) = (U/2) dh_T/dx,      k = phi h^3/(12 mu)

on the shared mesh (x sliding, y the cylinder axis). The block slides at U and the cylinder
does not rotate, so the entrainment speed is (U1 + U2)/2 = U/2. p = 0 on the whole boundary
(both x ends, and y = +-L/2 in 2D); in line mode (ny == 1) the problem is 1D in x.

Discretisation (finite volumes on the nodal grid, second order). The volumetric flux is
q = -k grad p + (U/2) h_T e_x. Each interior node owns the cell of size dx * dy around it;
on a face between two nodes the Poiseuille coefficient and the expected gap are the
arithmetic means of the nodal values. The net outflow of cell i is

    w_i = (A p - b)_i = sum_faces T_f (p_i - p_nb) + (U/2) dy (h_T,e - h_T,w)

with transmissibilities T = k_f dy/dx (x faces) and k_f dx/dy (y faces). A is a symmetric
M-matrix (positive definite when k > 0).

Cavitation (paper section 2.2: negative pressures set to zero) is solved as the linear
complementarity problem it is: p >= 0, w >= 0 (in the ruptured zone a full film would need
more fluid than arrives), p w = 0. Because A is an M-matrix, the primal-dual active-set
method (Hintermueller, Ito & Kunisch 2002, SIAM J. Optim. 13:865) ends after finitely many
steps, usually a handful: guess the cavitated set C, solve A_FF p_F = b_F on the pressurised
set F, then C <- {i in C: w_i > 0} + {i in F: p_i < 0}, until C repeats. A cavitated node
learns that it should carry pressure only from a pressurised neighbour, so the full-film
region grows by one node per step: a cold start therefore begins from the solution on a
coarser mesh (nested iteration), smoothed on this mesh by projected Gauss-Seidel sweeps
(projected_smoothing), which leaves 1-3 steps on each mesh whatever its size.

Nodes whose every face has k = 0 (a dry patch where k underflowed, H < -21) carry no film:
they are held at p = 0 and reported as cavitated.

Cost: each step is a sparse LU factorisation of A_FF (SuperLU, minimum-degree ordering),
which dominates a coupled solve on fine meshes. Three things avoid it: ``reuse`` (a solve a
little earlier in the coupled iteration, on the same pressurised set or one a few nodes
away: CG preconditioned with its factors, the set change eliminated exactly, BlockInverse
and ExtendedFactors), the same for an active-set step whose set differs from the step
before by a few nodes, and ``load_sensitivity`` (dW/dh by one back-substitution, so the
force balance takes Newton steps instead of extra Reynolds solves).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import LinAlgError, cho_factor, cho_solve
from scipy.sparse.linalg import splu

from .mesh import Mesh
from .percolation import FaceFilm
from .projected_smoothing import smoothed_cavitated_set

# Hysteresis of the active-set update, relative to the scales of p and w: a node changes
# side only when its multiplier or pressure is clearly of the wrong sign, so round-off near
# the free boundary cannot make the set cycle.
SET_TOLERANCE = 1e-12
# The solution is reported converged when the active set repeated and the relative residual
# (equations on pressurised nodes, complementarity elsewhere) is below this.
RESIDUAL_TOLERANCE = 1e-8
# Nested iteration for a cold start recurses to meshes with at most this many nodes a side.
COARSEST_NODES = 33
# Active-set steps a warm start gets before the solver falls back to the cold start.
WARM_START_STEPS = 4
# Reuse of LU factors (``reuse``): conjugate gradients on A_FF preconditioned by the factors
# of a nearby matrix stop at this relative residual (2-norm), and give up (a new
# factorisation is made) after REUSE_CG_STEPS steps, or after REUSE_CG_CHECK steps that have
# not cut the residual by REUSE_CG_CHECK_FACTOR. Factors of a pressurised set that differs
# from this one by c nodes serve through c back-substitutions (ExtendedFactors), so they
# are used up to REUSE_MAX_CHANGES nodes away: a factorisation costs 15-40
# back-substitutions (2.6k-160k unknowns; before the nested start was smoothed
# (projected_smoothing), 12 left Table 1 at 201^2 with 2-4 factorisations on the finest
# mesh instead of 4-5 and 8 or 20 were no faster; after it, 30 or 80 were slower at
# 201 x 853, where the corrections of 14-29 nodes are rebuilt at every step:
# bench/RESULTS.md).
REUSE_CG_TOLERANCE = 1e-12
REUSE_CG_STEPS = 12
REUSE_CG_CHECK = 3
REUSE_CG_CHECK_FACTOR = 1e-3
REUSE_MAX_CHANGES = 12


@dataclass
class ReynoldsSolution:
    """Fluid pressure on the mesh and how it was reached."""

    pressure: np.ndarray  # (ny, nx) Pa; 0 on the boundary and in the cavitated zone
    cavitated: np.ndarray  # (ny, nx) bool; interior nodes held at p = 0 (boundary False)
    iterations: int  # active-set steps (linear solves); 1 without cavitation
    residual: float  # max relative residual: equations on pressurised nodes, complementarity
    converged: bool
    # solver of the pressurised block A_FF (nodes interior & ~cavitated, C order) of the
    # last step (``BlockInverse``), kept for ``load_sensitivity`` and ``reuse``; None when
    # no node is pressurised
    factor: object | None = None

    def load_sensitivity(self, mesh, gap_slope, coefficient_slope, speed, squeeze_slope=None) -> np.ndarray:
        """dW/dh_j (N/m) at this solution: module function load_sensitivity."""
        return load_sensitivity(mesh, self, gap_slope, coefficient_slope, speed, squeeze_slope)


@dataclass(frozen=True)
class ReynoldsSystem:
    """Discrete Reynolds equation A p = b on the unknown nodes (interior nodes with a film)."""

    matrix: sp.csr_matrix  # (n, n) symmetric M-matrix, m^3/(Pa s)
    rhs: np.ndarray  # (n,) m^3/s
    unknown: np.ndarray  # (ny, nx) bool; the n unknowns in C order


def _interior(shape: tuple[int, int], line: bool) -> np.ndarray:
    interior = np.zeros(shape, dtype=bool)
    if line:
        interior[0, 1:-1] = True
    else:
        interior[1:-1, 1:-1] = True
    return interior


def _face_transmissibilities(mesh, coefficient, faces=None):
    """T of x faces (ny, nx-1) and y faces (ny-1, nx; empty in line mode), m^3/(Pa s): means
    of the nodal k, or ``faces`` (percolation.FaceFilm) evaluated at the faces."""
    if faces is not None:
        return faces.coefficient_x * (mesh.dy / mesh.dx), faces.coefficient_y * (mesh.dx / mesh.dy)
    tx = 0.5 * (coefficient[:, :-1] + coefficient[:, 1:]) * (mesh.dy / mesh.dx)
    ty = 0.5 * (coefficient[:-1, :] + coefficient[1:, :]) * (mesh.dx / mesh.dy)
    return tx, ty


def _couette_face_flux(mesh, expected_gap, speed, faces=None):
    """Couette flux (U/2) h_T,f dy through each x face, m^3/s, (ny, nx-1); h_T,f the mean of
    the nodal h_T, or faces.gap_x (percolation.FaceFilm)."""
    if faces is not None:
        return 0.5 * speed * faces.gap_x * mesh.dy
    return 0.5 * speed * 0.5 * (expected_gap[:, :-1] + expected_gap[:, 1:]) * mesh.dy


def _check_fields(mesh, expected_gap, coefficient):
    for name, field in (("expected_gap", expected_gap), ("coefficient", coefficient)):
        if field.shape != mesh.shape:
            raise ValueError(f"{name} has shape {field.shape}, the mesh {mesh.shape}")
        if not np.all(np.isfinite(field)):
            raise ValueError(f"{name} has non-finite values")
    if np.any(coefficient < 0.0):
        raise ValueError(f"Poiseuille coefficient must be >= 0; min {coefficient.min():.3g}")


def reynolds_system(mesh, expected_gap, coefficient, speed, faces=None, squeeze_rate=None) -> ReynoldsSystem:
    """Assemble the finite-volume Reynolds equation (Eq. 1) without loops over nodes.

    expected_gap = h_T (ny, nx) m, coefficient = k (ny, nx) m^3/(Pa s), speed = U m/s;
    ``faces`` (percolation.FaceFilm): k and h_T of the faces instead of nodal means. A node
    whose faces all carry no flow (sealed) is not an unknown and stays at p = 0.
    ``squeeze_rate``: dh_T/dt (ny, nx) m/s of a transient (physics.md section 14): each
    cell's volume changes by dA dh_T/dt, so its net outflow is w = A p - b + dA dh_T/dt
    (the squeeze term of the time-dependent Reynolds equation); None: steady.
    """
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    _check_fields(mesh, expected_gap, coefficient)
    tx, ty = _face_transmissibilities(mesh, coefficient, faces)

    diagonal = np.zeros(mesh.shape)
    diagonal[:, :-1] += tx
    diagonal[:, 1:] += tx
    diagonal[:-1, :] += ty
    diagonal[1:, :] += ty
    unknown = _interior(mesh.shape, mesh.line) & (diagonal > 0.0)
    number = np.full(mesh.shape, -1)
    n = int(unknown.sum())
    number[unknown] = np.arange(n)

    rows, cols, vals = [np.arange(n)], [np.arange(n)], [diagonal[unknown]]
    for a, c, t in ((number[:, :-1], number[:, 1:], tx), (number[:-1, :], number[1:, :], ty)):
        both = (a >= 0) & (c >= 0)
        rows += [a[both], c[both]]
        cols += [c[both], a[both]]
        vals += [-t[both], -t[both]]
    matrix = sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
    )

    couette = _couette_face_flux(mesh, expected_gap, speed, faces)
    outflow = np.zeros(mesh.shape)
    outflow[:, 1:-1] = couette[:, 1:] - couette[:, :-1]
    if squeeze_rate is not None:
        outflow += mesh.nodal_area * squeeze_rate
    return ReynoldsSystem(matrix=matrix, rhs=-outflow[unknown], unknown=unknown)


def _factorize(block):
    return splu(block, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})


class ExtendedFactors:
    """The LU factors ``lu`` of a block A on the node set ``source`` (flat mesh indices in
    block order), turned into the exact inverse of a matrix on another set ``target`` with
    the few changed nodes eliminated by capacitance (Schur complement) corrections: the
    preconditioner of CG on a nearby block B (``block``, on ``target``) in place of a new
    factorisation.

    With h the nodes both sets share, R those only ``source`` has and G those only
    ``target`` has, it inverts P = [[A_hh, B_hG], [B_Gh, B_GG]]:
      - A_hh^-1 from A^-1 by holding the R nodes at zero with multipliers:
        A_hh^-1 r = (z - W C^-1 z_R)_h, z = A^-1 r (extended by zero), W = A^-1 E_R,
        C = W_R (a principal block of A^-1, symmetric positive definite);
      - G by block elimination with S = B_GG - B_Gh V, V = A_hh^-1 B_hG.
    Building it costs |R| + |G| back-substitutions (``changes``); each solve one more and
    dense products with W and V. P equals B where the old and new matrices agree, so CG only
    resolves the change of the film, however the set moved (Hager 1989, SIAM Rev. 31:221,
    on updating an inverse by a few rows). ``usable`` is False when the sets differ by more
    than ``max_changes`` nodes (nothing is built) or C or S is not positive definite in
    floating point: then the block is factorised instead."""

    def __init__(self, lu, source, target, block, max_changes=np.inf):
        self.lu, self.source = lu, source
        position = np.full(int(max(source.max(initial=-1), target.max(initial=-1))) + 1, -1)
        position[source] = np.arange(source.size)
        where = position[target]
        self.shared = where >= 0
        self.into = where[self.shared]
        self.changes = int(np.count_nonzero(~self.shared)) + (source.size - self.into.size)
        self.same = self.changes == 0
        self.usable = self.changes <= max_changes
        self.removed = self.coupling = None
        if self.same or not self.usable:
            return
        kept = np.zeros(source.size, dtype=bool)
        kept[self.into] = True
        self.removed = np.flatnonzero(~kept)
        added = ~self.shared
        try:  # C and S are symmetric positive definite in exact arithmetic
            if self.removed.size:
                columns = np.zeros((source.size, self.removed.size))
                columns[self.removed, np.arange(self.removed.size)] = 1.0
                self.w = lu.solve(columns)
                self.capacitance = cho_factor(self.w[self.removed])
            if added.any():
                self.coupling = block[self.shared][:, added].tocsc()  # B_hG
                self.v = self._shared_inverse(self.coupling.toarray())
                self.schur = cho_factor(block[added][:, added].toarray() - self.coupling.T @ self.v)
        except LinAlgError:  # not positive definite after all: factorise the block instead
            self.usable = False

    def _shared_inverse(self, rhs):
        """A_hh^-1 rhs (rhs on the shared nodes, one column or several)."""
        extended = np.zeros((self.source.size,) + rhs.shape[1:])
        extended[self.into] = rhs
        z = self.lu.solve(extended)
        if self.removed.size:
            z -= self.w @ cho_solve(self.capacitance, z[self.removed])
        return z[self.into]

    def solve(self, rhs):
        if self.same:
            return self.lu.solve(rhs)
        solution = np.empty(rhs.size)
        y = self._shared_inverse(rhs[self.shared])
        if self.coupling is None:
            solution[self.shared] = y
            return solution
        added = cho_solve(self.schur, rhs[~self.shared] - self.coupling.T @ y)
        solution[self.shared] = y - self.v @ added
        solution[~self.shared] = added
        return solution


def _preconditioned_cg(block, rhs, preconditioner):
    """x with block x = rhs by conjugate gradients preconditioned with ``preconditioner``
    (ExtendedFactors: the exact inverse of a nearby SPD matrix); None when it does not
    converge fast (see REUSE_CG_*)."""
    x = np.zeros_like(rhs)
    r = rhs.copy()
    target = REUSE_CG_TOLERANCE * np.linalg.norm(rhs)
    start = np.linalg.norm(r)
    if start <= target:
        return x
    z = preconditioner.solve(r)
    d = z.copy()
    rz = r @ z
    for step in range(1, REUSE_CG_STEPS + 1):
        q = block @ d
        alpha = rz / (d @ q)
        x += alpha * d
        r -= alpha * q
        norm = np.linalg.norm(r)
        if norm <= target:
            return x
        if step == REUSE_CG_CHECK and norm > REUSE_CG_CHECK_FACTOR * start:
            return None
        z = preconditioner.solve(r)
        rz, rz_old = r @ z, rz
        d = z + (rz / rz_old) * d
    return None


class BlockInverse:
    """Solves with the pressurised block A_FF (nodes ``index``, flat mesh indices) of one
    Reynolds solve: by its own LU factors, or, given the factors of a nearby matrix
    (``nearby``: a BlockInverse on the same set or one that differs by at most
    REUSE_MAX_CHANGES nodes), by conjugate gradients preconditioned with them
    (ExtendedFactors), factorising A_FF only if CG stalls.

    In the coupled iteration consecutive Reynolds solves differ by a small change of the
    film, and the active-set steps by a few nodes of the free boundary, so the old factors
    are an almost exact inverse and CG needs a few back-substitutions instead of a
    factorisation (the cost of a solve on fine meshes).
    """

    def __init__(self, block, index, nearby=None):
        self.block = block  # A_FF, csc
        self.index = index
        self.preconditioner = None
        if nearby is not None:
            candidate = ExtendedFactors(*nearby.own_factors, index, block, REUSE_MAX_CHANGES)
            self.preconditioner = candidate if candidate.usable else None
        self.lu = _factorize(block) if self.preconditioner is None else None

    @property
    def own_factors(self):
        """(LU factors, their node set) of the last factorisation behind this inverse."""
        if self.lu is not None:
            return self.lu, self.index
        return self.preconditioner.lu, self.preconditioner.source

    @property
    def factors(self):
        """An approximate inverse of A_FF on this set (``solve``): its own LU factors, or the
        nearby ones (ExtendedFactors)."""
        return self.lu if self.lu is not None else self.preconditioner

    def solve(self, rhs):
        if self.lu is None:
            x = _preconditioned_cg(self.block, rhs, self.preconditioner)
            if x is not None:
                return x
            self.lu = _factorize(self.block)
        return self.lu.solve(rhs)


def _solve_on(matrix, rhs, free, index, nearby=None):
    """(p, BlockInverse of A_FF or None) with p = 0 off the free set and A_FF p_F = b_F on
    it; ``index``: flat mesh index of each unknown; ``nearby``: the BlockInverse of
    a nearby matrix to precondition with (BlockInverse)."""
    p = np.zeros(rhs.size)
    inverse = None
    if free.any():
        inverse = BlockInverse(matrix[free][:, free].tocsc(), index[free], nearby)
        p[free] = inverse.solve(rhs[free])
    return p, inverse


def _relative_residual(matrix, rhs, p, cavitated, cavitation):
    """Max relative violation of: w = 0 on pressurised nodes; with cavitation also w >= 0 and
    p = 0 on cavitated ones and p >= 0 everywhere (pressures turned into flux units by the
    diagonal). Relative to the larger of |b| and |diag p|."""
    w = matrix @ p - rhs
    diagonal = matrix.diagonal()
    scale = max(np.abs(rhs).max(initial=0.0), (diagonal * np.abs(p)).max(initial=0.0))
    if scale == 0.0:  # no flow and no pressure: p = 0 solves the problem exactly
        return 0.0
    violation = np.where(cavitated, np.maximum(-w, 0.0) + diagonal * np.abs(p), np.abs(w))
    if cavitation:
        violation = np.maximum(violation, diagonal * np.maximum(-p, 0.0))
    return float(violation.max(initial=0.0) / scale)


def _coarser(mesh, coarsest=COARSEST_NODES):
    """The mesh with every other node (same domain) in each direction longer than
    ``coarsest`` nodes, or None when no direction is."""
    def halve(nodes):
        if nodes.size <= coarsest:
            return nodes
        return np.linspace(nodes[0], nodes[-1], (nodes.size + 1) // 2)

    if mesh.nx <= coarsest and (mesh.line or mesh.ny <= coarsest):
        return None
    return Mesh(x=halve(mesh.x), y=mesh.y if mesh.line else halve(mesh.y), length=mesh.length)


def _interpolate(field, source, target):
    """Bilinear interpolation of a (ny, nx) field between meshes over the same domain."""
    def along(values, nodes_from, nodes_to, axis):
        if nodes_from.size == 1:
            return values
        i = np.clip(np.searchsorted(nodes_from, nodes_to, side="right") - 1, 0, nodes_from.size - 2)
        t = np.clip((nodes_to - nodes_from[i]) / (nodes_from[i + 1] - nodes_from[i]), 0.0, 1.0)
        shape = (-1, 1) if axis == 0 else (1, -1)
        lower, upper = np.take(values, i, axis=axis), np.take(values, i + 1, axis=axis)
        return lower + t.reshape(shape) * (upper - lower)

    return along(along(field, source.x, target.x, 1), source.y, target.y, 0)


def _nested_guess(mesh, coarse, system, expected_gap, coefficient, speed, max_iterations, squeeze_rate=None):
    """Cavitated set (over the unknowns of ``system``) guessed from the solution on the
    coarser mesh (nested iteration).

    A cavitated node only learns that it should carry pressure from a pressurised neighbour,
    so the active-set method grows the full-film region by one node per step: from a cold
    start the step count grows with the mesh. Solving on coarser meshes first, and smoothing
    the interpolated pressure on this mesh (projected_smoothing), leaves the free boundary a
    node or two to move on each level.
    """
    solution = solve_reynolds(
        coarse,
        _interpolate(expected_gap, mesh, coarse),
        _interpolate(coefficient, mesh, coarse),
        speed,
        max_iterations=max_iterations,
        squeeze_rate=None if squeeze_rate is None else _interpolate(squeeze_rate, mesh, coarse),
    )
    return smoothed_cavitated_set(system, _interpolate(solution.pressure, coarse, mesh))


def _active_set(matrix, rhs, cavitated, max_steps, index, nearby=None):
    """Primal-dual active-set steps from the cavitated set ``cavitated`` (unknown-node mask):
    (p, cavitated set of p, steps, whether the set repeated, BlockInverse of the last step).
    ``index``: flat mesh index of each unknown; ``nearby``: a BlockInverse (the previous
    evaluation's) whose factors may precondition the first step; each later step is
    preconditioned by the factors of the step before (BlockInverse), so a free boundary
    that moves by a few nodes costs back-substitutions, not a factorisation."""
    w_tol = SET_TOLERANCE * np.abs(rhs).max(initial=0.0)
    for steps in range(1, max_steps + 1):
        p, factor = _solve_on(matrix, rhs, ~cavitated, index, nearby)
        nearby = factor if factor is not None else nearby
        w = matrix @ p - rhs
        p_tol = SET_TOLERANCE * np.abs(p).max(initial=0.0)
        updated = np.where(cavitated, w >= -w_tol, p < -p_tol)
        repeated = np.array_equal(updated, cavitated)
        if repeated or steps == max_steps:
            break
        cavitated = updated
    return p, cavitated, steps, repeated, factor


def _cold_guess(mesh, system, expected_gap, coefficient, speed, max_iterations, squeeze_rate=None):
    """Cavitated set to start from without a warm start: from the solution on a mesh with half
    the nodes (recursively), and on the coarsest mesh the nodes where the gap diverges."""
    coarse = _coarser(mesh)
    if coarse is None:
        return system.rhs < 0.0
    return _nested_guess(mesh, coarse, system, expected_gap, coefficient, speed, max_iterations, squeeze_rate)


def _reusable(mesh, reuse):
    """The BlockInverse of the solution ``reuse`` when it is on this mesh, else None."""
    if reuse is None or reuse.factor is None or reuse.pressure.shape != mesh.shape:
        return None
    return reuse.factor


def solve_reynolds(mesh, expected_gap, coefficient, speed, cavitation=True,
                   cavitated_guess=None, max_iterations=100, reuse=None, faces=None,
                   squeeze_rate=None, pressure_guess=None) -> ReynoldsSolution:
    """Fluid pressure of Eq. (1) with p = 0 on the boundary.

    cavitation=True: Reynolds (Swift-Stieber) condition by the primal-dual active-set method.
    ``cavitated_guess`` (ny, nx) bool warm-starts it; a guess that has not settled within
    WARM_START_STEPS steps (a free boundary far away creeps one node per step) is dropped for
    the cold start: the solution on a mesh with half the nodes (recursively; on the coarsest
    mesh the nodes where the gap diverges). ``iterations`` counts the steps on ``mesh``.
    cavitation=False: full Sommerfeld, one linear solve, p may be negative.
    ``reuse``: the solution of a nearby problem on the same mesh (the previous evaluation of
    a coupled iteration); when the first linear solve is on its pressurised set, it runs by
    CG preconditioned with its LU factors (BlockInverse) instead of a new factorisation.
    ``faces`` (percolation.FaceFilm): the film on the faces (reynolds_system); the nested
    cold start on coarser meshes uses the nodal fields.
    ``squeeze_rate``: dh_T/dt (ny, nx) m/s of a transient step (reynolds_system).
    ``pressure_guess`` (ny, nx) Pa, e.g. a coarser mesh's solution interpolated to this one,
    warm-starts the set instead of ``cavitated_guess``: the set of the guess after projected
    Gauss-Seidel smoothing on this mesh's system (projected_smoothing).
    """
    if max_iterations < 1:
        raise ValueError(f"max_iterations must be >= 1, got {max_iterations}")
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    system = reynolds_system(mesh, expected_gap, coefficient, speed, faces, squeeze_rate)
    matrix, rhs = system.matrix, system.rhs
    index = np.flatnonzero(system.unknown)
    nearby = _reusable(mesh, reuse)
    if not cavitation:
        cavitated = np.zeros(rhs.size, dtype=bool)
        p, factor = _solve_on(matrix, rhs, ~cavitated, index, nearby)
        iterations, repeated = 1, True
    else:
        iterations, repeated = 0, False
        warm = None
        if pressure_guess is not None:
            warm = smoothed_cavitated_set(system, pressure_guess)
        elif cavitated_guess is not None:
            warm = np.asarray(cavitated_guess, dtype=bool)[system.unknown]
        if warm is not None:
            p, cavitated, iterations, repeated, factor = _active_set(
                matrix, rhs, warm, min(WARM_START_STEPS, max_iterations), index, nearby
            )
        if not repeated and iterations < max_iterations:
            cold = _cold_guess(mesh, system, expected_gap, coefficient, speed, max_iterations, squeeze_rate)
            p, cavitated, steps, repeated, factor = _active_set(matrix, rhs, cold, max_iterations - iterations, index)
            iterations += steps
    residual = _relative_residual(matrix, rhs, p, cavitated, cavitation)

    pressure = np.zeros(mesh.shape)
    pressure[system.unknown] = p
    cavitated_field = _interior(mesh.shape, mesh.line) & ~system.unknown
    cavitated_field[system.unknown] = cavitated
    return ReynoldsSolution(
        pressure=pressure,
        cavitated=cavitated_field,
        iterations=iterations,
        residual=residual,
        converged=bool(repeated and residual <= RESIDUAL_TOLERANCE),
        factor=factor,
    )


def boundary_flux(mesh, solution, expected_gap, coefficient, speed, faces=None) -> float:
    """Net volumetric outflow of the full-film region, m^3/s: through the domain boundary plus
    into the cavitated region. Zero for a mass-conserving solution.

    Evaluated from the face fluxes q_f = T_f (p_left - p_right) + (U/2) h_T,f dy of the faces
    between a pressurised interior node and a node that is not (boundary or cavitated),
    independently of the assembled matrix. Compare it with the inlet flux (U/2) h_T dy.
    ``faces`` (percolation.FaceFilm): the film on the faces, as the solve used it.
    """
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    _check_fields(mesh, expected_gap, coefficient)
    p = solution.pressure
    full = _interior(mesh.shape, mesh.line) & ~solution.cavitated
    tx, ty = _face_transmissibilities(mesh, coefficient, faces)
    qx = tx * (p[:, :-1] - p[:, 1:]) + _couette_face_flux(mesh, expected_gap, speed, faces)
    qy = ty * (p[:-1, :] - p[1:, :])
    total = 0.0
    for q, left, right in ((qx, full[:, :-1], full[:, 1:]), (qy, full[:-1, :], full[1:, :])):
        total += q[left & ~right].sum() - q[right & ~left].sum()
    return float(total)


def load_sensitivity(mesh, solution, gap_slope, coefficient_slope, speed, squeeze_slope=None) -> np.ndarray:
    """dW/dh_j, N/m (ny, nx): how the fluid load W = sum_i p_i dA_i changes with the film at
    node j, at the solution's active set, by the adjoint method (one more solve with A_FF:
    a back-substitution with the LU factors the solve left, or a few CG steps when it
    reused older factors).

    With the residual r = A(k) p - b(h_T) on the pressurised set F and A_FF lambda = dA_F
    (A is symmetric), dW/dh_j = -lambda^T dr/dh_j. In face form lambda^T r =
    sum_faces T_f (lambda_a - lambda_b)(p_a - p_b) + sum_x-faces c_f (lambda_a - lambda_b)
    (a the node before b, c_f the Couette flux), and T_f, c_f are face means of nodal k and
    h_T, so each face passes half its derivative to each of its nodes. ``gap_slope`` =
    dh_T/dh and ``coefficient_slope`` = dk/dh are nodal (ny, nx). The cavitated set moves
    with h too, but where it meets the pressurised set p = 0 and grad p = 0 (Reynolds
    condition), so that motion does not change W to first order.
    ``squeeze_slope`` (1/s, nodal): d(dh_T/dt)/dh of a transient step (the time
    discretisation's coefficient times dh_T/dh; reynolds_system's squeeze_rate); the cell term
    dA_j dh_T,j/dt adds lambda_j dA_j squeeze_slope_j to dr/dh_j.
    """
    if solution.factor is None:
        return np.zeros(mesh.shape)
    free = _interior(mesh.shape, mesh.line) & ~solution.cavitated
    adjoint = np.zeros(mesh.shape)
    adjoint[free] = solution.factor.solve(mesh.nodal_area[free])
    sensitivity = adjoint_sensitivity(mesh, adjoint, solution.pressure, gap_slope, coefficient_slope, speed)
    if squeeze_slope is not None:
        sensitivity -= adjoint * mesh.nodal_area * squeeze_slope
    return sensitivity


def adjoint_sensitivity(mesh, adjoint, pressure, gap_slope, coefficient_slope, speed, face_content=None):
    """-lambda^T dr/dh_j (ny, nx) for the adjoint ``adjoint`` (nodal, 0 off the unknowns) of
    the finite-volume residual r: Poiseuille faces T_f (p_a - p_b), Couette x faces
    c_f theta_f (a the node before b; ``face_content`` theta_f (ny, nx-1), 1 if None), with
    T_f and c_f face means of nodal k and h_T, so each face passes half its derivative to
    each of its nodes (see load_sensitivity). With ``coefficient_slope`` a
    percolation.FaceFilm of derivatives in the face film h_f = (h_a + h_b)/2 (faces
    evaluated at their own film), ``gap_slope`` is unused and each face passes half of its
    own derivative to each node."""
    p = pressure
    jump_x = adjoint[:, :-1] - adjoint[:, 1:]
    content = 1.0 if face_content is None else face_content
    if isinstance(coefficient_slope, FaceFilm):
        face_x = (0.5 * (mesh.dy / mesh.dx) * jump_x * (p[:, :-1] - p[:, 1:]) * coefficient_slope.coefficient_x
                  + 0.25 * speed * mesh.dy * jump_x * content * coefficient_slope.gap_x)
        face_y = (0.5 * (mesh.dx / mesh.dy) * (adjoint[:-1, :] - adjoint[1:, :]) * (p[:-1, :] - p[1:, :])
                  * coefficient_slope.coefficient_y)
        sensitivity = np.zeros(mesh.shape)
        sensitivity[:, :-1] -= face_x
        sensitivity[:, 1:] -= face_x
        sensitivity[:-1, :] -= face_y
        sensitivity[1:, :] -= face_y
        return sensitivity
    coefficient_part = np.zeros(mesh.shape)
    couette_part = np.zeros(mesh.shape)
    for part, face in (
        (coefficient_part, 0.5 * (mesh.dy / mesh.dx) * jump_x * (p[:, :-1] - p[:, 1:])),
        (couette_part, 0.25 * speed * mesh.dy * jump_x * content),
    ):
        part[:, :-1] += face
        part[:, 1:] += face
    face_y = 0.5 * (mesh.dx / mesh.dy) * (adjoint[:-1, :] - adjoint[1:, :]) * (p[:-1, :] - p[1:, :])
    coefficient_part[:-1, :] += face_y
    coefficient_part[1:, :] += face_y
    return -(np.asarray(coefficient_slope) * coefficient_part + np.asarray(gap_slope) * couette_part)
