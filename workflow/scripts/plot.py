"""Render one figure from results/data/<figure>.nc (lubecontact.plotting.figures) to PNG and PDF."""

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)
import xarray as xr

from lubecontact.io.job_log import job_log
from lubecontact.plotting import figures as plotting

with job_log(snakemake.log[0]):
    ds = xr.load_dataset(snakemake.input.data)
    reference = xr.load_dataset(snakemake.input.reference[0]) if snakemake.input.reference else None
    fig = plotting.render(ds, snakemake.params.plot, snakemake.params.title, reference=reference)
    plotting.save(fig, [snakemake.output.png, snakemake.output.pdf])
