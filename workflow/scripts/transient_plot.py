"""Draw one transient figure (lubecontact.unsteady.plots) from its case files: PNG and PDF."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

import xarray as xr

from lubecontact.plotting import save
from lubecontact.unsteady import plots, study

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    spec, cases = snakemake.params.spec, snakemake.params.cases
    data = [xr.load_dataset(path) for path in snakemake.input.cases]
    name = snakemake.wildcards.name
    if name == "stop":
        fig = plots.stop_figure([(c["label"], ds) for c, ds in zip(cases, data)], spec["title"])
    elif name == "reconnect":
        points = [{**c, "ds": ds} for c, ds in zip(cases, data)]
        fig = plots.reconnect_figure(points, spec["x"], study.key_units(spec["x"]), spec["title"])
    else:
        fig = plots.vibration_figure(data[0], spec["title"])
    save(fig, [snakemake.output.png, snakemake.output.pdf])
