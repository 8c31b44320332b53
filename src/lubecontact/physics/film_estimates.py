"""Closed-form film and contact estimates of a smooth or rough cylinder (docs/physics.md
sections 4-6): Martin's rigid film, the isoviscous-elastic film of Hamrock and Moes, the
Hertz line contact (half-width, approach, deflection scale), and the 1-D Reynolds line
load with the Reynolds exit condition. Used to size the mesh, to decide effects and to
judge the inlet.
"""

from __future__ import annotations

import math

import numpy as np

from lubecontact.physics.materials import effective_modulus
from lubecontact.physics.yield_stress_flow import flowing_viscosity, lubricant_law

MARTIN = 4.9  # Martin (1916) with the Reynolds exit condition: w' h0 / (mu u_m R) (4.895)

# Hamrock's isoviscous-elastic line-contact film beyond the reference table: H_min = 3.10 g_E^0.8
HAMROCK_COEFFICIENT, HAMROCK_EXPONENT = 3.10, 0.8


MARTIN_FRICTION = 7.283  # its Couette friction on the plane over the full film: F' / (mu u_m sqrt(2R/h0))


# docs/physics.md section 5: H_min = (h_min/R)(W'/U') of the isoviscous-elastic line contact
# (team reference solver, Reynolds condition), -> 3.10 g_E^0.8 (Hamrock) for g_E >= 20.
EI_G = np.array([0.324, 0.5, 0.75, 1.03, 2.0, 3.24, 5.0, 10.0, 20.0, 50.0])


EI_H = np.array([4.97, 5.08, 5.28, 5.59, 7.08, 9.35, 12.5, 20.5, 34.6, 70.7])


