# Figure grids -> cases -> chunks, at parse time (lubecontact.grid; library code).
#
# Each figure's YAML (config/figures/figNN.yaml, deep-merged with config["figures"][figNN])
# expands into scenes; a case is identified by its scene's content hash, so a case shared
# by several figures is one file, results/cases/<hash>.nc, solved once. A bad value fails
# here, before anything runs, naming the figure, the key and the value.

import sys
from pathlib import Path

from snakemake.utils import validate

# Run the library of this tree (src/), the very files declared as solve inputs, whatever
# lubecontact may be installed elsewhere; the scripts do the same.
sys.path.insert(0, str(Path(workflow.basedir) / "src"))
from lubecontact import grid as lcgrid


validate(config, "../schemas/config.schema.yaml")

FIGURES = list(config["figures"])
SPECS = {}
for _figure in FIGURES:
    SPECS[_figure] = lcgrid.figure_spec(_figure, config["figure_dir"], config["figures"])
    validate(SPECS[_figure], "../schemas/figure.schema.yaml")
GRIDS = lcgrid.expand_all(SPECS)
CHUNKS = lcgrid.plan_chunks(
    GRIDS.values(), None if config["cases_per_job"] == "curve" else config["cases_per_job"]
)
# The library files that decide a case's answer (solver, scene and what they import): an
# edit reruns the solve jobs; edits of plotting.py or grid.py do not.
SOLVER_SOURCES = [str(p) for p in lcgrid.solver_sources("src/lubecontact")]


wildcard_constraints:
    figure="|".join(FIGURES),


def case_path(case_id):
    return f"results/cases/{case_id}.nc"


def solve_resources(cases):
    """runtime (min) and mem_mb of a job solving ``cases``, from config solve_resources."""
    r = config["solve_resources"]
    nodes = [c.nodes for c in cases]
    seconds = sum(r["case_seconds"] * (n / 2601) ** 1.25 for n in nodes)
    runtime = int(r["startup_minutes"] + seconds / 60 + 1)
    mem_mb = int(r["mem_mb"] + r["mem_mb_per_10k_nodes"] * max(nodes) / 1e4)
    return runtime, mem_mb
