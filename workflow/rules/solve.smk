# Solve the cases: one job per chunk (config cases_per_job; default one curve = all speeds
# of one parameter combination), each case from a cold start, one netCDF per case.
#
# A job's output files are fixed when the workflow is parsed, so each chunk is its own rule
# (solve_<figure>_<swept values>_<hash of its members>). Its cases are listed in a small
# JSON plan (plans/solve/<chunk>.json, rewritten only when they change), not in params. Outputs are update(): Snakemake keeps existing
# case files, and the job skips a case whose file is complete (atomic writes) and was solved
# by the current solver sources (fingerprint in the file). So a chunk whose membership
# changed (a speed added to a grid) solves only its new cases, and after a crash of
# Snakemake itself (--unlock, rerun) only the missing cases are solved. A job that fails
# while Snakemake runs has its outputs removed by Snakemake and reruns whole; a retry gets
# the runtime scaled by the attempt number (e.g. after hitting a SLURM time limit).


for _chunk in CHUNKS:
    _runtime, _mem_mb = solve_resources(_chunk.cases)

    rule:
        name:
            f"solve_{_chunk.name}"
        input:
            sources=SOLVER_SOURCES,
            plan=plan_path(f"solve/{_chunk.name}", [c.plain() for c in _chunk.cases]),
        output:
            [update(case_path(c.id)) for c in _chunk.cases],
        log:
            f"{RESULTS}/logs/solve/{_chunk.name}.log",
        # a cluster profile can bundle several chunks per submission (group-components);
        # local runs ignore groups
        group:
            "solve"
        # longest first (the LPT rule): a long chunk started last would run alone at the end
        priority: int(solve_seconds(_chunk.cases))
        threads: 1
        resources:
            runtime=lambda wc, attempt, r=_runtime: r * attempt,
            mem_mb=_mem_mb,
        conda:
            "../envs/lubecontact.yaml"
        script:
            "../scripts/solve_chunk.py"
