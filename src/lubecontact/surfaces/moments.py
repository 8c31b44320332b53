"""Spectral moments of a surface: m0 = <z^2>, m2 = <z'^2>, m4 = <z''^2> (docs/physics.md section 18).

How they are taken (McCool 1986 needs them along one direction of an isotropic surface):

- Detrending: the least-squares plane z = a + b x + c y (a line for a profile) is removed
  from the whole map (only the mean from a periodic map); m0 is the mean square of what is
  left (all wavelengths).
- m2 and m4 along x from the profiles (rows) and along y from the columns: each profile is
  multiplied by a window (unless the map is periodic), Fourier transformed, and its
  one-sided power P(q) (sum over q = mean square) averaged over the profiles; then
  m_n = sum of q^n P(q) over 0 < q <= q_c = 2 pi / lambda_c. These are the mean square
  slope and curvature of the surface low-pass filtered at lambda_c, i.e. derivatives taken
  spectrally, not by finite differences.
- Window: a measured map does not wrap around, so without a window its edges add power
  at every wave number (m4 most). A Tukey window (cosine tapers over a quarter of the
  profile at each end) suppresses that leakage and still weighs half of the profile fully.
  On tilted synthetic maps with a known spectrum (bench/surfaces_window.py, 8 seeds) the
  largest errors of eta, R_peak, alpha were 4.0, 3.1, 7.2 % at 128^2 points (Hann: 5.1,
  3.9, 18 %) and 1.3, 1.0, 3.9 % at 256^2 (Hann: 3.3, 1.9, 2.8 %).
- The short-wavelength cut-off lambda_c (default ``DEFAULT_CUTOFF_INTERVALS`` sampling
  intervals, half the Nyquist wave number) keeps out the band near the Nyquist wave number
  where instrument noise, its transfer function and aliasing live. m2 and m4 depend on it
  (m4 most): every result reports the one used.
- Isotropy: gamma = sqrt(m2_y / m2_x) (Patir-Cheng's ratio of correlation lengths
  lambda_x / lambda_y for a surface stretched along x); McCool's formulas then use the mean
  of the x and y moments.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lubecontact.surfaces.reading import Surface, SurfaceError

DEFAULT_CUTOFF_INTERVALS = 4.0  # lambda_c = 4 sampling intervals unless given
WINDOWS = ("tukey", "hann", "none")
ROUNDOFF = 1e-9  # an RMS below this fraction of the heights' size is a plane's round-off
TUKEY_TAPER = 0.5  # fraction of a profile inside the Tukey window's cosine tapers


@dataclass(frozen=True)
class Moments:
    """m0 (m^2); m2 (1) and m4 (m^-2) per direction, (x,) for a profile or (x, y)."""

    m0: float
    m2: tuple[float, ...]
    m4: tuple[float, ...]
    cutoff: float  # lambda_c, m
    window: str
    sampling: tuple[float, ...]  # dx (, dy), m
    detrending: str  # what was removed before the moments: see detrending()

    @property
    def m2_mean(self) -> float:
        return float(np.mean(self.m2))

    @property
    def m4_mean(self) -> float:
        return float(np.mean(self.m4))

    @property
    def gamma(self) -> float | None:
        """sqrt(m2_y/m2_x) for a map; None for a profile (isotropy cannot be seen)."""
        return None if len(self.m2) == 1 else float(np.sqrt(self.m2[1] / self.m2[0]))


def detrended(surface: Surface) -> np.ndarray:
    """Heights minus their least-squares plane (a line for a profile); minus their mean only
    for a periodic map (a plane does not wrap around: its jump at the edge would add power
    at every wave number)."""
    z = surface.heights
    if surface.periodic:
        return z - z.mean()
    ny, nx = z.shape
    y, x = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    columns = [np.ones(z.size), x.ravel()] + ([] if surface.is_profile else [y.ravel()])
    basis = np.column_stack(columns)
    coef, *_ = np.linalg.lstsq(basis, z.ravel(), rcond=None)
    return z - (basis @ coef).reshape(z.shape)


def detrending(surface: Surface) -> str:
    """What ``detrended`` removes from ``surface``, in the words every result prints."""
    if surface.periodic:
        return "mean removed"
    return "line detrended" if surface.is_profile else "plane detrended"


def tukey_window(n: int, taper: float) -> np.ndarray:
    """The symmetric Tukey (tapered cosine) window of n points, ``taper`` the fraction of it
    inside the two cosine tapers (Harris 1978): w = (1 + cos(pi (2k/(taper (n-1)) - 1))) / 2
    over the first taper (n-1)/2 intervals, 1 in the middle, mirrored at the end; Hann from
    taper = 1 on. Evaluated in scipy.signal.windows.tukey's arithmetic, so a measured
    surface's parameters, and with them its cases' ids, are those computed with scipy's
    window to the last bit; written here because importing scipy.signal costs 0.7 s in
    every process that plans the workflow."""
    if n <= 1 or taper <= 0.0:
        return np.ones(n)
    if taper >= 1.0:
        return hann_window(n)
    k = np.arange(n, dtype=float)
    width = int(np.floor(taper * (n - 1) / 2.0))
    first, last = k[: width + 1], k[n - width - 1 :]
    return np.concatenate((
        0.5 * (1 + np.cos(np.pi * (-1 + 2.0 * first / taper / (n - 1)))),
        np.ones(n - 2 * width - 2),
        0.5 * (1 + np.cos(np.pi * (-2.0 / taper + 1 + 2.0 * last / taper / (n - 1)))),
    ))


def hann_window(n: int) -> np.ndarray:
    """The symmetric Hann window, (1 + cos(phi)) / 2 for phi from -pi to pi, in
    scipy.signal.windows.hann's arithmetic (see tukey_window)."""
    if n <= 1:
        return np.ones(n)
    return 0.5 + 0.5 * np.cos(np.linspace(-np.pi, np.pi, n))


