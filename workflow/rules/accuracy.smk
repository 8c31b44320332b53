# What accuracy costs (lubecontact.studies.accuracy): the Table 1 contact on a ladder of meshes,
# domain lengths and solver tolerances at speeds in every regime, each solve timed; then
# Richardson extrapolation -> error of every mesh -> table (netCDF + Markdown) -> figure.
# The study is config/accuracy.yaml, deep-merged with config["accuracy"] (config/test.yaml
# makes it tiny). Needs SOLVER_SOURCES (cases.smk).

from snakemake.exceptions import WorkflowError

from lubecontact.studies import accuracy_plan as lcconv

ACCURACY = lcconv.study_spec("config/accuracy.yaml", config.get("accuracy"))
# The timing job takes every core of a local run, so it runs alone and its wall times are
# those of one solve on an otherwise idle machine (each solve is single-threaded). Modes
# that run nothing (--report, --lint) have no core count.
try:
    ACCURACY_THREADS = workflow.cores
except WorkflowError:
    ACCURACY_THREADS = 1


rule accuracy_solve:
    input:
        sources=SOLVER_SOURCES,
        study="config/accuracy.yaml",
        code=["src/lubecontact/studies/accuracy.py", "src/lubecontact/studies/accuracy_plan.py"],
        plan=plan_path("accuracy/study", ACCURACY),
    output:
        f"{RESULTS}/accuracy/study.nc",
    log:
        f"{RESULTS}/logs/accuracy/solve.log",
    threads: ACCURACY_THREADS
    resources:
        runtime=60,
        mem_mb=3000,
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/accuracy_solve.py"


rule accuracy_table:
    input:
        study=f"{RESULTS}/accuracy/study.nc",
        code="src/lubecontact/studies/accuracy.py",
    output:
        nc=f"{RESULTS}/data/accuracy_cost.nc",
        md=report(f"{RESULTS}/data/accuracy_cost.md", category="Accuracy and cost"),
    params:
        targets=ACCURACY["targets"],
    log:
        f"{RESULTS}/logs/accuracy/table.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/accuracy_table.py"


rule accuracy_figure:
    input:
        data=f"{RESULTS}/data/accuracy_cost.nc",
        code="src/lubecontact/plotting/accuracy.py",
    output:
        png=report(
            f"{RESULTS}/figures/accuracy_cost.png",
            caption="../scripts/accuracy_caption.rst",
            category="Accuracy and cost",
        ),
        pdf=f"{RESULTS}/figures/accuracy_cost.pdf",
    log:
        f"{RESULTS}/logs/accuracy/figure.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/accuracy_plot.py"
