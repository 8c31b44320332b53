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
force balance takes Newton steps instead of extra Reynolds solves). The matrix itself is
assembled on a sparsity pattern kept per set of unknowns (numerics/reynolds_pattern.py), so
an evaluation computes its values and nothing of its structure.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

from lubecontact.numerics.linear_algebra import BlockInverse
from lubecontact.numerics.projected_smoothing import smoothed_cavitated_set
from lubecontact.numerics.reynolds_pattern import ReynoldsPattern, reynolds_pattern
from lubecontact.numerics.transfer import coarser_mesh, interpolate_field
from lubecontact.physics.percolation import FaceFilm, face_films

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

    def load_sensitivity(self, mesh, gap_slope, coefficient_slope, speed, squeeze=None, load_weight=None,
                         exterior=None) -> np.ndarray:
        """dW/dh_j (N/m) at this solution: module function load_sensitivity."""
        return load_sensitivity(mesh, self, gap_slope, coefficient_slope, speed, squeeze, load_weight, exterior)


@dataclass(frozen=True)
class ReynoldsSystem:
    """Discrete Reynolds equation A p = b on the unknown nodes (interior nodes with a film)."""

    matrix: sp.csr_matrix  # (n, n) symmetric M-matrix, m^3/(Pa s)
    rhs: np.ndarray  # (n,) m^3/s
    unknown: np.ndarray  # (ny, nx) bool; the n unknowns in C order
    pattern: ReynoldsPattern  # where A's entries are stored, kept across assemblies


def interior_nodes(shape: tuple[int, int], line: bool) -> np.ndarray:
    interior = np.zeros(shape, dtype=bool)
    if line:
        interior[0, 1:-1] = True
    else:
        interior[1:-1, 1:-1] = True
    return interior


def face_transmissibilities(mesh, coefficient, faces=None):
    """T of x faces (ny, nx-1) and y faces (ny-1, nx; empty in line mode), m^3/(Pa s): means
    of the nodal k, or ``faces`` (percolation.FaceFilm) evaluated at the faces."""
    if faces is not None:
        return faces.coefficient_x * (mesh.dy / mesh.dx), faces.coefficient_y * (mesh.dx / mesh.dy)
    tx = 0.5 * (coefficient[:, :-1] + coefficient[:, 1:]) * (mesh.dy / mesh.dx)
    ty = 0.5 * (coefficient[:-1, :] + coefficient[1:, :]) * (mesh.dx / mesh.dy)
    return tx, ty


def cell_diagonal(mesh, tx, ty) -> np.ndarray:
    """Each cell's Poiseuille diagonal A_ii (ny, nx), m^3/(Pa s): the sum of the
    transmissibilities of its faces (``face_transmissibilities``)."""
    diagonal = np.zeros(mesh.shape)
    diagonal[:, :-1] += tx
    diagonal[:, 1:] += tx
    diagonal[:-1, :] += ty
    diagonal[1:, :] += ty
    return diagonal


def couette_face_flux(mesh, expected_gap, speed, faces=None):
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


def reynolds_system(mesh, expected_gap, coefficient, speed, faces=None, squeeze_rate=None,
                    exterior=None) -> ReynoldsSystem:
    """Assemble the finite-volume Reynolds equation (Eq. 1) without loops over nodes.

    expected_gap = h_T (ny, nx) m, coefficient = k (ny, nx) m^3/(Pa s), speed = U m/s;
    ``faces`` (percolation.FaceFilm): k and h_T of the faces instead of nodal means. A node
    whose faces all carry no flow (sealed) is not an unknown and stays at p = 0.
    ``squeeze_rate``: dh_T/dt (ny, nx) m/s of a transient (docs/physics.md section 14): each
    cell's volume changes by dA dh_T/dt, so its net outflow is w = A p - b + dA dh_T/dt
    (the squeeze term of the time-dependent Reynolds equation); None: steady.
    ``exterior`` (numerics/modal_far_inlet.Exterior): a 2-D mesh open to the far inlet, whose
    first column's cells (rows 1 .. ny-2) add its dense block @ p - inflow to their outflow.
    """
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    _check_fields(mesh, expected_gap, coefficient)
    tx, ty = face_transmissibilities(mesh, coefficient, faces)
    diagonal = cell_diagonal(mesh, tx, ty)
    unknown = interior_nodes(mesh.shape, mesh.line) & (diagonal > 0.0)
    pattern = reynolds_pattern(unknown, 0 if exterior is None else exterior.inflow.size)
    couette = couette_face_flux(mesh, expected_gap, speed, faces)
    outflow = np.zeros(mesh.shape)
    outflow[:, 1:-1] = couette[:, 1:] - couette[:, :-1]
    if squeeze_rate is not None:
        outflow += mesh.nodal_area * squeeze_rate
    if exterior is not None:
        outflow[1:-1, 1] -= exterior.inflow
    matrix = pattern.matrix(diagonal[unknown], tx, ty, None if exterior is None else exterior.block)
    return ReynoldsSystem(matrix=matrix, rhs=-outflow[unknown], unknown=unknown, pattern=pattern)


