"""Run the accuracy study (lubecontact.convergence.run_study): every mesh, domain length and
tolerance of params.study at each speed, each solve timed; the raw study Dataset."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

from lubecontact.convergence import run_study
from lubecontact.output import write_case

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    study = run_study(snakemake.params.study, log=lambda line: print(line, flush=True))
    write_case(study, snakemake.output[0])  # atomic: temp file + rename
