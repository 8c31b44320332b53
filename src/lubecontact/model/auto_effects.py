"""``effects: auto``: simulate only the effects a scene calls for (docs/DESIGN.md "Effects").

Every effect of the model is a switch (``scene.effects``) and a disabled effect costs
nothing: :class:`lubecontact.model.solve.Model` builds only what is on. With ``effects: auto``
the switches are set from the scene's dimensionless groups at its operating point, before
anything is solved. An effect is dropped only when an estimate that errs on the safe side
says that contact resistance and friction coefficient change by less than the tolerance
(2 % unless told), shared by all dropped effects (their estimates add up); a resistance
that is astronomically large either way (OPEN_CIRCUIT_RESISTANCE) counts as unchanged.
A wrong drop is worse than a missed saving: every estimate below is a bound, or a fit to
full solves times SAFETY, and the decisions were checked against full solves
(tests/test_effects.py; bench/effects_cost.py on the Fig. 4 grid).

Estimates (w' = F/L, E'_H = 2 E* in Hamrock's convention, u_m = U/2):

- Rigid film: Martin (1916) h_0 = 4.9 mu u_m R/w' (docs/physics.md section 4), and the rigid
  smooth cylinder on the scene's own domain (``film_estimate``): 1D Reynolds with the
  Reynolds exit condition integrated on the truncated inlet (``reynolds_line_load``), and
  for a finite cylinder (ny > 1) the side leakage of Ocvirk's short bearing,
  W_s = (mu U L^3/4)(1/h_0^2 - 1/h_in^2), combined as 1/W = 1/W_long + 1/W_short.
- Isoviscous-elastic film (docs/physics.md section 5: Hamrock's H_min = 3.10 g_E^0.8, Moes
  1992): g_E = W'/sqrt(U'), U' = mu u_m/(E'_H R), W' = w'/(E'_H R); the reference table
  of H_min(g_E) below g_E = 50 (``elastic_film_factor``).
- Hertz line contact (Johnson 1985, Ch. 4; docs/physics.md section 6): b = sqrt(4 w' R/(pi E*)),
  approach of a strip of length L, delta_H = (2 w'/(pi E*))(ln(2L/b) + 1/2); the line
  load's deflection scale delta_w = 2 w'/(pi E*) (Johnson eq. 2.25).
- Rigid dry rough contact (``dry_contact``): the cylinder on the rough law (Eqs. 11-17)
  without fluid or deformation: its separation and m = -d ln R/d ln F (3-5 for Table 1;
  the alleviation near full contact makes R steep in the load).

Decisions (each recorded with its numbers in the reasons):

- hydrodynamics off at U = 0, or when a bound on the fluid's share of the load is small.
  The bound (``fluid_share_bound``) gives the fluid the dry contact's geometry with its
  contact zone widened (DRY_WIDTH_MARGIN) and deepened (DRY_DEPTH_MARGIN, DRY_FILM_MARGIN)
  beyond what elastic dry solves reach, a gap growing from its edge only as the shifted
  parabola (slower than a Hertzian one), the solver's floor h >= 0, no side leakage. The
  fluid's lift only lowers its pressure, so this lies above the coupled share (true share
  <= 0.46 of the bound over 33 varied scenes). Resistance then changes by ~ m x share
  (as seen in solves), friction by <= the share and the Couette shear over mu_b F.
- asperity_contact off (with plasticity, alleviation and flow factors, which then act on
  nothing) only in full film and only where the resistance is astronomical anyway: with
  h_low = FILM_SAFETY x film_estimate (2D elastic films were >= 0.80 of the estimate for
  g_E <= MAX_ELASTICITY; above it the film is not bounded and contact is kept), the rough
  law's far tail bounds the asperity load, F_c <= p_c(h_low) x domain area, and the
  resistance, R >= Psi/(g(h_low) x domain area) > OPEN_CIRCUIT_RESISTANCE. The friction
  change is <= F_c/F and mu_b F_c over Martin's Couette friction. The case then reports
  R = +inf, open circuit.
- elastic_deformation off (a) dry, when the Hertz approach is small against the roughness:
  |dR/R| <~ 0.06 max(m, 4) delta_H/sigma (fit to dry solves, x SAFETY); (b) in smooth full
  film, when the deflection scale is small against the film: |df/f| <~ delta_w/h (fit to
  2D and line solves, x SAFETY). Kept in lubricated rough contacts, whose resistance
  follows the deformed film exponentially (10-60 % in the solves).
- flow_factors off when 1 - phi(Lambda_low) (Eq. 2) times the resistance's sensitivity to the
  film in the Gaussian tail, t Lambda (t of Eq. 12), is within the budget.
- cavitation stays on while the fluid is solved (full Sommerfeld changes its load by O(1)).
- plasticity off when no asperity reaches 1.9 omega_c down to the lowest separation for
  summits up to SUMMIT_REACH standard deviations: Eqs. (6) and (14) are then Hertz exactly.
- alleviation off when Psi(A_r/A_n) at the lowest film is within the budget of 1: the
  resistance changes by at most 1/Psi_min - 1 (Eqs. 16-17).

The estimates take a few milliseconds and one rough-contact table (10-20 ms, cached per
material and roughness; ``auto_effects`` hands it back for the solve to reuse).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubecontact.model.contact_tables import contact_table, memoised
from lubecontact.numerics.mesh import domain_x
from lubecontact.physics.electrical import alleviation_factor, contact_resistance
from lubecontact.physics.film_estimates import (
    MARTIN_FRICTION,
    deflection_scale,
    elastic_film_factor,
    hertz_approach,
    hertz_half_width,
    martin_film,
    reynolds_line_load,
)
from lubecontact.physics.flow_factors import expected_gap, poiseuille_coefficient, pressure_flow_factor
from lubecontact.physics.materials import effective_modulus
from lubecontact.physics.rough_surface import GAUSS_REACH
from lubecontact.physics.shear_factors import couette_shear_factor

DEFAULT_TOLERANCE = 0.02  # relative change of resistance and of friction accepted, all dropped effects together
# A resistance this large is an open circuit for any purpose (connector insulation
# resistance requirements are of order 1e8-1e10 ohm); both runs at or above it agree.
OPEN_CIRCUIT_RESISTANCE = 1.0e12  # ohm
SAFETY = 2.0  # factor on every fitted (not bounding) relation below
FILM_SAFETY = 0.5  # h_low = FILM_SAFETY x film_estimate (films solved were >= 0.80 of it for g_E <= 0.6)
MAX_ELASTICITY = 0.6  # g_E up to which FILM_SAFETY was checked (end closure grows with g_E)
DEFLECTION_FRICTION = 1.0  # smooth full film: |df/f| <= 1.0 delta_w/h (0.2-0.75 seen in 19 solves)
DEFORMATION_SENSITIVITY = 0.06  # dry contact: |dR/R| ~ 0.06 m delta_H/sigma (fit, dry solves)
MIN_LOAD_EXPONENT = 4.0  # m used in that fit is at least this (Table 1: 3-4.8)
DRY_DEPTH_MARGIN = 1.25  # the elastic dry contact reached <= 1.21 x the rigid interpenetration
DRY_WIDTH_MARGIN = 1.25  # its zone of h <= 0 was <= 1.1 x the rigid one (or the Hertz width)
DRY_FILM_MARGIN = 0.25  # ... and its film <= 0.21 sigma below the rigid film (end rows)
SUMMIT_REACH = 6.0  # summit heights beyond 6 standard deviations (a 1e-9 fraction) are ignored
EFFECTS = ("hydrodynamics", "flow_factors", "cavitation", "asperity_contact", "plasticity",
           "elastic_deformation", "alleviation")
_NODES = 501  # points of the 1D quadratures (per clustered region)
_DRY_NODES = 401  # points across the rigid dry contact


# --- 1D estimates ------------------------------------------------------------------------------


def _clustered_grid(x_min: float, x_max: float, centres, scale: float) -> np.ndarray:
    """Nodes on [x_min, x_max]: uniform, plus nodes clustered as c + scale tan(theta) at each centre."""
    theta = np.linspace(-0.5 * np.pi, 0.5 * np.pi, _NODES)[1:-1]
    parts = [np.linspace(x_min, x_max, _NODES)]
    parts += [np.clip(c + scale * np.tan(theta), x_min, x_max) for c in centres]
    return np.unique(np.concatenate(parts))


def film_estimate(scene) -> float:
    """Minimum film (m) of a rigid smooth cylinder carrying F on the scene's domain.

    1D Reynolds (``reynolds_line_load``) on h = h_0 + x^2/2R over [x_min, x_max], so a short
    inlet starves the film as the mesh does; with ny > 1 the side leakage of the short
    bearing (Ocvirk) combined harmonically, 1/W = 1/W_long + 1/W_short. Checked against
    rigid smooth 2D solves: 0.81-0.93 of this on 31 x 21 meshes (it errs thick).
    """
    s = scene
    radius, length, force = s.geometry.radius, s.geometry.length, s.operating.force
    mu, speed = s.lubricant.viscosity, s.operating.speed
    x_min, x_max = domain_x(s, far_inlet=False)

    def load(h0: float) -> float:
        x = _clustered_grid(x_min, x_max, [0.0], math.sqrt(2.0 * radius * h0))
        h = h0 + x**2 / (2.0 * radius)
        w = reynolds_line_load(x, h, h**3 / (12.0 * mu), speed) * length
        if s.mesh.ny > 1:
            h_in = h0 + max(x_min**2, x_max**2) / (2.0 * radius)
            w = 1.0 / (1.0 / w + 1.0 / (0.25 * mu * speed * length**3 * (1.0 / h0**2 - 1.0 / h_in**2)))
        return w

    from scipy.optimize import brentq  # here: scipy.optimize costs ~0.1 s to import

    def excess(log_h: float) -> float:
        return math.log(load(math.exp(log_h)) / force)

    # the film lies within [e^-12, e^0.1] of Martin's (a short domain only thins it), except
    # where the quadrature loses it: films of 1e-18 m (a grease's flowing viscosity of 1e-12
    # Pa s, grease_start.py) carried 6 % more than Martin's load; then bracketed from there
    low, high = math.log(martin_film(s)) - 12.0, math.log(martin_film(s)) + 0.1
    if excess(low) > 0.0 > excess(high):
        return math.exp(brentq(excess, low, high, xtol=1e-4))
    return math.exp(decreasing_root(excess, high, 0.1, 1e-4))


@dataclass(frozen=True)
class OperatingPoint:
    """Film-related groups of a scene sliding at U > 0 (SI; Hamrock's E'_H = 2 E*)."""

    speed_parameter: float  # U' = mu u_m / (E'_H R)
    load_parameter: float  # W' = w' / (E'_H R)
    elasticity: float  # g_E = W' / sqrt(U')
    martin_film: float  # m, rigid infinite cylinder
    elastic_film: float  # m, isoviscous-elastic line contact (Hamrock / reference table)
    film: float  # m, rigid smooth cylinder on the scene's domain (film_estimate)
    deflection_scale: float  # m, delta_w


def operating_point(scene) -> OperatingPoint:
    s = scene
    if not s.operating.speed > 0.0:
        raise ValueError("film groups need a sliding speed > 0")
    e_h = 2.0 * effective_modulus(s)
    radius = s.geometry.radius
    u_prime = s.lubricant.viscosity * 0.5 * s.operating.speed / (e_h * radius)
    w_prime = s.operating.force / s.geometry.length / (e_h * radius)
    g_e = w_prime / math.sqrt(u_prime)
    martin = martin_film(s)
    return OperatingPoint(u_prime, w_prime, g_e, martin, martin * elastic_film_factor(g_e), film_estimate(s),
                          deflection_scale(s))


@dataclass(frozen=True)
class DryContact:
    """Rigid cylinder on the rough law (Eqs. 11-17), no fluid, no macro deformation."""

    separation: float  # m, mean-plane separation at x = 0 (h_min of the rigid dry contact)
    resistance: float  # ohm
    load_exponent: float  # m = -d ln R / d ln F

    def lowest_film(self, sigma: float) -> float:
        """A separation the elastic dry contact (the lowest state of any speed) stays above."""
        return DRY_DEPTH_MARGIN * min(self.separation, 0.0) + max(self.separation, 0.0) - DRY_FILM_MARGIN * sigma


def decreasing_root(f, guess: float, step: float, xtol: float) -> float:
    """Root of the decreasing function f: bracketed from ``guess`` by doubling steps, then Brent."""
    from scipy.optimize import brentq

    a, fa = guess, f(guess)
    for _ in range(200):
        b = a + step if fa > 0.0 else a - step
        fb = f(b)
        if fa * fb <= 0.0:
            return brentq(f, min(a, b), max(a, b), xtol=xtol)
        a, fa, step = b, fb, 2.0 * step
    raise RuntimeError(f"dry contact: no load balance found (last z = {a:.3g} m, load error {fa:.3g} N)")


def dry_contact(scene, contact) -> DryContact:
    """Rigid dry line contact of ``scene`` on its domain with the rough law ``contact``.

    The separation z at x = 0 balances F = L int p_c(x^2/2R + z) dx (a bracketed root, first
    over the whole domain, then again on nodes concentrated on the contact zone).
    """
    radius, length, force = scene.geometry.radius, scene.geometry.length, scene.operating.force
    x_min, x_max = domain_x(scene, far_inlet=False)
    sigma = contact.sigma

    def balance(x, load, guess, step):
        gap = x**2 / (2.0 * radius)
        weight = np.gradient(x) * length  # nodal areas of the line, m^2
        z = decreasing_root(lambda z: float(np.sum(contact.pressure(gap + z) * weight)) - load, guess, step, 1e-9 * sigma)
        return z, gap + z, weight

    z, _, _ = balance(np.linspace(x_min, x_max, _DRY_NODES), force, 0.0, sigma)
    reach = math.sqrt(2.0 * radius * max(contact.y_s + GAUSS_REACH * contact.height_std - z, sigma))
    x = np.linspace(max(x_min, -reach), min(x_max, reach), _DRY_NODES)

    guess = z

    def resistance(load):
        z, h, weight = balance(x, load, guess, 0.01 * sigma)
        return z, contact_resistance(contact.log_conductance(h), contact.area_fraction(h), weight,
                                     scene.effects.alleviation)[0]

    step = 0.01
    (z, r0), (_, r1) = resistance(force), resistance(force * (1.0 + step))
    return DryContact(z, r0, -math.log(r1 / r0) / math.log1p(step))


def fluid_share_bound(scene, dry: DryContact, sigma: float) -> tuple[float, float]:
    """(fluid load / F, Couette shear / F), bounds from above at the scene's speed.

    The fluid is given a land of half-width a = DRY_WIDTH_MARGIN x max(rigid dry contact
    half-width, Hertz b) at the film max(dry.lowest_film, 0) (the solver floors the fluid's
    film at h = 0), and beyond it the gap (|x| - a)^2/2R, which opens more slowly than the
    gap around a flattened contact; the scene's flow model (Patir-Cheng expected gap and flow
    factors, Eqs. 1-2); 1D Reynolds with the Reynolds exit condition (no side leakage); the
    Couette shear mu U phi_f/h of Patir & Cheng (1979) as the solver's friction.
    """
    s = scene
    radius, length, force = s.geometry.radius, s.geometry.length, s.operating.force
    mu, speed = s.lubricant.viscosity, s.operating.speed
    x_min, x_max = domain_x(s, far_inlet=False)
    land = DRY_WIDTH_MARGIN * max(math.sqrt(2.0 * radius * max(-dry.separation, 0.0)), hertz_half_width(s))
    x = _clustered_grid(x_min, x_max, [-land, land], math.sqrt(2.0 * radius * sigma))
    film = max(dry.lowest_film(sigma), 0.0) + np.maximum(np.abs(x) - land, 0.0) ** 2 / (2.0 * radius)
    h_t = expected_gap(film, sigma)
    k = poiseuille_coefficient(film, sigma, mu, flow_factors=s.effects.flow_factors)
    load = reynolds_line_load(x, h_t, k, speed) * length
    shear = float(np.trapezoid(mu * speed * couette_shear_factor(film / sigma) / sigma, x)) * length  # as friction.py
    return load / force, shear / force


# --- decisions -----------------------------------------------------------------------------


def _dry_state(full, contact) -> tuple[DryContact, float, float]:
    """(dry_contact, fluid share and shear bounds per unit mu U) of an all-effects scene: the
    fluid's pressure and shear on a fixed geometry are proportional to mu U (Eq. 1)."""

    def build():
        dry = dry_contact(full, contact)
        unit = full.replace({"operating.speed": 1.0})
        share, shear = fluid_share_bound(unit, dry, contact.sigma)
        return dry, share / unit.lubricant.viscosity, shear / unit.lubricant.viscosity

    s = full
    key = ("dry", s.geometry, s.cylinder, s.block, s.roughness, s.operating.force, s.mesh.x_min, s.mesh.x_max)
    return memoised(key, build)


