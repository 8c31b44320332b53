"""Greenwood-Williamson parameters from spectral moments (McCool 1986, Wear 107:37;
docs/physics.md sections 2 and 18).

    eta = m4 / (6 pi sqrt(3) m2)        summit density, 1/m^2
    R_peak = 0.375 sqrt(pi / m4)        mean summit radius, m
    alpha = m0 m4 / m2^2                Nayak's bandwidth parameter
    sigma = sqrt(m0),   sigma_s^2 = sigma^2 (1 - 0.8968/alpha)

so eta R_peak sigma = 0.02036 sqrt(alpha). Below alpha ~ 2 the summits are not the
well-separated peaks the Greenwood-Williamson picture assumes (``GW_ALPHA_MIN``).

Two rough surfaces in contact act as one whose heights are the sum of both: for
independent surfaces the spectral moments add, m_n = m_n1 + m_n2, so the composite's sigma
is sqrt(sigma1^2 + sigma2^2) and its eta, R_peak and alpha follow from the summed moments.
The shear flow factor needs the split V_ri = sigma_i^2 / sigma^2 (Patir & Cheng 1979).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from lubecontact.surfaces.moments import Moments
from lubecontact.surfaces.reading import SurfaceError

ETA_CONSTANT = 6.0 * math.pi * math.sqrt(3.0)  # eta = m4 / (6 pi sqrt(3) m2)
RADIUS_CONSTANT = 0.375  # R_peak = 0.375 sqrt(pi / m4)
SUMMIT_VARIANCE_FACTOR = 0.8968  # sigma_s^2 = sigma^2 (1 - 0.8968 / alpha)
GW_ALPHA_MIN = 2.0  # below: outside the Greenwood-Williamson picture (docs/physics.md section 18)
ISOTROPY_TOLERANCE = 1.25  # gamma within [1/1.25, 1.25] is reported as isotropic (gamma = 1 flow factors)
# RMS slope sqrt(m2) above which a surface is steeper than 45 degrees on average: the contact
# models (GW, Jackson-Green asperities, Patir-Cheng's flow) are built on gentle slopes (engineering
# surfaces: about 0.01 to 0.3); such a map is often heights and lengths read in different units
STEEPEST_RMS_SLOPE = 1.0


@dataclass(frozen=True)
class McCool:
    """One surface's (or a composite's) roughness parameters, SI units."""

    sigma: float  # m
    asperity_density: float  # eta, 1/m^2
    asperity_radius: float  # R_peak, m
    alpha: float  # 1
    summit_sigma: float  # sigma_s, m (NaN when alpha <= 0.8968)
    moments: Moments

    @property
    def gamma(self) -> float | None:
        return self.moments.gamma

    @property
    def isotropic(self) -> bool | None:
        """gamma within ISOTROPY_TOLERANCE of 1; None for a profile (not measurable)."""
        g = self.gamma
        return None if g is None else 1.0 / ISOTROPY_TOLERANCE <= g <= ISOTROPY_TOLERANCE

    def notes(self) -> list[str]:
        """Where the parameters leave the ground McCool's model stands on."""
        out = []
        if self.alpha < GW_ALPHA_MIN:
            out.append(f"alpha = {self.alpha:.3g} < {GW_ALPHA_MIN:g}: outside the Greenwood-Williamson picture")
        if self.isotropic is False:
            out.append(f"gamma = {self.gamma:.3g}: anisotropic; isotropic (gamma = 1) flow factors do not apply")
        if self.isotropic is None:
            out.append("a profile: isotropy assumed, not measured")
        slope = math.sqrt(self.moments.m2_mean)
        if slope > STEEPEST_RMS_SLOPE:
            out.append(f"RMS slope {slope:.3g} > {STEEPEST_RMS_SLOPE:g} (steeper than 45 degrees on average): outside the "
                       "gentle slopes the contact and flow models assume; check that heights and lengths are in the "
                       "units given (--unit, --size)")
        return out


def _from_moments(m0: float, m2: float, m4: float, moments: Moments) -> McCool:
    alpha = m0 * m4 / m2**2
    summit_var = m0 * (1.0 - SUMMIT_VARIANCE_FACTOR / alpha)
    return McCool(
        sigma=math.sqrt(m0),
        asperity_density=m4 / (ETA_CONSTANT * m2),
        asperity_radius=RADIUS_CONSTANT * math.sqrt(math.pi / m4),
        alpha=alpha,
        summit_sigma=math.sqrt(summit_var) if summit_var > 0 else math.nan,
        moments=moments,
    )


def parameters(moments: Moments) -> McCool:
    """McCool's parameters of one surface (mean of the x and y moments for a map)."""
    return _from_moments(moments.m0, moments.m2_mean, moments.m4_mean, moments)


def composite(first: Moments, second: Moments) -> tuple[McCool, tuple[float, float]]:
    """The composite of two independent surfaces and the sigma split (V_r1, V_r2).

    Both sets of moments must be taken with one cut-off; a profile with a map combines
    along x only (zip keeps the common directions)."""
    if not math.isclose(first.cutoff, second.cutoff, rel_tol=1e-12):
        raise SurfaceError(f"composite: cut-offs {first.cutoff:.4g} m and {second.cutoff:.4g} m differ; take both with one")
    summed = Moments(
        m0=first.m0 + second.m0,
        m2=tuple(a + b for a, b in zip(first.m2, second.m2)),
        m4=tuple(a + b for a, b in zip(first.m4, second.m4)),
        cutoff=first.cutoff,
        window=first.window if first.window == second.window else f"{first.window}+{second.window}",
        sampling=tuple(max(a, b) for a, b in zip(first.sampling, second.sampling)),
        detrending=first.detrending if first.detrending == second.detrending else f"{first.detrending}+{second.detrending}",
    )
    return parameters(summed), (first.m0 / summed.m0, second.m0 / summed.m0)
