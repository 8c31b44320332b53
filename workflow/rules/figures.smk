# Figures from <results>/data/*.nc only (lubecontact.plotting.figures): PNG (in the report) and PDF.
# Inputs are the data and plotting/figures.py; the plot section of the grid YAML is a param, so a
# style change re-renders without solving or collecting.


rule plot:
    input:
        data=f"{RESULTS}/data/{{figure}}.nc",
        code="src/lubecontact/plotting/figures.py",
        # compare: figXX draws that figure's data dashed on the same axes (figNNp: the paper's)
        reference=lambda w: [f"{RESULTS}/data/{SPECS[w.figure]['compare']}.nc"] if "compare" in SPECS[w.figure] else [],
    output:
        png=report(
            f"{RESULTS}/figures/{{figure}}.png",
            caption="../scripts/figure_caption.rst",
            category="Figures",
            labels=lambda w: {"figure": w.figure},
        ),
        pdf=f"{RESULTS}/figures/{{figure}}.pdf",
    params:
        data=lambda w: f"{RESULTS}/data/{w.figure}.nc",
        plot=lambda w: SPECS[w.figure]["plot"],
        title=lambda w: SPECS[w.figure]["title"],
        caption=lambda w: SPECS[w.figure]["caption"],
    log:
        f"{RESULTS}/logs/plot/{{figure}}.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/plot.py"