def _solve_on(system, free, index, nearby=None):
    """(p, BlockInverse of A_FF or None) with p = 0 off the free set and A_FF p_F = b_F on
    it (``system``: a ReynoldsSystem); ``index``: flat mesh index of each unknown;
    ``nearby``: the BlockInverse of a nearby matrix to precondition with (BlockInverse)."""
    p = np.zeros(system.rhs.size)
    inverse = None
    if free.any():
        inverse = BlockInverse(system.pattern.block(system.matrix, free), index[free], nearby)
        p[free] = inverse.solve(system.rhs[free])
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
        interpolate_field(expected_gap, mesh, coarse),
        interpolate_field(coefficient, mesh, coarse),
        speed,
        max_iterations=max_iterations,
        squeeze_rate=None if squeeze_rate is None else interpolate_field(squeeze_rate, mesh, coarse),
    )
    return smoothed_cavitated_set(system, interpolate_field(solution.pressure, coarse, mesh))


def _active_set(system, cavitated, max_steps, index, nearby=None):
    """Primal-dual active-set steps on ``system`` (a ReynoldsSystem) from the cavitated set
    ``cavitated`` (unknown-node mask):
    (p, cavitated set of p, steps, whether the set repeated, BlockInverse of the last step).
    ``index``: flat mesh index of each unknown; ``nearby``: a BlockInverse (the previous
    evaluation's) whose factors may precondition the first step; each later step is
    preconditioned by the factors of the step before (BlockInverse), so a free boundary
    that moves by a few nodes costs back-substitutions, not a factorisation."""
    matrix, rhs = system.matrix, system.rhs
    w_tol = SET_TOLERANCE * np.abs(rhs).max(initial=0.0)
    for steps in range(1, max_steps + 1):
        p, factor = _solve_on(system, ~cavitated, index, nearby)
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
    coarse = coarser_mesh(mesh, COARSEST_NODES)
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
                   squeeze_rate=None, pressure_guess=None, exterior=None) -> ReynoldsSolution:
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
    ``exterior``: the far inlet of a 2-D mesh (reynolds_system; not on the coarser meshes of
    the cold start, which only guess the set).
    ``pressure_guess`` (ny, nx) Pa, e.g. a coarser mesh's solution interpolated to this one,
    warm-starts the set instead of ``cavitated_guess``: the set of the guess after projected
    Gauss-Seidel smoothing on this mesh's system (projected_smoothing).
    """
    if max_iterations < 1:
        raise ValueError(f"max_iterations must be >= 1, got {max_iterations}")
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    system = reynolds_system(mesh, expected_gap, coefficient, speed, faces, squeeze_rate, exterior)
    matrix, rhs = system.matrix, system.rhs
    index = np.flatnonzero(system.unknown)
    nearby = _reusable(mesh, reuse)
    if not cavitation:
        cavitated = np.zeros(rhs.size, dtype=bool)
        p, factor = _solve_on(system, ~cavitated, index, nearby)
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
                system, warm, min(WARM_START_STEPS, max_iterations), index, nearby
            )
        if not repeated and iterations < max_iterations:
            cold = _cold_guess(mesh, system, expected_gap, coefficient, speed, max_iterations, squeeze_rate)
            p, cavitated, steps, repeated, factor = _active_set(system, cold, max_iterations - iterations, index)
            iterations += steps
    residual = _relative_residual(matrix, rhs, p, cavitated, cavitation)

    pressure = np.zeros(mesh.shape)
    pressure[system.unknown] = p
    cavitated_field = interior_nodes(mesh.shape, mesh.line) & ~system.unknown
    cavitated_field[system.unknown] = cavitated
    return ReynoldsSolution(
        pressure=pressure,
        cavitated=cavitated_field,
        iterations=iterations,
        residual=residual,
        converged=bool(repeated and residual <= RESIDUAL_TOLERANCE),
        factor=factor,
    )


@lru_cache(maxsize=8)
def cross_gradient_operators(ny: int, nx: int, dx: float, dy: float) -> tuple[sp.csr_matrix, sp.csr_matrix] | None:
    """(dG_t/dp of the x faces, of the y faces): (faces in C order, nodes) matrices of the
    pressure gradient along each face, the mean of its two nodes' differences (central, one-
    sided at the domain's edge, as numpy.gradient); None on a line (one row: no gradient along y)."""
    if ny == 1:
        return None

    def difference(n, spacing):  # (n, n): d/ds at each of n nodes
        rows = np.arange(n)
        lower, upper = np.maximum(rows - 1, 0), np.minimum(rows + 1, n - 1)
        weight = 1.0 / ((upper - lower) * spacing)
        return sp.csr_matrix((np.concatenate([weight, -weight]), (np.concatenate([rows, rows]),
                                                                   np.concatenate([upper, lower]))), shape=(n, n))

    def mean(n):  # (n - 1, n): the mean of each pair of neighbours
        rows = np.arange(n - 1)
        return sp.csr_matrix((np.full(2 * (n - 1), 0.5), (np.concatenate([rows, rows]),
                                                          np.concatenate([rows, rows + 1]))), shape=(n - 1, n))

    along_y = sp.kron(difference(ny, dy), sp.identity(nx))
    along_x = sp.kron(sp.identity(ny), difference(nx, dx))
    return ((sp.kron(sp.identity(ny), mean(nx)) @ along_y).tocsr(), (sp.kron(mean(ny), sp.identity(nx)) @ along_x).tocsr())


