"""Pressure flow of a yield-stress lubricant (a grease) through a plane slot
(docs/physics.md section 21).

A slot of thickness h carries a pressure gradient G (Pa/m) along x. The momentum balance
of the slot, dtau/dy = G, gives the shear stress tau(y) = G y linear across it (y = 0 on
the mid-plane), |tau| <= tau_w = |G| h/2 at the walls. Where |tau| < tau_y the material
does not yield: a plug fills |y| < y_0 = tau_y/|G|. With xi = tau_y/tau_w = 2 tau_y/(|G| h)
and no slip at the walls, the flux per unit width (integrated by parts,
Q = 2 int_0^{h/2} y gamma_dot(tau(y)) dy) is

    Newtonian          q = -h^3 G/(12 mu)
    Bingham            q = -h^3 G/(12 mu) (1 - 3 xi/2 + xi^3/2)  for xi < 1, else 0
                       (Buckingham-Reiner for the plane slot; Bird, Dai & Yarusso 1983,
                       Rev. Chem. Eng. 1:1, table for slit flow)
    Herschel-Bulkley   |q| = 2/(G^2 K^m) [S^(m+2)/(m+2) + tau_y S^(m+1)/(m+1)],
                       S = tau_w - tau_y > 0, m = 1/n, else 0
                       (gamma_dot = ((|tau| - tau_y)/K)^(1/n) above the yield stress,
                       substituting s = |G| y - tau_y: derived here, and checked against a
                       quadrature of the velocity profile in tests/test_yield_stress_flow.py;
                       the slit flows of Bird, Dai & Yarusso's review are of this form),

with n = 1, K = mu giving Bingham back: (1 - xi)^2 (2 + xi)/6 = (1 - 3 xi/2 + xi^3/2)/3.

Regularisation (bi-viscous law, O'Donovan & Tanner 1984, J. Non-Newt. Fluid Mech. 15:75):
below the yield stress the material creeps with the creep viscosity mu_c, so that the
shear rate is that of the model plus min(|tau|, tau_y)/mu_c. The creep flux adds to the
model's, in closed form:

    q_c = -h^3 G/(12 mu_c) c(xi),   c = 1 for xi >= 1,  c = (3 xi - xi^3)/2 for xi < 1,

continuous with a continuous slope at xi = 1, so the flux is C^1 in G and h and a Newton
solver stays smooth; for Bingham q = -h^3 G/(12 mu) [1 - c + (mu/mu_c) c]. As mu_c -> oo
the bi-viscous flux tends to Bingham's; at rest (G = 0) the film creeps with h^3/(12 mu_c).

The Poiseuille coefficient of a face becomes k_eff(G, h) = -q/G, equal to h^3/(12 mu)
times the reduction factor f in (0, 1] for Bingham.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# flowing_viscosity: a start's viscosity, so a thousandth in ln h is far below what the
# Newton corrects; and no film is sought beyond e^40 times (or below e^-40 of) the
# consistency's film.
FLOWING_LOG_TOLERANCE = 1e-3
FLOWING_LOG_REACH = 40.0


@dataclass(frozen=True)
class YieldStressLaw:
    """A yield-stress lubricant: consistency K (Pa s^n; the plastic viscosity mu of Bingham,
    n = 1), yield stress tau_y (Pa, > 0), flow index n (> 0) and creep viscosity mu_c (Pa s)
    of the bi-viscous regularisation (module docstring)."""

    consistency: float
    yield_stress: float
    flow_index: float
    creep_viscosity: float


def _model_flux(g, h, law: YieldStressLaw):
    """(|q|, d|q|/d|G|, d|q|/dh) of the unregularised law (Herschel-Bulkley; Bingham at
    n = 1) for |G| = g > 0 (module docstring); 0 where the plug fills the slot."""
    m = 1.0 / law.flow_index
    tau_y, k_m = law.yield_stress, law.consistency**m
    excess = 0.5 * g * h - tau_y  # S = tau_w - tau_y
    flowing = excess > 0.0
    s = np.where(flowing, excess, 0.0)
    g_safe = np.where(flowing, g, 1.0)
    integral = s ** (m + 2.0) / (m + 2.0) + tau_y * s ** (m + 1.0) / (m + 1.0)  # F(S)
    slope = s**m * (s + tau_y)  # dF/dS
    flux = 2.0 * integral / (g_safe**2 * k_m)
    d_g = 2.0 / k_m * (0.5 * h * slope / g_safe**2 - 2.0 * integral / g_safe**3)
    d_h = slope / (g_safe * k_m)
    return np.where(flowing, flux, 0.0), np.where(flowing, d_g, 0.0), np.where(flowing, d_h, 0.0)


def _creep_flux(g, h, law: YieldStressLaw):
    """(|q_c|, d|q_c|/d|G|, d|q_c|/dh) of the creep below the yield stress (module docstring):
    g h^3/(12 mu_c) in a plug-filled slot, (tau_y h^2/4 - tau_y^3/(3 g^2))/mu_c where it yields."""
    tau_y, mu_c = law.yield_stress, law.creep_viscosity
    yields = 0.5 * g * h > tau_y
    g_safe = np.where(yields, g, 1.0)
    flux = np.where(yields, (0.25 * tau_y * h**2 - tau_y**3 / (3.0 * g_safe**2)) / mu_c, g * h**3 / (12.0 * mu_c))
    d_g = np.where(yields, 2.0 * tau_y**3 / (3.0 * mu_c * g_safe**3), h**3 / (12.0 * mu_c))
    d_h = np.where(yields, 0.5 * tau_y * h / mu_c, 0.25 * g * h**2 / mu_c)
    return flux, d_g, d_h


def slot_flux(gradient, gap, law: YieldStressLaw):
    """(q, dq/dG, dq/dh): the regularised pressure-flow flux per unit width (m^2/s) of a slot
    of thickness ``gap`` (m, > 0) under the pressure gradient ``gradient`` G (Pa/m), and its
    derivatives (module docstring; vectorised, numpy broadcasting)."""
    gradient = np.asarray(gradient, dtype=float)
    gap = np.asarray(gap, dtype=float)
    g = np.abs(gradient)
    sign = np.sign(gradient)
    model, model_g, model_h = _model_flux(g, gap, law)
    creep, creep_g, creep_h = _creep_flux(g, gap, law)
    return -sign * (model + creep), -(model_g + creep_g), -sign * (model_h + creep_h)


def effective_coefficient(gradient, gap, law: YieldStressLaw):
    """(k_eff, dk_eff/dG, dk_eff/dh): the Poiseuille coefficient -q/G (m^3/(Pa s)) of the
    regularised law and its derivatives; at G = 0 its limit h^3/(12 mu_c) (the plug creeps)."""
    gradient = np.asarray(gradient, dtype=float)
    gap = np.asarray(gap, dtype=float)
    g = np.abs(gradient)
    model, model_g, model_h = _model_flux(g, gap, law)
    creep, creep_g, creep_h = _creep_flux(g, gap, law)
    yields = 0.5 * g * gap > law.yield_stress
    g_safe = np.where(yields, g, 1.0)
    plug = gap**3 / (12.0 * law.creep_viscosity)
    k = np.where(yields, (model + creep) / g_safe, plug)
    d_g = np.where(yields, np.sign(gradient) * ((model_g + creep_g) / g_safe - (model + creep) / g_safe**2), 0.0)
    d_h = np.where(yields, (model_h + creep_h) / g_safe, 3.0 * plug / gap)
    return k, d_g, d_h


def lubricant_law(lubricant) -> YieldStressLaw | None:
    """The flow law of a scene's lubricant section: a grease's (rheology bingham or
    herschel_bulkley), None for a Newtonian lubricant."""
    if lubricant.rheology == "newtonian":
        return None
    return YieldStressLaw(lubricant.viscosity, lubricant.yield_stress, lubricant.flow_index, lubricant.creep_viscosity)


def apparent_viscosity(shear_rate, law: YieldStressLaw):
    """The stress over the shear rate of the unregularised law where it flows,
    tau/gamma_dot = tau_y/gamma_dot + K gamma_dot^(n - 1) (Pa s; Bingham's mu + tau_y/gamma_dot at
    n = 1), at ``shear_rate`` (1/s, > 0): the viscosity a Newtonian film would need to carry the
    same shear stress at that rate (docs/physics.md section 21, "Its cold start")."""
    shear_rate = np.asarray(shear_rate, dtype=float)
    return law.yield_stress / shear_rate + law.consistency * shear_rate ** (law.flow_index - 1.0)


def flowing_viscosity(film_of, speed: float, law: YieldStressLaw) -> float | None:
    """The viscosity mu (Pa s) at which a Newtonian film carries the grease's shear: mu equal to
    the apparent viscosity at the Couette shear rate of its own film, mu = mu_a(|U|/h(mu)), with
    ``film_of`` the film estimate mu -> h(mu) (m) (docs/physics.md section 21, "Its cold start").

    With w the consistency's share of mu_a, d ln mu_a/d ln h = 1 - n w < 1, and a film estimate
    grows as mu^e with e <= 1 (1 for Martin's long rigid cylinder, 1/2 for the short bearing,
    about 0.7 for the elastic film), so ln h(mu_a(U/h)) - ln h falls as ln h rises, at the rate
    1 - e (1 - n w) > 0: one root, bracketed from the film at the consistency K by doubling
    steps and found by Brent's method to FLOWING_LOG_TOLERANCE in ln h. None where no film up
    to FLOWING_LOG_REACH e-folds from that one solves it: Martin's film of a yield stress that
    alone carries the load at any film (4.9 (U/2) R L tau_y/(F U) >= 1), which grows without
    bound."""
    from scipy.optimize import brentq  # here: scipy.optimize costs ~0.1 s to import

    rate = abs(speed)

    def excess(log_film: float) -> float:
        return math.log(film_of(float(apparent_viscosity(rate / math.exp(log_film), law)))) - log_film

    start = math.log(film_of(law.consistency))
    a, fa, step = start, excess(start), 1.0
    while abs(a - start) < FLOWING_LOG_REACH:
        b = a + step if fa > 0.0 else a - step
        fb = excess(b)
        if fa * fb <= 0.0:
            film = math.exp(brentq(excess, min(a, b), max(a, b), xtol=FLOWING_LOG_TOLERANCE))
            return float(apparent_viscosity(rate / film, law))
        a, fa, step = b, fb, 2.0 * step
    return None


def creep_squeeze_rate(gap, half_width, law: YieldStressLaw):
    """Rate (m/s) at which a film of thickness ``gap`` over a contact of half-width
    ``half_width`` (line contact, flow out of both ends) thins while it is held at its yield
    limit, |G| = 2 tau_y/h everywhere: the flux out of each end is the creep flux
    tau_y h^2/(6 mu_c) (module docstring, xi = 1), so dh/dt = -tau_y h^2/(6 mu_c a)
    (docs/physics.md section 21)."""
    return law.yield_stress * gap**2 / (6.0 * law.creep_viscosity * half_width)


def bingham_squeeze_stop_film(force, length, radius, half_domain, yield_stress):
    """Film (m) at which a rigid smooth cylinder (radius R, length L, force F) squeezing a
    Bingham film on -a <= x <= a (p = 0 at both ends, line contact) stops: the yield stress
    alone carries the load (docs/physics.md section 21).

    At rest the film is a plug wherever it holds, |dp/dx| <= 2 tau_y/h(x), and the largest
    pressure it can hold has |dp/dx| = 2 tau_y/h(x), h = h0 + x^2/(2R) (parabolic gap).
    From p(+-a) = 0, p(x) = int_|x|^a 2 tau_y/h(s) ds, and the load per unit length is

        F/L = int_-a^a p dx = 2 int_0^a s (2 tau_y/h(s)) ds       (by parts)
            = 4 tau_y R int_0^a (s/R) ds / (h0 + s^2/(2R))
            = 4 tau_y R ln(1 + a^2/(2 R h0)).

    The film squeezes while F/L exceeds what it holds; it stops where they are equal:
    h_stop = a^2 / (2 R (exp(F/(4 L R tau_y)) - 1)). (exp overflows to oo, h_stop -> 0,
    when the yield stress cannot hold the load on any film.)
    """
    exponent = force / (4.0 * length * radius * yield_stress)
    return half_domain**2 / (2.0 * radius * np.expm1(exponent))