def profile_power(profiles: np.ndarray, spacing: float, window: str) -> tuple[np.ndarray, np.ndarray]:
    """Wave numbers q (rad/m) and one-sided power P(q) (m^2, sum = mean square) averaged
    over the rows of ``profiles``; the window is scaled to unit mean square."""
    n = profiles.shape[1]
    w = {"tukey": lambda: tukey_window(n, TUKEY_TAPER), "hann": lambda: hann_window(n), "none": lambda: np.ones(n)}[window]()
    w = w / np.sqrt(np.mean(w**2))
    power = np.abs(np.fft.rfft(profiles * w, axis=1)) ** 2 / n**2
    power[:, 1 : (n + 1) // 2] *= 2.0  # both signs of q, except q = 0 and Nyquist (even n)
    q = 2.0 * np.pi * np.fft.rfftfreq(n, d=spacing)
    return q, power.mean(axis=0)


def spectral_moments(surface: Surface, cutoff: float | None = None, window: str | None = None) -> Moments:
    """m0, m2, m4 as the module docstring says; ``cutoff`` = lambda_c in m (None: default),
    ``window`` one of WINDOWS (None: 'none' for a periodic map, else 'tukey')."""
    window = window or ("none" if surface.periodic else "tukey")
    if window not in WINDOWS:
        raise SurfaceError(f"window {window!r} unknown; allowed: {', '.join(WINDOWS)}")
    sampling = (surface.dx,) if surface.is_profile else (surface.dx, surface.dy)
    cutoff = DEFAULT_CUTOFF_INTERVALS * max(sampling) if cutoff is None else float(cutoff)
    if not cutoff >= 2.0 * max(sampling) * (1 - 1e-12):
        raise SurfaceError(
            f"{surface.source}: cut-off wavelength {cutoff:.4g} m is shorter than the Nyquist wavelength "
            f"2 x {max(sampling):.4g} m; allowed: >= {2 * max(sampling):.4g} m"
        )
    z = detrended(surface)
    m0 = float(np.mean(z**2))
    # the heights' size, not only their range: a constant map has no range, and its plane's
    # round-off (1e-21 m on heights of 1 um) would pass for roughness
    size = max(float(np.ptp(surface.heights)), float(np.max(np.abs(surface.heights))))
    if not m0 > (ROUNDOFF * size) ** 2:
        raise SurfaceError(f"{surface.source}: all heights lie on a plane (sigma = 0): no roughness to describe")
    q_cut = 2.0 * np.pi / cutoff
    m2, m4 = [], []
    for profiles, spacing in zip((z, z.T), sampling):
        q, power = profile_power(profiles, spacing, window)
        keep = (q > 0) & (q <= q_cut * (1 + 1e-12))
        m2.append(float(np.sum(q[keep] ** 2 * power[keep])))
        m4.append(float(np.sum(q[keep] ** 4 * power[keep])))
    if not (np.mean(m2) > 0.0 and np.mean(m4) > 0.0):
        raise SurfaceError(f"{surface.source}: no roughness at wavelengths between the cut-off {cutoff:.4g} m and the map size")
    return Moments(m0, tuple(m2), tuple(m4), cutoff, window, sampling, detrending(surface))
