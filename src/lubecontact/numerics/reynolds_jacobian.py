"""The slope of the Reynolds residual with respect to the film, as a sparse matrix
(docs/physics.md section 20).

The finite-volume outflow of cell i (numerics/reynolds.py) is a sum over its faces of

    flux_f = T_f (p_a - p_b) + (U/2) dy h_T,f        (x faces; y faces without Couette)

with T_f = k_f dy/dx (or k_f dx/dy). On a face between nodes a and b both k_f and h_T,f
depend on the films h_a and h_b: with rough surfaces through the film on the face,
h_f = (h_a + h_b)/2 (physics/percolation.py), so d/dh_a = d/dh_b = (1/2) d/dh_f; with smooth
ones as means of the nodal values, so d/dh_a = (1/2) d/dh at node a. Cell a gains +flux_f,
cell b -flux_f. The matrix J[i, j] = d w_i / d h_j has at most seven entries a row.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from lubecontact.numerics.reynolds_pattern import unknown_numbers
from lubecontact.physics.percolation import FaceFilm


def face_slope_pairs(face_slopes: FaceFilm | None, gap_slope, coefficient_slope):
    """((dk/dh_a, dk/dh_b, dh_T/dh_a, dh_T/dh_b) of the x faces, (dk/dh_a, dk/dh_b) of the y
    faces), each without the factor 1/2 of the module docstring: the face's own slopes
    (rough surfaces) or the nodal slopes of its two nodes (smooth)."""
    if face_slopes is not None:
        return ((face_slopes.coefficient_x, face_slopes.coefficient_x, face_slopes.gap_x, face_slopes.gap_x),
                (face_slopes.coefficient_y, face_slopes.coefficient_y))
    return ((coefficient_slope[:, :-1], coefficient_slope[:, 1:], gap_slope[:, :-1], gap_slope[:, 1:]),
            (coefficient_slope[:-1, :], coefficient_slope[1:, :]))


def assembled(mesh, unknown, faces) -> sp.csr_matrix:
    """The (unknowns, nodes) matrix of per-face contributions ``faces``: each a tuple (node a,
    node b, d/dh_a, d/dh_b, sign at a, sign at b) adding sign x slope to the rows of a and b."""
    ny, nx = mesh.shape
    number = unknown_numbers(unknown)
    rows, cols, vals = [], [], []
    for a, b, slope_a, slope_b, sign_a, sign_b in faces:
        for cell, sign in ((a, sign_a), (b, sign_b)):
            owner = number.ravel()[cell]
            keep = owner >= 0
            for node, slope in ((a, slope_a), (b, slope_b)):
                rows.append(owner[keep])
                cols.append(node[keep])
                vals.append(sign * slope[keep])
    n = int(unknown.sum())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, ny * nx))


def outflow_film_jacobian(mesh, pressure, unknown, speed, face_slopes: FaceFilm | None = None,
                          gap_slope=None, coefficient_slope=None,
                          face_content: np.ndarray | None = None) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(d w / d h, d A_ii / d h): (number of unknowns, number of nodes) in m^2/s per m of
    film and m^3/(Pa s) per m, w the net outflow of each unknown node's cell and A_ii the
    diagonal of its row (reynolds.reynolds_system, C order), h the film at every node.
    ``pressure`` (ny, nx) Pa; ``face_slopes`` (rough surfaces: dk/dh_f and dh_T/dh_f on the
    faces) or the nodal ``gap_slope`` and ``coefficient_slope`` (smooth); ``face_content``
    (ny, nx-1): the film content carried through each x face, which weights its Couette flux
    (mass-conserving cavitation, jfo_outflow.py; None: a full film)."""
    ny, nx = mesh.shape
    flat = np.arange(ny * nx).reshape(mesh.shape)
    gx, gy = mesh.dy / mesh.dx, mesh.dx / mesh.dy
    couette = 0.5 * speed * mesh.dy * (1.0 if face_content is None else face_content)
    (dkx_a, dkx_b, dgx_a, dgx_b), (dky_a, dky_b) = face_slope_pairs(face_slopes, gap_slope, coefficient_slope)
    drop_x = pressure[:, :-1] - pressure[:, 1:]
    drop_y = pressure[:-1, :] - pressure[1:, :]
    x_a, x_b, y_a, y_b = flat[:, :-1], flat[:, 1:], flat[:-1, :], flat[1:, :]
    outflow = assembled(mesh, unknown, [
        (x_a, x_b, 0.5 * (dkx_a * gx * drop_x + couette * dgx_a), 0.5 * (dkx_b * gx * drop_x + couette * dgx_b), 1.0, -1.0),
        (y_a, y_b, 0.5 * dky_a * gy * drop_y, 0.5 * dky_b * gy * drop_y, 1.0, -1.0),
    ])
    diagonal = assembled(mesh, unknown, [
        (x_a, x_b, 0.5 * dkx_a * gx, 0.5 * dkx_b * gx, 1.0, 1.0),
        (y_a, y_b, 0.5 * dky_a * gy, 0.5 * dky_b * gy, 1.0, 1.0),
    ])
    return outflow, diagonal


