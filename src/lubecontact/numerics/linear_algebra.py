"""Sparse linear algebra of the Reynolds solves: SuperLU factors of a pressurised block,
their reuse on a nearby block (capacitance corrections, Hager 1989) as the preconditioner
of conjugate gradients, and ``BlockInverse``, which picks between them.

Consecutive Reynolds solves differ by a small change of the film and the active-set steps
by a few nodes of the free boundary, so old factors are an almost exact inverse and CG
needs a few back-substitutions instead of a factorisation.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import LinAlgError, cho_factor, cho_solve
from scipy.sparse.linalg import splu

# Reuse of LU factors (``reuse``): conjugate gradients on A_FF preconditioned by the factors
# of a nearby matrix stop at this relative residual (2-norm), and give up (a new
# factorisation is made) after REUSE_CG_STEPS steps, or after REUSE_CG_CHECK steps that have
# not cut the residual by REUSE_CG_CHECK_FACTOR. Factors of a pressurised set that differs
# from this one by c nodes serve through c back-substitutions (ExtendedFactors), so they
# are used up to REUSE_MAX_CHANGES nodes away: a factorisation costs 15-40
# back-substitutions (2.6k-160k unknowns; before the nested start was smoothed
# (projected_smoothing), 12 left Table 1 at 201^2 with 2-4 factorisations on the finest
# mesh instead of 4-5 and 8 or 20 were no faster; after it, 30 or 80 were slower at
# 201 x 853, where the corrections of 14-29 nodes are rebuilt at every step; counts of
# bench/run.py).
REUSE_CG_TOLERANCE = 1e-12


REUSE_CG_STEPS = 12


REUSE_CG_CHECK = 3


REUSE_CG_CHECK_FACTOR = 1e-3


REUSE_MAX_CHANGES = 12


def factorize(block):
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


def preconditioned_cg(block, rhs, preconditioner):
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
        self.lu = factorize(block) if self.preconditioner is None else None

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
            x = preconditioned_cg(self.block, rhs, self.preconditioner)
            if x is not None:
                return x
            self.lu = factorize(self.block)
        return self.lu.solve(rhs)
