"""Error budget of the accuracy study: Richardson extrapolation, error of every mesh against
it, domain and tolerance checks (lubecontact.convergence) -> netCDF and Markdown."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

import xarray as xr

from lubecontact.convergence import accuracy_table, markdown
from lubecontact.joblog import job_log
from lubecontact.output import write_case

with job_log(snakemake.log[0]):
    table = accuracy_table(xr.load_dataset(snakemake.input.study))
    write_case(table, snakemake.output.nc)
    Path(snakemake.output.md).write_text(markdown(table, snakemake.params.targets))
    print(table.attrs["notes"] or "no notes")
