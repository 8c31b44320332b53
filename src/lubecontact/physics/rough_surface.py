"""Statistical rough-surface contact per unit nominal area (paper Eqs. 11-13 and 15).

Greenwood-Williamson with the Jackson-Green asperity of :mod:`lubecontact.asperity`
(Jackson & Green 2006, Tribol. Int. 39:906). Asperity heights z are Gaussian, G(z) with
standard deviation s, z measured from the mean of the asperity heights; d is the
separation of the flat from that mean and h = d + y_s the separation of the mean planes
(Eq. 12). Per unit nominal area A_n:

- contact pressure   p_c(h)   = eta int_d^inf P(z - d) G(z) dz                  (Eq. 11)
- area fraction      A_r/A_n  = eta int_d^inf pi a(z - d)^2 G(z) dz
- spot conductances  g(h)     = eta int_d^inf k a(z - d) G(z) dz, in S/m^2      (Eq. 15)

with k a the Holm conductance of one spot, k = 4/(rho1 + rho2) (= 2/rho_L of Eq. 15).

Summit statistics (McCool 1986, Wear 107:37), with eta the asperity density and R the
asperity radius: y_s = 0.045944/(eta R) (Eq. 13, = 1/(sqrt(48) pi eta R)). The Gaussian
uses s = sigma as the paper (``roughness.height_std = "sigma"``) or McCool's summit
std (``"mccool"``), s^2 = sigma^2 - 3.717e-4/(eta R)^2 (= sigma^2 (1 - 0.8968/alpha)).

Numerics. With t = d/s, v = (z - d)/s and phi the standard normal density, every integral
is eta * int_0^inf f(s v) phi(v + t) dv: for a given scene a function of t alone, so its
logarithm Q(t) is tabulated once per scene and interpolated (cubic Hermite with exact
nodal slopes dQ/dt, which are integrals too: dI/dt = -int f(s v) (v + t) phi(v + t) dv).

- Table nodes: uniform in t (step 0.1) on [-20, 48], where the hot loop evaluates; below,
  uniform in asinh((t + 20)/2), so the step grows like 0.05 |t + 20| in deep interference,
  where Q is a slowly varying power of |t|. The table spans t in [about -1e6, 48].
- Near and above the mean (t >= -12): Q = log phi(t) + log int f(s v) exp(-v t - v^2/2) dv;
  the second integral is smooth and never underflows. Composite Gauss-Legendre in v on
  panels shared by all these nodes: a sqrt-substituted first panel where f is a pure Hertz
  power of v, log-spaced panels up to v = 1, panels of width 2 up to v = 24, and the kinks
  of the asperity law (1.9 omega_c; a/R = 1 with Eq. 8) as panel edges.
- Deep interference (t < -12): int f(s(x - t)) phi(x) dx over x in [-12, 12], fixed panels.
- Beyond the table Q is extended C1-continuously and monotonically: as a power law in |t|
  below it (p_c ~ |t|^k), and above it as the exact log phi(t) plus a power law in t of the
  smooth integral (whose Hertz asymptotes are t^(-5/2) for p_c, t^(-2) for A_r/A_n and
  t^(-3/2) for g).

So every quantity is finite and monotone for any finite h (p_c keeps increasing as h
decreases); far out the values themselves underflow to 0.0 while their logarithms
(``log_conductance``) stay finite. Table build: 10-20 ms on an idle core. Error against
adaptive quadrature of Eqs. (11)/(15) (tests/test_rough_contact.py) inside the table: below
2e-8 relative (1.4e-6 for p_c with Eq. 8 where a/R passes 1, t ~ -45); the extensions stay
within 1e-3 relative for t from -3e6 to 55 and within a few per cent far beyond.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import gamma, pbdv

from lubecontact.physics.asperity import Asperity
from lubecontact.physics.electrical import alleviation_factor
from lubecontact.physics.materials import spot_conductance_factor

SUMMIT_OFFSET_CONSTANT = 0.045944  # Eq. (13): y_s eta R (McCool; = 1/(sqrt(48) pi))
SUMMIT_VARIANCE_CONSTANT = 3.717e-4  # McCool: (sigma^2 - sigma_s^2)(eta R)^2 = 0.8968 (0.0203585)^2
HEIGHT_STDS = ("sigma", "mccool")

T_STEP = 0.1  # table step in t on [T_UNIFORM, T_MAX] (Hermite error ~ T_STEP^4/384 max|Q''''|)
T_UNIFORM = -20.0  # below: nodes uniform in asinh((t - T_UNIFORM)/T_SCALE), step T_STEP/T_SCALE
T_SCALE = 2.0  # (so the step is T_STEP at T_UNIFORM on both sides)
T_MAX = 48.0  # far-tail end: phi(48) = 1e-501, beyond any representable conductance
T_DEEP = -1.0e6  # deep-interference end (the first node at or below it)
T_SPLIT = -12.0  # below it the quadrature follows the peak of phi(v + t)
GAUSS_REACH = 12.0  # the Gaussian is integrated over [-12, 12] standard deviations (phi(12) = 5e-32)
GL_ORDER = 16  # Gauss-Legendre nodes per panel
FIRST_PANEL = 2.0**-12  # upper end (in units of s) of the first, sqrt-substituted panel
WIDE_PANEL = 2.0  # panel width in v above v = 1, and in x (16 nodes per 2 standard deviations)
_DU = T_STEP / T_SCALE
_C_UNIFORM = round(T_UNIFORM / T_STEP)  # node index c of T_UNIFORM (t = T_STEP c above it)
_C_MIN = _C_UNIFORM + math.floor(math.asinh((T_DEEP - T_UNIFORM) / T_SCALE) / _DU)  # first node
_C_MAX = round(T_MAX / T_STEP)
_T_LO = T_UNIFORM + T_SCALE * math.sinh((_C_MIN - _C_UNIFORM) * _DU)  # first node, about T_DEEP
_T_HI = _C_MAX * T_STEP  # last node, T_MAX
_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)
_EXP_FLOOR = -700.0  # exponents below this are held here (e^-700 is negligible, not subnormal)
_GL_X, _GL_W = np.polynomial.legendre.leggauss(GL_ORDER)

PRESSURE, AREA, CONDUCTANCE = 0, 1, 2  # rows of the table
_NAMES = ("contact pressure", "area fraction", "conductance")


def summit_offset(asperity_density: float, asperity_radius: float) -> float:
    """y_s = 0.045944/(eta R_peak), m (Eq. 13)."""
    return SUMMIT_OFFSET_CONSTANT / (asperity_density * asperity_radius)


def summit_height_std(sigma: float, asperity_density: float, asperity_radius: float) -> float:
    """McCool's std of summit heights, sigma_s = sqrt(sigma^2 - 3.717e-4/(eta R)^2), m."""
    variance = sigma**2 - SUMMIT_VARIANCE_CONSTANT / (asperity_density * asperity_radius) ** 2
    if not variance > 0.0:
        raise ValueError(
            f"McCool's summit height std is undefined for sigma = {sigma:g} m, eta R = "
            f"{asperity_density * asperity_radius:g} 1/m: needs eta R sigma > "
            f"{math.sqrt(SUMMIT_VARIANCE_CONSTANT):.4g}; use roughness.height_std = 'sigma'"
        )
    return math.sqrt(variance)


