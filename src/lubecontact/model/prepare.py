"""What a scene becomes before anything is solved, the same for a steady solve and a
transient: with ``effects: auto`` the switches decided from the scene's dimensionless
groups (model/auto_effects.py), with the rough-contact table the decision built so that
the solve reuses it, and the decision's reasons for the case notes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lubecontact.model.auto_effects import auto_effects


@dataclass(frozen=True)
class Prepared:
    """The concrete scene (no ``auto`` left), the rough-contact table built on the way
    (None: the model builds or looks it up itself) and notes for the case."""

    scene: object
    contact: object | None = None
    notes: list[str] = field(default_factory=list)


def prepare(scene) -> Prepared:
    """The scene as it will be solved: ``effects: auto`` decided, anything else unchanged."""
    if not scene.effects.auto:
        return Prepared(scene)
    decided = auto_effects(scene)
    reasons = "; ".join(f"{k}: {v}" for k, v in decided.reasons.items())
    return Prepared(decided.scene, decided.contact, [f"effects: auto -> {reasons}"])
