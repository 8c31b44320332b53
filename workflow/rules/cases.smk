# Figure grids -> cases -> chunks, at parse time (lubecontact.studies.figure_grids).
#
# Each figure's YAML (config/figures/figNN.yaml, deep-merged with config["figures"][figNN])
# expands into scenes; a case is identified by its scene's content hash, so a case shared
# by several figures is one file, <results>/cases/<hash>.nc, solved once. A bad value fails
# here, before anything runs, naming the figure, the key and the value. Needs common.smk.

FIGURES = list(config["figures"])
SPECS = {}
for _figure in FIGURES:
    SPECS[_figure] = lcgrid.figure_spec(_figure, config["figure_dir"], config["figures"])
    try:
        validate(SPECS[_figure], "../schemas/figure.schema.yaml")
    except WorkflowError as _err:  # Snakemake's words name neither the figure nor its file
        raise lcgrid.GridError(f"figure {_figure} ({config['figure_dir']}/{_figure}.yaml, deep-merged with config "
                               f"figures: {_figure}) does not fit workflow/schemas/figure.schema.yaml: "
                               f"{_err.args[-1] if _err.args else _err}") from None
_missing = lcgrid.missing_comparisons(SPECS)
if _missing:
    raise lcgrid.GridError("\n".join(_missing))
GRIDS = lcgrid.expand_all(SPECS)
# what each figure's plot: section names, checked now, not in its plot job after every solve
_plot_problems = [problem for grid in GRIDS.values() for problem in lcplotspec.plot_problems(grid)]
if _plot_problems:
    raise lcgrid.GridError("the figures' plot sections (config/figures/figNN.yaml, config figures:):\n  "
                        + "\n  ".join(_plot_problems))
CHUNKS = lcgrid.plan_chunks(
    GRIDS.values(), None if config["cases_per_job"] == "curve" else config["cases_per_job"]
)


wildcard_constraints:
    figure="|".join(FIGURES),


# Every case of this config. A case file counts only if it is complete (it opens, reads
# back, carries its scene hash and solver fingerprint: lubecontact.io.case_files); any other
# file under a case's name (truncated, overwritten) is moved to cases/.corrupt/ here, so
# Snakemake sees the case missing and solves it again, and rule all (which lists every
# case and data file) rebuilds what depends on it. Only the main Snakemake process does
# this, never a job on a cluster node.
ALL_CASES = {c.id: case_path(c.id) for chunk in CHUNKS for c in chunk.cases}
try:
    _main_process = workflow.is_main_process
except AttributeError:  # an API without execution settings (e.g. some linters)
    _main_process = False
if _main_process:
    for _line in lccases.quarantine(ALL_CASES, f"{RESULTS}/cases/.complete.json"):
        print(f"lubecontact: {_line}", file=sys.stderr)


def solve_seconds(cases):
    """Estimated seconds of a job solving ``cases`` (config solve_resources, with headroom)."""
    r = config["solve_resources"]
    return sum(r["case_seconds"] * (c.nodes / 2601) ** 1.25 for c in cases)


def solve_resources(cases):
    """runtime (min) and mem_mb of a job solving ``cases``, from config solve_resources."""
    r = config["solve_resources"]
    nodes = [c.nodes for c in cases]
    runtime = int(r["startup_minutes"] + solve_seconds(cases) / 60 + 1)
    mem_mb = int(r["mem_mb"] + r["mem_mb_per_10k_nodes"] * max(nodes) / 1e4)
    return runtime, mem_mb
