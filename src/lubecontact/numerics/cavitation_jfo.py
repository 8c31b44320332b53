"""Mass-conserving (Jakobsson-Floberg-Olsson) cavitation of the averaged Reynolds equation.

docs/physics.md section 16. The Reynolds (Swift-Stieber) condition of reynolds.py is right for a
steady convergent-divergent gap but loses mass where a film re-forms. JFO (Elrod & Adams
1974, Elrod 1981) carries a film content theta (the fraction of the expected gap h_T the
lubricant fills) and solves, with the flux q = -k grad p + (U/2) theta h_T e_x,

    div q + s = 0,    p >= 0,    1 - theta >= 0,    p (1 - theta) = 0

(the complementarity form of Giacopini, Fowell, Dini & Strozzi, J. Tribol. 132 (2010)
041702); s is an optional storage term for a transient, below. In the full film theta = 1
and this is Eq. (1); in a cavitated zone p = 0 and the Couette flux of theta h_T is
conserved, so a film re-forms with exactly the lubricant that reaches it.

Discretisation: the finite volumes of reynolds.py (same mesh, Poiseuille coefficient and
boundary p = 0), with the Couette flux of each x face upwinded in theta,

    F_f = (U/2) dy h_T,f theta_up(f)      (h_T,f the mean of the face's nodes),

so in the full film the equations are reynolds.py's exactly. Boundary nodes supply a full
film (theta = 1: flooded inlet, at x_min for U > 0 and at x_max for U < 0).

Solver: a primal-dual active-set method on the universal variable, in the spirit of
reynolds.py: each node is pressurised (unknown p, theta = 1) or cavitated (unknown theta,
p = 0); one sparse LU solve of the (non-symmetric) system for that set, then a pressurised
node with p < 0 becomes cavitated and a cavitated node with theta > 1 pressurised, until the
set repeats. A free boundary moves a few nodes per step, so a cold start begins from the
solution on the mesh with half the nodes (recursively), and on the coarsest mesh from the
Swift-Stieber set (reynolds.solve_reynolds), which for a single convergent-divergent gap
is already the JFO set.

Transient hook: ``storage = (capacity, history)``, both (ny, nx) m^3/s, adds
capacity_i theta_i - history_i to the net outflow of node i. An implicit (backward Euler)
step of d(theta h_T)/dt is capacity = h_T dA/dt and history = theta_old h_T,old dA/dt; a
squeeze term with theta = 1 can go in ``history`` alone. ``load_sensitivity`` does not
differentiate the capacity in h.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, gmres, splu

from lubecontact.numerics.linear_algebra import REUSE_CG_STEPS, REUSE_CG_TOLERANCE
from lubecontact.numerics.reynolds import (
    COARSEST_NODES,
    RESIDUAL_TOLERANCE,
    SET_TOLERANCE,
    adjoint_sensitivity,
    couette_face_flux,
    interior_nodes,
    reynolds_system,
    solve_reynolds,
)
from lubecontact.numerics.reynolds_pattern import unknown_numbers
from lubecontact.numerics.transfer import coarser_mesh, interpolate_field


@dataclass
class JFOSolution:
    """Pressure and film content on the mesh (the fields of reynolds.ReynoldsSolution, plus theta)."""

    pressure: np.ndarray  # (ny, nx) Pa; 0 on the boundary and in the cavitated zone
    content: np.ndarray  # (ny, nx) theta, film content in [0, 1]; 1 in the full film and on the boundary
    cavitated: np.ndarray  # (ny, nx) bool; interior nodes held at p = 0 (boundary False)
    iterations: int  # active-set steps (linear solves) on this mesh, the nested cold start not counted
    residual: float  # max relative violation of the mass balance and the complementarity
    converged: bool
    factor: object | None = None  # SystemInverse of the last step, for load_sensitivity and reuse
    face_content: np.ndarray | None = None  # (ny, nx-1) theta upwind of each x face
    unknown: np.ndarray | None = None  # (ny, nx) bool, the nodes of the system

    def load_sensitivity(self, mesh, gap_slope, coefficient_slope, speed, load_weight=None) -> np.ndarray:
        """dW/dh_j, N/m (ny, nx), of the fluid load W = sum p dA at this solution's active set.

        Adjoint of the JFO system M x = r (x = p on pressurised nodes, theta on cavitated
        ones): M^T lambda = dW/dx (nodal areas on pressurised nodes, 0 on cavitated ones),
        dW/dh_j = -lambda^T dr/dh_j, with the face terms of reynolds.adjoint_sensitivity and
        the Couette faces weighted by their upwind content. ``load_weight``: dW/dp in place
        of the nodal areas (reynolds.load_sensitivity).
        """
        if self.factor is None:
            return np.zeros(mesh.shape)
        pressurised = ~self.cavitated[self.unknown]
        adjoint = np.zeros(mesh.shape)
        weight = mesh.nodal_area if load_weight is None else load_weight
        adjoint[self.unknown] = self.factor.solve(weight[self.unknown] * pressurised, trans="T")
        return adjoint_sensitivity(mesh, adjoint, self.pressure, gap_slope, coefficient_slope, speed,
                                   self.face_content)


def couette_operator(mesh, expected_gap, speed, unknown, faces=None):
    """(G, g0): the net Couette outflow of the unknown nodes is G theta_u + g0 for theta = 1
    off the unknowns (boundary and film-less nodes): G (n, n) sparse, g0 (n,) m^3/s."""
    shape = mesh.shape
    c = couette_face_flux(mesh, expected_gap, speed, faces)  # (ny, nx-1), signed
    index = np.arange(shape[0] * shape[1]).reshape(shape)
    number = unknown_numbers(unknown)
    n = int(unknown.sum())
    left, right = index[:, :-1], index[:, 1:]
    source = left if speed >= 0.0 else right  # upwind node of each face
    # face f carries c_f theta[source]; it leaves ``left`` (+) and enters ``right`` (-)
    rows = np.concatenate([left.ravel(), right.ravel()])
    cols = np.concatenate([source.ravel(), source.ravel()])
    vals = np.concatenate([c.ravel(), -c.ravel()])
    flat_number = number.ravel()
    keep = flat_number[rows] >= 0
    rows, cols, vals = flat_number[rows[keep]], cols[keep], vals[keep]
    inside = flat_number[cols] >= 0
    G = sp.csr_matrix((vals[inside], (rows[inside], flat_number[cols[inside]])), shape=(n, n))
    g0 = np.bincount(rows[~inside], weights=vals[~inside], minlength=n)
    return G, g0


def upwind_content(mesh, content, speed):
    """theta upwind of each x face, (ny, nx-1)."""
    return content[:, :-1] if speed >= 0.0 else content[:, 1:]


class SystemInverse:
    """Solves with the JFO system matrix M of one active-set step (or its transpose): by its
    own LU factors, or, given the factors of a nearby matrix (``preconditioner``: the previous
    evaluation of a coupled iteration, same set), by GMRES preconditioned with them,
    factorising M only if that does not converge within REUSE_CG_STEPS steps."""

    def __init__(self, matrix, preconditioner=None):
        self.matrix = matrix  # csc
        self.preconditioner = preconditioner
        self.lu = splu(matrix, permc_spec="COLAMD") if preconditioner is None else None

    @property
    def factors(self):
        return self.lu if self.lu is not None else self.preconditioner

    def solve(self, rhs, trans="N"):
        if self.lu is None:
            operator = self.matrix if trans == "N" else self.matrix.T
            approximate = LinearOperator(operator.shape, matvec=lambda r: self.preconditioner.solve(r, trans=trans))
            x, _ = gmres(operator, rhs, M=approximate, rtol=REUSE_CG_TOLERANCE, atol=0.0,
                         restart=REUSE_CG_STEPS, maxiter=1)
            if np.linalg.norm(operator @ x - rhs) <= 10.0 * REUSE_CG_TOLERANCE * np.linalg.norm(rhs):
                return x
            self.lu = splu(self.matrix, permc_spec="COLAMD")
        return self.lu.solve(rhs, trans=trans)


def _step(A, G, g0, capacity, history, cavitated, preconditioner=None):
    """One linear solve on the set ``cavitated``: (x, SystemInverse), x = p (pressurised) or
    theta (cavitated)."""
    free = (~cavitated).astype(float)
    couette = G + sp.diags(capacity)
    matrix = (A @ sp.diags(free) + couette @ sp.diags(cavitated.astype(float))).tocsc()
    rhs = -g0 - couette @ free + history
    inverse = SystemInverse(matrix, preconditioner)
    return inverse.solve(rhs), inverse


def _residual(A, G, g0, capacity, history, p, theta):
    """Max relative violation of the mass balance, of p >= 0, theta <= 1 and p (1 - theta) = 0."""
    couette = G @ theta + g0 + capacity * theta - history
    balance = A @ p + couette
    diagonal = A.diagonal()
    scale = max(np.abs(g0).max(initial=0.0), np.abs(G @ np.ones_like(theta)).max(initial=0.0),
                (diagonal * np.abs(p)).max(initial=0.0), np.abs(history).max(initial=0.0))
    if scale == 0.0:
        return 0.0
    flux_scale = np.abs(G).sum(axis=1).A1 + capacity
    violation = np.maximum.reduce([
        np.abs(balance),
        diagonal * np.maximum(-p, 0.0),
        flux_scale * np.maximum(theta - 1.0, 0.0),
        np.minimum(diagonal * np.abs(p), flux_scale * np.abs(1.0 - theta)),
    ])
    return float(violation.max(initial=0.0) / scale)


def _cold_guess(mesh, expected_gap, coefficient, speed, storage, max_iterations):
    """Cavitated set to start from: the JFO solution on the mesh with half the nodes
    (recursively; nested iteration, as reynolds.py), on the coarsest mesh the Swift-Stieber
    set. Storage terms (per node, m^3/s) move between meshes per unit area."""
    coarse = coarser_mesh(mesh, COARSEST_NODES)
    if coarse is None:
        return solve_reynolds(mesh, expected_gap, coefficient, speed).cavitated

    def down(field):
        return interpolate_field(field, mesh, coarse)

    coarse_storage = None
    if storage is not None:
        coarse_storage = tuple(down(np.asarray(f, float) / mesh.nodal_area) * coarse.nodal_area for f in storage)
    solution = solve_jfo(coarse, down(expected_gap), down(coefficient), speed, max_iterations=max_iterations,
                         storage=coarse_storage)
    return interpolate_field(solution.content, coarse, mesh) < 1.0


def solve_jfo(mesh, expected_gap, coefficient, speed, cavitated_guess=None, max_iterations=100,
              storage=None, reuse=None, faces=None) -> JFOSolution:
    """Pressure and film content of the JFO problem (module docstring), p = 0 on the boundary.

    ``cavitated_guess`` (ny, nx) bool warm-starts the active set (else the nested cold
    start: module docstring); ``storage`` = (capacity, history) (ny, nx) m^3/s for a transient.
    ``reuse``: the solution of a nearby problem on the same mesh (the previous evaluation of
    a coupled iteration); when the first step is on its active set, it runs by GMRES
    preconditioned with its LU factors (SystemInverse) instead of a new factorisation.
    ``faces`` (percolation.FaceFilm): the film on the faces (reynolds.reynolds_system); the
    nested cold start uses the nodal fields.
    """
    expected_gap = np.asarray(expected_gap, dtype=float)
    coefficient = np.asarray(coefficient, dtype=float)
    system = reynolds_system(mesh, expected_gap, coefficient, speed, faces)
    unknown = system.unknown
    A = system.matrix
    G, g0 = couette_operator(mesh, expected_gap, speed, unknown, faces)
    n = A.shape[0]
    capacity = np.zeros(n) if storage is None else np.asarray(storage[0], dtype=float)[unknown]
    history = np.zeros(n) if storage is None else np.asarray(storage[1], dtype=float)[unknown]
    # a node whose content enters no equation (no Couette flux, no storage) cannot cavitate
    can_cavitate = (np.abs(G).sum(axis=0).A1 + capacity) > 0.0

    if cavitated_guess is None:
        cavitated_guess = _cold_guess(mesh, expected_gap, coefficient, speed, storage, max_iterations)
    cavitated = np.asarray(cavitated_guess, dtype=bool)[unknown] & can_cavitate
    p = np.zeros(n)
    theta = np.ones(n)
    lu, repeated = None, False
    reused = None
    if isinstance(reuse, JFOSolution) and reuse.factor is not None and np.array_equal(reuse.unknown, unknown) \
            and np.array_equal(reuse.cavitated[unknown], cavitated):
        reused = reuse.factor.factors
    for iterations in range(1, max_iterations + 1):
        if n == 0:
            repeated = True
            break
        x, lu = _step(A, G, g0, capacity, history, cavitated, reused if iterations == 1 else None)
        p = np.where(cavitated, 0.0, x)
        theta = np.where(cavitated, x, 1.0)
        p_tol = SET_TOLERANCE * np.abs(p).max(initial=0.0)
        updated = np.where(cavitated, theta <= 1.0 + SET_TOLERANCE, p < -p_tol) & can_cavitate
        repeated = np.array_equal(updated, cavitated)
        if repeated:
            break
        cavitated = updated
    residual = _residual(A, G, g0, capacity, history, p, theta)

    pressure = np.zeros(mesh.shape)
    pressure[unknown] = p
    content = np.ones(mesh.shape)
    content[unknown] = theta
    cavitated_field = interior_nodes(mesh.shape, mesh.line) & ~unknown
    cavitated_field[unknown] = cavitated
    return JFOSolution(
        pressure=pressure,
        content=content,
        cavitated=cavitated_field,
        iterations=iterations if n else 0,
        residual=residual,
        converged=bool(repeated and residual <= RESIDUAL_TOLERANCE),
        factor=lu,
        face_content=upwind_content(mesh, content, speed),
        unknown=unknown,
    )