@dataclass(frozen=True)
class AutoEffects:
    """The concrete scene, one reason per effect, and the rough-contact table built on the
    way (valid for the concrete scene; None if asperity contact is off or rebuilt elastic)."""

    scene: object
    reasons: dict
    contact: object | None


def _pct(x: float) -> str:
    return f"{100.0 * x:.2g} %"


class _Budget:
    """The tolerance shared by all dropped effects: their estimated changes of resistance
    and friction add up to at most ``tolerance`` each."""

    def __init__(self, tolerance: float):
        self.tolerance = tolerance
        self.resistance = self.friction = 0.0

    def take(self, resistance: float, friction: float) -> bool:
        fits = (self.resistance + resistance <= self.tolerance and self.friction + friction <= self.tolerance)
        if fits:
            self.resistance += resistance
            self.friction += friction
        return fits


def _verdict(on: bool, detail: str) -> str:
    return ("on: " if on else "off: ") + detail


def auto_effects(scene, tolerance: float = DEFAULT_TOLERANCE) -> AutoEffects:
    """Decide the effects of ``scene`` at its operating point, starting from all effects on
    (the scene's own flags are not consulted: it is meant for ``effects: auto``)."""
    if not 0.0 < tolerance < 1.0:
        raise ValueError(f"tolerance must be in (0, 1), got {tolerance!r}")
    full = scene.replace({"effects": dict.fromkeys(EFFECTS, True)})
    speed, force = full.operating.speed, full.operating.force
    mu, mu_b = full.lubricant.viscosity, full.interface.boundary_friction
    contact = contact_table(full)
    sigma = contact.sigma
    dry, share_per_mu_u, shear_per_mu_u = _dry_state(full, contact)
    m = dry.load_exponent
    x_min, x_max = domain_x(full, far_inlet=False)
    domain_area = (x_max - x_min) * full.geometry.length
    budget = _Budget(tolerance)
    on = dict.fromkeys(EFFECTS, True)
    why = {}

    # hydrodynamics: nothing to solve at rest; negligible fluid share at low speed
    if speed == 0.0:
        on["hydrodynamics"] = False
        why["hydrodynamics"] = "off: speed 0, no hydrodynamic pressure (the Reynolds source U/2 dh_T/dx vanishes)"
    else:
        share, shear = share_per_mu_u * mu * speed, shear_per_mu_u * mu * speed
        if share >= 1.0:
            why["hydrodynamics"] = f"on: the fluid can carry the load (bound on its share on the dry geometry {share:.3g})"
        else:
            d_friction = max(share, shear / mu_b) if mu_b > 0.0 else math.inf
            on["hydrodynamics"] = not budget.take(m * share, d_friction)
            why["hydrodynamics"] = _verdict(on["hydrodynamics"], (
                f"fluid load share <= {share:.3g} (fluid on the dry contact's geometry); resistance change "
                f"~ m x share = {m:.3g} x {share:.3g} = {_pct(m * share)}, friction change <= {_pct(d_friction)}"))
    hydro = on["hydrodynamics"]

    # the lowest film: the dry contact bounds every speed; in full film the fluid's own estimate
    point = operating_point(full) if hydro else None
    lowest = dry.lowest_film(sigma)
    film_known = hydro and point.elasticity <= MAX_ELASTICITY
    if film_known:
        lowest = max(lowest, FILM_SAFETY * point.film)
    lam_low = lowest / sigma
    groups = "" if not hydro else (
        f"Lambda = h/sigma = {point.martin_film / sigma:.3g} (rigid Martin), {point.elastic_film / sigma:.3g} "
        f"(isoviscous-elastic, g_E = {point.elasticity:.3g}), {point.film / sigma:.3g} (rigid, on the mesh "
        f"domain); lower estimate {lam_low:.3g}")

    # asperity contact: only in full film, with a film bounded from below
    if not hydro:
        why["asperity_contact"] = f"on: it carries the load of a dry contact (lowest h/sigma {lam_low:.3g})"
    elif not film_known:
        why["asperity_contact"] = (f"on: {groups}; g_E > {MAX_ELASTICITY:g}: the elastic film is not bounded from "
                                   f"below, or the fluid cannot carry the load")
    else:
        load = float(contact.pressure(lowest)) * domain_area  # p_c is largest at the lowest film
        log_r = (math.log(float(alleviation_factor(contact.area_fraction(lowest))[0]))
                 - float(contact.log_conductance(lowest)) - math.log(domain_area))
        # Couette friction of the full film at the thicker film estimate (a lower bound, halved)
        thick = max(point.elastic_film, point.film)
        fluid_friction = (MARTIN_FRICTION * mu * 0.5 * speed * math.sqrt(2.0 * full.geometry.radius / thick)
                          * full.geometry.length / force) / SAFETY
        d_friction = max(load / force, mu_b * load / (force * fluid_friction))
        open_circuit = log_r > math.log(OPEN_CIRCUIT_RESISTANCE)
        on["asperity_contact"] = not (open_circuit and budget.take(0.0, d_friction))
        why["asperity_contact"] = _verdict(on["asperity_contact"], (
            f"{groups}; asperity load <= p_c(h_low) x domain area = {load:.3g} N, friction change <= "
            f"{_pct(d_friction)}; resistance >= {math.exp(min(log_r, 700.0)):.3g} ohm"
            + ("" if on["asperity_contact"] else
               f" >= {OPEN_CIRCUIT_RESISTANCE:.0e} ohm: open circuit either way (the case reports R = +inf)")))
    contact_on = on["asperity_contact"]

    # elastic deformation: dry and stiff against the roughness, or smooth and stiff against the film
    if not hydro:
        approach = hertz_approach(full)
        d_resistance = SAFETY * DEFORMATION_SENSITIVITY * max(m, MIN_LOAD_EXPONENT) * approach / sigma
        on["elastic_deformation"] = not budget.take(d_resistance, 0.0)
        why["elastic_deformation"] = _verdict(on["elastic_deformation"], (
            f"dry: Hertz approach {approach:.3g} m = {approach / sigma:.3g} sigma, "
            f"resistance change <~ {_pct(d_resistance)}"))
    elif not contact_on:
        ratio = point.deflection_scale / point.film
        d_friction = SAFETY * DEFLECTION_FRICTION * ratio
        on["elastic_deformation"] = not budget.take(0.0, d_friction)
        why["elastic_deformation"] = _verdict(on["elastic_deformation"], (
            f"smooth full film, g_E = {point.elasticity:.3g}, deflection scale 2w'/(pi E*) = {ratio:.3g} x film: "
            f"friction change <~ {_pct(d_friction)}"))
    else:
        why["elastic_deformation"] = "on: lubricated rough contact, the resistance follows the deformed film exponentially"

    # flow factors and cavitation act on a fluid (flow factors only between rough surfaces)
    if not hydro:
        on["flow_factors"] = on["cavitation"] = False
        why["flow_factors"] = why["cavitation"] = "off: moot, hydrodynamics off"
    else:
        why["cavitation"] = "on: the fluid is solved (full Sommerfeld changes its load by O(1))"
        if not contact_on:
            on["flow_factors"] = False
            why["flow_factors"] = "off: moot, smooth surfaces (asperity_contact off) have phi = 1"
        else:
            t_low = (lowest - contact.y_s) / contact.height_std
            deficit = 1.0 - float(pressure_flow_factor(max(lam_low, 0.0)))
            d_resistance = deficit * max(1.0, t_low * lam_low)
            on["flow_factors"] = not budget.take(d_resistance, deficit)
            why["flow_factors"] = _verdict(on["flow_factors"], (
                f"1 - phi(Lambda_low = {lam_low:.3g}) = {deficit:.3g}; resistance change <~ t Lambda (1 - phi) = "
                f"{_pct(d_resistance)}"))

    # plasticity and alleviation act on the asperity contact
    if not contact_on:
        on["plasticity"] = on["alleviation"] = False
        why["plasticity"] = why["alleviation"] = "off: moot, asperity_contact off"
    else:
        deepest = SUMMIT_REACH * contact.height_std + contact.y_s - lowest  # largest interference, m
        onset = contact.asperity.transition_interference
        on["plasticity"] = deepest > onset  # below 1.9 omega_c Eqs. (6), (14) are Hertz: no change at all
        why["plasticity"] = _verdict(on["plasticity"], (
            f"deepest asperity interference {deepest:.3g} m against 1.9 omega_c = {onset:.3g} m"))
        psi = float(alleviation_factor(contact.area_fraction(lowest))[0])
        on["alleviation"] = not budget.take(1.0 / psi - 1.0, 0.0)
        why["alleviation"] = _verdict(on["alleviation"], (
            f"Psi at the lowest film = {psi:.3g}: resistance change <= 1/Psi - 1 = {_pct(1.0 / psi - 1.0)}"))

    concrete = scene.replace({"effects": on})
    reusable = contact if contact_on and on["plasticity"] else None
    return AutoEffects(concrete, {name: why[name] for name in EFFECTS}, reusable)


def resolve_auto_effects(scene, tolerance: float = DEFAULT_TOLERANCE):
    """(scene with concrete effects, reasons: effect -> "on: ..."/"off: ..." with its numbers)."""
    decided = auto_effects(scene, tolerance)
    return decided.scene, decided.reasons