def _cumulative_trapezoid(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    """scipy.integrate.cumulative_trapezoid(y, x, initial=0.0) of 1-D arrays, the same
    operations (numpy only: importing scipy.integrate costs ~0.1 s at start-up)."""
    return np.concatenate([[0.0], np.cumsum(np.diff(x) * (y[1:] + y[:-1]) / 2.0)])


def reynolds_line_load(x, expected_gap, coefficient, speed: float) -> float:
    """Fluid load per unit length (N/m) of the 1D Reynolds equation (Eq. 1, no side leakage)
    d/dx(k dp/dx) = (U/2) dh_T/dx with p = 0 at the inlet x[0] and the Reynolds exit
    condition p = dp/dx = 0 (or p = 0 at x[-1] if the film does not rupture before).

    With the flux q: p(x) = int (U h_T/2 - q)/k dx; the exit x_e is the first root of
    G(x) = int (U h_T/2)/k - (U h_T(x)/2) int 1/k after the narrowest gap, q = U h_T(x_e)/2
    (h_T(x_e) interpolated linearly between the nodes around the root).
    """
    a = _cumulative_trapezoid(0.5 * speed * expected_gap / coefficient, x)
    b = _cumulative_trapezoid(1.0 / coefficient, x)
    narrowest = int(np.argmin(expected_gap))
    g = a - 0.5 * speed * expected_gap * b
    ruptured = np.flatnonzero(g[narrowest:] <= 0.0)
    if ruptured.size:
        exit_ = narrowest + int(ruptured[0])
        before = max(exit_ - 1, 0)  # the root of g lies between these nodes: interpolate h_T*
        weight = g[before] / (g[before] - g[exit_]) if g[before] > g[exit_] else 1.0
        flux = 0.5 * speed * (expected_gap[before] + weight * (expected_gap[exit_] - expected_gap[before]))
        p = np.where(np.arange(x.size) < exit_, a - flux * b, 0.0)
    else:
        p = a - (a[-1] / b[-1]) * b
    return float(np.trapezoid(np.maximum(p, 0.0), x))


def martin_film(scene) -> float:
    """Rigid infinite-cylinder film h_0 = 4.9 mu (U/2) R L / F, m (Martin 1916; docs/physics.md section 4)."""
    s = scene
    return MARTIN * s.lubricant.viscosity * 0.5 * s.operating.speed * s.geometry.radius * s.geometry.length / s.operating.force


def entrained_film(scene) -> float:
    """Martin's film (m) of the scene's lubricant (martin_film); a grease's at its flowing
    viscosity, the apparent viscosity at its own film's shear rate
    (yield_stress_flow.flowing_viscosity; docs/physics.md section 21, "Its cold start"), else at
    its consistency where the yield stress alone would carry any film. Taken at the consistency
    K = 0.5 Pa s^n, a shear-thinning grease's (n = 0.7, tau_y = 300 Pa, Table 1 at 1 m/s) was
    2.45 um against the 19 nm of its line, and the automatic inlet it sized reached 4.4 mm."""
    martin = martin_film(scene)
    law = lubricant_law(scene.lubricant)
    if law is None or scene.operating.speed == 0.0:
        return martin
    viscosity = flowing_viscosity(lambda mu: martin * mu / law.consistency, scene.operating.speed, law)
    return martin if viscosity is None else martin * viscosity / law.consistency


def elastic_film_factor(g_e: float) -> float:
    """H_min(g_E)/4.9: isoviscous-elastic over rigid line-contact film (docs/physics.md section 5).

    Interpolated (log-log) in the reference table, Hamrock's 3.10 g_E^0.8 beyond g_E = 50,
    and the table's first value (1.4 % above rigid) below g_E = 0.324.
    """
    if g_e > EI_G[-1]:
        h = HAMROCK_COEFFICIENT * g_e**HAMROCK_EXPONENT
    else:
        h = math.exp(np.interp(math.log(max(g_e, EI_G[0])), np.log(EI_G), np.log(EI_H)))
    return h / MARTIN


def deflection_scale(scene) -> float:
    """delta_w = 2 w'/(pi E*), m: the deflection per unit log distance of a line load
    (Johnson 1985, eq. 2.25), the scale on which the film is deformed."""
    return 2.0 * scene.operating.force / scene.geometry.length / (math.pi * effective_modulus(scene))


def hertz_approach(scene) -> float:
    """Approach of a Hertzian strip of length L, (2 w'/(pi E*))(ln(2L/b) + 1/2), m
    (docs/physics.md section 6; the datum of lubecontact.physics.deformation's line mode)."""
    return deflection_scale(scene) * (math.log(2.0 * scene.geometry.length / hertz_half_width(scene)) + 0.5)


def hertz_half_width(scene) -> float:
    """Hertz line-contact half-width b = sqrt(4 w' R / (pi E*)), w' = F/L (Johnson 4.43)."""
    load_per_length = scene.operating.force / scene.geometry.length
    return float(np.sqrt(4.0 * load_per_length * scene.geometry.radius / (np.pi * effective_modulus(scene))))


def complete_elliptic_integrals(m: float) -> tuple[float, float]:
    """(K(m), E(m)), the complete elliptic integrals of the first and second kind of
    parameter m = e^2 < 1, by the arithmetic-geometric mean (Abramowitz and Stegun 17.6):
    K = pi / (2 a_N), E = K (1 - sum 2^(n-1) c_n^2), c_0^2 = m. Hand-written, in numpy, for
    the mesh and the scene checks, which load no scipy (tests/test_startup.py); held to
    scipy.special.ellipk and ellipe in tests/test_dry_contact.py."""
    a, b, c2 = 1.0, math.sqrt(1.0 - m), m
    total, weight = 0.5 * c2, 0.5
    while True:
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        weight *= 2.0
        total += weight * c * c
        if c * c <= 1e-17 * a * a:
            break
    k = math.pi / (2.0 * a)
    return k, k * (1.0 - total)


def hertz_ellipse(force: float, radius_x: float, radius_y: float, modulus: float) -> tuple[float, float]:
    """Semi-axes (along x, along y) of the Hertz contact of a body with principal radii
    radius_x, radius_y on a flat under ``force``, E* = ``modulus`` (Johnson 1985, section 4.2):
    with the major semi-axis a along the larger radius R_1, the minor b = a sqrt(1 - e^2), the
    eccentricity e solves R_1/R_2 = [E(e)/(1 - e^2) - K(e)] / [K(e) - E(e)] (K, E the complete
    elliptic integrals, complete_elliptic_integrals; bisected in ln(1 - e^2), where the ratio
    rises monotonically from 1) and a^3 = 3 F R_1 (K - E) / (pi E* e^2); a circle of radius
    (3 F R / (4 E*))^(1/3) where the radii are equal."""
    big, small = max(radius_x, radius_y), min(radius_x, radius_y)
    if big == small:
        radius = (3.0 * force * big / (4.0 * modulus)) ** (1.0 / 3.0)
        return radius, radius

    def ratio(m):
        k, e = complete_elliptic_integrals(m)
        return (e / (1.0 - m) - k) / (k - e)

    low, high = 1e-12, 60.0  # -ln(1 - e^2): e^2 from 1e-12 to 1 - 9e-27
    for _ in range(100):  # 60 / 2^100: far below round-off
        middle = 0.5 * (low + high)
        if ratio(-math.expm1(-middle)) < big / small:
            low = middle
        else:
            high = middle
    m = -math.expm1(-0.5 * (low + high))
    k, e = complete_elliptic_integrals(m)
    major = (3.0 * force * big * (k - e) / (math.pi * modulus * m)) ** (1.0 / 3.0)
    minor = major * math.sqrt(1.0 - m)
    return (minor, major) if radius_y > radius_x else (major, minor)


def contact_half_width(scene) -> float:
    """Half-width along x of the dry Hertz contact: the line contact's (hertz_half_width),
    or for a crowned cylinder (geometry.crown_radius) the larger of that and its Hertz
    ellipse's semi-axis along x (hertz_ellipse), which concentrates the load on a shorter
    length where the ellipse is shorter than the cylinder."""
    line = hertz_half_width(scene)
    crown = scene.geometry.crown_radius
    if crown is None:
        return line
    along_x, _ = hertz_ellipse(scene.operating.force, scene.geometry.radius, crown, effective_modulus(scene))
    return max(line, along_x)
