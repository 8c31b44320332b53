# lubecontact: regenerate the figures of Jackson & Angadi (2022), Lubricants 10, 32, and the
# project's own (accuracy, measured surfaces, transients, two steady states).
#
#   snakemake --workflow-profile workflow/profiles/default                 # all figures
#   snakemake --workflow-profile workflow/profiles/default --configfile config/test.yaml
#   snakemake --report results/report.html                                 # HTML report
#
# A root Snakefile hides workflow/profiles/default: pass --workflow-profile as above.
# config/test.yaml writes to results/test/ (config key `results`).
# Layout of results/ and what reruns when: results/README.md.

from snakemake.utils import min_version

min_version("9.0")


configfile: "config/config.yaml"


# the report's landing page: what this run is (workflow/report/workflow.rst)
report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/cases.smk"
include: "workflow/rules/solve.smk"
include: "workflow/rules/collect.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/accuracy.smk"
include: "workflow/rules/surfaces.smk"
include: "workflow/rules/transient.smk"
include: "workflow/rules/hysteresis.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/scheduler.smk"


localrules:
    all,
    collect,
    plot,
    accuracy_table,
    accuracy_figure,
    surfaces_psd,
    transient_figure,
    hysteresis_figure,


# The netCDF products besides the cases: each is a target of rule all, and at start one that
# does not read back (truncated by a full disk, overwritten) is moved to .corrupt/ beside it,
# each folder with its own memo of files found complete, as an incomplete case is
# (cases.smk), so a rerun builds it again instead of failing on it.
DATASETS = [
    *(f"{RESULTS}/data/{name}.nc" for name in [*FIGURES, "accuracy_cost", *(f"transient_{n}" for n in TRANSIENT_LADDERS)]),
    f"{RESULTS}/accuracy/study.nc",
    *(f"{RESULTS}/transient/{case}.nc" for case in TRANSIENT_OVERRIDES),
    *(f"{RESULTS}/hysteresis/{curve}.nc" for curve in HYSTERESIS_CURVES),
]
if _main_process:
    for _folder in dict.fromkeys(str(Path(p).parent) for p in DATASETS):
        _paths = [p for p in DATASETS if str(Path(p).parent) == _folder]
        for _line in lccases.quarantine_datasets(_paths, f"{_folder}/.complete.json"):
            print(f"lubecontact: {_line}", file=sys.stderr)


# Every product is a target, intermediates included: a case or data file deleted (or moved
# aside as incomplete, cases.smk, or above) is rebuilt by a plain rerun, and what depends on
# it follows (its input is then newer).
rule all:
    input:
        expand(f"{RESULTS}/figures/{{figure}}.{{ext}}", figure=FIGURES, ext=["png", "pdf"]),
        expand(f"{RESULTS}/figures/accuracy_cost.{{ext}}", ext=["png", "pdf"]),
        f"{RESULTS}/data/accuracy_cost.md",
        DATASETS,
        ALL_CASES.values(),
        expand(f"{RESULTS}/figures/surfaces_psd.{{ext}}", ext=["png", "pdf"]) if SURFACE_FILES else [],
        expand(f"{RESULTS}/figures/{{figure}}.{{ext}}", figure=TRANSIENT_FIGURES, ext=["png", "pdf"]),
        expand(f"{RESULTS}/data/transient_{{name}}.md", name=TRANSIENT_LADDERS),
        expand(f"{RESULTS}/figures/{{figure}}.{{ext}}", figure=HYSTERESIS_FIGURES, ext=["png", "pdf"]),
    default_target: True
