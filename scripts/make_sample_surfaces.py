#!/usr/bin/env python
"""Write the sample measured surfaces of config/surfaces/ (seeded, so the files are
reproducible byte for byte): two isotropic random surfaces with a rolled-off self-affine
spectrum (lubecontact.surfaces.synthetic), as plain text with a Gwyddion-style header
(size and unit in the file), a format SurfaceTopography reads as an instrument file.

  ground.asc  sigma 0.5 um, roll-off 120 um, short-wavelength end 16 um, H = 0.8
              (McCool: eta ~ 1e9 1/m^2, R_peak ~ 110 um, close to the paper's Table 1)
  honed.asc   sigma 1.0 um, roll-off 60 um, short-wavelength end 16 um, H = 0.5

Both are 128 x 128 points over 512 um x 512 um (4 um sampling). Usage (repository root):
  python scripts/make_sample_surfaces.py [--out config/surfaces]
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
from lubecontact.surfaces.synthetic import isotropic_surface, rolled_power_law  # noqa: E402

N, SIDE = 128, 512e-6  # points per side, side length (m)
SAMPLES = {  # name: (seed, rms height m, roll-off wavelength m, shortest wavelength m, Hurst exponent)
    "ground": (20221, 0.5e-6, 120e-6, 16e-6, 0.8),
    "honed": (20222, 1.0e-6, 60e-6, 16e-6, 0.5),
}


def write(path: Path, z: np.ndarray, description: str) -> None:
    with path.open("w") as out:
        out.write(f"# Channel: Height ({description})\n")
        out.write(f"# Width: {SIDE * 1e6:g} \u00b5m\n# Height: {SIDE * 1e6:g} \u00b5m\n# Value units: m\n")
        np.savetxt(out, z, fmt="%.5e")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="config/surfaces", help="output directory")
    out = Path(parser.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)
    for name, (seed, rms, rolloff, shortest, hurst) in SAMPLES.items():
        spectrum = lambda q, r=2 * np.pi / rolloff, s=2 * np.pi / shortest, h=hurst: rolled_power_law(q, r, s, h)  # noqa: E731
        z = isotropic_surface(spectrum, N, SIDE, seed, rms=rms)
        text = f"synthetic sample, seed {seed}, rolled power law {rolloff * 1e6:g}/{shortest * 1e6:g} um, H {hurst}"
        write(out / f"{name}.asc", z, text)
        print(f"wrote {out / f'{name}.asc'}")


if __name__ == "__main__":
    main()
