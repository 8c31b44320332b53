"""Control-volume means of a nodal law over a piecewise-linear film (docs/physics.md section 14).

A finite-volume cell around node i holds the fluid volume of the film content g(h) over the
cell, not g(h_i) times its area. Where g has a kink (the film content frozen below h = 0,
model/fluid_film.py) the two differ at first order in the node spacing, and in time a node's
content switches off at once when its film crosses the kink, a jump the error control cannot
step across. Here the film is linear between neighbouring nodes, and the cell's content is

    c_i = mean of g over the cell   (line: along x; 2-D: the mean of the x and y means),

each half cell from h_i to the face's film (h_i + h_j)/2: for any law by Gauss-Legendre
quadrature split at the kink (GaussHalfCells), for the expected gap in closed form
(numerics/expected_gap_cells.py), so c_i is smooth in the films wherever a half cell's film is
not flat. Its slopes dc_i/dh_i and dc_i/dh_j (neighbours) give the squeeze term's Jacobian
exactly:

    d/dh_i mean = int_0^1 g'(h(u)) (1 - u/2) du,  d/dh_j mean = int_0^1 g'(h(u)) u/2 du,

h(u) = h_i + u (h_j - h_i)/2 (the kink's motion adds g's jump there, zero: g is continuous).
Boundary nodes have one half cell, as their trapezoidal area (numerics/mesh.py).

Tried and not kept: the cell's film as the line through the node with the central
difference's slope, which keeps a linear g lumped (the nodal value) but leaves the kink
wherever that slope vanishes, at the film's minimum: the tight Table 1 stops failed again
(bench/EXPERIMENTS.md, twelfth session).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

GAUSS_POINTS = 4  # per piece: exact for polynomials of degree 7; g is smooth on each side of the kink
_XI, _WEIGHTS = np.polynomial.legendre.leggauss(GAUSS_POINTS)


@dataclass(frozen=True)
class ControlVolumeMean:
    """The cell means c (ny, nx) and their slopes: ``own`` dc_i/dh_i, ``west``/``east``
    dc_i/dh of the x neighbours, ``south``/``north`` of the y neighbours (zeros where absent)."""

    value: np.ndarray
    own: np.ndarray
    west: np.ndarray
    east: np.ndarray
    south: np.ndarray
    north: np.ndarray

    @classmethod
    def lumped(cls, value: np.ndarray, slope: np.ndarray) -> "ControlVolumeMean":
        """The nodal value standing for its cell (a law without a kink: smooth surfaces)."""
        zero = np.zeros_like(value)
        return cls(value, slope, zero, zero, zero, zero)

    def apply(self, v: np.ndarray) -> np.ndarray:
        """dc for the film change v (ny, nx)."""
        out = self.own * v
        out[:, 1:] += self.west[:, 1:] * v[:, :-1]
        out[:, :-1] += self.east[:, :-1] * v[:, 1:]
        out[1:, :] += self.south[1:, :] * v[:-1, :]
        out[:-1, :] += self.north[:-1, :] * v[1:, :]
        return out

    def frozen(self) -> np.ndarray:
        """The cells whose mean moves with none of the films it depends on (every slope 0):
        the whole cell below the law's kink, its content frozen (a sealed pocket)."""
        return (self.own == 0) & (self.west == 0) & (self.east == 0) & (self.south == 0) & (self.north == 0)

    def transpose(self, w: np.ndarray) -> np.ndarray:
        """(dc/dh)^T w for w (ny, nx): the adjoint of ``apply``."""
        out = self.own * w
        out[:, :-1] += self.west[:, 1:] * w[:, 1:]
        out[:, 1:] += self.east[:, :-1] * w[:, :-1]
        out[:-1, :] += self.south[1:, :] * w[1:, :]
        out[1:, :] += self.north[:-1, :] * w[:-1, :]
        return out

    def matrix(self) -> sp.csr_matrix:
        """dc/dh as a sparse (n, n) matrix over the flattened nodes (row-major, ny x nx)."""
        ny, nx = self.value.shape
        n = nx * ny
        diagonals = [self.own.ravel(), self.west.ravel()[1:], self.east.ravel()[:-1]]
        offsets = [0, -1, 1]
        if ny > 1:
            diagonals += [self.south.ravel()[nx:], self.north.ravel()[:-nx]]
            offsets += [-nx, nx]
        # a west/east entry across the end of a row is zero (the slopes are zero there)
        return sp.diags(diagonals, offsets, shape=(n, n), format="csr")


