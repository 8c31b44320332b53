"""Projected Gauss-Seidel smoothing of a pressure guess: the cavitated set a nested
(coarse-to-fine) start hands to the active-set method (reynolds.py).

The discrete Reynolds problem with the Swift-Stieber condition is the linear
complementarity problem p >= 0, w = A p - b >= 0, p w = 0 with A a symmetric M-matrix
(reynolds.py). A pressure interpolated from a coarser mesh has the right smooth part, but
its free boundary is off by about a coarse cell along its whole length (147 nodes on Table 1
at 201 x 853 nodes, 10 m/s), and each active-set step from that set costs an LU
factorisation. Interpolation errors are what relaxation removes fastest, so as in the
nested (full multigrid) iteration for free-boundary problems of Brandt & Cryer (1983, SIAM
J. Sci. Stat. Comput. 4:655) a few projected Gauss-Seidel sweeps on the fine mesh,

    p_i <- max(0, p_i + (b - A p)_i / A_ii),

move the guessed free boundary to within a node or two of the fine one before the first
factorisation. Projected Gauss-Seidel converges to the solution of the problem for an
M-matrix (Cryer 1971, SIAM J. Control 9:385); here it only makes the guess, whose set the
active-set method then corrects exactly, so the answer does not depend on the sweeps.

The 5-point finite-volume stencil couples a node only to nodes of the other colour of a
red-black (checkerboard) colouring, so each half-sweep updates one colour at once with a
sparse product (vectorised, no loop over nodes).
"""

from __future__ import annotations

import numpy as np

# Sweeps of the smoothing per node along the side of a square mesh of as many unknowns:
# sqrt(n) / 10 sweeps (5 at 51^2, 20 at 201^2, 40 at 401^2, 83 on 401 x 1705). A sweep costs
# O(n) and a factorisation of the 2D block about O(n^1.5), so the smoothing stays a fixed
# share of one factorisation (35 sweeps on 116k unknowns: about 0.1 s, a factorisation
# 0.35 s), while the distance the free boundary must move, in nodes, grows with the mesh.
# Measured on Table 1 (4 speeds, 51^2 to 401^2, counts of bench/run.py):
# a fixed 10 sweeps left 401^2 with a second factorisation of the finest mesh at 0.1-10 m/s,
# 0.1 per side node with one; 0.2 was no better at 401^2.
GUESS_SWEEPS_PER_SIDE_NODE = 0.1


def guess_sweeps(unknowns: int) -> int:
    """Sweeps for a system of ``unknowns`` nodes (GUESS_SWEEPS_PER_SIDE_NODE), at least 1."""
    return max(1, int(np.ceil(GUESS_SWEEPS_PER_SIDE_NODE * np.sqrt(unknowns))))


def red_black_colour(unknown: np.ndarray) -> np.ndarray:
    """Colour (True = red: even i + j) of each unknown node of the (ny, nx) mask ``unknown``,
    in the C order of the unknowns."""
    rows, columns = np.nonzero(unknown)
    return (rows + columns) % 2 == 0


def projected_gauss_seidel(matrix, rhs, colour, pressure, sweeps):
    """``sweeps`` red-black projected Gauss-Seidel sweeps on p >= 0, A p - b >= 0,
    p (A p - b) = 0 from ``pressure`` (clipped at 0), with A (csr, 5-point stencil, positive
    diagonal) = ``matrix``, b = ``rhs`` and ``colour`` from red_black_colour. Returns p."""
    p = np.maximum(np.asarray(pressure, dtype=float), 0.0)
    diagonal = matrix.diagonal()
    halves = []
    for rows in (colour, ~colour):
        halves.append((rows, matrix[rows], rhs[rows], diagonal[rows]))
    for _ in range(sweeps):
        for rows, block, b, d in halves:
            p[rows] = np.maximum(0.0, p[rows] + (b - block @ p) / d)
    return p


def smoothed_cavitated_set(system, pressure_guess) -> np.ndarray:
    """The cavitated set (mask over the unknowns of ``system``, a reynolds.ReynoldsSystem)
    of ``pressure_guess`` (ny, nx; e.g. a coarse solution interpolated to this mesh) after
    guess_sweeps projected Gauss-Seidel sweeps on the system."""
    start = np.asarray(pressure_guess, dtype=float)[system.unknown]
    colour = red_black_colour(system.unknown)
    p = projected_gauss_seidel(system.matrix, system.rhs, colour, start, guess_sweeps(start.size))
    return p <= 0.0
