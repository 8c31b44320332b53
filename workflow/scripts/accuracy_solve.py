"""Run the accuracy study (lubecontact.studies.accuracy.run_study): every mesh, domain length and
tolerance of the study plan (JSON input) at each speed, each solve timed; the raw study Dataset."""

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)

from lubecontact.io.case_schema import write_case
from lubecontact.io.job_log import job_log
from lubecontact.io.job_plans import read_plan
from lubecontact.studies.accuracy import run_study

with job_log(snakemake.log[0]):
    study = run_study(read_plan(snakemake.input.plan), log=lambda line: print(line, flush=True))
    write_case(study, snakemake.output[0])  # atomic: temp file + rename
