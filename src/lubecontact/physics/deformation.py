"""Macro-scale elastic deformation delta of Eq. (3) by influence coefficients.

Paper, section 2.2: the fluid plus contact pressure on the mesh is fed through an influence
coefficient matrix (refs. 35-38) to give the elastic deflection delta in h = h_o + z + delta
(Eq. 3). Here delta is the total normal displacement of both bodies, combined through
Johnson's effective modulus E* (Eq. 19), positive where the surfaces are pushed apart, so a
positive pressure opens the film.

Each node i carries the load p_i * nodal_area_i (trapezoidal weights, so a boundary node
carries half, a corner node a quarter) spread uniformly over a dx x dy cell centred on it:

- 2D mode (ny > 1): Love's (1929) displacement of a half-space under uniform pressure on a
  rectangle, ``love_rectangle``. It needs no datum.
- line mode (ny == 1): plane strain, per unit length p_i * w_i (w_i the trapezoidal weight
  in x) on a strip of width dx, ``plane_strain_strip``. A 2D displacement is defined only up
  to an additive constant (Johnson 1985, eq. 2.25); the datum used here measures
  distances in units of the cylinder length L, ln(|d|/L). With it a line-mode Hertz contact
  gets the mid-length displacement (2w'/(pi E*))(ln(2L/b) + 1/2) of a Hertzian strip of
  length L >> b on a half-space, the same as the 2D mode gives at y = 0. The solver's
  rigid-body approach z absorbs any other choice.

The sum u_i = sum_j K(x_i - x_j, y_i - y_j) q_j is a linear (aperiodic) convolution, done
by DC-FFT (Liu, Wang & Liu 2000, Wear 243:101): zero-pad the load to 2ny x 2nx, put the
kernel in wrap-around order [K_0 .. K_{n-1}, 0, K_{-(n-1)} .. K_{-1}] along each axis,
multiply the transforms and keep the first ny x nx outputs. The padded length is rounded up
to the next FFT-friendly size (more zeros in the middle slot), which changes nothing but
the speed: 2 x 201 = 402 = 2 x 3 x 67 is twice as slow as 405. This equals the direct sum
to round-off at O(N log N) per call; the kernel transform is built once.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy import fft
from scipy.special import xlogy


def x_asinh(a, b):
    """a * asinh(b/|a|), taken as 0 where a == 0 (its limit a ln(2|b|/|a|) -> 0)."""
    abs_a = np.abs(a)
    ratio = np.divide(b, abs_a, out=np.zeros(np.broadcast(a, b).shape), where=abs_a > 0)
    return a * np.arcsinh(ratio)


def love_rectangle(x, y, half_x, half_y, effective_modulus):
    """Total normal displacement (m) of both bodies at (x, y) under a unit pressure (1 Pa)
    on the rectangle |x| <= half_x, |y| <= half_y (Love 1929; Johnson 1985, eq. 3.25).

    u = (1/(pi E*)) [f(x+a, y+b) - f(x+a, y-b) - f(x-a, y+b) + f(x-a, y-b)] with
    f(X, Y) = X ln(Y + r) + Y ln(X + r), r = sqrt(X^2 + Y^2). Since
    ln(Y + r) = ln|X| + asinh(Y/|X|), the X ln|X| and Y ln|Y| parts cancel between corners
    and f is replaced by X asinh(Y/|X|) + Y asinh(X/|Y|): odd in X and Y, free of the
    cancellation in Y + r for Y < 0, and 0 (the 0 ln 0 limit) where X or Y is 0, so corners
    and edges give finite values, never NaN.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)

    def corner(cx, cy):
        return x_asinh(cx, cy) + x_asinh(cy, cx)

    total = (
        corner(x + half_x, y + half_y)
        - corner(x + half_x, y - half_y)
        - corner(x - half_x, y + half_y)
        + corner(x - half_x, y - half_y)
    )
    return total / (np.pi * effective_modulus)


def plane_strain_strip(d, width, effective_modulus, datum_length):
    """Total normal displacement (m) of both bodies in plane strain at offset d from the
    centre of a strip of the given width under a unit pressure (1 Pa) (Johnson 1985, eq. 2.25):

    K(d) = -(2/(pi E*)) [(d + D/2) ln|(d + D/2)/l| - (d - D/2) ln|(d - D/2)/l| - D],

    l = datum_length fixes the arbitrary additive constant (K is changed by
    (2 D/(pi E*)) ln(l'/l) if l is replaced by l'). 0 ln 0 is taken as 0 at the strip edges.
    """
    d = np.asarray(d, dtype=float)
    right, left = d + 0.5 * width, d - 0.5 * width
    bracket = xlogy(right, np.abs(right) / datum_length) - xlogy(left, np.abs(left) / datum_length) - width
    return -2.0 / (np.pi * effective_modulus) * bracket


