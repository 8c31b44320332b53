"""The computational mesh shared by the Reynolds, contact and deformation sub-models.

Paper, section 2.6: the same nodal grid carries the fluid pressure (Eq. 1) and the
rough-surface contact (Eq. 11). Nodes span [x_min, x_max] x [-L/2, L/2] with the
boundary nodes included; x is the sliding direction (inlet at x_min), y the cylinder axis.
``ny == 1`` is line-contact mode: one row of nodes, no side leakage, loads per unit length
times the cylinder length L.

Automatic domain (``x_min``/``x_max`` = auto): the length scale
``s = max(2 b_H, sqrt(2 R * 10 sigma))`` covers the Hertz width b_H (Johnson, E*; a crowned
cylinder's ellipse where it is wider, film_estimates.contact_half_width) and the
inlet/outlet zone where the undeformed gap (Eq. 4) is below ten roughness heights, the
film a fluid can build; without asperity contact, on deforming bodies, s = 2 b_H (the
smooth film is as thin as the load and the speed make it, whatever the roughness). The
domain is ``[-3.5 s, 1.5 s]``: longer upstream, where the fluid pressure builds, than
downstream, where it cavitates.

The inlet follows the film (docs/physics.md section 17): a film h fed from an inlet that ends at
X = x_min/sqrt(2 R h) is short of the fully flooded one by ~2.5/X^2 (lubecontact.physics.inlet),
and the resistance is exponential in the film. So the automatic inlet reaches at least
INLET_FILM_LENGTHS x sqrt(2 R h_M), h_M Martin's rigid film of the scene's speed (a grease's at its
flowing viscosity, film_estimates.entrained_film; thicker
than the elastic film at high speed, thinner below ~1 m/s, where the rough-contact scale
s governs anyway), by whole cells of the ``[-3.5 s, 1.5 s]`` mesh added upstream: the node
spacing, and every node of the slow cases, stay those of ``mesh.nx`` over that domain, and
the mesh has ``nodes_x(scene)`` >= nx nodes along x. Each speed thus has its own inlet
(cases of a sweep differ in their inlet, not in their spacing); the inlet stops at
MAX_DOMAIN_RADII x R (Eq. 4 needs |x| < R), where the validity flag ``inlet`` reports a
film still short of its flooded value.

Where the film upstream is the rigid one (numerics/far_inlet.py on a line,
numerics/modal_far_inlet.py on a straight cylinder; _far_inlet_missing: a steady Newtonian
contact between rough surfaces, the automatic domain) the mesh needs none of those cells: by
default (mesh.far_inlet auto) wherever the long inlet would add some, or wherever the scene
asks for it (true), ``build_mesh(scene)`` ends at -3.5 s and marks the mesh ``far_inlet``, and
the solvers take the exterior as its boundary condition (far_inlet_serves). A motion's mesh
(``far_inlet=False``, unsteady/integrator.py) keeps them: its squeeze reaches upstream.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lubecontact.physics.film_estimates import contact_half_width, entrained_film

UPSTREAM_LENGTHS = 3.5
DOWNSTREAM_LENGTHS = 1.5
MIN_INTERVALS_ACROSS_CONTACT = 2.0
INLET_FILM_LENGTHS = 20.0  # automatic inlet >= this many sqrt(2 R h_M) upstream of x = 0
MAX_DOMAIN_RADII = 0.9  # the automatic inlet never reaches beyond this fraction of R


def contact_width_estimate(scene) -> float:
    """Width in x over which solid contact is expected: the larger of the Hertz width 2 b_H
    (a crowned cylinder's: film_estimates.contact_half_width) and the width where the
    undeformed gap x^2/2R stays below 3 sigma (rough contact spreads the load beyond Hertz)."""
    return 2.0 * max(contact_half_width(scene), _rough_half_width(scene, 3.0))


def auto_length_scale(scene) -> float:
    """The automatic domain's length scale s (module docstring): the larger of the Hertz
    width and the half-width where the undeformed gap stays below ten roughness heights.
    Without asperity contact but with elastic deformation, the Hertz width alone: the smooth
    film is as thin as the load and the speed make it, not the roughness (a rigid smooth
    cylinder keeps the roughness scale: its Hertz width has no meaning, and the film's own
    scale changes with the speed, where the spacing of a sweep's cases must not)."""
    smooth_elastic = not scene.effects.asperity_contact and scene.effects.elastic_deformation
    rough = 0.0 if smooth_elastic else _rough_half_width(scene, 10.0)
    return max(2.0 * contact_half_width(scene), rough)


def _rough_half_width(scene, heights: float) -> float:
    """Half-width where the undeformed gap x^2/2R (Eq. 4) stays below ``heights`` roughness
    heights, sqrt(2 R heights sigma)."""
    return float(np.sqrt(2.0 * scene.geometry.radius * heights * scene.roughness.sigma))


def film_inlet_length(scene) -> float:
    """Inlet length (m) the film of the scene's speed needs: INLET_FILM_LENGTHS sqrt(2 R h_M),
    h_M Martin's film (a grease's at its flowing viscosity: film_estimates.entrained_film;
    0 without a fluid)."""
    if not scene.effects.hydrodynamics or scene.operating.speed == 0.0:
        return 0.0

    return INLET_FILM_LENGTHS * float(np.sqrt(2.0 * scene.geometry.radius * entrained_film(scene)))


def _far_inlet_missing(scene) -> list[str]:
    """What the rigid film upstream (numerics/far_inlet.py on a line, numerics/modal_far_inlet.py
    on a 2-D mesh) needs and the scene lacks: a straight cylinder (one gap for every row), on a
    2-D mesh Reynolds or no cavitation (its exterior is in that solve only), the automatic
    domain, a Newtonian lubricant (a grease's flux is not linear in its pressure gradient),
    rough surfaces (their films on the faces) and a steady solve (a motion's squeeze reaches
    upstream)."""
    needs = {"a straight cylinder (no geometry.crown_radius)": scene.geometry.crown_radius is None,
             "on a 2-D mesh, effects.cavitation reynolds or none (its exterior is in the Reynolds solve only)":
                 scene.mesh.ny == 1 or scene.effects.cavitation != "jfo",
             "the automatic domain (mesh.x_min and mesh.x_max left out)": scene.mesh.x_min is None,
             "a Newtonian lubricant (lubricant.rheology: newtonian)": scene.lubricant.rheology == "newtonian",
             "asperity contact (effects.asperity_contact: true)": bool(scene.effects.asperity_contact),
             "a steady solve (motion.kind: steady, no vibration)": (scene.motion.kind == "steady"
                                                                   and scene.motion.vibration == "none")}
    return [need for need, met in needs.items() if not met]


def far_inlet_problems(scene) -> list[str]:
    """Why the far inlet a scene asks for (mesh.far_inlet: true) cannot serve (empty when it
    can, or is not asked for: mesh.far_inlet auto takes it only where it fits)."""
    if scene.mesh.far_inlet is not True:
        return []
    missing = _far_inlet_missing(scene)
    if not missing:
        return []
    return ["mesh.far_inlet: true needs " + ", ".join(missing) + " (docs/physics.md section 17, \"The far inlet\")"]


def far_inlet_serves(scene) -> bool:
    """Whether the scene's mesh is open to the far inlet: a fluid sliding at U > 0 on a scene
    it fits (_far_inlet_missing), asked for (mesh.far_inlet: true) or, by default (auto),
    wherever the long inlet would add columns upstream of the domain for the film
    (docs/physics.md section 17, "The far inlet": there the rigid film upstream replaces
    them, as the exact limit of an ever longer inlet)."""
    asked, effects = scene.mesh.far_inlet, scene.effects
    if asked is False or not (effects.hydrodynamics and scene.operating.speed > 0.0) or _far_inlet_missing(scene):
        return False
    return asked is True or _long_inlet(scene)[2] > 0


def _long_inlet(scene) -> tuple[float, float, int]:
    """(x_min, x_max, cells added upstream) of the long inlet: the domain before the cells are
    added, and the whole cells of its spacing that reach the film's inlet (film_inlet_length,
    up to MAX_DOMAIN_RADII x R; none on an explicit domain)."""
    s = auto_length_scale(scene)
    x_min = -UPSTREAM_LENGTHS * s if scene.mesh.x_min is None else float(scene.mesh.x_min)
    x_max = DOWNSTREAM_LENGTHS * s if scene.mesh.x_max is None else float(scene.mesh.x_max)
    if scene.mesh.x_min is not None or not x_max > x_min:
        return x_min, x_max, 0
    spacing = (x_max - x_min) / (scene.mesh.nx - 1)
    inlet = min(film_inlet_length(scene), MAX_DOMAIN_RADII * scene.geometry.radius)
    return x_min, x_max, max(0, int(np.ceil((inlet + x_min) / spacing - 1e-9)))


def _inlet_cells(scene, far_inlet: bool) -> tuple[float, float, int]:
    """(x_min, x_max, cells added upstream) of the domain before the cells are added (_long_inlet);
    none where ``far_inlet`` and far_inlet_serves."""
    x_min, x_max, cells = _long_inlet(scene)
    return x_min, x_max, 0 if far_inlet and far_inlet_serves(scene) else cells


def nodes_x(scene, far_inlet: bool = True) -> int:
    """Nodes along x: mesh.nx plus the cells the automatic inlet adds for the film (none
    where the far inlet serves, unless ``far_inlet`` is False)."""
    return scene.mesh.nx + _inlet_cells(scene, far_inlet)[2]


def domain_x(scene, far_inlet: bool = True) -> tuple[float, float]:
    """(x_min, x_max) in m: the scene's values, or the automatic domain where they are None
    (without the inlet cells where the far inlet serves, unless ``far_inlet`` is False)."""
    x_min, x_max, cells = _inlet_cells(scene, far_inlet)
    return x_min - cells * (x_max - x_min) / (scene.mesh.nx - 1), x_max


def mesh_problems(scene) -> list[str]:
    """Reasons the scene's mesh cannot resolve the problem (empty when fine)."""
    problems = far_inlet_problems(scene)
    x_min, x_max = domain_x(scene)
    if not x_max > x_min:
        problems.append(f"mesh.x_max ({x_max:g} m) must be greater than mesh.x_min ({x_min:g} m)")
        return problems
    if scene.geometry.radius <= max(abs(x_min), abs(x_max)):
        problems.append(
            f"mesh domain [{x_min:g}, {x_max:g}] m reaches beyond the cylinder radius "
            f"{scene.geometry.radius:g} m (Eq. 4 needs |x| < R)"
        )
    dx = (x_max - x_min) / (nodes_x(scene) - 1)
    width = contact_width_estimate(scene)
    if dx * MIN_INTERVALS_ACROSS_CONTACT > width:
        base_min = _inlet_cells(scene, True)[0]  # mesh.nx spans the domain before the film's inlet cells
        needed = int(np.ceil(MIN_INTERVALS_ACROSS_CONTACT * (x_max - base_min) / width)) + 1
        problems.append(
            f"mesh.nx = {scene.mesh.nx} is too coarse: node spacing {dx:.3g} m against an expected "
            f"contact width of {width:.3g} m; use mesh.nx >= {needed} (or a smaller domain)"
        )
    return problems


@dataclass(frozen=True)
class Mesh:
    """Node coordinates and trapezoidal nodal areas of the shared grid."""

    x: np.ndarray  # (nx,) m
    y: np.ndarray  # (ny,) m; [0.0] in line mode
    length: float  # cylinder length L, m
    far_inlet: bool = False  # x_min is open to the rigid film upstream (numerics/far_inlet.py, modal_far_inlet.py)

    @property
    def nx(self) -> int:
        return self.x.size

    @property
    def ny(self) -> int:
        return self.y.size

    @property
    def shape(self) -> tuple[int, int]:
        return (self.ny, self.nx)

    @property
    def line(self) -> bool:
        """Line-contact mode: one row of nodes standing for the whole length L."""
        return self.ny == 1

    @property
    def dx(self) -> float:
        return float(self.x[1] - self.x[0])

    @property
    def dy(self) -> float:
        """Node spacing in y; the cylinder length L in line mode."""
        return self.length if self.line else float(self.y[1] - self.y[0])

    @cached_property
    def nodal_area(self) -> np.ndarray:
        """(ny, nx) trapezoidal weights in m^2: sum(p * nodal_area) integrates p over the domain."""
        wx = np.full(self.nx, self.dx)
        wx[[0, -1]] *= 0.5
        if self.line:
            wy = np.array([self.length])
        else:
            wy = np.full(self.ny, self.dy)
            wy[[0, -1]] *= 0.5
        return np.outer(wy, wx)


def describe_mesh(mesh: Mesh, requested_nx: int) -> str:
    """The mesh a solve ran on, in words for a case's attribute ``mesh`` and the CLI: nodes,
    domain and spacing along x, and what lies upstream of x_min (the far inlet, or the long
    inlet's columns beyond the ``requested_nx`` of mesh.nx)."""
    added = mesh.nx - requested_nx
    upstream = ("open upstream to the far inlet (the rigid film beyond x_min as its boundary condition)"
                if mesh.far_inlet else f"the long inlet: {added} columns added upstream for the film" if added > 0
                else "p = 0 at x_min")
    return (f"{mesh.ny} x {mesh.nx} nodes (y x x), x from {mesh.x[0] * 1e3:.4g} to {mesh.x[-1] * 1e3:.4g} mm "
            f"every {mesh.dx * 1e6:.3g} um; {upstream}")


def rest_mesh(mesh: Mesh, refinement: int) -> Mesh:
    """The mesh a motion's steps go on with at rest (unsteady/integrator.TimeIntegrator.rest_domain,
    docs/physics.md section 14): x on [-x_max, x_max], symmetric about the line of contact as
    the gap x^2/2R is (nothing is entrained at rest, so the inlet needs no more length than
    the outlet), at ``refinement`` times the nodes per metre of ``mesh``; y as in ``mesh``.
    Its first node is the node of ``mesh`` nearest -x_max (within ``mesh``), so every node
    of ``mesh`` on it is one of its nodes."""
    x_max = float(mesh.x[-1])
    cells = min(int(round(2.0 * x_max / mesh.dx)), mesh.nx - 1)
    x = np.linspace(float(mesh.x[-1 - cells]), x_max, cells * refinement + 1)
    return Mesh(x=x, y=mesh.y, length=mesh.length)


def mirrored_mesh(mesh: Mesh) -> Mesh:
    """``mesh`` mirrored about the line of contact, x -> -x: the mesh of a motion's return
    strokes (unsteady/integrator.TimeIntegrator.reversed_domain), whose inlet lies beyond
    x_max where the sliding reverses (docs/physics.md section 17); y as in ``mesh``."""
    return Mesh(x=-mesh.x[::-1], y=mesh.y, length=mesh.length)


def build_mesh(scene, far_inlet: bool = True) -> Mesh:
    """The scene's mesh; open to the far inlet where it serves and ``far_inlet`` (a motion's
    mesh is not: module docstring)."""
    x_min, x_max = domain_x(scene, far_inlet)
    x = np.linspace(x_min, x_max, nodes_x(scene, far_inlet))
    half = 0.5 * scene.geometry.length
    y = np.zeros(1) if scene.mesh.ny == 1 else np.linspace(-half, half, scene.mesh.ny)
    return Mesh(x=x, y=y, length=scene.geometry.length, far_inlet=far_inlet and far_inlet_serves(scene))
