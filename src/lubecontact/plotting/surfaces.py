"""Figure of measured surfaces: the profile power spectra the moments are taken from,
the short-wavelength cut-off of m2 and m4 marked, McCool's parameters in the legend.

Library code: matplotlib's object API (no pyplot state), reads no files.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure

from lubecontact.surfaces.mccool import McCool
from lubecontact.surfaces.moments import detrended, profile_power
from lubecontact.surfaces.reading import Surface


def profile_psd(surface: Surface, axis: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """q (rad/m) and the one-sided profile PSD C(q) = P(q) / dq (m^3) along x (axis 0) or y,
    with the window the moments use; the q = 0 bin is left out."""
    z = detrended(surface)
    profiles, spacing = (z, surface.dx) if axis == 0 else (z.T, surface.dy)
    window = "none" if surface.periodic else "tukey"
    q, power = profile_power(profiles, spacing, window)
    dq = q[1] - q[0]
    return q[1:], power[1:] / dq


def psd_figure(entries: Sequence[tuple[str, Surface, McCool]], title: str = "") -> Figure:
    """One log-log panel: each surface's PSD along x (solid) and y (dashed), its cut-off
    q_c = 2 pi / lambda_c (dotted vertical line), and sigma, eta, R_peak, alpha in the legend."""
    fig = Figure(figsize=(7.0, 4.6), layout="constrained")
    ax = fig.subplots()
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red"]
    for k, (label, surface, p) in enumerate(entries):
        colour = colours[k % len(colours)]
        text = (
            f"{label}: \u03c3 = {p.sigma * 1e6:.3g} \u00b5m, \u03b7 = {p.asperity_density:.3g} m\u207b\u00b2, "
            f"R = {p.asperity_radius * 1e6:.3g} \u00b5m, \u03b1 = {p.alpha:.3g}"
            + ("" if p.gamma is None else f", \u03b3 = {p.gamma:.2f}")
        )
        q, c = profile_psd(surface, 0)
        ax.loglog(q, c, color=colour, label=text)
        if not surface.is_profile:
            q, c = profile_psd(surface, 1)
            ax.loglog(q, c, color=colour, linestyle="--", linewidth=0.8)
        q_cut = 2 * np.pi / p.moments.cutoff
        ax.axvline(q_cut, color=colour, linestyle=":", linewidth=1.2)
        ax.text(q_cut, 0.02 + 0.06 * k, f" \u03bb_c = {p.moments.cutoff * 1e6:.3g} \u00b5m", color=colour,
                transform=ax.get_xaxis_transform(), fontsize="x-small")
    ax.set_xlabel("wave number q (rad/m)")
    ax.set_ylabel("profile power spectral density C(q) (m\u00b3)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize="x-small", title="solid: along x, dashed: along y; dotted: cut-off of m2, m4",
              title_fontsize="x-small", loc="lower left")
    if title:
        fig.suptitle(title, fontsize="medium")
    return fig
