"""Draw the measured surfaces' profile spectra (lubecontact.surfaces.figure) to PNG and PDF."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

from lubecontact.surfaces import parameters, read_surface, spectral_moments
from lubecontact.surfaces.figure import psd_figure
from lubecontact.plotting import save

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    entries = []
    for path in snakemake.input.surfaces:
        surface = read_surface(path)
        entries.append((Path(path).name, surface, parameters(spectral_moments(surface))))
    fig = psd_figure(entries, "Measured surfaces: profile spectra and McCool parameters")
    save(fig, [snakemake.output.png, snakemake.output.pdf])
