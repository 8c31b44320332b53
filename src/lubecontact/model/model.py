"""The coupled model of one operating point and its state (paper section 2.5, Eqs. 3-4).

``Model`` holds the sub-models a scene calls for, built once (disabled effects are None or
False: a switched-off effect costs nothing); ``State`` is everything at one cylinder
position z and deformation delta; ``SolveError`` carries the last state of a failed force
balance so that a failure is reported with what was computed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from lubecontact.model.contact_tables import contact_table
from lubecontact.numerics.cavitation_jfo import JFOSolution
from lubecontact.numerics.control_volume import ControlVolumeMean
from lubecontact.numerics.far_inlet import FarInlet
from lubecontact.numerics.modal_far_inlet import ModalFarInlet
from lubecontact.numerics.mesh import Mesh, build_mesh
from lubecontact.numerics.reynolds import ReynoldsSolution
from lubecontact.numerics.transfer import coarser_mesh
from lubecontact.physics.deformation import ElasticDeformation
from lubecontact.physics.materials import effective_modulus
from lubecontact.physics.percolation import FaceFilm
from lubecontact.physics.rough_surface import RoughContact
from lubecontact.scene import Scene


class SolveError(RuntimeError):
    """The force balance failed; ``state`` is the last state evaluated (or None). A solve
    reports it as ``converged = 0`` with the message in the case notes, never swallowed."""

    def __init__(self, message: str, state: State | None = None):
        super().__init__(message)
        self.state = state


class SqueezeTerm(Protocol):
    """A transient step's time derivative of the film content h_T and the step's stopping
    tests (unsteady/integrator.Squeeze, where each is described)."""

    coefficient: float  # d rate / d h_T, 1/s
    history: np.ndarray  # the BDF history part of the rate, m/s
    film_scale: float  # m, a length on which the force changes
    preconditioner: object  # the one Newton's, kept across a run's steps (monolithic_newton.KeptPreconditioner)

    def rate(self, expected_gap: np.ndarray) -> np.ndarray:
        """dh_T/dt (m/s) at each node for the film content ``expected_gap`` (m)."""

    def settled(self, film: np.ndarray, correction: np.ndarray) -> bool:
        """Whether a film correction (m, per node) meets the step's stopping test."""

    def settled_position(self, displacement: float) -> bool:
        """Whether the displacement (m) that would close the force balance meets it."""

    def settled_pressure(self, residual: float) -> bool:
        """Whether a Reynolds residual (relative to the peak pressure) meets it."""

    def settled_outflow(self, outflow: np.ndarray, cell_area: np.ndarray, film: np.ndarray) -> bool:
        """Whether each cell's outflow left over (m^3/s) meets it."""

    def outflow_scale_floor(self, cell_area: np.ndarray, pressure: float) -> np.ndarray:
        """The smallest scale (m^3/(Pa s)) of a cell's outflow in the Newton's residual."""


class AppliedLoad(Protocol):
    """The force on the cylinder as a function of its position, where it is not the constant
    operating.force: a transient step of a contact with mass and spring (unsteady/dynamics.py)."""

    def force(self, z: float) -> tuple[float, float]:
        """(F, dF/dz) at cylinder position z (m): N and N/m."""


def undeformed_gap(geometry, mesh: Mesh) -> np.ndarray:
    """h_o (ny, nx), m: the cylinder's gap above the flat, R - sqrt(R^2 - x^2) (Eq. 4), plus
    on a crowned cylinder its crown R_c - sqrt(R_c^2 - y^2) along the axis
    (geometry.crown_radius; docs/physics.md section 11, item 8)."""
    radius = geometry.radius
    gap = np.broadcast_to(radius - np.sqrt(radius**2 - mesh.x**2), mesh.shape).copy()
    crown = geometry.crown_radius
    if crown is not None:
        gap += (crown - np.sqrt(crown**2 - mesh.y**2))[:, None]
    return gap


