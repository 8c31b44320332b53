"""A lubricant's viscosity at a temperature from its datasheet (docs/physics.md section 19).

Kinematic viscosity: the ASTM D341 (Walther) relation log10 log10 Z = A - B log10 T, T in
kelvin, Z = nu + 0.7 + exp(-1.47 - 1.84 nu - 0.51 nu^2) with nu in mm^2/s (cSt), fitted
through the two datasheet points (40 C and 100 C), and the standard's inverse of Z.
Density: the API MPMS 11.1 / ASTM D1250 law of the lubricating-oil group (Table 54D, 15 C
base). Dynamic viscosity mu = rho nu.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

KELVIN = 273.15  # 0 C in kelvin
# D341's equations hold down to this kinematic viscosity (mm^2/s) with the exponential term
# (below 0.115 mm^2/s Z < 1 and log10 log10 Z does not even exist).
D341_LOWEST_VISCOSITY = 0.21
# D341 (section 3): the charts stay straight up to about 340 C.
D341_HIGHEST_TEMPERATURE = 340.0
# API MPMS 11.1 lubricating oils, 15 C base: alpha_15 = K1 / rho_15 per C (K0 = 0), i.e.
# K1 = 0.34878 kg/m^3 per F at the 60 F base times 1.8.
LUBE_OIL_K1 = 0.34878 * 1.8
DENSITY_REFERENCE = 15.0  # C: the datasheet's density is at 15 C (ISO 12185, ASTM D4052)
# C: the datasheet's two kinematic viscosities (ISO 3448 grades by the first); below the first
# the Walther line is extrapolated, which D341 supports only above the oil's pour point
DATASHEET_TEMPERATURES = (40.0, 100.0)


def walther_z(nu: float) -> float:
    """ASTM D341's Z of a kinematic viscosity nu (mm^2/s)."""
    return nu + 0.7 + math.exp(-1.47 - 1.84 * nu - 0.51 * nu * nu)


def viscosity_of_z(z: float) -> float:
    """ASTM D341's inverse of ``walther_z``: nu (mm^2/s) of a Z."""
    w = z - 0.7
    return w - math.exp(-0.7487 - 3.295 * w + 0.6119 * w * w - 0.3193 * w**3)


@dataclass(frozen=True)
class WaltherLine:
    """log10 log10 Z = a - b log10 T (T in kelvin): a straight line on D341's chart."""

    a: float
    b: float

    @classmethod
    def through(cls, t1: float, nu1: float, t2: float, nu2: float) -> WaltherLine:
        """The line through (t1, nu1) and (t2, nu2), temperatures in C, nu in mm^2/s."""
        y1, y2 = (math.log10(math.log10(walther_z(nu))) for nu in (nu1, nu2))
        x1, x2 = (math.log10(t + KELVIN) for t in (t1, t2))
        b = (y1 - y2) / (x2 - x1)
        return cls(a=y1 + b * x1, b=b)

    @classmethod
    def of_datasheet(cls, nu_40: float, nu_100: float) -> WaltherLine:
        """The line through a datasheet's two points (DATASHEET_TEMPERATURES), nu in mm^2/s."""
        (low, high) = DATASHEET_TEMPERATURES
        return cls.through(low, nu_40, high, nu_100)

    def kinematic_viscosity(self, t: float) -> float:
        """nu (mm^2/s) at t (C)."""
        return viscosity_of_z(10.0 ** 10.0 ** (self.a - self.b * math.log10(t + KELVIN)))

    def temperature(self, nu: float) -> float:
        """The temperature (C) at which the oil has the kinematic viscosity nu (mm^2/s)."""
        return 10.0 ** ((self.a - math.log10(math.log10(walther_z(nu)))) / self.b) - KELVIN


def density(rho_15: float, t: float) -> float:
    """Density (kg/m^3) at t (C) of a lubricating oil of density rho_15 at 15 C:
    rho_15 exp(-alpha dt (1 + 0.8 alpha dt)), alpha = K1/rho_15, dt = t - 15 C."""
    alpha = LUBE_OIL_K1 / rho_15
    dt = t - DENSITY_REFERENCE
    return rho_15 * math.exp(-alpha * dt * (1.0 + 0.8 * alpha * dt))


def dynamic_viscosity(nu_40: float, nu_100: float, rho_15: float, t: float) -> float:
    """mu (Pa s) at t (C) of an oil with nu_40, nu_100 (mm^2/s) and rho_15 (kg/m^3)."""
    nu = WaltherLine.of_datasheet(nu_40, nu_100).kinematic_viscosity(t)
    return density(rho_15, t) * nu * 1e-6
