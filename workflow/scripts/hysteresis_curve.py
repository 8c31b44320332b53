"""Solve one curve speeding up and slowing down (lubecontact.sweep, direction "both") and
write it; the log lists, speed by speed, what each direction reached, and where they differ most."""

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)

from lubecontact import load_scene, sweep
from lubecontact.io.case_schema import write_case
from lubecontact.io.job_log import job_log


def main(sm):
    curve = sm.params.curve
    scene = load_scene(sm.input.scene, curve["set"])
    print(f"{curve['label']}: {len(curve['speeds'])} speeds up and down ({curve['set']})")
    ds = sweep(scene, curve["speeds"], direction="both", progress=False)
    up, down = ds.sel(direction="up"), ds.sel(direction="down")
    for i, speed in enumerate(ds["speed"].values):
        print(f"{speed:g} m/s: fluid load fraction {float(up['fluid_load_fraction'][i]):.3g} up, "
              f"{float(down['fluid_load_fraction'][i]):.3g} down; contact resistance "
              f"{float(up['contact_resistance'][i]):.4g} ohm up, {float(down['contact_resistance'][i]):.4g} ohm down"
              + ("" if int(up["converged"][i]) == int(down["converged"][i]) == 1 else "; NOT CONVERGED in a direction"))
    print(ds.attrs["hysteresis"])
    write_case(ds, sm.output[0])  # atomic; a point that did not converge is kept, converged = 0


with job_log(snakemake.log[0]):
    main(snakemake)
