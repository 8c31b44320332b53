"""Collect one figure's cases into <results>/data/<figure>.nc (lubecontact.grid.collect).

A case file that does not read fails the job with its path and the remedy: the next run
of Snakemake moves it aside and solves the case again (workflow/rules/cases.smk)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

from lubecontact.casefiles import read_case
from lubecontact.grid import collect
from lubecontact.joblog import job_log
from lubecontact.output import write_case
from lubecontact.plans import read_plan


with job_log(snakemake.log[0]):
    paths = {Path(p).stem: p for p in snakemake.input.cases}
    ds = collect(read_plan(snakemake.input.plan), lambda case_id: read_case(paths[case_id]))
    write_case(ds, snakemake.output[0])  # atomic netCDF write
    print(ds)
