"""The far inlet as an exact boundary condition (docs/physics.md section 17, "The far inlet").

Upstream of the mesh's first Reynolds node x_1 (< 0) the film is far above the roughness
and the surfaces barely deform: the steady Reynolds equation there is Martin's, on the rigid
parabola h(x) = c + x^2/(2R), and its flux is constant,

    h^3/(12 mu) dp/dx = (U/2)(h - h*),   p(-inf) = 0.

Integrated from -inf, with I_n = int_{-inf}^{x_1} h^-n dx and K_n = int_{-inf}^{x_1}
(x_1 - x) h^-n dx, it ties the flux through the first face to the pressure p_1 there and
gives the load and the shear the fluid carries upstream of x_1:

    flux    q = U I_2 / (2 I_3) - p_1 / (12 mu I_3)                       (a Robin condition)
    load    W = p_1 K_3 / I_3 + 6 mu U (K_2 - K_3 I_2 / I_3)
    h*        = I_2 / I_3 - p_1 / (6 mu U I_3)
    shear     mu U (4 J_1 - 3 h* J_2) on the block upstream of x_0 (J_n: I_n up to x_0)

per unit width. The flux is the first x face's (reynolds.py) with the Poiseuille coefficient
dx / (12 mu I_3) and the Couette gap I_2 / I_3: one more conductance to the pressure zero at
-inf, so the matrix stays a symmetric M-matrix. The parabola goes through the film of that
face, h_f = (h_0 + h_1)/2 (percolation.py), c = h_f - (x_0^2 + x_1^2)/(4R), so its slopes
pass half to each of the face's nodes as every face's do (reynolds_jacobian.py); since
dh/dc = 1 everywhere, dI_n/dc = -n I_{n+1} and dK_n/dc = -n K_{n+1}.

The mesh then needs no inlet cells (numerics/mesh.py): the automatic domain [-3.5 s, 1.5 s]
is as flooded as an infinite inlet. A scene asks for it (mesh.far_inlet), and is refused
where it does not hold (numerics/mesh.far_inlet_problems). This module is a line's
exterior (on a cylinder of finite length the fluid upstream also leaks sideways: a per-row
exterior made the Table 1 film at 10 m/s on 51 x 51 4 % thicker than the long inlet, so a
2-D mesh takes numerics/modal_far_inlet.py), for a Newtonian film (a grease's flux is
not linear in the pressure gradient), steady (a time step's squeeze makes the flux vary
along x), rough surfaces whose films the faces carry (percolation.py), and a first node far
above the roughness (the automatic domain's end lies where the gap is >= 122 sigma: flow
factors 1, and the deformation there varies slowly). The parabola stands for the circle of
Eq. (4), whose gap is larger by x^4/(8R^3), 0.3 % at the domain's end on Table 1.

The integrals, in s = (x_1 - x) |x_1| / (R h_1) with h_1 = h(x_1) and e = h_1 R / (2 x_1^2),
are those of (1 + s + e s^2)^-n over s > 0, by Gauss-Legendre after s = a t / (1 - t),
a = 1 / (1 + sqrt(e)), which maps the integrand's decay onto a polynomial in t (tested
against adaptive quadrature in tests/test_far_inlet.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lubecontact.physics.percolation import FaceFilm

QUADRATURE_NODES = 64
_POINTS, _WEIGHTS = np.polynomial.legendre.leggauss(QUADRATURE_NODES)
UNIT_POINTS, UNIT_WEIGHTS = 0.5 * (_POINTS + 1.0), 0.5 * _WEIGHTS  # Gauss-Legendre on (0, 1)
# The exterior needs the gap to grow upstream: its film at x_1 is held at least this fraction
# of the parabola's own rise x_1^2 / (2R). Only an iterate far from any solution gets there
# (a cylinder sunk by more than a hundred roughness heights at the domain's end).
SMALLEST_FILM_FRACTION = 1.0e-3


@dataclass(frozen=True)
class ParabolaIntegrals:
    """I_n = int_{-inf}^{end} h^-n dx (n = 1..4, m^(1-n)) and K_n = int_{-inf}^{end} (end - x)
    h^-n dx (n = 2..4, m^(2-n)) per row, for h = c + x^2/(2R) (module docstring)."""

    i: dict
    k: dict


def parabola_integrals(offset: np.ndarray, end: float, radius: float) -> ParabolaIntegrals:
    """The integrals of the module docstring for the parabolas c + x^2/(2R) with c =
    ``offset`` (per row, m) up to x = ``end`` < 0."""
    rise = end * end / (2.0 * radius)
    film = np.maximum(np.asarray(offset, dtype=float) + rise, SMALLEST_FILM_FRACTION * rise)[..., None]
    slope = abs(end) / radius
    length = film / slope  # m: the s of the module docstring is (end - x) / length
    curvature = film * radius / (2.0 * end * end)  # e
    a = 1.0 / (1.0 + np.sqrt(curvature))
    s = a * UNIT_POINTS / (1.0 - UNIT_POINTS)
    weight = UNIT_WEIGHTS * a / (1.0 - UNIT_POINTS) ** 2
    inverse = 1.0 / (1.0 + s + curvature * s * s)
    i, k = {}, {}
    power = inverse
    for n in range(1, 5):
        i[n] = (length / film**n * np.sum(weight * power, axis=-1, keepdims=True))[..., 0]
        if n >= 2:
            k[n] = (length**2 / film**n * np.sum(weight * s * power, axis=-1, keepdims=True))[..., 0]
        power = power * inverse
    return ParabolaIntegrals(i, k)


@dataclass(frozen=True)
class FarInlet:
    """The exact far inlet of one mesh (module docstring): Martin's film from -inf up to the
    first Reynolds node, for a Newtonian lubricant of ``viscosity`` sliding at ``speed``."""

    start: float  # x_0, m: the mesh's first node (its boundary)
    end: float  # x_1, m: the first Reynolds node, where the exterior meets the mesh
    spacing: float  # dx, m
    widths: np.ndarray  # (ny,) m: the width each row of nodes stands for (0 on the sides, p = 0 there)
    radius: float  # R, m
    viscosity: float  # mu, Pa s
    speed: float  # U, m/s (> 0: the inlet at x_min)

    @classmethod
    def on(cls, mesh, radius: float, viscosity: float, speed: float) -> "FarInlet":
        """The far inlet of ``mesh``: its rows' widths are their nodal areas per dx, except the
        two rows on the cylinder's ends of a 2-D mesh, held at p = 0 (reynolds.py), whose
        exterior carries nothing either."""
        widths = mesh.nodal_area[:, 1] / mesh.dx
        if not mesh.line:
            widths[[0, -1]] = 0.0
        return cls(float(mesh.x[0]), float(mesh.x[1]), mesh.dx, widths, radius, viscosity, speed)

    def offset(self, film: np.ndarray) -> np.ndarray:
        """c (per row, m) of the parabola through the first x face's film h_f."""
        face = 0.5 * (film[:, 0] + film[:, 1])
        return face - (self.start**2 + self.end**2) / (4.0 * self.radius)

    def integrals(self, film: np.ndarray, end: float | None = None) -> ParabolaIntegrals:
        return parabola_integrals(self.offset(film), self.end if end is None else end, self.radius)

    def faces(self, film: np.ndarray, values: FaceFilm, slopes: FaceFilm) -> tuple[FaceFilm, FaceFilm]:
        """``values`` and ``slopes`` (percolation.face_film) with the first x face's coefficient
        dx / (12 mu I_3) and Couette gap I_2 / I_3, and their slopes in its film."""
        n = self.integrals(film)
        i2, i3, i4 = n.i[2], n.i[3], n.i[4]
        values, slopes = _copied(values), _copied(slopes)
        values.coefficient_x[:, 0] = self.spacing / (12.0 * self.viscosity * i3)
        slopes.coefficient_x[:, 0] = self.spacing / (12.0 * self.viscosity) * 3.0 * i4 / i3**2
        values.gap_x[:, 0] = i2 / i3
        slopes.gap_x[:, 0] = -2.0 + 3.0 * i2 * i4 / i3**2
        return values, slopes

    def exterior(self, film: np.ndarray) -> None:
        """No dense block: a line's exterior is its first face's (``faces``); a 2-D mesh's is
        numerics/modal_far_inlet.ModalFarInlet.exterior."""
        return None

    def load(self, pressure: np.ndarray, film: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        """(W, weights, film slope): the load the exterior adds to the mesh's trapezoidal
        sum of p dA (N), which already counts the first node's pressure over dx (the half
        of it upstream of x_1 is the exterior's, and is taken out); ``weights`` (ny, nx, m^2)
        is dW/dp, on the first Reynolds node; ``film slope`` (ny, nx, N/m) dW/dh at fixed p."""
        n = self.integrals(film)
        i2, i3, i4, k2, k3, k4 = n.i[2], n.i[3], n.i[4], n.k[2], n.k[3], n.k[4]
        couette = 6.0 * self.viscosity * self.speed
        reach = k3 / i3 - 0.5 * self.spacing  # m: dW/dp_1 per unit width
        p1 = pressure[:, 1]
        value = self.widths * (p1 * reach + couette * (k2 - k3 * i2 / i3))
        # d/dc of p_1 K_3/I_3 + 6 mu U (K_2 - K_3 I_2/I_3), half to each node of the first face
        d_reach = 3.0 * (k3 * i4 - k4 * i3) / i3**2
        d_constant = 3.0 * i2 * (k4 * i3 - k3 * i4) / i3**2
        slope = 0.5 * self.widths * (p1 * d_reach + couette * d_constant)
        weights, film_slope = np.zeros(pressure.shape), np.zeros(pressure.shape)
        weights[:, 1] = self.widths * reach
        film_slope[:, 0] = film_slope[:, 1] = slope
        return float(np.sum(value)), weights, film_slope

    def upstream(self, pressure: np.ndarray, film: np.ndarray) -> tuple[np.ndarray, float]:
        """(p at x_0 (ny,) Pa, shear upstream of x_0 N) of the exterior film for the mesh's first
        Reynolds node's pressure p_1, with J_n the integrals up to x_0: the pressure
        6 mu U (J_2 - h* J_3) (0 on the sides), for the pressure gradient at the first nodes,
        and int tau dA of the block's shear mu U / h + (h/2) dp/dx of the full film (friction.py,
        flow factors 1), mu U (4 J_1 - 3 h* J_2) per unit width."""
        inner, outer = self.integrals(film), self.integrals(film, self.start)
        h_star = self._film_at_peak(pressure, inner)
        couette = self.viscosity * self.speed
        boundary = np.where(self.widths > 0.0, 6.0 * couette * (outer.i[2] - h_star * outer.i[3]), 0.0)
        return boundary, float(np.sum(self.widths * couette * (4.0 * outer.i[1] - 3.0 * h_star * outer.i[2])))

    def _film_at_peak(self, pressure: np.ndarray, inner: ParabolaIntegrals) -> np.ndarray:
        """h* (per row, m) of the exterior's flux U h*/2, from its pressure at x_1."""
        return inner.i[2] / inner.i[3] - pressure[:, 1] / (6.0 * self.viscosity * self.speed * inner.i[3])


def _copied(faces: FaceFilm) -> FaceFilm:
    return FaceFilm(faces.coefficient_x.copy(), faces.coefficient_y, faces.gap_x.copy())
