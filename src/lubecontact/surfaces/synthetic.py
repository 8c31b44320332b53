"""Seeded isotropic random surfaces with a known spectrum (tests and the shipped samples).

A periodic n x n map of side L is the sum of the grid's Fourier modes q = 2 pi (i, j) / L
with amplitude sqrt(C(|q|) dq^2) and random phases (the seed; phase(-q) = -phase(q), so
the heights are real), so its mean square is the sum of C dq^2 over the grid and its statistics follow the isotropic areal power
spectral density C(q) (m^4, m0 = integral of C over the q-plane), with no sampling noise
in the amplitudes. Profile moments of such a surface (docs/physics.md section 18):
m0 = 2 pi int C q dq, m2 = pi int C q^3 dq, m4 = (3 pi / 4) int C q^5 dq.
"""

from __future__ import annotations

import numpy as np


def rolled_power_law(q, rolloff: float, cutoff: float, hurst: float):
    """Unit-level self-affine spectrum: 1 below ``rolloff``, (q/rolloff)^(-2(1+H)) up to
    ``cutoff`` (wave numbers in rad/m), 0 beyond."""
    q = np.asarray(q, dtype=float)
    c = np.where(q < rolloff, 1.0, (np.maximum(q, rolloff) / rolloff) ** (-2.0 * (1.0 + hurst)))
    return np.where(q <= cutoff, c, 0.0)


def isotropic_surface(spectrum, n: int, length: float, seed: int, rms: float | None = None) -> np.ndarray:
    """Heights z[iy, ix] (m) of a periodic n x n map of side ``length`` (m) whose areal
    spectrum is ``spectrum(q)`` (m^4); ``rms`` rescales the heights to that RMS (m)."""
    rng = np.random.default_rng(seed)
    q1 = 2.0 * np.pi * np.fft.fftfreq(n, d=length / n)
    qx, qy = np.meshgrid(q1, q1, indexing="xy")
    dq = 2.0 * np.pi / length
    c = np.asarray(spectrum(np.hypot(qx, qy)), dtype=float)
    c[0, 0] = 0.0  # no mean height
    phase = 2.0 * np.pi * rng.random((n, n))
    phase = phase - np.roll(phase[::-1, ::-1], 1, axis=(0, 1))  # phase(-q) = -phase(q): real heights
    z = n * n * np.real(np.fft.ifft2(np.sqrt(c * dq**2) * np.exp(1j * phase)))
    if rms is not None:
        z *= rms / np.sqrt(np.mean(z**2))
    return z
