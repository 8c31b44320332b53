"""Figure accuracy_cost from results/data/accuracy_cost.nc (lubecontact.convergence)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

import xarray as xr

from lubecontact import plotting
from lubecontact.convergence import plot_accuracy_cost
from lubecontact.joblog import job_log

with job_log(snakemake.log[0]):
    fig = plot_accuracy_cost(xr.load_dataset(snakemake.input.data))
    plotting.save(fig, [snakemake.output.png, snakemake.output.pdf])
