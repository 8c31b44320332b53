"""Draw one transient figure (lubecontact.plotting.transient) from its case files: PNG and PDF."""

import sys

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)
import xarray as xr

from lubecontact.plotting import transient as plots
from lubecontact.plotting.figures import save, unit_label
from lubecontact.studies import transient_cases as study

# the figures of curves (config/transient.yaml: a list of {label, set}), each drawn by its own function
CURVE_FIGURES = {"stop": plots.stop_figure, "shock": plots.shock_figure, "grease": plots.grease_stop_figure}

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    spec, cases = snakemake.params.spec, snakemake.params.cases
    data = [xr.load_dataset(path) for path in snakemake.input.cases]
    name = snakemake.wildcards.name
    if name in CURVE_FIGURES:
        fig = CURVE_FIGURES[name]([(c["label"], ds) for c, ds in zip(cases, data)], spec["title"])
    elif "x" in spec:  # a design chart: reconnect, temperature
        points = [{**c, "ds": ds} for c, ds in zip(cases, data)]
        fig = plots.reconnect_figure(points, study.key_words(spec["x"]), unit_label(study.key_units(spec["x"])),
                                     spec["title"], log_x=spec.get("x_scale", "log") == "log")
    else:
        fig = plots.vibration_figure(data[0], spec["title"])
    save(fig, [snakemake.output.png, snakemake.output.pdf])
