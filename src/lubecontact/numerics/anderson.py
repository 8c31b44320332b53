"""Anderson acceleration of a fixed-point iteration x = G(x) (Walker & Ni 2011, SIAM J.
Numer. Anal. 49:1715).

The coupled solver iterates the macro deformation: delta <- influence(p(h(delta)) + p_c(h(delta)))
(paper Fig. 1 loop, Eqs. 3-18). Plain under-relaxation converges only slowly when the contact
is stiff against the surface compliance; Anderson mixing with a short memory turns the same
evaluations into a quasi-Newton (multisecant) method.
"""

from __future__ import annotations

import numpy as np


class AndersonMixer:
    """Type-II Anderson mixing with memory ``memory`` and mixing parameter ``beta``.

    ``step(x, gx)`` returns the next iterate given the current one and its image G(x).
    If a step makes the residual grow ``restart_growth``-fold over the best seen, the
    history is dropped and a plain damped step is taken (a safeguard, not a fix: the
    caller still judges convergence on the true residual).
    """

    def __init__(self, memory: int = 6, beta: float = 0.6, restart_growth: float = 10.0):
        self.memory = memory
        self.beta = beta
        self.restart_growth = restart_growth
        self._x: list[np.ndarray] = []
        self._f: list[np.ndarray] = []
        self._best = np.inf

    def reset(self) -> None:
        self._x.clear()
        self._f.clear()

    def step(self, x: np.ndarray, gx: np.ndarray) -> np.ndarray:
        x = x.ravel()
        f = gx.ravel() - x
        norm = float(np.linalg.norm(f))
        if norm > self.restart_growth * self._best:
            self.reset()
        self._best = min(self._best, norm)
        self._x.append(x.copy())
        self._f.append(f.copy())
        if len(self._x) > self.memory + 1:
            self._x.pop(0)
            self._f.pop(0)
        if len(self._x) == 1:
            return (x + self.beta * f).reshape(gx.shape)
        dx = np.diff(np.asarray(self._x), axis=0).T  # (n, m)
        df = np.diff(np.asarray(self._f), axis=0).T
        gamma, *_ = np.linalg.lstsq(df, f, rcond=None)
        new = x + self.beta * f - (dx + self.beta * df) @ gamma
        return new.reshape(gx.shape)