def _wrap_around(n: int, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Node offsets of a DC-FFT kernel of length size >= 2n in wrap-around order,
    0 .. n-1, (zero slots), -(n-1) .. -1, and the mask of the slots that are not zero."""
    m = np.arange(size)
    return np.where(m < n, m, m - size), (m < n) | (m > size - n)


class ElasticDeformation:
    """delta of Eq. (3) on a mesh: ``deformation(pressure) -> displacement``, both (ny, nx).

    The kernel transform is built once here; each call is two real FFTs of the padded grid.
    """

    def __init__(self, mesh, effective_modulus: float):
        self.mesh = mesh
        self.effective_modulus = float(effective_modulus)
        # pressure on each node's dx x dy cell that carries its trapezoidal load p * nodal_area
        self._cell_weight = mesh.nodal_area / (mesh.dx * mesh.dy)
        # padded lengths >= 2n with small prime factors only (2n itself can be 2 x a prime)
        self._padded = (
            1 if mesh.line else fft.next_fast_len(2 * mesh.ny),
            fft.next_fast_len(2 * mesh.nx, real=True),
        )
        x_offset, x_used = _wrap_around(mesh.nx, self._padded[1])
        y_offset, y_used = (np.zeros(1), np.ones(1, bool)) if mesh.line else _wrap_around(mesh.ny, self._padded[0])
        kernel = self.influence((x_offset * mesh.dx)[None, :], (y_offset * mesh.dy)[:, None])
        self._near_fields = {}  # near_field's sparse matrices, by radius
        self._kernel_hat = fft.rfft2(np.where(y_used[:, None] & x_used[None, :], kernel, 0.0))

    def influence(self, x_offset, y_offset):
        """Displacement (m) at offset (x_offset, y_offset) from a node whose cell carries 1 Pa."""
        m = self.mesh
        if m.line:
            return plane_strain_strip(x_offset, m.dx, self.effective_modulus, m.length)
        return love_rectangle(x_offset, y_offset, 0.5 * m.dx, 0.5 * m.dy, self.effective_modulus)

    def _checked(self, pressure) -> np.ndarray:
        pressure = np.asarray(pressure, dtype=float)
        if pressure.shape != self.mesh.shape:
            raise ValueError(f"pressure has shape {pressure.shape}, the mesh needs {self.mesh.shape}")
        return pressure

    def _cell_pressure(self, pressure):
        return self._checked(pressure) * self._cell_weight

    def __call__(self, pressure):
        """Displacement (m, (ny, nx)) of both surfaces under the nodal pressure (Pa, (ny, nx)), by DC-FFT."""
        load_hat = fft.rfft2(self._cell_pressure(pressure), s=self._padded)
        u = fft.irfft2(self._kernel_hat * load_hat, s=self._padded)
        return u[: self.mesh.ny, : self.mesh.nx]

    @cached_property
    def matrix(self) -> np.ndarray:
        """K as a dense (N, N) matrix, N the nodes in C order: the displacement at node i
        under 1 Pa at node j, the O(N^2) sum over node pairs (N^2 memory: small meshes, the
        dense Newton steps of line contacts; kept once built)."""
        xs, ys = np.meshgrid(self.mesh.x, self.mesh.y)
        xs, ys = xs.ravel(), ys.ravel()
        return self.influence(xs[:, None] - xs[None, :], ys[:, None] - ys[None, :]) * self._cell_weight.ravel()

    def near_field(self, radius: int) -> sp.csr_matrix:
        """The entries of K between nodes at most ``radius`` nodes apart along each axis, as a
        sparse (N, N) matrix (C order; exact where it has entries): the local part of the
        influence coefficients, for the Newton's preconditioner (model/monolithic_newton.py).
        Built once per radius and kept."""
        if radius not in self._near_fields:
            self._near_fields[radius] = self._near_field(radius)
        return self._near_fields[radius]

    def _near_field(self, radius: int) -> sp.csr_matrix:
        ny, nx = self.mesh.shape
        index = np.arange(nx * ny).reshape(ny, nx)
        rows, cols, values = [], [], []
        reach_y, reach_x = min(radius, ny - 1), min(radius, nx - 1)
        for oy in range(-reach_y, reach_y + 1):
            for ox in range(-reach_x, reach_x + 1):
                # targets (iy, ix), sources (iy - oy, ix - ox), both on the mesh
                ty, tx = slice(max(0, oy), ny + min(0, oy)), slice(max(0, ox), nx + min(0, ox))
                sy, sx = slice(max(0, -oy), ny + min(0, -oy)), slice(max(0, -ox), nx + min(0, -ox))
                rows.append(index[ty, tx].ravel())
                cols.append(index[sy, sx].ravel())
                values.append(self.influence(ox * self.mesh.dx, oy * self.mesh.dy) * self._cell_weight[sy, sx].ravel())
        n = nx * ny
        return sp.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))

    def direct(self, pressure):
        """The same displacement by the O(N^2) sum over all node pairs (for tests; N^2 memory)."""
        return (self.matrix @ self._checked(pressure).ravel()).reshape(self.mesh.shape)
