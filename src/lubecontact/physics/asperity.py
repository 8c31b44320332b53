"""One asperity: an elastic-plastic hemisphere on a rigid flat (paper Eqs. 6-10 and 14).

Jackson & Green 2005 (J. Tribol. 127:343) fitted finite-element results of a hemisphere of
radius R (here the asperity radius R_peak) flattened by a rigid flat to an interference
omega. With E* the effective modulus of Eq. (19) and S_y, nu the yield strength and Poisson
ratio of the body that yields first:

- C = 1.295 exp(0.736 nu)                                    (Eq. 10)
- omega_c = (pi C S_y / (2 E*))^2 R                           (Eq. 9)
- P_c = (4/3) (R/E*)^2 (C pi S_y / 2)^3,  A_c = pi R omega_c   (JG 2005, not printed in the paper)
- B = 0.14 exp(23 S_y/E*)                                     (JG 2005, exponent of Eq. 14)

With omega* = omega/omega_c and omega_t* = 1.9:

- omega* <= 1.9: P/P_c = omega*^(3/2)  (Eq. 6, = Hertz (4/3) E* sqrt(R) omega^(3/2))
- omega* >= 1.9: P/P_c = exp(-omega*^(5/12)/4) omega*^(3/2)
                         + 4 H_G/(C S_y) [1 - exp(-omega*^(5/9)/25)] omega*   (Eq. 7)
- contact radius a = sqrt(D omega R), D = 1 below 1.9 omega_c, (omega*/1.9)^B above (Eq. 14);
  contact area pi a^2. The area is continuous at omega* = 1.9; the load is not: the fit
  jumps by -0.75 % there for the paper's Table 1 (a property of the fit, kept as published).

Hardness H_G/S_y (the paper's Eq. 8 is Wadwalkar, Jackson & Kogut 2010):

- ``"wadwalkar"``: 2.84 - 0.92 [1 - cos(pi a/R)] (Eq. 8). It is fitted for moderate a/R and
  decreases to 1.0 at a/R = 1, past which the cosine would rise again: beyond a/R = 1 it is
  held at its a/R = 1 value (1.0), which keeps it finite and non-increasing.
- ``"jg2005"``: 2.84 [1 - exp(-0.82 (a/R)^(-0.7))] (Jackson & Green 2005).

With plasticity switched off the asperity is purely elastic at every interference (Hertz,
the classic Greenwood-Williamson asperity): P = (4/3) E* sqrt(R) omega^(3/2), a = sqrt(R omega).

Every law is vectorised over omega; omega <= 0 (no contact) gives zero load and radius.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lubecontact.physics.materials import effective_modulus, yielding_body

OMEGA_T_STAR = 1.9  # omega_t*: end of the elastic range of Eqs. (6), (7) and (14)
WADWALKAR_MAX_A_OVER_R = 1.0  # Eq. (8) is held at its value here for larger a/R
HARDNESS_MODELS = ("wadwalkar", "jg2005")


def jg_constant(poisson_ratio):
    """C(nu) = 1.295 exp(0.736 nu), Eq. (10)."""
    return 1.295 * np.exp(0.736 * poisson_ratio)


def hardness_ratio(a_over_r, model: str = "wadwalkar"):
    """Hardness over yield strength, H_G/S_y, as a function of a/R (Eq. 8 or JG 2005).

    ``"wadwalkar"`` (Eq. 8) is fitted for moderate a/R; beyond a/R = 1 it is held at its
    a/R = 1 value (1.0). ``"jg2005"`` is defined for every a/R > 0 (2.84 as a/R -> 0).
    """
    a_over_r = np.asarray(a_over_r, dtype=float)
    if model == "wadwalkar":
        clamped = np.minimum(a_over_r, WADWALKAR_MAX_A_OVER_R)
        return 2.84 - 0.92 * (1.0 - np.cos(np.pi * clamped))
    if model == "jg2005":
        with np.errstate(divide="ignore"):  # a/R = 0: (a/R)^-0.7 = inf, H_G/S_y = 2.84 exactly
            return 2.84 * (1.0 - np.exp(-0.82 * a_over_r**-0.7))
    raise ValueError(f"hardness model {model!r} is unknown; allowed: {', '.join(HARDNESS_MODELS)}")


@dataclass(frozen=True)
class Asperity:
    """Jackson-Green (2005) hemispherical asperity, or a Hertzian one if ``plastic`` is False."""

    radius: float  # R_peak, m
    modulus: float  # E* (Eq. 19), Pa
    yield_strength: float  # S_y of the yielding body, Pa
    poisson_ratio: float  # nu of the yielding body (enters C only)
    hardness_model: str = "wadwalkar"
    plastic: bool = True

    def __post_init__(self):
        if self.hardness_model not in HARDNESS_MODELS:
            raise ValueError(
                f"hardness model {self.hardness_model!r} is unknown; allowed: {', '.join(HARDNESS_MODELS)}"
            )

    @classmethod
    def from_scene(cls, scene) -> Asperity:
        body = yielding_body(scene)
        return cls(
            radius=scene.roughness.asperity_radius,
            modulus=effective_modulus(scene),
            yield_strength=body.yield_strength,
            poisson_ratio=body.poisson_ratio,
            hardness_model=scene.roughness.hardness_model,
            plastic=bool(scene.effects.plasticity),
        )

    @property
    def c(self) -> float:
        """C of Eq. (10)."""
        return float(jg_constant(self.poisson_ratio))

    @property
    def critical_interference(self) -> float:
        """omega_c of Eq. (9), m."""
        return (np.pi * self.c * self.yield_strength / (2.0 * self.modulus)) ** 2 * self.radius

    @property
    def critical_load(self) -> float:
        """P_c = (4/3)(R/E*)^2 (C pi S_y/2)^3, N (JG 2005)."""
        return 4.0 / 3.0 * (self.radius / self.modulus) ** 2 * (self.c * np.pi * self.yield_strength / 2.0) ** 3

    @property
    def critical_area(self) -> float:
        """A_c = pi R omega_c, m^2 (JG 2005)."""
        return np.pi * self.radius * self.critical_interference

    @property
    def area_exponent(self) -> float:
        """B = 0.14 exp(23 S_y/E*) of Eq. (14) (JG 2005)."""
        return 0.14 * np.exp(23.0 * self.yield_strength / self.modulus)

    @property
    def transition_interference(self) -> float:
        """omega_t = 1.9 omega_c, m: where Eq. (6) hands over to Eq. (7) (inf if elastic)."""
        return OMEGA_T_STAR * self.critical_interference if self.plastic else np.inf

    @property
    def breakpoints(self) -> tuple[float, ...]:
        """Interferences (m) where P(omega) or a(omega) is not smooth, for quadrature: the
        switch 1.9 omega_c (a kink in a, a jump in P) and, with Eq. (8), where a/R reaches 1
        (a^2 = D omega R = R^2, with D = (omega/omega_t)^B)."""
        if not self.plastic:
            return ()
        omega_t = self.transition_interference
        if self.hardness_model != "wadwalkar":
            return (omega_t,)
        # radius limit: solve a(omega) = R on the branch where it is reached
        omega_r = self.radius if self.radius <= omega_t else (self.radius * omega_t**self.area_exponent) ** (
            1.0 / (1.0 + self.area_exponent)
        )
        return tuple(sorted({omega_t, omega_r}))

    def contact_radius(self, omega):
        """a(omega) of Eq. (14), m; Hertz a = sqrt(R omega) if elastic."""
        w = np.maximum(np.asarray(omega, dtype=float), 0.0)
        if not self.plastic:
            return np.sqrt(self.radius * w)
        ratio = np.maximum(w / self.transition_interference, 1.0)  # omega*/1.9, at least 1
        return np.sqrt(ratio**self.area_exponent * w * self.radius)

    def contact_area(self, omega):
        """pi a^2, m^2 (the area of Eq. 14's radius)."""
        return np.pi * self.contact_radius(omega) ** 2

    def load(self, omega):
        """Contact force P(omega), N: Eq. (6) up to omega* = 1.9, Eq. (7) beyond; Hertz if elastic."""
        w = np.maximum(np.asarray(omega, dtype=float), 0.0)
        if not self.plastic:
            return 4.0 / 3.0 * self.modulus * np.sqrt(self.radius) * w**1.5
        omega_c = self.critical_interference
        ws = w / omega_c
        # Eq. (7) evaluated only on its own range (below it at omega* = 1.9, then discarded)
        wp = np.maximum(ws, OMEGA_T_STAR)
        h_ratio = hardness_ratio(self.contact_radius(wp * omega_c) / self.radius, self.hardness_model)
        plastic = np.exp(-0.25 * wp ** (5.0 / 12.0)) * wp**1.5 + 4.0 * h_ratio / self.c * (
            1.0 - np.exp(-(wp ** (5.0 / 9.0)) / 25.0)
        ) * wp
        return self.critical_load * np.where(ws <= OMEGA_T_STAR, ws**1.5, plastic)
