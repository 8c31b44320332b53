"""Error budget of the accuracy study: Richardson extrapolation, error of every mesh against
it, domain and tolerance checks (lubecontact.studies.accuracy) -> netCDF and Markdown."""

from pathlib import Path

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)
import xarray as xr

from lubecontact.io.case_schema import write_case
from lubecontact.io.job_log import job_log
from lubecontact.studies.accuracy import accuracy_table, markdown

with job_log(snakemake.log[0]):
    table = accuracy_table(xr.load_dataset(snakemake.input.study))
    write_case(table, snakemake.output.nc)
    Path(snakemake.output.md).write_text(markdown(table, snakemake.params.targets))
    print(table.attrs["notes"] or "no notes")
