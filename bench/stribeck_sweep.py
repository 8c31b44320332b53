"""Table 1 speed sweep (the Stribeck curve of Figs. 4-5 at sigma = 0.5 um), 51 x 51 by default.

Prints, per speed, resistance, friction coefficient, fluid load fraction and minimum film,
and writes them as JSON (``--out``), so that a change of the near-contact flow or of the
friction model can be measured before and after (earlier results: bench/HISTORY.md).

    PYTHONPATH=src python bench/stribeck_sweep.py [--nodes 51] [--speeds 11] [--set effects.cavitation=jfo] [--out f.json]

``--speeds 26`` is the figures' grid (config/figures/fig04.yaml: 1e-4 ... 10 m/s, 26 speeds).
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

import lubecontact as lc
from lubecontact.scene.scene import parse_override

COLUMNS = ("contact_resistance", "friction_coefficient", "fluid_load_fraction", "min_film_thickness", "converged")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--nodes", type=int, default=51)
    parser.add_argument("--speeds", type=int, default=11, help="number of speeds, log-spaced over 1e-4 ... 10 m/s")
    parser.add_argument("--set", action="append", default=[], help="scene override KEY=VALUE")
    parser.add_argument("--out")
    args = parser.parse_args()
    overrides = {"mesh.nx": args.nodes, "mesh.ny": args.nodes, **dict(parse_override(s) for s in args.set)}
    scene = lc.load_scene("config/scenes/table1.yaml", overrides)
    speeds = np.geomspace(1e-4, 10.0, args.speeds)
    start = time.perf_counter()
    ds = lc.sweep(scene, speeds, progress=False)
    rows = {name: ds[name].values.tolist() for name in COLUMNS}
    rows["speed"] = speeds.tolist()
    print(f"{'U m/s':>9} {'R ohm':>11} {'f':>8} {'fluid':>7} {'h_min um':>9} conv")
    for i, u in enumerate(speeds):
        print(f"{u:9.3g} {rows['contact_resistance'][i]:11.4g} {rows['friction_coefficient'][i]:8.4f} "
              f"{rows['fluid_load_fraction'][i]:7.4f} {1e6 * rows['min_film_thickness'][i]:9.4f} {rows['converged'][i]}")
    print(f"wall time {time.perf_counter() - start:.1f} s")
    if args.out:
        with open(args.out, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
