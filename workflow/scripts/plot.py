"""Render one figure from results/data/<figure>.nc (lubecontact.plotting) to PNG and PDF."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

import xarray as xr

from lubecontact import plotting
from lubecontact.joblog import job_log

with job_log(snakemake.log[0]):
    ds = xr.load_dataset(snakemake.input.data)
    reference = xr.load_dataset(snakemake.input.reference[0]) if snakemake.input.reference else None
    fig = plotting.render(ds, snakemake.params.plot, snakemake.params.title, reference=reference)
    plotting.save(fig, [snakemake.output.png, snakemake.output.pdf])
