"""Conduction through the lubricant film (docs/physics.md section 13), per nominal area.

- Ohmic film: a lubricant of resistivity rho_f (ohm m) and thickness t conducts
  1/(rho_f t) per nominal area (S/m^2).
- Tunnelling through a thin insulating film, Simmons (J. Appl. Phys. 34 (1963) 1793,
  eq. 25, low-voltage limit) for a rectangular barrier of height phi and width t:
  rho_t = (2 t / (3 sqrt(2 m phi))) (h/e)^2 exp[(4 pi t / h) sqrt(2 m phi)] (ohm m^2),
  m the electron mass, h Planck's constant, e the elementary charge (CODATA values of
  scipy.constants). It grows e-fold every ~0.1 nm of film at phi = 1 eV, so it counts
  only for films of a few nanometres.

Both are taken in logarithms: the conductance of a 10 um film by tunnelling is e^-1e5.

Film thickness. Between rough surfaces the gap varies; the film is taken as the mean
gap, Patir and Cheng's h_T (the expected gap; held at its h = 0 value sigma/sqrt(2 pi)
where the mean planes interpenetrate, as the fluid sees it in the solver), over the part
of the nominal area not in asperity contact (1 - A_r/A_n). Since the mean of 1/t is at least 1/(mean of t) (Jensen), this
underestimates the ohmic conductance of a rough film: the film resistance is an upper
bound, the side a contact-open decision may err on.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import constants


def simmons_log_specific_conductance(thickness, barrier_height_ev: float):
    """ln of the tunnelling conductance per area 1/rho_t (S/m^2) through a film of
    ``thickness`` (m, > 0) and barrier height ``barrier_height_ev`` (eV), Simmons' eq. 25."""
    t = np.asarray(thickness, dtype=float)
    root = math.sqrt(2.0 * constants.m_e * barrier_height_ev * constants.e)  # sqrt(2 m phi), kg m/s
    log_prefactor = math.log(3.0 * root / 2.0) + 2.0 * math.log(constants.e / constants.h)
    return log_prefactor - np.log(t) - 4.0 * math.pi * t * root / constants.h


def simmons_specific_resistance(thickness, barrier_height_ev: float):
    """rho_t (ohm m^2) of Simmons' eq. 25 (docs/physics.md section 13); +inf beyond float range."""
    with np.errstate(over="ignore"):
        return np.exp(-simmons_log_specific_conductance(thickness, barrier_height_ev))


def film_log_conductance(thickness, wetted_fraction, resistivity: float | None, barrier_height_ev: float | None):
    """ln of the film's conductance per nominal area (S/m^2): the wetted fraction times the
    ohmic (``resistivity`` in ohm m, None: insulator) and tunnelling (``barrier_height_ev``,
    None: none) conductances of a film of ``thickness`` (m) in parallel; -inf where nothing conducts."""
    t = np.asarray(thickness, dtype=float)
    if (t <= 0.0).any() or np.isnan(t).any():
        raise ValueError("film thickness must be positive")
    log_g = np.full(t.shape, -np.inf)
    if resistivity is not None:
        log_g = np.logaddexp(log_g, -np.log(resistivity * t))
    if barrier_height_ev is not None:
        log_g = np.logaddexp(log_g, simmons_log_specific_conductance(t, barrier_height_ev))
    with np.errstate(divide="ignore"):
        return log_g + np.log(np.clip(wetted_fraction, 0.0, 1.0))
