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

# Sweeps of the smoothing. On Table 1 (F = 5 N, 4 speeds) at 201^2 the first fine-mesh
# evaluation then factorises once or twice instead of three times; 5, 10, 20 and 50 sweeps
# were compared (bench/RESULTS.md, "projected smoothing"): fewer leave the walk, more only
# cost time. A free boundary moves about a node per sweep.
GUESS_SWEEPS = 10


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
    GUESS_SWEEPS projected Gauss-Seidel sweeps on the system."""
    start = np.asarray(pressure_guess, dtype=float)[system.unknown]
    colour = red_black_colour(system.unknown)
    p = projected_gauss_seidel(system.matrix.tocsr(), system.rhs, colour, start, GUESS_SWEEPS)
    return p <= 0.0
