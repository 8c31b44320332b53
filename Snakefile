# lubecontact: regenerate Figures 3-11 of Jackson & Angadi (2022), Lubricants 10, 32.
#
#   snakemake --workflow-profile workflow/profiles/default                 # all figures
#   snakemake --workflow-profile workflow/profiles/default --configfile config/test.yaml
#   snakemake --report results/report.html                                 # HTML report
#
# A root Snakefile hides workflow/profiles/default: pass --workflow-profile as above.
# Layout of results/ and what reruns when: results/README.md.

from snakemake.utils import min_version

min_version("9.0")


configfile: "config/config.yaml"


include: "workflow/rules/cases.smk"
include: "workflow/rules/solve.smk"
include: "workflow/rules/collect.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/accuracy.smk"
include: "workflow/rules/transient.smk"


localrules:
    all,
    collect,
    plot,
    accuracy_table,
    accuracy_figure,
    transient_figure,


rule all:
    input:
        expand("results/figures/{figure}.{ext}", figure=FIGURES, ext=["png", "pdf"]),
        expand("results/figures/accuracy_cost.{ext}", ext=["png", "pdf"]),
        "results/data/accuracy_cost.md",
        expand("results/figures/{figure}.{ext}", figure=TRANSIENT_FIGURES, ext=["png", "pdf"]),
    default_target: True
