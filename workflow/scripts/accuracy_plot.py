"""Figure accuracy_cost from results/data/accuracy_cost.nc (lubecontact.studies.accuracy)."""

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)
import xarray as xr

from lubecontact.io.job_log import job_log
from lubecontact.plotting import figures as plotting
from lubecontact.plotting.accuracy import plot_accuracy_cost

with job_log(snakemake.log[0]):
    fig = plot_accuracy_cost(xr.load_dataset(snakemake.input.data))
    plotting.save(fig, [snakemake.output.png, snakemake.output.pdf])
