# Curves swept speeding up and slowing down (lubecontact.sweep, direction "both"): where a
# figure's contact has two steady states (lift-off and touch-down, docs/physics.md section
# 23), both branches, which the figure build's cold cases cannot show. Config key
# `hysteresis`: the figure grids to follow (their curves; `grid`, `set` and speeds as the
# figure has them). Each curve is one case, <results>/hysteresis/<id>.nc (id: a digest of
# its scene and speeds, studies/hysteresis_cases.py); an edit of the solver, of the sweep or
# of the scene reruns the curves it decides. Needs common.smk and cases.smk (GRIDS).

from lubecontact.studies import hysteresis_cases as lchysteresis

_hysteresis_problems = lchysteresis.study_problems(config["hysteresis"], GRIDS)
if _hysteresis_problems:
    raise lcgrid.GridError("\n".join(_hysteresis_problems))
HYSTERESIS = {name: lchysteresis.curve_cases(GRIDS[name]) for name in config["hysteresis"]}
HYSTERESIS_CURVES = {c["id"]: c for cases in HYSTERESIS.values() for c in cases}
HYSTERESIS_FIGURES = [f"hysteresis_{name}" for name in HYSTERESIS]


rule hysteresis_curve:
    input:
        sources=[*SOLVER_SOURCES, "src/lubecontact/studies/sweep.py"],
        scene=lambda w: HYSTERESIS_CURVES[w.curve]["scene"],
    output:
        f"{RESULTS}/hysteresis/{{curve}}.nc",
    params:
        curve=lambda w: HYSTERESIS_CURVES[w.curve],
    wildcard_constraints:
        curve="[0-9a-f]{16}",
    log:
        f"{RESULTS}/logs/hysteresis/{{curve}}.log",
    threads: 1
    resources:
        runtime=30,  # minutes; a Fig. 8 curve (26 speeds both ways at 51 x 51) takes seconds
        mem_mb=2000,
    group:
        "solve"
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/hysteresis_curve.py"


rule hysteresis_figure:
    input:
        curves=lambda w: [f"{RESULTS}/hysteresis/{c['id']}.nc" for c in HYSTERESIS[w.name]],
        # the module and the styles and words it takes from the other figures
        code=[f"src/lubecontact/plotting/{name}.py" for name in ("hysteresis", "figures", "transient")],
    output:
        png=report(f"{RESULTS}/figures/hysteresis_{{name}}.png", category="Two steady states"),
        pdf=f"{RESULTS}/figures/hysteresis_{{name}}.pdf",
    params:
        labels=lambda w: [c["label"] for c in HYSTERESIS[w.name]],
        title=lambda w: (f"{SPECS[w.name]['title'].split(':')[0]}, speeding up (solid) and slowing down (dashed): "
                         "where they part, the contact has two steady states"),
    wildcard_constraints:
        name="|".join(HYSTERESIS) or "(?!)",  # a regular expression no name matches
    log:
        f"{RESULTS}/logs/hysteresis/figure_{{name}}.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/hysteresis_plot.py"
