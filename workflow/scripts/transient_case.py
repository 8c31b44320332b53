"""Run one transient case (lubecontact.transient) from the base scene and its overrides."""

import sys

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)

from lubecontact import load_scene, transient
from lubecontact.io.case_schema import write_case

with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    scene = load_scene(snakemake.input.base, snakemake.params.overrides)
    if scene.hash != snakemake.wildcards.case:
        raise RuntimeError(f"case {snakemake.wildcards.case}: the scene now hashes to {scene.hash}")
    ds = transient(scene, progress=False)
    print(f"{ds['steps'].item()} steps, {ds['coupled_solves'].item()} coupled solves, "
          f"{ds['solve_time'].item():.1f} s, converged {ds['converged'].item()}: {ds.attrs['notes']}")
    write_case(ds, snakemake.output[0])  # atomic; a run that did not converge is kept, flagged
