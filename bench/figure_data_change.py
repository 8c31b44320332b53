"""What a change of the model moved in the figures: the largest relative change of each
collected value, per figure, between two builds of the figure datasets (results/data/*.nc).

    python bench/figure_data_change.py BEFORE/results/data AFTER/results/data [fig03 fig04 ...]

Build BEFORE from a worktree of the old commit and AFTER from the new one (e.g.
`snakemake --cores 1 results/data/fig04.nc ...` in each). Resistances are compared in
ln R (they span 60 decades; an open circuit, R = inf, must stay one); points that did not
converge in either build are counted, not compared. Prints a Markdown table.
"""

import sys
from pathlib import Path

import numpy as np
import xarray as xr

QUANTITIES = ("contact_resistance", "friction_coefficient", "fluid_load_fraction", "min_film_thickness",
              "real_contact_area")


def change(before: xr.DataArray, after: xr.DataArray, logarithmic: bool) -> float:
    """Largest |after - before| relative to |before| (or of ln R), over finite pairs."""
    a, b = np.asarray(before, dtype=float), np.asarray(after, dtype=float)
    both = np.isfinite(a) & np.isfinite(b)
    if logarithmic:
        both &= (a > 0) & (b > 0)
        return float(np.max(np.abs(np.log(b[both]) - np.log(a[both])), initial=0.0))
    scale = np.maximum(np.abs(a[both]), 1e-300)
    return float(np.max(np.abs(b[both] - a[both]) / scale, initial=0.0))


def main(before_dir: Path, after_dir: Path, figures: list[str]) -> None:
    print("| figure | points | not converged (before / after) | " + " | ".join(
        "max |Δ ln R|" if q == "contact_resistance" else f"max rel. Δ {q}" for q in QUANTITIES) + " |")
    print("|---" * (3 + len(QUANTITIES)) + "|")
    for figure in figures:
        before = xr.open_dataset(before_dir / f"{figure}.nc")
        after = xr.open_dataset(after_dir / f"{figure}.nc")
        ok = (before.converged == 1) & (after.converged == 1)
        cells = [f"{change(before[q].where(ok), after[q].where(ok), q == 'contact_resistance'):.2g}" for q in QUANTITIES]
        opened = int(((np.isinf(before.contact_resistance)) != (np.isinf(after.contact_resistance))).sum())
        note = f" ({opened} open circuits changed)" if opened else ""
        print(f"| {figure} | {int(ok.size)} | {int((before.converged == 0).sum())} / {int((after.converged == 0).sum())}{note} | "
              + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    before_dir, after_dir = Path(sys.argv[1]), Path(sys.argv[2])
    names = sys.argv[3:] or sorted(p.stem for p in before_dir.glob("fig*.nc") if (after_dir / p.name).exists())
    main(before_dir, after_dir, names)
