#!/usr/bin/env python
"""How far McCool's parameters from a windowed (measured-like) map scatter around the truth.

Seeded synthetic surfaces with a Gaussian correlation (ACF sigma^2 exp(-r^2/l^2), l = 6
samples; analytic: m2 = 2 sigma^2/l^2, m4 = 12 sigma^2/l^4, alpha = 3), tilted by 1 mrad and
analysed as non-periodic, for each window of lubecontact.surfaces.moments: the largest and
the mean relative error over the seeds of sigma, eta, R_peak, alpha. An accuracy study, not
a test (a few seconds):

  .venv/bin/python bench/surfaces_window.py [--seeds 8]
"""

import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from lubecontact.surfaces import parameters, spectral_moments  # noqa: E402
from lubecontact.surfaces.moments import WINDOWS  # noqa: E402
from lubecontact.surfaces.reading import from_array  # noqa: E402
from lubecontact.surfaces.synthetic import isotropic_surface  # noqa: E402

RMS, CORR, DX = 0.4e-6, 6e-6, 1e-6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, default=8)
    seeds = range(parser.parse_args().seeds)
    spectrum = lambda q: RMS**2 * CORR**2 / (4 * math.pi) * np.exp(-(q**2) * CORR**2 / 4)  # noqa: E731
    truth = np.array([RMS, 1 / (math.pi * math.sqrt(3) * CORR**2), 0.375 * math.sqrt(math.pi / 12) * CORR**2 / RMS, 3.0])
    print("| points | window | max error sigma, eta, R_peak, alpha (%) | mean error (%) |")
    print("|---|---|---|---|")
    for n in (128, 256):
        maps = [isotropic_surface(spectrum, n, n * DX, seed) + 1e-3 * DX * np.arange(n) for seed in seeds]
        for window in (w for w in WINDOWS if w != "none"):
            errors = []
            for z in maps:
                p = parameters(spectral_moments(from_array(z, (n * DX, n * DX)), window=window))
                errors.append(np.array([p.sigma, p.asperity_density, p.asperity_radius, p.alpha]) / truth - 1)
            e = 100 * np.array(errors)
            fmt = lambda v: ", ".join(f"{x:.1f}" for x in v)  # noqa: E731
            print(f"| {n}\u00b2 | {window} | {fmt(np.abs(e).max(axis=0))} | {fmt(e.mean(axis=0))} |")


if __name__ == "__main__":
    main()
