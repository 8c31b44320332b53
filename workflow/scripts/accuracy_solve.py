"""Run the accuracy study (lubecontact.convergence.run_study): every mesh, domain length and
tolerance of the study plan (JSON input) at each speed, each solve timed; the raw study Dataset."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

from lubecontact.convergence import run_study
from lubecontact.joblog import job_log
from lubecontact.output import write_case
from lubecontact.plans import read_plan

with job_log(snakemake.log[0]):
    study = run_study(read_plan(snakemake.input.plan), log=lambda line: print(line, flush=True))
    write_case(study, snakemake.output[0])  # atomic: temp file + rename
