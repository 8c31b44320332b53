"""Material combinations of the two bodies (cylinder and block).

The paper (Eq. 19) combines the two elastic bodies into one effective modulus,
1/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2. This is Johnson's E* convention, used both
in the Jackson-Green asperity law and in the macro deformation (23.78 GPa for Table 1).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class YieldingBody:
    """The body that yields first: smaller yield strength, with its own Poisson ratio
    (Jackson-Green's C(nu) uses the Poisson ratio of the yielding body)."""

    yield_strength: float  # Pa
    poisson_ratio: float  # 1


def effective_modulus(scene) -> float:
    """E* of Eq. (19) in Pa."""
    c, b = scene.cylinder, scene.block
    return 1.0 / ((1.0 - c.poisson_ratio**2) / c.youngs_modulus + (1.0 - b.poisson_ratio**2) / b.youngs_modulus)


def yielding_body(scene) -> YieldingBody:
    """The softer of the two bodies in yield (JG 2005 with dissimilar materials)."""
    softer = min((scene.cylinder, scene.block), key=lambda m: m.yield_strength)
    return YieldingBody(softer.yield_strength, softer.poisson_ratio)


def spot_conductance_factor(scene) -> float:
    """Holm conductance of one circular spot of radius a is factor * a, in S/m.

    Two half-spaces of resistivities rho1, rho2 in series: R = (rho1 + rho2)/(4a),
    so the factor is 4/(rho1 + rho2) (= 2/rho for one material, Eq. 15).
    """
    return 4.0 / (scene.cylinder.resistivity + scene.block.resistivity)