def boundary_flux(mesh, solution, expected_gap, coefficient, speed, faces=None, reduction=None) -> float:
    """Net volumetric outflow of the full-film region, m^3/s: through the domain boundary plus
    into the cavitated region. Zero for a mass-conserving solution.

    Evaluated from the face fluxes q_f = T_f (p_left - p_right) + (U/2) h_T,f dy of the faces
    between a pressurised interior node and a node that is not (boundary or cavitated),
    independently of the assembled matrix; with mass-conserving cavitation each x face's
    Couette flux carries the content upwind of it (the solution's face_content,
    cavitation_jfo.JFOSolution). Compare it with the inlet flux (U/2) h_T dy.
    ``faces`` (percolation.FaceFilm): the film on the faces, as the solve used it.
    ``reduction(G, s)``: a grease's reduction factor of the Poiseuille term at the face
    gradients G (Pa/m, the magnitude |(G_n, G_t)| of the gradient across the face and, in
    2-D, along it, cross_gradient_operators, as the grease's outflow takes it,
    numerics/yield_stress_reynolds.py) and
    face contents s (m, the mean of the two nodes' h_T;
    numerics/yield_stress_reynolds.reduction_factor), T_f r_f in place of T_f.
    """
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    _check_fields(mesh, expected_gap, coefficient)
    p = solution.pressure
    full = interior_nodes(mesh.shape, mesh.line) & ~solution.cavitated
    tx, ty = face_transmissibilities(mesh, coefficient, faces)
    if reduction is not None:
        sx, sy = face_films(expected_gap)
        gx, gy = np.diff(p, axis=1) / mesh.dx, np.diff(p, axis=0) / mesh.dy
        along = cross_gradient_operators(*mesh.shape, mesh.dx, mesh.dy)
        if along is not None:  # 2-D: each face's gradient along it
            gx = np.hypot(gx, (along[0] @ p.ravel()).reshape(gx.shape))
            gy = np.hypot(gy, (along[1] @ p.ravel()).reshape(gy.shape))
        tx = tx * reduction(gx, sx)
        ty = ty * reduction(gy, sy)
    carried = getattr(solution, "face_content", None)
    couette = couette_face_flux(mesh, expected_gap, speed, faces)
    qx = tx * (p[:, :-1] - p[:, 1:]) + (couette if carried is None else carried * couette)
    qy = ty * (p[:-1, :] - p[1:, :])
    total = 0.0
    for q, left, right in ((qx, full[:, :-1], full[:, 1:]), (qy, full[:-1, :], full[1:, :])):
        total += q[left & ~right].sum() - q[right & ~left].sum()
    return float(total)


def load_sensitivity(mesh, solution, gap_slope, coefficient_slope, speed, squeeze=None, load_weight=None,
                     exterior=None) -> np.ndarray:
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
    ``squeeze`` (c0 in 1/s, control_volume.ControlVolumeMean of the cells' content): a
    transient step's squeeze term dA_i dh_T,i/dt with dh_T,i/dt = c0 c_i + history
    (reynolds_system's squeeze_rate) adds c0 (dc/dh)^T (lambda dA) to lambda^T dr/dh.
    ``load_weight`` (ny, nx, m^2): dW/dp_i where the load is not the nodal areas' sum (a mesh
    open to the far inlet, numerics/far_inlet.FarInlet.load); None: the nodal areas.
    ``exterior`` (numerics/modal_far_inlet.Exterior): a 2-D mesh's far inlet, whose outflow
    moves with the parabola's offset c: -lambda^T dr/dc dc/dh on the first x faces' nodes.
    """
    if solution.factor is None:
        return np.zeros(mesh.shape)
    free = interior_nodes(mesh.shape, mesh.line) & ~solution.cavitated
    adjoint = np.zeros(mesh.shape)
    adjoint[free] = solution.factor.solve((mesh.nodal_area if load_weight is None else load_weight)[free])
    sensitivity = adjoint_sensitivity(mesh, adjoint, solution.pressure, gap_slope, coefficient_slope, speed)
    if exterior is not None:
        sensitivity -= float(adjoint[1:-1, 1] @ exterior.outflow_slope(solution.pressure)) * exterior.offset_slope
    if squeeze is not None:
        coefficient, content = squeeze
        sensitivity -= coefficient * content.transpose(adjoint * mesh.nodal_area)
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
