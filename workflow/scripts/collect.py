"""Collect one figure's cases into <results>/data/<figure>.nc (lubecontact.studies.collect).

A case file that does not read fails the job with its path and the remedy: the next run
of Snakemake moves it aside and solves the case again (workflow/rules/cases.smk)."""

from pathlib import Path

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)

from lubecontact.io.case_files import read_case
from lubecontact.io.case_schema import write_case
from lubecontact.io.job_log import job_log
from lubecontact.io.job_plans import read_plan
from lubecontact.studies.collect import collect

with job_log(snakemake.log[0]):
    paths = {Path(p).stem: p for p in snakemake.input.cases}
    ds = collect(read_plan(snakemake.input.plan), lambda case_id: read_case(paths[case_id]))
    write_case(ds, snakemake.output[0])  # atomic netCDF write
    print(ds)
