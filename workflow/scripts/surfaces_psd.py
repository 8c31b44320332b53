"""Draw the measured surfaces' profile spectra (lubecontact.plotting.surfaces) to PNG and PDF."""

import sys
from pathlib import Path

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)

from lubecontact.plotting.figures import save
from lubecontact.plotting.surfaces import psd_figure
from lubecontact.surfaces import parameters, read_surface, spectral_moments

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    entries = []
    for path in snakemake.input.surfaces:
        surface = read_surface(path)
        entries.append((Path(path).name, surface, parameters(spectral_moments(surface))))
    fig = psd_figure(entries, "Measured surfaces: profile spectra and McCool parameters")
    save(fig, [snakemake.output.png, snakemake.output.pdf])
