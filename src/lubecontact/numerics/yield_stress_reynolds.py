"""The finite-volume Reynolds outflow of a yield-stress lubricant and its Jacobian
(docs/physics.md section 21).

With a grease the Poiseuille flux of a face depends on the pressure gradient at the face
(physics/yield_stress_flow.py): the flux vector is -k_eff(|grad p|, s) grad p, so its
normal component on the face between nodes a and b (x faces; y faces alike with dy) is

    flux_f = T_f r_f (p_a - p_b) + (U/2) dy h_T,f,      r_f = r(|G_f|, s_f),

with G_f = (G_n, G_t): G_n = (p_b - p_a)/dx across the face, and in 2-D G_t along it, the
mean of the two nodes' differences along y (central, one-sided at the domain's edge;
reynolds.cross_gradient_operators), both exact at the face's midpoint for a quadratic pressure. T_f
is the Newtonian transmissibility (numerics/reynolds.py), r the law's reduction factor
k_eff(G, s)/(s^3/(12 K)) and s_f = (h_T,a + h_T,b)/2 the film content of the face (the slot
the law sees; h itself on smooth surfaces). On rough surfaces r multiplies the Patir-Cheng
coefficient: an approximation, exact for smooth films. The net outflow of cell i is
w_i = sum_f (+-) flux_f, as reynolds.reynolds_system's A p - b, now with A = A(p). Until the
forty-fourth session each face saw G_n alone: a plug then held its pressure along staircase
paths, and carried more than the law lets it (docs/physics.md section 21).

Its derivatives: d flux_f/dp_a = -d flux_f/dp_b = T_f (r + G_n dr/dG_n) (the tangent
transmissibility, >= 0), d flux_f/dp_k = T_f (p_a - p_b) dr/dG_t dG_t/dp_k at the nodes k
that G_t reads, with dr/dG_n = r' G_n/|G| and dr/dG_t = r' G_t/|G|, and d flux_f/dh_a =
(1/2)(dk/dh_a (dy/dx) r_f + T_f dr/ds dh_T/dh_a)(p_a - p_b) + the Couette slope. The residual
of the one-Newton solver divides w by the cell's secant diagonal s_i = sum_f T_f r_f, which
depends on p and h as well. Each is assembled face by face as a sparse matrix
(reynolds_jacobian.assembled; the G_t terms through each side's rows, node_rows).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from lubecontact.numerics.reynolds import ReynoldsSystem, cross_gradient_operators, face_transmissibilities
from lubecontact.numerics.reynolds_jacobian import assembled, face_slope_pairs
from lubecontact.numerics.reynolds_pattern import unknown_numbers
from lubecontact.physics.percolation import face_films
from lubecontact.physics.yield_stress_flow import YieldStressLaw, effective_coefficient


@dataclass(frozen=True)
class YieldStressOutflow:
    """The outflow w (m^3/s) and secant diagonal s (m^3/(Pa s)) of each unknown's cell, and
    ``blocks``, which assembles their derivatives in the unknown pressures ((n, n) matrices)
    and in the film at every node ((n, nodes) matrices) when a Newton direction asks for
    them: the trial points of a line search need only w and s."""

    outflow: np.ndarray
    scale: np.ndarray
    blocks: Callable[[], tuple[sp.csc_matrix, sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]]
    # per unknown, 1 where the scale is s_i and 0 where a floor replaced it
    # (reynolds_jacobian.with_scale_floor)
    scale_moves: np.ndarray | float = 1.0

    @cached_property
    def jacobian_blocks(self) -> tuple[sp.csc_matrix, sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """(dw/dp, ds/dp, dw/dh, ds/dh), assembled once (a rebranched direction reuses them)."""
        return self.blocks()

    def residual_jacobians(self, slope_pressure, slope_flow) -> tuple[sp.csc_matrix, sp.csr_matrix]:
        """(dR/dp, dR/dh) of the residual R = phi(p, w/s) whose slopes in its two arguments
        are ``slope_pressure`` and ``slope_flow`` (n,) (complementarity.fischer_burmeister),
        with d(w/s) = dw/s - w ds/s^2."""
        outflow_pressure, scale_pressure, outflow_film, scale_film = self.jacobian_blocks
        flow = sp.diags(slope_flow / self.scale)
        # (w/s)/s, not w/s^2: at Newton iterates far from the answer s and w reach 1e192 and
        # 1e198 (measured on a 1 N stop with a 5 kPa Bingham grease), s^2 overflows, while
        # w/s stays a pressure (1e3-1e6 Pa)
        level = sp.diags(slope_flow * self.scale_moves * (self.outflow / self.scale) / self.scale)
        pressure = sp.diags(slope_pressure) + flow @ outflow_pressure - level @ scale_pressure
        return pressure.tocsc(), (flow @ outflow_film - level @ scale_film).tocsr()


def reduction_factor(gradient, content, law: YieldStressLaw):
    """(r, dr/dG, dr/ds): k_eff(G, s) over the Newtonian s^3/(12 K) (module docstring)."""
    newtonian = content**3 / (12.0 * law.consistency)
    k, k_g, k_s = effective_coefficient(gradient, content, law)
    return k / newtonian, k_g / newtonian, (k_s - 3.0 * k / content) / newtonian


def node_rows(unknown, nodes) -> sp.csr_matrix:
    """(unknowns, faces) selection: 1 in the row of each face's node in ``nodes`` (one side's
    nodes, in C order of the faces) where that node is an unknown."""
    owner = unknown_numbers(unknown).ravel()[nodes.ravel()]
    keep = owner >= 0
    return sp.csr_matrix((np.ones(int(keep.sum())), (owner[keep], np.flatnonzero(keep))),
                         shape=(int(unknown.sum()), nodes.size))


def yield_stress_outflow(mesh, system: ReynoldsSystem, pressure, coefficient, content, content_slope, speed,
                         law: YieldStressLaw, faces=None, face_slopes=None, coefficient_slope=None,
                         added_outflow_film: Callable[[], sp.csr_matrix] | None = None) -> YieldStressOutflow:
    """The grease's outflow and Jacobians (module docstring) at ``pressure`` (ny, nx, Pa,
    zero off the unknowns). ``system``: reynolds.reynolds_system of the same film (its
    unknowns and right-hand side b); ``coefficient`` k and ``content`` h_T (ny, nx) and
    dh_T/dh (``content_slope``) at the nodes; ``faces``/``face_slopes`` the face values of
    rough surfaces (percolation.FaceFilm), else the nodal ``coefficient_slope`` dk/dh;
    ``added_outflow_film``: builds a further dw/dh (a time step's squeeze outflow)."""
    ny, nx = mesh.shape
    unknown = system.unknown
    flat = np.arange(ny * nx).reshape(mesh.shape)
    tx, ty = face_transmissibilities(mesh, coefficient, faces)
    sx, sy = face_films(content)
    slope_pairs = face_slope_pairs(face_slopes, content_slope, coefficient_slope)
    net = np.zeros(mesh.shape)
    scale = np.zeros(mesh.shape)
    flow_p, scale_p, flow_h, scale_h = [], [], [], []
    cross_p = []  # (a, b, d flux/dG_t, d(T r)/dG_t, dG_t/dp) of each direction's faces, in 2-D
    operators = cross_gradient_operators(ny, nx, mesh.dx, mesh.dy)
    directions = (
        (tx, sx, mesh.dx, mesh.dy / mesh.dx, (slice(None), slice(None, -1)), (slice(None), slice(1, None)),
         slope_pairs[0][:2], None if operators is None else operators[0]),
        (ty, sy, mesh.dy, mesh.dx / mesh.dy, (slice(None, -1), slice(None)), (slice(1, None), slice(None)),
         slope_pairs[1], None if operators is None else operators[1]),
    )
    for t, s, spacing, geometry, side_a, side_b, (dk_a, dk_b), cross in directions:
        drop = pressure[side_a] - pressure[side_b]
        normal = -drop / spacing
        along_face = np.zeros(drop.shape) if cross is None else (cross @ pressure.ravel()).reshape(drop.shape)
        magnitude = np.hypot(normal, along_face)
        signed = np.where(normal < 0.0, -magnitude, magnitude)  # |G| with the sign of G_n (normal where G_t = 0)
        r, r_g, r_s = reduction_factor(signed, s, law)  # r_g = sign(G_n) r'(|G|)
        moving = magnitude > 0.0
        across = np.divide(np.abs(normal), magnitude, out=np.ones(drop.shape), where=moving)  # (dr/dG_n) / r_g
        tangential = np.divide(np.sign(signed) * along_face, magnitude, out=np.zeros(drop.shape), where=moving)
        flux = t * r * drop
        net[side_a] += flux
        net[side_b] -= flux
        scale[side_a] += t * r
        scale[side_b] += t * r
        a, b = flat[side_a], flat[side_b]
        tangent = t * (r - drop / spacing * r_g * across)  # T (r + G_n dr/dG_n)
        flow_p.append((a, b, tangent, -tangent, 1.0, -1.0))
        scale_p.append((a, b, -t * r_g * across / spacing, t * r_g * across / spacing, 1.0, 1.0))
        if cross is not None:
            cross_p.append((a, b, t * drop * r_g * tangential, t * r_g * tangential, cross))
        ds_a, ds_b = 0.5 * content_slope[side_a], 0.5 * content_slope[side_b]
        dt_a, dt_b = 0.5 * dk_a * geometry, 0.5 * dk_b * geometry
        flow_h.append((a, b, (dt_a * r + t * r_s * ds_a) * drop, (dt_b * r + t * r_s * ds_b) * drop, 1.0, -1.0))
        scale_h.append((a, b, dt_a * r + t * r_s * ds_a, dt_b * r + t * r_s * ds_b, 1.0, 1.0))
    _, _, dg_a, dg_b = slope_pairs[0]
    couette = 0.5 * speed * mesh.dy
    flow_h.append((flat[:, :-1], flat[:, 1:], 0.5 * couette * dg_a, 0.5 * couette * dg_b, 1.0, -1.0))
    columns = flat[unknown]

    def blocks():
        outflow_film = assembled(mesh, unknown, flow_h)
        if added_outflow_film is not None:
            outflow_film = outflow_film + added_outflow_film()
        outflow_pressure, scale_pressure = assembled(mesh, unknown, flow_p), assembled(mesh, unknown, scale_p)
        for a, b, flux_slope, scale_slope, cross in cross_p:
            on_a, on_b = node_rows(unknown, a), node_rows(unknown, b)
            outflow_pressure = outflow_pressure + (on_a - on_b) @ sp.diags(flux_slope.ravel()) @ cross
            scale_pressure = scale_pressure + (on_a + on_b) @ sp.diags(scale_slope.ravel()) @ cross
        return (outflow_pressure[:, columns].tocsc(), scale_pressure[:, columns], outflow_film,
                assembled(mesh, unknown, scale_h))

    return YieldStressOutflow(outflow=net[unknown] - system.rhs, scale=scale[unknown], blocks=blocks)
