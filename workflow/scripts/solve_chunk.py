"""Solve the cases of one chunk, one after the other, each from a cold start.

params.cases: [{id, scene, set}] in the order of the output files. A case whose file is
complete (files are written atomically: temp file + rename) and was solved by the current
solver sources (fingerprint attribute) is kept, so a job rerun because its membership
changed or because it was killed solves only what is missing. A case that does not
converge is written with converged = 0 and the job goes on; a scene that does not rebuild
to its id, or a solver exception, fails the job loudly.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(snakemake.scriptdir).resolve().parents[1] / "src"))  # this tree's library

import xarray as xr

import lubecontact
from lubecontact.grid import sources_fingerprint
from lubecontact.output import write_case

FINGERPRINT = "solver_sources_sha256"


def is_current(path, case_id, fingerprint):
    if not Path(path).exists():
        return False
    with xr.open_dataset(path) as ds:
        return ds.attrs.get("scene_hash") == case_id and ds.attrs.get(FINGERPRINT) == fingerprint


def main(sm):
    fingerprint = sources_fingerprint(sm.input.sources)
    for path, case in zip(sm.output, sm.params.cases):
        if is_current(path, case["id"], fingerprint):
            print(f"{case['id']}: kept {path} (same scene, same solver sources)")
            continue
        scene = lubecontact.load_scene(case["scene"], case["set"])
        if scene.hash != case["id"]:
            raise RuntimeError(
                f"case {case['id']}: load_scene({case['scene']!r}, {case['set']}) now gives scene "
                f"{scene.hash}; the scene file changed since the workflow was planned, rerun snakemake"
            )
        try:
            ds = lubecontact.solve(scene)
        except Exception as err:
            raise RuntimeError(f"case {case['id']} ({case['set']}): solve failed") from err
        ds.attrs[FINGERPRINT] = fingerprint
        write_case(ds, path)
        status = "converged" if int(ds["converged"]) == 1 else "NOT CONVERGED (converged = 0 in the file)"
        print(f"{case['id']}: {status}, {int(ds['iterations'])} iterations, {float(ds['solve_time']):.2f} s, {case['set']}")


with open(snakemake.log[0], "w") as log:
    sys.stdout = sys.stderr = log
    main(snakemake)
