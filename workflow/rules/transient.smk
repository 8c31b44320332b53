# Transient figures (lubecontact.transient): the Table 1 contact after a stop from 1 m/s,
# under vibration and struck by shocks, and what its reconnect time's accuracy costs. config/transient.yaml (deep-merged with config["transient"]) names the
# cases; each is a scene identified by its content hash, run once into
# <results>/transient/<hash>.nc and shared by the figures that use it. Edits of the solver or
# of the unsteady package rerun the cases (TRANSIENT_SOURCES).

from lubecontact.studies import transient_cases as lcstudy

TRANSIENT = lcstudy.study_spec("config/transient.yaml", config.get("transient"))
TRANSIENT_CASES = lcstudy.figure_cases(TRANSIENT)
TRANSIENT_OVERRIDES = lcstudy.case_overrides(TRANSIENT, TRANSIENT_CASES)
# the convergence ladders (figure "accuracy") have their own rule: a table beside the figure
TRANSIENT_LADDERS = [name for name, figure in TRANSIENT["figures"].items() if lcstudy.is_ladder(figure)]
TRANSIENT_DRAWN = [name for name in TRANSIENT["figures"] if name not in TRANSIENT_LADDERS]
TRANSIENT_FIGURES = [f"transient_{name}" for name in TRANSIENT["figures"]]


wildcard_constraints:
    case="[0-9a-f]{16}",


rule transient_case:
    input:
        sources=TRANSIENT_SOURCES,
        base=TRANSIENT["base"],
    output:
        f"{RESULTS}/transient/{{case}}.nc",
    params:
        overrides=lambda w: TRANSIENT_OVERRIDES[w.case],
    log:
        f"{RESULTS}/logs/transient/{{case}}.log",
    threads: 1
    resources:
        runtime=30,  # minutes; the default study's longest case takes a few
        mem_mb=2000,
    # bundled with the solve jobs on a cluster (group-components: solve: N in the SLURM
    # profile): each transient case alone was one sbatch submission, 28 of the default
    # study's 32; local runs ignore groups
    group:
        "solve"
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/transient_case.py"


rule transient_figure:
    input:
        cases=lambda w: [f"{RESULTS}/transient/{c['id']}.nc" for c in TRANSIENT_CASES[w.name]],
        code="src/lubecontact/plotting/transient.py",
    output:
        png=report(f"{RESULTS}/figures/transient_{{name}}.png", category="Transient"),
        pdf=f"{RESULTS}/figures/transient_{{name}}.pdf",
    params:
        cases=lambda w: [{k: v for k, v in c.items() if k != "overrides"} for c in TRANSIENT_CASES[w.name]],
        spec=lambda w: TRANSIENT["figures"][w.name],
    wildcard_constraints:
        name="|".join(TRANSIENT_DRAWN),
    log:
        f"{RESULTS}/logs/transient/figure_{{name}}.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/transient_plot.py"


# What a reconnect time's accuracy costs: the ladder's runs -> Richardson extrapolation of
# each ladder (meshes, time-step tolerances, refinements of the mesh at rest) -> table and figure
rule transient_accuracy:
    input:
        cases=lambda w: [f"{RESULTS}/transient/{c['id']}.nc" for c in TRANSIENT_CASES[w.name]],
        code=["src/lubecontact/studies/transient_accuracy.py", "src/lubecontact/plotting/accuracy.py"],
    output:
        nc=f"{RESULTS}/data/transient_{{name}}.nc",
        md=report(f"{RESULTS}/data/transient_{{name}}.md", category="Accuracy and cost"),
        png=report(f"{RESULTS}/figures/transient_{{name}}.png", category="Accuracy and cost"),
        pdf=f"{RESULTS}/figures/transient_{{name}}.pdf",
    params:
        cases=lambda w: [{k: v for k, v in c.items() if k != "overrides"} for c in TRANSIENT_CASES[w.name]],
        title=lambda w: TRANSIENT["figures"][w.name]["title"],
    wildcard_constraints:
        name="|".join(TRANSIENT_LADDERS) or "(?!)",  # a regular expression no name matches
    log:
        f"{RESULTS}/logs/transient/accuracy_{{name}}.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/transient_accuracy.py"


rule transient_figures:
    input:
        expand(f"{RESULTS}/figures/{{figure}}.{{ext}}", figure=TRANSIENT_FIGURES, ext=["png", "pdf"]),