def gaussian_moment(n, t):
    """F_n(t) = int_t^inf (s - t)^n phi(s) ds with phi the standard normal density.

    Closed form through the parabolic cylinder function D: F_n(t) = Gamma(n+1)/sqrt(2 pi)
    exp(-t^2/4) D_{-n-1}(t) (Abramowitz & Stegun 19.5.3 / 19.3.7). F_0 = 1 - Phi(t).
    Greenwood-Williamson elastic limit: p_c = (4/3) eta E* R^(1/2) s^(3/2) F_3/2(d/s),
    A_r/A_n = pi eta R s F_1(d/s). Meant for moderate |t| (tests, checks).
    """
    t = np.asarray(t, dtype=float)
    return gamma(n + 1.0) / math.sqrt(2.0 * math.pi) * np.exp(-0.25 * t**2) * pbdv(-n - 1.0, t)[0]


def _panels(edges, logarithmic: bool) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights on consecutive panels (in log v if asked)."""
    edges = np.log(edges) if logarithmic else np.asarray(edges, dtype=float)
    a, b = edges[:-1, None], edges[1:, None]
    nodes = (0.5 * (b - a) * _GL_X + 0.5 * (a + b)).ravel()
    weights = (0.5 * (b - a) * _GL_W).ravel()
    if logarithmic:
        nodes = np.exp(nodes)
        weights = weights * nodes
    return nodes, weights


def _v_quadrature(breakpoints, v_max: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights in v = omega/s on [0, v_max], every breakpoint (in v) a panel edge.

    The first panel [0, e1], e1 = 2^j <= min(FIRST_PANEL, breakpoints), lies where the
    asperity is Hertzian (f a power of v): in w = sqrt(v) its integrand is a polynomial.
    Log-spaced panels follow up to v = 1, then panels of width WIDE_PANEL.
    """
    inside = [b for b in breakpoints if 0.0 < b < v_max]
    j_lo = math.floor(math.log2(min([FIRST_PANEL, *inside])))
    w, ww = _panels([0.0, math.sqrt(2.0**j_lo)], logarithmic=False)
    edges = np.unique(np.concatenate([2.0 ** np.arange(j_lo, 1), np.arange(1.0, v_max, WIDE_PANEL), inside, [v_max]]))
    v, wv = _panels(edges, logarithmic=True)
    return np.concatenate([w**2, v]), np.concatenate([2.0 * w * ww, wv])


