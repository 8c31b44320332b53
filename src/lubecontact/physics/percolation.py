"""The averaged film on the faces of the finite volumes, down to percolation (docs/physics.md section 15).

Near contact the Poiseuille coefficient vanishes at the percolation threshold
(flow_factors.percolating_coefficient_and_slope). A face between a node that conducts and
one that has sealed must then close continuously as the film reaches the threshold, not
drop from k/2 to 0 when the second node seals (arithmetic means of nodal k, reynolds.py):
a jump of the sealed set moves the fluid load by a finite amount and the coupled iteration
cycles (seen on Table 1 near percolation). So with rough surfaces each face gets the film halfway
between its nodes, h_f = (h_a + h_b)/2, and is evaluated there:

    T_f = k(h_f) (dy/dx or dx/dy),    Couette flux of an x face (U/2) h_T(max(h_f, 0)) dy

The Couette content is frozen at its threshold value below h_f = 0: lubricant sealed in
closed pockets is incompressible and is carried through the contact with the volume it was
sealed with (model/fluid_film.FLUID_FILM_FLOOR_SIGMAS). Both are second-order accurate like
the nodal means (and closer to the mesh limit on Table 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class FaceFilm:
    """Values (or derivatives in the face film h_f) on the faces: Poiseuille coefficient of the
    x faces (ny, nx-1) and y faces (ny-1, nx), m^3/(Pa s), and Couette gap of the x faces, m."""

    coefficient_x: np.ndarray
    coefficient_y: np.ndarray
    gap_x: np.ndarray


def face_films(film: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Film halfway between neighbouring nodes: x faces (ny, nx-1), y faces (ny-1, nx), m."""
    return 0.5 * (film[:, :-1] + film[:, 1:]), 0.5 * (film[:-1, :] + film[1:, :])


def face_film(film, coefficient_law, gap_law) -> tuple[FaceFilm, FaceFilm]:
    """(values, slopes d/dh_f) on the faces. ``coefficient_law(h)`` and ``gap_law(h)`` return
    (value, derivative) at films h; the gap is evaluated at max(h_f, 0) (frozen below)."""
    hx, hy = face_films(np.asarray(film, dtype=float))
    kx, dkx = coefficient_law(hx)
    ky, dky = coefficient_law(hy)
    gap, dgap = gap_law(np.maximum(hx, 0.0))
    return FaceFilm(kx, ky, gap), FaceFilm(dkx, dky, np.where(hx > 0.0, dgap, 0.0))
