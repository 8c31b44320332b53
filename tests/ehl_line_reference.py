"""An independent isoviscous-elastic smooth line-contact solver, written for the tests: the
truth lubecontact's coupled solver (model/coupling.py) is judged against, and the one a
rewrite of it will be judged against (issue 27). numpy/scipy only; it imports nothing from
lubecontact. docs/physics.md section 5 gives the formulas and the numbers it reproduces.

Hertzian units (Venner & Lubrecht, Multilevel Methods in Lubrication, ch. 7): X = x/b,
P = p/p_h, H = h R/b², with b = sqrt(8 w' R/(π E')) and p_h = 2 w'/(π b), E' = 2E*,
E* = 1/[(1 - ν1²)/E1 + (1 - ν2²)/E2]. Then

- Reynolds, one surface sliding at U (u_m = U/2): d/dX(H³ dP/dX) = λ dH/dX,
  λ = 12 μ u_m R²/(b³ p_h);
- film: H = H0 + X²/2 - (1/π) ∫ P(s) ln|X - s| ds (plane strain, both bodies: Johnson,
  Contact Mechanics, eq. 2.25 summed over the two half-planes), the log kernel integrated
  exactly over piecewise-constant pressure elements;
- cavitation (Swift-Stieber): P ≥ 0, A(P) ≥ 0, P A = 0 with A = -d/dX(H³ dP/dX) + λ dH/dX,
  as one Fischer-Burmeister equation per node;
- load balance ∫ P dX = π/2 as one more equation for the unknown H0.

All of it is one nonlinear system in (P, H0), solved by a semismooth Newton method with an
Armijo line search on the merit |Φ|²/2 and a dense Jacobian (a few thousand unknowns at most).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.linalg import lu_factor, lu_solve

MARTIN_LOAD = 4.895  # w' h_min/(μ u_m R), rigid cylinder, Reynolds exit condition (Martin 1916)


def moes_central_film(m: float) -> float:
    """Moes' central film H_c = (h_c/R)/sqrt(U) of the isoviscous (L = 0) line contact
    (Moes, Wear 159 (1992); Venner & Lubrecht ch. 7): (H_RI^(7/3) + H_EI^(7/3))^(3/7),
    H_RI = 3/M, H_EI = 2.621 M^(-1/5), with M = W/sqrt(U), W = w'/(E' R) and
    U = μ u_s/(E' R), u_s = u1 + u2 the sum of the surface speeds (= U for one sliding surface)."""
    rigid, elastic = 3.0 / m, 2.621 * m ** -0.2
    return (rigid ** (7 / 3) + elastic ** (7 / 3)) ** (3 / 7)


def moes_load_parameter(load: float, radius: float, e_star: float, viscosity: float, sum_speed: float) -> float:
    """Moes' M = W/sqrt(U) (see moes_central_film) of a line load w' (N/m) at sum speed u_s (m/s)."""
    e_prime = 2.0 * e_star
    return (load / (e_prime * radius)) / math.sqrt(viscosity * sum_speed / (e_prime * radius))


def speed_for_moes_load_parameter(m: float, load: float, radius: float, e_star: float, viscosity: float) -> float:
    """The sum speed u_s (m/s) at which moes_load_parameter is m."""
    e_prime = 2.0 * e_star
    w = load / (e_prime * radius)
    return (w / m) ** 2 * e_prime * radius / viscosity


def film_in_moes_units(h: float, radius: float, e_star: float, viscosity: float, sum_speed: float) -> float:
    """H = (h/R)/sqrt(U), U = μ u_s/(E' R)."""
    return (h / radius) / math.sqrt(viscosity * sum_speed / (2.0 * e_star * radius))


def log_kernel(offsets: np.ndarray, width: float) -> np.ndarray:
    """∫ ln|d - s| ds over |s| ≤ width/2 (an element centred at 0, seen from offset d), exactly:
    [t ln|t| - t] from d - width/2 to d + width/2, with 0 ln 0 = 0."""

    def t_log_t(t):
        magnitude = np.abs(t)
        safe = np.where(magnitude > 0.0, magnitude, 1.0)
        return np.where(magnitude > 0.0, t * np.log(safe), 0.0)

    return t_log_t(offsets + width / 2) - t_log_t(offsets - width / 2) - width


@dataclass
class LineFilm:
    """A solved line contact, in metres and pascals."""

    x: np.ndarray
    pressure: np.ndarray
    film: np.ndarray
    central_film: float  # h at x = 0
    min_film: float  # smallest h over the nodes
    iterations: int
    residual: float  # max |Φ| at the end


def _fischer_burmeister(a, b):
    """φ(a, b) = a + b - sqrt(a² + b²) and its partial derivatives (the generalized
    Jacobian's element 1 - 1/sqrt(2) at the kink a = b = 0)."""
    r = np.sqrt(a * a + b * b)
    kink = r < 1e-300
    safe = np.where(kink, 1.0, r)
    da = np.where(kink, 1.0 - 1.0 / math.sqrt(2.0), 1.0 - a / safe)
    db = np.where(kink, 1.0 - 1.0 / math.sqrt(2.0), 1.0 - b / safe)
    return a + b - r, da, db


class _System:
    """The discrete equations in Hertzian units on a uniform node grid X (P = 0 at both ends)."""

    def __init__(self, grid: np.ndarray, lam: float, elastic: bool, scale: float):
        self.grid, self.lam, self.scale = grid, lam, scale
        self.step = grid[1] - grid[0]
        # deflection of every node by the inner elements' pressures (the end nodes carry P = 0)
        self.compliance = (-log_kernel(grid[:, None] - grid[None, 1:-1], self.step) / math.pi) if elastic else None

    def film(self, pressure: np.ndarray, h0: float) -> np.ndarray:
        film = h0 + 0.5 * self.grid**2
        return film if self.compliance is None else film + self.compliance @ pressure

    def residual(self, z: np.ndarray, jacobian: bool = False):
        pressure, h0 = z[:-1], z[-1]
        n, dx, lam = pressure.size, self.step, self.lam
        h = self.film(pressure, h0)
        p = np.concatenate([[0.0], pressure, [0.0]])
        g = 0.5 * (h[:-1] ** 3 + h[1:] ** 3)  # face coefficients H³
        dp = (p[1:] - p[:-1]) / dx
        flux = -g * dp + lam * 0.5 * (h[:-1] + h[1:])  # faces 0..n
        excess = (flux[1:] - flux[:-1]) / dx  # A at the inner nodes
        phi, da, db = _fischer_burmeister(pressure, self.scale * excess)
        load = dx * pressure.sum() - math.pi / 2
        value = np.concatenate([phi, [load]])
        if not jacobian:
            return value
        # dA_i/dP_j through the Poiseuille term (tridiagonal)
        jac_p = np.zeros((n, n))
        idx = np.arange(n)
        jac_p[idx, idx] = (g[1:] + g[:-1]) / dx**2
        jac_p[idx[:-1], idx[:-1] + 1] = -g[1:-1] / dx**2
        jac_p[idx[1:], idx[1:] - 1] = -g[1:-1] / dx**2
        # dA_i/dH_k for k = i-1, i, i+1 (full-grid node indices i+1-1 .. i+1+1)
        dflux_left = -1.5 * h[:-1] ** 2 * dp + 0.5 * lam  # d flux_f / d h_f (left node of face f)
        dflux_right = -1.5 * h[1:] ** 2 * dp + 0.5 * lam  # d flux_f / d h_{f+1}
        d_h = sparse.diags([-dflux_left[:-1] / dx, (dflux_left[1:] - dflux_right[:-1]) / dx, dflux_right[1:] / dx],
                           [0, 1, 2], shape=(n, n + 2), format="csr")  # columns: full-grid nodes i-1, i, i+1
        # dH/dP is the compliance; dH/dH0 = 1
        if self.compliance is not None:
            jac_p += d_h @ self.compliance
        dexcess_dh0 = np.asarray(d_h.sum(axis=1)).ravel()
        jac = np.zeros((n + 1, n + 1))
        jac[:n, :n] = db[:, None] * self.scale * jac_p
        jac[idx, idx] += da
        jac[:n, n] = db * self.scale * dexcess_dh0
        jac[n, :n] = dx
        return value, jac


def _newton(system: _System, z: np.ndarray, tolerance: float = 1e-10, max_iterations: int = 200):
    value, jac = system.residual(z, jacobian=True)
    merit = 0.5 * value @ value
    for iteration in range(1, max_iterations + 1):
        direction = lu_solve(lu_factor(jac), -value)
        step = 1.0
        while True:
            trial = z + step * direction
            if system.compliance is None:
                trial[-1] = max(trial[-1], 0.05 * z[-1])  # a rigid gap stays open
            trial_value = system.residual(trial)
            trial_merit = 0.5 * trial_value @ trial_value
            if trial_merit <= (1.0 - 1e-4 * step) * merit or step < 1e-8:
                break
            step *= 0.5
        z = trial
        value, jac = system.residual(z, jacobian=True)
        merit = 0.5 * value @ value
        if np.max(np.abs(value)) < tolerance:
            return z, iteration, float(np.max(np.abs(value)))
    worst = np.max(np.abs(value))
    raise RuntimeError(f"reference solver: no convergence in {max_iterations} Newton steps, |Φ| = {worst:.3g}")


def solve_line_contact(load: float, radius: float, e_star: float, viscosity: float, sliding_speed: float,
                       elastic: bool = True, nodes: int = 1201, x_in: float | None = None,
                       x_out: float | None = None) -> LineFilm:
    """Smooth isoviscous line contact: a cylinder of radius R (m) pressed with w' (N/m) on a
    plane sliding at U (m/s) (u_m = U/2), viscosity μ (Pa s). The domain [x_in, x_out] (m)
    defaults to an inlet 4 b + 30 inlet lengths sqrt(2 R h) of Moes' central film before the
    centre and an outlet 1.5 b + 3 inlet lengths after it (b the Hertz half-width); rigid
    (elastic=False): 40 and 4 inlet lengths of Martin's film."""
    e_prime = 2.0 * e_star
    b = math.sqrt(8.0 * load * radius / (math.pi * e_prime))
    p_h = 2.0 * load / (math.pi * b)
    lam = 12.0 * viscosity * 0.5 * sliding_speed * radius**2 / (b**3 * p_h)
    if elastic:
        m = moes_load_parameter(load, radius, e_star, viscosity, sliding_speed)
        guess = moes_central_film(m) * radius * math.sqrt(viscosity * sliding_speed / (e_prime * radius))
        inlet = math.sqrt(2.0 * radius * guess)
        x_in = -(4.0 * b + 30.0 * inlet) if x_in is None else x_in
        x_out = (1.5 * b + 3.0 * inlet) if x_out is None else x_out
    else:
        guess = MARTIN_LOAD * viscosity * 0.5 * sliding_speed * radius / load
        inlet = math.sqrt(2.0 * radius * guess)
        x_in = -40.0 * inlet if x_in is None else x_in
        x_out = 4.0 * inlet if x_out is None else x_out
    grid = np.linspace(x_in / b, x_out / b, nodes)
    h0 = guess * radius / b**2
    # start: the Hertz pressure where it exists, else a Martin-like bump over the inlet length
    width = max(1.0, math.sqrt(2.0 * h0))
    start = np.sqrt(np.clip(1.0 - (grid[1:-1] / width) ** 2, 0.0, None))
    start *= (math.pi / 2) / ((grid[1] - grid[0]) * start.sum())
    # the complementarity scale: A ~ H³ P/dX², made O(1) at the expected film
    system = _System(grid, lam, elastic, scale=(grid[1] - grid[0]) ** 2 / h0**3)
    if elastic:  # H0 is a datum: the start's film at X = 0 is the guess
        h0 -= system.film(start, 0.0)[np.argmin(np.abs(grid))]
    z, iterations, residual = _newton(system, np.concatenate([start, [h0]]))
    pressure = np.concatenate([[0.0], z[:-1], [0.0]]) * p_h
    film = system.film(z[:-1], z[-1]) * b**2 / radius
    x = grid * b
    central = float(np.interp(0.0, x, film))
    return LineFilm(x, pressure, film, central, float(film.min()), iterations, residual)
