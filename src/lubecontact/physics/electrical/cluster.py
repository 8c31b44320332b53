"""Greenwood's (1966) cluster (macro) constriction resistance (docs/physics.md section 12).

Greenwood, *Constriction resistance and the real area of contact*, Br. J. Appl. Phys. 17
(1966) 1621: n spots of radii a_i at centre distances s_ij between two half-spaces of one
resistivity rho have

    R = rho/(2 sum a_i) + (rho/pi) sum_{i != j} a_i a_j / (s_ij (sum a_i)^2).

The first term is the spots in parallel (Holm); the second is the constriction of the
cluster as a whole. With a_i = rho g_i dA_i / 2 (g the spot conductance per nominal area,
Eq. 15, before any alleviation) the pair sum becomes the continuum

    R_macro = (rho*/pi) iint g(r) g(r') / |r - r'| dA dA' / G^2,   G = int g dA,

with rho* = (rho1 + rho2)/2 for two bodies (each half-space adds its own rho/2 share).
R_macro depends on the shape of g only (it is homogeneous of degree 0), so g is scaled by
its largest value first: the Gaussian tails of g (down to 1e-300 S/m^2) stay representable.

The double integral is taken with g constant on each node's dx x dy cell (dx x L in line
mode, where g does not vary along the cylinder), exactly for that piecewise-constant g:
the pair integral of 1/r over two cells is a fourth difference of
H(X, Y) = X^2 Y/2 asinh(Y/|X|) + X Y^2/2 asinh(X/|Y|) - (X^2 + Y^2)^(3/2)/6
(d^4 H/dX^2 dY^2 = 1/r), whose self-cell value is the rectangle's closed form of
docs/physics.md section 12. The sum over cell pairs is the DC-FFT convolution of
:class:`lubecontact.physics.deformation.ElasticDeformation` with this kernel in place of Love's:
in 2D and in line mode alike, since the current spreads in three dimensions even where
the deformation is taken in plane strain.
"""

from __future__ import annotations

import math

import numpy as np

from lubecontact.physics.deformation import ElasticDeformation, x_asinh

# weights of the second difference f(o - D) - 2 f(o) + f(o + D) in each direction
_SECOND_DIFFERENCE = ((-1.0, 1.0), (0.0, -2.0), (1.0, 1.0))


def pair_primitive(x, y):
    """H(X, Y) with d^4 H / dX^2 dY^2 = 1/sqrt(X^2 + Y^2), even in X and in Y, 0 at the origin."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    return 0.5 * x * y * (x_asinh(x, y) + x_asinh(y, x)) - np.hypot(x, y) ** 3 / 6.0


def cell_pair_integral(x_offset, y_offset, width, height):
    """iint over two width x height rectangles whose centres are (x_offset, y_offset) apart
    of 1/|r - r'| dA dA' (m^3): the fourth difference of ``pair_primitive``."""
    total = 0.0
    for i, ci in _SECOND_DIFFERENCE:
        for j, cj in _SECOND_DIFFERENCE:
            total = total + ci * cj * pair_primitive(x_offset + i * width, y_offset + j * height)
    return total


class ClusterOperator(ElasticDeformation):
    """``operator(g)`` = the cell mean of int g(r')/|r - r'| dA' at each node (m times g's unit).

    The DC-FFT convolution of the elastic deformation with the cell-pair kernel of 1/r
    (2D mode: dx x dy cells; line mode: dx x L strips) instead of Love's or the plane-strain one.
    """

    def __init__(self, mesh):
        super().__init__(mesh, effective_modulus=1.0)  # the modulus is not used by this kernel

    def influence(self, x_offset, y_offset):
        m = self.mesh
        return cell_pair_integral(x_offset, y_offset, m.dx, m.dy) / (m.dx * m.dy)


def macro_constriction_resistance(operator: ClusterOperator, log_conductance, resistivity: float) -> float:
    """R_macro (ohm) of the conductance per nominal area g = exp(log_conductance) (S/m^2, on
    ``operator.mesh``) between half-spaces of mean resistivity ``resistivity`` = rho* (ohm m).
    +inf where no node conducts (no current, no cluster)."""
    log_g = np.asarray(log_conductance, dtype=float)
    peak = float(log_g.max(initial=-np.inf))
    if peak == -np.inf:
        return math.inf
    if peak == np.inf:  # a node of infinite conductance: the cluster is that node
        log_g = np.where(np.isinf(log_g) & (log_g > 0), 0.0, -np.inf)
        peak = 0.0
    shape = np.exp(log_g - peak)  # in (0, 1], largest 1
    area = operator.mesh.nodal_area
    total = float(np.sum(shape * area))
    pair_sum = float(np.sum(shape * area * operator(shape)))
    return resistivity / math.pi * pair_sum / total**2
