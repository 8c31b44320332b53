"""Solve the cases of one chunk, one after the other, each from a cold start.

input.plan: JSON list of {id, scene, set} in the order of the output files. A case whose
file is complete (it reads back with its scene hash and the fingerprint of the current
solver sources: lubecontact.io.case_files) is kept, so a job rerun because its membership
changed or because it was killed solves only what is missing; an unreadable file is
solved again. Each file's CF history names the command line that solves it alone
(job_plans.solve_command). A case that does not converge is written with converged = 0 and
the job goes on; a scene that does not rebuild to its id, or a solver exception, fails the
job loudly (its traceback in the job's log).
"""

import this_tree  # noqa: F401  (this tree's src/ first on sys.path)

import lubecontact
from lubecontact.io.case_files import FINGERPRINT, case_problem
from lubecontact.io.job_log import job_log
from lubecontact.io.job_plans import read_plan, solve_command
from lubecontact.model.solve import solve_case
from lubecontact.studies.figure_grids import sources_fingerprint


def main(sm):
    fingerprint = sources_fingerprint(sm.input.sources)
    for path, case in zip(sm.output, read_plan(sm.input.plan)):
        why = case_problem(path, case["id"], fingerprint)
        if why is None:
            print(f"{case['id']}: kept {path} (same scene, same solver sources)")
            continue
        if why != "missing":
            print(f"{case['id']}: solving again, {path}: {why}")
        scene = lubecontact.load_scene(case["scene"], case["set"])
        if scene.hash != case["id"]:
            raise RuntimeError(
                f"case {case['id']}: load_scene({case['scene']!r}, {case['set']}) now gives scene "
                f"{scene.hash}; the scene file changed since the workflow was planned, rerun snakemake"
            )
        try:
            result, _ = solve_case(scene)  # a case file without xarray (lubecontact.io.case_result)
        except Exception as err:
            raise RuntimeError(f"case {case['id']} ({case['set']}): solve failed") from err
        # CF history: the same case by the command line, then the line the writer adds
        rerun = f"the same case alone, from the repository's root: {solve_command(case, path)}"
        result.with_attrs(**{FINGERPRINT: fingerprint, "history": rerun}).write(path)
        out = result.scalars
        status = "converged" if int(out["converged"]) == 1 else "NOT CONVERGED (converged = 0 in the file)"
        print(f"{case['id']}: {status}, {int(out['iterations'])} iterations, {float(out['solve_time']):.2f} s, {case['set']}")


with job_log(snakemake.log[0]):
    main(snakemake)
