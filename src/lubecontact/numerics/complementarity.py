"""The Fischer-Burmeister function: a complementarity condition as one semismooth equation
(docs/physics.md section 20).

    phi(a, b) = a + b - sqrt(a^2 + b^2) = 0   <=>   a >= 0, b >= 0, a b = 0

(Fischer 1992, Optimization 24:269). phi is smooth except at a = b = 0, where it is
semismooth (strongly: its generalised Jacobian is Lipschitz), so Newton's method on it
converges quadratically near a solution (Qi & Sun 1993, Math. Program. 58:353). FBNS
(Woloszynski, Podsiadlo & Stachowiak, Tribol. Lett. 58, 2015) solves the cavitation
condition of the Reynolds equation, p >= 0 and flow residual >= 0 with p times residual
= 0, this way.
"""

from __future__ import annotations

import numpy as np

# At a = b = 0 any (1 - cos t, 1 - sin t) is in the generalised Jacobian; the direction
# t = pi/4 (equal weights) is the usual choice (De Luca, Facchinei & Kanzow 1996).
DEGENERATE_SLOPE = 1.0 - np.sqrt(0.5)


def fischer_burmeister(a: np.ndarray, b: np.ndarray, smoothing: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(phi, dphi/da, dphi/db) elementwise; both slopes lie in [0, 2] and do not vanish
    together, so a row da * I + db * A of an M-matrix A stays nonsingular. With
    ``smoothing`` mu > 0, phi = a + b - sqrt(a^2 + b^2 + 2 mu^2) (Kanzow 1996, SIAM J. Matrix
    Anal. Appl. 17:851): smooth everywhere, zero where a, b > 0 and a b = mu^2."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    root = np.sqrt(a * a + b * b + 2.0 * smoothing * smoothing)
    degenerate = root == 0.0
    safe = np.where(degenerate, 1.0, root)
    phi = a + b - root
    da = np.where(degenerate, DEGENERATE_SLOPE, 1.0 - a / safe)
    db = np.where(degenerate, DEGENERATE_SLOPE, 1.0 - b / safe)
    return phi, da, db
