"""The transient's accuracy study (lubecontact.studies.transient_accuracy): the ladder's
case files -> table (netCDF, Markdown) -> figure (PNG, PDF)."""

from pathlib import Path

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)
import xarray as xr

from lubecontact.io.case_schema import write_case
from lubecontact.io.job_log import job_log
from lubecontact.plotting.accuracy import plot_transient_accuracy
from lubecontact.plotting.figures import save
from lubecontact.studies.transient_accuracy import ladder_table, markdown

with job_log(snakemake.log[0]):
    table = ladder_table(snakemake.params.cases, [xr.load_dataset(path) for path in snakemake.input.cases])
    table.attrs["title"] = snakemake.params.title
    write_case(table, snakemake.output.nc)
    Path(snakemake.output.md).write_text(markdown(table))
    save(plot_transient_accuracy(table, snakemake.params.title), [snakemake.output.png, snakemake.output.pdf])
    print(table.attrs["notes"] or "no notes")
