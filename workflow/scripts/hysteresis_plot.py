"""Draw one figure of curves swept speeding up and slowing down (lubecontact.plotting.hysteresis): PNG and PDF."""

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)
import xarray as xr

from lubecontact.io.job_log import job_log
from lubecontact.plotting.figures import save
from lubecontact.plotting.hysteresis import hysteresis_figure

with job_log(snakemake.log[0]):
    curves = [(label, xr.load_dataset(path)) for label, path in zip(snakemake.params.labels, snakemake.input.curves)]
    save(hysteresis_figure(curves, snakemake.params.title), [snakemake.output.png, snakemake.output.pdf])
    for label, ds in curves:
        print(f"{label}: {ds.attrs['hysteresis']}")
