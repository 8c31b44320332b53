"""Collect one figure's cases into results/data/<figure>.nc (lubecontact.grid.collect)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

import xarray as xr

from lubecontact.grid import collect
from lubecontact.output import write_case

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    paths = {Path(p).stem: p for p in snakemake.input}
    ds = collect(snakemake.params.layout, lambda case_id: xr.load_dataset(paths[case_id]))
    write_case(ds, snakemake.output[0])  # atomic netCDF write
    print(ds)
