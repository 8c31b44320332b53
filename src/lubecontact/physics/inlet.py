"""How long the inlet must be for the film it feeds (docs/physics.md section 17).

Martin's rigid cylinder (docs/physics.md section 4) on a domain whose inlet ends at
X_in = x_min / sqrt(2 R h_0) (p = 0 there, Reynolds exit condition) carries less load at a
given film than the fully flooded one; at a given load its film is thinner by the factor

    f(X_in) = W(X_in) / W(infinity)      (load proportional to 1/h_0 at fixed speed),

computed here with the 1D Reynolds integral of :func:`lubecontact.model.auto_effects.reynolds_line_load`
on h = h_0 (1 + X^2). Measured: f = 0.78 at X = 3, 0.91 at 5, 0.976 at 10, 0.994 at 20,
0.999 at 50; 1 - f ~ 2.5/X^2. The film a speed carries thus sets the inlet the domain needs.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from lubecontact.physics.film_estimates import reynolds_line_load

_FAR = 2000.0  # X of the inlet standing for a fully flooded one (1 - f ~ 6e-7)


@lru_cache(maxsize=4096)
def _load(inlet: float) -> float:
    near = np.linspace(-min(inlet, 4.0), 4.0, 4001)
    far = -np.geomspace(inlet, 4.0, 2001)[:-1] if inlet > 4.0 else np.empty(0)
    x = np.concatenate([far, near])
    h = 1.0 + x**2
    return reynolds_line_load(x, h, h**3, 2.0)


def inlet_film_fraction(inlet: float) -> float:
    """f(X_in): the rigid film with the inlet at X_in = |x_min|/sqrt(2 R h_0) over the fully
    flooded one (0 < f <= 1); X_in is rounded to 3 significant digits (cached)."""
    if not inlet > 0.0:
        return 0.0
    return min(1.0, _load(float(f"{min(inlet, _FAR):.3g}")) / _load(_FAR))


def required_inlet(deficit: float) -> float:
    """The X_in at which 1 - f(X_in) = ``deficit`` (0 < deficit < 0.2)."""
    from scipy.optimize import brentq  # here: scipy.optimize costs ~0.1 s to import

    return brentq(lambda x: 1.0 - _load(x) / _load(_FAR) - deficit, 2.0, math.sqrt(10.0 / deficit), xtol=1e-3)
