"""The sparsity pattern of the finite-volume Reynolds matrix (numerics/reynolds.py), built
once per set of unknowns and kept, so that each assembly only computes the values.

The matrix A of Eq. (1) couples each unknown to itself and to its unknown neighbours
through the faces between them (T_f off the diagonal, the sum of a cell's T_f on it), and on
a 2-D mesh open to the far inlet the first column's interior cells to each other through
the exterior's dense block (numerics/modal_far_inlet.Exterior). Which entries exist depends
only on the set of unknowns and on whether the exterior is attached; the film moves the
values. A coupled solve assembles A at every evaluation (a Table 1 stop at 51 x 51 about
630 times) on a set that rarely changes, so the pattern (CSR row pointers and column
indices, and where each face and the exterior's block land in the stored values) is found
once, and an assembly is one scatter-add of the values (``ReynoldsPattern.matrix``).

The active-set method solves on the pressurised block A_FF of every step
(reynolds._solve_on). A is symmetric (each face enters both its rows with the same T_f; the
exterior's block is S diag(f) S with S the symmetric sine matrix), so A_FF's compressed
rows are also its compressed columns: ``ReynoldsPattern.block`` takes them from the stored
entries of A by one mask, without the row and column slicing of a general sparse matrix.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

# Patterns kept at once (least recently used dropped): a coupled solve alternates between
# its mesh and the nested start's coarser meshes, each with one set of unknowns. A pattern
# holds about 13 bytes per stored entry (five per unknown): 11 MB at 201 x 853 nodes.
KEPT_PATTERNS = 4


def unknown_numbers(unknown: np.ndarray) -> np.ndarray:
    """Each node's index among the unknowns (C order) of the mask ``unknown``, -1 off them."""
    number = np.full(unknown.shape, -1)
    number[unknown] = np.arange(int(unknown.sum()))
    return number


@dataclass(frozen=True)
class ReynoldsPattern:
    """Where the entries of A on one set of unknowns are stored (CSR, sorted columns)."""

    size: int  # n, the unknowns
    indptr: np.ndarray  # (n + 1,) CSR row pointers
    indices: np.ndarray  # (nnz,) CSR column of each stored entry
    rows: np.ndarray  # (nnz,) row of each stored entry
    targets: np.ndarray  # stored entry of each value of ``matrix``'s concatenated values
    x_faces: np.ndarray  # (ny, nx-1) bool: x faces between two unknowns
    y_faces: np.ndarray  # (ny-1, nx) bool: y faces between two unknowns

    def matrix(self, diagonal: np.ndarray, tx: np.ndarray, ty: np.ndarray,
               block: np.ndarray | None = None) -> sp.csr_matrix:
        """A (n, n) from the cells' diagonal on the unknowns (n,), the x and y faces'
        transmissibilities (ny, nx-1) and (ny-1, nx), and the exterior's block (m, m) when
        the pattern has one: entries landing on the same place are summed."""
        x, y = tx[self.x_faces], ty[self.y_faces]
        values = [diagonal, -x, -x, -y, -y] + ([] if block is None else [block.ravel()])
        data = np.bincount(self.targets, weights=np.concatenate(values), minlength=self.indices.size)
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.size, self.size))

    def block(self, matrix: sp.csr_matrix, free: np.ndarray) -> sp.csc_matrix:
        """A_FF (CSC) of ``matrix`` (assembled by ``matrix``) on the unknowns ``free`` (n,
        bool), its rows and columns in the order of the unknowns (as matrix[free][:, free]).
        Exact for the symmetric A of this pattern: its CSR rows are A_FF's CSC columns."""
        kept = free[self.rows] & free[self.indices]
        before = np.concatenate([[0], np.cumsum(kept)])[self.indptr]  # kept entries before each row
        indptr = np.concatenate([[0], np.diff(before)[free].cumsum()])
        entries = np.flatnonzero(kept)
        number = np.cumsum(free) - 1
        size = indptr.size - 1
        return sp.csc_matrix((matrix.data[entries], number[self.indices[entries]], indptr), shape=(size, size))


def reynolds_pattern(unknown: np.ndarray, exterior_rows: int) -> ReynoldsPattern:
    """The ReynoldsPattern of the unknowns ``unknown`` (ny, nx bool, numbered in C order),
    with the exterior's block on the first column's interior cells (rows 1 .. ny-2 of
    column 1) when ``exterior_rows`` > 0. Kept for the last KEPT_PATTERNS sets."""
    return _cached_pattern(unknown.shape, np.packbits(unknown).tobytes(), exterior_rows)


@lru_cache(maxsize=KEPT_PATTERNS)
def _cached_pattern(shape: tuple[int, int], packed: bytes, exterior_rows: int) -> ReynoldsPattern:
    unknown = np.unpackbits(np.frombuffer(packed, dtype=np.uint8), count=shape[0] * shape[1]).reshape(shape) == 1
    n = int(unknown.sum())
    number = unknown_numbers(unknown)
    rows, cols = [np.arange(n)], [np.arange(n)]
    x_faces = unknown[:, :-1] & unknown[:, 1:]
    y_faces = unknown[:-1, :] & unknown[1:, :]
    for a, c, both in ((number[:, :-1], number[:, 1:], x_faces), (number[:-1, :], number[1:, :], y_faces)):
        rows += [a[both], c[both]]
        cols += [c[both], a[both]]
    if exterior_rows:
        first = number[1:-1, 1]
        if np.any(first < 0):
            raise ValueError("the far inlet's first column has a node without flow")
        rows.append(np.repeat(first, first.size))
        cols.append(np.tile(first, first.size))
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    keys = rows * n + cols
    stored = np.unique(keys)  # sorted by row, then column: the canonical CSR order
    stored_rows = (stored // n).astype(np.int32)
    indptr = np.concatenate([[0], np.cumsum(np.bincount(stored_rows, minlength=n))]).astype(np.int32)
    return ReynoldsPattern(size=n, indptr=indptr, indices=(stored % n).astype(np.int32), rows=stored_rows,
                           targets=np.searchsorted(stored, keys).astype(np.int32), x_faces=x_faces, y_faces=y_faces)
