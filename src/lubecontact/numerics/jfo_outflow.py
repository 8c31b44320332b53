"""Mass-conserving (JFO) cavitation in one unknown per node, for the one Newton
(docs/physics.md section 20, "JFO in the one Newton").

The JFO problem of cavitation_jfo.py holds two unknowns at every node, the pressure p and the
film content theta, tied by a complementarity: p >= 0, 1 - theta >= 0, p (1 - theta) = 0.
Written in one universal variable u, after Elrod & Adams (1974) and Elrod (1981),

    p = max(u, 0),        theta = 1 + min(u, 0) / P,

every u gives a complementary pair, and the mass balance of each cell (cavitation_jfo.py's
finite volumes, the Couette flux of each x face upwinded in theta),

    w(u) = A p + G theta + g0 = 0,

is one equation per unknown, piecewise linear in u, so semismooth: its generalised Jacobian
is dw/du = A S + G (I - S) / P with S = diag(u > 0) (at u = 0 the cavitated branch). In the
full film it is the Reynolds outflow A p - b of reynolds.py exactly. P (Pa) is a unit, not a
parameter: every P > 0 has the same solutions (p, theta), only u's scale in a cavitated zone
changes; the one Newton takes the nominal pressure, the load over the mesh's area. A node
whose content enters no equation (no Couette flux through its faces: cavitation_jfo.py's
can_cavitate) keeps p = u of either sign, as the active-set solver keeps it pressurised.

The residual the one Newton drives to zero is w / A_ii, a pressure, as for full Sommerfeld:
the complementarity is in the variable, not in the residual, so there is no
Fischer-Burmeister function to smooth.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from lubecontact.numerics.cavitation_jfo import couette_operator
from lubecontact.numerics.reynolds_jacobian import LinearOutflow


@dataclass(frozen=True)
class UniversalSplit:
    """The pair (p, theta) of the universal variable u at the Reynolds unknowns (module
    docstring): pressure (Pa), content (1), and which unknowns are on the pressure branch
    (u > 0, or unable to cavitate), where dp/du = 1 and dtheta/du = 0 (elsewhere 0 and 1/P)."""

    pressure: np.ndarray
    content: np.ndarray
    pressurised: np.ndarray  # bool


def can_cavitate(couette: sp.csr_matrix) -> np.ndarray:
    """Per unknown, whether its content enters an equation: a Couette flux through one of its
    faces (a column of G with an entry)."""
    return np.abs(couette).sum(axis=0).A1 > 0.0


def universal_split(variable: np.ndarray, unit: float, cavitating: np.ndarray) -> UniversalSplit:
    """(p, theta) of the universal variable ``variable`` (Pa, per unknown), ``unit`` P (Pa);
    ``cavitating``: the unknowns that may cavitate (can_cavitate); at u = 0 the cavitated branch."""
    pressurised = (variable > 0.0) | ~cavitating
    return UniversalSplit(np.where(pressurised, variable, 0.0), np.where(pressurised, 1.0, 1.0 + variable / unit),
                          pressurised)


def content_field(mesh, unknown: np.ndarray, split: UniversalSplit) -> np.ndarray:
    """theta on the mesh (ny, nx): the unknowns' content, 1 elsewhere (a boundary supplies a full film)."""
    content = np.ones(mesh.shape)
    content[unknown] = split.content
    return content


def mass_conserving_outflow(mesh, system, expected_gap, speed, faces, variable: np.ndarray, unit: float,
                            film_slopes, storage=None) -> tuple[LinearOutflow, UniversalSplit]:
    """The JFO outflow w(u) of the Reynolds unknowns (m^3/s) as a reynolds_jacobian.LinearOutflow
    whose matrix is dw/du (module docstring), and the split (p, theta) of ``variable`` (u, Pa,
    per unknown). ``system``: reynolds.reynolds_system of this film (A and its unknowns);
    ``film_slopes(content)``: (dw/dh, dA_ii/dh) at the film content ``content`` (ny, nx), the
    Couette faces weighted by their upwind content and a step's squeezed cells by their own
    (monolithic_newton.linearise). ``storage`` = (capacity, history) per unknown, m^3/s: a
    time step's cells hold theta times their content c, and add capacity theta - history to
    their outflow, as cavitation_jfo.py's hook (BDF: capacity = c0 dA c, history = -dA (c1
    (theta c)^n + c2 (theta c)^(n-1))); capacity is then part of dw/du on the cavitated branch."""
    couette, inflow = couette_operator(mesh, expected_gap, speed, system.unknown, faces)
    capacity = np.zeros(variable.shape) if storage is None else storage[0]
    stored = 0.0 if storage is None else storage[1]
    split = universal_split(variable, unit, can_cavitate(couette) | (capacity > 0.0))
    matrix = system.matrix
    outflow = matrix @ split.pressure + couette @ split.content + inflow + capacity * split.content - stored
    content_slope = ~split.pressurised / unit  # dtheta/du
    slope = matrix @ sp.diags(split.pressurised * 1.0) + couette @ sp.diags(content_slope) \
        + sp.diags(capacity * content_slope)
    content = content_field(mesh, system.unknown, split)
    return LinearOutflow(slope.tocsr(), matrix.diagonal(), outflow, lambda: film_slopes(content)), split