class GaussHalfCells:
    """Half-cell means of a law h -> (g, dg/dh), smooth on each side of ``kink``, by
    Gauss-Legendre quadrature split at the kink (any law; a law with a closed form may have
    its own, numerics/expected_gap_cells.py)."""

    def __init__(self, law, kink: float):
        self.law = law
        self.kink = kink

    def __call__(self, start: np.ndarray, neighbour: np.ndarray):
        """(mean, d mean/d start, d mean/d neighbour) of the law over the film from ``start``
        to the face's film (start + neighbour)/2, linear in between, split at the kink: the
        piece beyond the kink is evaluated only where the half cell crosses it (elsewhere it
        has no length)."""
        kink = self.kink
        face = 0.5 * (start + neighbour)
        crossing = (start - kink) * (face - kink) < 0.0
        split = np.where(crossing, (kink - start) / np.where(crossing, face - start, 1.0), 1.0)
        mean = np.zeros_like(start)
        d_start = np.zeros_like(start)
        d_neighbour = np.zeros_like(start)
        _add_piece((mean, d_start, d_neighbour), start, face, 0.0, split, self.law, Ellipsis)
        if crossing.any():
            _add_piece((mean, d_start, d_neighbour), start, face, split, 1.0, self.law, crossing)
        return mean, d_start, d_neighbour


def _add_piece(sums, start, face, low, high, law, where):
    """Add to ``sums`` (mean, d/d start, d/d neighbour) at ``where`` (a mask, or Ellipsis for
    every node) the Gauss-Legendre quadrature of the piece u in [low, high] (scalars or arrays
    like ``start``) of the half cell h(u) = start + u (face - start)."""
    start, face = start[where], face[where]
    low = low[where] if np.ndim(low) else low
    high = high[where] if np.ndim(high) else high
    half = 0.5 * (high - low)
    for xi, weight in zip(_XI, _WEIGHTS):
        u = low + half * (1.0 + xi)
        g, slope = law(start + u * (face - start))
        w = weight * half
        for total, term in zip(sums, (w * g, w * slope * (1.0 - 0.5 * u), w * slope * 0.5 * u)):
            total[where] += term


def _axis_weights(n: int):
    """The weights of a node's previous and next half cell along an axis of n nodes (each
    half a cell; boundary nodes: their one half cell)."""
    w_prev, w_next = np.full(n, 0.5), np.full(n, 0.5)
    w_prev[0], w_next[0] = 0.0, 1.0
    w_prev[-1], w_next[-1] = 1.0, 0.0
    return w_prev, w_next


def control_volume_mean(film: np.ndarray, half_cells) -> ControlVolumeMean:
    """The cell means of a law over the film (ny, nx), linear between nodes, from its
    ``half_cells`` (start, neighbour) -> (mean, d/d start, d/d neighbour) (GaussHalfCells, or
    a closed form); one row (ny = 1) is a line: x only.

    Every half cell (previous and next, along x and y) goes to ``half_cells`` in one flat
    array: a call's cost on these meshes is numpy's per-operation overhead, not its length."""
    axes = [film] if film.shape[0] == 1 else [film, film.T]  # each with its axis last
    pairs = []
    for along in axes:
        pairs.append((along, np.concatenate([along[..., :1], along[..., :-1]], axis=-1)))  # previous node
        pairs.append((along, np.concatenate([along[..., 1:], along[..., -1:]], axis=-1)))  # next node
    flat = half_cells(np.concatenate([start.ravel() for start, _ in pairs]),
                      np.concatenate([neighbour.ravel() for _, neighbour in pairs]))
    halves = [[part.reshape(pairs[k][0].shape) for k, part in enumerate(np.split(result, len(pairs)))]
              for result in flat]  # halves[quantity][pair]
    means = []
    for axis, along in enumerate(axes):
        w_prev, w_next = _axis_weights(along.shape[-1])
        (m_prev, m_next), (own_prev, own_next), (d_prev, d_next) = (q[2 * axis: 2 * axis + 2] for q in halves)
        means.append((w_prev * m_prev + w_next * m_next, w_prev * own_prev + w_next * own_next,
                      w_prev * d_prev, w_next * d_next))
    value, own, west, east = means[0]
    if len(axes) == 1:
        zero = np.zeros_like(film)
        return ControlVolumeMean(value, own, west, east, zero, zero)
    y_value, y_own, south, north = (a.T for a in means[1])
    return ControlVolumeMean(0.5 * (value + y_value), 0.5 * (own + y_own), 0.5 * west, 0.5 * east,
                             0.5 * south, 0.5 * north)
