"""The whole electrical path of one operating point (docs/DESIGN.md "Electrical path").

Per nominal area the interface conducts through the metal spots, g_s (Eq. 15), and, with
``film_conduction`` / ``tunnelling`` on, through the film, g_f (:mod:`.film`); the two are
in parallel. The current then crowds from the bodies into the conducting patch: with
``macro_constriction`` on, Greenwood's cluster term R_macro of the whole conductance
g = g_s + g_f (:mod:`.cluster`) is in series:

    contact_resistance = 1/(1/spot_resistance + 1/film_resistance) + macro_constriction_resistance.

Greenwood's first-order picture treats every conducting element, spot or film, alike: it
takes the flux through each element proportional to its own conductance, so the cluster
term of the combined g follows from the same pair sum.

Cluster term and Cooper's alleviation Psi (no double counting). Psi (Eq. 16) is the
crowding of a spot's current by its neighbours within one node (Cooper, Mikic &
Yovanovich 1969: each spot in its own flux tube). Greenwood's sum over i != j contains
the interaction of *every* pair of spots, neighbours within a node included: the
continuum double integral runs over all cell pairs, the self-cell included (see
:mod:`.cluster`). Psi is a flux-tube model (a regular array of spots, each in its own
tube) of the very interaction the pair sum holds directly, so applying both counts the
neighbours twice. With
``macro_constriction`` on, the spot term is therefore Greenwood's first term, the spots in
parallel without Psi (``effects.alleviation`` then has no effect, said in the notes), and
the A_r/A_n clamp of Psi (spots.MAX_AREA_FRACTION) no longer enters the answer.
As A_r/A_n -> 1 the result tends to the constriction of the whole patch, not to zero.

``open_circuit`` is decided by the user's circuit, not by the model: the contact counts as
open when contact_resistance > ``interface.open_resistance`` (docs/physics.md section 13).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubecontact.physics.electrical.cluster import ClusterOperator, macro_constriction_resistance
from lubecontact.physics.electrical.film import film_log_conductance
from lubecontact.physics.electrical.spots import contact_resistance
from lubecontact.physics.flow_factors import expected_gap

# the output variables this module decides, in the order of the case's scalars
OUTPUTS = ("spot_resistance", "macro_constriction_resistance", "film_resistance", "contact_resistance")


@dataclass(frozen=True)
class ElectricalPath:
    """The parts of the path (ohm), the Psi-clamped node count and what the notes must say."""

    spot_resistance: float  # metal spots in parallel (with Psi when the cluster term is off)
    macro_constriction_resistance: float  # Greenwood's cluster term; 0.0 when off
    film_resistance: float  # the film in parallel over the domain; +inf when it does not conduct
    contact_resistance: float  # the whole path
    clamped_nodes: int
    notes: tuple[str, ...] = ()

    def scalars(self, open_resistance: float) -> dict:
        """The case scalars this path decides, ``open_circuit`` included."""
        values = {name: getattr(self, name) for name in OUTPUTS}
        values["clamped_nodes"] = self.clamped_nodes
        values["open_circuit"] = int(self.contact_resistance > open_resistance)
        return values


def _parallel(a: float, b: float) -> float:
    """a and b (ohm, each in [0, inf]) in parallel."""
    if a == 0.0 or b == 0.0:
        return 0.0
    if math.isinf(a) or math.isinf(b):  # exact: the paper's insulating film leaves R bit for bit
        return min(a, b)
    conductance = 1.0 / a + 1.0 / b
    return math.inf if conductance == 0.0 else 1.0 / conductance


def film_thickness(scene, contact, film) -> np.ndarray:
    """Thickness (m) of the conducting film: h_T of max(h, 0) between rough surfaces (see
    :mod:`.film`), h itself between smooth ones (positive wherever a smooth film carries load)."""
    if contact is None:
        return np.maximum(film, np.finfo(float).tiny)
    return expected_gap(np.maximum(film, 0.0), contact.sigma)


def electrical_path(scene, mesh, contact, film) -> ElectricalPath:
    """The path of ``scene`` on ``mesh`` with the mean-plane separation ``film`` (m, (ny, nx))
    and the rough-contact law ``contact`` (RoughContact, None without asperity contact)."""
    effects = scene.effects
    area = mesh.nodal_area
    notes = []
    if contact is not None:
        log_g = contact.log_conductance(film)
        area_fraction = contact.area_fraction(film)
    else:
        log_g, area_fraction = np.full(mesh.shape, -np.inf), np.zeros(mesh.shape)
    use_psi = effects.alleviation and not effects.macro_constriction
    if effects.alleviation and effects.macro_constriction and contact is not None:
        notes.append("alleviation: Psi not applied, the cluster constriction (macro_constriction) holds the "
                     "spot interactions it stands for")
    spot, clamped = contact_resistance(log_g, area_fraction, area, use_psi)

    log_film = np.full(mesh.shape, -np.inf)
    if effects.film_conduction or effects.tunnelling:
        log_film = film_log_conductance(
            film_thickness(scene, contact, film),
            1.0 - np.minimum(area_fraction, 1.0),
            scene.lubricant.resistivity if effects.film_conduction else None,
            scene.interface.barrier_height if effects.tunnelling else None,
        )
    film_resistance = contact_resistance(log_film, 0.0, area, False)[0]

    macro = 0.0
    if effects.macro_constriction:
        rho = 0.5 * (scene.cylinder.resistivity + scene.block.resistivity)
        macro = macro_constriction_resistance(ClusterOperator(mesh), np.logaddexp(log_g, log_film), rho)
    total = _parallel(spot, film_resistance) + macro  # macro is +inf only where nothing conducts
    return ElectricalPath(spot, macro, film_resistance, total, int(clamped), tuple(notes))
