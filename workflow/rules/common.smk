# Shared by all the workflow files: the library (imported once, here), the checked config, the
# results directory, the paths of cases and plans, and the library files that decide a
# result (an edit of one of them reruns the jobs that use it; an edit of plotting or CLI
# code reruns none of them).

import sys
from pathlib import Path

from snakemake.utils import validate

# Every rule runs the library of this tree (src/), the very files declared as job inputs
# below, whatever lubecontact may be installed elsewhere: this process imports it from
# there, and every rule script imports workflow/scripts/this_tree.py first.
sys.path.insert(0, str(Path(workflow.basedir) / "src"))

import lubecontact
from lubecontact.io import case_files as lccases
from lubecontact.io import job_plans as lcplans
from lubecontact.studies import figure_grids as lcgrid
from lubecontact.studies import plot_spec as lcplotspec

validate(config, "../schemas/config.schema.yaml")

# Everything the workflow writes goes under RESULTS (config key `results`, default
# "results"; config/test.yaml: results/test).
RESULTS = config["results"]

# The library files that decide a case's answer: what the steady solve and the scene import,
# directly or not; what the transient imports besides. Plotting, studies and the CLI are
# not among them.
SOLVER_SOURCES = [str(p) for p in lcgrid.solver_sources("src/lubecontact", lcgrid.SOLVER_ROOTS)]
TRANSIENT_SOURCES = [str(p) for p in lcgrid.solver_sources("src/lubecontact", lcgrid.TRANSIENT_ROOTS)]


def case_path(case_id):
    return f"{RESULTS}/cases/{case_id}.nc"


def plan_path(name, data):
    """A job's plan as a small JSON input file (lubecontact.io.job_plans), not as params."""
    return lcplans.write_plan(f"{RESULTS}/plans/{name}.json", data)