def exterior_film_jacobian(unknown, exterior, pressure) -> sp.csr_matrix:
    """d w / d h of a 2-D mesh's far inlet (numerics/modal_far_inlet.Exterior): its outflow of
    the first column's cells moves with the offset c of the cylinder's gap upstream, which
    moves with the first x faces' films: the rank-one (number of unknowns, number of nodes)
    block (dw/dc) (dc/dh)^T, ``pressure`` (ny, nx) Pa."""
    rows = unknown_numbers(unknown)[1:-1, 1]
    columns = np.flatnonzero(exterior.offset_slope.ravel())
    values = np.outer(exterior.outflow_slope(pressure), exterior.offset_slope.ravel()[columns])
    return sp.csr_matrix((values.ravel(), (np.repeat(rows, columns.size), np.tile(columns, rows.size))),
                         shape=(int(unknown.sum()), unknown.size))


def squeeze_film_jacobian(mesh, unknown, coefficient: float, content) -> sp.csr_matrix:
    """d w / d h of a transient step's squeeze outflow dA dh_T/dt (reynolds.reynolds_system,
    docs/physics.md section 14): (number of unknowns, number of nodes), the unknowns' rows of
    c0 dA dc/dh, with dh_T/dt = c0 c + history (BDF's c0 in 1/s) and ``content`` the cells'
    content c (control_volume.ControlVolumeMean: a node's row reaches its neighbours)."""
    rows = np.flatnonzero(unknown.ravel())
    return (coefficient * sp.diags(mesh.nodal_area.ravel()) @ content.matrix()).tocsr()[rows]


@dataclass(frozen=True)
class LinearOutflow:
    """The outflow w = A p - b of a Newtonian film (reynolds.reynolds_system) at one film, with
    what the one Newton's residual phi(p, w/A_ii) needs for its Jacobians (docs/physics.md
    section 20): ``matrix``, the slope of w in the Newton's unknown (A; with mass-conserving
    cavitation the slope in the universal variable, jfo_outflow.py), the diagonal A_ii of A,
    w, and ``film_slopes``, which builds (dw/dh, dA_ii/dh)
    (outflow_film_jacobian, plus a step's squeeze_film_jacobian) when a Newton direction asks
    for them: the trial points of a line search need only the residual."""

    matrix: sp.csr_matrix
    scale: np.ndarray
    outflow: np.ndarray
    film_slopes: Callable[[], tuple[sp.csr_matrix, sp.csr_matrix]]
    # per unknown, 1 where the scale is A_ii and 0 where a floor replaced it (with_scale_floor)
    scale_moves: np.ndarray | float = 1.0

    @cached_property
    def film_jacobians(self) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """(dw/dh, dA_ii/dh), built once (a rebranched direction reuses them)."""
        return self.film_slopes()

    def residual_jacobians(self, slope_pressure, slope_flow) -> tuple[sp.csc_matrix, sp.csr_matrix]:
        """(dR/dp, dR/dh) of R = phi(p, w/A_ii) whose slopes in its two arguments are
        ``slope_pressure`` and ``slope_flow`` (n,): D_a + D_b M/A_ii (M: ``matrix``), and
        D_b d(w/A_ii)/dh with
        d(w/s) = dw/s - w ds/s^2."""
        outflow_film, scale_film = self.film_jacobians
        flow = sp.diags(slope_flow / self.scale)
        pressure = (sp.diags(slope_pressure) + flow @ self.matrix).tocsc()
        film = flow @ outflow_film - sp.diags(slope_flow * self.scale_moves * self.outflow / self.scale**2) @ scale_film
        return pressure, film.tocsr()


def with_scale_floor(parts, floor: np.ndarray):
    """``parts`` (LinearOutflow, or yield_stress_reynolds.YieldStressOutflow) with its scale
    raised to ``floor`` where it is lower, the derivatives of the scale dropped there (the
    floor is held fixed through a solve)."""
    return dataclasses.replace(parts, scale=np.maximum(parts.scale, floor), scale_moves=(parts.scale >= floor) * 1.0)