def _table_nodes() -> tuple[np.ndarray, np.ndarray]:
    """Table abscissae t(c), c = _C_MIN.._C_MAX, and dt/dc: t = T_STEP c from T_UNIFORM
    on, T_UNIFORM + T_SCALE sinh((c - _C_UNIFORM) T_STEP/T_SCALE) below."""
    c = np.arange(_C_MIN, _C_MAX + 1, dtype=float)
    deep = (c - _C_UNIFORM) * _DU
    t = np.where(c >= _C_UNIFORM, T_STEP * c, T_UNIFORM + T_SCALE * np.sinh(deep))
    return t, np.where(c >= _C_UNIFORM, T_STEP, T_STEP * np.cosh(deep))


def _log_integrals(integrand, breakpoints, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q(t) = log int_0^inf f(v) phi(v + t) dv and dQ/dt for the rows f of ``integrand(v)``
    (a callable returning shape (n_f, *v.shape)); ``breakpoints``: kinks of f in v."""
    near = t >= T_SPLIT
    # near the mean and above: log phi(t) + log of the smooth int f(v) exp(-v t - v^2/2) dv
    tn = t[near]
    v, w = _v_quadrature(breakpoints, GAUSS_REACH - T_SPLIT)
    f = integrand(v)
    q = np.empty((f.shape[0], t.size))
    dq = np.empty_like(q)
    e = np.exp(np.maximum(-np.outer(tn, v) - 0.5 * v**2, _EXP_FLOOR))
    i0 = (e @ (w * f).T).T  # (n_f, n_near), > 0
    i1 = (e @ (w * v * f).T).T  # = -(d/dt of i0) - t i0
    q[:, near] = np.log(i0) - 0.5 * tn**2 - _LOG_SQRT_2PI
    dq[:, near] = -i1 / i0 - tn
    # deep interference: int f(x - t) phi(x) dx over x in [-12, 12] (v = x - t > 0)
    td = t[~near]
    x, wx = _panels(np.arange(-GAUSS_REACH, GAUSS_REACH + WIDE_PANEL / 2, WIDE_PANEL), logarithmic=False)
    kernel = wx * np.exp(-0.5 * x**2 - _LOG_SQRT_2PI)
    f = integrand(x[None, :] - td[:, None])  # (n_f, n_deep, n_x)
    i0 = f @ kernel
    q[:, ~near] = np.log(i0)
    dq[:, ~near] = -(f @ (kernel * x)) / i0  # dI/dt = -int f(x - t) x phi(x) dx
    return q, dq


def _check_monotone(q: np.ndarray, dq_dc: np.ndarray) -> None:
    """Fritsch-Carlson on unit steps in c: every Hermite cubic is strictly decreasing."""
    secant = np.diff(q, axis=1)
    alpha, beta = dq_dc[:, :-1] / secant, dq_dc[:, 1:] / secant
    bad = ~((secant < 0.0) & (alpha >= 0.0) & (beta >= 0.0) & (alpha**2 + beta**2 <= 9.0))
    if bad.any():
        row, col = np.argwhere(bad)[0]
        raise RuntimeError(
            f"rough-contact table of {_NAMES[row]} is not monotone near t = {_table_nodes()[0][col]:g}: "
            "refine T_STEP or the quadrature"
        )


def _hermite_nodes(q: np.ndarray, dq: np.ndarray) -> np.ndarray:
    """(q_k, q_k+1, m_k, m_k+1) of every table interval [c_k, c_k + 1] of one row (``q``,
    ``dq`` = dQ/dc on the nodes), as rows: one gather per evaluated point."""
    return np.ascontiguousarray(np.stack([q[:-1], q[1:], dq[:-1], dq[1:]], axis=-1))


def _hermite(x: np.ndarray, nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q(t) and dQ/dt of the table at every t of ``x`` in (_T_LO, _T_HI): the cubic Hermite
    interpolant in its basis form (as the numba kernel it replaces; the transient's step
    control is sensitive to the rounding of the interpolant, tests/test_transient.py)."""
    c = x / T_STEP
    dc_dt = 1.0 / T_STEP
    deep = x < T_UNIFORM
    if deep.any():  # nodes uniform in asinh((t - T_UNIFORM)/T_SCALE)
        y = (x[deep] - T_UNIFORM) / T_SCALE
        c[deep] = _C_UNIFORM + np.arcsinh(y) / _DU
        dc_dt = np.full_like(x, dc_dt)
        dc_dt[deep] = 1.0 / (T_STEP * np.sqrt(1.0 + y * y))
    c -= _C_MIN
    k = c.astype(np.intp)  # c >= 0 here: truncation is floor
    np.minimum(k, nodes.shape[0] - 1, out=k)
    s = c - k
    s2 = s * s
    s3 = s2 * s
    a = nodes[k]
    q0, q1, m0, m1 = a[:, 0], a[:, 1], a[:, 2], a[:, 3]
    value = (2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * m0 + (3 * s2 - 2 * s3) * q1 + (s3 - s2) * m1
    slope = dc_dt * ((6 * s2 - 6 * s) * (q0 - q1) + (3 * s2 - 4 * s + 1) * m0 + (3 * s2 - 2 * s) * m1)
    return value, slope


def _evaluate(t: np.ndarray, nodes: np.ndarray, k_lo: float, j_hi: float, k_hi: float,
              take_exp: bool) -> tuple[np.ndarray, np.ndarray]:
    """Q(t) and dQ/dt of one table row (``nodes`` of _hermite_nodes) at every t (1-D,
    no NaN): Hermite inside, the extensions outside. With ``take_exp``: exp(Q), d exp(Q)/dt.

    Plain numpy: 1-4 % of a solve on 51^2-401^2 meshes. The numba kernel it replaced was 2-5x
    faster per call (per solve: ~1 ms less at 51^2, ~0.04 s at 201^2, ~0.1 s of 8-12 s at
    401^2), but importing numba and loading its cache cost 0.3-0.6 s in every new process."""
    lo = t <= _T_LO
    hi = t >= _T_HI
    if lo.any() or hi.any():
        value, slope = np.empty_like(t), np.empty_like(t)
        mid = ~(lo | hi)
        value[mid], slope[mid] = _hermite(t[mid], nodes)
        x = t[lo]  # deep interference: power law in |t| (t = -inf: Q = +inf, dQ/dt = 0)
        value[lo] = nodes[0, 0] + k_lo * np.log(x / _T_LO)
        slope[lo] = k_lo / x
        x = t[hi]  # far tail: exact log phi + power law of the smooth integral (t -> inf: Q -> -inf)
        with np.errstate(over="ignore"):
            value[hi] = j_hi + k_hi * np.log(x / _T_HI) - 0.5 * x * x - _LOG_SQRT_2PI
        slope[hi] = k_hi / x - x
    else:
        value, slope = _hermite(t, nodes)
    if take_exp:
        with np.errstate(over="ignore", invalid="ignore"):
            np.exp(value, out=value)
            slope *= value
            slope[~(np.abs(slope) > 0.0)] = 0.0  # 0.0 where exp(Q) or dQ/dt is 0 (no 0 * inf at h = +-inf)
    return value, slope


class RoughContact:
    """Eqs. (11)-(15) of one scene as functions of the mean-plane separation h (any shape, m).

    Built once per scene (a table in t = (h - y_s)/s), evaluated in O(1) per node.
    """

    def __init__(self, asperity: Asperity, asperity_density: float, sigma: float, height_std: float,
                 spot_factor: float):
        self.asperity = asperity
        self.sigma = float(sigma)  # m, the scene's roughness
        self.height_std = float(height_std)  # m, s of the Gaussian G (sigma or sigma_s)
        self.y_s = summit_offset(asperity_density, asperity.radius)  # m, Eq. (13)
        s = self.height_std

        def integrand(v):
            a = asperity.contact_radius(s * v)
            return asperity_density * np.stack([asperity.load(s * v), np.pi * a**2, spot_factor * a])

        t, dt_dc = _table_nodes()
        q, dq_dt = _log_integrals(integrand, [b / s for b in asperity.breakpoints], t)
        self._q, self._dq = q, dq_dt * dt_dc
        _check_monotone(self._q, self._dq)
        self._nodes = [_hermite_nodes(q_row, dq_row) for q_row, dq_row in zip(self._q, self._dq)]
        self._k_lo = _T_LO * dq_dt[:, 0]
        self._j_hi = q[:, -1] + 0.5 * _T_HI**2 + _LOG_SQRT_2PI
        self._k_hi = _T_HI * (dq_dt[:, -1] + _T_HI)

    @classmethod
    def from_scene(cls, scene) -> RoughContact:
        r = scene.roughness
        if r.height_std == "sigma":
            s = r.sigma
        elif r.height_std == "mccool":
            s = summit_height_std(r.sigma, r.asperity_density, r.asperity_radius)
        else:
            raise ValueError(f"roughness.height_std {r.height_std!r} is unknown; allowed: {', '.join(HEIGHT_STDS)}")
        return cls(Asperity.from_scene(scene), r.asperity_density, r.sigma, s, spot_conductance_factor(scene))

    def _eval(self, row: int, h, take_exp: bool):
        h = np.asarray(h, dtype=float)
        if np.isnan(h).any():
            raise ValueError("rough contact evaluated at a NaN separation")
        with np.errstate(over="ignore"):  # |h| > ~1e300 s: t = +-inf, the limits are exact
            t = np.ascontiguousarray(((h - self.y_s) / self.height_std).ravel())
        value, slope = _evaluate(t, self._nodes[row], self._k_lo[row], self._j_hi[row], self._k_hi[row], take_exp)
        return value.reshape(h.shape), (slope / self.height_std).reshape(h.shape)

    def pressure(self, h) -> np.ndarray:
        """Nominal contact pressure p_c(h), Pa (Eq. 11 per unit nominal area)."""
        return self._eval(PRESSURE, h, True)[0]

    def pressure_and_slope(self, h) -> tuple[np.ndarray, np.ndarray]:
        """(p_c, dp_c/dh) in Pa and Pa/m; the slope is that of the interpolant, <= 0."""
        return self._eval(PRESSURE, h, True)

    def area_fraction(self, h) -> np.ndarray:
        """A_r/A_n (may exceed 1 at deep interference, where GW is far outside its validity)."""
        return self._eval(AREA, h, True)[0]

    def conductance(self, h) -> np.ndarray:
        """g = sum of Holm spot conductances per nominal area (Eq. 15), S/m^2 (0.0 once it underflows)."""
        return self._eval(CONDUCTANCE, h, True)[0]

    def log_conductance(self, h) -> np.ndarray:
        """Natural log of g = sum of Holm spot conductances per nominal area (Eq. 15), g in S/m^2.
        Finite for every finite h, also where g itself underflows."""
        return self._eval(CONDUCTANCE, h, False)[0]


def rough_contact(scene, separation):
    """Rough-contact laws of a scene on the separations h (m) given, as an xarray.Dataset.

    ``conductance`` is g/Psi (Eqs. 15-17) when ``scene.effects.alleviation``, else g.
    """
    import xarray as xr

    contact = RoughContact.from_scene(scene)
    h = np.atleast_1d(np.asarray(separation, dtype=float))
    if h.ndim != 1:
        raise ValueError("separation must be a scalar or a 1-D array")
    area = contact.area_fraction(h)
    conductance = contact.conductance(h)
    if scene.effects.alleviation:
        conductance = conductance / alleviation_factor(area)[0]

    def var(values, units, long_name):
        return xr.Variable(("separation",), values, {"units": units, "long_name": long_name})

    return xr.Dataset(
        {
            "pressure": var(contact.pressure(h), "Pa", "nominal asperity contact pressure (Eq. 11)"),
            "area_fraction": var(area, "1", "real over nominal contact area A_r/A_n"),
            "conductance": var(
                conductance,
                "S m-2",
                "contact conductance per nominal area (Eq. 15"
                + (", over the alleviation factor of Eqs. 16-17)" if scene.effects.alleviation else ")"),
            ),
        },
        coords={"separation": var(h, "m", "mean-plane separation h (Eq. 12)")},
        attrs={
            "title": "lubecontact rough contact per unit nominal area",
            "Conventions": "CF-1.10",
            "scene_hash": scene.hash,
            "height_std": contact.height_std,
            "summit_offset": contact.y_s,
        },
    )