@dataclass
class Model:
    """The sub-models a scene calls for, built once (disabled effects are None / False)."""

    scene: Scene
    mesh: Mesh
    undeformed_gap: np.ndarray  # h_o of Eq. (4), (ny, nx)
    contact: RoughContact | None  # when effects.asperity_contact
    deformation: ElasticDeformation | None  # when effects.elastic_deformation
    hydrodynamic: bool  # Reynolds solved (effect on and speed > 0)
    squeeze: SqueezeTerm | None = None  # a transient step's squeeze term, None for a steady solve
    load: AppliedLoad | None = None  # F(z) of a contact with mass and spring; None: operating.force
    far_inlet: FarInlet | ModalFarInlet | None = None  # the film upstream of the mesh, on a mesh open to it

    @classmethod
    def assemble(cls, scene: Scene, mesh: Mesh | None = None, contact: RoughContact | None = None) -> Model:
        """The model of ``scene`` on its mesh (or on ``mesh``, same domain), reusing the
        rough-contact tables ``contact`` of the same scene when given."""
        effects = scene.effects
        mesh = build_mesh(scene) if mesh is None else mesh
        undeformed = undeformed_gap(scene.geometry, mesh)
        if not effects.asperity_contact:
            contact = None
        elif contact is None:
            contact = contact_table(scene)  # built once per roughness/materials, not per solve
        deformation = None
        if effects.elastic_deformation:
            deformation = ElasticDeformation(mesh, effective_modulus(scene))
        hydrodynamic = bool(effects.hydrodynamics) and scene.operating.speed > 0.0
        far_inlet = None
        if mesh.far_inlet and hydrodynamic:
            exterior = FarInlet if mesh.line else ModalFarInlet
            far_inlet = exterior.on(mesh, scene.geometry.radius, scene.lubricant.viscosity, scene.operating.speed)
        return cls(scene, mesh, undeformed, contact, deformation, hydrodynamic, far_inlet=far_inlet)

    def coarsened(self, coarsest: int) -> Model | None:
        """The same model on the mesh with every other node (same domain) in each direction
        longer than ``coarsest`` nodes; None when there is none, or for a transient step
        (its squeeze history lives on this mesh; it starts from the previous step)."""
        if self.squeeze is not None:
            return None

        coarse = coarser_mesh(self.mesh, coarsest)
        return None if coarse is None else Model.assemble(self.scene, coarse, self.contact)

    @property
    def effects_run(self) -> dict[str, bool]:
        e = self.scene.effects
        return {
            "hydrodynamics": self.hydrodynamic,
            "flow_factors": self.hydrodynamic and self.contact is not None and e.flow_factors,
            "cavitation": self.hydrodynamic and e.cavitation != "none",
            "asperity_contact": self.contact is not None,
            "plasticity": self.contact is not None and e.plasticity,
            "elastic_deformation": self.deformation is not None,
            "alleviation": self.contact is not None and e.alleviation and not e.macro_constriction,
            "macro_constriction": e.macro_constriction,
            "film_conduction": e.film_conduction,
            "tunnelling": e.tunnelling,
        }


@dataclass
class State:
    """Everything at one (z, delta)."""

    z: float
    delta: np.ndarray
    film: np.ndarray  # h, (ny, nx)
    contact_pressure: np.ndarray
    fluid_pressure: np.ndarray
    expected_gap: np.ndarray | None  # h_T used by the fluid
    reynolds: ReynoldsSolution | JFOSolution | None  # the fluid's solution (None without a fluid)
    contact_force: float
    fluid_force: float
    contact_slope: np.ndarray | None = None  # dp_c/dh (Pa/m) of the contact law, <= 0
    flow_coefficient: np.ndarray | None = None  # k used by the fluid, m^3/(Pa s)
    load_gradient: np.ndarray | None = None  # dF/dh_j (N/m), set by balance_force
    # the film on the faces (rough surfaces) and its slopes d/dh_f, as the fluid used them
    # (model/fluid_film.fluid_faces), else None
    faces: FaceFilm | None = None
    face_slopes: FaceFilm | None = None
    # a time step's cells' film content and its slopes (model/fluid_film.squeeze_content), else None
    squeeze_content: ControlVolumeMean | None = None

    @property
    def total_force(self) -> float:
        return self.contact_force + self.fluid_force

    @property
    def total_pressure(self) -> np.ndarray:
        return self.contact_pressure + self.fluid_pressure
